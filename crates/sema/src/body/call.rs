//! Calls of user functions and of function block instances.
//!
//! Rules: arguments are all formal (`name := v`, `name => var`) or all
//! positional (E055); function block instances take formal arguments only.
//! Positional arguments bind the inputs and in-outs in declaration order,
//! then the outputs. Formal calls may leave inputs and outputs out (inputs
//! keep their value / get their initial value), never a VAR_IN_OUT (E057).
//! `EN` (BOOL input) and `ENO` (BOOL output) are accepted on every call.
//! The standard counters accept `RESET` for `R`.

use super::{Access, Checker, Named};
use crate::convert::{fits, Fit};
use crate::model::{Pou, Section, Var};
use crate::names::expr_text;
use crate::ops::{Ty, Typed};
use crate::types::{PouId, TypeId, TypeKind};
use automat_base::{Code, Span, Symbol};

use automat_syntax::ast::{Arg, ArgDir, Expr, ExprKind, PouKind};

/// What is being called, for messages.
#[derive(Clone, Copy)]
pub(crate) enum Callee {
    Function,
    Instance,
}

impl<'m> Checker<'m> {
    /// Types a call; `as_stmt` when its value is discarded.
    pub(crate) fn call(
        &mut self,
        e: &Expr,
        callee: &Expr,
        args: &[Arg],
        expect: Option<TypeId>,
        as_stmt: bool,
    ) -> Typed {
        if let ExprKind::Name(id) = &callee.kind {
            if self.name_calls_a_function(id.sym) {
                return self.call_by_name(e, id.sym, id.span, args, expect, as_stmt);
            }
        }
        // The callee is a variable or member: it must be a function block
        // instance. `inst.f(...)` with no member `f` is a function or method
        // called through an instance.
        let t = match &callee.kind {
            ExprKind::Member { base, member } => {
                let b = self.expr(base, None);
                if let Ty::Of(bt) = b.ty {
                    if let Some(fb) = self.fb_of(bt) {
                        let has = self
                            .model
                            .pou(fb)
                            .is_some_and(|p| p.vars.get(member.sym).is_some());
                        if !has {
                            self.err(Code::E054, member.span, |c| {
                                format!(
                                    "`{}` cannot be called through the instance `{}`: function block `{}` has no method or member `{}`",
                                    c.name(member.sym),
                                    expr_text(c.interner, base),
                                    c.type_name(bt),
                                    c.name(member.sym)
                                )
                            });
                            self.args_unchecked(args);
                            return Typed::ERROR;
                        }
                    }
                }
                self.member_of(&b, base, *member, Access::Read)
            }
            _ => self.expr(callee, None),
        };
        let fb = match t.ty {
            Ty::Error => {
                self.args_unchecked(args);
                return Typed::ERROR;
            }
            Ty::Of(id) => self.fb_of(id),
            _ => None,
        };
        let Some(pou) = fb else {
            self.err(Code::E054, callee.span, |c| {
                format!(
                    "`{}` of type {} is not callable",
                    expr_text(c.interner, callee),
                    c.tyname(t.ty)
                )
            });
            self.args_unchecked(args);
            return Typed::ERROR;
        };
        self.pou_args(pou, args, Callee::Instance, e.span);
        if !as_stmt {
            self.err(Code::E054, callee.span, |c| {
                format!(
                    "the function block instance `{}` has no value; call it as a statement and read its outputs",
                    expr_text(c.interner, callee)
                )
            });
            return Typed::ERROR;
        }
        Typed::ERROR
    }

    /// Whether `name(...)` calls the function of that name rather than an
    /// instance: no variable has the name, or it is the function's own
    /// return value, or the variable cannot be called and a function of
    /// that name exists (a local `sel` or `max` does not hide `SEL`/`MAX`).
    pub(crate) fn name_calls_a_function(&mut self, sym: Symbol) -> bool {
        let Some((v, _)) = self.var(sym) else {
            return true;
        };
        if v.section == crate::model::Section::Return {
            return true;
        }
        if self.fb_of(v.ty).is_some() {
            return false;
        }
        let user_function = self
            .model
            .pou_named(sym)
            .is_some_and(|(_, p)| p.kind == PouKind::Function);
        user_function || self.std_fn(sym).is_some()
    }

