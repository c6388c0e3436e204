//! Base-class polymorphism: a `REF_TO B` or `VAR_IN_OUT x : B` designating
//! an instance of `B` or of a class derived from it, through `B`'s hidden
//! interface `<B>^` (see `poly_bases` in `mod.rs`).

use super::*;

impl<'a> Oop<'a> {
    /// Wraps `value` into `<B>^` (interface `i`). `view`: the value stands
    /// for an instance (a VAR_IN_OUT argument); otherwise for a reference
    /// (`REF(x)`, a reference variable).
    pub(super) fn wrap_poly(&mut self, value: &mut Expr, i: Symbol, view: bool, cx: &Ctx) {
        let Some(b) = self.poly_class.get(&i).copied() else {
            return;
        };
        let span = value.span;
        if !view && self.is_nothing(value) {
            // `NULL` (an input `n := NULL`): no instance.
            let f = format!("__IN_{}", self.name(i));
            *value = call_expr(self.sym(&f), Vec::new(), span);
            return;
        }
        if !view {
            // `REF(x)`: the instance `x`.
            if let ExprKind::Call { callee, args } = &mut value.kind {
                let is_ref = self.is_word(callee, "REF");
                if let (true, [a]) = (is_ref, args.as_mut_slice()) {
                    if let (None, Some(inner)) = (a.name, a.value.take()) {
                        *value = inner;
                        self.wrap_poly(value, i, true, cx);
                        return;
                    }
                }
            }
            match self.type_of_rewritten(value, cx) {
                Some(T::Ref(TypeSpec::Named(d))) if self.class(d.sym).is_some() => {
                    self.poly_from_class(value, i, b, d.sym, false);
                }
                Some(T::Itf(j)) if self.poly_class.contains_key(&j) => {
                    self.poly_from_poly(value, i, b, j);
                }
                Some(T::Class(_)) => {
                    let bn = self.name(b);
                    self.err(
                        Code::E212,
                        span,
                        format!(
                            "a `REF_TO {bn}` takes a reference to an instance: `REF(instance)`"
                        ),
                    );
                    value.kind = ExprKind::Error;
                }
                Some(T::Ref(TypeSpec::Named(p))) if self.pou_vars.contains_key(&p.sym) => {
                    self.not_derived(value, p.sym, b);
                }
                _ => {}
            }
            return;
        }
        if let Some((j, obj)) = self.poly_view(value, cx) {
            let mut obj = obj;
            self.expr(&mut obj, cx);
            *value = obj;
            self.poly_from_poly(value, i, b, j);
            return;
        }
        match self.type_of_rewritten(value, cx) {
            Some(T::Class(c)) => self.poly_from_class(value, i, b, c, true),
            Some(T::Pou(p)) => self.not_derived(value, p, b),
            Some(T::Itf(j)) if self.poly_class.contains_key(&j) => {
                let bn = self.name(b);
                self.err(
                    Code::E212,
                    span,
                    format!("a VAR_IN_OUT of type `{bn}` takes an instance: dereference the reference (`r^`)"),
                );
                value.kind = ExprKind::Error;
            }
            _ => {}
        }
    }

    /// An instance (`view`) or a reference of class `c` as `<B>^`.
    fn poly_from_class(&mut self, value: &mut Expr, i: Symbol, b: Symbol, c: Symbol, view: bool) {
        let span = value.span;
        if self.bad_impl.contains(&c) || self.broken.contains(&c) {
            value.kind = ExprKind::Error;
            return;
        }
        if !self.derives_from(c, b) {
            self.not_derived(value, c, b);
            return;
        }
        let f = format!("__IC_{}__{}", self.name(i), self.name(c));
        let f = self.sym(&f);
        let inner = std::mem::replace(
            value,
            Expr {
                kind: ExprKind::Error,
                span,
            },
        );
        let arg = if view {
            call_expr(self.sym("REF"), vec![inner], span)
        } else {
            inner
        };
        *value = call_expr(f, vec![arg], span);
    }

