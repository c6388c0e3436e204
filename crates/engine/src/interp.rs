//! The dispatch loop. Registers hold raw 64-bit patterns: I64 as `i64`,
//! F32 and F64 as their IEEE bits. Register indexes were verified in
//! `Engine::new`, so the window arithmetic stays inside the register file.

use crate::{builtins, fast, mem, Engine};
use automat_ir::code::{Addr, Base, CheckKind, Cmp, FloatOp, Inst, IntOp, MemTy, ShiftOp};
use automat_ir::interrupt::{POLL_COPY_BYTES, POLL_INSTRUCTIONS};
use automat_ir::{Fault, FaultKind, Program, Site};

#[derive(Clone, Copy, Debug)]
pub struct Frame {
    func: u32,
    pc: u32,
    this: u32,
}

/// Mutable state of one run, passed to the builtins.
pub struct Ctx<'a> {
    pub image: &'a mut [u8],
    pub regs: &'a mut [u64],
    pub base: usize,
}

impl Ctx<'_> {
    #[inline]
    pub fn get(&self, r: u32) -> u64 {
        self.regs.get(self.base + r as usize).copied().unwrap_or(0)
    }
    #[inline]
    pub fn set(&mut self, r: u32, v: u64) {
        if let Some(slot) = self.regs.get_mut(self.base + r as usize) {
            *slot = v;
        }
    }
    #[inline]
    fn i(&self, r: u32) -> i64 {
        self.get(r) as i64
    }
    #[inline]
    fn f32(&self, r: u32) -> f32 {
        f32::from_bits(self.get(r) as u32)
    }
    #[inline]
    fn f64(&self, r: u32) -> f64 {
        f64::from_bits(self.get(r))
    }
}

pub fn fault(
    program: &Program,
    func: u32,
    site: Option<u32>,
    kind: FaultKind,
    message: String,
) -> Fault {
    let site = site
        .and_then(|s| program.sites.get(s as usize).cloned())
        .unwrap_or_else(|| Site {
            pou: program
                .funcs
                .get(func as usize)
                .map(|f| f.name.clone())
                .unwrap_or_default(),
            location: String::new(),
            meaning: None,
        });
    // Code generated from another language says what its faults mean.
    let message = site.meaning.clone().unwrap_or(message);
    Fault {
        kind,
        message,
        site,
    }
}

/// The fault of a failed range check (`Check` with constant bounds and
/// `CheckDyn` with bounds in registers share it): index, subrange, NULL.
pub fn check_range(
    program: &Program,
    func: u32,
    kind: CheckKind,
    v: i64,
    lo: i64,
    hi: i64,
    site: u32,
) -> Result<(), Fault> {
    if (lo..=hi).contains(&v) {
        return Ok(());
    }
    let (k, message) = match kind {
        CheckKind::Index => (
            FaultKind::IndexOutOfBounds,
            format!("index {v} outside {lo}..{hi}"),
        ),
        CheckKind::Subrange => (
            FaultKind::SubrangeViolation,
            format!("value {v} outside {lo}..{hi}"),
        ),
        CheckKind::Ref if v == 0 => (
            FaultKind::Function,
            "dereference of a NULL reference".to_string(),
        ),
        CheckKind::Ref => (
            FaultKind::Function,
            format!("dereference of an invalid pointer (offset {v}; a target of this type lies at 1..{hi} in the image)"),
        ),
    };
    Err(fault(program, func, Some(site), k, message))
}

#[inline]
fn addr(ctx: &Ctx, this: u32, a: Addr) -> u32 {
    match a.base {
        Base::Abs => a.offset,
        Base::This => this.wrapping_add(a.offset),
        Base::Reg(r) => (ctx.get(r) as u32).wrapping_add(a.offset),
    }
}

fn wrap(v: i64, ty: MemTy) -> i64 {
    match ty {
        MemTy::I8 => v as i8 as i64,
        MemTy::U8 => v as u8 as i64,
        MemTy::I16 => v as i16 as i64,
        MemTy::U16 => v as u16 as i64,
        MemTy::I32 => v as i32 as i64,
        MemTy::U32 => v as u32 as i64,
        _ => v,
    }
}

