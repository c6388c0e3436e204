//! What an expression designates (an instance, an interface, a class), for method calls and conversions.

use super::*;

impl<'a> Oop<'a> {
    pub(super) fn spec_t(&self, ty: &TypeSpec) -> T {
        match ty {
            TypeSpec::Named(id) => {
                if self.classes.contains_key(&id.sym) {
                    T::Class(id.sym)
                } else if self.itfs.contains_key(&id.sym) {
                    T::Itf(id.sym)
                } else if let Some(i) = self.itf_structs.get(&id.sym) {
                    // A declaration already retyped.
                    T::Itf(*i)
                } else if self.pou_vars.contains_key(&id.sym) {
                    T::Pou(id.sym)
                } else {
                    // A derived type: its definition (aliases chain at most a few levels).
                    let mut t = self.types.get(&id.sym);
                    for _ in 0..8 {
                        match t {
                            Some(TypeSpec::Named(n))
                                if !self.classes.contains_key(&n.sym)
                                    && !self.itfs.contains_key(&n.sym) =>
                            {
                                t = self.types.get(&n.sym);
                            }
                            Some(spec) => return self.spec_t(&spec.clone()),
                            None => return T::Other,
                        }
                    }
                    T::Other
                }
            }
            TypeSpec::Struct { members, .. } => T::Struct(members.clone()),
            TypeSpec::Array { elem, .. } => T::Array((**elem).clone()),
            TypeSpec::Ref { target, .. } => match &**target {
                TypeSpec::Named(id) if self.poly.contains_key(&id.sym) => {
                    T::Itf(self.poly.get(&id.sym).copied().unwrap_or(id.sym))
                }
                t => T::Ref(t.clone()),
            },
            _ => T::Other,
        }
    }

    /// A variable of class `c` (or a base): its type as written and its section.
    pub(super) fn class_var_kind(&self, c: Symbol, n: Symbol) -> Option<(TypeSpec, VarKind)> {
        for k in self.chain(c) {
            for b in &self.class(k)?.var_blocks {
                for decl in &b.decls {
                    if decl.names.iter().any(|x| x.sym == n) {
                        return Some((decl.ty.clone(), b.kind));
                    }
                }
            }
        }
        None
    }

    /// An instance reached through a reference to a base class: `r^` for
    /// `r : REF_TO B`, or a `VAR_IN_OUT x : B`. Returns `B`'s `<B>^`
    /// interface and the expression holding the reference (`r`, `x`).
    pub(super) fn poly_view(&self, e: &Expr, cx: &Ctx) -> Option<(Symbol, Expr)> {
        match &e.kind {
            ExprKind::Paren(i) => self.poly_view(i, cx),
            ExprKind::Deref(b) if !self.is_kw(b, "THIS", cx) && !self.is_kw(b, "SUPER", cx) => {
                match self.type_of(b, cx) {
                    T::Itf(i) if self.poly_class.contains_key(&i) => Some((i, (**b).clone())),
                    _ => None,
                }
            }
            ExprKind::Name(id) if cx.byref.contains(&id.sym) => {
                // Declared `x : B` (a class's member, as written), `REF_TO B`
                // (a split parameter) or already `__ITF_<B^>`.
                let ty = cx
                    .locals
                    .get(&id.sym)
                    .cloned()
                    .or_else(|| cx.class.and_then(|c| self.class_var(c, id.sym)))?;
                let i = match &ty {
                    TypeSpec::Named(n) => self
                        .poly
                        .get(&n.sym)
                        .or_else(|| self.itf_structs.get(&n.sym))
                        .copied()?,
                    TypeSpec::Ref { target, .. } => match &**target {
                        TypeSpec::Named(n) => self.poly.get(&n.sym).copied()?,
                        _ => return None,
                    },
                    _ => return None,
                };
                self.poly_class.contains_key(&i).then(|| (i, e.clone()))
            }
            _ => None,
        }
    }

    pub(super) fn class_var(&self, c: Symbol, n: Symbol) -> Option<TypeSpec> {
        for k in self.chain(c) {
            for b in &self.class(k)?.var_blocks {
                for decl in &b.decls {
                    if decl.names.iter().any(|x| x.sym == n) {
                        return Some(decl.ty.clone());
                    }
                }
            }
        }
        None
    }

    pub(super) fn type_of(&self, e: &Expr, cx: &Ctx) -> T {
        match &e.kind {
            ExprKind::Paren(i) => self.type_of(i, cx),
            ExprKind::Name(id) => {
                if let Some(t) = cx.locals.get(&id.sym) {
                    return self.spec_t(t);
                }
                // A method's result, by the method's name.
                if let Some((r, f)) = cx.result {
                    if r == id.sym {
                        if let Some(t) = self.returns.get(&f) {
                            return self.spec_t(t);
                        }
                    }
                }
                if let Some(c) = cx.class {
                    if let Some(t) = self.class_var(c, id.sym) {
                        return self.spec_t(&t);
                    }
                }
                self.globals
                    .get(&id.sym)
                    .map_or(T::Other, |t| self.spec_t(t))
            }
            ExprKind::Deref(b) => {
                if self.is_kw(b, "THIS", cx) && cx.class.is_some() {
                    return T::Class(cx.class.unwrap_or(id_none()));
                }
                match self.type_of(b, cx) {
                    T::Ref(t) => self.spec_t(&t),
                    _ => T::Other,
                }
            }
            ExprKind::Member { base, member } => match self.type_of(base, cx) {
                T::Class(c) => self
                    .class_var(c, member.sym)
                    .map_or(T::Other, |t| self.spec_t(&t)),
                T::Pou(p) => self
                    .pou_vars
                    .get(&p)
                    .and_then(|v| v.get(&member.sym))
                    .map_or(T::Other, |t| self.spec_t(t)),
                T::Struct(ms) => ms
                    .iter()
                    .find(|d| d.names.iter().any(|n| n.sym == member.sym))
                    .map_or(T::Other, |d| self.spec_t(&d.ty)),
                _ => T::Other,
            },
            ExprKind::Index { base, .. } => match self.type_of(base, cx) {
                T::Array(t) => self.spec_t(&t),
                _ => T::Other,
            },
            // A call's result: a plain function's, or a method's through an
            // instance or an interface.
            ExprKind::Call { callee, .. } => {
                let ret = match &callee.kind {
                    ExprKind::Name(f) => self.returns.get(&f.sym),
                    ExprKind::Member { base, member } => match self.type_of(base, cx) {
                        T::Class(c) => self
                            .method_of(c, member.sym)
                            .and_then(|(_, m)| m.return_type.as_ref()),
                        T::Itf(i) => self
                            .itf_method(i, member.sym)
                            .and_then(|m| m.return_type.as_ref()),
                        _ => None,
                    },
                    _ => None,
                };
                ret.map_or(T::Other, |t| self.spec_t(t))
            }
            _ => T::Other,
        }
    }

    /// `THIS` / `SUPER`, unless a variable of that name is in scope.
    pub(super) fn is_kw(&self, e: &Expr, w: &str, cx: &Ctx) -> bool {
        match &e.kind {
            ExprKind::Name(id) => {
                !cx.locals.contains_key(&id.sym)
                    && self.interner.name(id.sym).eq_ignore_ascii_case(w)
            }
            _ => false,
        }
    }

    pub(super) fn is_word(&self, e: &Expr, w: &str) -> bool {
        matches!(&e.kind, ExprKind::Name(id) if self.interner.name(id.sym).eq_ignore_ascii_case(w))
    }
}
