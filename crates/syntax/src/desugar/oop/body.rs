//! Bodies: method and property calls, THIS/SUPER, interface conversions of assignments and arguments.

use super::*;

impl<'a> Oop<'a> {
    pub(super) fn stmts(&mut self, list: &mut Vec<Stmt>, cx: &Ctx) {
        let mut i = 0;
        while i < list.len() {
            // `SUPER^();` in a body: the base's body, here.
            if let Some(s) = list.get(i) {
                if let StmtKind::Expr(e) = &s.kind {
                    if let ExprKind::Call { callee, args } = &e.kind {
                        if args.is_empty()
                            && matches!(&callee.kind, ExprKind::Deref(b) if self.is_kw(b, "SUPER", cx))
                        {
                            let span = s.span;
                            let base = cx
                                .defined_in
                                .and_then(|k| self.class(k))
                                .and_then(|c| c.extends);
                            let body = base.and_then(|b| {
                                self.chain(b.sym)
                                    .into_iter()
                                    .filter_map(|k| self.class(k))
                                    .find(|x| !x.body.is_empty())
                                    .map(|x| (x.name.sym, x.body.clone()))
                            });
                            match (base, cx.in_method, body) {
                                (Some(_), false, Some((_, b)))
                                    if self.inlined + b.len() > MAX_INLINED =>
                                {
                                    let _ = b;
                                    self.err(Code::E213, span, format!("`SUPER^();` would copy more than {MAX_INLINED} statements of base bodies"));
                                    self.inlined = usize::MAX / 2;
                                    if let Some(s) = list.get_mut(i) {
                                        s.kind = StmtKind::Empty;
                                    }
                                    i += 1;
                                    continue;
                                }
                                (Some(_), false, Some((k, mut b))) => {
                                    self.inlined += b.len();
                                    let sub = Ctx {
                                        defined_in: Some(k),
                                        ..cx.clone()
                                    };
                                    self.stmts(&mut b, &sub);
                                    let n = b.len();
                                    list.splice(i..=i, b);
                                    i += n;
                                    continue;
                                }
                                (Some(_), false, None) => {
                                    list.remove(i);
                                    continue;
                                }
                                _ => {
                                    self.err(Code::E208, span, "`SUPER^()` runs the base's body: only in the body of a function block that EXTENDS another".into());
                                    if let Some(s) = list.get_mut(i) {
                                        s.kind = StmtKind::Empty;
                                    }
                                    i += 1;
                                    continue;
                                }
                            }
                        }
                    }
                }
            }
            // `r^(...)` through a reference to a base class: plain
            // statements, rewritten in turn by the loop.
            if let Some(b) = list.get(i).and_then(|s| self.body_call(s, cx)) {
                list.splice(i..=i, b);
                continue;
            }
            if let Some(s) = list.get_mut(i) {
                self.stmt(s, cx);
            }
            i += 1;
        }
    }