pub(crate) fn shift(op: ShiftOp, width: u8, v: i64, n: i64) -> i64 {
    let w = width as u32;
    let mask: u64 = if w >= 64 { u64::MAX } else { (1u64 << w) - 1 };
    let x = v as u64 & mask;
    let n = n.max(0) as u64;
    let r = match op {
        ShiftOp::Shl if n >= w as u64 => 0,
        ShiftOp::Shr if n >= w as u64 => 0,
        ShiftOp::Shl => x << n,
        ShiftOp::Shr => x >> n,
        ShiftOp::Rol | ShiftOp::Ror => {
            let k = (n % w as u64) as u32;
            if k == 0 {
                x
            } else if op == ShiftOp::Rol {
                (x << k) | (x >> (w - k))
            } else {
                (x >> k) | (x << (w - k))
            }
        }
    };
    (r & mask) as i64
}

fn cmp<T: PartialOrd>(c: Cmp, a: T, b: T) -> u64 {
    (match c {
        Cmp::Eq => a == b,
        Cmp::Ne => a != b,
        Cmp::Lt => a < b,
        Cmp::Le => a <= b,
        Cmp::Gt => a > b,
        Cmp::Ge => a >= b,
    }) as u64
}

fn float<
    T: std::ops::Add<Output = T>
        + std::ops::Sub<Output = T>
        + std::ops::Mul<Output = T>
        + std::ops::Div<Output = T>,
>(
    op: FloatOp,
    a: T,
    b: T,
) -> T {
    match op {
        FloatOp::Add => a + b,
        FloatOp::Sub => a - b,
        FloatOp::Mul => a * b,
        FloatOp::Div => a / b,
    }
}

/// The fault of a raised [`automat_ir::Interrupt`], at the statement of
/// `site` (the runtime replaces the message with the reason).
pub fn interrupted(program: &Program, f: u32, site: Option<u32>) -> Fault {
    fault(
        program,
        f,
        site,
        FaultKind::Watchdog,
        automat_ir::interrupt::INTERRUPTED.to_string(),
    )
}

