//! Calls of small standard-library-sized FBs compiled in place
//! (`translate.rs` decides which: `inlinable`, `INLINE_BUDGET`).
//!
//! Why this is more than pasting the callee's body: a thousand
//! `TON`/`R_TRIG`/`CTU` calls per scan are the typical PLC load, and an
//! inlined body that goes through memory for every field read, then makes
//! the caller reload its own loop variables, spends three times the
//! instructions of the same code in C. So:
//! - the callee's scalar fields that its first block touches are promoted
//!   like the caller's (`promote.rs`): read from a variable, still stored
//!   to the image on every assignment (the image stays exact at every
//!   fault); one read first there is loaded once at the body's entry, one
//!   assigned first (`TON.NOW`) not at all. Fields touched only on some
//!   paths stay in memory: loading them at the entry would add loads;
//! - after the body only the caller's promoted slots the callee can write
//!   are reloaded: a callee whose stores all go through its own `This`
//!   and whose builtins only compute registers (time arithmetic's
//!   overflow path, conversions) writes only its own instance's bytes.

use crate::promote;
use crate::translate::{class_type, leaders, this_extent, Tx};
use crate::JitError;
use automat_ir::code::{Addr, Base, Builtin, Func, Inst, MemTy};
use cranelift_codegen::ir::{condcodes::IntCC, InstBuilder, Value};

