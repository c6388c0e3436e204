//! CODESYS references (`REFERENCE TO T`, `--lib codesys`) rewritten into
//! the standard's `REF_TO T`, before the object-orientation desugaring.
//!
//! The rules:
//! - A variable, input, member or structure field declared `REFERENCE TO T`
//!   becomes `REF_TO T`, and every use of it as a value or a place is
//!   dereferenced: `r := 5` is `r^ := 5`, `y := r + 1` is `y := r^ + 1`,
//!   `rm.Start()` is `rm^.Start()` (so a reference to a base class
//!   dispatches as a `REF_TO` base does), `rfb(IN := x)` is `rfb^(...)`.
//!   Reading one that is bound to nothing is therefore a NULL dereference,
//!   the runtime's fault at that use.
//! - `r REF= x;` (parsed as `r := __REFBIND(x)`) binds: `r := REF(x)`, or
//!   `r := r2` when `x` is itself a reference (both bound to one variable).
//!   In a declaration (`r : REFERENCE TO T REF= x;`) the parser makes it
//!   the initial value `REF(x)`.
//! - `__ISVALIDREF(r)` is `r <> NULL`.
//! - An argument given to an input declared `REFERENCE TO T` is bound, not
//!   copied: `F(r := x)` passes `REF(x)` (so the function writes `x`).
//! - `rfb(IN := x, Q => q);` writes the inputs and reads the outputs
//!   through the reference and runs the body with `__RC_<FB>(__x := rfb^)`,
//!   a FUNCTION calling its VAR_IN_OUT instance (`fb_call`).
//!
//! Types are followed as written (TYPE aliases, arrays, structures, the
//! variables of function blocks and classes with their bases), which is
//! all a reference's use needs: anything not found is left for the checker.

use crate::ast::oop::Class;
use crate::ast::{
    Arg, ArgDir, BinaryOp, Body, Expr, ExprKind, Ident, Item, SourceUnit, Stmt, StmtKind, TypeSpec,
    VarBlock, VarKind,
};
use crate::parser::reference::REF_BIND;
use automat_base::{Interner, Symbol};
use std::collections::HashMap;

/// Rewrites every `REFERENCE TO` of the project (see the module comment).
pub(crate) fn desugar_references(units: &mut [SourceUnit], interner: &mut Interner) {
    if !units.iter().any(unit_has_reference) {
        return;
    }
    let null = interner.intern("NULL");
    let mut r = Refs {
        called: Vec::new(),
        owners: HashMap::new(),
        aliases: HashMap::new(),
        globals: HashMap::new(),
        params: HashMap::new(),
        bind: interner.intern(REF_BIND),
        valid: interner.intern("__ISVALIDREF"),
        reff: interner.intern("REF"),
        null,
        this: interner.intern("THIS"),
        super_: interner.intern("SUPER"),
        interner,
    };
    for unit in units.iter() {
        for item in &unit.items {
            r.collect(item);
        }
    }
    for unit in units.iter_mut() {
        let before = r.called.len();
        for item in &mut unit.items {
            r.rewrite_item(item);
        }
        // The wrappers, in the unit of their first call.
        let new = r.called.get(before..).unwrap_or_default().to_vec();
        for (fb, at) in new {
            let item = r.call_wrapper(fb, at);
            unit.items.push(item);
        }
    }
}

/// Whether a `REFERENCE TO` or `REF=` occurs (most projects: no, and the
/// pass costs nothing).
fn unit_has_reference(unit: &SourceUnit) -> bool {
    let blocks_have = |bs: &[VarBlock]| {
        bs.iter()
            .any(|b| b.decls.iter().any(|d| spec_has_reference(&d.ty)))
    };
    unit.items.iter().any(|item| match item {
        Item::Pou(p) => blocks_have(&p.var_blocks),
        Item::Class(c) => {
            blocks_have(&c.var_blocks) || c.methods.iter().any(|m| blocks_have(&m.var_blocks))
        }
        Item::Types(t) => t.decls.iter().any(|d| spec_has_reference(&d.spec)),
        Item::Globals(b) => blocks_have(std::slice::from_ref(b)),
        Item::Config(c) => {
            blocks_have(&c.globals) || c.resources.iter().any(|r| blocks_have(&r.globals))
        }
        Item::Interface(_) | Item::Namespace(_) => false,
    })
}

