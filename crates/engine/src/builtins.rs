//! The standard functions of [`Builtin`], implemented with `automat-iec`.
//! Errors come back as a fault kind and a message; the caller adds the site.

use crate::interp::Ctx;
use crate::mem;
use automat_iec::{Elementary as E, ErrorKind, IecError, Value};
use automat_ir::code::{Builtin, MathFn, Reg, StrFn, TimeFn};
use automat_ir::FaultKind;

type R = Result<(), (FaultKind, String)>;

fn iec(e: IecError) -> (FaultKind, String) {
    let kind = match e.kind {
        ErrorKind::DivisionByZero => FaultKind::DivisionByZero,
        ErrorKind::StringIndex => FaultKind::StringIndex,
        _ => FaultKind::Function,
    };
    (kind, e.message)
}

fn arg(args: &[Reg], i: usize) -> Result<Reg, (FaultKind, String)> {
    args.get(i)
        .copied()
        .ok_or_else(|| (FaultKind::Function, format!("builtin argument {i} missing")))
}

/// A register's bits as a value of type `e`.
pub fn to_value(bits: u64, e: E) -> Value {
    let i = bits as i64;
    match e {
        E::Bool => Value::Bool(bits & 1 != 0),
        E::Real => Value::Real(f32::from_bits(bits as u32) as f64, E::Real),
        E::Lreal => Value::Real(f64::from_bits(bits), E::Lreal),
        E::Time | E::Ltime => Value::Duration(i, e),
        E::Date | E::Ldate => Value::Date(i, e),
        E::Tod | E::Ltod => Value::Tod(i, e),
        E::Dt | E::Ldt => Value::Dt(i, e),
        E::Char => Value::Char(bits as u8),
        E::Wchar => Value::WChar(bits as u16),
        E::String | E::Wstring => Value::Str(Vec::new()),
        _ if e.is_unsigned_int() || e.is_bit_string() => Value::Int(bits as i128, e),
        _ => Value::Int(i as i128, e),
    }
}

/// A value as register bits.
pub fn from_value(v: &Value) -> u64 {
    match v {
        Value::Bool(b) => *b as u64,
        Value::Int(i, _) => *i as i64 as u64,
        Value::Real(r, E::Real) => (*r as f32).to_bits() as u64,
        Value::Real(r, _) => r.to_bits(),
        Value::Duration(i, _) | Value::Date(i, _) | Value::Tod(i, _) | Value::Dt(i, _) => *i as u64,
        Value::Char(c) => *c as u64,
        Value::WChar(c) => *c as u64,
        Value::Str(_) | Value::WStr(_) => 0,
    }
}

