//! One IR function to one Cranelift function: basic blocks, the watchdog
//! budget, control flow and calls. Instruction bodies are in `emit.rs`.
//!
//! # The watchdog, exactly as the interpreter counts it
//! The interpreter spends one unit of budget per instruction and faults on
//! the instruction it has no unit left for, naming that instruction's
//! statement. Here every basic block (a block also ends after a `Call`, so
//! the callee's spending is seen) charges its whole length on entry: if the
//! budget stays non-negative the block runs at full speed; otherwise it
//! runs a second, counting copy of itself that checks before every
//! instruction and faults at exactly the interpreter's instruction, after
//! exactly the same stores and with any earlier fault of the block first.
//! The budget lives in a variable and is written back to the context only
//! around calls and returns.
//!
//! All of this only in code compiled with a budget (`Helpers::counted`);
//! without one (the default) there is no bookkeeping at all.
//!
//! # The interrupt flag
//! Loop headers (targets of backward jumps) poll it: counted code when the
//! budget reaches `RunCtx::mark` (every `POLL_INSTRUCTIONS`), uncounted
//! code by loading the flag each iteration; a raised flag calls
//! `rt::jit_poll` on a cold path, which records the fault. `rt::jit_copy`
//! polls after long copies. Straight-line code needs no poll: without
//! recursion, only loops run long.

use crate::promote::{self, Fact};
use crate::rt::{self, BuiltinCall, RunCtx};
use crate::JitError;
use automat_ir::code::{Addr, Base, Func, Inst, MemTy, Reg, RegClass};
use cranelift_codegen::ir::{
    condcodes::IntCC, types, BlockArg, FuncRef, Function, InstBuilder, MemFlagsData, StackSlot,
    StackSlotData, StackSlotKind, Type, Value,
};
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext, Variable};
use std::collections::HashMap;

/// Functions a compiled POU calls.
pub struct Helpers {
    pub fault: FuncRef,
    pub builtin: FuncRef,
    pub copy: FuncRef,
    /// `rt::jit_poll` through its trampoline (`compile.rs`): the
    /// interrupt flag, polled at loop headers; the status is left in
    /// `RunCtx::polled`.
    pub poll: FuncRef,
    /// Whether the code counts the instruction budget (compiled so only
    /// when a finite budget is set): blocks charge their length, loop
    /// headers poll when the budget reaches `RunCtx::mark`. Without it
    /// there is no budget bookkeeping at all and loop headers test the
    /// interrupt flag itself, at `flag`.
    pub counted: bool,
    /// The address of the interrupt flag (an `AtomicBool` the `Jit` owns).
    pub flag: i64,
    /// (IR function index, reference) of every callee.
    pub callees: Vec<(u32, FuncRef)>,
    /// For the fast variant of a function with `This` accesses: the
    /// checked variant, run when the entry check fails, and the extent.
    pub checked: Option<(FuncRef, u64)>,
    /// The function only ever runs on instances proved inside the image
    /// (`instances.rs`): its `This` accesses need no check at all.
    pub static_this: bool,
    pub ptr: Type,
    pub target: cranelift_codegen::isa::TargetFrontendConfig,
}

pub(crate) struct Tx<'a, 'b> {
    pub b: FunctionBuilder<'b>,
    pub f: &'a Func,
    pub index: u32,
    pub h: &'a Helpers,
    pub vars: Vec<Variable>,
    pub left: Variable,
    pub ctx: Value,
    pub this: Value,
    pub image: Value,
    pub len: Value,
    /// Argument slots of builtins (sized to the largest call).
    pub slots: Option<StackSlot>,
    pub builtins: &'a mut Vec<BuiltinCall>,
    /// `This` accesses need no check: the entry proved them in the image.
    pub this_safe: bool,
    /// Every function of the program (for inlining).
    pub funcs: &'a [Func],
    /// Inside an inlined callee: where its `Ret` continues.
    pub ret_to: Option<cranelift_codegen::ir::Block>,
    /// Instructions inlined so far into this function (bounded).
    pub inlined: usize,
    /// The instruction being translated (its index in `f`).
    pub pc: u32,
    /// The variables block-local registers share (`locals.rs`).
    pub pools: Pools,
    /// Promoted slots of the instance (`promote.rs`): offset -> (type, variable).
    pub promoted: HashMap<u32, (MemTy, Variable)>,
    /// What is known about registers in the current block (`promote.rs`).
    pub facts: HashMap<Reg, Fact>,
    /// Ranges `Check` proved of Cranelift values in the current block:
    /// two loads of one promoted slot give the same value, so a second
    /// check of it (another register) is seen to be proved too.
    pub ranges: HashMap<Value, (i64, i64)>,
    /// `this .. this + extent` is proved inside the image (0: nothing is).
    pub extent: u64,
    /// Values the current block stored through register addresses since
    /// its last other write (`inline.rs`: a call's arguments).
    pub args: Vec<crate::inline::Arg>,
}

