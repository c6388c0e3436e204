//! Initial values: folded and checked against the declared type (E039 for
//! a wrong type, too many array elements or an unknown structure member,
//! E038 for a constant outside a subrange, W003 for a narrowed constant).

use super::Builder;
use crate::convert::{fits, stored_value, Fit};
use crate::ops::Ty;
use crate::types::{Dim, TypeId, TypeKind};
use crate::value::{ArrayInit, FieldInit, Init};
use automat_base::{Code, Diagnostic, Span, Symbol};
use automat_syntax::ast::{Ident, Initializer};
use rustc_hash::FxHashMap;

impl<'a> Builder<'a> {
    /// The initial value of a `REF_TO` variable: `NULL`, or `REF(x)` /
    /// `ADR(x)` of a variable whose address is fixed in the image — a
    /// global, or a variable of the same PROGRAM or FUNCTION_BLOCK (each
    /// instance then refers to its own `x`), of the referenced type.
    fn ref_init(
        &mut self,
        e: &automat_syntax::ast::Expr,
        ty: TypeId,
        scope: usize,
        name: Ident,
    ) -> Option<Init> {
        use automat_syntax::ast::ExprKind;
        let TypeKind::Ref(target) = *self.types.get(ty) else {
            return None;
        };
        let n = self.name(name.sym);
        let mut inner = e;
        while let ExprKind::Paren(x) = &inner.kind {
            inner = x;
        }
        if let ExprKind::Name(id) = &inner.kind {
            if self.name(id.sym).eq_ignore_ascii_case("NULL")
                && self.find_slot(scope, id.sym).is_none()
            {
                return Some(Init::Ref(None));
            }
        }
        let arg = match &inner.kind {
            ExprKind::Call { callee, args } => match (&callee.kind, args.as_slice()) {
                (ExprKind::Name(f), [a])
                    if a.name.is_none()
                        && (self.name(f.sym).eq_ignore_ascii_case("REF")
                            || self.name(f.sym).eq_ignore_ascii_case("ADR")) =>
                {
                    a.value.as_ref()
                }
                _ => None,
            },
            _ => None,
        };
        let Some(ExprKind::Name(x)) = arg.map(|a| &a.kind) else {
            self.emit(Diagnostic::error(
                Code::E039,
                e.span,
                format!(
                    "the initial value of `{n}` (a {}) must be NULL or REF(variable)",
                    self.type_name(ty)
                ),
            ));
            return None;
        };
        if matches!(
            self.init_section,
            Some(crate::model::Section::Temp | crate::model::Section::InOut)
        ) {
            self.emit(Diagnostic::error(
                Code::E039,
                e.span,
                format!("`{n}` is re-initialised at every call: REF(...) cannot be its initial value; assign it in the body"),
            ));
            return None;
        }
        let xn = self.name(x.sym);
        let Some((s, i)) = self.find_slot(scope, x.sym) else {
            self.emit(Diagnostic::error(
                Code::E020,
                x.span,
                format!("unknown variable `{xn}` in the initial value of `{n}`"),
            ));
            return None;
        };
        let owner = self.scopes.get(s).map(|sc| sc.owner);
        let fixed = match owner {
            Some(super::Owner::Pou(pid)) => self.pous.get(pid.0 as usize).is_some_and(|p| {
                matches!(
                    p.ast.kind,
                    automat_syntax::ast::PouKind::Program
                        | automat_syntax::ast::PouKind::FunctionBlock
                )
            }),
            Some(_) => true,
            None => false,
        };
        let (xty, section) = match self.resolve_slot(s, i) {
            super::fold::SlotInfo::Var { ty, section, .. } => (ty, section),
            super::fold::SlotInfo::Cycle => {
                self.emit(Diagnostic::error(
                    Code::E039,
                    x.span,
                    format!("the initial value of `{n}` refers to `{xn}`, whose declaration depends on it"),
                ));
                return None;
            }
        };
        let movable = matches!(
            section,
            crate::model::Section::Temp
                | crate::model::Section::InOut
                | crate::model::Section::Return
        );
        if !fixed || movable {
            self.emit(Diagnostic::error(
                Code::E039,
                x.span,
                format!("`{xn}` has no fixed address (a function's or VAR_TEMP variable, or a VAR_IN_OUT): REF({xn}) cannot be the initial value of `{n}`"),
            ));
            return None;
        }
        if xty != target && xty != TypeId::ERROR {
            let (xt, tt) = (self.type_name(xty), self.type_name(target));
            self.emit(Diagnostic::error(
                Code::E039,
                x.span,
                format!("REF({xn}) refers to a {xt}, but `{n}` is a REF_TO {tt}"),
            ));
            return None;
        }
        Some(Init::Ref(Some(x.sym)))
    }

