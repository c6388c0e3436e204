//! Resolving a parsed scenario against a program and its plant: names to
//! places, signals or quantities; types checked (E321, E322); actions to
//! the coupling's [`Action`]s.
//!
//! A name is, in this order: `plant.<quantity>`; a signal of the model
//! (its bound variable when bound, so conditions see what the PLC sees;
//! the model's value otherwise); a variable path of the program.

use crate::ast::{self, ActionKind, CmpOp, Expr, Lit, LogicOp, Name};
use automat_base::{Code, Diagnostic, Span};
use automat_iec::Elementary as E;
use automat_ir::Program;
use automat_plant::{Dir, Kind, Plant, Value};
use automat_project::{image, Action, Binding, Sim};
use automat_runtime::{resolve, value, Place, PlaceType};

/// Where a referenced value comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum Src {
    Place(Place),
    Signal(usize),
    Quantity(usize),
}

/// The type of a value in a condition.
#[derive(Clone, Debug, PartialEq)]
pub enum Ty {
    Bool,
    Num,
    Time,
    Enum(String, Vec<(String, i64)>),
}

/// A referenced value: its name as written, source and type.
#[derive(Clone, Debug, PartialEq)]
pub struct Ref {
    pub name: String,
    pub src: Src,
    pub ty: Ty,
}

/// A resolved condition.
#[derive(Clone, Debug, PartialEq)]
pub enum Cond {
    Ref(usize),
    Bool(bool),
    Num(f64),
    Not(Box<Cond>),
    Logic(LogicOp, Box<Cond>, Box<Cond>),
    Cmp(CmpOp, Box<Cond>, Box<Cond>),
}

/// What the names of a scenario are resolved against.
pub struct Scope<'a> {
    pub program: &'a Program,
    pub plant: &'a dyn Plant,
    pub bindings: &'a [Binding],
}

fn ty_name(t: &Ty) -> String {
    match t {
        Ty::Bool => "BOOL".into(),
        Ty::Num => "a number".into(),
        Ty::Time => "a TIME".into(),
        Ty::Enum(n, _) => n.clone(),
    }
}

fn mismatch(span: Span, msg: String) -> Diagnostic {
    Diagnostic::error(Code::E322, span, msg)
}

fn place_ty(p: &Place) -> Option<Ty> {
    Some(match &p.ty {
        PlaceType::Elementary(E::Bool) => Ty::Bool,
        PlaceType::Elementary(e) if e.is_num() || e.is_bit_string() => Ty::Num,
        PlaceType::Elementary(e) if e.is_duration() => Ty::Time,
        PlaceType::Enum { name, values, .. } => Ty::Enum(name.clone(), values.clone()),
        _ => return None,
    })
}

fn kind_ty(k: Kind) -> Ty {
    match k {
        Kind::Bool => Ty::Bool,
        Kind::Int | Kind::Real => Ty::Num,
    }
}