    fn call_by_name(
        &mut self,
        e: &Expr,
        sym: Symbol,
        span: Span,
        args: &[Arg],
        expect: Option<TypeId>,
        as_stmt: bool,
    ) -> Typed {
        match self.lookup_callee(sym) {
            Named::Pou(id, p) => match p.kind {
                PouKind::Function => {
                    self.pou_args(id, args, Callee::Function, e.span);
                    match p.return_type {
                        Some(t) if t != TypeId::ERROR => Typed::of(t),
                        Some(_) => Typed::ERROR,
                        None => {
                            if !as_stmt {
                                self.err(Code::E030, span, |c| {
                                    format!("function `{}` has no return value", c.pou_name(sym))
                                });
                            }
                            Typed::ERROR
                        }
                    }
                }
                PouKind::FunctionBlock => {
                    self.err(Code::E053, span, |c| {
                        let n = c.pou_name(sym);
                        format!("`{n}` is a function block type, not a function; declare an instance (`inst : {n};`) and call the instance")
                    });
                    self.args_unchecked(args);
                    Typed::ERROR
                }
                PouKind::Program => {
                    self.err(Code::E054, span, |c| {
                        format!(
                            "program `{}` cannot be called from Structured Text",
                            c.pou_name(sym)
                        )
                    });
                    self.args_unchecked(args);
                    Typed::ERROR
                }
            },
            Named::StdFn => self.std_call(e, sym, span, args, expect, as_stmt),
            Named::Type => {
                self.err(Code::E054, span, |c| {
                    format!("`{}` is a type, not a function", c.name(sym))
                });
                self.args_unchecked(args);
                Typed::ERROR
            }
            Named::Var | Named::Unknown if self.interner.name(sym) == "__ISVALIDREF" => {
                self.isvalidref_misuse(span, args);
                Typed::ERROR
            }
            Named::Var | Named::Unknown => {
                self.err(Code::E022, span, |c| {
                    format!(
                        "unknown function or function block `{}`{}",
                        c.name(sym),
                        c.pou_hint(sym)
                    )
                });
                self.args_unchecked(args);
                Typed::ERROR
            }
        }
    }

    /// Types argument values without a signature (the callee is in error),
    /// so errors inside them are still reported.
    pub(crate) fn args_unchecked(&mut self, args: &[Arg]) {
        for a in args {
            if let Some(v) = &a.value {
                self.expr(v, None);
            }
        }
    }

