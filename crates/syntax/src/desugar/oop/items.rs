//! The generated items: a class as a FUNCTION_BLOCK, its methods and properties as functions, an interface as a structure with its dispatch and conversion functions.

use super::*;

impl<'a> Oop<'a> {
    pub(super) fn class_items(&mut self, c: Symbol) -> Vec<Item> {
        let mut out = Vec::new();
        if self.broken.contains(&c) {
            return out;
        }
        let Some(cl) = self.class(c) else { return out };
        let chain = self.chain(c);
        // Variables: outermost base first.
        let mut var_blocks = Vec::new();
        for k in chain.iter().rev() {
            if let Some(kc) = self.class(*k) {
                var_blocks.extend(kc.var_blocks.iter().cloned());
            }
        }
        let byref = self.split_poly_inouts(&mut var_blocks);
        let written = Ctx {
            class: Some(c),
            defined_in: Some(c),
            in_method: false,
            locals: Self::locals_of(&var_blocks),
            result: None,
            pou: None,
            byref: HashSet::new(),
        };
        self.itf_inits(&mut var_blocks, &written);
        for b in &mut var_blocks {
            self.retype_block(b);
        }
        let members = Self::locals_of(&var_blocks);
        // Body: own, or the nearest base's.
        let (src_class, mut body) = chain
            .iter()
            .filter_map(|k| self.class(*k).map(|x| (*k, x)))
            .find(|(_, x)| !x.body.is_empty())
            .map_or((c, Vec::new()), |(k, x)| (k, x.body.clone()));
        let cx = Ctx {
            class: Some(c),
            defined_in: Some(src_class),
            in_method: false,
            locals: members.clone(),
            result: None,
            pou: None,
            byref,
        };
        self.stmts(&mut body, &cx);
        out.push(Item::Pou(Pou {
            kind: PouKind::FunctionBlock,
            name: cl.name,
            return_type: None,
            var_blocks,
            body: Body::St(body),
            lang: Lang::St,
            span: cl.span,
        }));
        // Methods, own and inherited.
        let mut done = HashSet::new();
        for (m, k, meth) in self.all_methods(c) {
            if meth.is_abstract {
                continue;
            }
            let fname = self.method_fn(c, m);
            done.insert((c, k, m));
            out.push(self.method_fn_item(c, k, meth, fname));
            let _ = m;
        }
        for p in self.collect_props(c) {
            out.extend(p);
        }
        // SUPER^.m() copies, as the bodies above asked for them.
        let mut i = 0;
        while let Some(&(cc, base, m)) = self.supers.get(i) {
            i += 1;
            if cc != c || !done.insert((cc, base, m)) {
                continue;
            }
            if let Some((k, meth)) = self.method_of(base, m) {
                if meth.is_abstract {
                    continue;
                }
                let fname = self.super_fn(c, base, m);
                out.push(self.method_fn_item(c, k, meth, fname));
            }
        }
        out
    }

    pub(super) fn collect_props(&mut self, c: Symbol) -> Vec<Vec<Item>> {
        let mut out = Vec::new();
        let mut seen = HashSet::new();
        for k in self.chain(c) {
            let Some(cl) = self.class(k) else { continue };
            for p in &cl.properties {
                if !seen.insert(p.name.sym) {
                    continue;
                }
                let mut items = Vec::new();
                if let Some(g) = &p.get {
                    let fname = self.prop_fn(c, p.name.sym, true);
                    let m = Method {
                        name: p.name,
                        visibility: p.visibility,
                        visibility_span: None,
                        is_abstract: false,
                        is_final: false,
                        is_override: false,
                        return_type: Some(p.ty.clone()),
                        var_blocks: g.var_blocks.clone(),
                        body: g.body.clone(),
                        usings: Vec::new(),
                        span: g.span,
                    };
                    items.push(self.method_fn_item(c, k, &m, fname));
                }
                if let Some(s) = &p.set {
                    let fname = self.prop_fn(c, p.name.sym, false);
                    let mut blocks = vec![VarBlock {
                        kind: VarKind::Input,
                        constant: false,
                        retain: Default::default(),
                        decls: vec![VarDecl {
                            names: vec![p.name],
                            location: None,
                            ty: p.ty.clone(),
                            edge: None,
                            init: None,
                            span: p.name.span,
                        }],
                        span: s.span,
                    }];
                    blocks.extend(s.var_blocks.iter().cloned());
                    let m = Method {
                        name: p.name,
                        visibility: p.visibility,
                        visibility_span: None,
                        is_abstract: false,
                        is_final: false,
                        is_override: false,
                        return_type: None,
                        var_blocks: blocks,
                        body: s.body.clone(),
                        usings: Vec::new(),
                        span: s.span,
                    };
                    let mut item = self.method_fn_item(c, k, &m, fname);
                    // In a SET the name is the input, not a result.
                    if let Item::Pou(pou) = &mut item {
                        pou.return_type = None;
                    }
                    items.push(item);
                }
                out.push(items);
            }
        }
        out
    }