    /// Checks and folds the initial value of `name` (a variable, member or
    /// type) of type `ty`. `None` after an error (reported).
    pub(super) fn check_init(
        &mut self,
        init: &Initializer,
        ty: TypeId,
        scope: usize,
        name: Ident,
    ) -> Option<Init> {
        if ty == TypeId::ERROR {
            return None;
        }
        match init {
            Initializer::Expr(e) if matches!(self.types.get(ty), TypeKind::Ref(_)) => {
                self.ref_init(e, ty, scope, name)
            }
            Initializer::Expr(e) => {
                let t = self.fold(e, scope, Some(ty));
                if t.ty == Ty::Error {
                    return None;
                }
                let n = self.name(name.sym);
                match fits(&self.types, &t, ty) {
                    Fit::Ok => {}
                    Fit::NarrowedConstant => {
                        let (v, tn) = (show(&t), self.type_name(ty));
                        self.emit(Diagnostic::warning(
                            Code::W003,
                            e.span,
                            format!("the constant {v} is narrowed to {tn} for `{n}`"),
                        ));
                    }
                    Fit::OutOfRange => {
                        let (v, tn) = (show(&t), self.type_name(ty));
                        self.emit(Diagnostic::error(
                            Code::E039,
                            e.span,
                            format!("the initial value {v} does not fit `{n}` of type {tn}"),
                        ));
                        return None;
                    }
                    Fit::OutOfSubrange { lo, hi } => {
                        let v = show(&t);
                        self.emit(Diagnostic::error(
                            Code::E038,
                            e.span,
                            format!(
                                "the initial value {v} of `{n}` is outside its subrange {lo}..{hi}"
                            ),
                        ));
                        return None;
                    }
                    Fit::Mismatch => {
                        let from = crate::names::value_desc(&self.types, self.interner, &t);
                        let tn = self.type_name(ty);
                        self.emit(Diagnostic::error(
                            Code::E039,
                            e.span,
                            format!("{from} cannot initialise `{n}` of type {tn}"),
                        ));
                        return None;
                    }
                }
                stored_value(&self.types, &t, ty).map(Init::Value)
            }
            Initializer::Array { elems, span } => {
                let (elem, dims) = match self.types.get(ty) {
                    TypeKind::Array { elem, dims } => (*elem, dims.clone()),
                    _ => return self.init_shape_error(*span, ty, name, "an array"),
                };
                self.check_array_init(elems, elem, &dims, *span, scope, name)
            }
            Initializer::Struct { fields, span } => {
                self.check_struct_init(fields, ty, *span, scope, name)
            }
        }
    }

    fn init_shape_error(
        &mut self,
        span: Span,
        ty: TypeId,
        name: Ident,
        what: &str,
    ) -> Option<Init> {
        let (n, tn) = (self.name(name.sym), self.type_name(ty));
        self.emit(Diagnostic::error(
            Code::E039,
            span,
            format!("{what} initial value does not fit `{n}` of type {tn}"),
        ));
        None
    }

