//! NAMESPACE and USING (IEC 61131-3 3rd edition, 6.9), removed before any
//! later stage sees the project: every item declared in a namespace is
//! renamed to its qualified name as written (`Motion.Clamp`, one symbol
//! whose spelling holds the dots, which no identifier can), and every
//! reference to it is rewritten to that name. Checking and lowering then
//! see plain items, and messages show the names as the user writes them.
//!
//! Resolution of a name written inside a namespace, in this order:
//! 1. the current namespace, then the enclosing ones outwards;
//! 2. the namespaces named by `USING` (of this namespace, of the enclosing
//!    ones and of the POU's header): one of them must declare it, two is
//!    an ambiguity (E216);
//! 3. the global namespace (the name stays as written).
//!
//! A qualified name `A.B.x` names `x` of namespace `A.B` looked up from the
//! current namespace outwards (`A.B` relative to it first, then to each
//! enclosing one, then from the global one) and then under each USING'd
//! namespace. In expressions, where `A.B.x` parses as member accesses, the
//! longest prefix that names a namespace item wins, unless its first part
//! is a variable of the POU. Local variables, methods and properties hide
//! namespace items of the same name.
//!
//! `USING` after a METHOD's header adds to the namespaces its body sees.
//!
//! `NAMESPACE INTERNAL N`: its items (and those of the namespaces nested
//! in it) are visible in the namespace enclosing `N` and everything nested
//! there; for an INTERNAL namespace at the top, only inside `N` (E217).

use crate::ast::oop::{Class, Interface, Method, Property};
use crate::ast::{
    Arg, ArrayDim, Body, CaseLabel, Configuration, Expr, ExprKind, Ident, Initializer, Item,
    Namespace, Pou, SourceUnit, Stmt, StmtKind, TypeSpec, VarBlock, VarKind,
};
use automat_base::{Code, Diagnostic, Interner, Span, Symbol};
use std::collections::{HashMap, HashSet};

/// Replaces every namespace of `units` by its items under their qualified
/// names, followed by the namespace emptied of them, and rewrites the
/// references (a project without NAMESPACE is left untouched).
/// Diagnostics: E215, E216.
pub fn desugar_namespaces(units: &mut [SourceUnit], interner: &mut Interner) -> Vec<Diagnostic> {
    // A METHOD's USING too: with no namespace declared, it names none (E215).
    let any = units.iter().any(|u| {
        u.items.iter().any(|i| match i {
            Item::Namespace(_) => true,
            Item::Class(c) => c.methods.iter().any(|m| !m.usings.is_empty()),
            _ => false,
        })
    });
    if !any {
        return Vec::new();
    }
    let mut t = Tables::default();
    for u in units.iter() {
        for item in &u.items {
            t.collect(item, &[], interner);
        }
    }
    let mut r = Rewriter {
        t,
        interner,
        diags: Vec::new(),
        locals: HashSet::new(),
    };
    let global = Scope::default();
    for u in units.iter_mut() {
        let items = std::mem::take(&mut u.items);
        let mut out = Vec::with_capacity(items.len());
        for item in items {
            // The namespace stays, emptied, after its items: later stages
            // ignore it, export refuses it (TC6 XML has no namespaces).
            let husk = match &item {
                Item::Namespace(n) => Some(Item::Namespace(Box::new(Namespace {
                    name: n.name.clone(),
                    internal: n.internal,
                    usings: n.usings.clone(),
                    items: Vec::new(),
                    span: n.span,
                }))),
                _ => None,
            };
            r.flatten(item, &global, &mut out);
            out.extend(husk);
        }
        u.items = out;
    }
    r.diags
}

/// A namespace's path: its parts, case-folded.
type Path = Vec<Symbol>;

#[derive(Default)]
struct Tables {
    /// Every declared namespace, and every prefix of one.
    namespaces: HashSet<Path>,
    /// (namespace, name as declared there) → the item's qualified name.
    members: HashMap<(Path, Symbol), Symbol>,
    /// The qualified name of an item → its namespace.
    home: HashMap<Symbol, Path>,
    /// The namespaces declared `NAMESPACE INTERNAL` (any opening of them).
    internal: HashSet<Path>,
}