    pub(super) fn method_fn(&mut self, c: Symbol, m: Symbol) -> Symbol {
        let n = format!("__M_{}__{}", self.name(c), self.name(m));
        self.sym(&n)
    }

    pub(super) fn super_fn(&mut self, c: Symbol, base: Symbol, m: Symbol) -> Symbol {
        let n = format!(
            "__MS_{}__{}__{}",
            self.name(c),
            self.name(base),
            self.name(m)
        );
        self.sym(&n)
    }

    pub(super) fn prop_fn(&mut self, c: Symbol, p: Symbol, get: bool) -> Symbol {
        let n = format!(
            "__P{}_{}__{}",
            if get { 'G' } else { 'S' },
            self.name(c),
            self.name(p)
        );
        self.sym(&n)
    }

    /// The FUNCTION for method `meth` (written in class `k`) compiled for class `c`.
    pub(super) fn method_fn_item(
        &mut self,
        c: Symbol,
        k: Symbol,
        meth: &Method,
        fname: Symbol,
    ) -> Item {
        let span = meth.span;
        let this_block = VarBlock {
            kind: VarKind::InOut,
            constant: false,
            retain: Default::default(),
            decls: vec![VarDecl {
                names: vec![Ident {
                    sym: self.this,
                    span: meth.name.span,
                }],
                location: None,
                ty: TypeSpec::Named(Ident {
                    sym: c,
                    span: meth.name.span,
                }),
                edge: None,
                init: None,
                span: meth.name.span,
            }],
            span: meth.name.span,
        };
        let mut var_blocks = vec![this_block];
        let mut own_blocks = meth.var_blocks.clone();
        let mut byref = self.split_poly_inouts(&mut own_blocks);
        // The class's VAR_IN_OUT of a base class, reached through `__THIS`.
        let own_names = Self::locals_of(&own_blocks);
        for kc in self.chain(c) {
            for b in self.class(kc).map_or(&[][..], |x| &x.var_blocks[..]) {
                if b.kind != VarKind::InOut {
                    continue;
                }
                for d in &b.decls {
                    if matches!(&d.ty, TypeSpec::Named(t) if self.poly.contains_key(&t.sym)) {
                        byref.extend(
                            d.names
                                .iter()
                                .map(|n| n.sym)
                                .filter(|n| !own_names.contains_key(n)),
                        );
                    }
                }
            }
        }
        var_blocks.extend(own_blocks.iter().cloned());
        // The class's VAR_EXTERNAL are the method's too (globals by name).
        let mut externals = Vec::new();
        for kc in self.chain(c) {
            if let Some(x) = self.class(kc) {
                externals.extend(
                    x.var_blocks
                        .iter()
                        .filter(|b| b.kind == VarKind::External)
                        .cloned(),
                );
            }
        }
        let mut locals = Self::locals_of(&own_blocks);
        for (n, t) in Self::locals_of(&externals) {
            locals.entry(n).or_insert(t);
        }
        let own = Self::locals_of(&own_blocks);
        for b in &mut externals {
            b.decls
                .retain(|d| d.names.iter().all(|n| !own.contains_key(&n.sym)));
        }
        externals.retain(|b| !b.decls.is_empty());
        var_blocks.extend(externals);
        for b in var_blocks.iter_mut().skip(1) {
            self.retype_block(b);
        }
        // The result, assigned by the method's name, has its type there
        // (`Make := sq;` for an interface result designates `sq`;
        // `type_of` looks it up through `cx.result`).
        if let Some(r) = &meth.return_type {
            self.returns.insert(fname, r.clone());
        }
        let cx = Ctx {
            class: Some(c),
            defined_in: Some(k),
            in_method: true,
            locals,
            result: meth.return_type.as_ref().map(|_| (meth.name.sym, fname)),
            pou: None,
            byref,
        };
        let mut body = meth.body.clone();
        self.stmts(&mut body, &cx);
        let mut ret = meth.return_type.clone();
        if let Some(r) = &mut ret {
            self.retype_spec(r, VarKind::Output);
        }
        Item::Pou(Pou {
            kind: PouKind::Function,
            name: Ident {
                sym: fname,
                span: meth.name.span,
            },
            return_type: ret,
            var_blocks,
            body: Body::St(body),
            lang: Lang::St,
            span,
        })
    }

