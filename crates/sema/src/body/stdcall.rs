//! Calls of standard functions: binding arguments to the signature, finding
//! the generic type `T`, checking every argument.
//!
//! `T` is the least upper bound of the typed generic arguments (untyped
//! literals adapt to it). With only untyped arguments, `T` is the expected
//! type of the call when the result is `T` and that type suits, else the
//! literal's natural type for the kind (DINT/LINT, DWORD for ANY_BIT, LREAL
//! for reals, STRING). A `T` outside the parameter kind widens to the
//! kind's narrowest member it converts to (an INT argument of SQRT makes
//! `T` REAL); otherwise E052.

use super::{Access, Checker};
use crate::lattice::{implicit, int_fits, lub};
use crate::names::expr_text;
use crate::ops::{Ty, Typed};
use crate::stdlib::{Kind, PDir, PTy, Param, RTy, Sig};
use crate::types::{Elem, TypeId, TypeKind};
use automat_base::{Code, Span, Symbol};
use automat_syntax::ast::{Arg, ArgDir, Expr, ExprKind};
use std::rc::Rc;

impl<'m> Checker<'m> {
    pub(crate) fn std_call(
        &mut self,
        e: &Expr,
        sym: Symbol,
        span: Span,
        args: &[Arg],
        expect: Option<TypeId>,
        as_stmt: bool,
    ) -> Typed {
        let Some(sig) = self.std_fn(sym) else {
            self.args_unchecked(args);
            return Typed::ERROR;
        };
        let Some(slots) = self.bind_std(&sig, sym, args, e.span) else {
            self.args_unchecked(args);
            return Typed::ERROR;
        };
        // Generic arguments first: they decide `T`.
        let mut gen: Vec<(usize, Typed)> = Vec::new();
        for (i, (p, a)) in slots.iter().enumerate() {
            if let (PTy::Gen(_), Some(v)) = (p.ty, &a.value) {
                gen.push((i, self.expr(v, None)));
            }
        }
        let kind = slots.iter().find_map(|(p, _)| match p.ty {
            PTy::Gen(k) => Some(k),
            _ => None,
        });
        let want = if sig.ret == RTy::Gen { expect } else { None };
        let t = match kind {
            Some(k) => self.generic_type(sym, &slots, &gen, k, want),
            None => None,
        };
        let mut ref_arg = None;
        for (i, (p, a)) in slots.iter().enumerate() {
            let Some(v) = &a.value else { continue };
            let what = |c: &Self| {
                format!(
                    "parameter `{}` of `{}`",
                    param_name(c, &sig, i, &slots),
                    c.name(sym)
                )
            };
            match p.ty {
                PTy::Gen(_) => {
                    let (Some(t), Some((_, at))) = (t, gen.iter().find(|(j, _)| *j == i)) else {
                        continue;
                    };
                    self.arg_fits(at, t, v.span, &what);
                }
                PTy::Elem(el) if p.dir == PDir::In => {
                    let at = self.expr(v, Some(TypeId::elem(el)));
                    self.arg_fits(&at, TypeId::elem(el), v.span, &what);
                }
                PTy::Str(w) => {
                    let at = self.expr(v, None);
                    let to = if w { TypeId::WSTRING } else { TypeId::STRING };
                    self.arg_fits(&at, to, v.span, &what);
                }
                PTy::Array => {
                    let at = self.expr(v, None);
                    let is_array = match at.ty {
                        Ty::Error => true,
                        Ty::Of(id) => matches!(self.model.types.get(id), TypeKind::Array { .. }),
                        _ => false,
                    };
                    if !is_array {
                        self.err(Code::E052, v.span, |c| {
                            format!("{} expects an array, found {}", what(c), c.tyname(at.ty))
                        });
                    }
                }
                // `SIZEOF(INT)`: a type name stands for a value of its type.
                PTy::Free(_)
                    if sig.op == crate::stdlib::StdOp::Sizeof && self.type_named(v).is_some() => {}
                PTy::Free(k) if p.dir == PDir::In => {
                    let at = self.expr(v, None);
                    if matches!(sig.ret, RTy::RefToArg) {
                        if !is_place(v) {
                            self.err(Code::E042, v.span, |c| {
                                format!(
                                    "`{}` needs a variable, not `{}`",
                                    c.name(sym),
                                    expr_text(c.interner, v)
                                )
                            });
                        }
                        ref_arg = Some(at.ty);
                    }
                    if !self.in_kind(&at, k) {
                        self.err(Code::E052, v.span, |c| {
                            format!(
                                "{} must be {}, found {}",
                                what(c),
                                k.name(),
                                c.tyname(at.ty)
                            )
                        });
                    }
                }
                PTy::Free(_) | PTy::Elem(_) if p.dir != PDir::In => {
                    let at = self.expr_access(v, None, Access::Output);
                    let ok = match (p.ty, at.ty) {
                        (_, Ty::Error) => true,
                        (PTy::Free(k), _) => self.in_kind(&at, k),
                        (PTy::Elem(el), Ty::Of(id)) => {
                            crate::convert::fits(&self.model.types, &Typed::elem(el), id)
                                == crate::convert::Fit::Ok
                        }
                        _ => false,
                    };
                    if !ok {
                        let kn = match p.ty {
                            PTy::Free(k) => k.name().to_string(),
                            PTy::Elem(el) => el.name().to_string(),
                            _ => String::new(),
                        };
                        self.err(Code::E052, v.span, |c| {
                            format!(
                                "the output {} ({kn}) cannot be stored in {}",
                                what(c),
                                c.tyname(at.ty)
                            )
                        });
                    }
                }
                _ => {
                    self.expr(v, None);
                }
            }
        }
        // The generic TRUNC (ANY_REAL -> ANY_INT) takes the integer type
        // the context needs, as MatIEC does (DINT without a context).
        if sig.name == "TRUNC" {
            if let Some(to) =
                expect.filter(|&t| self.model.types.elem(t).is_some_and(|e| e.is_int()))
            {
                return Typed::of(to);
            }
        }
        match sig.ret {
            RTy::Gen => t.map_or(Typed::ERROR, Typed::of),
            RTy::Elem(el) => Typed::elem(el),
            RTy::Str(w) => Typed::of(if w { TypeId::WSTRING } else { TypeId::STRING }),
            RTy::RefToArg => match ref_arg {
                Some(Ty::Of(t)) => Typed {
                    ty: Ty::RefOf(t),
                    value: None,
                },
                _ => Typed::ERROR,
            },
            RTy::Void => {
                if !as_stmt {
                    self.err(Code::E030, span, |c| {
                        format!("function `{}` has no return value", c.name(sym))
                    });
                }
                Typed::ERROR
            }
        }
    }