    fn not_derived(&mut self, value: &mut Expr, c: Symbol, b: Symbol) {
        let (cn, bn) = (self.name(c), self.name(b));
        self.err(
            Code::E212,
            value.span,
            format!("`{cn}` is neither `{bn}` nor derived from it: a reference to `{bn}` cannot designate it"),
        );
        value.kind = ExprKind::Error;
    }

    /// A `<D>^` value as `<B>^`: D is B or derives from it.
    fn poly_from_poly(&mut self, value: &mut Expr, i: Symbol, b: Symbol, j: Symbol) {
        if i == j {
            return;
        }
        let span = value.span;
        if !self.itf_chain(j).contains(&i) {
            let d = self.poly_class.get(&j).copied().unwrap_or(j);
            let (dn, bn) = (self.name(d), self.name(b));
            self.err(
                Code::E212,
                span,
                format!("a reference to `{dn}` cannot be assigned to a reference to `{bn}`: `{dn}` is not derived from `{bn}`"),
            );
            value.kind = ExprKind::Error;
            return;
        }
        let f = format!("__IC_{}__{}", self.name(i), self.name(j));
        let f = self.sym(&f);
        let inner = std::mem::replace(
            value,
            Expr {
                kind: ExprKind::Error,
                span,
            },
        );
        *value = call_expr(f, vec![inner], span);
    }

    /// `rd := rb` or `rd := REF(b)` for `rd : REF_TO D`, where `b`'s class
    /// is a base of `D`: refused (a base instance is not a `D`).
    pub(super) fn refuse_base_ref(&mut self, value: &mut Expr, d: Symbol, cx: &Ctx) {
        let from = match self.type_of_rewritten(value, cx) {
            Some(T::Itf(j)) => self.poly_class.get(&j).copied(),
            _ => None,
        };
        let from = from.or_else(|| match &value.kind {
            ExprKind::Call { callee, args } if self.is_word(callee, "REF") => {
                match args.first().and_then(|a| a.value.as_ref()) {
                    Some(v) => match self.type_of_rewritten(v, cx) {
                        Some(T::Class(c)) => Some(c),
                        _ => self
                            .poly_view(v, cx)
                            .and_then(|(j, _)| self.poly_class.get(&j).copied()),
                    },
                    None => None,
                }
            }
            _ => None,
        });
        if let Some(c) = from {
            if c != d {
                let (cn, dn) = (self.name(c), self.name(d));
                self.err(
                    Code::E212,
                    value.span,
                    format!("a `REF_TO {dn}` cannot designate a `{cn}`: only `{dn}` or a class derived from it"),
                );
                value.kind = ExprKind::Error;
            }
        }
    }

    /// `r^.field` / `x.field` through a reference to base `B`: the field of
    /// the designated instance, `__BR_<B^>__<field>(r)^`. Only the inputs
    /// and outputs are visible, as for any instance from outside.
    pub(super) fn poly_member(
        &mut self,
        e: &mut Expr,
        i: Symbol,
        obj: Expr,
        member: Ident,
        cx: &Ctx,
    ) {
        let Some(b) = self.poly_class.get(&i).copied() else {
            return;
        };
        let span = e.span;
        let (bn, n) = (self.name(b), self.name(member.sym));
        match self.class_var_kind(b, member.sym) {
            Some((_, VarKind::Input | VarKind::Output)) => {}
            Some(_) if self.var_refused(b, member, cx) => return,
            Some(_) if self.internal_reachable(b, member.sym, cx) => {}
            Some(_) => {
                self.err(
                    Code::E024,
                    member.span,
                    format!("`{n}` is not an input or output of `{bn}` (through a reference only those are visible)"),
                );
                return;
            }
            None if self.property_of(b, member.sym).is_some() => {
                // A read of the property: the GET of the instance's class.
                let Some((_, prop)) = self.property_of(b, member.sym) else {
                    return;
                };
                self.check_access(b, prop.visibility, member, cx);
                if prop.get.is_none() {
                    self.err(
                        Code::E210,
                        member.span,
                        format!("the property `{n}` has no GET"),
                    );
                    return;
                }
                let mut obj = obj;
                self.expr(&mut obj, cx);
                if !self.poly_props.contains(&(i, member.sym, true)) {
                    self.poly_props.push((i, member.sym, true));
                }
                let f = self.prop_dispatch_name(i, member.sym, true);
                *e = call_expr(f, vec![obj], span);
                return;
            }
            None => {
                self.err(
                    Code::E024,
                    member.span,
                    format!("`{bn}` has no variable `{n}`"),
                );
                return;
            }
        }
        let mut obj = obj;
        self.expr(&mut obj, cx);
        if !self.poly_fields.contains(&(i, member.sym)) {
            self.poly_fields.push((i, member.sym));
        }
        let f = self.field_fn_name(i, member.sym);
        e.kind = ExprKind::Deref(Box::new(call_expr(f, vec![obj], span)));
    }