/// Per register class, the variables shared by block-local registers:
/// slot k of every block uses the k-th (`locals.rs` says why).
#[derive(Default)]
pub(crate) struct Pools([Vec<Variable>; 3]);

impl Pools {
    /// The variable of every register of `f`: a pool slot's when it is
    /// block-local, one of a second pool's when `locals::shared` gives it
    /// one, else its own.
    pub(crate) fn vars(&mut self, b: &mut FunctionBuilder<'_>, f: &Func) -> Vec<Variable> {
        let lead = leaders(&f.code);
        let slots = crate::locals::slots(f, &lead);
        let shared = crate::locals::shared(f, &lead);
        // The variables of registers live in several blocks, shared by
        // those whose ranges do not overlap: this function's own (an
        // inlined callee's ranges are in its own block numbering).
        let mut long = Pools::default();
        f.regs
            .iter()
            .zip(slots)
            .zip(shared)
            .map(|((c, slot), wide)| match (slot, wide) {
                (Some(k), _) => self.var(b, *c, k),
                (None, Some(k)) => long.var(b, *c, k),
                (None, None) => b.declare_var(class_type(*c)),
            })
            .collect()
    }

    /// The k-th variable of class `c` in this pool, declared when new.
    fn var(&mut self, b: &mut FunctionBuilder<'_>, c: RegClass, k: u32) -> Variable {
        let [i, s, d] = &mut self.0;
        let pool = match c {
            RegClass::I64 => i,
            RegClass::F32 => s,
            RegClass::F64 => d,
        };
        while pool.len() <= k as usize {
            pool.push(b.declare_var(class_type(c)));
        }
        pool.get(k as usize)
            .copied()
            .unwrap_or_else(|| b.declare_var(class_type(c)))
    }
}

/// Callees at most this long, without calls of their own, are inlined.
const INLINE_MAX: usize = 64;
/// At most this many instructions are inlined into one function, so the
/// compile time of a program stays proportional to its size.
const INLINE_BUDGET: usize = 4096;

/// Whether calls of `f` are inlined: a small leaf (no calls).
fn inlinable(f: &Func) -> bool {
    f.code.len() <= INLINE_MAX && !f.code.iter().any(|i| matches!(i, Inst::Call { .. }))
}

fn max_builtin_args(f: &Func) -> Option<u32> {
    f.code
        .iter()
        .filter_map(|i| match i {
            Inst::Builtin { count, .. } => Some(*count as u32 + 1),
            _ => None,
        })
        .max()
}

pub fn class_type(c: RegClass) -> Type {
    match c {
        RegClass::I64 => types::I64,
        RegClass::F32 => types::F32,
        RegClass::F64 => types::F64,
    }
}

/// Flags of image and context accesses: no alignment is promised, and a
/// bounds check (or the verifier) has made every access valid.
pub fn mem() -> MemFlagsData {
    MemFlagsData::new().with_notrap()
}

/// The end of the furthest `This` access of `f` (0: none), as an offset
/// from `this`.
pub fn this_extent(f: &Func) -> u64 {
    f.code
        .iter()
        .filter_map(|inst| match *inst {
            Inst::Load { ty, addr, .. } | Inst::Store { ty, addr, .. } => Some((addr, ty.size())),
            Inst::LoadBit { addr, .. } | Inst::StoreBit { addr, .. } => Some((addr, 1)),
            _ => None,
        })
        .filter(|(a, _)| a.base == automat_ir::code::Base::This)
        .map(|(a, size)| a.offset as u64 + size as u64)
        .max()
        .unwrap_or(0)
}

