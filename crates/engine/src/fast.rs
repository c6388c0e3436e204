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

use crate::mem;
use automat_ir::code::{Base, Cmp, FloatOp, Func, Inst, IntOp, MemTy};

#[derive(Clone, Copy, Debug)]
pub enum Op {
    /// Run by the full interpreter.
    Slow,
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
    Jump {
        target: u32,
    },
    Branch {
        cond: u32,
        then: u32,
        els: u32,
    },
}

/// Decodes one function whose register window starts at `window`.
pub fn decode(func: &Func, window: u32) -> Vec<Op> {
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
    for (i, slot) in ops.iter_mut().enumerate() {
        if let Some(op) = fuse_long(code.get(i..).unwrap_or(&[]), &r) {
            *slot = op;
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
    ops
}

/// Superinstructions over two to six instructions at the start of `c`.
fn fuse_long(c: &[Inst], r: &impl Fn(u32) -> u32) -> Option<Op> {
    use Inst as I;
    match c {
        [I::IConst { dst: l, value: lo }, I::IConst { dst: h, value: hi }, I::ICmp {
            cmp: Cmp::Ge,
            signed: true,
            dst: d1,
            a: v1,
            b: b1,
        }, I::ICmp {
            cmp: Cmp::Le,
            signed: true,
            dst: d2,
            a: v2,
            b: b2,
        }, I::Int {
            op: IntOp::And,
            dst: d3,
            a: a3,
            b: b3,
        }, I::Branch { cond, then, els }, ..]
            if b1 == l
                && b2 == h
                && v1 == v2
                && a3 == d1
                && b3 == d2
                && cond == d3
                && ![*l, *h, *d1].contains(v1)
                && l != h =>
        {
            Some(Op::RangeBranch {
                val: r(*v1),
                regs: [r(*l), r(*h), r(*d1), r(*d2), r(*d3)],
                lo: *lo,
                hi: *hi,
                then: *then,
                els: *els,
            })
        }
        [I::Load { dst: l, ty, addr }, I::ICmp {
            cmp,
            signed,
            dst,
            a,
            b,
        }, I::Branch { cond, then, els }, ..]
            if addr.base == Base::This && a == l && cond == dst && b != l =>
        {
            Some(Op::LoadCmpBranch {
                ldst: r(*l),
                off: addr.offset,
                ty: *ty,
                cmp: *cmp,
                signed: *signed,
                dst: r(*dst),
                b: r(*b),
                then: *then,
                els: *els,
            })
        }
        [I::F64Const { dst: c0, value }, I::FCmp {
            cmp,
            wide: true,
            dst,
            a,
            b,
        }, I::Branch { cond, then, els }, ..]
            if b == c0 && a != c0 && cond == dst =>
        {
            Some(Op::F64CmpImmBranch {
                cdst: r(*c0),
                imm: *value,
                cmp: *cmp,
                dst: r(*dst),
                a: r(*a),
                then: *then,
                els: *els,
            })
        }
        [I::F64Const { dst: c0, value }, I::Float {
            op,
            wide: true,
            dst,
            a,
            b,
        }, ..]
            if b == c0 =>
        {
            Some(Op::F64Imm {
                op: *op,
                dst: r(*dst),
                a: r(*a),
                cdst: r(*c0),
                imm: *value,
            })
        }
        [I::IConst { dst, value }, I::Store { src, ty, addr }, ..]
            if src == dst && addr.base == Base::This =>
        {
            Some(Op::StoreThisImm {
                cdst: r(*dst),
                value: *value as u64,
                off: addr.offset,
                ty: *ty,
            })
        }
        [I::Store { src, ty, addr }, I::Jump { target }, ..] if addr.base == Base::This => {
            Some(Op::StoreThisJump {
                src: r(*src),
                off: addr.offset,
                ty: *ty,
                target: *target,
            })
        }
        _ => None,
    }
}

#[inline(always)]
fn farith(op: FloatOp, x: f64, y: f64) -> f64 {
    match op {
        FloatOp::Add => x + y,
        FloatOp::Sub => x - y,
        FloatOp::Mul => x * y,
        FloatOp::Div => x / y,
    }
}

#[inline(always)]
fn get(regs: &[u64], r: u32) -> u64 {
    regs.get(r as usize).copied().unwrap_or(0)
}

#[inline(always)]
fn set(regs: &mut [u64], r: u32, v: u64) {
    if let Some(slot) = regs.get_mut(r as usize) {
        *slot = v;
    }
}

#[inline(always)]
fn int(op: IntOp, x: i64, y: i64) -> i64 {
    match op {
        IntOp::Add => x.wrapping_add(y),
        IntOp::Sub => x.wrapping_sub(y),
        IntOp::Mul => x.wrapping_mul(y),
        IntOp::And => x & y,
        IntOp::Or => x | y,
        IntOp::Xor => x ^ y,
    }
}

#[inline(always)]
fn compare<T: PartialOrd>(c: Cmp, a: T, b: T) -> bool {
    match c {
        Cmp::Eq => a == b,
        Cmp::Ne => a != b,
        Cmp::Lt => a < b,
        Cmp::Le => a <= b,
        Cmp::Gt => a > b,
        Cmp::Ge => a >= b,
    }
}

#[inline(always)]
fn icmp(c: Cmp, signed: bool, a: u64, b: u64) -> bool {
    if signed {
        compare(c, a as i64, b as i64)
    } else {
        compare(c, a, b)
    }
}

#[inline(always)]
fn wrap(v: u64, ty: MemTy) -> u64 {
    (match ty {
        MemTy::I8 => v as i8 as i64,
        MemTy::U8 => v as u8 as i64,
        MemTy::I16 => v as i16 as i64,
        MemTy::U16 => v as u16 as i64,
        MemTy::I32 => v as i32 as i64,
        MemTy::U32 => v as u32 as i64,
        _ => v as i64,
    }) as u64
}

/// Executes the op at `*pc` (already counted against the budget) and moves
/// `pc` on; `false` (with nothing changed) when the full interpreter must
/// run the instruction instead.
#[inline(always)]
pub fn exec(
    op: Op,
    regs: &mut [u64],
    image: &mut [u8],
    this: u32,
    pc: &mut u32,
    left: &mut u64,
) -> bool {
    match op {
        Op::Slow => return false,
        Op::IConst { dst, value } => set(regs, dst, value),
        Op::Mov { dst, src } => set(regs, dst, get(regs, src)),
        Op::LoadThis { dst, off, ty } => match mem::load(image, this.wrapping_add(off), ty) {
            Some(v) => set(regs, dst, v),
            None => return false,
        },
        Op::LoadAbs { dst, off, ty } => match mem::load(image, off, ty) {
            Some(v) => set(regs, dst, v),
            None => return false,
        },
        Op::LoadReg { dst, base, off, ty } => {
            match mem::load(image, (get(regs, base) as u32).wrapping_add(off), ty) {
                Some(v) => set(regs, dst, v),
                None => return false,
            }
        }
        Op::StoreThis { src, off, ty } => {
            if mem::store(image, this.wrapping_add(off), ty, get(regs, src)).is_none() {
                return false;
            }
        }
        Op::StoreAbs { src, off, ty } => {
            if mem::store(image, off, ty, get(regs, src)).is_none() {
                return false;
            }
        }
        Op::StoreReg { src, base, off, ty } => {
            let at = (get(regs, base) as u32).wrapping_add(off);
            if mem::store(image, at, ty, get(regs, src)).is_none() {
                return false;
            }
        }
        Op::AddrOfThis { dst, off } => set(regs, dst, this.wrapping_add(off) as u64),
        Op::Int { op, dst, a, b } => {
            let r = int(op, get(regs, a) as i64, get(regs, b) as i64);
            set(regs, dst, r as u64);
        }
        Op::IntImm {
            op,
            dst,
            a,
            cdst,
            imm,
        } => {
            set(regs, cdst, imm as u64);
            let r = int(op, get(regs, a) as i64, imm);
            set(regs, dst, r as u64);
            *left = left.saturating_sub(1);
            *pc += 2;
            return true;
        }
        Op::Wrap { dst, src, ty } => set(regs, dst, wrap(get(regs, src), ty)),
        Op::ICmp {
            cmp,
            signed,
            dst,
            a,
            b,
        } => {
            let r = icmp(cmp, signed, get(regs, a), get(regs, b));
            set(regs, dst, r as u64);
        }
        Op::CmpBranch {
            cmp,
            signed,
            dst,
            a,
            b,
            then,
            els,
        } => {
            let r = icmp(cmp, signed, get(regs, a), get(regs, b));
            set(regs, dst, r as u64);
            *left = left.saturating_sub(1);
            *pc = if r { then } else { els };
            return true;
        }
        Op::F64 { op, dst, a, b } => {
            let (x, y) = (f64::from_bits(get(regs, a)), f64::from_bits(get(regs, b)));
            set(regs, dst, farith(op, x, y).to_bits());
        }
        Op::F64Cmp { cmp, dst, a, b } => {
            let r = compare(
                cmp,
                f64::from_bits(get(regs, a)),
                f64::from_bits(get(regs, b)),
            );
            set(regs, dst, r as u64);
        }
        Op::Check { val, lo, hi } => {
            let v = get(regs, val) as i64;
            if v < lo || v > hi {
                return false;
            }
        }
        Op::F64Imm {
            op,
            dst,
            a,
            cdst,
            imm,
        } => {
            set(regs, cdst, imm.to_bits());
            set(
                regs,
                dst,
                farith(op, f64::from_bits(get(regs, a)), imm).to_bits(),
            );
            *left = left.saturating_sub(1);
            *pc += 2;
            return true;
        }
        Op::StoreThisImm {
            cdst,
            value,
            off,
            ty,
        } => {
            if mem::store(image, this.wrapping_add(off), ty, value).is_none() {
                return false;
            }
            set(regs, cdst, value);
            *left = left.saturating_sub(1);
            *pc += 2;
            return true;
        }
        Op::StoreThisJump {
            src,
            off,
            ty,
            target,
        } => {
            if mem::store(image, this.wrapping_add(off), ty, get(regs, src)).is_none() {
                return false;
            }
            *left = left.saturating_sub(1);
            *pc = target;
            return true;
        }
        Op::RangeBranch {
            val,
            regs: [l, h, d1, d2, d3],
            lo,
            hi,
            then,
            els,
        } => {
            let v = get(regs, val) as i64;
            let (ge, le) = (v >= lo, v <= hi);
            set(regs, l, lo as u64);
            set(regs, h, hi as u64);
            set(regs, d1, ge as u64);
            set(regs, d2, le as u64);
            set(regs, d3, (ge & le) as u64);
            *left = left.saturating_sub(5);
            *pc = if ge & le { then } else { els };
            return true;
        }
        Op::LoadCmpBranch {
            ldst,
            off,
            ty,
            cmp,
            signed,
            dst,
            b,
            then,
            els,
        } => {
            let Some(v) = mem::load(image, this.wrapping_add(off), ty) else {
                return false;
            };
            set(regs, ldst, v);
            let c = icmp(cmp, signed, v, get(regs, b));
            set(regs, dst, c as u64);
            *left = left.saturating_sub(2);
            *pc = if c { then } else { els };
            return true;
        }
        Op::F64CmpImmBranch {
            cdst,
            imm,
            cmp,
            dst,
            a,
            then,
            els,
        } => {
            set(regs, cdst, imm.to_bits());
            let c = compare(cmp, f64::from_bits(get(regs, a)), imm);
            set(regs, dst, c as u64);
            *left = left.saturating_sub(2);
            *pc = if c { then } else { els };
            return true;
        }
        Op::Jump { target } => {
            *pc = target;
            return true;
        }
        Op::Branch { cond, then, els } => {
            *pc = if get(regs, cond) != 0 { then } else { els };
            return true;
        }
    }
    *pc += 1;
    true
}