    pub(super) fn stmt(&mut self, s: &mut Stmt, cx: &Ctx) {
        if self.depth > crate::MAX_DEPTH * 2 {
            return;
        }
        self.depth += 1;
        let span = s.span;
        match &mut s.kind {
            StmtKind::Assign { target, value } => {
                // `r^.prop := v` through a reference to a base class.
                if let Some(k) = self.poly_prop_set(target, value, cx) {
                    s.kind = k;
                    self.depth -= 1;
                    return;
                }
                // `x.prop := v` / `prop := v`: the SET accessor.
                if let Some((c, this, prop)) = self.prop_target(target, cx) {
                    let mut v = value.clone();
                    self.expr(&mut v, cx);
                    match self.property_of(c, prop.sym) {
                        Some((_, p)) if p.set.is_some() => {
                            self.check_access(c, p.visibility, prop, cx);
                            let f = self.prop_fn(c, prop.sym, false);
                            let call = Expr {
                                kind: ExprKind::Call {
                                    callee: Box::new(Expr {
                                        kind: ExprKind::Name(Ident {
                                            sym: f,
                                            span: prop.span,
                                        }),
                                        span: prop.span,
                                    }),
                                    args: vec![
                                        Arg {
                                            name: Some(Ident {
                                                sym: self.this,
                                                span,
                                            }),
                                            dir: ArgDir::In,
                                            value: Some(this),
                                            span,
                                        },
                                        Arg {
                                            name: Some(prop),
                                            dir: ArgDir::In,
                                            value: Some(v),
                                            span,
                                        },
                                    ],
                                },
                                span,
                            };
                            s.kind = StmtKind::Expr(call);
                        }
                        _ => {
                            let n = self.name(prop.sym);
                            self.err(
                                Code::E210,
                                prop.span,
                                format!("the property `{n}` has no SET"),
                            );
                            s.kind = StmtKind::Empty;
                        }
                    }
                    self.depth -= 1;
                    return;
                }
                let tt = self.type_of(target, cx);
                self.poly_write_check(target, cx);
                self.expr(target, cx);
                if let (T::Itf(i), true) = (&tt, self.is_nothing(value)) {
                    // `itf := NULL;`: no instance (every reference NULL).
                    let f = format!("__IN_{}", self.name(*i));
                    let f = self.sym(&f);
                    let vs = value.span;
                    *value = Expr {
                        kind: ExprKind::Call {
                            callee: Box::new(Expr {
                                kind: ExprKind::Name(Ident { sym: f, span: vs }),
                                span: vs,
                            }),
                            args: Vec::new(),
                        },
                        span: vs,
                    };
                    self.depth -= 1;
                    return;
                }
                self.expr(value, cx);
                match tt {
                    T::Itf(i) => self.wrap_itf(value, i, cx),
                    T::Ref(TypeSpec::Named(d)) if self.class(d.sym).is_some() => {
                        self.refuse_base_ref(value, d.sym, cx)
                    }
                    _ => {}
                }
            }
            StmtKind::Expr(e) => self.expr(e, cx),
            StmtKind::If {
                branches,
                else_body,
            } => {
                for b in branches {
                    self.expr(&mut b.cond, cx);
                    self.stmts(&mut b.body, cx);
                }
                if let Some(e) = else_body {
                    self.stmts(e, cx);
                }
            }
            StmtKind::Case {
                selector,
                arms,
                else_body,
            } => {
                self.expr(selector, cx);
                for a in arms {
                    self.stmts(&mut a.body, cx);
                }
                if let Some(e) = else_body {
                    self.stmts(e, cx);
                }
            }
            StmtKind::For {
                var,
                from,
                to,
                by,
                body,
            } => {
                if !cx.locals.contains_key(&var.sym) && cx.in_method {
                    if let Some(c) = cx.class {
                        if self.class_var(c, var.sym).is_some() {
                            self.err(
                                Code::E208,
                                var.span,
                                "a FOR loop of a method counts with a variable of the method"
                                    .into(),
                            );
                        }
                    }
                }
                self.expr(from, cx);
                self.expr(to, cx);
                if let Some(b) = by {
                    self.expr(b, cx);
                }
                self.stmts(body, cx);
            }
            StmtKind::While { cond, body } => {
                self.expr(cond, cx);
                self.stmts(body, cx);
            }
            StmtKind::Repeat { body, until } => {
                self.stmts(body, cx);
                self.expr(until, cx);
            }
            _ => {}
        }
        self.depth -= 1;
    }

    /// `x.prop` or a bare `prop` of the current class as an assignment target.
    pub(super) fn prop_target(&mut self, target: &Expr, cx: &Ctx) -> Option<(Symbol, Expr, Ident)> {
        match &target.kind {
            ExprKind::Member { base, member } => {
                if let T::Class(c) = self.type_of(base, cx) {
                    if self.class_var(c, member.sym).is_none()
                        && self.property_of(c, member.sym).is_some()
                    {
                        let mut b = (**base).clone();
                        self.expr(&mut b, cx);
                        return Some((c, b, *member));
                    }
                }
                None
            }
            ExprKind::Name(id) => {
                let c = cx.class?;
                if cx.locals.contains_key(&id.sym)
                    || self.class_var(c, id.sym).is_some()
                    || cx.result.is_some_and(|(r, _)| r == id.sym)
                {
                    return None;
                }
                self.property_of(c, id.sym)?;
                Some((c, self.this_expr(cx, id.span), *id))
            }
            _ => None,
        }
    }

    pub(super) fn this_expr(&self, cx: &Ctx, span: Span) -> Expr {
        let sym = if cx.in_method { self.this } else { self.self_ };
        Expr {
            kind: ExprKind::Name(Ident { sym, span }),
            span,
        }
    }