impl Scope<'_> {
    fn signal(&self, name: &str) -> Option<usize> {
        self.plant
            .signals()
            .iter()
            .position(|s| s.name.eq_ignore_ascii_case(name))
    }

    /// Resolves a name used in a condition.
    pub fn reference(&self, n: &Name) -> Result<Ref, Diagnostic> {
        let unknown = |why: String| Diagnostic::error(Code::E321, n.span, why);
        if let Some(q) = n.text.strip_prefix("plant.") {
            let quantities = self.plant.quantities();
            let i = quantities
                .iter()
                .position(|x| x.name.eq_ignore_ascii_case(q))
                .ok_or_else(|| {
                    unknown(format!(
                        "the {} model has no quantity `{q}` (it has: {})",
                        self.plant.name(),
                        quantities
                            .iter()
                            .map(|x| x.name)
                            .collect::<Vec<_>>()
                            .join(", ")
                    ))
                })?;
            return Ok(Ref {
                name: n.text.clone(),
                src: Src::Quantity(i),
                ty: Ty::Num,
            });
        }
        if let Some(i) = self.signal(&n.text) {
            let kind = self.plant.signals().get(i).map_or(Kind::Bool, |s| s.kind);
            return Ok(match self.bindings.iter().find(|b| b.signal == i) {
                Some(b) => Ref {
                    name: n.text.clone(),
                    src: Src::Place(b.place.clone()),
                    ty: place_ty(&b.place).unwrap_or(kind_ty(kind)),
                },
                None => Ref {
                    name: n.text.clone(),
                    src: Src::Signal(i),
                    ty: kind_ty(kind),
                },
            });
        }
        let place = resolve(self.program, &n.text).map_err(|e| {
            unknown(format!(
                "`{}` is no signal of the {} model, no `plant.` quantity and no variable: {e}",
                n.text,
                self.plant.name()
            ))
        })?;
        let ty = place_ty(&place).ok_or_else(|| {
            mismatch(
                n.span,
                format!(
                    "`{}`: only BOOL, numbers, TIME and enumerations can be checked",
                    n.text
                ),
            )
        })?;
        Ok(Ref {
            name: n.text.clone(),
            src: Src::Place(place),
            ty,
        })
    }

    /// Resolves and type-checks a condition; `refs` collects the names.
    pub fn condition(&self, e: &Expr, refs: &mut Vec<Ref>) -> Result<Cond, Diagnostic> {
        let (c, ty, span) = self.typed(e, refs)?;
        if ty != Some(Ty::Bool) {
            return Err(mismatch(span, "a condition must be BOOL".into()));
        }
        Ok(c)
    }

    /// The condition, its type (`None` for an enumeration literal, typed by
    /// the other side of its comparison) and its span.
    fn typed(&self, e: &Expr, refs: &mut Vec<Ref>) -> Result<(Cond, Option<Ty>, Span), Diagnostic> {
        Ok(match e {
            Expr::Ref(n) => {
                let r = self.reference(n)?;
                let ty = r.ty.clone();
                let i = match refs.iter().position(|x| x.name == r.name) {
                    Some(i) => i,
                    None => {
                        refs.push(r);
                        refs.len() - 1
                    }
                };
                (Cond::Ref(i), Some(ty), n.span)
            }
            Expr::Lit(l, span) => match l {
                Lit::Bool(b) => (Cond::Bool(*b), Some(Ty::Bool), *span),
                Lit::Int(i) => (Cond::Num(*i as f64), Some(Ty::Num), *span),
                Lit::Real(r) => (Cond::Num(*r), Some(Ty::Num), *span),
                Lit::Time(t) => (Cond::Num(*t as f64), Some(Ty::Time), *span),
                Lit::Enum(..) => (Cond::Bool(false), None, *span),
            },
            Expr::Not(x) => {
                let (c, ty, span) = self.typed(x, refs)?;
                if ty != Some(Ty::Bool) {
                    return Err(mismatch(span, "NOT needs a BOOL operand".into()));
                }
                (Cond::Not(Box::new(c)), Some(Ty::Bool), span)
            }
            Expr::Logic(op, a, b) => {
                let (ca, ta, sa) = self.typed(a, refs)?;
                let (cb, tb, sb) = self.typed(b, refs)?;
                for (t, s) in [(&ta, sa), (&tb, sb)] {
                    if *t != Some(Ty::Bool) {
                        return Err(mismatch(s, "AND, OR and XOR need BOOL operands".into()));
                    }
                }
                (
                    Cond::Logic(*op, Box::new(ca), Box::new(cb)),
                    Some(Ty::Bool),
                    sa.to(sb),
                )
            }
            Expr::Cmp(op, a, b) => {
                let (ca, ta, sa) = self.typed(a, refs)?;
                let (cb, tb, sb) = self.typed(b, refs)?;
                let span = sa.to(sb);
                let (ca, cb) = match (&ta, &tb) {
                    (Some(Ty::Enum(..)), None) => (ca, enum_value(b, ta.as_ref(), sb)?),
                    (None, Some(Ty::Enum(..))) => (enum_value(a, tb.as_ref(), sa)?, cb),
                    (Some(x), Some(y)) if x == y => (ca, cb),
                    _ => {
                        return Err(mismatch(
                            span,
                            format!(
                                "cannot compare {} with {}",
                                ta.as_ref().map_or("an enumeration value".into(), ty_name),
                                tb.as_ref().map_or("an enumeration value".into(), ty_name)
                            ),
                        ))
                    }
                };
                if ta == Some(Ty::Bool) && !matches!(op, CmpOp::Eq | CmpOp::Ne) {
                    return Err(mismatch(
                        span,
                        "BOOL values compare only with = and <>".into(),
                    ));
                }
                (
                    Cond::Cmp(*op, Box::new(ca), Box::new(cb)),
                    Some(Ty::Bool),
                    span,
                )
            }
        })
    }

    /// The plant value of a literal set on something of type `ty`.
    fn lit_value(&self, lit: &Lit, ty: &Ty, span: Span, what: &str) -> Result<Value, Diagnostic> {
        let bad = || mismatch(span, format!("{what} is {}, not this value", ty_name(ty)));
        Ok(match (lit, ty) {
            (Lit::Bool(b), Ty::Bool) => Value::Bool(*b),
            (Lit::Int(i), Ty::Num) => Value::Int(*i),
            (Lit::Real(r), Ty::Num) => Value::Real(*r),
            (Lit::Time(t), Ty::Time) => Value::Int(*t),
            (Lit::Enum(t, v), Ty::Enum(name, values)) if t.eq_ignore_ascii_case(name) => values
                .iter()
                .find(|(n, _)| n.eq_ignore_ascii_case(v))
                .map(|(_, x)| Value::Int(*x))
                .ok_or_else(|| mismatch(span, format!("{name} has no value `{v}`")))?,
            _ => return Err(bad()),
        })
    }

    /// `press` (with its release after `dur`) or `release`: an operator
    /// signal, or a BOOL variable of the program that is no signal.
    fn press(
        &self,
        n: &Name,
        t: i64,
        press: bool,
        dur: Option<i64>,
    ) -> Result<Vec<(i64, Action)>, Diagnostic> {
        let make = |v: bool| -> Result<Action, Diagnostic> {
            match self.signal(&n.text) {
                Some(i) => {
                    let s = self.plant.signals().get(i);
                    if s.is_none_or(|s| s.kind != Kind::Bool || s.dir != Dir::Operator) {
                        return Err(mismatch(
                            n.span,
                            format!(
                                "`{}` is not a BOOL operator signal; use `stuck` for sensors and actuators",
                                n.text
                            ),
                        ));
                    }
                    Ok(Action::Set {
                        signal: i,
                        value: Value::Bool(v),
                    })
                }
                None => {
                    let r = self.reference(n)?;
                    let (Src::Place(place), Ty::Bool) = (r.src, r.ty) else {
                        return Err(mismatch(n.span, format!("`{}` is not BOOL", n.text)));
                    };
                    Ok(Action::Write {
                        place,
                        value: Value::Bool(v),
                    })
                }
            }
        };
        let mut out = vec![(t, make(press)?)];
        if let (true, Some(d)) = (press, dur) {
            out.push((t.saturating_add(d), make(false)?));
        }
        Ok(out)
    }

    /// Resolves one `at` action into coupling actions at their times.
    pub fn action(&self, a: &ast::Action) -> Result<Vec<(i64, Action)>, Diagnostic> {
        let t = a.at_ns;
        let signal_of = |n: &Name| {
            self.signal(&n.text).ok_or_else(|| {
                Diagnostic::error(
                    Code::E302,
                    n.span,
                    format!(
                        "the {} model has no signal `{}` (it has: {})",
                        self.plant.name(),
                        n.text,
                        self.plant
                            .signals()
                            .iter()
                            .map(|s| s.name)
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                )
            })
        };
        let sig = |i: usize| self.plant.signals().get(i).copied();
        Ok(match &a.kind {
            ActionKind::Press(n, dur) => self.press(n, t, true, *dur)?,
            ActionKind::Release(n) => self.press(n, t, false, None)?,
            ActionKind::Set(n, lit, span) => match self.signal(&n.text) {
                Some(i) => {
                    let s = sig(i).ok_or_else(|| mismatch(n.span, "no signal".into()))?;
                    if s.dir != Dir::Operator {
                        return Err(mismatch(
                            n.span,
                            format!("`{}` is not an operator signal: use `stuck` to force a sensor or actuator", n.text),
                        ));
                    }
                    let value =
                        self.lit_value(lit, &kind_ty(s.kind), *span, &format!("`{}`", n.text))?;
                    vec![(t, Action::Set { signal: i, value })]
                }
                None => {
                    let r = self.reference(n)?;
                    let Src::Place(place) = r.src else {
                        return Err(mismatch(n.span, format!("`{}` cannot be set", n.text)));
                    };
                    let value = self.lit_value(lit, &r.ty, *span, &format!("`{}`", n.text))?;
                    vec![(t, Action::Write { place, value })]
                }
            },
            ActionKind::Stuck(n, lit, span) => {
                let i = signal_of(n)?;
                let kind = sig(i).map_or(Kind::Bool, |s| s.kind);
                let value = self.lit_value(lit, &kind_ty(kind), *span, &format!("`{}`", n.text))?;
                vec![(t, Action::Stuck { signal: i, value })]
            }
            ActionKind::Unstick(n) => vec![(
                t,
                Action::Unstick {
                    signal: signal_of(n)?,
                },
            )],
            ActionKind::Noise(n, amplitude) => {
                let i = signal_of(n)?;
                if sig(i).is_none_or(|s| s.kind == Kind::Bool || s.dir == Dir::Actuator) {
                    return Err(mismatch(
                        n.span,
                        format!("noise needs an Int or Real sensor; `{}` is not", n.text),
                    ));
                }
                vec![(
                    t,
                    Action::Noise {
                        signal: i,
                        amplitude: *amplitude,
                    },
                )]
            }
            ActionKind::Plant(cmd, args) => vec![(
                t,
                Action::Command {
                    name: cmd.text.clone(),
                    args: args.clone(),
                },
            )],
        })
    }
}