    /// Writing an output through a reference to a base class is refused as
    /// for any instance (E042).
    pub(super) fn poly_write_check(&mut self, target: &Expr, cx: &Ctx) {
        let ExprKind::Member { base, member } = &target.kind else {
            return;
        };
        let Some((i, _)) = self.poly_view(base, cx) else {
            return;
        };
        let Some(b) = self.poly_class.get(&i).copied() else {
            return;
        };
        if let Some((_, VarKind::Output)) = self.class_var_kind(b, member.sym) {
            let (bn, n) = (self.name(b), self.name(member.sym));
            self.err(
                Code::E042,
                member.span,
                format!("the output `{n}` of `{bn}` cannot be written from outside"),
            );
        }
    }

    /// `r^.prop := v` through a reference to a base class: the SET of the
    /// instance's class, `__BS_<B^>__<prop>(r, v)`. `None`: not such a target.
    pub(super) fn poly_prop_set(
        &mut self,
        target: &Expr,
        value: &Expr,
        cx: &Ctx,
    ) -> Option<StmtKind> {
        let ExprKind::Member { base, member } = &target.kind else {
            return None;
        };
        let (i, obj) = self.poly_view(base, cx)?;
        let b = self.poly_class.get(&i).copied()?;
        if self.class_var_kind(b, member.sym).is_some() {
            return None;
        }
        let (_, prop) = self.property_of(b, member.sym)?;
        self.check_access(b, prop.visibility, *member, cx);
        if prop.set.is_none() {
            let n = self.name(member.sym);
            self.err(
                Code::E210,
                member.span,
                format!("the property `{n}` has no SET"),
            );
            return Some(StmtKind::Empty);
        }
        let mut obj = obj;
        self.expr(&mut obj, cx);
        let mut v = value.clone();
        self.expr(&mut v, cx);
        if !self.poly_props.contains(&(i, member.sym, false)) {
            self.poly_props.push((i, member.sym, false));
        }
        let f = self.prop_dispatch_name(i, member.sym, false);
        Some(StmtKind::Expr(call_expr(f, vec![obj, v], target.span)))
    }

    fn prop_dispatch_name(&mut self, i: Symbol, p: Symbol, get: bool) -> Symbol {
        let pre = if get { "__BG_" } else { "__BS_" };
        let n = format!("{pre}{}__{}", self.name(i), self.name(p));
        self.sym(&n)
    }