    /// Wraps `value` (of a class or another interface) into interface `i`.
    pub(super) fn wrap_itf(&mut self, value: &mut Expr, i: Symbol, cx: &Ctx) {
        if self.poly_class.contains_key(&i) {
            self.wrap_poly(value, i, false, cx);
            return;
        }
        let span = value.span;
        if self.is_nothing(value) {
            // `NULL` (an input `shp := NULL`): designates no instance.
            let f = format!("__IN_{}", self.name(i));
            *value = super::poly::call_expr(self.sym(&f), Vec::new(), span);
            return;
        }
        match self.type_of_rewritten(value, cx) {
            Some(T::Class(c)) => {
                if self.bad_impl.contains(&c) {
                    // Reported at the class already.
                    value.kind = ExprKind::Error;
                    return;
                }
                if !self.implements(c, i) || self.broken.contains(&c) {
                    let (cn, iname) = (self.name(c), self.name(i));
                    self.err(
                        Code::E212,
                        span,
                        format!("`{cn}` does not implement interface `{iname}`"),
                    );
                    value.kind = ExprKind::Error;
                    return;
                }
                let f = format!("__IC_{}__{}", self.name(i), self.name(c));
                let f = self.sym(&f);
                let rsym = self.sym("REF");
                let inner = std::mem::replace(
                    value,
                    Expr {
                        kind: ExprKind::Error,
                        span,
                    },
                );
                let r = Expr {
                    kind: ExprKind::Call {
                        callee: Box::new(Expr {
                            kind: ExprKind::Name(Ident { sym: rsym, span }),
                            span,
                        }),
                        args: vec![Arg {
                            name: None,
                            dir: ArgDir::In,
                            value: Some(inner),
                            span,
                        }],
                    },
                    span,
                };
                *value = Expr {
                    kind: ExprKind::Call {
                        callee: Box::new(Expr {
                            kind: ExprKind::Name(Ident { sym: f, span }),
                            span,
                        }),
                        args: vec![Arg {
                            name: None,
                            dir: ArgDir::In,
                            value: Some(r),
                            span,
                        }],
                    },
                    span,
                };
            }
            Some(T::Itf(j)) if j != i && self.itf_chain(j).contains(&i) => {
                // An interface that extends `i`: the same instance, seen as `i`.
                let f = format!("__IC_{}__{}", self.name(i), self.name(j));
                let f = self.sym(&f);
                let inner = std::mem::replace(
                    value,
                    Expr {
                        kind: ExprKind::Error,
                        span,
                    },
                );
                *value = Expr {
                    kind: ExprKind::Call {
                        callee: Box::new(Expr {
                            kind: ExprKind::Name(Ident { sym: f, span }),
                            span,
                        }),
                        args: vec![Arg {
                            name: None,
                            dir: ArgDir::In,
                            value: Some(inner),
                            span,
                        }],
                    },
                    span,
                };
            }
            Some(T::Itf(j)) if j != i => {
                let (jn, iname) = (self.name(j), self.name(i));
                self.err(
                    Code::E212,
                    span,
                    format!("a `{jn}` value cannot be assigned to an interface `{iname}` variable"),
                );
                value.kind = ExprKind::Error;
            }
            _ => {}
        }
    }

    /// The type of an expression after rewriting (`__THIS.x` is a member of the class).
    pub(super) fn type_of_rewritten(&self, e: &Expr, cx: &Ctx) -> Option<T> {
        match &e.kind {
            ExprKind::Name(id) if id.sym == self.this || id.sym == self.self_ => {
                cx.class.map(T::Class)
            }
            ExprKind::Member { base, member } if matches!(&base.kind, ExprKind::Name(b) if b.sym == self.this || b.sym == self.self_) =>
            {
                let c = cx.class?;
                Some(
                    self.class_var(c, member.sym)
                        .map_or(T::Other, |t| self.spec_t(&t)),
                )
            }
            _ => Some(self.type_of(e, cx)),
        }
    }

    /// The namespace part of a qualified name (`Motion` of `Motion.Axis`);
    /// empty for a name of the global namespace.
    fn namespace_of(&self, name: Symbol) -> String {
        let text = self.name(name);
        text.rsplit_once('.')
            .map_or(String::new(), |(ns, _)| ns.to_ascii_uppercase())
    }