pub fn call(ctx: &mut Ctx, op: Builtin, dst: Option<Reg>, args: &[Reg]) -> R {
    let a = |i: usize| arg(args, i);
    let set = |ctx: &mut Ctx, v: u64| {
        if let Some(d) = dst {
            ctx.set(d, v);
        }
    };
    match op {
        Builtin::Math(m, wide) => {
            let x = if wide {
                f64::from_bits(ctx.get(a(0)?))
            } else {
                f32::from_bits(ctx.get(a(0)?) as u32) as f64
            };
            let y = math(m, x);
            set(
                ctx,
                if wide {
                    y.to_bits()
                } else {
                    (y as f32).to_bits() as u64
                },
            );
        }
        Builtin::Pow(wide) | Builtin::PowInt(wide) => {
            let b = ctx.get(a(0)?);
            let e = ctx.get(a(1)?);
            let r = match (op, wide) {
                (Builtin::Pow(_), true) => {
                    automat_iec::arith::expt_lreal(f64::from_bits(b), f64::from_bits(e)).to_bits()
                }
                (Builtin::Pow(_), false) => automat_iec::arith::expt_real(
                    f32::from_bits(b as u32),
                    f32::from_bits(e as u32),
                )
                .to_bits() as u64,
                (_, true) => {
                    automat_iec::arith::expt_lreal_int(f64::from_bits(b), e as i64).to_bits()
                }
                (_, false) => automat_iec::arith::expt_real_int(f32::from_bits(b as u32), e as i64)
                    .to_bits() as u64,
            };
            set(ctx, r);
        }
        Builtin::Convert(from, to) => {
            let v = to_value(ctx.get(a(0)?), from);
            let r = automat_iec::convert(&v, to).map_err(iec)?;
            set(ctx, from_value(&r));
        }
        Builtin::Trunc(from, to) => {
            let v = to_value(ctx.get(a(0)?), from);
            let r = automat_iec::trunc(&v, to).map_err(iec)?;
            set(ctx, from_value(&r));
        }
        Builtin::ToString(from, wide) => {
            if !wide && crate::strplace::int_text(ctx, from, args).is_some() {
                return Ok(());
            }
            let (d, cap) = (ctx.get(a(0)?) as u32, ctx.get(a(1)?) as u32);
            let v = to_value(ctx.get(a(2)?), from);
            let target = if wide { E::Wstring } else { E::String };
            let r = automat_iec::convert(&v, target).map_err(iec)?;
            write(ctx, d, cap, &r)?;
        }
        Builtin::FromString(to, wide) => {
            let s = ctx.get(a(0)?) as u32;
            let v = if wide {
                Value::WStr(mem::read_wstr(ctx.image, s))
            } else {
                Value::Str(mem::read_str(ctx.image, s))
            };
            let r = automat_iec::convert(&v, to).map_err(iec)?;
            set(ctx, from_value(&r));
        }
        Builtin::Str(s, wide) => {
            if !wide && crate::strplace::narrow(ctx, s, dst, args).is_some() {
                return Ok(());
            }
            if wide {
                strings::<u16>(ctx, s, dst, args, true)?
            } else {
                strings::<u8>(ctx, s, dst, args, false)?
            }
        }
        Builtin::Time(t) => {
            let x = ctx.get(a(0)?) as i64;
            let yb = ctx.get(a(1)?);
            let y = yb as i64;
            use automat_iec::time as tm;
            let r = match t {
                TimeFn::AddTime => tm::add_time(x, y),
                TimeFn::SubTime => tm::sub_time(x, y),
                TimeFn::AddTodTime => Ok(tm::add_tod_time(x, y)),
                TimeFn::SubTodTime => Ok(tm::sub_tod_time(x, y)),
                TimeFn::SubTodTod => tm::sub_tod_tod(x, y),
                TimeFn::AddDtTime => tm::add_dt_time(x, y),
                TimeFn::SubDtTime => tm::sub_dt_time(x, y),
                TimeFn::SubDtDt => tm::sub_dt_dt(x, y),
                TimeFn::SubDateDate => tm::sub_date_date(x, y),
                TimeFn::MulTime => tm::mul_time(x, y),
                TimeFn::DivTime => tm::div_time(x, y),
                TimeFn::MulTimeReal => tm::mul_time_real(x, f64::from_bits(yb)),
                TimeFn::DivTimeReal => tm::div_time_real(x, f64::from_bits(yb)),
                TimeFn::ConcatDateTod => tm::concat_date_tod(x, y),
            }
            .map_err(iec)?;
            set(ctx, r as u64);
        }
        Builtin::FromBcd(from, to) => {
            let v = to_value(ctx.get(a(0)?), from);
            let r = automat_iec::convert::from_bcd(&v, to).map_err(bcd)?;
            set(ctx, from_value(&r));
        }
        Builtin::ToBcd(from, to) => {
            let v = to_value(ctx.get(a(0)?), from);
            let r = automat_iec::convert::to_bcd(&v, to).map_err(bcd)?;
            set(ctx, from_value(&r));
        }
        Builtin::Atan2(wide) => {
            let (y, x) = (ctx.get(a(0)?), ctx.get(a(1)?));
            let r = if wide {
                f64::from_bits(y).atan2(f64::from_bits(x)).to_bits()
            } else {
                f32::from_bits(y as u32)
                    .atan2(f32::from_bits(x as u32))
                    .to_bits() as u64
            };
            set(ctx, r);
        }
        Builtin::Date(d) => {
            let mut xs = [0i64; 7];
            for (i, x) in xs.iter_mut().enumerate().take(args.len().min(7)) {
                *x = ctx.get(a(i)?) as i64;
            }
            let r = crate::dates::call(d, &xs).map_err(iec)?;
            set(ctx, r as u64);
        }
        Builtin::StrConv(to_wide) => {
            let (d, cap, s) = (
                ctx.get(a(0)?) as u32,
                ctx.get(a(1)?) as u32,
                ctx.get(a(2)?) as u32,
            );
            let ok = if to_wide {
                let w = automat_iec::convert::str_to_wstr(&mem::read_str(ctx.image, s));
                mem::write_wstr(ctx.image, d, cap, &w)
            } else {
                let n = automat_iec::convert::wstr_to_str(&mem::read_wstr(ctx.image, s));
                mem::write_str(ctx.image, d, cap, &n)
            };
            ok.ok_or((
                FaultKind::Function,
                format!("string store at {d} outside the image"),
            ))?;
        }
    }
    Ok(())
}

/// BCD errors are function faults whatever the library calls them.
fn bcd(e: IecError) -> (FaultKind, String) {
    (FaultKind::Function, e.message)
}

fn math(m: MathFn, x: f64) -> f64 {
    match m {
        MathFn::Abs => x.abs(),
        MathFn::Sqrt => x.sqrt(),
        MathFn::Ln => x.ln(),
        MathFn::Log => x.log10(),
        MathFn::Exp => x.exp(),
        MathFn::Sin => x.sin(),
        MathFn::Cos => x.cos(),
        MathFn::Tan => x.tan(),
        MathFn::Asin => x.asin(),
        MathFn::Acos => x.acos(),
        MathFn::Atan => x.atan(),
        MathFn::Neg => -x,
    }
}