    /// Matches arguments to parameters: `(param, arg)` in parameter order.
    /// `None` after a reported error that leaves nothing to check.
    fn bind_std<'a>(
        &mut self,
        sig: &Rc<Sig>,
        sym: Symbol,
        args: &'a [Arg],
        span: Span,
    ) -> Option<Vec<(Param, &'a Arg)>> {
        let formal = args.iter().any(|a| a.name.is_some());
        let positional = args.iter().any(|a| a.name.is_none());
        if formal && positional {
            let a = args.iter().find(|a| a.name.is_none())?;
            self.err(Code::E055, a.span, |c| {
                format!(
                    "the call of `{}` mixes formal (`name := value`) and positional arguments",
                    c.name(sym)
                )
            });
            return None;
        }
        let arity_error = |c: &Self, n: usize| {
            let min = sig.min_args();
            let amount = match sig.max_args() {
                Some(_) => format!("{min} argument{}", if min == 1 { "" } else { "s" }),
                None => format!("at least {min} arguments"),
            };
            format!("function `{}` expects {amount}, found {n}", c.name(sym))
        };
        let args_span = |fallback: Span| match (args.first(), args.last()) {
            (Some(f), Some(l)) => f.span.to(l.span),
            _ => fallback,
        };
        if positional || args.is_empty() {
            let n = args.len();
            let too_many = sig.max_args().is_some_and(|m| n > m);
            if n < sig.min_args() || too_many {
                self.err(Code::E050, args_span(span), |c| arity_error(c, n));
            }
            return Some(
                args.iter()
                    .enumerate()
                    .filter_map(|(i, a)| sig.param_at(i).map(|p| (p, a)))
                    .collect(),
            );
        }
        let mut slots: Vec<(usize, Param, &'a Arg)> = Vec::with_capacity(args.len());
        for a in args {
            let Some(name) = a.name else { continue };
            if name.sym == self.model.syms.en || name.sym == self.model.syms.eno {
                self.en_eno(name.sym, a);
                continue;
            }
            let text = self.name(name.sym);
            let Some(pos) = sig.position_of(text) else {
                self.err(Code::E051, name.span, |c| {
                    format!(
                        "function `{}` has no parameter `{}`",
                        c.name(sym),
                        c.name(name.sym)
                    )
                });
                if let Some(v) = &a.value {
                    self.expr(v, None);
                }
                continue;
            };
            if slots.iter().any(|(p, ..)| *p == pos) {
                self.err(Code::E056, name.span, |c| {
                    format!(
                        "parameter `{}` is given twice in the call of `{}`",
                        c.name(name.sym),
                        c.name(sym)
                    )
                });
                continue;
            }
            let Some(param) = sig.param_at(pos) else {
                continue;
            };
            let out = matches!(a.dir, ArgDir::Out | ArgDir::OutNot);
            if out != (param.dir == PDir::Out) {
                self.err(Code::E051, a.span, |c| {
                    if out {
                        format!(
                            "`{}` is an input of `{}`: pass it with `:=`",
                            c.name(name.sym),
                            c.name(sym)
                        )
                    } else {
                        format!(
                            "`{}` is an output of `{}`: bind it with `=>`",
                            c.name(name.sym),
                            c.name(sym)
                        )
                    }
                });
                continue;
            }
            slots.push((pos, param, a));
        }
        let n = slots.len();
        let missing = sig
            .params
            .iter()
            .enumerate()
            .any(|(i, p)| p.dir == PDir::In && !slots.iter().any(|(q, ..)| *q == i))
            || n < sig.min_args();
        if missing {
            self.err(Code::E050, args_span(span), |c| arity_error(c, n));
        }
        slots.sort_by_key(|(p, ..)| *p);
        Some(slots.into_iter().map(|(_, p, a)| (p, a)).collect())
    }

    /// The generic type `T` of a call (`None` when an argument is in error,
    /// or after reporting why none exists).
    fn generic_type(
        &mut self,
        sym: Symbol,
        slots: &[(Param, &Arg)],
        gen: &[(usize, Typed)],
        kind: Kind,
        expect: Option<TypeId>,
    ) -> Option<TypeId> {
        let mut acc: Option<TypeId> = None;
        let mut untyped: Option<&Typed> = None;
        for (i, t) in gen {
            match t.ty {
                Ty::Error | Ty::RefOf(_) => return None,
                Ty::Of(id) => {
                    let next = match acc {
                        None => Some(id),
                        Some(a) => self.common(a, id),
                    };
                    let Some(next) = next else {
                        let prev = acc.unwrap_or(TypeId::ERROR);
                        let span = slots
                            .get(*i)
                            .and_then(|(_, a)| a.value.as_ref())
                            .map_or(Span::default(), |v| v.span);
                        self.err(Code::E052, span, |c| {
                            format!(
                                "the arguments of `{}` have incompatible types {} and {}",
                                c.name(sym),
                                c.type_name(prev),
                                c.type_name(id)
                            )
                        });
                        return None;
                    };
                    acc = Some(next);
                }
                _ => {
                    if untyped.is_none() || t.ty == Ty::AnyReal {
                        untyped = Some(t);
                    }
                }
            }
        }
        let t = match acc {
            Some(t) => t,
            None => {
                let u = untyped?;
                let suits = |c: &Self, x: TypeId| {
                    c.kind_has(kind, x)
                        && gen.iter().all(|(_, g)| {
                            crate::convert::fits(&c.model.types, g, x) == crate::convert::Fit::Ok
                        })
                };
                match expect {
                    Some(x) if suits(self, x) => x,
                    _ => natural(u, kind)?,
                }
            }
        };
        if self.kind_has(kind, t) {
            return Some(t);
        }
        if let Some(e) = self.model.types.elem(t) {
            if let Some(&w) = kind.widen_targets().iter().find(|&&w| implicit(e, w)) {
                return Some(TypeId::elem(w));
            }
        }
        let (i, _) = gen.first()?;
        let span = slots
            .get(*i)
            .and_then(|(_, a)| a.value.as_ref())
            .map_or(Span::default(), |v| v.span);
        self.err(Code::E052, span, |c| {
            format!(
                "the arguments of `{}` must be {}, found {}",
                c.name(sym),
                kind.name(),
                c.type_name(t)
            )
        });
        None
    }

    /// The common type of two generic arguments.
    fn common(&self, a: TypeId, b: TypeId) -> Option<TypeId> {
        if a == b {
            return Some(a);
        }
        let types = &self.model.types;
        if let (Some(x), Some(y)) = (types.elem(a), types.elem(b)) {
            return lub(x, y).map(TypeId::elem);
        }
        match (types.get(a), types.get(b)) {
            (TypeKind::String { wide: w1, len: l1 }, TypeKind::String { wide: w2, len: l2 })
                if w1 == w2 =>
            {
                Some(if l1 >= l2 { a } else { b })
            }
            _ => None,
        }
    }

    /// Whether a type belongs to a generic kind.
    fn kind_has(&self, kind: Kind, t: TypeId) -> bool {
        let types = &self.model.types;
        if let Some(e) = types.elem(t) {
            return kind.has_elem(e);
        }
        match types.get(t) {
            TypeKind::String { .. } => kind.has_string(),
            TypeKind::Enum { .. } => matches!(kind, Kind::Any | Kind::AnyElementary),
            TypeKind::Error => true,
            _ => kind == Kind::Any,
        }
    }

    /// Whether an argument suits a free generic parameter (a numeric type
    /// that widens into the kind counts).
    fn in_kind(&self, t: &Typed, kind: Kind) -> bool {
        match t.ty {
            Ty::Error => true,
            Ty::AnyInt => !matches!(kind, Kind::AnyString | Kind::AnyDate | Kind::AnyDuration),
            Ty::AnyReal => matches!(
                kind,
                Kind::Any | Kind::AnyElementary | Kind::AnyMagnitude | Kind::AnyNum | Kind::AnyReal
            ),
            Ty::AnyStr { .. } => kind.has_string(),
            Ty::RefOf(_) => kind == Kind::Any,
            Ty::Of(id) => {
                self.kind_has(kind, id)
                    || self
                        .model
                        .types
                        .elem(id)
                        .is_some_and(|e| kind.widen_targets().iter().any(|&w| implicit(e, w)))
            }
        }
    }
}

