//! The fast path of the dispatch loop: each function's code pre-decoded in
//! [`crate::Engine::new`] into [`Op`]s that the loop tries first.
//!
//! # Why and how
//! - An `Op` names its exact operation (the address base and the register
//!   window are resolved once, registers are absolute indexes into the
//!   register file), so the hot instructions cost one dispatch instead of
//!   several nested matches and window additions.
//! - `Op`s sit at the same indexes as the `Inst`s they come from: jump
//!   targets stay valid, and anything the fast path does not handle, or any
//!   instruction that would fault, falls back to the full interpreter
//!   ([`Op::Slow`] or `exec` returning `false` before any side effect),
//!   which produces the fault exactly as before.
//! - Superinstructions fuse two neighbours: `IConst` + integer op using that
//!   constant, `ICmp` + `Branch` on its result. The fused op sits at the
//!   first index and performs both effects (including writing the
//!   intermediate register), then skips the second, which stays decoded on
//!   its own for code that jumps straight to it.
//! - Only safe code: registers and image are reached with `get`, which the
//!   verifier's invariants make always succeed for valid programs.

use automat_ir::code::{Base, Cmp, FloatOp, Func, Inst, IntOp, MemTy, ShiftOp};

pub use crate::exec::exec;

#[derive(Clone, Copy, Debug)]
pub enum Op {
    /// Run by the full interpreter.
    Slow,
    /// A superinstruction too large for an `Op`: index into [`Code::big`].
    Big(u32),
    IConst {
        dst: u32,
        value: u64,
    },
    Mov {
        dst: u32,
        src: u32,
    },
    LoadThis {
        dst: u32,
        off: u32,
        ty: MemTy,
    },
    LoadAbs {
        dst: u32,
        off: u32,
        ty: MemTy,
    },
    LoadReg {
        dst: u32,
        base: u32,
        off: u32,
        ty: MemTy,
    },
    StoreThis {
        src: u32,
        off: u32,
        ty: MemTy,
    },
    StoreAbs {
        src: u32,
        off: u32,
        ty: MemTy,
    },
    StoreReg {
        src: u32,
        base: u32,
        off: u32,
        ty: MemTy,
    },
    AddrOfThis {
        dst: u32,
        off: u32,
    },
    Int {
        op: IntOp,
        dst: u32,
        a: u32,
        b: u32,
    },
    /// `IConst { cdst, imm }` then `Int { op, dst, a, b: cdst }`.
    IntImm {
        op: IntOp,
        dst: u32,
        a: u32,
        cdst: u32,
        imm: i64,
    },
    Wrap {
        dst: u32,
        src: u32,
        ty: MemTy,
    },
    ICmp {
        cmp: Cmp,
        signed: bool,
        dst: u32,
        a: u32,
        b: u32,
    },
    /// `ICmp` into `dst` then `Branch` on `dst`.
    CmpBranch {
        cmp: Cmp,
        signed: bool,
        dst: u32,
        a: u32,
        b: u32,
        then: u32,
        els: u32,
    },
    /// LREAL arithmetic.
    F64 {
        op: FloatOp,
        dst: u32,
        a: u32,
        b: u32,
    },
    F64Cmp {
        cmp: Cmp,
        dst: u32,
        a: u32,
        b: u32,
    },
    Check {
        val: u32,
        lo: i64,
        hi: i64,
    },
    /// `Int` then `Wrap` of its result.
    IntWrap {
        op: IntOp,
        dst: u32,
        a: u32,
        b: u32,
        wdst: u32,
        ty: MemTy,
    },
    /// Two loads relative to `this`.
    Load2This {
        d1: u32,
        o1: u32,
        t1: MemTy,
        d2: u32,
        o2: u32,
        t2: MemTy,
    },
    /// `F64Const { cdst, imm }` then `Float { op, wide, dst, a, b: cdst }`.
    F64Imm {
        op: FloatOp,
        dst: u32,
        a: u32,
        cdst: u32,
        imm: f64,
    },
    /// `IConst { cdst, value }` then `Store { src: cdst, .. }` at `this + off`.
    StoreThisImm {
        cdst: u32,
        value: u64,
        off: u32,
        ty: MemTy,
    },
    /// `Store` at `this + off` then `Jump` (the back edge of loops).
    StoreThisJump {
        src: u32,
        off: u32,
        ty: MemTy,
        target: u32,
    },
    Shift {
        op: ShiftOp,
        width: u8,
        dst: u32,
        a: u32,
        n: u32,
    },
    Jump {
        target: u32,
    },
    Branch {
        cond: u32,
        then: u32,
        els: u32,
    },
}