/// Instruction indexes that start a basic block.
pub(crate) fn leaders(code: &[Inst]) -> Vec<bool> {
    let mut l = vec![false; code.len() + 1];
    if let Some(x) = l.first_mut() {
        *x = true;
    }
    let mut mark = |t: u32| {
        if let Some(x) = l.get_mut(t as usize) {
            *x = true;
        }
    };
    for (pc, inst) in code.iter().enumerate() {
        match *inst {
            Inst::Jump { target } => {
                mark(target);
                mark(pc as u32 + 1);
            }
            Inst::Branch { then, els, .. } => {
                mark(then);
                mark(els);
                mark(pc as u32 + 1);
            }
            Inst::Ret | Inst::Call { .. } => mark(pc as u32 + 1),
            _ => {}
        }
    }
    l
}

/// Instruction indexes that a jump or branch at or after them targets:
/// the headers of every loop, where the interrupt flag is polled.
fn loop_headers(code: &[Inst]) -> Vec<bool> {
    let mut h = vec![false; code.len() + 1];
    for (pc, inst) in code.iter().enumerate() {
        let targets = match *inst {
            Inst::Jump { target } => [Some(target), None],
            Inst::Branch { then, els, .. } => [Some(then), Some(els)],
            _ => [None, None],
        };
        for t in targets.into_iter().flatten() {
            if (t as usize) <= pc {
                if let Some(x) = h.get_mut(t as usize) {
                    *x = true;
                }
            }
        }
    }
    h
}

fn is_terminator(inst: &Inst) -> bool {
    matches!(inst, Inst::Jump { .. } | Inst::Branch { .. } | Inst::Ret)
}

pub fn function(
    func: &mut Function,
    fctx: &mut FunctionBuilderContext,
    f: &Func,
    index: u32,
    h: &Helpers,
    builtins: &mut Vec<BuiltinCall>,
    funcs: &[Func],
) -> Result<(), JitError> {
    let mut b = FunctionBuilder::new(func, fctx);
    let entry = b.create_block();
    b.append_block_params_for_function_params(entry);
    b.switch_to_block(entry);
    let params = b.block_params(entry).to_vec();
    let (Some(&ctx), Some(&this)) = (params.first(), params.get(1)) else {
        return Err(JitError::Backend("function parameters".into()));
    };
    let mut pools = Pools::default();
    let vars = pools.vars(&mut b, f);
    let left = b.declare_var(types::I64);
    let image = b.ins().load(h.ptr, mem(), ctx, rt::OFF_IMAGE);
    let len = b.ins().load(types::I64, mem(), ctx, rt::OFF_LEN);
    if let Some((checked, extent)) = h.checked {
        // Every `This` access of the function lies in this..this+extent:
        // when that is inside the image they all are and run unchecked;
        // otherwise the checked variant runs and faults where the
        // interpreter would.
        let end = b.ins().iadd_imm_s(this, extent as i64);
        let out = b.ins().icmp(IntCC::UnsignedGreaterThan, end, len);
        let slow = b.create_block();
        let go = b.create_block();
        b.set_cold_block(slow);
        b.ins().brif(out, slow, &[], go, &[]);
        b.switch_to_block(slow);
        let call = b.ins().call(checked, &[ctx, this]);
        let st = b.inst_results(call).to_vec();
        b.ins().return_(&st);
        b.switch_to_block(go);
    }
    let l0 = b.ins().load(types::I64, mem(), ctx, rt::OFF_LEFT);
    b.def_var(left, l0);
    // Slots for the builtins of the function and of the callees it inlines.
    let max_args = f
        .code
        .iter()
        .filter_map(|i| match i {
            Inst::Call { func, .. } => funcs
                .get(*func as usize)
                .filter(|c| inlinable(c))
                .and_then(max_builtin_args),
            _ => None,
        })
        .chain(max_builtin_args(f))
        .max();
    let slots = max_args.map(|n| {
        b.create_sized_stack_slot(StackSlotData::new(StackSlotKind::ExplicitSlot, n * 8, 3))
    });
    let mut tx = Tx {
        b,
        f,
        index,
        h,
        vars,
        left,
        ctx,
        this,
        image,
        len,
        slots,
        builtins,
        this_safe: h.checked.is_some() || h.static_this,
        funcs,
        ret_to: None,
        inlined: 0,
        pc: 0,
        pools,
        promoted: HashMap::new(),
        facts: HashMap::new(),
        ranges: HashMap::new(),
        extent: 0,
        args: Vec::new(),
    };
    if tx.this_safe {
        tx.extent = this_extent(f);
        tx.promote(f);
    }
    tx.body()?;
    tx.b.seal_all_blocks();
    tx.b.finalize(h.target);
    Ok(())
}