impl<'a> Tx<'a, '_> {
    /// Compiles the body of callee `g` (function `index`) in place with
    /// `this` = `t`, when every `This` access of it is inside the image;
    /// otherwise falls through to the ordinary call, whose checked variant
    /// faults exactly. Its faults name `g` and its own instruction, as the
    /// interpreter's do; its `Ret` continues at `cont`.
    pub(crate) fn inline(
        &mut self,
        g: &'a Func,
        index: u32,
        t: Value,
        cont: cranelift_codegen::ir::Block,
        origin: Option<(Value, i64)>,
    ) -> Result<(), JitError> {
        let extent = this_extent(g);
        let end = self.b.ins().iadd_imm_s(t, extent as i64);
        let ok = self
            .b
            .ins()
            .icmp(IntCC::UnsignedLessThanOrEqual, end, self.len);
        let inline = self.b.create_block();
        let call = self.b.create_block();
        self.b.ins().brif(ok, inline, &[], call, &[]);
        self.b.switch_to_block(inline);
        self.inline_body(g, index, t, cont, extent, origin)?;
        self.b.switch_to_block(call);
        Ok(())
    }

    /// The body of `g` in place, `this` = `t` proved to have `extent`
    /// bytes inside the image; its `Ret` continues at `cont`.
    pub(crate) fn inline_body(
        &mut self,
        g: &'a Func,
        index: u32,
        t: Value,
        cont: cranelift_codegen::ir::Block,
        extent: u64,
        origin: Option<(Value, i64)>,
    ) -> Result<(), JitError> {
        let vars = self.pools.vars(&mut self.b, g);
        let saved = (
            std::mem::replace(&mut self.f, g),
            std::mem::replace(&mut self.index, index),
            std::mem::replace(&mut self.this, t),
            std::mem::replace(&mut self.vars, vars),
            std::mem::replace(&mut self.this_safe, true),
            self.ret_to.replace(cont),
            std::mem::take(&mut self.promoted),
            std::mem::take(&mut self.facts),
            std::mem::take(&mut self.ranges),
            std::mem::replace(&mut self.extent, extent),
            std::mem::take(&mut self.args),
        );
        self.inlined += g.code.len();
        self.promote_inlined(g, &saved.10, origin);
        let pc = self.pc;
        let r = self.body();
        self.pc = pc;
        (
            self.f,
            self.index,
            self.this,
            self.vars,
            self.this_safe,
            self.ret_to,
            self.promoted,
            self.facts,
            self.ranges,
            self.extent,
            self.args,
        ) = saved;
        self.args.clear();
        r
    }

    /// The bytes `this + [lo, end)` of this instance that the instance
    /// `a` of callee `g` occupies, when the block's facts prove them
    /// inside the proved extent.
    pub(crate) fn proved_instance(&self, a: Addr, g: &Func) -> Option<(u64, u64)> {
        let size = this_extent(g);
        if a.base == Base::This {
            // A scalar instance (`tmr(IN := x)`) at a constant offset.
            let end = (a.offset as u64).checked_add(size)?;
            return (self.this_safe && end <= self.extent).then_some((a.offset as u64, end));
        }
        self.proved_range(a, u32::try_from(size).ok()?)
    }

    /// The offset of a register address `proved_range` proved: the plain
    /// sum (it does not wrap, see `signed_offset`).
    pub(crate) fn proved_offset(&mut self, a: Addr) -> Result<Value, JitError> {
        let Base::Reg(r) = a.base else {
            // `This` inside the proved extent: the plain sum too.
            return Ok(self.offset(a));
        };
        let v = self.get(r)?;
        Ok(self
            .b
            .ins()
            .iadd_imm_s(v, crate::translate::signed_offset(a)))
    }

    /// After an inlined call of `g` on the bytes `range` of this
    /// instance: reloads the promoted slots it may have written. A callee
    /// that writes memory only through its own `This` (no register or
    /// absolute stores, copies or builtins) writes only inside `range`.
    pub(crate) fn reload_after(&mut self, g: &Func, range: Option<(u64, u64)>) {
        let own_only = !g.code.iter().any(writes_elsewhere);
        match range {
            Some((lo, end)) if own_only => {
                self.reload_slots(|off, n| (off as u64) < end && lo < off as u64 + n as u64)
            }
            _ => self.reload_slots(|_, _| true),
        }
    }

    /// Declares the promoted slots of the inlined `g` (`this` = `t`, its
    /// instance): the fields the caller has just stored (`args`: their
    /// values, no load), and those its first block touches
    /// (`entry_first`), loaded when read first.
    fn promote_inlined(&mut self, g: &Func, args: &[Arg], origin: Option<(Value, i64)>) {
        let (stored, read) = entry_first(g);
        let mut known = Vec::new();
        for (off, ty) in exact_slots(g) {
            let passed = origin.and_then(|(base, k)| {
                args.iter()
                    .rev()
                    .find(|a| a.base == base && a.ty == ty && a.offset == k + off as i64)
                    .map(|a| a.value)
            });
            if passed.is_none() && !stored.contains(&off) && !read.contains(&off) {
                continue;
            }
            let v = self.b.declare_var(class_type(ty.class()));
            self.promoted.insert(off, (ty, v));
            if let Some(value) = passed {
                self.b.def_var(v, value);
                known.push(off);
            }
        }
        self.reload_slots(|off, _| read.contains(&off) && !known.contains(&off));
    }

    /// The address register's value and offset of a call's instance
    /// (`this`), to find the arguments stored through it.
    pub(crate) fn origin(&mut self, this: Addr) -> Option<(Value, i64)> {
        let Base::Reg(r) = this.base else {
            return None;
        };
        Some((self.get(r).ok()?, crate::translate::signed_offset(this)))
    }

    /// Records what `inst` stores through a register address proved
    /// inside this instance (a call's arguments: `t[i](IN := x)` stores
    /// `t[i].IN` then calls `t[i]`); forgets all on any other write.
    pub(crate) fn note_args(&mut self, inst: &Inst) -> Result<(), JitError> {
        match *inst {
            Inst::Store { src, ty, addr } if matches!(addr.base, Base::Reg(_)) => {
                let Base::Reg(r) = addr.base else {
                    return Ok(());
                };
                if self.proved_range(addr, ty.size()).is_none() {
                    self.args.clear();
                    return Ok(());
                }
                // The instance address a call on `r + k` passes is
                // `r + k` computed the same way (`proved_offset`), so an
                // argument is identified by `r`'s value and its offset
                // from `r` (signed, as `signed_offset` reads it).
                let base = self.get(r)?;
                let offset = crate::translate::signed_offset(addr);
                let end = offset + ty.size() as i64;
                self.args.retain(|a| {
                    a.base != base || a.offset + a.ty.size() as i64 <= offset || end <= a.offset
                });
                let v = self.get(src)?;
                let value = self.wrap(v, ty);
                self.args.push(Arg {
                    base,
                    offset,
                    ty,
                    value,
                });
            }
            Inst::Store { .. } | Inst::StoreBit { .. } | Inst::Copy { .. } => self.args.clear(),
            Inst::Builtin { op, .. } if !register_only(op) => self.args.clear(),
            _ => {}
        }
        Ok(())
    }
}