    pub(super) fn interface_items(&mut self, i: Symbol) -> Vec<Item> {
        let mut out = Vec::new();
        let Some(it) = self.itf(i) else { return out };
        let span = it.name.span;
        let impls = self.implementors(i);
        let id_sym = self.sym("__id");
        let uint = self.sym("UINT");
        let mut members = vec![VarDecl {
            names: vec![Ident { sym: id_sym, span }],
            location: None,
            ty: TypeSpec::Named(Ident { sym: uint, span }),
            edge: None,
            init: None,
            span,
        }];
        let mut fields = Vec::new();
        for c in &impls {
            let f = format!("__r{}", self.ids.get(c).copied().unwrap_or(0));
            let f = self.sym(&f);
            fields.push((*c, f));
            members.push(VarDecl {
                names: vec![Ident { sym: f, span }],
                location: None,
                ty: TypeSpec::Ref {
                    target: Box::new(TypeSpec::Named(Ident { sym: *c, span })),
                    span,
                    reference: false,
                },
                edge: None,
                init: None,
                span,
            });
        }
        let sname = format!("__ITF_{}", self.name(i));
        let ssym = self.sym(&sname);
        out.push(Item::Types(TypeBlock {
            decls: vec![TypeDecl {
                name: Ident { sym: ssym, span },
                spec: TypeSpec::Struct { members, span },
                init: None,
                span,
            }],
            span,
        }));
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
        let int_e = |v: i128| Expr {
            kind: ExprKind::Literal(Box::new(Literal {
                kind: LitKind::Int(v),
                ty: None,
            })),
            span,
        };
        let assign = |t: Expr, v: Expr| Stmt {
            kind: StmtKind::Assign {
                target: t,
                value: v,
            },
            span,
        };
        // The value without an instance.
        let nname = format!("__IN_{}", self.name(i));
        let nsym = self.sym(&nname);
        out.push(Item::Pou(Pou {
            kind: PouKind::Function,
            name: id(nsym),
            return_type: Some(TypeSpec::Named(id(ssym))),
            var_blocks: Vec::new(),
            body: Body::St(Vec::new()),
            lang: Lang::St,
            span,
        }));
        // Conversions from each class.
        let rsym = self.sym("__r");
        for (c, f) in &fields {
            let cname = format!("__IC_{}__{}", self.name(i), self.name(*c));
            let csym = self.sym(&cname);
            let body = vec![
                assign(
                    member_e(name_e(csym), id_sym),
                    int_e(i128::from(self.ids.get(c).copied().unwrap_or(0))),
                ),
                assign(member_e(name_e(csym), *f), name_e(rsym)),
            ];
            out.push(Item::Pou(Pou {
                kind: PouKind::Function,
                name: id(csym),
                return_type: Some(TypeSpec::Named(id(ssym))),
                var_blocks: vec![VarBlock {
                    kind: VarKind::Input,
                    constant: false,
                    retain: Default::default(),
                    decls: vec![VarDecl {
                        names: vec![id(rsym)],
                        location: None,
                        ty: TypeSpec::Ref {
                            target: Box::new(TypeSpec::Named(id(*c))),
                            span,
                            reference: false,
                        },
                        edge: None,
                        init: None,
                        span,
                    }],
                    span,
                }],
                body: Body::St(body),
                lang: Lang::St,
                span,
            }));
        }
        // Conversions from each interface that extends this one: every class
        // implementing it implements this one too.
        let mut subs: Vec<Symbol> = self
            .itfs
            .keys()
            .copied()
            .filter(|j| *j != i && self.itf_chain(*j).contains(&i))
            .collect();
        subs.sort_by_key(|j| self.itf(*j).map(|x| x.span.start));
        for j in subs {
            let cname = format!("__IC_{}__{}", self.name(i), self.name(j));
            let csym = self.sym(&cname);
            let jname = format!("__ITF_{}", self.name(j));
            let jsym = self.sym(&jname);
            let osym = self.sym("__o");
            let mut body = vec![assign(
                member_e(name_e(csym), id_sym),
                member_e(name_e(osym), id_sym),
            )];
            for c in self.implementors(j) {
                if let Some((_, f)) = fields.iter().find(|(k, _)| *k == c) {
                    body.push(assign(
                        member_e(name_e(csym), *f),
                        member_e(name_e(osym), *f),
                    ));
                }
            }
            out.push(Item::Pou(Pou {
                kind: PouKind::Function,
                name: id(csym),
                return_type: Some(TypeSpec::Named(id(ssym))),
                var_blocks: vec![VarBlock {
                    kind: VarKind::Input,
                    constant: false,
                    retain: Default::default(),
                    decls: vec![VarDecl {
                        names: vec![id(osym)],
                        location: None,
                        ty: TypeSpec::Named(id(jsym)),
                        edge: None,
                        init: None,
                        span,
                    }],
                    span,
                }],
                body: Body::St(body),
                lang: Lang::St,
                span,
            }));
        }
        // Dispatchers.
        let osym = self.sym("__o");
        let mut methods: Vec<&Method> = Vec::new();
        for k in self.itf_chain(i) {
            if let Some(x) = self.itf(k) {
                for m in &x.methods {
                    if !methods.iter().any(|y| y.name.sym == m.name.sym) {
                        methods.push(m);
                    }
                }
            }
        }
        for m in methods {
            let dname = format!("__ID_{}__{}", self.name(i), self.name(m.name.sym));
            let dsym = self.sym(&dname);
            let this_sym = self.this;
            let args_for = |this: Expr| {
                let mut args = vec![Arg {
                    name: Some(id(this_sym)),
                    dir: ArgDir::In,
                    value: Some(this),
                    span,
                }];
                for b in &m.var_blocks {
                    for decl in &b.decls {
                        for n in &decl.names {
                            let dir = if b.kind == VarKind::Output {
                                ArgDir::Out
                            } else {
                                ArgDir::In
                            };
                            if matches!(b.kind, VarKind::Input | VarKind::Output | VarKind::InOut) {
                                args.push(Arg {
                                    name: Some(id(n.sym)),
                                    dir,
                                    value: Some(name_e(n.sym)),
                                    span,
                                });
                            }
                        }
                    }
                }
                args
            };
            let mut arms = Vec::new();
            for (c, f) in &fields {
                let target = self.method_fn(*c, m.name.sym);
                let this = Expr {
                    kind: ExprKind::Deref(Box::new(member_e(name_e(osym), *f))),
                    span,
                };
                let call = Expr {
                    kind: ExprKind::Call {
                        callee: Box::new(name_e(target)),
                        args: args_for(this),
                    },
                    span,
                };
                let stmt = if m.return_type.is_some() {
                    assign(name_e(dsym), call)
                } else {
                    Stmt {
                        kind: StmtKind::Expr(call),
                        span,
                    }
                };
                arms.push((
                    i128::from(self.ids.get(c).copied().unwrap_or(0)),
                    vec![stmt],
                ));
            }
            // No instance: the first class's reference is NULL, and
            // dereferencing it is the runtime's fault.
            let body: Vec<Stmt> =
                super::poly::dispatch_case(member_e(name_e(osym), id_sym), arms, true, span)
                    .into_iter()
                    .collect();
            let mut var_blocks = vec![VarBlock {
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
            }];
            let mut params: Vec<VarBlock> = m
                .var_blocks
                .iter()
                .filter(|b| b.kind != VarKind::Local && b.kind != VarKind::Temp)
                .cloned()
                .collect();
            self.split_poly_inouts(&mut params);
            var_blocks.extend(params);
            for b in var_blocks.iter_mut().skip(1) {
                self.retype_block(b);
            }
            out.push(Item::Pou(Pou {
                kind: PouKind::Function,
                name: id(dsym),
                return_type: m.return_type.clone(),
                var_blocks,
                body: Body::St(body),
                lang: Lang::St,
                span,
            }));
        }
        out
    }