impl Tx<'_, '_> {
    pub fn var(&self, r: Reg) -> Result<Variable, JitError> {
        self.vars
            .get(r as usize)
            .copied()
            .ok_or_else(|| JitError::Backend(format!("{}: no register r{r}", self.f.name)))
    }

    pub fn get(&mut self, r: Reg) -> Result<Value, JitError> {
        let v = self.var(r)?;
        Ok(self.b.use_var(v))
    }

    pub fn set(&mut self, r: Reg, val: Value) -> Result<(), JitError> {
        let v = self.var(r)?;
        self.b.def_var(v, val);
        Ok(())
    }

    pub fn iconst(&mut self, v: i64) -> Value {
        self.b.ins().iconst(types::I64, v)
    }

    /// Branches to a cold block that records a fault and returns 1 when
    /// `cond` is non-zero; continues in a fresh block otherwise.
    pub fn fault_if(&mut self, cond: Value, kind: i64, site: i64, args: [Value; 3]) {
        let cold = self.b.create_block();
        let cont = self.b.create_block();
        self.b.set_cold_block(cold);
        self.b.ins().brif(cond, cold, &[], cont, &[]);
        // Both have their only predecessor: sealed now, a variable read in
        // `cont` is the value it had before the check (not a fresh block
        // parameter), so `ranges` recognises it.
        self.b.seal_block(cold);
        self.b.seal_block(cont);
        self.b.switch_to_block(cold);
        let k = self.iconst(kind);
        let func = self.iconst(self.index as i64);
        let s = self.iconst(site);
        let [a, b2, c] = args;
        self.b
            .ins()
            .call(self.h.fault, &[self.ctx, k, func, s, a, b2, c]);
        let one = self.b.ins().iconst(types::I32, 1);
        self.b.ins().return_(&[one]);
        self.b.switch_to_block(cont);
    }

    /// Returns `status` from this function when it is non-zero (a fault a
    /// callee or helper already recorded).
    pub fn propagate(&mut self, status: Value) {
        let cold = self.b.create_block();
        let cont = self.b.create_block();
        self.b.set_cold_block(cold);
        self.b.ins().brif(status, cold, &[], cont, &[]);
        self.b.switch_to_block(cold);
        self.b.ins().return_(&[status]);
        self.b.switch_to_block(cont);
    }

    fn store_left(&mut self) {
        if !self.h.counted {
            return;
        }
        let l = self.b.use_var(self.left);
        self.b.ins().store(mem(), l, self.ctx, rt::OFF_LEFT);
    }