impl Tables {
    fn collect(&mut self, item: &Item, path: &[Symbol], interner: &mut Interner) {
        let Item::Namespace(n) = item else {
            if !path.is_empty() {
                for name in declared_names(item) {
                    let flat = qualified(path, name.sym, interner);
                    self.members.insert((path.to_vec(), name.sym), flat);
                    self.home.insert(flat, path.to_vec());
                }
            }
            return;
        };
        let mut inner = path.to_vec();
        for part in &n.name {
            inner.push(part.sym);
            self.namespaces.insert(inner.clone());
        }
        if n.internal && !n.name.is_empty() {
            self.internal.insert(inner.clone());
        }
        for i in &n.items {
            self.collect(i, &inner, interner);
        }
    }
}

/// The names an item declares in its namespace.
fn declared_names(item: &Item) -> Vec<Ident> {
    match item {
        Item::Pou(p) => vec![p.name],
        Item::Class(c) => vec![c.name],
        Item::Interface(i) => vec![i.name],
        Item::Types(t) => t.decls.iter().map(|d| d.name).collect(),
        Item::Globals(b) => b
            .decls
            .iter()
            .flat_map(|d| d.names.iter().copied())
            .collect(),
        Item::Config(_) | Item::Namespace(_) => Vec::new(),
    }
}

/// `A.B.name` spelled as first written.
fn qualified(path: &[Symbol], name: Symbol, interner: &mut Interner) -> Symbol {
    let mut text = String::new();
    for p in path {
        text.push_str(interner.name(*p));
        text.push('.');
    }
    text.push_str(interner.name(name));
    interner.intern(&text)
}

/// Where a name is written: the namespace and the USING'd ones.
#[derive(Clone, Default)]
struct Scope {
    path: Path,
    usings: Vec<Path>,
}

struct Rewriter<'a> {
    t: Tables,
    interner: &'a mut Interner,
    diags: Vec<Diagnostic>,
    /// The variables, methods and properties of the POU being rewritten:
    /// they hide namespace items.
    locals: HashSet<Symbol>,
}