    /// Checks the arguments of a call of a user POU or instance.
    pub(crate) fn pou_args(&mut self, id: PouId, args: &[Arg], kind: Callee, span: Span) {
        let Some(pou) = self.model.pou(id) else {
            return;
        };
        let formal = args.iter().any(|a| a.name.is_some());
        let positional = args.iter().any(|a| a.name.is_none());
        if formal && positional {
            if let Some(a) = args.iter().find(|a| a.name.is_none()) {
                self.err(Code::E055, a.span, |c| {
                    format!(
                        "the call of `{}` mixes formal (`name := value`) and positional arguments",
                        c.pou_name(pou.name)
                    )
                });
            }
            self.args_unchecked(args);
            return;
        }
        if positional {
            if let Callee::Instance = kind {
                if let Some(a) = args.first() {
                    self.err(Code::E055, a.span, |c| {
                        format!(
                            "function block `{}` must be called with formal arguments (`name := value`)",
                            c.pou_name(pou.name)
                        )
                    });
                }
                self.args_unchecked(args);
                return;
            }
            self.positional_args(pou, args, span);
            return;
        }
        let mut seen: Vec<(Symbol, Span)> = Vec::new();
        for a in args {
            let Some(name) = a.name else { continue };
            if seen.iter().any(|(s, _)| *s == name.sym) {
                self.err(Code::E056, name.span, |c| {
                    format!(
                        "parameter `{}` is given twice in the call of `{}`",
                        c.name(name.sym),
                        c.pou_name(pou.name)
                    )
                });
                if let Some(v) = &a.value {
                    self.expr(v, None);
                }
                continue;
            }
            seen.push((name.sym, name.span));
            if name.sym == self.model.syms.en || name.sym == self.model.syms.eno {
                self.en_eno(name.sym, a);
                continue;
            }
            let param = pou
                .vars
                .get(name.sym)
                .filter(|v| v.section.is_param())
                .or_else(|| {
                    // The standard counters: RESET is R.
                    (pou.builtin && name.sym == self.model.syms.reset)
                        .then(|| pou.vars.get(self.model.syms.r))
                        .flatten()
                });
            let Some(param) = param else {
                self.err(Code::E051, name.span, |c| {
                    let what = match pou.kind {
                        PouKind::Function => "function",
                        PouKind::FunctionBlock => "function block",
                        PouKind::Program => "program",
                    };
                    format!(
                        "{what} `{}` has no parameter `{}`",
                        c.pou_name(pou.name),
                        c.name(name.sym)
                    )
                });
                if let Some(v) = &a.value {
                    self.expr(v, None);
                }
                continue;
            };
            self.bind(pou, param, a, false);
        }
        for v in pou.vars.vars.iter().filter(|v| v.section == Section::InOut) {
            let bound = seen.iter().any(|(s, _)| *s == v.name);
            if !bound {
                self.err(Code::E057, span, |c| {
                    format!(
                        "the VAR_IN_OUT `{}` of `{}` is not bound in this call",
                        c.name(v.name),
                        c.pou_name(pou.name)
                    )
                });
            }
        }
    }

    fn positional_args(&mut self, pou: &'m Pou, args: &[Arg], span: Span) {
        let ins: Vec<&Var> = pou
            .vars
            .vars
            .iter()
            .filter(|v| matches!(v.section, Section::Input | Section::InOut))
            .collect();
        let outs = pou
            .vars
            .vars
            .iter()
            .filter(|v| v.section == Section::Output);
        let order: Vec<&Var> = ins.iter().copied().chain(outs).collect();
        let (need, n) = (ins.len(), args.len());
        if n < need || n > order.len() {
            let at = args
                .first()
                .map_or(span, |a| a.span)
                .to(args.last().map_or(span, |a| a.span));
            let at = if args.is_empty() { span } else { at };
            // A method's instance (`__THIS`) is not written by the caller.
            let hidden = usize::from(ins.first().is_some_and(|v| v.name == self.model.syms.this_));
            let (need, n) = (need - hidden, n.saturating_sub(hidden));
            self.err(Code::E050, at, |c| {
                format!(
                    "function `{}` expects {need} argument{}, found {n}",
                    c.pou_name(pou.name),
                    if need == 1 { "" } else { "s" }
                )
            });
        }
        for (i, a) in args.iter().enumerate() {
            match order.get(i) {
                // A positional output is bound like `name => var`.
                Some(p) if p.section == Section::Output => self.bind(pou, p, a, true),
                Some(p) => self.bind(pou, p, a, false),
                None => {
                    if let Some(v) = &a.value {
                        self.expr(v, None);
                    }
                }
            }
        }
    }

    /// `EN := bool` / `ENO => bool_var`.
    pub(crate) fn en_eno(&mut self, sym: Symbol, a: &Arg) {
        let Some(v) = &a.value else { return };
        let is_en = sym == self.model.syms.en;
        let out = matches!(a.dir, ArgDir::Out | ArgDir::OutNot);
        if is_en == out {
            self.err(Code::E051, a.span, |_| {
                if is_en {
                    "`EN` is an input: pass it with `:=`".into()
                } else {
                    "`ENO` is an output: bind it with `=>`".into()
                }
            });
            self.expr(v, None);
            return;
        }
        let access = if out { Access::Output } else { Access::Read };
        let t = self.expr_access(v, Some(TypeId::BOOL), access);
        if fits(&self.model.types, &t, TypeId::BOOL) != Fit::Ok {
            self.err(Code::E052, v.span, |c| {
                format!("`{}` needs BOOL, found {}", c.name(sym), c.tyname(t.ty))
            });
        }
    }