fn spec_has_reference(t: &TypeSpec) -> bool {
    match t {
        TypeSpec::Ref {
            reference, target, ..
        } => *reference || spec_has_reference(target),
        TypeSpec::Array { elem, .. } => spec_has_reference(elem),
        TypeSpec::Struct { members, .. } => members.iter().any(|m| spec_has_reference(&m.ty)),
        _ => false,
    }
}

/// `REFERENCE TO T` becomes `REF_TO T`, in place.
fn plain_spec(t: &mut TypeSpec) {
    match t {
        TypeSpec::Ref {
            reference, target, ..
        } => {
            *reference = false;
            plain_spec(target);
        }
        TypeSpec::Array { elem, .. } => plain_spec(elem),
        TypeSpec::Struct { members, .. } => members.iter_mut().for_each(|m| plain_spec(&mut m.ty)),
        _ => {}
    }
}

fn plain_blocks(bs: &mut [VarBlock]) {
    for b in bs {
        for d in &mut b.decls {
            plain_spec(&mut d.ty);
        }
    }
}

fn vars_of(bs: &[VarBlock], into: &mut HashMap<Symbol, TypeSpec>) {
    for b in bs {
        for d in &b.decls {
            for n in &d.names {
                into.insert(n.sym, d.ty.clone());
            }
        }
    }
}

/// Inputs and in-outs in declaration order (for positional arguments).
fn params_of(bs: &[VarBlock]) -> Params {
    let mut v = Vec::new();
    for b in bs {
        if matches!(b.kind, VarKind::Input | VarKind::InOut) {
            for d in &b.decls {
                for n in &d.names {
                    v.push((n.sym, d.ty.clone()));
                }
            }
        }
    }
    v
}

/// Inputs and in-outs (name, type as written), in declaration order.
type Params = Vec<(Symbol, TypeSpec)>;

/// A type with variables: a structure, a function block, program or class.
struct Owner {
    extends: Option<Symbol>,
    vars: HashMap<Symbol, TypeSpec>,
}

/// Where a body is rewritten.
struct Scope {
    locals: HashMap<Symbol, TypeSpec>,
    /// The POU or class whose variables the body sees.
    owner: Option<Symbol>,
}

struct Refs<'a> {
    interner: &'a mut Interner,
    /// Function blocks called through a reference: a `__RC_<FB>` each.
    called: Vec<(Symbol, automat_base::Span)>,
    owners: HashMap<Symbol, Owner>,
    aliases: HashMap<Symbol, TypeSpec>,
    globals: HashMap<Symbol, TypeSpec>,
    /// The inputs of a POU or class `(name, None)` and of a method `(class, Some(method))`.
    params: HashMap<(Symbol, Option<Symbol>), Params>,
    bind: Symbol,
    valid: Symbol,
    reff: Symbol,
    null: Symbol,
    this: Symbol,
    super_: Symbol,
}

/// Bases followed at most (the OOP checks report longer or cyclic chains).
const MAX_CHAIN: usize = 70;
/// TYPE aliases followed at most.
const MAX_ALIASES: usize = 32;