    /// `FUNCTION __BG_<B^>__<p> : <type>` (GET) or `__BS_<B^>__<p>` (SET,
    /// with the input `__v`) over `__o : __ITF_<B^>`: a CASE on the class
    /// number calling that class's accessor; without an instance it
    /// dereferences the first class's NULL reference (the runtime's fault).
    pub(super) fn poly_prop_fn(&mut self, i: Symbol, p: Symbol, get: bool) -> Option<Item> {
        let b = self.poly_class.get(&i).copied()?;
        let (_, prop) = self.property_of(b, p)?;
        let mut ty = prop.ty.clone();
        self.retype_spec(&mut ty, VarKind::Local);
        let span = self.itf(i).map_or(Span::default(), |x| x.name.span);
        let fsym = self.prop_dispatch_name(i, p, get);
        let osym = self.sym("__o");
        let vsym = self.sym("__v");
        let id_sym = self.sym("__id");
        let ssym = {
            let n = format!("__ITF_{}", self.name(i));
            self.sym(&n)
        };
        let this_sym = self.this;
        let id = |s: Symbol| Ident { sym: s, span };
        let name_e = |s: Symbol| Expr {
            kind: ExprKind::Name(id(s)),
            span,
        };
        let member_e = |b: Expr, m: Symbol| Expr {
            kind: ExprKind::Member {
                base: Box::new(b),
                member: id(m),
            },
            span,
        };
        let named = |n: Symbol, v: Expr| Arg {
            name: Some(id(n)),
            dir: ArgDir::In,
            value: Some(v),
            span,
        };
        let mut arms = Vec::new();
        for c in self.implementors(i) {
            let k = self.ids.get(&c).copied().unwrap_or(0);
            let r = format!("__r{k}");
            let r = self.sym(&r);
            let this = Expr {
                kind: ExprKind::Deref(Box::new(member_e(name_e(osym), r))),
                span,
            };
            let accessor = self.prop_fn(c, p, get);
            let mut args = vec![named(this_sym, this)];
            if !get {
                args.push(named(p, name_e(vsym)));
            }
            let call = Expr {
                kind: ExprKind::Call {
                    callee: Box::new(name_e(accessor)),
                    args,
                },
                span,
            };
            let stmt = Stmt {
                kind: if get {
                    StmtKind::Assign {
                        target: name_e(fsym),
                        value: call,
                    }
                } else {
                    StmtKind::Expr(call)
                },
                span,
            };
            arms.push((i128::from(k), vec![stmt]));
        }
        let body: Vec<Stmt> = dispatch_case(member_e(name_e(osym), id_sym), arms, true, span)
            .into_iter()
            .collect();
        let decl = |n: Symbol, t: TypeSpec| VarDecl {
            names: vec![id(n)],
            location: None,
            ty: t,
            edge: None,
            init: None,
            span,
        };
        let mut decls = vec![decl(osym, TypeSpec::Named(id(ssym)))];
        if !get {
            decls.push(decl(vsym, ty.clone()));
        }
        Some(Item::Pou(Pou {
            kind: PouKind::Function,
            name: id(fsym),
            return_type: get.then_some(ty),
            var_blocks: vec![VarBlock {
                kind: VarKind::Input,
                constant: false,
                retain: Default::default(),
                decls,
                span,
            }],
            body: Body::St(body),
            lang: Lang::St,
            span,
        }))
    }

    fn field_fn_name(&mut self, i: Symbol, field: Symbol) -> Symbol {
        let n = format!("__BR_{}__{}", self.name(i), self.name(field));
        self.sym(&n)
    }

