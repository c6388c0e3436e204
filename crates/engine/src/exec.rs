//! Execution of the pre-decoded [`Op`]s (see `fast.rs` for the contract:
//! `false` means nothing changed and the full interpreter runs the
//! instruction, which also produces any fault).

use crate::fast::{Big, Op};
use crate::mem;
use automat_ir::code::{Cmp, FloatOp, IntOp, MemTy};

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
    big: &[Big],
    regs: &mut [u64],
    image: &mut [u8],
    this: u32,
    pc: &mut u32,
    left: &mut u64,
) -> bool {
    match op {
        Op::Slow => return false,
        Op::Big(i) => {
            return match big.get(i as usize) {
                Some(&b) => exec_big(b, regs, image, this, pc, left),
                None => false,
            }
        }
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
        Op::IntWrap {
            op,
            dst,
            a,
            b,
            wdst,
            ty,
        } => {
            let v = int(op, get(regs, a) as i64, get(regs, b) as i64) as u64;
            set(regs, dst, v);
            set(regs, wdst, wrap(v, ty));
            *left = left.saturating_sub(1);
            *pc += 2;
            return true;
        }
        Op::Load2This {
            d1,
            o1,
            t1,
            d2,
            o2,
            t2,
        } => {
            let (Some(v1), Some(v2)) = (
                mem::load(image, this.wrapping_add(o1), t1),
                mem::load(image, this.wrapping_add(o2), t2),
            ) else {
                return false;
            };
            set(regs, d1, v1);
            set(regs, d2, v2);
            *left = left.saturating_sub(1);
            *pc += 2;
            return true;
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
        Op::Shift {
            op,
            width,
            dst,
            a,
            n,
        } => {
            let v = crate::interp::shift(op, width, get(regs, a) as i64, get(regs, n) as i64);
            set(regs, dst, v as u64);
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

/// The larger superinstructions (all of them end the op: they move `pc`).
#[inline(always)]
fn exec_big(
    b: Big,
    regs: &mut [u64],
    image: &mut [u8],
    this: u32,
    pc: &mut u32,
    left: &mut u64,
) -> bool {
    match b {
        Big::ShiftImmWrap {
            op,
            width,
            dst,
            a,
            cdst,
            n,
            wdst,
            ty,
        } => {
            set(regs, cdst, n as u64);
            let v = crate::interp::shift(op, width, get(regs, a) as i64, n) as u64;
            set(regs, dst, v);
            set(regs, wdst, wrap(v, ty));
            *left = left.saturating_sub(2);
            *pc += 3;
            true
        }
        Big::IntWrapStore {
            op,
            dst,
            a,
            b,
            wdst,
            ty,
            sty,
            off,
        } => {
            let v = int(op, get(regs, a) as i64, get(regs, b) as i64) as u64;
            let w = wrap(v, ty);
            if mem::store(image, this.wrapping_add(off), sty, w).is_none() {
                return false;
            }
            set(regs, dst, v);
            set(regs, wdst, w);
            *left = left.saturating_sub(2);
            *pc += 3;
            true
        }
        Big::IndexAddr {
            val,
            lo,
            hi,
            regs: [c1, d1, d2, c2, d3, d4],
            stride,
            off,
            bias,
        } => {
            let v = get(regs, val) as i64;
            if v < lo || v > hi {
                return false;
            }
            let scaled = v.wrapping_mul(stride);
            let base = this.wrapping_add(off) as u64;
            let rel = scaled.wrapping_add(bias);
            set(regs, c1, stride as u64);
            set(regs, d1, scaled as u64);
            set(regs, d2, base);
            set(regs, c2, bias as u64);
            set(regs, d3, rel as u64);
            set(regs, d4, (base as i64).wrapping_add(rel) as u64);
            *left = left.saturating_sub(6);
            *pc += 7;
            true
        }
        Big::IntImmWrap {
            op,
            dst,
            a,
            cdst,
            imm,
            wdst,
            ty,
        } => {
            set(regs, cdst, imm as u64);
            let v = int(op, get(regs, a) as i64, imm) as u64;
            set(regs, dst, v);
            set(regs, wdst, wrap(v, ty));
            *left = left.saturating_sub(2);
            *pc += 3;
            true
        }
        Big::LoadCmpImmBranch {
            ldst,
            off,
            ty,
            cdst,
            imm,
            cmp,
            signed,
            dst,
            then,
            els,
        } => {
            let Some(v) = mem::load(image, this.wrapping_add(off), ty) else {
                return false;
            };
            set(regs, ldst, v);
            set(regs, cdst, imm as u64);
            let c = icmp(cmp, signed, v, imm as u64);
            set(regs, dst, c as u64);
            *left = left.saturating_sub(3);
            *pc = if c { then } else { els };
            true
        }
        Big::RangeBranch {
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
            true
        }
        Big::LoadCmpBranch {
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
            true
        }
        Big::F64CmpImmBranch {
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
            true
        }
    }
}