    pub(super) fn check_access(
        &mut self,
        owner_seen: Symbol,
        vis: Visibility,
        name: Ident,
        cx: &Ctx,
    ) {
        // Where the member was declared.
        let owner = self
            .chain(owner_seen)
            .into_iter()
            .find(|k| {
                self.class(*k).is_some_and(|c| {
                    c.methods.iter().any(|m| m.name.sym == name.sym)
                        || c.properties.iter().any(|p| p.name.sym == name.sym)
                })
            })
            .unwrap_or(owner_seen);
        if !self.visible(owner, vis, cx) {
            let (n, o) = (self.name(name.sym), self.name(owner));
            let v = access_word(vis);
            self.err(Code::E207, name.span, format!("`{n}` is {v} in `{o}`"));
        }
    }

    /// Whether the code compiled under `cx` may use a member of class
    /// `owner` declared with access `vis`.
    pub(super) fn visible(&self, owner: Symbol, vis: Visibility, cx: &Ctx) -> bool {
        match vis {
            Visibility::Public => true,
            // Names in a namespace are qualified (`desugar_namespaces`):
            // the same namespace is the same text before the last dot.
            Visibility::Internal => {
                let site = cx.pou.or(cx.defined_in);
                site.is_some_and(|s| self.namespace_of(s) == self.namespace_of(owner))
            }
            Visibility::Private => cx.defined_in == Some(owner),
            Visibility::Protected => cx.defined_in.is_some_and(|k| self.derives_from(k, owner)),
        }
    }

    pub(super) fn expr(&mut self, e: &mut Expr, cx: &Ctx) {
        if self.depth > crate::MAX_DEPTH * 2 {
            return;
        }
        self.depth += 1;
        let before = self.diags.len();
        self.expr_inner(e, cx);
        // A misuse reported here: the checker sees an error expression
        // (no second diagnostic for the same mistake).
        if self.diags.len() > before {
            e.kind = ExprKind::Error;
        }
        self.depth -= 1;
    }