pub fn run(engine: &mut Engine, func: u32, this: u32, now: i64) -> Result<(), Fault> {
    let Engine {
        program,
        image,
        regs,
        windows,
        stack,
        budget,
        decoded,
        interrupt,
        ..
    } = engine;
    let program: &Program = program;
    stack.clear();
    let mut f = func;
    let mut this = this;
    let mut pc: u32 = 0;
    let mut left = *budget;
    // The flag is polled when `left` falls to `mark`, every
    // POLL_INSTRUCTIONS: the same compare the budget needs, so the poll is
    // free and the budget's count stays exact.
    let mut mark = left.saturating_sub(POLL_INSTRUCTIONS);
    let bad = |f: u32, what: String| fault(program, f, None, FaultKind::Function, what);
    let Some(mut code) = program.funcs.get(f as usize).map(|x| x.code.as_slice()) else {
        return Err(bad(f, format!("no function {f}")));
    };
    let mut ops = fast::slices(decoded, f);
    let mut ctx = Ctx {
        image,
        regs,
        base: windows.get(f as usize).copied().unwrap_or(0) as usize,
    };
    loop {
        if left <= mark {
            let site = program.funcs.get(f as usize).and_then(|x| x.stmt_site(pc));
            if left == 0 {
                return Err(fault(
                    program,
                    f,
                    site,
                    FaultKind::Watchdog,
                    format!("watchdog: more than {} instructions in one run", *budget),
                ));
            }
            if interrupt.is_raised() {
                return Err(interrupted(program, f, site));
            }
            mark = left.saturating_sub(POLL_INSTRUCTIONS);
        }
        left -= 1;
        if let Some(&op) = ops.0.get(pc as usize) {
            if fast::exec(op, ops.1, ctx.regs, ctx.image, this, &mut pc, &mut left) {
                continue;
            }
        }
        let Some(inst) = code.get(pc as usize) else {
            return Err(bad(f, format!("fell off the end of the code at {pc}")));
        };
        pc += 1;
        match *inst {
            Inst::IConst { dst, value } => ctx.set(dst, value as u64),
            Inst::F32Const { dst, value } => ctx.set(dst, value.to_bits() as u64),
            Inst::F64Const { dst, value } => ctx.set(dst, value.to_bits()),
            Inst::Mov { dst, src } => ctx.set(dst, ctx.get(src)),
            Inst::Load { dst, ty, addr: a } => {
                let at = addr(&ctx, this, a);
                match mem::load(ctx.image, at, ty) {
                    Some(v) => ctx.set(dst, v),
                    None => {
                        return Err(bad(f, format!("load of {ty:?} at {at} outside the image")))
                    }
                }
            }
            Inst::Store { src, ty, addr: a } => {
                let at = addr(&ctx, this, a);
                let v = ctx.get(src);
                if mem::store(ctx.image, at, ty, v).is_none() {
                    return Err(bad(f, format!("store of {ty:?} at {at} outside the image")));
                }
            }
            Inst::LoadBit { dst, addr: a, bit } => {
                let at = addr(&ctx, this, a);
                match ctx.image.get(at as usize) {
                    Some(b) => ctx.set(dst, ((b >> bit) & 1) as u64),
                    None => return Err(bad(f, format!("bit load at {at} outside the image"))),
                }
            }
            Inst::StoreBit { src, addr: a, bit } => {
                let at = addr(&ctx, this, a);
                let on = ctx.get(src) & 1 != 0;
                match ctx.image.get_mut(at as usize) {
                    Some(b) if on => *b |= 1 << bit,
                    Some(b) => *b &= !(1 << bit),
                    None => return Err(bad(f, format!("bit store at {at} outside the image"))),
                }
            }
            Inst::AddrOf { dst, addr: a } => ctx.set(dst, addr(&ctx, this, a) as u64),
            Inst::Copy { dst, src, len } => {
                let (d, s) = (
                    addr(&ctx, this, dst) as usize,
                    addr(&ctx, this, src) as usize,
                );
                let n = len as usize;
                if d + n > ctx.image.len() || s + n > ctx.image.len() {
                    return Err(bad(
                        f,
                        format!("copy of {n} bytes {s} -> {d} outside the image"),
                    ));
                }
                ctx.image.copy_within(s..s + n, d);
                if len >= POLL_COPY_BYTES && interrupt.is_raised() {
                    let site = program
                        .funcs
                        .get(f as usize)
                        .and_then(|x| x.stmt_site(pc - 1));
                    return Err(interrupted(program, f, site));
                }
            }
            Inst::Int { op, dst, a, b } => {
                let (x, y) = (ctx.i(a), ctx.i(b));
                let r = match op {
                    IntOp::Add => x.wrapping_add(y),
                    IntOp::Sub => x.wrapping_sub(y),
                    IntOp::Mul => x.wrapping_mul(y),
                    IntOp::And => x & y,
                    IntOp::Or => x | y,
                    IntOp::Xor => x ^ y,
                };
                ctx.set(dst, r as u64);
            }
            Inst::Div {
                signed,
                dst,
                a,
                b,
                site,
            }
            | Inst::Rem {
                signed,
                dst,
                a,
                b,
                site,
            } => {
                let (x, y) = (ctx.i(a), ctx.i(b));
                let is_div = matches!(inst, Inst::Div { .. });
                if y == 0 {
                    let what = if is_div { "division" } else { "MOD" };
                    return Err(fault(
                        program,
                        f,
                        Some(site),
                        FaultKind::DivisionByZero,
                        format!("{what} by zero ({x} / 0)"),
                    ));
                }
                let r = match (signed, is_div) {
                    (true, true) => x.wrapping_div(y),
                    (true, false) => x.wrapping_rem(y),
                    (false, true) => ((x as u64) / (y as u64)) as i64,
                    (false, false) => ((x as u64) % (y as u64)) as i64,
                };
                ctx.set(dst, r as u64);
            }
            Inst::Neg { dst, src } => ctx.set(dst, ctx.i(src).wrapping_neg() as u64),
            Inst::Not { dst, src } => ctx.set(dst, !ctx.get(src)),
            Inst::Wrap { dst, src, ty } => ctx.set(dst, wrap(ctx.i(src), ty) as u64),
            Inst::Shift {
                op,
                width,
                dst,
                a,
                n,
            } => ctx.set(dst, shift(op, width, ctx.i(a), ctx.i(n)) as u64),
            Inst::ICmp {
                cmp: c,
                signed,
                dst,
                a,
                b,
            } => {
                let r = if signed {
                    cmp(c, ctx.i(a), ctx.i(b))
                } else {
                    cmp(c, ctx.get(a), ctx.get(b))
                };
                ctx.set(dst, r);
            }
            Inst::Float {
                op,
                wide,
                dst,
                a,
                b,
            } => {
                if wide {
                    ctx.set(dst, float(op, ctx.f64(a), ctx.f64(b)).to_bits());
                } else {
                    ctx.set(dst, float(op, ctx.f32(a), ctx.f32(b)).to_bits() as u64);
                }
            }
            Inst::FCmp {
                cmp: c,
                wide,
                dst,
                a,
                b,
            } => {
                let r = if wide {
                    cmp(c, ctx.f64(a), ctx.f64(b))
                } else {
                    cmp(c, ctx.f32(a), ctx.f32(b))
                };
                ctx.set(dst, r);
            }
            Inst::FResize { to_wide, dst, src } => {
                if to_wide {
                    ctx.set(dst, (ctx.f32(src) as f64).to_bits());
                } else {
                    ctx.set(dst, (ctx.f64(src) as f32).to_bits() as u64);
                }
            }
            Inst::Check {
                kind,
                val,
                lo,
                hi,
                site,
            } => check_range(program, f, kind, ctx.i(val), lo, hi, site)?,
            Inst::Now { dst } => ctx.set(dst, now as u64),
            Inst::CheckDyn {
                kind,
                val,
                lo,
                hi,
                site,
            } => check_range(program, f, kind, ctx.i(val), ctx.i(lo), ctx.i(hi), site)?,
            Inst::Builtin {
                op,
                dst,
                first,
                count,
                site,
            } => {
                let args = program
                    .funcs
                    .get(f as usize)
                    .map(|x| x.builtin_args(first, count))
                    .unwrap_or(&[]);
                if let Err((kind, message)) = builtins::call(&mut ctx, op, dst, args) {
                    return Err(fault(program, f, Some(site), kind, message));
                }
            }
            Inst::Jump { target } => pc = target,
            Inst::Branch { cond, then, els } => pc = if ctx.get(cond) != 0 { then } else { els },
            Inst::Call {
                func: callee,
                this: t,
            } => {
                if stack.len() == stack.capacity() {
                    return Err(bad(
                        f,
                        format!("call depth exceeded calling function {callee} (recursion?)"),
                    ));
                }
                let new_this = addr(&ctx, this, t);
                stack.push(Frame { func: f, pc, this });
                f = callee;
                this = new_this;
                pc = 0;
                code = match program.funcs.get(f as usize) {
                    Some(x) => &x.code,
                    None => return Err(bad(f, format!("no function {f}"))),
                };
                ops = fast::slices(decoded, f);
                ctx.base = windows.get(f as usize).copied().unwrap_or(0) as usize;
            }
            Inst::Ret => match stack.pop() {
                None => return Ok(()),
                Some(fr) => {
                    f = fr.func;
                    pc = fr.pc;
                    this = fr.this;
                    code = program
                        .funcs
                        .get(f as usize)
                        .map(|x| x.code.as_slice())
                        .unwrap_or(&[]);
                    ops = fast::slices(decoded, f);
                    ctx.base = windows.get(f as usize).copied().unwrap_or(0) as usize;
                }
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shifts_and_rotations_at_width() {
        assert_eq!(shift(ShiftOp::Shl, 8, 0x81, 1), 0x02);
        assert_eq!(shift(ShiftOp::Rol, 8, 0x81, 1), 0x03);
        assert_eq!(shift(ShiftOp::Ror, 16, 1, 1), 0x8000);
        assert_eq!(shift(ShiftOp::Shr, 32, -1, 4), 0x0FFF_FFFF);
        assert_eq!(shift(ShiftOp::Shl, 8, 1, 9), 0);
        assert_eq!(shift(ShiftOp::Rol, 64, i64::MIN, 1), 1);
    }

    #[test]
    fn wraps_at_width() {
        assert_eq!(wrap(300, MemTy::U8), 44);
        assert_eq!(wrap(32768, MemTy::I16), -32768);
        assert_eq!(wrap(-1, MemTy::U32), 0xFFFF_FFFF);
    }
}