    pub(crate) fn body(&mut self) -> Result<(), JitError> {
        let code = &self.f.code;
        let lead = leaders(code);
        let headers = loop_headers(code);
        let diamonds = if self.h.counted || !self.this_safe {
            HashMap::new()
        } else {
            crate::select::diamonds(code, &lead, &crate::locals::slots(self.f, &lead))
        };
        let slots: Vec<(u32, MemTy)> = self.promoted.iter().map(|(o, (t, _))| (*o, *t)).collect();
        let known = crate::loops::entry_ranges(self.f, &lead, &slots, self.extent);
        let mut blocks = Vec::with_capacity(code.len());
        for &is in lead.iter().take(code.len()) {
            blocks.push(is.then(|| self.b.create_block()));
        }
        let block_at = |pc: u32| blocks.get(pc as usize).copied().flatten();
        let first = block_at(0).ok_or_else(|| JitError::Backend("empty function".into()))?;
        self.b.ins().jump(first, &[]);
        let mut start = 0usize;
        while start < code.len() {
            let mut end = start + 1;
            while end < code.len() && !lead.get(end).copied().unwrap_or(true) {
                end += 1;
            }
            let Some(block) = block_at(start as u32) else {
                return Err(JitError::Backend("block map".into()));
            };
            self.b.switch_to_block(block);
            self.forget();
            if headers.get(start).copied().unwrap_or(false) {
                self.poll(start)?;
            }
            self.charge(start, end)?;
            self.seed(&known, start);
            for pc in start..end {
                let inst = code
                    .get(pc)
                    .copied()
                    .ok_or_else(|| JitError::Backend("pc".into()))?;
                self.pc = pc as u32;
                if let (Inst::Branch { cond, .. }, Some(d)) = (inst, diamonds.get(&(pc as u32))) {
                    let join = block_at(d.join)
                        .ok_or_else(|| JitError::Backend(format!("no block at {}", d.join)))?;
                    self.select(cond, d, join)?;
                    continue;
                }
                self.control(&inst, pc as u32, &block_at)?;
            }
            if !code.get(end - 1).is_some_and(is_terminator) {
                let next =
                    block_at(end as u32).ok_or_else(|| JitError::Backend("fall-through".into()))?;
                self.b.ins().jump(next, &[]);
            }
            start = end;
        }
        Ok(())
    }

    /// At a loop header (`pc`, the target of a backward jump): when the
    /// budget has fallen to `RunCtx::mark` (every `POLL_INSTRUCTIONS`),
    /// the cold path calls `rt::jit_poll`, which faults if the interrupt
    /// flag is raised and sets the next mark. Every endless run passes a
    /// loop header (no recursion), so this is the only poll needed; it
    /// costs one load and compare per loop iteration.
    fn poll(&mut self, pc: usize) -> Result<(), JitError> {
        let (l, due) = if self.h.counted {
            let l = self.b.use_var(self.left);
            let mark = self.b.ins().load(types::I64, mem(), self.ctx, rt::OFF_MARK);
            (l, self.b.ins().icmp(IntCC::SignedLessThan, l, mark))
        } else {
            // The flag itself: one byte load per iteration (an AtomicBool
            // is a byte; a relaxed load is a plain load on every host).
            let at = self.iconst(self.h.flag);
            let v = self.b.ins().load(types::I8, mem(), at, 0);
            (self.iconst(0), v)
        };
        let slow = self.b.create_block();
        let cont = self.b.create_block();
        self.b.set_cold_block(slow);
        self.b.ins().brif(due, slow, &[], cont, &[]);
        self.b.switch_to_block(slow);
        let (fv, pv) = (self.iconst(self.index as i64), self.iconst(pc as i64));
        // Through the trampoline that preserves every register, so that
        // values live across the loop need not be spilled for this call.
        self.b.ins().call(self.h.poll, &[self.ctx, l, fv, pv]);
        let status = self
            .b
            .ins()
            .load(types::I32, mem(), self.ctx, rt::OFF_POLLED);
        self.propagate(status);
        self.b.ins().jump(cont, &[]);
        self.b.switch_to_block(cont);
        Ok(())
    }

    /// Charges the block `start..end` to the budget on entry; when it does
    /// not cover the block, runs the counting copy (which ends in a fault).
    fn charge(&mut self, start: usize, end: usize) -> Result<(), JitError> {
        if !self.h.counted {
            return Ok(());
        }
        let n = (end - start) as i64;
        let l = self.b.use_var(self.left);
        let l2 = self.b.ins().iadd_imm_s(l, -n);
        self.b.def_var(self.left, l2);
        let short = self.b.ins().icmp_imm_s(IntCC::SignedLessThan, l2, 0);
        let slow = self.b.create_block();
        let fast = self.b.create_block();
        self.b.set_cold_block(slow);
        self.b.ins().brif(short, slow, &[], fast, &[]);
        self.b.switch_to_block(slow);
        let mut left = self.b.ins().iadd_imm_s(l2, n);
        let zero = self.iconst(0);
        for pc in start..end {
            let out = self.b.ins().icmp_imm_s(IntCC::Equal, left, 0);
            self.fault_if(out, rt::F_WATCHDOG, pc as i64, [zero, zero, zero]);
            left = self.b.ins().iadd_imm_s(left, -1);
            let inst = self
                .f
                .code
                .get(pc)
                .copied()
                .ok_or_else(|| JitError::Backend("pc".into()))?;
            if !is_terminator(&inst) && !matches!(inst, Inst::Call { .. }) {
                self.pc = pc as u32;
                self.emit(&inst)?;
            }
        }
        // The budget ran out at or before the block's last instruction, so
        // a fault returned above; this point is never reached.
        self.forget();
        let wd = self.iconst(0);
        self.b.def_var(self.left, wd);
        let last = self.iconst(1);
        self.fault_if(last, rt::F_WATCHDOG, end as i64 - 1, [zero, zero, zero]);
        let one = self.b.ins().iconst(types::I32, 1);
        self.b.ins().return_(&[one]);
        self.b.switch_to_block(fast);
        Ok(())
    }