fn write(ctx: &mut Ctx, d: u32, cap: u32, v: &Value) -> R {
    let ok = match v {
        Value::Str(s) => mem::write_str(ctx.image, d, cap, s),
        Value::WStr(s) => mem::write_wstr(ctx.image, d, cap, s),
        _ => None,
    };
    ok.ok_or((
        FaultKind::Function,
        format!("string store at {d} outside the image"),
    ))
}

/// Character units of STRING (u8) and WSTRING (u16).
trait Unit: Copy + Ord + Default {
    fn read(image: &[u8], at: u32) -> Vec<Self>;
    fn write(image: &mut [u8], at: u32, cap: u32, s: &[Self]) -> Option<()>;
    fn from_code(c: u64) -> Self;
}

impl Unit for u8 {
    fn read(image: &[u8], at: u32) -> Vec<u8> {
        mem::read_str(image, at)
    }
    fn write(image: &mut [u8], at: u32, cap: u32, s: &[u8]) -> Option<()> {
        mem::write_str(image, at, cap, s)
    }
    fn from_code(c: u64) -> u8 {
        c as u8
    }
}

impl Unit for u16 {
    fn read(image: &[u8], at: u32) -> Vec<u16> {
        mem::read_wstr(image, at)
    }
    fn write(image: &mut [u8], at: u32, cap: u32, s: &[u16]) -> Option<()> {
        mem::write_wstr(image, at, cap, s)
    }
    fn from_code(c: u64) -> u16 {
        c as u16
    }
}

fn strings<C: Unit>(ctx: &mut Ctx, s: StrFn, dst: Option<Reg>, args: &[Reg], _wide: bool) -> R {
    use automat_iec::strings as st;
    let a = |i: usize| arg(args, i);
    let rd = |ctx: &Ctx, i: usize| -> Result<Vec<C>, (FaultKind, String)> {
        Ok(C::read(ctx.image, ctx.get(a(i)?) as u32))
    };
    let int =
        |ctx: &Ctx, i: usize| -> Result<i64, (FaultKind, String)> { Ok(ctx.get(a(i)?) as i64) };
    // Functions with a scalar result.
    match s {
        StrFn::Len => {
            let n = rd(ctx, 0)?.len();
            if let Some(d) = dst {
                ctx.set(d, n as u64);
            }
            return Ok(());
        }
        StrFn::Find => {
            let p = st::find(&rd(ctx, 0)?, &rd(ctx, 1)?);
            if let Some(d) = dst {
                ctx.set(d, p as u64);
            }
            return Ok(());
        }
        StrFn::Compare => {
            let o = st::compare(&rd(ctx, 0)?, &rd(ctx, 1)?) as i64;
            if let Some(d) = dst {
                ctx.set(d, o as u64);
            }
            return Ok(());
        }
        _ => {}
    }
    let (d, cap) = (ctx.get(a(0)?) as u32, ctx.get(a(1)?) as u32);
    let out: Vec<C> = match s {
        StrFn::Assign => rd(ctx, 2)?,
        StrFn::Left => st::left(&rd(ctx, 2)?, int(ctx, 3)?).map_err(iec)?,
        StrFn::Right => st::right(&rd(ctx, 2)?, int(ctx, 3)?).map_err(iec)?,
        StrFn::Mid => st::mid(&rd(ctx, 2)?, int(ctx, 3)?, int(ctx, 4)?).map_err(iec)?,
        StrFn::Concat => {
            let parts = (2..args.len())
                .map(|i| rd(ctx, i))
                .collect::<Result<Vec<_>, _>>()?;
            let refs: Vec<&[C]> = parts.iter().map(Vec::as_slice).collect();
            st::concat(&refs)
        }
        StrFn::Insert => st::insert(&rd(ctx, 2)?, &rd(ctx, 3)?, int(ctx, 4)?).map_err(iec)?,
        StrFn::Delete => st::delete(&rd(ctx, 2)?, int(ctx, 3)?, int(ctx, 4)?).map_err(iec)?,
        StrFn::Replace => {
            st::replace(&rd(ctx, 2)?, &rd(ctx, 3)?, int(ctx, 4)?, int(ctx, 5)?).map_err(iec)?
        }
        StrFn::FromChar => vec![C::from_code(ctx.get(a(2)?))],
        StrFn::Len | StrFn::Find | StrFn::Compare => Vec::new(),
    };
    C::write(ctx.image, d, cap, &out).ok_or((
        FaultKind::Function,
        format!("string store at {d} outside the image"),
    ))
}