    /// One argument bound to a parameter (`positional_out`: a positional
    /// argument in an output's position, bound like `=>`).
    fn bind(&mut self, pou: &'m Pou, param: &'m Var, a: &Arg, positional_out: bool) {
        let out = positional_out || matches!(a.dir, ArgDir::Out | ArgDir::OutNot);
        match (param.section, out) {
            (Section::Output, true) => {
                let Some(v) = &a.value else { return };
                let target = self.expr_access(v, None, Access::Output);
                let Ty::Of(tt) = target.ty else { return };
                let from = if a.dir == ArgDir::OutNot {
                    if param.ty != TypeId::BOOL && param.ty != TypeId::ERROR {
                        self.err(Code::E052, a.span, |c| {
                            format!("`NOT {} =>` needs a BOOL output", c.name(param.name))
                        });
                        return;
                    }
                    Typed::of(TypeId::BOOL)
                } else {
                    Typed::of(param.ty)
                };
                let fit = fits(&self.model.types, &from, tt);
                if fit == Fit::Mismatch && self.codesys_narrowing(&from, tt) {
                    self.warn(Code::W161, v.span, |c| {
                        format!(
                            "the output `{}` of `{}` ({}) is converted implicitly to {} for `{}`: the value may not fit",
                            c.name(param.name),
                            c.pou_name(pou.name),
                            c.type_name(param.ty),
                            c.type_name(tt),
                            expr_text(c.interner, v)
                        )
                    });
                } else if fit != Fit::Ok {
                    self.err(Code::E052, v.span, |c| {
                        format!(
                            "the output `{}` of `{}` has type {}, which cannot be stored in `{}` of type {}",
                            c.name(param.name),
                            c.pou_name(pou.name),
                            c.type_name(param.ty),
                            expr_text(c.interner, v),
                            c.type_name(tt)
                        )
                    });
                    if fit == Fit::Mismatch && super::stmt::narrowing(&self.model.types, &from, tt)
                    {
                        self.note_codesys(
                            "CODESYS converts such a value implicitly (warning W161)",
                        );
                    }
                }
            }
            (Section::Output, false) => {
                self.err(Code::E051, a.span, |c| {
                    format!(
                        "`{}` is an output of `{}`: bind it with `=>`",
                        c.name(param.name),
                        c.pou_name(pou.name)
                    )
                });
                if let Some(v) = &a.value {
                    self.expr(v, None);
                }
            }
            (_, true) => {
                self.err(Code::E051, a.span, |c| {
                    format!(
                        "`{}` is an input of `{}`: pass it with `:=`",
                        c.name(param.name),
                        c.pou_name(pou.name)
                    )
                });
                if let Some(v) = &a.value {
                    self.expr(v, None);
                }
            }
            (Section::InOut, false) => {
                let Some(v) = &a.value else { return };
                let t = self.expr_access(v, Some(param.ty), Access::InOut);
                if let Ty::Of(at) = t.ty {
                    if !self.inout_compatible(at, param.ty) {
                        self.err(Code::E052, v.span, |c| {
                            format!(
                                "the VAR_IN_OUT `{}` of `{}` needs a variable of type {}, found {}",
                                c.name(param.name),
                                c.pou_name(pou.name),
                                c.type_name(param.ty),
                                c.type_name(at)
                            )
                        });
                    }
                }
            }
            (_, false) => {
                let Some(v) = &a.value else { return };
                let t = self.expr(v, Some(param.ty));
                let what = |c: &Self| {
                    format!(
                        "parameter `{}` of `{}`",
                        c.name(param.name),
                        c.pou_name(pou.name)
                    )
                };
                if fits(&self.model.types, &t, param.ty) == Fit::Mismatch
                    && self.codesys_narrowing(&t, param.ty)
                {
                    self.warn(Code::W161, v.span, |c| {
                        let from = crate::names::value_desc(&c.model.types, c.interner, &t);
                        format!(
                            "{from} is converted implicitly to {} for {}: the value may not fit",
                            c.type_name(param.ty),
                            what(c)
                        )
                    });
                    return;
                }
                let narrow = fits(&self.model.types, &t, param.ty) == Fit::Mismatch
                    && super::stmt::narrowing(&self.model.types, &t, param.ty);
                self.arg_fits(&t, param.ty, v.span, &what);
                if narrow {
                    self.note_codesys("CODESYS converts such a value implicitly (warning W161)");
                }
            }
        }
    }

