//! Resolving a parsed scenario against a program and its plant: names to
//! places, signals or quantities; types checked (E321, E322); actions to
//! the coupling's [`Action`]s.
//!
//! A name is, in this order: `plant.<quantity>`; a signal of the model
//! (its bound variable when bound, so conditions see what the PLC sees;
//! the model's value otherwise); a variable path of the program (also a
//! direct address `%IX0.1`, or a dialect's operand such as FST `I0.1`).
//!
//! A project without `[plant]` is checked against [`NoPlant`]: every name
//! is a variable, `press`/`release`/`set` write variables, and what needs
//! a model (`plant.` quantities, `stuck`, `unstick`, `noise`, `plant`
//! commands) is E325. Functions out of place (`count` outside a window,
//! an event inside `rise`/`prev`) are E326.

use crate::ast::{self, ActionKind, ArithOp, CmpOp, Expr, Func, Lit, LogicOp, Name};
use automat_base::{Code, Diagnostic, Span};
use automat_iec::Elementary as E;
use automat_ir::Program;
use automat_plant::{Dir, Kind, Plant, Value};
use automat_project::{Action, Binding};
use automat_runtime::slc_place::looks_dynamic;
use automat_runtime::{locate, resolve, Locator, Place, PlaceType};

/// Where a referenced value comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum Src {
    Place(Place),
    /// An SLC-500 indexed or indirect address, found in each scan's image.
    Located(Locator),
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

/// A resolved condition or value.
#[derive(Clone, Debug, PartialEq)]
pub enum Cond {
    Ref(usize),
    Bool(bool),
    Num(f64),
    Not(Box<Cond>),
    Logic(LogicOp, Box<Cond>, Box<Cond>),
    Cmp(CmpOp, Box<Cond>, Box<Cond>),
    Arith(ArithOp, Box<Cond>, Box<Cond>),
    Neg(Box<Cond>),
    Abs(Box<Cond>),
    Min(Box<Cond>, Box<Cond>),
    Max(Box<Cond>, Box<Cond>),
    /// The value after the previous scan (before the first: the initial
    /// values).
    Prev(Box<Cond>),
    Rise(Box<Cond>),
    Fall(Box<Cond>),
    Change(Box<Cond>),
    /// The counter of the expectation's `count(...)` number n.
    Count(usize),
}

/// A project without a plant: no signals, no quantities.
pub struct NoPlant;

impl Plant for NoPlant {
    fn name(&self) -> &'static str {
        "none"
    }
    fn signals(&self) -> &'static [automat_plant::Signal] {
        &[]
    }
    fn quantities(&self) -> &'static [automat_plant::Quantity] {
        &[]
    }
    fn set(&mut self, _: usize, _: Value) {}
    fn get(&self, _: usize) -> Value {
        Value::Bool(false)
    }
    fn quantity(&self, _: usize) -> f64 {
        f64::NAN
    }
    fn step_ns(&self) -> i64 {
        // Nothing to integrate: one step per scan at most.
        i64::MAX / 4
    }
    fn step(&mut self, _: i64, _: &mut automat_plant::Rng) {}
}

/// Where the checker is in an expression: what it may contain there.
#[derive(Default)]
pub struct Ctx {
    /// The `count(...)` arguments met so far; `None`: no count allowed
    /// (the expectation has no window to count over).
    pub counts: Option<Vec<Cond>>,
    /// Inside `rise`, `fall`, `change` or `prev` (values of one scan).
    in_temporal: bool,
    /// Inside `count`.
    in_count: bool,
}

impl Ctx {
    /// A context where `count(...)` counts over the expectation's window.
    pub fn counting() -> Ctx {
        Ctx {
            counts: Some(Vec::new()),
            ..Ctx::default()
        }
    }
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
    type_ty(&p.ty)
}

