//! Constant folding during declarations: array bounds, string lengths,
//! subrange limits, enumeration values and initial values. Names resolve to
//! CONSTANT variables of the scope chain (resolved on demand), to project
//! globals, and to enumeration values.
//!
//! Contract: [`Builder::fold`] returns a [`Typed`] whose value is known, or
//! [`Typed::ERROR`] after reporting why (E070 not constant, E071 division
//! by zero, E073 overflow, ...).

use super::{Builder, MAX_DEPTH};
use crate::lattice::int_fits;
use crate::model::Section;
use crate::ops::{self, Ty, Typed};
use crate::types::{TypeId, TypeKind};
use crate::value::{self, FoldError, Value};
use automat_base::{Code, Diagnostic, Span, Symbol};
use automat_syntax::ast::{Expr, ExprKind, Ident};

/// What a name resolved to in a scope chain.
pub(super) enum SlotInfo {
    Var {
        ty: TypeId,
        constant: bool,
        section: Section,
        /// Its initial value was in error (already reported).
        poisoned: bool,
    },
    /// The slot is being resolved: a cycle.
    Cycle,
}

impl<'a> Builder<'a> {
    /// Folds a constant expression in a scope; `expect` picks among
    /// enumerations sharing a value name.
    pub(super) fn fold(&mut self, e: &Expr, scope: usize, expect: Option<TypeId>) -> Typed {
        if self.depth >= MAX_DEPTH {
            self.emit(Diagnostic::error(
                Code::E070,
                e.span,
                "constant expression nested too deeply",
            ));
            return Typed::ERROR;
        }
        self.depth += 1;
        let r = self.fold_inner(e, scope, expect);
        self.depth -= 1;
        r
    }

    fn fold_inner(&mut self, e: &Expr, scope: usize, expect: Option<TypeId>) -> Typed {
        match &e.kind {
            ExprKind::Literal(lit) => {
                let ty = lit.ty.map(|t| self.literal_prefix(t));
                match crate::literal::literal(&self.types, self.interner, &lit.kind, ty, e.span) {
                    Ok(t) => t,
                    Err(d) => {
                        self.emit(d);
                        Typed::ERROR
                    }
                }
            }
            ExprKind::Paren(inner) => self.fold(inner, scope, expect),
            ExprKind::Name(id) => self.fold_name(*id, scope, expect),
            ExprKind::Member { base, member } => {
                if let ExprKind::Name(t) = &base.kind {
                    if let Some(r) = self.qualified_enum(*t, *member) {
                        return r;
                    }
                }
                self.not_constant(e.span, "a member access")
            }
            ExprKind::Unary { op, operand } => {
                let v = self.fold(operand, scope, expect);
                if v.ty == Ty::Error {
                    return v;
                }
                let Some(ty) = ops::unary(&self.types, *op, &v) else {
                    let t = crate::names::ty_name(&self.types, self.interner, v.ty);
                    self.emit(Diagnostic::error(
                        Code::E031,
                        e.span,
                        format!("operator `{}` is not defined for {t}", unary_symbol(*op)),
                    ));
                    return Typed::ERROR;
                };
                let elem = match (ty, expect) {
                    (Ty::Of(t), _) => self.types.elem(t),
                    (Ty::AnyInt, Some(x)) => self.types.elem(x),
                    _ => None,
                };
                let folded = v.value.as_ref().map(|x| value::unary(*op, x, elem));
                self.finish_fold(folded, ty, e.span)
            }
            ExprKind::Binary { op, lhs, rhs } => {
                let l = self.fold(lhs, scope, expect);
                let r = self.fold(rhs, scope, expect);
                if l.ty == Ty::Error || r.ty == Ty::Error {
                    return Typed::ERROR;
                }
                let Some(ty) = ops::binary(&self.types, *op, &l, &r) else {
                    let (a, b) = (
                        crate::names::ty_name(&self.types, self.interner, l.ty),
                        crate::names::ty_name(&self.types, self.interner, r.ty),
                    );
                    self.emit(Diagnostic::error(
                        Code::E031,
                        e.span,
                        format!("operator `{}` is not defined for {a} and {b}", op.symbol()),
                    ));
                    return Typed::ERROR;
                };
                let folded = match (&l.value, &r.value) {
                    (Some(a), Some(b)) => Some(value::binary(*op, a, b)),
                    _ => None,
                };
                self.finish_fold(folded, ty, e.span)
            }
            ExprKind::Error => Typed::ERROR,
            ExprKind::Call { .. } => self.not_constant(e.span, "a function call"),
            _ => self.not_constant(e.span, "this expression"),
        }
    }