impl Refs<'_> {
    fn collect(&mut self, item: &Item) {
        match item {
            Item::Pou(p) => {
                let mut vars = HashMap::new();
                vars_of(&p.var_blocks, &mut vars);
                self.owners.insert(
                    p.name.sym,
                    Owner {
                        extends: None,
                        vars,
                    },
                );
                self.params
                    .insert((p.name.sym, None), params_of(&p.var_blocks));
            }
            Item::Class(c) => self.collect_class(c),
            Item::Types(t) => {
                for d in &t.decls {
                    if let TypeSpec::Struct { members, .. } = &d.spec {
                        let mut vars = HashMap::new();
                        for m in members {
                            for n in &m.names {
                                vars.insert(n.sym, m.ty.clone());
                            }
                        }
                        self.owners.insert(
                            d.name.sym,
                            Owner {
                                extends: None,
                                vars,
                            },
                        );
                    } else {
                        self.aliases.insert(d.name.sym, d.spec.clone());
                    }
                }
            }
            Item::Globals(b) => vars_of(std::slice::from_ref(b), &mut self.globals),
            Item::Config(c) => {
                vars_of(&c.globals, &mut self.globals);
                for r in &c.resources {
                    vars_of(&r.globals, &mut self.globals);
                }
            }
            Item::Interface(_) | Item::Namespace(_) => {}
        }
    }

    fn collect_class(&mut self, c: &Class) {
        let mut vars = HashMap::new();
        vars_of(&c.var_blocks, &mut vars);
        self.owners.insert(
            c.name.sym,
            Owner {
                extends: c.extends.map(|e| e.sym),
                vars,
            },
        );
        self.params
            .insert((c.name.sym, None), params_of(&c.var_blocks));
        for m in &c.methods {
            self.params
                .insert((c.name.sym, Some(m.name.sym)), params_of(&m.var_blocks));
        }
    }

    fn rewrite_item(&mut self, item: &mut Item) {
        match item {
            Item::Pou(p) => {
                let mut locals = HashMap::new();
                vars_of(&p.var_blocks, &mut locals);
                let scope = Scope {
                    locals,
                    owner: None,
                };
                let Body::St(body) = &mut p.body;
                self.stmts(body, &scope);
                plain_blocks(&mut p.var_blocks);
            }
            Item::Class(c) => {
                let owner = Some(c.name.sym);
                let scope = Scope {
                    locals: HashMap::new(),
                    owner,
                };
                self.stmts(&mut c.body, &scope);
                for m in &mut c.methods {
                    let mut locals = HashMap::new();
                    vars_of(&m.var_blocks, &mut locals);
                    self.stmts(&mut m.body, &Scope { locals, owner });
                    plain_blocks(&mut m.var_blocks);
                }
                for p in &mut c.properties {
                    for acc in [&mut p.get, &mut p.set].into_iter().flatten() {
                        let mut locals = HashMap::new();
                        vars_of(&acc.var_blocks, &mut locals);
                        self.stmts(&mut acc.body, &Scope { locals, owner });
                    }
                }
                plain_blocks(&mut c.var_blocks);
            }
            Item::Types(t) => {
                for d in &mut t.decls {
                    plain_spec(&mut d.spec);
                }
            }
            Item::Globals(b) => plain_blocks(std::slice::from_mut(b)),
            Item::Config(c) => {
                plain_blocks(&mut c.globals);
                for r in &mut c.resources {
                    plain_blocks(&mut r.globals);
                }
            }
            Item::Interface(_) | Item::Namespace(_) => {}
        }
    }

    fn stmts(&mut self, list: &mut Vec<Stmt>, sc: &Scope) {
        let mut i = 0;
        while i < list.len() {
            // `rfb(IN := x);`: plain statements, rewritten in turn.
            if let Some(b) = list.get(i).and_then(|s| self.fb_call(s, sc)) {
                list.splice(i..=i, b);
            }
            if let Some(s) = list.get_mut(i) {
                self.stmt(s, sc);
            }
            i += 1;
        }
    }

    fn stmt(&mut self, s: &mut Stmt, sc: &Scope) {
        match &mut s.kind {
            StmtKind::Assign { target, value } => {
                if let Some(x) = self.bind_source(value) {
                    self.expr(target, sc, false);
                    let mut x = x;
                    self.expr(&mut x, sc, false);
                    *value = if self.is_reference(&x, sc) {
                        x
                    } else {
                        self.ref_of(x)
                    };
                } else {
                    self.expr(target, sc, true);
                    self.expr(value, sc, true);
                }
            }
            StmtKind::Expr(e) => self.expr(e, sc, true),
            StmtKind::If {
                branches,
                else_body,
            } => {
                for b in branches {
                    self.expr(&mut b.cond, sc, true);
                    self.stmts(&mut b.body, sc);
                }
                if let Some(b) = else_body {
                    self.stmts(b, sc);
                }
            }
            StmtKind::Case {
                selector,
                arms,
                else_body,
            } => {
                self.expr(selector, sc, true);
                for a in arms {
                    self.stmts(&mut a.body, sc);
                }
                if let Some(b) = else_body {
                    self.stmts(b, sc);
                }
            }
            StmtKind::For {
                from, to, by, body, ..
            } => {
                self.expr(from, sc, true);
                self.expr(to, sc, true);
                if let Some(b) = by {
                    self.expr(b, sc, true);
                }
                self.stmts(body, sc);
            }
            StmtKind::While { cond, body } => {
                self.expr(cond, sc, true);
                self.stmts(body, sc);
            }
            StmtKind::Repeat { body, until } => {
                self.stmts(body, sc);
                self.expr(until, sc, true);
            }
            StmtKind::Return
            | StmtKind::Exit
            | StmtKind::Continue
            | StmtKind::Empty
            | StmtKind::Label(_)
            | StmtKind::Goto(_) => {}
        }
    }

    /// The `x` of `__REFBIND(x)` (what `REF=` binds to).
    fn bind_source(&self, value: &Expr) -> Option<Expr> {
        let ExprKind::Call { callee, args } = &value.kind else {
            return None;
        };
        if !matches!(&callee.kind, ExprKind::Name(n) if n.sym == self.bind) {
            return None;
        }
        args.first().and_then(|a| a.value.clone())
    }

    fn ref_of(&self, x: Expr) -> Expr {
        let span = x.span;
        Expr {
            kind: ExprKind::Call {
                callee: Box::new(Expr {
                    kind: ExprKind::Name(Ident {
                        sym: self.reff,
                        span,
                    }),
                    span,
                }),
                args: vec![Arg {
                    name: None,
                    dir: ArgDir::In,
                    value: Some(x),
                    span,
                }],
            },
            span,
        }
    }

    /// Rewrites `e`'s uses of references; `deref`: `e` itself is used as a
    /// value or place (not bound, not tested by `__ISVALIDREF`).
    fn expr(&mut self, e: &mut Expr, sc: &Scope, deref: bool) {
        match &mut e.kind {
            ExprKind::Member { base, .. } => self.expr(base, sc, true),
            ExprKind::Partial { base, .. } => self.expr(base, sc, true),
            ExprKind::Index { base, indices } => {
                self.expr(base, sc, true);
                for i in indices {
                    self.expr(i, sc, true);
                }
            }
            ExprKind::Deref(b) => self.expr(b, sc, true),
            ExprKind::Unary { operand, .. } => self.expr(operand, sc, true),
            ExprKind::Binary { lhs, rhs, .. } => {
                self.expr(lhs, sc, true);
                self.expr(rhs, sc, true);
            }
            ExprKind::Paren(x) => self.expr(x, sc, deref),
            ExprKind::Call { .. } => {
                self.call(e, sc);
                return;
            }
            ExprKind::Literal(_) | ExprKind::Name(_) | ExprKind::Address(_) | ExprKind::Error => {}
        }
        if deref
            && matches!(
                e.kind,
                ExprKind::Name(_) | ExprKind::Member { .. } | ExprKind::Index { .. }
            )
            && self.is_reference(e, sc)
        {
            let span = e.span;
            let inner = std::mem::replace(&mut e.kind, ExprKind::Error);
            e.kind = ExprKind::Deref(Box::new(Expr { kind: inner, span }));
        }
    }

    fn call(&mut self, e: &mut Expr, sc: &Scope) {
        let span = e.span;
        let ExprKind::Call { callee, args } = &mut e.kind else {
            return;
        };
        // `__ISVALIDREF` of anything but one reference is left for the
        // checker, which says what is wrong with it (E163).
        let valid = matches!(&callee.kind, ExprKind::Name(n) if n.sym == self.valid);
        let one_reference = match args.as_slice() {
            [a] => a.name.is_none() && a.value.as_ref().is_some_and(|v| self.is_reference(v, sc)),
            _ => false,
        };
        if valid && one_reference {
            let Some(mut x) = args.first_mut().and_then(|a| a.value.take()) else {
                return;
            };
            self.expr(&mut x, sc, false);
            let null = Expr {
                kind: ExprKind::Name(Ident {
                    sym: self.null,
                    span,
                }),
                span,
            };
            e.kind = ExprKind::Paren(Box::new(Expr {
                kind: ExprKind::Binary {
                    op: BinaryOp::Ne,
                    lhs: Box::new(x),
                    rhs: Box::new(null),
                },
                span,
            }));
            return;
        }
        let params = self.callee_params(callee, sc).cloned();
        self.expr(callee, sc, true);
        for (k, a) in args.iter_mut().enumerate() {
            let Some(v) = &mut a.value else { continue };
            let binds = a.dir == ArgDir::In
                && params.as_ref().is_some_and(|ps| {
                    let p = match a.name {
                        Some(n) => ps.iter().find(|(s, _)| *s == n.sym),
                        None => ps.get(k),
                    };
                    p.is_some_and(|(_, t)| self.spec_is_reference(t))
                });
            if binds {
                self.expr(v, sc, false);
                if !self.is_reference(v, sc) {
                    let x = std::mem::replace(
                        v,
                        Expr {
                            kind: ExprKind::Error,
                            span,
                        },
                    );
                    *v = self.ref_of(x);
                }
            } else {
                self.expr(v, sc, true);
            }
        }
    }

    /// The inputs of what `callee` names: a POU, an instance (its type's),
    /// a method of an instance's class.
    fn callee_params(&self, callee: &Expr, sc: &Scope) -> Option<&Params> {
        match &callee.kind {
            ExprKind::Name(n) => match self.lookup(n.sym, sc) {
                Some(t) => self
                    .params
                    .get(&(self.type_name(&self.deref_spec(t))?, None)),
                None => self
                    .params
                    .get(&(n.sym, None))
                    .or_else(|| self.method_params(sc.owner?, n.sym)),
            },
            ExprKind::Member { base, member } => {
                let t = self.ty(base, sc)?;
                let c = self.type_name(&self.deref_spec(t))?;
                self.method_params(c, member.sym)
            }
            ExprKind::Deref(b) => {
                let t = self.ty(b, sc)?;
                self.params
                    .get(&(self.type_name(&self.deref_spec(t))?, None))
            }
            _ => None,
        }
    }

    fn method_params(&self, c: Symbol, m: Symbol) -> Option<&Params> {
        self.chain(c)
            .into_iter()
            .find_map(|k| self.params.get(&(k, Some(m))))
    }

    /// A reference's target (a `REFERENCE TO` used as its target); other types unchanged.
    fn deref_spec(&self, t: TypeSpec) -> TypeSpec {
        match self.resolve(t) {
            TypeSpec::Ref {
                target,
                reference: true,
                ..
            } => *target,
            t => t,
        }
    }

    fn type_name(&self, t: &TypeSpec) -> Option<Symbol> {
        match t {
            TypeSpec::Named(n) => Some(n.sym),
            _ => None,
        }
    }

    fn chain(&self, c: Symbol) -> Vec<Symbol> {
        let mut out = vec![c];
        let mut cur = c;
        while let Some(b) = self.owners.get(&cur).and_then(|o| o.extends) {
            if out.len() > MAX_CHAIN || out.contains(&b) {
                break;
            }
            out.push(b);
            cur = b;
        }
        out
    }

    fn lookup(&self, n: Symbol, sc: &Scope) -> Option<TypeSpec> {
        if let Some(t) = sc.locals.get(&n) {
            return Some(t.clone());
        }
        if let Some(o) = sc.owner {
            if let Some(t) = self.member(o, n) {
                return Some(t);
            }
        }
        self.globals.get(&n).cloned()
    }

    fn member(&self, owner: Symbol, m: Symbol) -> Option<TypeSpec> {
        self.chain(owner)
            .into_iter()
            .find_map(|k| self.owners.get(&k)?.vars.get(&m).cloned())
    }

    /// Through TYPE aliases.
    fn resolve(&self, mut t: TypeSpec) -> TypeSpec {
        for _ in 0..MAX_ALIASES {
            let TypeSpec::Named(n) = &t else { break };
            let Some(a) = self.aliases.get(&n.sym) else {
                break;
            };
            t = a.clone();
        }
        t
    }

    /// The declared type of a place (after this pass's own rewriting).
    fn ty(&self, e: &Expr, sc: &Scope) -> Option<TypeSpec> {
        match &e.kind {
            ExprKind::Name(n) if n.sym == self.this || n.sym == self.super_ => {
                let o = sc.owner?;
                let c = if n.sym == self.this {
                    o
                } else {
                    self.owners.get(&o)?.extends?
                };
                Some(TypeSpec::Ref {
                    target: Box::new(TypeSpec::Named(Ident {
                        sym: c,
                        span: n.span,
                    })),
                    span: n.span,
                    reference: false,
                })
            }
            ExprKind::Name(n) => self.lookup(n.sym, sc),
            ExprKind::Member { base, member } => match self.resolve(self.ty(base, sc)?) {
                TypeSpec::Named(o) => self.member(o.sym, member.sym),
                TypeSpec::Struct { members, .. } => members
                    .iter()
                    .find(|m| m.names.iter().any(|x| x.sym == member.sym))
                    .map(|m| m.ty.clone()),
                _ => None,
            },
            ExprKind::Index { base, .. } => match self.resolve(self.ty(base, sc)?) {
                TypeSpec::Array { elem, .. } => Some(*elem),
                _ => None,
            },
            ExprKind::Deref(b) => match self.resolve(self.ty(b, sc)?) {
                TypeSpec::Ref { target, .. } => Some(*target),
                _ => None,
            },
            ExprKind::Paren(x) => self.ty(x, sc),
            _ => None,
        }
    }

    fn spec_is_reference(&self, t: &TypeSpec) -> bool {
        matches!(
            self.resolve(t.clone()),
            TypeSpec::Ref {
                reference: true,
                ..
            }
        )
    }

    fn is_reference(&self, e: &Expr, sc: &Scope) -> bool {
        self.ty(e, sc).is_some_and(|t| self.spec_is_reference(&t))
    }
}