/// A value the caller stored at `base + offset` (`base`: the value of the
/// address register), as a load of `ty` there reads it back.
pub struct Arg {
    base: Value,
    offset: i64,
    ty: MemTy,
    value: Value,
}

/// The `This` slots of `g` every overlapping access of which is a `Load`
/// or `Store` of exactly that offset and type (`promote::slots` without
/// its use count: a slot the caller passes needs no load at all).
fn exact_slots(g: &Func) -> Vec<(u32, MemTy)> {
    let mut out: Vec<(u32, MemTy)> = Vec::new();
    let mut spoiled: Vec<(u32, u32)> = Vec::new();
    for inst in &g.code {
        match *inst {
            Inst::Load { ty, addr, .. } | Inst::Store { ty, addr, .. }
                if addr.base == Base::This && !out.contains(&(addr.offset, ty)) =>
            {
                out.push((addr.offset, ty))
            }
            Inst::LoadBit { addr, .. } | Inst::StoreBit { addr, .. } if addr.base == Base::This => {
                spoiled.push((addr.offset, 1))
            }
            Inst::Copy { dst, src, len } => {
                for a in [dst, src] {
                    if a.base == Base::This {
                        spoiled.push((a.offset, len));
                    }
                }
            }
            _ => {}
        }
    }
    let overlaps = |a: u32, n: u32, b: u32, m: u32| {
        (a as u64) < b as u64 + m as u64 && (b as u64) < a as u64 + n as u64
    };
    let all = out.clone();
    out.retain(|&(off, ty)| {
        spoiled
            .iter()
            .all(|&(o, n)| !overlaps(off, ty.size(), o, n))
            && all
                .iter()
                .all(|&(o, t)| (o, t) == (off, ty) || !overlaps(off, ty.size(), o, t.size()))
    });
    out.truncate(promote::MAX_SLOTS);
    out
}

/// Whether builtin `op` writes nothing but its destination register (the
/// string builtins write a buffer in the image).
pub fn register_only(op: Builtin) -> bool {
    !matches!(
        op,
        Builtin::ToString(..) | Builtin::Str(..) | Builtin::StrConv(..)
    )
}

/// Whether `inst` can write memory other than through a `This` store.
fn writes_elsewhere(inst: &Inst) -> bool {
    match *inst {
        Inst::Store { addr, .. } | Inst::StoreBit { addr, .. } => addr.base != Base::This,
        // Even a builtin that writes only its register counts: its (cold)
        // call clobbers the caller-saved registers, and a caller's slot
        // kept live across it is spilled, which costs more per iteration
        // than reloading it from the image after the body.
        Inst::Builtin { .. } | Inst::Copy { .. } | Inst::Call { .. } => true,
        _ => false,
    }
}

/// How `g`'s first block first touches each `This` offset: (stored
/// before any read, read before any store). Both kinds are touched on every
/// path through `g`, so keeping them in variables adds no load: a stored
/// one needs no load at all, a read one is loaded once at the entry instead
/// of at its first read.
fn entry_first(g: &Func) -> (Vec<u32>, Vec<u32>) {
    let lead = leaders(&g.code);
    let (mut stored, mut read) = (Vec::new(), Vec::new());
    for (pc, inst) in g.code.iter().enumerate() {
        if pc > 0 && lead.get(pc).copied().unwrap_or(true) {
            break;
        }
        let (off, is_store) = match *inst {
            Inst::Load { addr, .. } | Inst::LoadBit { addr, .. } if addr.base == Base::This => {
                (addr.offset, false)
            }
            Inst::Store { addr, .. } | Inst::StoreBit { addr, .. } if addr.base == Base::This => {
                (addr.offset, true)
            }
            // A read through memory other than a `This` load (a copy, a
            // string builtin, a register address) ends what is known.
            Inst::Copy { .. } | Inst::Builtin { .. } | Inst::Load { .. } | Inst::LoadBit { .. } => {
                break
            }
            _ if is_control(inst) => break,
            _ => continue,
        };
        if !stored.contains(&off) && !read.contains(&off) {
            if is_store {
                stored.push(off);
            } else {
                read.push(off);
            }
        }
    }
    (stored, read)
}

fn is_control(inst: &Inst) -> bool {
    matches!(
        inst,
        Inst::Jump { .. } | Inst::Branch { .. } | Inst::Ret | Inst::Call { .. }
    )
}