impl Rewriter<'_> {
    fn flatten(&mut self, item: Item, scope: &Scope, out: &mut Vec<Item>) {
        match item {
            Item::Namespace(n) => {
                let n: Namespace = *n;
                let mut inner = scope.clone();
                inner.path.extend(n.name.iter().map(|i| i.sym));
                self.add_usings(&mut inner, &n.usings);
                for i in n.items {
                    self.flatten(i, &inner, out);
                }
            }
            mut item => {
                self.rename_declared(&mut item, &scope.path);
                self.item(&mut item, scope);
                out.push(item);
            }
        }
    }

    /// Resolves `USING` clauses written in `inner` (relative to its path
    /// outwards, then global) and adds them to it (E215 for an unknown one).
    fn add_usings(&mut self, inner: &mut Scope, usings: &[crate::ast::Using]) {
        {
            {
                for u in usings {
                    let mut found = None;
                    let written: Path = u.path.iter().map(|i| i.sym).collect();
                    // Relative to the namespace's own path outwards, then global.
                    for k in (0..=inner.path.len()).rev() {
                        let mut full = inner.path[..k].to_vec();
                        full.extend(written.iter().copied());
                        if self.t.namespaces.contains(&full) {
                            found = Some(full);
                            break;
                        }
                    }
                    match found {
                        Some(p) => inner.usings.push(p),
                        None => {
                            let name = self.spell_path(&written);
                            self.diags.push(Diagnostic::error(
                                Code::E215,
                                u.span,
                                format!("`USING {name}`: no namespace `{name}` is declared"),
                            ));
                        }
                    }
                }
            }
        }
    }

    /// E217 when item `flat` lies in an INTERNAL namespace not visible from `scope`.
    fn check_internal(&mut self, flat: Symbol, scope: &Scope, span: Span) {
        let Some(home) = self.t.home.get(&flat) else {
            return;
        };
        for k in 1..=home.len() {
            let ns = &home[..k];
            if !self.t.internal.contains(ns) {
                continue;
            }
            let parent = &ns[..k - 1];
            let visible = scope.path.starts_with(ns)
                || (!parent.is_empty() && scope.path.starts_with(parent));
            if !visible {
                let (item, nsname) = (self.interner.name(flat).to_string(), self.spell_path(ns));
                let where_ = if parent.is_empty() {
                    format!("inside `{nsname}` only")
                } else {
                    format!("in `{}` only", self.spell_path(parent))
                };
                self.diags.push(Diagnostic::error(
                    Code::E217,
                    span,
                    format!("`{item}` belongs to the INTERNAL namespace `{nsname}`: it is visible {where_}"),
                ));
                return;
            }
        }
    }

    fn spell_path(&self, path: &[Symbol]) -> String {
        path.iter()
            .map(|s| self.interner.name(*s))
            .collect::<Vec<_>>()
            .join(".")
    }

    fn rename_declared(&mut self, item: &mut Item, path: &Path) {
        if path.is_empty() {
            return;
        }
        let members = &self.t.members;
        let rename = |id: &mut Ident| {
            if let Some(f) = members.get(&(path.clone(), id.sym)) {
                id.sym = *f;
            }
        };
        match item {
            Item::Pou(p) => rename(&mut p.name),
            Item::Class(c) => rename(&mut c.name),
            Item::Interface(i) => rename(&mut i.name),
            Item::Types(t) => t.decls.iter_mut().for_each(|d| rename(&mut d.name)),
            Item::Globals(b) => b
                .decls
                .iter_mut()
                .for_each(|d| d.names.iter_mut().for_each(rename)),
            Item::Config(_) | Item::Namespace(_) => {}
        }
    }

    // ---- resolution ----

    /// An unqualified name: its qualified name, or `None` (global).
    fn resolve_simple(&mut self, scope: &Scope, id: Ident) -> Option<Symbol> {
        for k in (1..=scope.path.len()).rev() {
            if let Some(f) = self.t.members.get(&(scope.path[..k].to_vec(), id.sym)) {
                return Some(*f);
            }
        }
        let hit = self.resolve_using(scope, id);
        if let Some(f) = hit {
            self.check_internal(f, scope, id.span);
        }
        hit
    }

    /// An unqualified name through the USING'd namespaces (E216 when two declare it).
    fn resolve_using(&mut self, scope: &Scope, id: Ident) -> Option<Symbol> {
        let mut hits: Vec<Symbol> = Vec::new();
        for u in &scope.usings {
            if let Some(f) = self.t.members.get(&(u.clone(), id.sym)) {
                if !hits.contains(f) {
                    hits.push(*f);
                }
            }
        }
        if hits.len() > 1 {
            let names: Vec<String> = hits
                .iter()
                .map(|h| format!("`{}`", self.interner.name(*h)))
                .collect();
            self.diags.push(Diagnostic::error(
                Code::E216,
                id.span,
                format!(
                    "`{}` is ambiguous: the namespaces named by USING declare {}",
                    self.interner.name(id.sym),
                    names.join(" and ")
                ),
            ));
        }
        hits.first().copied()
    }

    /// `ns… . item` (the parts as written): the item's qualified name.
    fn resolve_qualified(&self, scope: &Scope, parts: &[Symbol]) -> Option<Symbol> {
        let (item, ns) = parts.split_last()?;
        let bases = (0..=scope.path.len())
            .rev()
            .map(|k| scope.path[..k].to_vec())
            .chain(scope.usings.iter().cloned());
        for mut full in bases {
            full.extend(ns.iter().copied());
            if let Some(f) = self.t.members.get(&(full, *item)) {
                return Some(*f);
            }
        }
        None
    }

    /// A name in a type position: plain or spelled with dots.
    fn type_name(&mut self, scope: &Scope, id: &mut Ident) {
        let text = self.interner.name(id.sym);
        if text.contains('.') {
            let parts: Vec<String> = text.split('.').map(str::to_string).collect();
            let syms: Vec<Symbol> = parts.iter().map(|p| self.interner.intern(p)).collect();
            if let Some(f) = self.resolve_qualified(scope, &syms) {
                self.check_internal(f, scope, id.span);
                id.sym = f;
            }
        } else if let Some(f) = self.resolve_simple(scope, *id) {
            id.sym = f;
        }
    }

    // ---- items ----

    fn item(&mut self, item: &mut Item, scope: &Scope) {
        match item {
            Item::Pou(p) => self.pou(p, scope),
            Item::Types(t) => {
                self.locals.clear();
                for d in &mut t.decls {
                    self.ty(&mut d.spec, scope);
                    if let Some(i) = &mut d.init {
                        self.init(i, scope);
                    }
                }
            }
            Item::Globals(b) => {
                self.locals.clear();
                self.block(b, scope);
            }
            Item::Config(c) => self.config(c, scope),
            Item::Class(c) => self.class(c, scope),
            Item::Interface(i) => self.interface(i, scope),
            Item::Namespace(_) => {}
        }
    }

    fn pou(&mut self, p: &mut Pou, scope: &Scope) {
        self.locals = locals_of(&p.var_blocks);
        if let Some(t) = &mut p.return_type {
            self.ty(t, scope);
        }
        self.blocks(&mut p.var_blocks, scope);
        let Body::St(body) = &mut p.body;
        self.stmts(body, scope);
    }

    fn class(&mut self, c: &mut Class, scope: &Scope) {
        if let Some(b) = &mut c.extends {
            self.type_name(scope, b);
        }
        for i in &mut c.implements {
            self.type_name(scope, i);
        }
        let mut members = locals_of(&c.var_blocks);
        members.extend(c.methods.iter().map(|m| m.name.sym));
        members.extend(c.properties.iter().map(|p| p.name.sym));
        self.locals = members.clone();
        self.blocks(&mut c.var_blocks, scope);
        self.stmts(&mut c.body, scope);
        for m in &mut c.methods {
            self.locals = members.clone();
            self.locals.extend(locals_of(&m.var_blocks));
            self.method(m, scope);
        }
        for p in &mut c.properties {
            self.locals = members.clone();
            self.property(p, scope, &members);
        }
    }

    fn method(&mut self, m: &mut Method, scope: &Scope) {
        let own;
        let scope = if m.usings.is_empty() {
            scope
        } else {
            let mut inner = scope.clone();
            let usings = std::mem::take(&mut m.usings);
            self.add_usings(&mut inner, &usings);
            m.usings = usings;
            own = inner;
            &own
        };
        if let Some(t) = &mut m.return_type {
            self.ty(t, scope);
        }
        self.blocks(&mut m.var_blocks, scope);
        self.stmts(&mut m.body, scope);
    }

    fn property(&mut self, p: &mut Property, scope: &Scope, members: &HashSet<Symbol>) {
        self.ty(&mut p.ty, scope);
        for a in [&mut p.get, &mut p.set].into_iter().flatten() {
            self.locals = members.clone();
            self.locals.extend(locals_of(&a.var_blocks));
            self.blocks(&mut a.var_blocks, scope);
            self.stmts(&mut a.body, scope);
        }
    }

    fn interface(&mut self, i: &mut Interface, scope: &Scope) {
        for e in &mut i.extends {
            self.type_name(scope, e);
        }
        let members: HashSet<Symbol> = i.methods.iter().map(|m| m.name.sym).collect();
        for m in &mut i.methods {
            self.locals = members.clone();
            self.method(m, scope);
        }
        for p in &mut i.properties {
            self.property(p, scope, &members);
        }
    }

    fn config(&mut self, c: &mut Configuration, scope: &Scope) {
        self.locals.clear();
        self.blocks(&mut c.globals, scope);
        for r in &mut c.resources {
            self.blocks(&mut r.globals, scope);
            for p in &mut r.programs {
                self.type_name(scope, &mut p.ty);
            }
        }
    }

    fn blocks(&mut self, blocks: &mut [VarBlock], scope: &Scope) {
        for b in blocks {
            self.block(b, scope);
        }
    }

    fn block(&mut self, b: &mut VarBlock, scope: &Scope) {
        for d in &mut b.decls {
            // A VAR_EXTERNAL names a global: one of a namespace, maybe.
            if b.kind == VarKind::External {
                for n in &mut d.names {
                    // `Motion.MaxPos` or a name seen from here.
                    self.type_name(scope, n);
                }
            }
            self.ty(&mut d.ty, scope);
            if let Some(i) = &mut d.init {
                self.init(i, scope);
            }
        }
    }

    fn ty(&mut self, t: &mut TypeSpec, scope: &Scope) {
        match t {
            TypeSpec::Named(id) => self.type_name(scope, id),
            TypeSpec::String { len, .. } => {
                if let Some(e) = len {
                    self.expr(e, scope);
                }
            }
            TypeSpec::Array { dims, elem, .. } => {
                for d in dims {
                    if let ArrayDim::Range { lo, hi, .. } = d {
                        self.expr(lo, scope);
                        self.expr(hi, scope);
                    }
                }
                self.ty(elem, scope);
            }
            TypeSpec::Subrange { base, lo, hi, .. } => {
                self.type_name(scope, base);
                self.expr(lo, scope);
                self.expr(hi, scope);
            }
            TypeSpec::Enum { values, .. } => {
                for v in values {
                    if let Some(e) = &mut v.value {
                        self.expr(e, scope);
                    }
                }
            }
            TypeSpec::Struct { members, .. } => {
                for m in members {
                    self.ty(&mut m.ty, scope);
                    if let Some(i) = &mut m.init {
                        self.init(i, scope);
                    }
                }
            }
            TypeSpec::Ref { target, .. } => self.ty(target, scope),
        }
    }

    fn init(&mut self, i: &mut Initializer, scope: &Scope) {
        match i {
            Initializer::Expr(e) => self.expr(e, scope),
            Initializer::Array { elems, .. } => {
                for e in elems {
                    if let Some(r) = &mut e.repeat {
                        self.expr(r, scope);
                    }
                    if let Some(v) = &mut e.value {
                        self.init(v, scope);
                    }
                }
            }
            Initializer::Struct { fields, .. } => {
                for f in fields {
                    self.init(&mut f.value, scope);
                }
            }
        }
    }

    // ---- bodies ----

    fn stmts(&mut self, body: &mut [Stmt], scope: &Scope) {
        for s in body {
            self.stmt(s, scope);
        }
    }

    fn stmt(&mut self, s: &mut Stmt, scope: &Scope) {
        match &mut s.kind {
            StmtKind::Assign { target, value } => {
                self.expr(target, scope);
                self.expr(value, scope);
            }
            StmtKind::Expr(e) => self.expr(e, scope),
            StmtKind::If {
                branches,
                else_body,
            } => {
                for b in branches {
                    self.expr(&mut b.cond, scope);
                    self.stmts(&mut b.body, scope);
                }
                if let Some(e) = else_body {
                    self.stmts(e, scope);
                }
            }
            StmtKind::Case {
                selector,
                arms,
                else_body,
            } => {
                self.expr(selector, scope);
                for a in arms {
                    for l in &mut a.labels {
                        match l {
                            CaseLabel::Value(e) => self.expr(e, scope),
                            CaseLabel::Range(lo, hi) => {
                                self.expr(lo, scope);
                                self.expr(hi, scope);
                            }
                        }
                    }
                    self.stmts(&mut a.body, scope);
                }
                if let Some(e) = else_body {
                    self.stmts(e, scope);
                }
            }
            StmtKind::For {
                from, to, by, body, ..
            } => {
                self.expr(from, scope);
                self.expr(to, scope);
                if let Some(b) = by {
                    self.expr(b, scope);
                }
                self.stmts(body, scope);
            }
            StmtKind::While { cond, body } | StmtKind::Repeat { body, until: cond } => {
                self.expr(cond, scope);
                self.stmts(body, scope);
            }
            StmtKind::Return
            | StmtKind::Exit
            | StmtKind::Continue
            | StmtKind::Empty
            | StmtKind::Label(_)
            | StmtKind::Goto(_) => {}
        }
    }

    fn expr(&mut self, e: &mut Expr, scope: &Scope) {
        // What stays above a rewritten qualified name is members only:
        // nothing more to resolve.
        if matches!(e.kind, ExprKind::Member { .. }) {
            if let Some(q) = self.qualified_member(e, scope) {
                *e = q;
                return;
            }
        }
        match &mut e.kind {
            ExprKind::Name(id) => {
                if !self.locals.contains(&id.sym) {
                    if let Some(f) = self.resolve_simple(scope, *id) {
                        id.sym = f;
                    }
                }
            }
            ExprKind::Member { base, .. } => self.expr(base, scope),
            ExprKind::Literal(l) => {
                if let Some(t) = &mut l.ty {
                    self.type_name(scope, t);
                }
            }
            ExprKind::Partial { base, .. } | ExprKind::Deref(base) | ExprKind::Paren(base) => {
                self.expr(base, scope)
            }
            ExprKind::Index { base, indices } => {
                self.expr(base, scope);
                for i in indices {
                    self.expr(i, scope);
                }
            }
            ExprKind::Unary { operand, .. } => self.expr(operand, scope),
            ExprKind::Binary { lhs, rhs, .. } => {
                self.expr(lhs, scope);
                self.expr(rhs, scope);
            }
            ExprKind::Call { callee, args } => {
                self.expr(callee, scope);
                self.args(args, scope);
            }
            ExprKind::Address(_) | ExprKind::Error => {}
        }
    }

    fn args(&mut self, args: &mut [Arg], scope: &Scope) {
        for a in args {
            if let Some(v) = &mut a.value {
                self.expr(v, scope);
            }
        }
    }

    /// `A.B.x.field…` whose longest prefix `A.B.x` names a namespace item:
    /// the same access with that prefix replaced by the item's name.
    fn qualified_member(&mut self, e: &Expr, scope: &Scope) -> Option<Expr> {
        // The chain of members down to its root name, outermost first.
        let mut members: Vec<(Ident, Span)> = Vec::new();
        let mut cur = e;
        let root = loop {
            match &cur.kind {
                ExprKind::Member { base, member } => {
                    members.push((*member, cur.span));
                    cur = base;
                }
                ExprKind::Name(id) => break *id,
                _ => return None,
            }
        };
        if self.locals.contains(&root.sym) {
            return None;
        }
        members.reverse();
        let mut parts = vec![root.sym];
        parts.extend(members.iter().map(|(m, _)| m.sym));
        for j in (2..=parts.len()).rev() {
            let Some(flat) = self.resolve_qualified(scope, &parts[..j]) else {
                continue;
            };
            let (_, head_span) = members[j - 2];
            self.check_internal(flat, scope, head_span);
            let mut out = Expr {
                kind: ExprKind::Name(Ident {
                    sym: flat,
                    span: head_span,
                }),
                span: head_span,
            };
            for (m, span) in &members[j - 1..] {
                out = Expr {
                    kind: ExprKind::Member {
                        base: Box::new(out),
                        member: *m,
                    },
                    span: *span,
                };
            }
            return Some(out);
        }
        None
    }
}

/// The names a POU's (or method's) declarations make local, which hide
/// namespace items; VAR_EXTERNAL names a global and hides nothing.
fn locals_of(blocks: &[VarBlock]) -> HashSet<Symbol> {
    blocks
        .iter()
        .filter(|b| b.kind != VarKind::External)
        .flat_map(|b| b.decls.iter().flat_map(|d| d.names.iter().map(|n| n.sym)))
        .collect()
}