/// The type an untyped generic argument takes when nothing else decides.
fn natural(u: &Typed, kind: Kind) -> Option<TypeId> {
    Some(match (u.ty, &u.value) {
        (Ty::AnyStr { wide }, _) => {
            if wide {
                TypeId::WSTRING
            } else {
                TypeId::STRING
            }
        }
        (Ty::AnyReal, _) => TypeId::elem(Elem::Lreal),
        (Ty::AnyInt, Some(v)) => {
            let v = v.as_int().unwrap_or(0);
            let order: &[Elem] = match kind {
                Kind::AnyReal => &[Elem::Lreal],
                Kind::AnyBit => &[Elem::Dword, Elem::Lword],
                _ => &[Elem::Dint, Elem::Lint, Elem::Ulint],
            };
            TypeId::elem(order.iter().copied().find(|&e| int_fits(v, e))?)
        }
        _ => return None,
    })
}

/// The formal name of the parameter in slot `i` (for messages): as the
/// call spells it, or by position.
fn param_name(c: &Checker, sig: &Sig, i: usize, slots: &[(Param, &Arg)]) -> String {
    match slots.get(i) {
        Some((_, a)) => match a.name {
            Some(n) => c.name(n.sym).to_string(),
            None => sig.name_at(i),
        },
        None => String::new(),
    }
}

/// Whether an expression denotes a variable (for REF and ADR).
fn is_place(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Name(_)
        | ExprKind::Member { .. }
        | ExprKind::Index { .. }
        | ExprKind::Deref(_)
        | ExprKind::Partial { .. } => true,
        ExprKind::Paren(inner) => is_place(inner),
        _ => false,
    }
}