    /// Control instructions here, everything else in `emit`.
    fn control(
        &mut self,
        inst: &Inst,
        pc: u32,
        block_at: &dyn Fn(u32) -> Option<cranelift_codegen::ir::Block>,
    ) -> Result<(), JitError> {
        let missing = |t: u32| JitError::Backend(format!("no block at {t}"));
        match *inst {
            Inst::Jump { target } => {
                let t = block_at(target).ok_or_else(|| missing(target))?;
                self.b.ins().jump(t, &[]);
            }
            Inst::Branch { cond, then, els } => {
                let c = self.get(cond)?;
                let t = block_at(then).ok_or_else(|| missing(then))?;
                let e = block_at(els).ok_or_else(|| missing(els))?;
                let no: &[BlockArg] = &[];
                // A condition the facts decide (`loops.rs`): a jump.
                match self.facts.get(&cond) {
                    Some(Fact::Range(1, 1)) => self.b.ins().jump(t, no),
                    Some(Fact::Range(0, 0)) => self.b.ins().jump(e, no),
                    _ => self.b.ins().brif(c, t, no, e, no),
                };
            }
            Inst::Ret if self.ret_to.is_some() => {
                if let Some(b) = self.ret_to {
                    self.b.ins().jump(b, &[]);
                }
            }
            Inst::Ret => {
                self.store_left();
                let zero = self.b.ins().iconst(types::I32, 0);
                self.b.ins().return_(&[zero]);
            }
            Inst::Call { func, this } => {
                let callee = self
                    .h
                    .callees
                    .iter()
                    .find(|(i, _)| *i == func)
                    .map(|(_, r)| *r)
                    .ok_or_else(|| JitError::Backend(format!("callee {func} at {pc}")))?;
                let origin = self.origin(this);
                let cont = self.b.create_block();
                let small = self
                    .funcs
                    .get(func as usize)
                    .filter(|g| inlinable(g) && self.inlined + g.code.len() <= INLINE_BUDGET);
                if let Some(g) = small {
                    if let Some(range) = self.proved_instance(this, g) {
                        // No entry check and no call to fall back on: the
                        // instance is proved inside this one, so inside
                        // the image.
                        let t = self.proved_offset(this)?;
                        self.inline_body(g, func, t, cont, this_extent(g), origin)?;
                        self.b.switch_to_block(cont);
                        self.reload_after(g, Some(range));
                        self.forget();
                        return Ok(());
                    }
                }
                let t = self.offset(this);
                if let Some(g) = small {
                    self.inline(g, func, t, cont, origin)?;
                }
                self.store_left();
                let call = self.b.ins().call(callee, &[self.ctx, t]);
                let status = self
                    .b
                    .inst_results(call)
                    .first()
                    .copied()
                    .ok_or_else(|| JitError::Backend("call result".into()))?;
                self.propagate(status);
                if self.h.counted {
                    let l = self.b.ins().load(types::I64, mem(), self.ctx, rt::OFF_LEFT);
                    self.b.def_var(self.left, l);
                }
                self.b.ins().jump(cont, &[]);
                self.b.switch_to_block(cont);
                // The callee may have written this instance.
                self.reload_slots(|_, _| true);
                self.forget();
            }
            _ => self.emit(inst)?,
        }
        Ok(())
    }
}