    pub(super) fn expr_inner(&mut self, e: &mut Expr, cx: &Ctx) {
        let span = e.span;
        match &mut e.kind {
            ExprKind::Name(id) => {
                let id = *id;
                // A class's variable by its name (in a body the class's
                // variables are its locals): a base's PRIVATE one is refused.
                if let Some(c) = cx.class {
                    let shadowed = cx.in_method && cx.locals.contains_key(&id.sym);
                    if !shadowed && self.var_refused(c, id, cx) {
                        return;
                    }
                }
                // A variable of that name (in a body: the POU's or class's own).
                if cx.locals.contains_key(&id.sym) {
                    return;
                }
                if let Some((m, f)) = cx.result {
                    if id.sym == m {
                        e.kind = ExprKind::Name(Ident {
                            sym: f,
                            span: id.span,
                        });
                        return;
                    }
                }
                let Some(c) = cx.class else {
                    if self.is_kw(e, "THIS", cx) || self.is_kw(e, "SUPER", cx) {
                        self.err(
                            Code::E208,
                            span,
                            "`THIS` and `SUPER` exist only in methods and in the bodies of classes"
                                .into(),
                        );
                    }
                    return;
                };
                if self.is_kw(e, "THIS", cx) || self.is_kw(e, "SUPER", cx) {
                    self.err(
                        Code::E208,
                        span,
                        "write `THIS^` (THIS is a reference to the instance)".into(),
                    );
                    return;
                }
                if !cx.in_method {
                    // A class's body sees its variables directly; a property is read by its GET.
                    if self.class_var(c, id.sym).is_none() {
                        self.read_property(e, c, self.this_expr(cx, id.span), id, cx);
                    }
                    return;
                }
                if self.class_var(c, id.sym).is_some() {
                    e.kind = ExprKind::Member {
                        base: Box::new(self.this_expr(cx, id.span)),
                        member: id,
                    };
                } else {
                    self.read_property(e, c, self.this_expr(cx, id.span), id, cx);
                }
            }
            ExprKind::Deref(b) => {
                if self.is_kw(b, "THIS", cx) {
                    if cx.class.is_none() {
                        self.err(
                            Code::E208,
                            span,
                            "`THIS` exists only in methods and in the bodies of classes".into(),
                        );
                        return;
                    }
                    *e = self.this_expr(cx, span);
                    return;
                }
                if self.is_kw(b, "SUPER", cx) {
                    self.err(
                        Code::E208,
                        span,
                        "`SUPER^` is only used to call a base method: `SUPER^.m()`".into(),
                    );
                    return;
                }
                self.expr(b, cx);
            }
            ExprKind::Member { base, member } => {
                let member = *member;
                if let Some((i, obj)) = self.poly_view(base, cx) {
                    self.poly_member(e, i, obj, member, cx);
                    return;
                }
                let bt = self.type_of(base, cx);
                if let T::Class(c) = bt {
                    if self.class_var(c, member.sym).is_none()
                        && self.property_of(c, member.sym).is_some()
                    {
                        let mut b = (**base).clone();
                        self.expr(&mut b, cx);
                        self.read_property(e, c, b, member, cx);
                        return;
                    }
                    if self.var_refused(c, member, cx) {
                        return;
                    }
                    let own = matches!(&base.kind, ExprKind::Name(b) if b.sym == self.this || b.sym == self.self_);
                    if !own && self.field_fn_needed(c, member.sym, cx) {
                        let mut b = (**base).clone();
                        self.expr(&mut b, cx);
                        self.internal_member(e, c, b, member);
                        return;
                    }
                }
                self.expr(base, cx);
            }
            ExprKind::Index { base, indices } => {
                self.expr(base, cx);
                for i in indices {
                    self.expr(i, cx);
                }
            }
            ExprKind::Unary { operand, .. } => self.expr(operand, cx),
            ExprKind::Binary { op, lhs, rhs } => {
                // `itf = NULL`, `itf <> 0`: whether an instance is assigned.
                if matches!(op, BinaryOp::Eq | BinaryOp::Ne) {
                    let (lt, rt) = (self.type_of(lhs, cx), self.type_of(rhs, cx));
                    // A value that is no place (a call's result) through
                    // `__IZ_<A>` (nulltest.rs).
                    let ne = *op == BinaryOp::Ne;
                    if let (T::Itf(a), true) = (&lt, self.is_nothing(rhs)) {
                        self.expr(lhs, cx);
                        if is_place(lhs) {
                            self.itf_id(lhs, rhs);
                        } else {
                            *e = self.itf_null_call(*a, lhs, ne, e.span);
                        }
                        return;
                    }
                    if let (T::Itf(a), true) = (&rt, self.is_nothing(lhs)) {
                        self.expr(rhs, cx);
                        if is_place(rhs) {
                            self.itf_id(rhs, lhs);
                        } else {
                            *e = self.itf_null_call(*a, rhs, ne, e.span);
                        }
                        return;
                    }
                    // `i1 = i2`: the same instance (or both none). Two places
                    // of one interface compare inline; other values (two
                    // interfaces, a call's result) through `__IE_<A>__<B>`,
                    // which evaluates each once.
                    if let (T::Itf(a), T::Itf(b)) = (&lt, &rt) {
                        let (a, b, ne) = (*a, *b, *op == BinaryOp::Ne);
                        self.expr(lhs, cx);
                        self.expr(rhs, cx);
                        *e = if a == b && is_place(lhs) && is_place(rhs) {
                            let classes = self.implementors(a);
                            self.itf_equal(&classes, lhs, rhs, ne, e.span)
                        } else {
                            self.itf_equal_call(a, b, lhs, rhs, ne, e.span)
                        };
                        return;
                    }
                }
                self.expr(lhs, cx);
                self.expr(rhs, cx);
            }
            ExprKind::Paren(i) => self.expr(i, cx),
            ExprKind::Call { .. } => self.call(e, cx),
            _ => {}
        }
    }

