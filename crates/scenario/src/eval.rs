//! Judging a resolved scenario during a run: the values a condition sees
//! (read from the image, the plant or the coupling each scan), and the
//! evaluation of [`Cond`]s on them. `check.rs` builds what is judged here.

use crate::ast::{ArithOp, CmpOp, LogicOp};
use crate::check::{Cond, Ref, Src};
use automat_iec::Elementary as E;
use automat_plant::Value;
use automat_project::{image, Sim};
use automat_runtime::{value, Place, PlaceType};

/// A value during a run: BOOL, or a number (TIME in ns, enumerations by
/// their value).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Val {
    B(bool),
    N(f64),
}

fn to_val(v: Value) -> Val {
    match v {
        Value::Bool(b) => Val::B(b),
        Value::Int(i) => Val::N(i as f64),
        Value::Real(r) => Val::N(r),
    }
}

/// The value at `p` as the judge sees it: what `image::read` then `to_val`
/// give, read straight from the bytes for the elementary types the
/// scenarios name every scan (BOOL, integers and bit strings, REAL,
/// LREAL, TIME), without going through `automat_iec::Value`; every other
/// place takes the general path.
fn read_place(image: &[u8], p: &Place) -> Val {
    fn at<const N: usize>(image: &[u8], offset: u32) -> Option<[u8; N]> {
        let start = usize::try_from(offset).ok()?;
        image.get(start..start.checked_add(N)?)?.try_into().ok()
    }
    let ty = match &p.ty {
        PlaceType::Elementary(e) => *e,
        PlaceType::Enum { base, .. } if p.bit.is_none() => *base,
        _ => return image::read(image, p).map_or(Val::N(f64::NAN), to_val),
    };
    let n = |v: Option<f64>| Val::N(v.unwrap_or(f64::NAN));
    match ty {
        E::Bool => match (at::<1>(image, p.offset), p.bit) {
            (Some([b]), Some(k)) => Val::B(k < 8 && b >> k & 1 != 0),
            (Some([b]), None) => Val::B(b != 0),
            (None, _) => Val::N(f64::NAN),
        },
        E::Sint => n(at(image, p.offset).map(|b| i8::from_le_bytes(b) as f64)),
        E::Int => n(at(image, p.offset).map(|b| i16::from_le_bytes(b) as f64)),
        E::Dint => n(at(image, p.offset).map(|b| i32::from_le_bytes(b) as f64)),
        E::Lint | E::Time | E::Ltime => {
            n(at(image, p.offset).map(|b| i64::from_le_bytes(b) as f64))
        }
        E::Usint | E::Byte => n(at(image, p.offset).map(|b| u8::from_le_bytes(b) as f64)),
        E::Uint | E::Word => n(at(image, p.offset).map(|b| u16::from_le_bytes(b) as f64)),
        E::Udint | E::Dword => n(at(image, p.offset).map(|b| u32::from_le_bytes(b) as f64)),
        // Beyond i64 the general path saturates (`image::read`).
        E::Ulint | E::Lword => n(at(image, p.offset)
            .map(|b| i64::try_from(u64::from_le_bytes(b)).unwrap_or(i64::MAX) as f64)),
        E::Real => n(at(image, p.offset).map(|b| f64::from(f32::from_le_bytes(b)))),
        E::Lreal => n(at(image, p.offset).map(f64::from_le_bytes)),
        _ => image::read(image, p).map_or(Val::N(f64::NAN), to_val),
    }
}

impl Ref {
    pub fn read(&self, image: &[u8], sim: &Sim) -> Val {
        match &self.src {
            Src::Place(p) => read_place(image, p),
            Src::Located(l) => l
                .place(image)
                .map_or(Val::N(f64::NAN), |p| read_place(image, &p)),
            Src::Signal(i) => to_val(sim.plant().get(*i)),
            Src::Quantity(i) => Val::N(sim.plant().quantity(*i)),
        }
    }

    /// The value as people read it (`TRUE`, `CraneStep#Rest1`, `0.05`).
    pub fn show(&self, image: &[u8], sim: &Sim) -> String {
        match &self.src {
            Src::Place(p) => value::format(image, p),
            Src::Located(l) => match l.place(image) {
                Ok(p) => value::format(image, &p),
                Err(e) => format!("? ({e})"),
            },
            Src::Signal(i) => show_value(sim.plant().get(*i)),
            Src::Quantity(i) => show_f64(sim.plant().quantity(*i)),
        }
    }
}

pub fn show_value(v: Value) -> String {
    match v {
        Value::Bool(true) => "TRUE".into(),
        Value::Bool(false) => "FALSE".into(),
        Value::Int(i) => i.to_string(),
        Value::Real(r) => show_f64(r),
    }
}

/// A quantity with at most 6 decimals, trailing zeros dropped.
pub fn show_f64(x: f64) -> String {
    let s = format!("{x:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.to_string()
    }
}

/// The values a condition is evaluated on: after this scan, after the
/// previous one, and the expectation's counters.
#[derive(Clone, Copy)]
pub struct Frame<'a> {
    pub now: &'a [Val],
    pub prev: &'a [Val],
    pub counts: &'a [f64],
}

impl<'a> Frame<'a> {
    /// Values of one scan (no previous scan, no counters).
    pub fn of(vals: &'a [Val]) -> Frame<'a> {
        Frame {
            now: vals,
            prev: vals,
            counts: &[],
        }
    }
    fn before(&self) -> Frame<'a> {
        Frame {
            now: self.prev,
            ..*self
        }
    }
}

