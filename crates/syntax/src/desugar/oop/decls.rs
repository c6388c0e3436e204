//! Declarations: class and interface types in variable declarations, and the POU rewrite entry.

use super::*;
use crate::ast::{FieldInit, Initializer};

/// What an interface's initial value becomes.
enum ItfInit {
    /// Left as written (not an instance: the checker reports it).
    AsWritten,
    /// No instance: the structure's default (NULL, or an error reported).
    Nothing,
    Value(Initializer),
}

impl<'a> Oop<'a> {
    pub(super) fn retype_block(&mut self, b: &mut VarBlock) {
        let kind = b.kind;
        for decl in &mut b.decls {
            self.retype_decl(decl, kind);
        }
    }

    /// Interface types become their structures; an instance of an abstract
    /// class is refused.
    pub(super) fn retype_decl(&mut self, decl: &mut VarDecl, kind: VarKind) {
        if self.nothing_init(&decl.ty, decl.init.as_ref()) {
            decl.init = None;
        }
        self.retype_spec(&mut decl.ty, kind);
    }

    /// `NULL` as the initial value of an interface (a structure member
    /// `a : IShape := NULL;`), or `[NULL, NULL]` of an array of them: no
    /// instance, the structure's default (the declaration drops it).
    fn nothing_init(&self, ty: &TypeSpec, init: Option<&Initializer>) -> bool {
        match (ty, init) {
            (_, Some(Initializer::Expr(e))) => self.itf_decl(ty).is_some() && self.is_nothing(e),
            (TypeSpec::Array { elem, .. }, Some(Initializer::Array { elems, .. })) => {
                elems.iter().all(|el| {
                    el.value
                        .as_ref()
                        .is_some_and(|v| self.nothing_init(elem, Some(v)))
                })
            }
            _ => false,
        }
    }

    pub(super) fn retype_spec(&mut self, ty: &mut TypeSpec, kind: VarKind) {
        match ty {
            TypeSpec::Named(id) => {
                if self.itfs.contains_key(&id.sym) {
                    let n = format!("__ITF_{}", self.name(id.sym));
                    id.sym = self.sym(&n);
                } else if let Some(c) = self.class(id.sym) {
                    if c.is_abstract && kind != VarKind::InOut {
                        let n = self.name(id.sym);
                        self.err(
                            Code::E204,
                            id.span,
                            format!("`{n}` is ABSTRACT and cannot be instantiated"),
                        );
                    }
                }
            }
            TypeSpec::Array { elem, .. } => self.retype_spec(elem, kind),
            TypeSpec::Struct { members, .. } => {
                for m in members {
                    self.retype_spec(&mut m.ty, kind);
                }
            }
            // A reference to a base class may designate an instance of a
            // derived class: the base's `<B>^` interface.
            TypeSpec::Ref { target, .. } => {
                if let TypeSpec::Named(id) = &**target {
                    if let Some(i) = self.poly.get(&id.sym) {
                        let n = format!("__ITF_{}", self.name(*i));
                        let id = Ident {
                            sym: self.sym(&n),
                            span: id.span,
                        };
                        *ty = TypeSpec::Named(id);
                    }
                }
            }
            _ => {}
        }
    }

    /// A `VAR_IN_OUT x : B` of a base class becomes the input `x : REF_TO B`
    /// (then `<B>^`), in the same place among the parameters; returns
    /// those names (written as instances in the body).
    pub(super) fn split_poly_inouts(&self, blocks: &mut Vec<VarBlock>) -> HashSet<Symbol> {
        let mut names = HashSet::new();
        let is_poly =
            |d: &VarDecl| matches!(&d.ty, TypeSpec::Named(id) if self.poly.contains_key(&id.sym));
        if !blocks
            .iter()
            .any(|b| b.kind == VarKind::InOut && b.decls.iter().any(is_poly))
        {
            return names;
        }
        let mut out = Vec::new();
        for b in std::mem::take(blocks) {
            if b.kind != VarKind::InOut || !b.decls.iter().any(is_poly) {
                out.push(b);
                continue;
            }
            let mut cur: Option<VarBlock> = None;
            for mut d in b.decls.iter().cloned() {
                let poly = is_poly(&d);
                if poly {
                    names.extend(d.names.iter().map(|n| n.sym));
                    let span = d.ty.span();
                    d.ty = TypeSpec::Ref {
                        target: Box::new(d.ty.clone()),
                        span,
                        reference: false,
                    };
                }
                let kind = if poly { VarKind::Input } else { VarKind::InOut };
                match &mut cur {
                    Some(c) if c.kind == kind => c.decls.push(d),
                    _ => {
                        if let Some(c) = cur.take() {
                            out.push(c);
                        }
                        cur = Some(VarBlock {
                            kind,
                            decls: vec![d],
                            ..b.clone()
                        });
                    }
                }
            }
            if let Some(c) = cur {
                out.push(c);
            }
        }
        *blocks = out;
        names
    }