    /// `FUNCTION __IE_<A>__<B> : BOOL` over `__a : __ITF_A` and
    /// `__b : __ITF_B`: whether they designate the same instance (or none).
    pub(super) fn itf_equal_fn(&mut self, a: Symbol, b: Symbol) -> Item {
        let span = self.itf(a).map_or(Span::default(), |i| i.name.span);
        let id = |s: Symbol| Ident { sym: s, span };
        let name_e = |s: Symbol| Expr {
            kind: ExprKind::Name(Ident { sym: s, span }),
            span,
        };
        let in_b = self.implementors(b);
        let common: Vec<Symbol> = self
            .implementors(a)
            .into_iter()
            .filter(|c| in_b.contains(c))
            .collect();
        let (asym, bsym) = (self.sym("__a"), self.sym("__b"));
        let value = self.itf_equal(&common, &name_e(asym), &name_e(bsym), false, span);
        let fname = format!("__IE_{}__{}", self.name(a), self.name(b));
        let fsym = self.sym(&fname);
        let sa = format!("__ITF_{}", self.name(a));
        let sb = format!("__ITF_{}", self.name(b));
        let (sa, sb) = (self.sym(&sa), self.sym(&sb));
        let input = |n: Symbol, t: Symbol| VarDecl {
            names: vec![id(n)],
            location: None,
            ty: TypeSpec::Named(id(t)),
            edge: None,
            init: None,
            span,
        };
        let bool_sym = self.sym("BOOL");
        Item::Pou(Pou {
            kind: PouKind::Function,
            name: id(fsym),
            return_type: Some(TypeSpec::Named(id(bool_sym))),
            var_blocks: vec![VarBlock {
                kind: VarKind::Input,
                constant: false,
                retain: Default::default(),
                decls: vec![input(asym, sa), input(bsym, sb)],
                span,
            }],
            body: Body::St(vec![Stmt {
                kind: StmtKind::Assign {
                    target: name_e(fsym),
                    value,
                },
                span,
            }]),
            lang: Lang::St,
            span,
        })
    }