    /// CODESYS converts a value between integer, bit-string and real types
    /// implicitly when it is passed to a parameter of a user POU or an output
    /// is bound to a variable, as in an assignment (W161 instead of E052).
    /// Standard functions keep their strict signatures.
    fn codesys_narrowing(&self, v: &Typed, to: TypeId) -> bool {
        self.model.codesys && super::stmt::narrowing(&self.model.types, v, to)
    }

    /// Reports an argument that does not convert to its parameter's type.
    /// `what` names the parameter: "parameter `IN` of `LIMIT`".
    pub(crate) fn arg_fits(
        &mut self,
        t: &Typed,
        to: TypeId,
        span: Span,
        what: &dyn Fn(&Self) -> String,
    ) {
        match fits(&self.model.types, t, to) {
            Fit::Ok => {}
            Fit::Mismatch
                if self.model.codesys && crate::convert::pointer_cast(&self.model.types, t, to) => {
            }
            Fit::NarrowedConstant => {
                let v = t.value.as_ref().map_or_else(String::new, |v| v.show());
                self.warn(Code::W003, span, |c| {
                    format!(
                        "the constant {v} is narrowed to {} for {}",
                        c.type_name(to),
                        what(c)
                    )
                });
            }
            Fit::OutOfSubrange { lo, hi } => {
                let v = t.value.as_ref().map_or_else(String::new, |v| v.show());
                self.err(Code::E038, span, |c| {
                    format!(
                        "the value {v} is outside the subrange {lo}..{hi} of {}",
                        what(c)
                    )
                });
            }
            Fit::OutOfRange => {
                let v = t.value.as_ref().map_or_else(String::new, |v| v.show());
                self.err(Code::E052, span, |c| {
                    format!(
                        "the value {v} does not fit {} of type {}",
                        what(c),
                        c.type_name(to)
                    )
                });
            }
            Fit::Mismatch => {
                self.err(Code::E052, span, |c| {
                    format!(
                        "{} expects {}, found {}{}",
                        what(c),
                        c.type_name(to),
                        c.tyname(t.ty),
                        c.conversion_hint(t.ty, to)
                    )
                });
            }
        }
    }

    /// A variable passed to a VAR_IN_OUT: the same type, or an array of the
    /// same element type and rank for `ARRAY[*]`, or a string of the same width.
    fn inout_compatible(&self, arg: TypeId, param: TypeId) -> bool {
        if arg == param || param == TypeId::ERROR {
            return true;
        }
        let types = &self.model.types;
        match (types.get(arg), types.get(param)) {
            (TypeKind::String { wide: a, .. }, TypeKind::String { wide: b, .. }) => a == b,
            (TypeKind::Array { elem: ea, dims: da }, TypeKind::Array { elem: eb, dims: db }) => {
                ea == eb
                    && da.len() == db.len()
                    && da
                        .iter()
                        .zip(db)
                        .all(|(x, y)| x == y || *y == crate::types::Dim::Star)
            }
            (TypeKind::Subrange { base, .. }, TypeKind::Elem(e)) => base == e,
            _ => false,
        }
    }
}