/// Whether two values are the same (NaN is the same as NaN: a value that
/// cannot be read does not change).
pub fn same(a: Val, b: Val) -> bool {
    match (a, b) {
        (Val::B(x), Val::B(y)) => x == y,
        (Val::N(x), Val::N(y)) => x == y || (x.is_nan() && y.is_nan()),
        _ => false,
    }
}

fn num(v: Val) -> f64 {
    match v {
        Val::B(b) => f64::from(u8::from(b)),
        Val::N(x) => x,
    }
}

impl Cond {
    /// The value on the frame. Division by zero gives ±infinity or NaN (a
    /// comparison with NaN is FALSE); `MOD` by zero gives 0, as in IEC.
    pub fn eval(&self, f: Frame) -> Val {
        self.value(&f)
    }

    pub fn truth(&self, f: Frame) -> bool {
        self.holds(&f)
    }

    /// [`Cond::eval`] with the frame by reference: evaluated for several
    /// expectations every scan, the tree walk should not copy the frame's
    /// three slices at every node.
    fn value(&self, f: &Frame) -> Val {
        match self {
            Cond::Ref(i) => f.now.get(*i).copied().unwrap_or(Val::B(false)),
            Cond::Bool(b) => Val::B(*b),
            Cond::Num(x) => Val::N(*x),
            Cond::Not(x) => Val::B(!x.holds(f)),
            // Conditions have no side effects: AND and OR stop early.
            Cond::Logic(op, a, b) => Val::B(match op {
                LogicOp::And => a.holds(f) && b.holds(f),
                LogicOp::Or => a.holds(f) || b.holds(f),
                LogicOp::Xor => a.holds(f) != b.holds(f),
            }),
            Cond::Cmp(op, a, b) => {
                let (x, y) = (num(a.value(f)), num(b.value(f)));
                Val::B(match op {
                    CmpOp::Eq => x == y,
                    CmpOp::Ne => x != y,
                    CmpOp::Lt => x < y,
                    CmpOp::Le => x <= y,
                    CmpOp::Gt => x > y,
                    CmpOp::Ge => x >= y,
                })
            }
            Cond::Arith(op, a, b) => {
                let (x, y) = (num(a.value(f)), num(b.value(f)));
                Val::N(match op {
                    ArithOp::Add => x + y,
                    ArithOp::Sub => x - y,
                    ArithOp::Mul => x * y,
                    ArithOp::Div => x / y,
                    ArithOp::Mod if y == 0.0 => 0.0,
                    ArithOp::Mod => x % y,
                })
            }
            Cond::Neg(x) => Val::N(-num(x.value(f))),
            Cond::Abs(x) => Val::N(num(x.value(f)).abs()),
            Cond::Min(a, b) => Val::N(num(a.value(f)).min(num(b.value(f)))),
            Cond::Max(a, b) => Val::N(num(a.value(f)).max(num(b.value(f)))),
            Cond::Prev(x) => x.value(&f.before()),
            Cond::Rise(x) => Val::B(x.holds(f) && !x.holds(&f.before())),
            Cond::Fall(x) => Val::B(!x.holds(f) && x.holds(&f.before())),
            Cond::Change(x) => Val::B(!same(x.value(f), x.value(&f.before()))),
            Cond::Count(i) => Val::N(f.counts.get(*i).copied().unwrap_or(0.0)),
        }
    }

    fn holds(&self, f: &Frame) -> bool {
        match self.value(f) {
            Val::B(b) => b,
            Val::N(x) => x != 0.0,
        }
    }

    /// Whether `rise`, `fall` or `change` occurs in it.
    pub fn has_event(&self) -> bool {
        match self {
            Cond::Rise(_) | Cond::Fall(_) | Cond::Change(_) => true,
            Cond::Not(x) | Cond::Neg(x) | Cond::Abs(x) | Cond::Prev(x) => x.has_event(),
            Cond::Logic(_, a, b)
            | Cond::Cmp(_, a, b)
            | Cond::Arith(_, a, b)
            | Cond::Min(a, b)
            | Cond::Max(a, b) => a.has_event() || b.has_event(),
            Cond::Ref(_) | Cond::Bool(_) | Cond::Num(_) | Cond::Count(_) => false,
        }
    }

    /// The references it reads, each once, in order of first use.
    pub fn refs(&self, out: &mut Vec<usize>) {
        match self {
            Cond::Ref(i) => {
                if !out.contains(i) {
                    out.push(*i);
                }
            }
            Cond::Not(x)
            | Cond::Neg(x)
            | Cond::Abs(x)
            | Cond::Prev(x)
            | Cond::Rise(x)
            | Cond::Fall(x)
            | Cond::Change(x) => x.refs(out),
            Cond::Logic(_, a, b)
            | Cond::Cmp(_, a, b)
            | Cond::Arith(_, a, b)
            | Cond::Min(a, b)
            | Cond::Max(a, b) => {
                a.refs(out);
                b.refs(out);
            }
            Cond::Bool(_) | Cond::Num(_) | Cond::Count(_) => {}
        }
    }

    /// Whether it looks at the values after the previous scan (`prev`,
    /// `rise`, `fall`, `change`).
    pub fn uses_prev(&self) -> bool {
        match self {
            Cond::Prev(_) | Cond::Rise(_) | Cond::Fall(_) | Cond::Change(_) => true,
            Cond::Not(x) | Cond::Neg(x) | Cond::Abs(x) => x.uses_prev(),
            Cond::Logic(_, a, b)
            | Cond::Cmp(_, a, b)
            | Cond::Arith(_, a, b)
            | Cond::Min(a, b)
            | Cond::Max(a, b) => a.uses_prev() || b.uses_prev(),
            Cond::Ref(_) | Cond::Bool(_) | Cond::Num(_) | Cond::Count(_) => false,
        }
    }
}