    /// `FUNCTION __BR_<B^>__<f> : REF_TO <type of f>` over `__o : __ITF_<B^>`:
    /// a CASE on the class number; without an instance it dereferences
    /// the first class's NULL reference (the runtime's fault).
    pub(super) fn poly_field_fn(&mut self, i: Symbol, field: Symbol) -> Option<Item> {
        let b = self.poly_class.get(&i).copied()?;
        let (mut ty, _) = self.class_var_kind(b, field)?;
        self.retype_spec(&mut ty, VarKind::Local);
        let span = self.itf(i).map_or(Span::default(), |x| x.name.span);
        let fsym = self.field_fn_name(i, field);
        let osym = self.sym("__o");
        let id_sym = self.sym("__id");
        let ssym = {
            let n = format!("__ITF_{}", self.name(i));
            self.sym(&n)
        };
        let rsym = self.sym("REF");
        let id = |s: Symbol| Ident { sym: s, span };
        let name_e = |s: Symbol| Expr {
            kind: ExprKind::Name(id(s)),
            span,
        };
        let member_e = |b: Expr, m: Symbol| Expr {
            kind: ExprKind::Member {
                base: Box::new(b),
                member: id(m),
            },
            span,
        };
        // An internal variable (reached from the class's own code) only
        // through `__PF_` (the checker lets only `__THIS.v` reach it).
        let internal = !matches!(
            self.class_var_kind(b, field),
            Some((_, VarKind::Input | VarKind::Output))
        );
        let mut arms = Vec::new();
        for c in self.implementors(i) {
            let k = self.ids.get(&c).copied().unwrap_or(0);
            let r = format!("__r{k}");
            let r = self.sym(&r);
            let instance = Expr {
                kind: ExprKind::Deref(Box::new(member_e(name_e(osym), r))),
                span,
            };
            let value = if internal {
                if !self.private_fields.contains(&(c, field)) {
                    self.private_fields.push((c, field));
                }
                let f = self.private_fn_name(c, field);
                self.private_call(f, instance, span)
            } else {
                call_expr(rsym, vec![member_e(instance, field)], span)
            };
            let stmt = Stmt {
                kind: StmtKind::Assign {
                    target: name_e(fsym),
                    value,
                },
                span,
            };
            arms.push((i128::from(k), vec![stmt]));
        }
        let body: Vec<Stmt> = dispatch_case(member_e(name_e(osym), id_sym), arms, true, span)
            .into_iter()
            .collect();
        Some(Item::Pou(Pou {
            kind: PouKind::Function,
            name: id(fsym),
            return_type: Some(TypeSpec::Ref {
                target: Box::new(ty),
                span,
                reference: false,
            }),
            var_blocks: vec![VarBlock {
                kind: VarKind::Input,
                constant: false,
                retain: Default::default(),
                decls: vec![VarDecl {
                    names: vec![id(osym)],
                    location: None,
                    ty: TypeSpec::Named(id(ssym)),
                    edge: None,
                    init: None,
                    span,
                }],
                span,
            }],
            body: Body::St(body),
            lang: Lang::St,
            span,
        }))
    }
}

/// `f(a, b, …)` with positional arguments.
/// `CASE <selector> OF k: body; ... END_CASE`, the dispatch on an
/// interface value's class number (`None` without arms). `else_first`: with
/// no instance (`__id` 0) the first arm runs, whose reference is NULL, so
/// its dereference is the runtime's fault.
pub(super) fn dispatch_case(
    selector: Expr,
    arms: Vec<(i128, Vec<Stmt>)>,
    else_first: bool,
    span: Span,
) -> Option<Stmt> {
    let else_body = if else_first {
        arms.first().map(|(_, b)| b.clone())
    } else {
        None
    };
    let arms: Vec<CaseArm> = arms
        .into_iter()
        .map(|(k, body)| CaseArm {
            labels: vec![CaseLabel::Value(Expr {
                kind: ExprKind::Literal(Box::new(Literal {
                    kind: LitKind::Int(k),
                    ty: None,
                })),
                span,
            })],
            body,
            span,
        })
        .collect();
    if arms.is_empty() {
        return None;
    }
    Some(Stmt {
        kind: StmtKind::Case {
            selector,
            arms,
            else_body,
        },
        span,
    })
}

pub(super) fn call_expr(f: Symbol, args: Vec<Expr>, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Call {
            callee: Box::new(Expr {
                kind: ExprKind::Name(Ident { sym: f, span }),
                span,
            }),
            args: args
                .into_iter()
                .map(|v| Arg {
                    name: None,
                    dir: ArgDir::In,
                    value: Some(v),
                    span,
                })
                .collect(),
        },
        span,
    }
}