impl Refs<'_> {
    /// `rfb(IN := x, Q => q);` for `rfb : REFERENCE TO F` becomes
    /// `rfb.IN := x; __RC_F(__x := rfb); q := rfb.Q;` (then dereferenced
    /// like every use): `__RC_F` calls the instance it is given as a
    /// VAR_IN_OUT, which the code generator can, unlike a call through `^`.
    fn fb_call(&mut self, s: &Stmt, sc: &Scope) -> Option<Vec<Stmt>> {
        let StmtKind::Expr(Expr {
            kind: ExprKind::Call { callee, args },
            ..
        }) = &s.kind
        else {
            return None;
        };
        if !matches!(callee.kind, ExprKind::Name(_) | ExprKind::Member { .. }) {
            return None;
        }
        let t = self.ty(callee, sc)?;
        let TypeSpec::Ref {
            target,
            reference: true,
            ..
        } = self.resolve(t)
        else {
            return None;
        };
        let TypeSpec::Named(fb) = self.resolve(*target) else {
            return None;
        };
        // Positional arguments: left to the checker's message.
        if args.iter().any(|a| a.name.is_none()) {
            return None;
        }
        let span = s.span;
        if !self.called.iter().any(|(f, _)| *f == fb.sym) {
            self.called.push((fb.sym, span));
        }
        let field = |m: Ident| Expr {
            kind: ExprKind::Member {
                base: callee.clone(),
                member: m,
            },
            span: m.span,
        };
        let mut out = Vec::new();
        let mut after = Vec::new();
        for a in args {
            let (Some(n), Some(v)) = (a.name, &a.value) else {
                continue;
            };
            let value = field(n);
            match a.dir {
                ArgDir::In => out.push(Stmt {
                    kind: StmtKind::Assign {
                        target: value,
                        value: v.clone(),
                    },
                    span: a.span,
                }),
                ArgDir::Out | ArgDir::OutNot => {
                    let value = if a.dir == ArgDir::OutNot {
                        Expr {
                            kind: ExprKind::Unary {
                                op: crate::ast::UnaryOp::Not,
                                operand: Box::new(value),
                            },
                            span: a.span,
                        }
                    } else {
                        value
                    };
                    after.push(Stmt {
                        kind: StmtKind::Assign {
                            target: v.clone(),
                            value,
                        },
                        span: a.span,
                    });
                }
            }
        }
        let wrapper = self.wrapper_name(fb.sym);
        let x = self.interner.intern("__x");
        let call = Expr {
            kind: ExprKind::Call {
                callee: Box::new(Expr {
                    kind: ExprKind::Name(Ident {
                        sym: wrapper,
                        span: callee.span,
                    }),
                    span: callee.span,
                }),
                args: vec![Arg {
                    name: Some(Ident { sym: x, span }),
                    dir: ArgDir::In,
                    value: Some((**callee).clone()),
                    span,
                }],
            },
            span,
        };
        out.push(Stmt {
            kind: StmtKind::Expr(call),
            span,
        });
        out.extend(after);
        Some(out)
    }

    fn wrapper_name(&mut self, fb: Symbol) -> Symbol {
        let n = format!("__RC_{}", self.interner.name(fb));
        self.interner.intern(&n)
    }

    /// `FUNCTION __RC_F VAR_IN_OUT __x : F; END_VAR __x(); END_FUNCTION`.
    /// At the first call's span (for any message about it).
    fn call_wrapper(&mut self, fb: Symbol, span: automat_base::Span) -> Item {
        let name = self.wrapper_name(fb);
        let x = Ident {
            sym: self.interner.intern("__x"),
            span,
        };
        let call = Expr {
            kind: ExprKind::Call {
                callee: Box::new(Expr {
                    kind: ExprKind::Name(x),
                    span,
                }),
                args: Vec::new(),
            },
            span,
        };
        Item::Pou(crate::ast::Pou {
            kind: crate::ast::PouKind::Function,
            name: Ident { sym: name, span },
            return_type: None,
            var_blocks: vec![VarBlock {
                kind: VarKind::InOut,
                constant: false,
                retain: Default::default(),
                decls: vec![crate::ast::VarDecl {
                    names: vec![x],
                    location: None,
                    ty: TypeSpec::Named(Ident { sym: fb, span }),
                    edge: None,
                    init: None,
                    span,
                }],
                span,
            }],
            body: Body::St(vec![Stmt {
                kind: StmtKind::Expr(call),
                span,
            }]),
            lang: crate::ast::Lang::St,
            span,
        })
    }
}