    fn check_array_init(
        &mut self,
        elems: &[automat_syntax::ast::ArrayInitElem],
        elem: TypeId,
        dims: &[Dim],
        span: Span,
        scope: usize,
        name: Ident,
    ) -> Option<Init> {
        // `[[1, 2], [3, 4]]` for a two-dimensional array: rows of the remaining dimensions.
        let nested = dims.len() > 1
            && elems
                .iter()
                .any(|e| matches!(e.value, Some(Initializer::Array { .. })));
        let (item_ty, capacity) = if nested {
            let rest = dims.get(1..).unwrap_or(&[]).to_vec();
            let row = self.types.array(elem, rest);
            (row, dims.first().map(|d| d.len()))
        } else {
            let star = dims.iter().any(|d| matches!(d, Dim::Star));
            let total = dims.iter().fold(1u64, |acc, d| acc.saturating_mul(d.len()));
            (elem, (!star).then_some(total))
        };
        let mut out = Vec::with_capacity(elems.len());
        let mut count: u64 = 0;
        let mut ok = true;
        for el in elems {
            let repeat = match &el.repeat {
                None => 1,
                Some(r) => match self.fold_int(r, scope, "a repetition count") {
                    Some(n) if (0..=u32::MAX as i128).contains(&n) => n as u64,
                    Some(n) => {
                        self.emit(Diagnostic::error(
                            Code::E039,
                            r.span,
                            format!("repetition count {n} is out of range"),
                        ));
                        ok = false;
                        continue;
                    }
                    None => {
                        ok = false;
                        continue;
                    }
                },
            };
            count = count.saturating_add(repeat);
            let value = match &el.value {
                None => None,
                Some(v) => match self.check_init(v, item_ty, scope, name) {
                    Some(i) => Some(i),
                    None => {
                        ok = false;
                        None
                    }
                },
            };
            out.push(ArrayInit { repeat, value });
        }
        if let Some(cap) = capacity {
            if count > cap {
                let n = self.name(name.sym);
                self.emit(Diagnostic::error(
                    Code::E039,
                    span,
                    format!("`{n}` has {cap} elements but its initial value gives {count}"),
                ));
                return None;
            }
        }
        ok.then_some(Init::Array(out))
    }

    fn check_struct_init(
        &mut self,
        fields: &[automat_syntax::ast::FieldInit],
        ty: TypeId,
        span: Span,
        scope: usize,
        name: Ident,
    ) -> Option<Init> {
        // The members a structure initialiser may name: a structure's, or a
        // function block's variables (CODESYS initialises instances this way).
        let members: Vec<(Symbol, TypeId)> = match self.types.get(ty) {
            TypeKind::Struct { members, .. } => members.iter().map(|m| (m.name, m.ty)).collect(),
            TypeKind::Fb { pou, .. } => self.fb_members(*pou),
            _ => return self.init_shape_error(span, ty, name, "a structure"),
        };
        let mut out = Vec::with_capacity(fields.len());
        let mut seen: FxHashMap<Symbol, Span> = FxHashMap::default();
        let mut ok = true;
        for f in fields {
            let Some(&(_, mty)) = members.iter().find(|(m, _)| *m == f.name.sym) else {
                let (tn, fnm) = (self.type_name(ty), self.name(f.name.sym));
                self.emit(Diagnostic::error(
                    Code::E039,
                    f.name.span,
                    format!("`{tn}` has no member `{fnm}`"),
                ));
                ok = false;
                continue;
            };
            if let Some(&first) = seen.get(&f.name.sym) {
                let fnm = self.name(f.name.sym);
                self.emit(
                    Diagnostic::error(
                        Code::E039,
                        f.name.span,
                        format!("member `{fnm}` is initialised twice"),
                    )
                    .with_label(first, "first initialised here"),
                );
                ok = false;
                continue;
            }
            seen.insert(f.name.sym, f.name.span);
            match self.check_init(&f.value, mty, scope, f.name) {
                Some(v) => out.push(FieldInit {
                    name: f.name.sym,
                    value: v,
                }),
                None => ok = false,
            }
        }
        ok.then_some(Init::Struct(out))
    }

    /// The variables of a function block (resolved on demand) with their types.
    fn fb_members(&mut self, pou: crate::types::PouId) -> Vec<(Symbol, TypeId)> {
        let Some(scope) = self.pous.get(pou.0 as usize).map(|p| p.scope) else {
            return Vec::new();
        };
        let n = self.scopes.get(scope).map_or(0, |s| s.slots.len());
        let mut out = Vec::with_capacity(n);
        for i in 0..n as u32 {
            let name = self
                .scopes
                .get(scope)
                .and_then(|s| s.slots.get(i as usize))
                .map(|s| s.name.sym);
            if let (Some(name), super::fold::SlotInfo::Var { ty, .. }) =
                (name, self.resolve_slot(scope, i))
            {
                out.push((name, ty));
            }
        }
        out
    }
}

fn show(t: &crate::ops::Typed) -> String {
    t.value.as_ref().map_or_else(|| "?".into(), |v| v.show())
}