    /// Initial values of interface variables and references to a base
    /// class, as written in `blocks` (before retyping): `d : IDevice := v;`
    /// and `r : REF_TO Motor := REF(f);` become the structure's initialiser
    /// `(__id := <class of v>, __r<id> := REF(v))`; `:= NULL` is no
    /// instance (the structure's default).
    pub(super) fn itf_inits(&mut self, blocks: &mut [VarBlock], cx: &Ctx) {
        // The initial values of the interface variables (and references to
        // a base class) of these declarations, as written: one of them may
        // be initialised from another.
        let mut sources: HashMap<Symbol, Option<Expr>> = HashMap::new();
        // (A VAR_EXTERNAL's value is the global's, not known here.)
        for b in blocks.iter().filter(|b| b.kind != VarKind::External) {
            for decl in &b.decls {
                if self.itf_decl(&decl.ty).is_some() {
                    let init = match &decl.init {
                        Some(Initializer::Expr(e)) => Some(e.clone()),
                        _ => None,
                    };
                    for n in &decl.names {
                        sources.insert(n.sym, init.clone());
                    }
                }
            }
        }
        for b in blocks.iter_mut() {
            for decl in &mut b.decls {
                self.itf_init(decl, cx, &sources);
            }
        }
    }

    /// The interface a declaration stands for, and whether its value is
    /// written as a reference (`REF(x)`, a `REF_TO` of a base class).
    fn itf_decl(&self, ty: &TypeSpec) -> Option<(Symbol, bool)> {
        match ty {
            TypeSpec::Named(id)
                if self.itfs.contains_key(&id.sym) && !self.poly_class.contains_key(&id.sym) =>
            {
                Some((id.sym, false))
            }
            TypeSpec::Ref { target, .. } => match &**target {
                TypeSpec::Named(id) => self.poly.get(&id.sym).map(|i| (*i, true)),
                _ => None,
            },
            _ => None,
        }
    }

    /// `d2 : IDevice := d1;`: follows `d1` (of these declarations, of the
    /// same interface or one extending it) to its own initial value.
    /// `None` when the declaration ends up with no instance (or an error).
    fn itf_init_source(
        &mut self,
        mut init: Expr,
        itf: Symbol,
        sources: &HashMap<Symbol, Option<Expr>>,
        cx: &Ctx,
    ) -> Option<Expr> {
        let mut seen: Vec<Symbol> = Vec::new();
        loop {
            let mut e = &init;
            while let ExprKind::Paren(i) = &e.kind {
                e = i;
            }
            let ExprKind::Name(n) = e.kind else {
                return Some(init);
            };
            let T::Itf(j) = self.type_of(e, cx) else {
                return Some(init);
            };
            let (vn, jn, iname) = (self.name(n.sym), self.name(j), self.name(itf));
            let Some(src) = sources.get(&n.sym) else {
                self.err(
                    Code::E039,
                    init.span,
                    format!("`{vn}` is not declared here: an interface variable's initial value is an instance, NULL or another interface variable of the same declarations"),
                );
                return None;
            };
            if !self.itf_chain(j).contains(&itf) {
                let msg = match (self.poly_class.get(&j), self.poly_class.get(&itf)) {
                    (Some(a), Some(b)) => {
                        let (an, bn) = (self.name(*a), self.name(*b));
                        format!("`{vn}` is a reference to `{an}`, which is not derived from `{bn}`")
                    }
                    _ => format!("`{vn}` is of interface `{jn}`, which is not `{iname}` and does not extend it"),
                };
                self.err(Code::E212, init.span, msg);
                return None;
            }
            if seen.contains(&n.sym) {
                self.err(
                    Code::E039,
                    init.span,
                    format!("interface variables initialised from each other (through `{vn}`): one of them needs an instance or NULL"),
                );
                return None;
            }
            seen.push(n.sym);
            match src {
                Some(v) if !self.is_nothing(v) => init = v.clone(),
                _ => return None,
            }
        }
    }