    /// `FUNCTION __IQ_<A>__<B> : BOOL` (CODESYS `__QUERYINTERFACE`) over
    /// `__a : __ITF_A` and `VAR_IN_OUT __b : __ITF_B`: `__b` designates
    /// `__a`'s instance when its class implements B (TRUE), else none.
    pub(super) fn itf_query_fn(&mut self, a: Symbol, b: Symbol) -> Item {
        let span = self.itf(a).map_or(Span::default(), |i| i.name.span);
        let id = |s: Symbol| Ident { sym: s, span };
        let name_e = |s: Symbol| Expr {
            kind: ExprKind::Name(Ident { sym: s, span }),
            span,
        };
        let member_e = |base: Expr, m: Symbol| Expr {
            kind: ExprKind::Member {
                base: Box::new(base),
                member: id(m),
            },
            span,
        };
        let int_e = |v: i128| Expr {
            kind: ExprKind::Literal(Box::new(Literal {
                kind: LitKind::Int(v),
                ty: None,
            })),
            span,
        };
        let assign = |t: Expr, v: Expr| Stmt {
            kind: StmtKind::Assign {
                target: t,
                value: v,
            },
            span,
        };
        let in_b = self.implementors(b);
        let common: Vec<Symbol> = self
            .implementors(a)
            .into_iter()
            .filter(|c| in_b.contains(c))
            .collect();
        let (asym, bsym, id_sym) = (self.sym("__a"), self.sym("__b"), self.sym("__id"));
        let fname = format!("__IQ_{}__{}", self.name(a), self.name(b));
        let fsym = self.sym(&fname);
        let none = format!("__IN_{}", self.name(b));
        let none = self.sym(&none);
        let mut body = vec![assign(
            name_e(bsym),
            Expr {
                kind: ExprKind::Call {
                    callee: Box::new(name_e(none)),
                    args: Vec::new(),
                },
                span,
            },
        )];
        let mut arms = Vec::new();
        for c in &common {
            let n = self.ids.get(c).copied().unwrap_or(0);
            let field = format!("__r{n}");
            let field = self.sym(&field);
            let true_e = Expr {
                kind: ExprKind::Literal(Box::new(Literal {
                    kind: LitKind::Bool(true),
                    ty: None,
                })),
                span,
            };
            arms.push((
                i128::from(n),
                vec![
                    assign(member_e(name_e(bsym), id_sym), int_e(i128::from(n))),
                    assign(member_e(name_e(bsym), field), member_e(name_e(asym), field)),
                    assign(name_e(fsym), true_e),
                ],
            ));
        }
        body.extend(super::poly::dispatch_case(
            member_e(name_e(asym), id_sym),
            arms,
            false,
            span,
        ));
        let sa = format!("__ITF_{}", self.name(a));
        let sb = format!("__ITF_{}", self.name(b));
        let (sa, sb) = (self.sym(&sa), self.sym(&sb));
        let block = |kind: VarKind, n: Symbol, t: Symbol| VarBlock {
            kind,
            constant: false,
            retain: Default::default(),
            decls: vec![VarDecl {
                names: vec![id(n)],
                location: None,
                ty: TypeSpec::Named(id(t)),
                edge: None,
                init: None,
                span,
            }],
            span,
        };
        let bool_sym = self.sym("BOOL");
        Item::Pou(Pou {
            kind: PouKind::Function,
            name: id(fsym),
            return_type: Some(TypeSpec::Named(id(bool_sym))),
            var_blocks: vec![
                block(VarKind::Input, asym, sa),
                block(VarKind::InOut, bsym, sb),
            ],
            body: Body::St(body),
            lang: Lang::St,
            span,
        })
    }