    /// Checks a folded value against its type (overflow of a typed integer).
    fn finish_fold(
        &mut self,
        folded: Option<Result<Option<Value>, FoldError>>,
        ty: Ty,
        span: Span,
    ) -> Typed {
        let value = match folded {
            Some(Ok(Some(v))) => v,
            Some(Err(FoldError::DivByZero)) => {
                self.emit(Diagnostic::error(
                    Code::E071,
                    span,
                    "division by zero in a constant expression",
                ));
                return Typed::ERROR;
            }
            Some(Err(FoldError::Overflow)) => {
                self.emit(Diagnostic::error(
                    Code::E073,
                    span,
                    "constant expression overflows",
                ));
                return Typed::ERROR;
            }
            _ => return self.not_constant(span, "this expression"),
        };
        if let (Ty::Of(t), Some(v)) = (ty, value.as_int()) {
            if let Some(e) = self.types.elem(t) {
                if matches!(value, Value::Int(_)) && !int_fits(v, e) {
                    self.emit(Diagnostic::error(
                        Code::E073,
                        span,
                        format!(
                            "constant expression overflows {}: its value is {v}",
                            e.name()
                        ),
                    ));
                    return Typed::ERROR;
                }
            }
        }
        Typed::with(ty, value)
    }

    fn not_constant(&mut self, span: Span, what: &str) -> Typed {
        self.emit(Diagnostic::error(
            Code::E070,
            span,
            format!("{what} is not a constant expression"),
        ));
        Typed::ERROR
    }

    /// The type named by a literal prefix (`INT#`, `Color#`).
    fn literal_prefix(&mut self, t: Ident) -> TypeId {
        let (id, _) = self.resolve_spec(
            &automat_syntax::ast::TypeSpec::Named(t),
            0,
            super::typeres::SpecCtx::default(),
        );
        id
    }

    /// `Color.Red` (CODESYS's qualified enumeration value), if `t` names an enumeration.
    fn qualified_enum(&mut self, t: Ident, member: Ident) -> Option<Typed> {
        let (id, _) = self.resolve_named(t.sym, Some(t.span), false)?;
        let TypeKind::Enum { values, .. } = self.types.get(id) else {
            return None;
        };
        match values.iter().find(|v| v.name == member.sym) {
            Some(v) => Some(Typed::with(Ty::Of(id), Value::Enum(v.value))),
            None => {
                let (tn, vn) = (self.name(t.sym), self.name(member.sym));
                self.emit(Diagnostic::error(
                    Code::E020,
                    member.span,
                    format!("enumeration `{tn}` has no value `{vn}`"),
                ));
                Some(Typed::ERROR)
            }
        }
    }

    fn fold_name(&mut self, id: Ident, scope: usize, expect: Option<TypeId>) -> Typed {
        if let Some(&(_, v, base)) = self.enum_in_progress.iter().find(|(s, ..)| *s == id.sym) {
            return Typed::with(Ty::elem(base), Value::Int(v));
        }
        if let Some((s, i)) = self.find_slot(scope, id.sym) {
            return self.const_of_slot(s, i, id);
        }
        if let Some(t) = self.enum_value(id.sym, expect) {
            return t;
        }
        let n = self.name(id.sym);
        let msg = if self.type_slots.contains_key(&id.sym) || self.syms.is_elementary(id.sym) {
            self.emit(Diagnostic::error(
                Code::E026,
                id.span,
                format!("`{n}` is a type, not a constant"),
            ));
            return Typed::ERROR;
        } else {
            format!("unknown constant `{n}`")
        };
        self.emit(Diagnostic::error(Code::E020, id.span, msg));
        Typed::ERROR
    }