    pub(super) fn call(&mut self, e: &mut Expr, cx: &Ctx) {
        if self.query_interface(e, cx) {
            return;
        }
        let span = e.span;
        let ExprKind::Call { callee, args } = &mut e.kind else {
            return;
        };
        let target = match &callee.kind {
            ExprKind::Member { base, member } => {
                if let ExprKind::Deref(b) = &base.kind {
                    if self.is_kw(b, "SUPER", cx) {
                        Target2::Super(cx.defined_in.unwrap_or(id_none()), *member)
                    } else {
                        self.member_target(base, *member, cx)
                    }
                } else {
                    self.member_target(base, *member, cx)
                }
            }
            ExprKind::Name(id) => match cx.class {
                Some(c)
                    if !cx.locals.contains_key(&id.sym)
                        && self.class_var(c, id.sym).is_none()
                        && self.method_of(c, id.sym).is_some() =>
                {
                    Target2::Method(c, self.this_expr(cx, id.span), *id)
                }
                _ => Target2::Plain,
            },
            _ => Target2::Plain,
        };
        // Arguments first (they may hold method calls too).
        for a in args.iter_mut() {
            if let Some(v) = &mut a.value {
                self.expr(v, cx);
            }
        }
        let (fname, this, params): (Symbol, Option<Expr>, Vec<Param>) = match target {
            Target2::Plain => {
                if let ExprKind::Member { base, .. } = &mut callee.kind {
                    self.expr(base, cx);
                }
                if let ExprKind::Name(id) = &callee.kind {
                    if let Some(ps) = self.pou_params.get(&id.sym).cloned() {
                        self.convert_args(args, &ps, cx);
                    } else if let Some(TypeSpec::Named(fb)) = cx
                        .locals
                        .get(&id.sym)
                        .cloned()
                        .or_else(|| cx.class.and_then(|c| self.class_var(c, id.sym)))
                    {
                        // An instance call of an FB-typed variable (a plain
                        // function block, or one with methods: its inputs
                        // with its bases').
                        if let Some(ps) = self.pou_params.get(&fb.sym).cloned() {
                            self.convert_args(args, &ps, cx);
                        } else if self.class(fb.sym).is_some() {
                            let ps = self.class_inputs(fb.sym);
                            self.convert_args(args, &ps, cx);
                        }
                    }
                    if cx.in_method
                        && cx
                            .class
                            .is_some_and(|c| self.class_var(c, id.sym).is_some())
                        && !cx.locals.contains_key(&id.sym)
                    {
                        let id = *id;
                        callee.kind = ExprKind::Member {
                            base: Box::new(self.this_expr(cx, id.span)),
                            member: id,
                        };
                    }
                }
                return;
            }
            Target2::Method(c, mut this, m) => {
                let Some((_, meth)) = self.method_of(c, m.sym) else {
                    let (n, cn) = (self.name(m.sym), self.name(c));
                    self.err(Code::E206, m.span, format!("`{cn}` has no method `{n}`"));
                    return;
                };
                self.check_access(c, meth.visibility, m, cx);
                if meth.is_abstract {
                    let (n, cn) = (self.name(m.sym), self.name(c));
                    self.err(
                        Code::E204,
                        m.span,
                        format!("`{n}` is ABSTRACT in `{cn}`: it has no implementation to call"),
                    );
                    return;
                }
                self.expr(&mut this, cx);
                (self.method_fn(c, m.sym), Some(this), params_of(meth))
            }
            Target2::Super(k, m) => {
                let base = self
                    .class(k)
                    .and_then(|c| c.extends)
                    .map(|b| b.sym)
                    .filter(|b| self.class(*b).is_some());
                let (Some(base), Some(c)) = (base, cx.class) else {
                    self.err(
                        Code::E208,
                        span,
                        "`SUPER` is only usable in a class that EXTENDS another".into(),
                    );
                    return;
                };
                match self.method_of(base, m.sym) {
                    Some((_, meth)) if !meth.is_abstract => {
                        self.check_access(base, meth.visibility, m, cx);
                        self.supers.push((c, base, m.sym));
                        (
                            self.super_fn(c, base, m.sym),
                            Some(self.this_expr(cx, m.span)),
                            params_of(meth),
                        )
                    }
                    Some(_) => {
                        let n = self.name(m.sym);
                        self.err(
                            Code::E204,
                            m.span,
                            format!(
                                "`{n}` is ABSTRACT in the base: SUPER^.{n}() has nothing to call"
                            ),
                        );
                        return;
                    }
                    None => {
                        let (n, bn) = (self.name(m.sym), self.name(base));
                        self.err(Code::E206, m.span, format!("`{bn}` has no method `{n}`"));
                        return;
                    }
                }
            }
            Target2::Itf(i, mut obj, m) => {
                let base = self.poly_class.get(&i).copied();
                let Some(meth) = self.itf_method(i, m.sym) else {
                    let (n, iname) = (self.name(m.sym), self.name(i));
                    let msg = match base {
                        Some(b) => format!("`{}` has no method `{n}`", self.name(b)),
                        None => format!("interface `{iname}` has no method `{n}`"),
                    };
                    self.err(Code::E206, m.span, msg);
                    return;
                };
                if let Some(b) = base {
                    self.check_access(b, meth.visibility, m, cx);
                }
                self.expr(&mut obj, cx);
                let f = format!("__ID_{}__{}", self.name(i), self.name(m.sym));
                let osym = self.sym("__o");
                let params = params_of(meth);
                self.convert_args(args, &params, cx);
                let positional = args.first().is_some_and(|a| a.name.is_none());
                args.insert(
                    0,
                    Arg {
                        name: (!positional).then_some(Ident { sym: osym, span }),
                        dir: ArgDir::In,
                        value: Some(obj),
                        span,
                    },
                );
                let f = self.sym(&f);
                **callee = Expr {
                    kind: ExprKind::Name(Ident {
                        sym: f,
                        span: callee.span,
                    }),
                    span: callee.span,
                };
                return;
            }
        };
        self.convert_args(args, &params, cx);
        if let Some(this) = this {
            let positional = args.first().is_some_and(|a| a.name.is_none());
            args.insert(
                0,
                Arg {
                    name: (!positional).then_some(Ident {
                        sym: self.this,
                        span,
                    }),
                    dir: ArgDir::In,
                    value: Some(this),
                    span,
                },
            );
        }
        let cs = callee.span;
        **callee = Expr {
            kind: ExprKind::Name(Ident {
                sym: fname,
                span: cs,
            }),
            span: cs,
        };
    }