/// The larger superinstructions, kept out of [`Op`] so that `Op` stays 24
/// bytes: small ops are what the loop streams through.
#[derive(Clone, Copy, Debug)]
pub enum Big {
    /// `IConst n`, `Shift` by it, `Wrap` of the result (`SHL(x, 13)`).
    ShiftImmWrap {
        op: ShiftOp,
        width: u8,
        dst: u32,
        a: u32,
        cdst: u32,
        n: i64,
        wdst: u32,
        ty: MemTy,
    },
    /// `Int`, `Wrap` of its result, `Store` of that at `this + off`.
    IntWrapStore {
        op: IntOp,
        dst: u32,
        a: u32,
        b: u32,
        wdst: u32,
        ty: MemTy,
        sty: MemTy,
        off: u32,
    },
    /// An array element's address: `Check val in lo..hi; IConst c1 stride;
    /// Mul d1 val c1; AddrOf d2 this+off; IConst c2 bias; Add d3 d1 c2;
    /// Add d4 d2 d3`, with every intermediate register written.
    IndexAddr {
        val: u32,
        lo: i64,
        hi: i64,
        regs: [u32; 6],
        stride: i64,
        off: u32,
        bias: i64,
    },
    /// `IConst`, `Int` using it, `Wrap` of the result.
    IntImmWrap {
        op: IntOp,
        dst: u32,
        a: u32,
        cdst: u32,
        imm: i64,
        wdst: u32,
        ty: MemTy,
    },
    /// `Load` at `this + off`, `IConst`, `ICmp` of the two, `Branch`.
    LoadCmpImmBranch {
        ldst: u32,
        off: u32,
        ty: MemTy,
        cdst: u32,
        imm: i64,
        cmp: Cmp,
        signed: bool,
        dst: u32,
        then: u32,
        els: u32,
    },
    /// The range test of loop counters: `IConst lo; IConst hi; ICmp Ge;
    /// ICmp Le; And; Branch`, with every intermediate register written.
    RangeBranch {
        val: u32,
        regs: [u32; 5],
        lo: i64,
        hi: i64,
        then: u32,
        els: u32,
    },
    /// `Load` at `this + off` then `ICmp` of it then `Branch` (loop heads).
    LoadCmpBranch {
        ldst: u32,
        off: u32,
        ty: MemTy,
        cmp: Cmp,
        signed: bool,
        dst: u32,
        b: u32,
        then: u32,
        els: u32,
    },
    /// `F64Const`, `FCmp` against it, `Branch` on the result.
    F64CmpImmBranch {
        cdst: u32,
        imm: f64,
        cmp: Cmp,
        dst: u32,
        a: u32,
        then: u32,
        els: u32,
    },
}

const _: () = assert!(std::mem::size_of::<Op>() <= 24);

/// One function's pre-decoded code.
#[derive(Clone, Debug, Default)]
pub struct Code {
    pub ops: Vec<Op>,
    pub big: Vec<Big>,
}

/// The decoded code of function `f` as two slices, which the dispatch
/// loop keeps in registers (empty for a function that does not exist: the
/// full interpreter then faults).
#[inline]
pub fn slices(decoded: &[Code], f: u32) -> (&[Op], &[Big]) {
    decoded
        .get(f as usize)
        .map(|c| (c.ops.as_slice(), c.big.as_slice()))
        .unwrap_or((&[], &[]))
}

/// What a pattern of `fuse.rs` fuses into.
pub enum Fused {
    Op(Op),
    Big(Big),
}