    /// The slot declaring `name` in `scope` or its parents.
    pub(super) fn find_slot(&self, scope: usize, name: Symbol) -> Option<(usize, u32)> {
        let mut cur = Some(scope);
        while let Some(s) = cur {
            let sc = self.scopes.get(s)?;
            if let Some(&i) = sc.by_name.get(&name) {
                return Some((s, i));
            }
            cur = sc.parent;
        }
        None
    }

    fn const_of_slot(&mut self, s: usize, i: u32, id: Ident) -> Typed {
        let n = self.name(id.sym);
        match self.resolve_slot(s, i) {
            SlotInfo::Cycle => {
                self.emit(Diagnostic::error(
                    Code::E070,
                    id.span,
                    format!("constant `{n}` is defined in terms of itself"),
                ));
                Typed::ERROR
            }
            SlotInfo::Var {
                section: Section::External,
                ..
            } => match self.find_global(id.sym) {
                Some((gs, gi)) if (gs, gi) != (s, i) => self.const_of_slot(gs, gi, id),
                _ => {
                    self.emit(Diagnostic::error(
                        Code::E070,
                        id.span,
                        format!("`{n}` has no constant VAR_GLOBAL to take a value from"),
                    ));
                    Typed::ERROR
                }
            },
            SlotInfo::Var { poisoned: true, .. } => Typed::ERROR,
            SlotInfo::Var { ty, .. } if ty == TypeId::ERROR => Typed::ERROR,
            SlotInfo::Var { ty, constant, .. } => {
                let value = self
                    .slot_var(s, i)
                    .and_then(|v| v.init.as_ref())
                    .and_then(|x| x.as_value())
                    .cloned();
                if !constant {
                    self.emit(Diagnostic::error(
                        Code::E070,
                        id.span,
                        format!("`{n}` is a variable, not a constant"),
                    ));
                    return Typed::ERROR;
                }
                match value.or_else(|| crate::value::default_value(&self.types, ty)) {
                    Some(v) => Typed::with(Ty::Of(ty), v),
                    None => self.not_constant(id.span, "a constant of this type"),
                }
            }
        }
    }

    /// A global variable of the name: project list first, then configurations,
    /// resources and programs, in declaration order.
    pub(super) fn find_global(&self, name: Symbol) -> Option<(usize, u32)> {
        self.globals_by_name.get(&name)?.first().copied()
    }

    /// An enumeration value by its bare name; the expected type wins when
    /// several enumerations declare the name.
    pub(super) fn enum_value(&mut self, name: Symbol, expect: Option<TypeId>) -> Option<Typed> {
        let decls = self.enum_decls.get(&name).cloned().unwrap_or_default();
        for d in decls {
            self.resolve_named(d, None, false);
        }
        let candidates = self.enum_values.get(&name)?;
        let pick = expect
            .filter(|t| candidates.contains(t))
            .or_else(|| candidates.first().copied())?;
        match self.types.get(pick) {
            TypeKind::Enum { values, .. } => values
                .iter()
                .find(|v| v.name == name)
                .map(|v| Typed::with(Ty::Of(pick), Value::Enum(v.value))),
            _ => None,
        }
    }

    /// Folds an integer constant (array bound, string length, ...).
    pub(super) fn fold_int(&mut self, e: &Expr, scope: usize, what: &str) -> Option<i128> {
        let t = self.fold(e, scope, None);
        if t.ty == Ty::Error {
            return None;
        }
        let is_int = match t.ty {
            Ty::AnyInt => true,
            Ty::Of(id) => self.types.elem(id).is_some_and(|e| e.is_int()),
            _ => false,
        };
        match (&t.value, is_int) {
            (Some(v), true) => v.as_int(),
            _ => {
                let tn = crate::names::ty_name(&self.types, self.interner, t.ty);
                self.emit(Diagnostic::error(
                    Code::E030,
                    e.span,
                    format!("{what} must be an integer constant, found {tn}"),
                ));
                None
            }
        }
    }
}

fn unary_symbol(op: automat_syntax::ast::UnaryOp) -> &'static str {
    match op {
        automat_syntax::ast::UnaryOp::Neg => "-",
        automat_syntax::ast::UnaryOp::Plus => "+",
        automat_syntax::ast::UnaryOp::Not => "NOT",
    }
}