fn type_ty(ty: &PlaceType) -> Option<Ty> {
    Some(match ty {
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

    /// Whether the project has no plant ([`NoPlant`]).
    pub fn plantless(&self) -> bool {
        self.plant.signals().is_empty() && self.plant.quantities().is_empty()
    }

    /// E325: `what` needs a plant model, and the project has none.
    fn needs_plant(&self, span: Span, what: &str) -> Diagnostic {
        Diagnostic::error(
            Code::E325,
            span,
            format!("{what} needs a plant model, and the project has no [plant]"),
        )
        .with_note("without a plant, a scenario sets and presses the program's own variables (`set x = 5`, `press Start for 200ms`) and checks them")
    }

    /// Resolves a name used in a condition.
    pub fn reference(&self, n: &Name) -> Result<Ref, Diagnostic> {
        let unknown = |why: String| Diagnostic::error(Code::E321, n.span, why);
        if n.text.starts_with("plant.") && self.plantless() {
            return Err(self.needs_plant(n.span, &format!("`{}`", n.text)));
        }
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
        if looks_dynamic(&n.text) {
            let l = locate(self.program, &n.text).map_err(|e| unknown(e.to_string()))?;
            let ty = type_ty(&l.ty()).ok_or_else(|| mismatch(n.span, "no value".into()))?;
            return Ok(Ref {
                name: n.text.clone(),
                src: Src::Located(l),
                ty,
            });
        }
        let place = resolve(self.program, &n.text)
            .or_else(|e| {
                pl7_object(&n.text)
                    .and_then(|alias| resolve(self.program, &alias).ok())
                    .ok_or(e)
            })
            .map_err(|e| {
                if self.plantless() {
                    unknown(format!("`{}` is no variable of the program: {e}", n.text))
                } else {
                    unknown(format!(
                    "`{}` is no signal of the {} model, no `plant.` quantity and no variable: {e}",
                    n.text,
                    self.plant.name()
                ))
                }
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

    /// Resolves and type-checks a condition without `count(...)`; `refs`
    /// collects the names.
    pub fn condition(&self, e: &Expr, refs: &mut Vec<Ref>) -> Result<Cond, Diagnostic> {
        self.condition_in(e, refs, &mut Ctx::default())
    }

    /// [`Scope::condition`] in a context (`Ctx::counting()` collects the
    /// arguments of `count(...)`).
    pub fn condition_in(
        &self,
        e: &Expr,
        refs: &mut Vec<Ref>,
        ctx: &mut Ctx,
    ) -> Result<Cond, Diagnostic> {
        let (c, ty, span) = self.typed(e, refs, ctx)?;
        if ty != Some(Ty::Bool) {
            return Err(mismatch(span, "a condition must be BOOL".into()));
        }
        Ok(c)
    }

    /// A value of any type (what `stable` watches).
    pub fn value_in(
        &self,
        e: &Expr,
        refs: &mut Vec<Ref>,
        ctx: &mut Ctx,
    ) -> Result<Cond, Diagnostic> {
        let (c, ty, span) = self.typed(e, refs, ctx)?;
        if ty.is_none() {
            return Err(mismatch(
                span,
                "an enumeration value alone is no value to watch".into(),
            ));
        }
        Ok(c)
    }

    /// The condition, its type (`None` for an enumeration literal, typed by
    /// the other side of its comparison) and its span. Recursion is bounded
    /// by the parser's nesting limit (`parse::MAX_NESTING`) and operand
    /// count (`parse::MAX_TERMS`).
    fn typed(
        &self,
        e: &Expr,
        refs: &mut Vec<Ref>,
        ctx: &mut Ctx,
    ) -> Result<(Cond, Option<Ty>, Span), Diagnostic> {
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
                let (c, ty, span) = self.typed(x, refs, ctx)?;
                if ty != Some(Ty::Bool) {
                    return Err(mismatch(span, "NOT needs a BOOL operand".into()));
                }
                (Cond::Not(Box::new(c)), Some(Ty::Bool), span)
            }
            Expr::Logic(op, a, b) => {
                let (ca, ta, sa) = self.typed(a, refs, ctx)?;
                let (cb, tb, sb) = self.typed(b, refs, ctx)?;
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
                let (ca, ta, sa) = self.typed(a, refs, ctx)?;
                let (cb, tb, sb) = self.typed(b, refs, ctx)?;
                let span = sa.to(sb);
                // A bit of an SLC-500 data file compares with 1 and 0 too.
                let (ca, ta) = slc_bit_number(a, ca, ta, &cb, &tb, refs);
                let (cb, tb) = slc_bit_number(b, cb, tb, &ca, &ta, refs);
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
            Expr::Arith(op, a, b) => {
                let (ca, ta, sa) = self.typed(a, refs, ctx)?;
                let (cb, tb, sb) = self.typed(b, refs, ctx)?;
                let span = sa.to(sb);
                let ty = arith_type(*op, ta.as_ref(), tb.as_ref()).ok_or_else(|| {
                    mismatch(
                        span,
                        format!(
                            "`{}` does not apply to {} and {} (arithmetic is on numbers and TIMEs: TIME ± TIME, TIME * or / a number, TIME / TIME)",
                            op.text(),
                            ta.as_ref().map_or("an enumeration value".into(), ty_name),
                            tb.as_ref().map_or("an enumeration value".into(), ty_name)
                        ),
                    )
                })?;
                (Cond::Arith(*op, Box::new(ca), Box::new(cb)), Some(ty), span)
            }
            Expr::Neg(x, minus) => {
                let (c, ty, span) = self.typed(x, refs, ctx)?;
                if !matches!(ty, Some(Ty::Num | Ty::Time)) {
                    return Err(mismatch(
                        minus.to(span),
                        "a minus sign needs a number or a TIME".into(),
                    ));
                }
                (Cond::Neg(Box::new(c)), ty, minus.to(span))
            }
            Expr::Call(f, args, span) => self.call(*f, args, *span, refs, ctx)?,
        })
    }

    fn call(
        &self,
        f: Func,
        args: &[Expr],
        span: Span,
        refs: &mut Vec<Ref>,
        ctx: &mut Ctx,
    ) -> Result<(Cond, Option<Ty>, Span), Diagnostic> {
        let misplaced = |why: &str| Diagnostic::error(Code::E326, span, why.to_string());
        let temporal = f.is_event() || f == Func::Prev;
        if temporal && ctx.in_temporal {
            return Err(misplaced(&format!(
                "{}(...) inside rise, fall, change or prev: they compare one scan with the one before, and take plain values",
                f.name()
            )));
        }
        if f == Func::Count {
            if ctx.in_temporal || ctx.in_count {
                return Err(misplaced(
                    "count(...) inside rise, fall, change, prev or count: count only at the top of a condition",
                ));
            }
            if ctx.counts.is_none() {
                return Err(misplaced(
                    "count(...) counts over a window: use it in `expect C during A..B`, `expect at T C` or `expect always C [during A..B]`",
                ));
            }
        }
        let (outer_t, outer_c) = (ctx.in_temporal, ctx.in_count);
        ctx.in_temporal |= temporal;
        ctx.in_count |= f == Func::Count;
        let mut typed = Vec::with_capacity(args.len());
        let mut result = Ok(());
        for a in args {
            match self.typed(a, refs, ctx) {
                Ok(t) => typed.push(t),
                Err(d) => {
                    result = Err(d);
                    break;
                }
            }
        }
        ctx.in_temporal = outer_t;
        ctx.in_count = outer_c;
        result?;
        let mut it = typed.into_iter();
        let Some((c, ty, sa)) = it.next() else {
            return Err(misplaced("a function without its argument"));
        };
        let second = it.next();
        let need = |ok: bool, what: &str| {
            if ok {
                Ok(())
            } else {
                Err(mismatch(sa, format!("{}(...) needs {what}", f.name())))
            }
        };
        let b = Box::new(c);
        Ok(match f {
            Func::Rise | Func::Fall => {
                need(ty == Some(Ty::Bool), "a BOOL condition")?;
                let c = if f == Func::Rise {
                    Cond::Rise(b)
                } else {
                    Cond::Fall(b)
                };
                (c, Some(Ty::Bool), span)
            }
            Func::Change => {
                need(ty.is_some(), "a value (a name or an expression)")?;
                (Cond::Change(b), Some(Ty::Bool), span)
            }
            Func::Prev => {
                need(ty.is_some(), "a value (a name or an expression)")?;
                (Cond::Prev(b), ty, span)
            }
            Func::Count => {
                need(ty == Some(Ty::Bool), "a BOOL condition (such as rise(x))")?;
                let counts = ctx.counts.get_or_insert_with(Vec::new);
                counts.push(*b);
                (Cond::Count(counts.len() - 1), Some(Ty::Num), span)
            }
            Func::Abs => {
                need(matches!(ty, Some(Ty::Num | Ty::Time)), "a number or a TIME")?;
                (Cond::Abs(b), ty, span)
            }
            Func::Min | Func::Max => {
                let Some((c2, ty2, s2)) = second else {
                    return Err(misplaced("min and max take two arguments"));
                };
                need(matches!(ty, Some(Ty::Num | Ty::Time)), "numbers or TIMEs")?;
                if ty2 != ty {
                    return Err(mismatch(
                        s2,
                        format!("{}(...) needs two values of one type", f.name()),
                    ));
                }
                let c = if f == Func::Min {
                    Cond::Min(b, Box::new(c2))
                } else {
                    Cond::Max(b, Box::new(c2))
                };
                (c, ty, span)
            }
        })
    }

    /// A condition that anchors a window or a reaction: an event, or a
    /// plain condition meaning its rising edge.
    pub fn event(&self, e: &Expr, refs: &mut Vec<Ref>) -> Result<Cond, Diagnostic> {
        let c = self.condition(e, refs)?;
        Ok(if c.has_event() {
            c
        } else {
            Cond::Rise(Box::new(c))
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
        let (list, located) = self.actions(a)?;
        match (located.first(), &a.kind) {
            (Some(_), ActionKind::Set(n, ..)) => Err(mismatch(
                n.span,
                format!(
                    "`{}` is an indexed or indirect address: it is set by an `at` or `when` line of a scenario file",
                    n.text
                ),
            )),
            _ => Ok(list),
        }
    }

    /// [`Scope::action`], with the sets of SLC indexed or indirect
    /// addresses apart: their place is found when they are due.
    pub fn actions(&self, a: &ast::Action) -> Result<ActionList, Diagnostic> {
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
        if self.plantless() {
            let needs = match &a.kind {
                ActionKind::Stuck(n, ..) => Some((n.span, "`stuck`")),
                ActionKind::Unstick(n) => Some((n.span, "`unstick`")),
                ActionKind::Noise(n, _) => Some((n.span, "`noise`")),
                ActionKind::Plant(n, _) => Some((n.span, "a `plant` command")),
                _ => None,
            };
            if let Some((span, what)) = needs {
                return Err(self.needs_plant(span, what));
            }
        }
        if let ActionKind::Set(n, lit, span) = &a.kind {
            if self.signal(&n.text).is_none() && looks_dynamic(&n.text) {
                let r = self.reference(n)?;
                let Src::Located(loc) = r.src else {
                    return Err(mismatch(n.span, format!("`{}` cannot be set", n.text)));
                };
                let lit = match lit {
                    Lit::Int(v @ (0 | 1)) if loc.slc_bit() => &Lit::Bool(*v == 1),
                    _ => lit,
                };
                let value = self.lit_value(lit, &r.ty, *span, &format!("`{}`", n.text))?;
                return Ok((
                    Vec::new(),
                    vec![LocatedWrite {
                        at_ns: t,
                        name: n.text.clone(),
                        line: a.line,
                        loc,
                        value,
                    }],
                ));
            }
        }
        let list = match &a.kind {
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
                    // An SLC-500 bit is set to 1 or 0 as well.
                    let lit = match lit {
                        Lit::Int(v @ (0 | 1)) if place.slc_bit => &Lit::Bool(*v == 1),
                        _ => lit,
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
        };
        Ok((list, Vec::new()))
    }
}

/// A `set` of an SLC-500 indexed or indirect address: written at its
/// time to the place it names in the image of the scan before.
#[derive(Clone, Debug, PartialEq)]
pub struct LocatedWrite {
    pub at_ns: i64,
    /// As written, for a failure.
    pub name: String,
    pub line: u32,
    pub loc: Locator,
    pub value: Value,
}

/// The coupling actions of a line, and its sets of indexed or indirect
/// addresses.
pub type ActionList = (Vec<(i64, Action)>, Vec<LocatedWrite>);

/// `e` (typed `c`, `t`) as a BOOL when it is the literal 1 or 0 compared
/// with a bit of an SLC-500 data file (`other`, typed `other_ty`), which
/// prints as 1/0.
fn slc_bit_number(
    e: &Expr,
    c: Cond,
    t: Option<Ty>,
    other: &Cond,
    other_ty: &Option<Ty>,
    refs: &[Ref],
) -> (Cond, Option<Ty>) {
    let slc = matches!(other, Cond::Ref(i)
    if match refs.get(*i).map(|r| &r.src) {
        Some(Src::Place(p)) => p.slc_bit,
        Some(Src::Located(l)) => l.slc_bit(),
        _ => false,
    });
    match e {
        Expr::Lit(Lit::Int(v @ (0 | 1)), _) if slc && *other_ty == Some(Ty::Bool) => {
            (Cond::Bool(*v == 1), Some(Ty::Bool))
        }
        _ => (c, t),
    }
}

/// The variable a PL7 object stands for in a program of the `pl7` dialect
/// (`crates/dialect/src/pl7`): a step's activity `%Xi` and time `%Xi.T`
/// are the global mirrors `__pl7_x_i` / `__pl7_t_i`, a system bit `%Si` and
/// word `%SWi` the globals `_Si` / `_SWi`.
fn pl7_object(text: &str) -> Option<String> {
    let up = text.to_ascii_uppercase();
    let rest = up.strip_prefix('%')?;
    let digits = |s: &str| !s.is_empty() && s.len() <= 5 && s.bytes().all(|b| b.is_ascii_digit());
    if let Some(step) = rest.strip_prefix('X') {
        let (n, time) = match step.split_once('.') {
            Some((n, "T")) => (n, true),
            Some(_) => return None,
            None => (step, false),
        };
        return digits(n).then(|| format!("__pl7_{}_{n}", if time { 't' } else { 'x' }));
    }
    let word = rest.strip_prefix("SW").or_else(|| rest.strip_prefix('S'))?;
    digits(word).then(|| format!("_{rest}"))
}

/// The type of `a op b`, `None` when the operator does not apply.
fn arith_type(op: ArithOp, a: Option<&Ty>, b: Option<&Ty>) -> Option<Ty> {
    use ArithOp::*;
    Some(match (op, a?, b?) {
        (_, Ty::Num, Ty::Num) => Ty::Num,
        (Add | Sub, Ty::Time, Ty::Time) => Ty::Time,
        (Mul, Ty::Time, Ty::Num) | (Mul, Ty::Num, Ty::Time) | (Div, Ty::Time, Ty::Num) => Ty::Time,
        (Div, Ty::Time, Ty::Time) => Ty::Num,
        _ => return None,
    })
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