    fn itf_init(&mut self, decl: &mut VarDecl, cx: &Ctx, sources: &HashMap<Symbol, Option<Expr>>) {
        // `[sq, NULL, c2]` of an array of interfaces: each element as a
        // scalar's initial value is (a NULL one designating nothing).
        if let (TypeSpec::Array { elem, .. }, Some(Initializer::Array { elems, .. })) =
            (&decl.ty, &mut decl.init)
        {
            let Some((itf, by_ref)) = self.itf_decl(elem) else {
                return;
            };
            for el in elems.iter_mut() {
                let Some(Initializer::Expr(e)) = &el.value else {
                    continue;
                };
                let span = e.span;
                match self.itf_value(e.clone(), itf, by_ref, cx, sources) {
                    ItfInit::AsWritten => {}
                    ItfInit::Nothing => el.value = Some(self.itf_struct(0, None, span)),
                    ItfInit::Value(v) => el.value = Some(v),
                }
            }
            return;
        }
        let Some(Initializer::Expr(init)) = &decl.init else {
            return;
        };
        let Some((itf, by_ref)) = self.itf_decl(&decl.ty) else {
            return;
        };
        match self.itf_value(init.clone(), itf, by_ref, cx, sources) {
            ItfInit::AsWritten => {}
            ItfInit::Nothing => decl.init = None,
            ItfInit::Value(v) => decl.init = Some(v),
        }
    }

    /// The initial value `init` of an interface `itf` (or, `by_ref`, of a
    /// reference to a base class) as the interface's structure.
    fn itf_value(
        &mut self,
        init: Expr,
        itf: Symbol,
        by_ref: bool,
        cx: &Ctx,
        sources: &HashMap<Symbol, Option<Expr>>,
    ) -> ItfInit {
        if self.is_nothing(&init) {
            return ItfInit::Nothing;
        }
        let Some(init) = self.itf_init_source(init, itf, sources, cx) else {
            return ItfInit::Nothing;
        };
        let span = init.span;
        let inst = if by_ref {
            match &init.kind {
                ExprKind::Call { callee, args }
                    if self.is_word(callee, "REF") && args.len() == 1 =>
                {
                    match args.first().and_then(|a| a.value.clone()) {
                        Some(v) => v,
                        None => return ItfInit::AsWritten,
                    }
                }
                _ => return ItfInit::AsWritten,
            }
        } else {
            init
        };
        let T::Class(c) = self.type_of(&inst, cx) else {
            return ItfInit::AsWritten;
        };
        if self.bad_impl.contains(&c) || self.broken.contains(&c) {
            return ItfInit::Nothing;
        }
        if !self.implements(c, itf) {
            let cn = self.name(c);
            let msg = match self.poly_class.get(&itf) {
                Some(b) => {
                    let bn = self.name(*b);
                    format!("`{cn}` is neither `{bn}` nor derived from it: a reference to `{bn}` cannot designate it")
                }
                None => format!("`{cn}` does not implement interface `{}`", self.name(itf)),
            };
            self.err(Code::E212, span, msg);
            return ItfInit::Nothing;
        }
        let k = self.ids.get(&c).copied().unwrap_or(0);
        ItfInit::Value(self.itf_struct(k, Some(inst), span))
    }

    /// `(__id := k, __r<k> := REF(inst))`: the interface's structure
    /// designating `inst` of the class numbered `k`; `(__id := 0)` nothing.
    fn itf_struct(&mut self, k: u32, inst: Option<Expr>, span: Span) -> Initializer {
        let id_sym = self.sym("__id");
        let lit = Expr {
            kind: ExprKind::Literal(Box::new(Literal {
                kind: LitKind::Int(i128::from(k)),
                ty: None,
            })),
            span,
        };
        let mut fields = vec![FieldInit {
            name: Ident { sym: id_sym, span },
            value: Initializer::Expr(lit),
            span,
        }];
        if let Some(inst) = inst {
            let r = format!("__r{k}");
            let r = self.sym(&r);
            let rsym = self.sym("REF");
            fields.push(FieldInit {
                name: Ident { sym: r, span },
                value: Initializer::Expr(super::poly::call_expr(rsym, vec![inst], span)),
                span,
            });
        }
        Initializer::Struct { fields, span }
    }

    pub(super) fn locals_of(blocks: &[VarBlock]) -> HashMap<Symbol, TypeSpec> {
        let mut m = HashMap::new();
        for b in blocks {
            for decl in &b.decls {
                for n in &decl.names {
                    m.insert(n.sym, decl.ty.clone());
                }
            }
        }
        m
    }

    pub(super) fn rewrite_pou(&mut self, p: &mut Pou) {
        let byref = self.split_poly_inouts(&mut p.var_blocks);
        let mut locals = Self::locals_of(&p.var_blocks);
        // A function's result is assigned to its name.
        if let (PouKind::Function, Some(r)) = (p.kind, &p.return_type) {
            locals.insert(p.name.sym, r.clone());
        }
        let cx = Ctx {
            class: None,
            defined_in: None,
            in_method: false,
            locals,
            result: None,
            pou: Some(p.name.sym),
            byref,
        };
        self.itf_inits(&mut p.var_blocks, &cx);
        for b in &mut p.var_blocks {
            self.retype_block(b);
        }
        if let Some(r) = &mut p.return_type {
            self.retype_spec(r, VarKind::Output);
        }
        let Body::St(stmts) = &mut p.body;
        self.stmts(stmts, &cx);
    }
}