    /// `FUNCTION <f> : BOOL` (CODESYS `__QUERYPOINTER`) over
    /// `__a : __ITF_A` and `VAR_IN_OUT __p : POINTER TO <target>`: `__p` is
    /// the address of `__a`'s instance (TRUE), or NULL without one (FALSE).
    /// The instance's reference converts to the pointer as CODESYS
    /// pointers do (`--lib codesys`).
    pub(super) fn itf_pointer_fn(&mut self, a: Symbol, target: TypeSpec, fsym: Symbol) -> Item {
        let span = self.itf(a).map_or(Span::default(), |i| i.name.span);
        let id = |s: Symbol| Ident { sym: s, span };
        let name_e = |s: Symbol| Expr {
            kind: ExprKind::Name(Ident { sym: s, span }),
            span,
        };
        let member_e = |base: Expr, m: Symbol| Expr {
            kind: ExprKind::Member {
                base: Box::new(base),
                member: id(m),
            },
            span,
        };
        let assign = |t: Expr, v: Expr| Stmt {
            kind: StmtKind::Assign {
                target: t,
                value: v,
            },
            span,
        };
        let (asym, psym, id_sym) = (self.sym("__a"), self.sym("__p"), self.sym("__id"));
        let null = self.sym("NULL");
        let mut body = vec![assign(name_e(psym), name_e(null))];
        let mut arms = Vec::new();
        for c in self.implementors(a) {
            let n = self.ids.get(&c).copied().unwrap_or(0);
            let field = format!("__r{n}");
            let field = self.sym(&field);
            arms.push((
                i128::from(n),
                vec![
                    assign(name_e(psym), member_e(name_e(asym), field)),
                    assign(
                        name_e(fsym),
                        Expr {
                            kind: ExprKind::Literal(Box::new(Literal {
                                kind: LitKind::Bool(true),
                                ty: None,
                            })),
                            span,
                        },
                    ),
                ],
            ));
        }
        body.extend(super::poly::dispatch_case(
            member_e(name_e(asym), id_sym),
            arms,
            false,
            span,
        ));
        let sa = format!("__ITF_{}", self.name(a));
        let sa = self.sym(&sa);
        let decl = |n: Symbol, ty: TypeSpec| VarDecl {
            names: vec![id(n)],
            location: None,
            ty,
            edge: None,
            init: None,
            span,
        };
        let block = |kind: VarKind, d: VarDecl| VarBlock {
            kind,
            constant: false,
            retain: Default::default(),
            decls: vec![d],
            span,
        };
        let mut pointer = TypeSpec::Ref {
            target: Box::new(target),
            span,
            reference: false,
        };
        self.retype_spec(&mut pointer, VarKind::InOut);
        let bool_sym = self.sym("BOOL");
        Item::Pou(Pou {
            kind: PouKind::Function,
            name: id(fsym),
            return_type: Some(TypeSpec::Named(id(bool_sym))),
            var_blocks: vec![
                block(VarKind::Input, decl(asym, TypeSpec::Named(id(sa)))),
                block(VarKind::InOut, decl(psym, pointer)),
            ],
            body: Body::St(body),
            lang: Lang::St,
            span,
        })
    }
}