/// An enumeration literal compared with a value of type `ty`, as its number.
fn enum_value(e: &Expr, ty: Option<&Ty>, span: Span) -> Result<Cond, Diagnostic> {
    let (Expr::Lit(Lit::Enum(t, v), _), Some(Ty::Enum(name, values))) = (e, ty) else {
        return Err(mismatch(
            span,
            "cannot compare two enumeration literals".into(),
        ));
    };
    if !t.eq_ignore_ascii_case(name) {
        return Err(mismatch(
            span,
            format!("`{t}#{v}` is not a value of {name}"),
        ));
    }
    values
        .iter()
        .find(|(n, _)| n.eq_ignore_ascii_case(v))
        .map(|(_, x)| Cond::Num(*x as f64))
        .ok_or_else(|| mismatch(span, format!("{name} has no value `{v}`")))
}

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

impl Ref {
    pub fn read(&self, image: &[u8], sim: &Sim) -> Val {
        match &self.src {
            Src::Place(p) => image::read(image, p).map_or(Val::N(f64::NAN), to_val),
            Src::Signal(i) => to_val(sim.plant().get(*i)),
            Src::Quantity(i) => Val::N(sim.plant().quantity(*i)),
        }
    }

    /// The value as people read it (`TRUE`, `CraneStep#Rest1`, `0.05`).
    pub fn show(&self, image: &[u8], sim: &Sim) -> String {
        match &self.src {
            Src::Place(p) => value::format(image, p),
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

impl Cond {
    pub fn eval(&self, vals: &[Val]) -> Val {
        match self {
            Cond::Ref(i) => vals.get(*i).copied().unwrap_or(Val::B(false)),
            Cond::Bool(b) => Val::B(*b),
            Cond::Num(x) => Val::N(*x),
            Cond::Not(x) => Val::B(!x.truth(vals)),
            Cond::Logic(op, a, b) => {
                let (a, b) = (a.truth(vals), b.truth(vals));
                Val::B(match op {
                    LogicOp::And => a && b,
                    LogicOp::Or => a || b,
                    LogicOp::Xor => a != b,
                })
            }
            Cond::Cmp(op, a, b) => {
                let num = |v: Val| match v {
                    Val::B(b) => f64::from(u8::from(b)),
                    Val::N(x) => x,
                };
                let (x, y) = (num(a.eval(vals)), num(b.eval(vals)));
                Val::B(match op {
                    CmpOp::Eq => x == y,
                    CmpOp::Ne => x != y,
                    CmpOp::Lt => x < y,
                    CmpOp::Le => x <= y,
                    CmpOp::Gt => x > y,
                    CmpOp::Ge => x >= y,
                })
            }
        }
    }

    pub fn truth(&self, vals: &[Val]) -> bool {
        match self.eval(vals) {
            Val::B(b) => b,
            Val::N(x) => x != 0.0,
        }
    }
}