/// Decodes one function whose register window starts at `window`.
pub fn decode(func: &Func, window: u32) -> Code {
    let r = |x: u32| window.saturating_add(x);
    let code = &func.code;
    let single = |inst: &Inst| -> Op {
        match *inst {
            Inst::IConst { dst, value } => Op::IConst {
                dst: r(dst),
                value: value as u64,
            },
            Inst::F64Const { dst, value } => Op::IConst {
                dst: r(dst),
                value: value.to_bits(),
            },
            Inst::Mov { dst, src } => Op::Mov {
                dst: r(dst),
                src: r(src),
            },
            Inst::Load { dst, ty, addr } => match addr.base {
                Base::This => Op::LoadThis {
                    dst: r(dst),
                    off: addr.offset,
                    ty,
                },
                Base::Abs => Op::LoadAbs {
                    dst: r(dst),
                    off: addr.offset,
                    ty,
                },
                Base::Reg(b) => Op::LoadReg {
                    dst: r(dst),
                    base: r(b),
                    off: addr.offset,
                    ty,
                },
            },
            Inst::Store { src, ty, addr } => match addr.base {
                Base::This => Op::StoreThis {
                    src: r(src),
                    off: addr.offset,
                    ty,
                },
                Base::Abs => Op::StoreAbs {
                    src: r(src),
                    off: addr.offset,
                    ty,
                },
                Base::Reg(b) => Op::StoreReg {
                    src: r(src),
                    base: r(b),
                    off: addr.offset,
                    ty,
                },
            },
            Inst::AddrOf { dst, addr } if addr.base == Base::This => Op::AddrOfThis {
                dst: r(dst),
                off: addr.offset,
            },
            Inst::Int { op, dst, a, b } => Op::Int {
                op,
                dst: r(dst),
                a: r(a),
                b: r(b),
            },
            // A wrap to 64 bits changes nothing.
            Inst::Wrap {
                dst,
                src,
                ty: MemTy::I64,
            } => Op::Mov {
                dst: r(dst),
                src: r(src),
            },
            Inst::Shift {
                op,
                width,
                dst,
                a,
                n,
            } => Op::Shift {
                op,
                width,
                dst: r(dst),
                a: r(a),
                n: r(n),
            },
            Inst::Wrap { dst, src, ty } => Op::Wrap {
                dst: r(dst),
                src: r(src),
                ty,
            },
            Inst::ICmp {
                cmp,
                signed,
                dst,
                a,
                b,
            } => Op::ICmp {
                cmp,
                signed,
                dst: r(dst),
                a: r(a),
                b: r(b),
            },
            Inst::Float {
                op,
                wide: true,
                dst,
                a,
                b,
            } => Op::F64 {
                op,
                dst: r(dst),
                a: r(a),
                b: r(b),
            },
            Inst::FCmp {
                cmp,
                wide: true,
                dst,
                a,
                b,
            } => Op::F64Cmp {
                cmp,
                dst: r(dst),
                a: r(a),
                b: r(b),
            },
            Inst::Check { val, lo, hi, .. } => Op::Check {
                val: r(val),
                lo,
                hi,
            },
            Inst::Jump { target } => Op::Jump { target },
            Inst::Branch { cond, then, els } => Op::Branch {
                cond: r(cond),
                then,
                els,
            },
            _ => Op::Slow,
        }
    };
    let mut ops: Vec<Op> = code.iter().map(single).collect();
    let mut big = Vec::new();
    for (i, slot) in ops.iter_mut().enumerate() {
        match crate::fuse::long(code.get(i..).unwrap_or(&[]), &r) {
            Some(Fused::Op(op)) => *slot = op,
            Some(Fused::Big(b)) => {
                *slot = Op::Big(big.len() as u32);
                big.push(b);
            }
            None => {}
        }
    }
    for (i, pair) in code.windows(2).enumerate() {
        let fused = match (pair.first(), pair.get(1)) {
            (Some(&Inst::IConst { dst: c, value }), Some(&Inst::Int { op, dst, a, b }))
                if b == c =>
            {
                Some(Op::IntImm {
                    op,
                    dst: r(dst),
                    a: r(a),
                    cdst: r(c),
                    imm: value,
                })
            }
            (
                Some(&Inst::ICmp {
                    cmp,
                    signed,
                    dst,
                    a,
                    b,
                }),
                Some(&Inst::Branch { cond, then, els }),
            ) if cond == dst => Some(Op::CmpBranch {
                cmp,
                signed,
                dst: r(dst),
                a: r(a),
                b: r(b),
                then,
                els,
            }),
            _ => None,
        };
        if let (Some(op), Some(slot)) = (fused, ops.get_mut(i)) {
            // Longer fusions found above win.
            if matches!(slot, Op::IConst { .. } | Op::ICmp { .. }) {
                *slot = op;
            }
        }
    }
    Code { ops, big }
}
