//! Superinstruction patterns: runs of two to seven instructions that the
//! lowering emits again and again (loop heads and counters, array element
//! addresses, operations with a constant operand), each turned into one
//! [`Op`]. A pattern only matches straight-line code that ends at most in
//! one branch, and the fused op writes every register the run writes, so
//! later code sees exactly the same state (see `fast.rs`).

use crate::fast::{Big, Fused, Op};
use automat_ir::code::{Base, Cmp, Inst, IntOp, MemTy};

/// The superinstruction for the run starting at `c`, if any; `r` maps a
/// function register to its absolute index in the register file.
pub fn long(c: &[Inst], r: &impl Fn(u32) -> u32) -> Option<Fused> {
    use Inst as I;
    match c {
        [I::IConst { dst: c0, value }, I::Shift {
            op,
            width,
            dst,
            a,
            n,
        }, I::Wrap { dst: w, src, ty }, ..]
            if n == c0 && a != c0 && src == dst =>
        {
            Some(Fused::Big(Big::ShiftImmWrap {
                op: *op,
                width: *width,
                dst: r(*dst),
                a: r(*a),
                cdst: r(*c0),
                n: *value,
                wdst: r(*w),
                ty: *ty,
            }))
        }
        [I::Int { op, dst, a, b }, I::Wrap { dst: w, src, ty }, I::Store {
            src: s,
            ty: sty,
            addr,
        }, ..]
            if src == dst && s == w && addr.base == Base::This =>
        {
            Some(Fused::Big(Big::IntWrapStore {
                op: *op,
                dst: r(*dst),
                a: r(*a),
                b: r(*b),
                wdst: r(*w),
                ty: *ty,
                sty: *sty,
                off: addr.offset,
            }))
        }
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
            Some(Fused::Big(Big::RangeBranch {
                val: r(*v1),
                regs: [r(*l), r(*h), r(*d1), r(*d2), r(*d3)],
                lo: *lo,
                hi: *hi,
                then: *then,
                els: *els,
            }))
        }
        [I::Check { val, lo, hi, .. }, I::IConst {
            dst: c1,
            value: stride,
        }, I::Int {
            op: IntOp::Mul,
            dst: d1,
            a: m1,
            b: m2,
        }, I::AddrOf { dst: d2, addr }, I::IConst {
            dst: c2,
            value: bias,
        }, I::Int {
            op: IntOp::Add,
            dst: d3,
            a: a3,
            b: b3,
        }, I::Int {
            op: IntOp::Add,
            dst: d4,
            a: a4,
            b: b4,
        }, ..]
            if addr.base == Base::This
                && m1 == val
                && m2 == c1
                && a3 == d1
                && b3 == c2
                && a4 == d2
                && b4 == d3
                && val != c1
                && ![*c1, *d1, *d2].contains(c2)
                && ![*c1, *d1].contains(d2)
                && d3 != d2
                && c1 != d1 =>
        {
            Some(Fused::Big(Big::IndexAddr {
                val: r(*val),
                lo: *lo,
                hi: *hi,
                regs: [r(*c1), r(*d1), r(*d2), r(*c2), r(*d3), r(*d4)],
                stride: *stride,
                off: addr.offset,
                bias: *bias,
            }))
        }
        [I::Load { dst: l, ty, addr }, I::IConst { dst: c0, value }, I::ICmp {
            cmp,
            signed,
            dst,
            a,
            b,
        }, I::Branch { cond, then, els }, ..]
            if addr.base == Base::This && a == l && b == c0 && l != c0 && cond == dst =>
        {
            Some(Fused::Big(Big::LoadCmpImmBranch {
                ldst: r(*l),
                off: addr.offset,
                ty: *ty,
                cdst: r(*c0),
                imm: *value,
                cmp: *cmp,
                signed: *signed,
                dst: r(*dst),
                then: *then,
                els: *els,
            }))
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
            Some(Fused::Big(Big::LoadCmpBranch {
                ldst: r(*l),
                off: addr.offset,
                ty: *ty,
                cmp: *cmp,
                signed: *signed,
                dst: r(*dst),
                b: r(*b),
                then: *then,
                els: *els,
            }))
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
            Some(Fused::Big(Big::F64CmpImmBranch {
                cdst: r(*c0),
                imm: *value,
                cmp: *cmp,
                dst: r(*dst),
                a: r(*a),
                then: *then,
                els: *els,
            }))
        }
        [I::IConst { dst: c0, value }, I::Int { op, dst, a, b }, I::Wrap { dst: w, src, ty }, ..]
            if b == c0 && src == dst && *ty != MemTy::I64 =>
        {
            Some(Fused::Big(Big::IntImmWrap {
                op: *op,
                dst: r(*dst),
                a: r(*a),
                cdst: r(*c0),
                imm: *value,
                wdst: r(*w),
                ty: *ty,
            }))
        }
        [I::Int { op, dst, a, b }, I::Wrap { dst: w, src, ty }, ..]
            if src == dst && *ty != MemTy::I64 =>
        {
            Some(Fused::Op(Op::IntWrap {
                op: *op,
                dst: r(*dst),
                a: r(*a),
                b: r(*b),
                wdst: r(*w),
                ty: *ty,
            }))
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
            Some(Fused::Op(Op::F64Imm {
                op: *op,
                dst: r(*dst),
                a: r(*a),
                cdst: r(*c0),
                imm: *value,
            }))
        }
        [I::IConst { dst, value }, I::Store { src, ty, addr }, ..]
            if src == dst && addr.base == Base::This =>
        {
            Some(Fused::Op(Op::StoreThisImm {
                cdst: r(*dst),
                value: *value as u64,
                off: addr.offset,
                ty: *ty,
            }))
        }
        [I::Store { src, ty, addr }, I::Jump { target }, ..] if addr.base == Base::This => {
            Some(Fused::Op(Op::StoreThisJump {
                src: r(*src),
                off: addr.offset,
                ty: *ty,
                target: *target,
            }))
        }
        [I::Load {
            dst: d1,
            ty: t1,
            addr: a1,
        }, I::Load {
            dst: d2,
            ty: t2,
            addr: a2,
        }, ..]
            if a1.base == Base::This && a2.base == Base::This =>
        {
            Some(Fused::Op(Op::Load2This {
                d1: r(*d1),
                o1: a1.offset,
                t1: *t1,
                d2: r(*d2),
                o2: a2.offset,
                t2: *t2,
            }))
        }
        _ => None,
    }
}