impl Tx<'_, '_> {
    /// A branch whose arms both store one instance slot (`select.rs`):
    /// both arms computed, the chosen value stored once, then on to the
    /// join. The arms' own blocks stay unreachable.
    fn select(
        &mut self,
        cond: Reg,
        d: &crate::select::Diamond,
        join: cranelift_codegen::ir::Block,
    ) -> Result<(), JitError> {
        let code = self.f.code.as_slice();
        let c = self.get(cond)?;
        let mut chosen = Vec::with_capacity(2);
        for arm in [&d.then, &d.els] {
            self.forget();
            for pc in arm.pure.clone() {
                let inst = code
                    .get(pc)
                    .copied()
                    .ok_or_else(|| JitError::Backend("pc".into()))?;
                self.pc = pc as u32;
                self.emit(&inst)?;
            }
            let Some(Inst::Store { src, .. }) = code.get(arm.store).copied() else {
                return Err(JitError::Backend("select store".into()));
            };
            chosen.push((src, self.get(src)?));
        }
        self.forget();
        let (Some(&(src, t)), Some(&(_, e))) = (chosen.first(), chosen.get(1)) else {
            return Err(JitError::Backend("select arms".into()));
        };
        let v = self.b.ins().select(c, t, e);
        // The then-arm's store, of the chosen value (its source register
        // is local to that arm's block: nothing reads it afterwards).
        self.set(src, v)?;
        let store = code
            .get(d.then.store)
            .copied()
            .ok_or_else(|| JitError::Backend("select store".into()))?;
        self.pc = d.then.store as u32;
        self.emit(&store)?;
        self.forget();
        self.b.ins().jump(join, &[]);
        Ok(())
    }
}

impl Tx<'_, '_> {
    /// Declares the promoted slots of `f` and loads them (`promote.rs`).
    fn promote(&mut self, f: &Func) {
        for (off, ty) in promote::slots(f) {
            let v = self.b.declare_var(class_type(ty.class()));
            self.promoted.insert(off, (ty, v));
        }
        self.reload_slots(|_, _| true);
    }

    /// Reloads from the image every promoted slot `which(offset, size)`
    /// selects: something may have written it.
    pub fn reload_slots(&mut self, which: impl Fn(u32, u32) -> bool) {
        let mut todo: Vec<(u32, MemTy, Variable)> = self
            .promoted
            .iter()
            .filter(|(off, (ty, _))| which(**off, ty.size()))
            .map(|(off, (ty, v))| (*off, *ty, *v))
            .collect();
        todo.sort_by_key(|t| t.0);
        for (off, ty, var) in todo {
            let at = self.b.ins().iadd_imm_s(self.this, off as i64);
            let p = self.b.ins().iadd(self.image, at);
            let v = self.load(ty, p);
            self.b.def_var(var, v);
        }
    }

    /// A native pointer to `size` bytes at `a` without a check, when the
    /// block's facts prove them inside `this .. this + extent`.
    pub fn proved_pointer(&mut self, a: Addr, size: u32) -> Option<Value> {
        self.proved_range(a, size)?;
        let Base::Reg(r) = a.base else { return None };
        let v = self.get(r).ok()?;
        let at = self.b.ins().iadd_imm_s(v, signed_offset(a));
        Some(self.b.ins().iadd(self.image, at))
    }

    /// The bytes `this + [lo, hi)` a register access may touch, when the
    /// facts prove them inside the proved extent.
    pub(crate) fn proved_range(&self, a: Addr, size: u32) -> Option<(u64, u64)> {
        let Base::Reg(r) = a.base else { return None };
        let Some(Fact::This(lo, hi)) = self.facts.get(&r).copied() else {
            return None;
        };
        let lo = lo.checked_add(signed_offset(a))?;
        let end = hi.checked_add(signed_offset(a))?.checked_add(size as i64)?;
        (self.this_safe && lo >= 0 && end as u64 <= self.extent).then_some((lo as u64, end as u64))
    }

    /// Ends what is known about registers and values (a new block, or
    /// after code that does not dominate what follows).
    pub fn forget(&mut self) {
        self.args.clear();
        self.facts.clear();
        self.ranges.clear();
    }