    pub(super) fn member_target(&mut self, base: &Expr, member: Ident, cx: &Ctx) -> Target2 {
        if let Some((i, obj)) = self.poly_view(base, cx) {
            return Target2::Itf(i, obj, member);
        }
        match self.type_of(base, cx) {
            T::Class(c) => {
                if self.class_var(c, member.sym).is_some() {
                    return Target2::Plain;
                }
                Target2::Method(c, base.clone(), member)
            }
            T::Itf(i) if self.poly_class.contains_key(&i) => {
                // `r.m()` for `r : REF_TO B`: the reference is not the instance.
                let n = self.name(member.sym);
                self.err(
                    Code::E206,
                    member.span,
                    format!("a reference has no method `{n}`: dereference it (`r^.{n}()`)"),
                );
                Target2::Plain
            }
            T::Itf(i) => Target2::Itf(i, base.clone(), member),
            _ => Target2::Plain,
        }
    }

    /// Named inputs whose parameter is an interface take class instances.
    pub(super) fn convert_args(&mut self, args: &mut [Arg], params: &[Param], cx: &Ctx) {
        for (k, a) in args.iter_mut().enumerate() {
            let ty = match &a.name {
                Some(n) => params
                    .iter()
                    .find(|(p, _, _)| *p == n.sym)
                    .map(|(_, t, io)| (t.clone(), *io)),
                None => params.get(k).map(|(_, t, io)| (t.clone(), *io)),
            };
            let (Some((ty, inout)), Some(v), ArgDir::In) = (ty, &mut a.value, a.dir) else {
                continue;
            };
            match (&ty, inout) {
                // A VAR_IN_OUT of a base class: an instance of it or of a derived one.
                (TypeSpec::Named(t), true) => {
                    if let Some(i) = self.poly.get(&t.sym).copied() {
                        self.wrap_poly(v, i, true, cx);
                    }
                }
                (TypeSpec::Named(t), false) if self.itfs.contains_key(&t.sym) => {
                    self.wrap_itf(v, t.sym, cx);
                }
                (TypeSpec::Ref { target, .. }, false) => match &**target {
                    TypeSpec::Named(t) if self.poly.contains_key(&t.sym) => {
                        let i = self.poly.get(&t.sym).copied().unwrap_or(t.sym);
                        self.wrap_poly(v, i, false, cx);
                    }
                    TypeSpec::Named(t) if self.class(t.sym).is_some() => {
                        self.refuse_base_ref(v, t.sym, cx);
                    }
                    _ => {}
                },
                _ => {}
            }
        }
    }
}

/// A variable, a member or an element (evaluated twice without effect).
pub(super) fn is_place(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Name(_) => true,
        ExprKind::Paren(i) => is_place(i),
        ExprKind::Member { base, .. } => is_place(base),
        ExprKind::Index { base, indices } => {
            is_place(base)
                && indices
                    .iter()
                    .all(|i| is_place(i) || matches!(i.kind, ExprKind::Literal(_)))
        }
        _ => false,
    }
}