    /// Every instruction but control: the slots and facts of `promote.rs`
    /// around `emit_plain`.
    pub fn emit(&mut self, inst: &Inst) -> Result<(), JitError> {
        self.note_args(inst)?;
        match *inst {
            Inst::Load { dst, ty, addr } if addr.base == Base::This => {
                if let Some(&(t, var)) = self.promoted.get(&addr.offset) {
                    if t == ty {
                        let v = self.b.use_var(var);
                        self.facts.remove(&dst);
                        if let Some(&(lo, hi)) = self.ranges.get(&v) {
                            self.facts.insert(dst, Fact::Range(lo, hi));
                        }
                        return self.set(dst, v);
                    }
                }
                self.emit_plain(inst)?;
            }
            Inst::Store { src, ty, addr } if addr.base == Base::This => {
                self.emit_plain(inst)?;
                if let Some(&(t, var)) = self.promoted.get(&addr.offset) {
                    if t == ty {
                        // What a load of the stored bytes gives back (the
                        // value itself when its range fits the type).
                        let v = self.get(src)?;
                        let v = match self.facts.get(&src) {
                            Some(&Fact::Range(a, b)) if crate::loops::fits((a, b), ty) => v,
                            _ => self.wrap(v, ty),
                        };
                        self.b.def_var(var, v);
                    }
                }
            }
            Inst::Store { addr, .. } | Inst::StoreBit { addr, .. }
                if matches!(addr.base, Base::Reg(_)) =>
            {
                let size = match *inst {
                    Inst::Store { ty, .. } => ty.size(),
                    _ => 1,
                };
                let range = self.proved_range(addr, size);
                self.emit_plain(inst)?;
                match range {
                    Some((lo, end)) => {
                        self.reload_slots(|off, n| (off as u64) < end && lo < off as u64 + n as u64)
                    }
                    None => self.reload_slots(|_, _| true),
                }
            }
            // Time arithmetic, conversions, math: a register result only.
            Inst::Builtin { op, .. } if crate::inline::register_only(op) => {
                self.emit_plain(inst)?
            }
            Inst::Store { .. }
            | Inst::StoreBit { .. }
            | Inst::Copy { .. }
            | Inst::Builtin { .. } => {
                self.emit_plain(inst)?;
                self.reload_slots(|_, _| true);
            }
            // A check the block's facts already prove (the same index
            // checked again, as `a[i].x := a[i].y` does): nothing can fail.
            Inst::Check { val, lo, hi, .. } if matches!(self.facts.get(&val), Some(&Fact::Range(a, b)) if lo <= a && b <= hi) =>
                {}
            // A wrap of a value already in the type's range (`loops.rs`).
            Inst::Wrap { dst, src, ty } if matches!(self.facts.get(&src), Some(&Fact::Range(a, b)) if crate::loops::fits((a, b), ty)) =>
            {
                let v = self.get(src)?;
                self.set(dst, v)?;
            }
            _ => self.emit_plain(inst)?,
        }
        if let Inst::Check { val, lo, hi, .. } = *inst {
            // Past the check the value is in both ranges.
            let (lo, hi) = match self.facts.get(&val) {
                Some(&Fact::Range(a, b)) => (lo.max(a), hi.min(b)),
                _ => (lo, hi),
            };
            self.facts.insert(val, Fact::Range(lo, hi));
            let v = self.get(val)?;
            self.ranges.insert(v, (lo, hi));
        } else if let Some(d) = promote::writes(inst) {
            let new = crate::loops::derive(inst, &self.facts, self.extent);
            self.facts.remove(&d);
            if let Some((r, f)) = new {
                self.facts.insert(r, f);
            }
        }
        Ok(())
    }
}

/// The offset of a register address as a signed number. Why: an array
/// element `a[i]` with `a` at `this + k` and elements of `n` bytes is
/// lowered as `(this + n * i) + (k - n * lo)`, where the offset wraps
/// below zero as a u32 (the interpreter's `(v as u32).wrapping_add(off)`).
/// When `v + off` computed this way lies in `0 ..= extent` (checked by
/// `proved_range`), that u32 sum does not wrap and is the same number, so
/// the access is proved like any other.
pub(crate) fn signed_offset(a: Addr) -> i64 {
    a.offset as i32 as i64
}

/// The context layout generated code relies on.
const _: () = assert!(std::mem::size_of::<*mut u8>() == 8 && rt::OFF_NOW > rt::OFF_LEFT);
#[allow(dead_code)]
fn _ctx_is_sized(_: &RunCtx) {}
