//! Object orientation (IEC 61131-3 3rd edition) rewritten into plain POUs,
//! so that checking, lowering and both engines see ordinary code.
//!
//! The rules (see `docs/object-orientation.md` for the user's view):
//! - A class (a FUNCTION_BLOCK with methods, EXTENDS or IMPLEMENTS, or a
//!   CLASS) becomes a FUNCTION_BLOCK of the same name whose variables are
//!   its bases' (outermost base first) then its own. Its body is its own
//!   statements, or, when it has none, its nearest base's; `SUPER^();` in a
//!   body runs the base's body there.
//! - Every method of a class, its own or inherited, becomes one FUNCTION
//!   `__M_<class>__<method>` whose first parameter is the VAR_IN_OUT
//!   `__THIS : <class>`; the method's VAR are the function's (initialised at
//!   each call, as the standard says). A method inherited from a base is
//!   compiled again for each derived class, so a call made inside it (`m()`,
//!   `THIS^.m()`) reaches the derived class's override: dispatch is static
//!   per compiled copy and therefore exact. `SUPER^.m()` calls the copy of
//!   the base's implementation compiled for the same class.
//! - A property's GET is `__PG_<class>__<prop>` (the property's name is the
//!   result), its SET `__PS_<class>__<prop>` (the name is the input).
//! - An interface `I` becomes the structure `__ITF_I` holding the class
//!   number `__id` (0: no instance) and one `REF_TO` per class implementing
//!   it; a call `itf.m()` goes through `__ID_I__m`, a CASE on `__id` (with no
//!   instance it dereferences a NULL reference: the runtime's fault). An
//!   assignment of an instance to an interface variable (or as an input)
//!   calls `__IC_I__<class>(REF(instance))`.
//!
//! Every misuse is reported here, at the source's names (E200–E213).

use crate::ast::oop::{Class, ClassKind, Interface, Method, Visibility};
use crate::ast::{
    Arg, ArgDir, BinaryOp, Body, CaseArm, CaseLabel, Expr, ExprKind, Ident, Item, Lang, LitKind,
    Literal, Pou, PouKind, SourceUnit, Stmt, StmtKind, TypeBlock, TypeDecl, TypeSpec, VarBlock,
    VarDecl, VarKind,
};
use automat_base::{Code, Diagnostic, Interner, Span, Symbol};
use std::collections::{HashMap, HashSet};

/// Rewrites the classes and interfaces of the whole project (every unit)
/// into plain items, appended to the unit that declared them; the classes
/// and interfaces stay, marked `desugared` (later stages ignore them).
pub fn desugar_oop(units: &mut [SourceUnit], interner: &mut Interner) -> Vec<Diagnostic> {
    crate::desugar::eno::implicit_eno(units, interner);
    promote_bases(units);
    let mut classes: HashMap<Symbol, (usize, Class)> = HashMap::new();
    let mut itfs: HashMap<Symbol, (usize, Interface)> = HashMap::new();
    let mut order: Vec<Symbol> = Vec::new();
    let mut diags = Vec::new();
    for (u, unit) in units.iter().enumerate() {
        for item in &unit.items {
            match item {
                Item::Class(c) if !c.desugared => {
                    if classes.contains_key(&c.name.sym) {
                        diags.push(Diagnostic::error(
                            Code::E209,
                            c.name.span,
                            format!("class `{}` is declared twice", interner.name(c.name.sym)),
                        ));
                        continue;
                    }
                    order.push(c.name.sym);
                    classes.insert(c.name.sym, (u, (**c).clone()));
                }
                Item::Interface(i) if !i.desugared => {
                    itfs.insert(i.name.sym, (u, (**i).clone()));
                }
                _ => {}
            }
        }
    }
    if classes.is_empty() && itfs.is_empty() {
        return diags;
    }
    let mut d = Oop::new(interner, &classes, &itfs, &order);
    d.check_classes();
    d.check_interfaces();
    // Each class gets its own copy of every inherited method: bound the total.
    let copies: usize = order.iter().map(|c| d.all_methods(*c).len()).sum();
    let bytes: u64 = order
        .iter()
        .flat_map(|c| d.all_methods(*c))
        .map(|(_, _, m)| u64::from(m.span.end.saturating_sub(m.span.start)))
        .sum();
    if bytes > MAX_COPIED_BYTES {
        if let Some((_, c)) = order.first().and_then(|s| classes.get(s)) {
            d.err(
                Code::E213,
                c.name.span,
                format!("the classes of this project would copy {bytes} bytes of inherited method text, more than {MAX_COPIED_BYTES}"),
            );
        }
        d.broken.extend(order.iter().copied());
    } else if copies > MAX_METHOD_COPIES {
        if let Some((_, c)) = order.first().and_then(|s| classes.get(s)) {
            d.err(
                Code::E213,
                c.name.span,
                format!("the classes of this project need {copies} method bodies with their inherited methods, more than {MAX_METHOD_COPIES}"),
            );
        }
        d.broken.extend(order.iter().copied());
    }
    let mut out: Vec<(usize, Item)> = Vec::new();
    // Plain POUs first: their bodies and declarations see classes too.
    d.pou_params = collect_params(units);
    collect_names(units, &mut d.types, &mut d.pou_vars, &mut d.globals);
    for unit in units.iter_mut() {
        for item in &mut unit.items {
            match item {
                Item::Pou(p) => d.rewrite_pou(p),
                Item::Globals(b) => d.retype_block(b),
                Item::Config(c) => {
                    for b in &mut c.globals {
                        d.retype_block(b);
                    }
                    for r in &mut c.resources {
                        for b in &mut r.globals {
                            d.retype_block(b);
                        }
                    }
                }
                Item::Types(t) => {
                    for decl in &mut t.decls {
                        if let TypeSpec::Struct { members, .. } = &mut decl.spec {
                            for m in members {
                                d.retype_decl(m, VarKind::Local);
                            }
                        }
                    }
                }
                Item::Class(c) => c.desugared = true,
                Item::Interface(i) => i.desugared = true,
            }
        }
    }
    for sym in order.clone() {
        if let Some((u, _)) = classes.get(&sym) {
            for item in d.class_items(sym) {
                out.push((*u, item));
            }
        }
    }
    for (sym, (u, _)) in itfs.iter() {
        for item in d.interface_items(*sym) {
            out.push((*u, item));
        }
    }
    diags.append(&mut d.diags);
    for (u, item) in out {
        if let Some(unit) = units.get_mut(u) {
            unit.items.push(item);
        }
    }
    diags
}

/// Bases of a class, at most.
const MAX_INHERITANCE: usize = 64;
/// Compiled method bodies (own and inherited, per class), at most.
const MAX_METHOD_COPIES: usize = 50_000;
/// Source text of those bodies, at most.
const MAX_COPIED_BYTES: u64 = 64 << 20;
/// Statements copied into bodies by `SUPER^();`, at most.
const MAX_INLINED: usize = 100_000;

/// A plain FUNCTION_BLOCK named after `EXTENDS` becomes a class (with no
/// methods), so that it can be a base.
fn promote_bases(units: &mut [SourceUnit]) {
    let mut bases = HashSet::new();
    for unit in units.iter() {
        for item in &unit.items {
            if let Item::Class(c) = item {
                if let (false, Some(b)) = (c.desugared, c.extends) {
                    bases.insert(b.sym);
                }
            }
        }
    }
    if bases.is_empty() {
        return;
    }
    for unit in units.iter_mut() {
        for item in &mut unit.items {
            let Item::Pou(p) = item else { continue };
            if p.kind != PouKind::FunctionBlock || !bases.contains(&p.name.sym) {
                continue;
            }
            let Body::St(body) = &p.body;
            *item = Item::Class(Box::new(Class {
                kind: ClassKind::FunctionBlock,
                name: p.name,
                is_abstract: false,
                is_final: false,
                extends: None,
                implements: Vec::new(),
                var_blocks: std::mem::take(&mut p.var_blocks),
                methods: Vec::new(),
                properties: Vec::new(),
                body: body.clone(),
                span: p.span,
                desugared: false,
            }));
        }
    }
}

/// Input and in-out parameter types of every plain POU (for interface
/// conversions of call arguments).
fn collect_params(units: &[SourceUnit]) -> HashMap<Symbol, Vec<(Symbol, TypeSpec)>> {
    let mut out = HashMap::new();
    for unit in units {
        for item in &unit.items {
            if let Item::Pou(p) = item {
                let mut v = Vec::new();
                for b in &p.var_blocks {
                    if matches!(b.kind, VarKind::Input | VarKind::InOut) {
                        for decl in &b.decls {
                            for n in &decl.names {
                                v.push((n.sym, decl.ty.clone()));
                            }
                        }
                    }
                }
                out.insert(p.name.sym, v);
            }
        }
    }
    out
}

fn collect_names(
    units: &[SourceUnit],
    types: &mut HashMap<Symbol, TypeSpec>,
    pou_vars: &mut HashMap<Symbol, HashMap<Symbol, TypeSpec>>,
    globals: &mut HashMap<Symbol, TypeSpec>,
) {
    let add_block = |b: &VarBlock, into: &mut HashMap<Symbol, TypeSpec>| {
        for decl in &b.decls {
            for n in &decl.names {
                into.insert(n.sym, decl.ty.clone());
            }
        }
    };
    for unit in units {
        for item in &unit.items {
            match item {
                Item::Pou(p) => {
                    let mut v = HashMap::new();
                    for b in &p.var_blocks {
                        add_block(b, &mut v);
                    }
                    pou_vars.insert(p.name.sym, v);
                }
                Item::Types(t) => {
                    for d in &t.decls {
                        types.insert(d.name.sym, d.spec.clone());
                    }
                }
                Item::Globals(b) => add_block(b, globals),
                Item::Config(c) => {
                    for b in &c.globals {
                        add_block(b, globals);
                    }
                    for r in &c.resources {
                        for b in &r.globals {
                            add_block(b, globals);
                        }
                    }
                }
                Item::Class(_) | Item::Interface(_) => {}
            }
        }
    }
}

/// What an expression designates, as far as methods are concerned.
#[derive(Clone, Debug)]
enum T {
    Class(Symbol),
    Itf(Symbol),
    Struct(Vec<VarDecl>),
    Array(TypeSpec),
    Ref(TypeSpec),
    /// A plain function block or program: its variables.
    Pou(Symbol),
    Other,
}

/// Where a body is rewritten.
#[derive(Clone)]
struct Ctx {
    /// The class the code is compiled for (the dynamic class of THIS).
    class: Option<Symbol>,
    /// The class whose source the code is (SUPER is its base).
    defined_in: Option<Symbol>,
    /// In a method or accessor: `__THIS`; in a body: `__SELF`.
    in_method: bool,
    /// Names of the local variables (parameters, VAR, VAR_TEMP) and their types.
    locals: HashMap<Symbol, TypeSpec>,
    /// The method's (or GET's) own name and the function it became.
    result: Option<(Symbol, Symbol)>,
}

struct Oop<'a> {
    interner: &'a mut Interner,
    classes: &'a HashMap<Symbol, (usize, Class)>,
    itfs: &'a HashMap<Symbol, (usize, Interface)>,
    order: &'a [Symbol],
    diags: Vec<Diagnostic>,
    /// Class number (1-based) for interface values.
    ids: HashMap<Symbol, u32>,
    /// Classes whose inheritance chain is broken (no code is generated for them).
    broken: HashSet<Symbol>,
    /// Classes that miss (or mistype) a method of an interface they implement.
    bad_impl: HashSet<Symbol>,
    /// Statements copied by `SUPER^();` so far.
    inlined: usize,
    /// Copies of base implementations needed by SUPER^.m(): (class, base, method).
    supers: Vec<(Symbol, Symbol, Symbol)>,
    pou_params: HashMap<Symbol, Vec<(Symbol, TypeSpec)>>,
    /// TYPE declarations, every variable of every plain POU, the globals (as written).
    types: HashMap<Symbol, TypeSpec>,
    pou_vars: HashMap<Symbol, HashMap<Symbol, TypeSpec>>,
    globals: HashMap<Symbol, TypeSpec>,
    this: Symbol,
    self_: Symbol,
    depth: u32,
}

impl<'a> Oop<'a> {
    fn new(
        interner: &'a mut Interner,
        classes: &'a HashMap<Symbol, (usize, Class)>,
        itfs: &'a HashMap<Symbol, (usize, Interface)>,
        order: &'a [Symbol],
    ) -> Oop<'a> {
        let ids = order
            .iter()
            .enumerate()
            .map(|(i, s)| (*s, i as u32 + 1))
            .collect();
        let this = interner.intern("__THIS");
        let self_ = interner.intern("__SELF");
        Oop {
            interner,
            classes,
            itfs,
            order,
            diags: Vec::new(),
            ids,
            broken: HashSet::new(),
            bad_impl: HashSet::new(),
            inlined: 0,
            supers: Vec::new(),
            pou_params: HashMap::new(),
            types: HashMap::new(),
            pou_vars: HashMap::new(),
            globals: HashMap::new(),
            this,
            self_,
            depth: 0,
        }
    }

    fn name(&self, s: Symbol) -> String {
        self.interner.name(s).to_string()
    }

    fn err(&mut self, code: Code, span: Span, msg: String) {
        self.diags.push(Diagnostic::error(code, span, msg));
    }

    fn sym(&mut self, s: &str) -> Symbol {
        self.interner.intern(s)
    }

    fn class(&self, s: Symbol) -> Option<&'a Class> {
        self.classes.get(&s).map(|(_, c)| c)
    }

    fn itf(&self, s: Symbol) -> Option<&'a Interface> {
        self.itfs.get(&s).map(|(_, i)| i)
    }

    /// The class and its bases, outermost base last; `None` when the chain
    /// is broken (reported by `check_classes`).
    fn chain(&self, s: Symbol) -> Vec<Symbol> {
        let mut out = vec![s];
        let mut cur = s;
        while let Some(b) = self.class(cur).and_then(|c| c.extends) {
            // Past the limit the class is refused (E213): stop looking.
            if out.len() > MAX_INHERITANCE + 1
                || out.contains(&b.sym)
                || self.class(b.sym).is_none()
            {
                break;
            }
            out.push(b.sym);
            cur = b.sym;
        }
        out
    }

    fn derives_from(&self, c: Symbol, base: Symbol) -> bool {
        self.chain(c).contains(&base)
    }

    /// The implementation of method `m` seen from class `c`: (defining class, method).
    fn method_of(&self, c: Symbol, m: Symbol) -> Option<(Symbol, &'a Method)> {
        for k in self.chain(c) {
            if let Some(meth) = self.class(k)?.methods.iter().find(|x| x.name.sym == m) {
                return Some((k, meth));
            }
        }
        None
    }

    fn property_of(&self, c: Symbol, p: Symbol) -> Option<(Symbol, &'a crate::ast::oop::Property)> {
        for k in self.chain(c) {
            if let Some(prop) = self.class(k)?.properties.iter().find(|x| x.name.sym == p) {
                return Some((k, prop));
            }
        }
        None
    }

    /// Every method name visible on class `c`, each with its implementation.
    fn all_methods(&self, c: Symbol) -> Vec<(Symbol, Symbol, &'a Method)> {
        let mut seen = HashSet::new();
        let mut out = Vec::new();
        for k in self.chain(c) {
            if let Some(cl) = self.class(k) {
                for m in &cl.methods {
                    if seen.insert(m.name.sym) {
                        out.push((m.name.sym, k, m));
                    }
                }
            }
        }
        out
    }

    /// The interfaces `i` extends, itself included.
    fn itf_chain(&self, i: Symbol) -> Vec<Symbol> {
        let mut out = vec![i];
        let mut k = 0;
        while let Some(&cur) = out.get(k) {
            if let Some(it) = self.itf(cur) {
                for e in &it.extends {
                    if !out.contains(&e.sym) && self.itf(e.sym).is_some() {
                        out.push(e.sym);
                    }
                }
            }
            k += 1;
        }
        out
    }

    fn itf_method(&self, i: Symbol, m: Symbol) -> Option<&'a Method> {
        self.itf_chain(i)
            .into_iter()
            .filter_map(|k| self.itf(k))
            .find_map(|it| it.methods.iter().find(|x| x.name.sym == m))
    }

    /// Interfaces class `c` implements (through its bases and interface EXTENDS).
    fn implements(&self, c: Symbol, i: Symbol) -> bool {
        self.chain(c).into_iter().any(|k| {
            self.class(k).is_some_and(|cl| {
                cl.implements
                    .iter()
                    .any(|x| self.itf_chain(x.sym).contains(&i))
            })
        })
    }

    fn implementors(&self, i: Symbol) -> Vec<Symbol> {
        self.order
            .iter()
            .copied()
            .filter(|c| !self.broken.contains(c) && !self.bad_impl.contains(c))
            .filter(|c| self.implements(*c, i))
            .filter(|c| !self.class(*c).is_some_and(|x| x.is_abstract))
            .collect()
    }

    // ---- the rules ----

    fn check_classes(&mut self) {
        for &c in self.order {
            let Some(cl) = self.class(c) else { continue };
            // Bases.
            let mut seen = vec![c];
            let mut cur = cl;
            while let Some(b) = cur.extends {
                if seen.len() > MAX_INHERITANCE {
                    break;
                }
                match self.class(b.sym) {
                    None => {
                        // Reported once, at the class that names it.
                        if cur.name.sym == c {
                            let n = self.name(b.sym);
                            self.err(Code::E200, b.span, format!("`{n}` is not a function block or class with which `EXTENDS` can be used here"));
                        }
                        self.broken.insert(c);
                        break;
                    }
                    Some(base) => {
                        if seen.contains(&b.sym) {
                            if cur.name.sym == c || b.sym == c {
                                let n = self.name(c);
                                self.err(
                                    Code::E202,
                                    cl.name.span,
                                    format!("`{n}` extends itself through its bases"),
                                );
                            }
                            self.broken.insert(c);
                            break;
                        }
                        if cur.name.sym == c {
                            if base.is_final {
                                let (n, bn) = (self.name(c), self.name(b.sym));
                                self.err(
                                    Code::E201,
                                    b.span,
                                    format!("`{n}` cannot extend `{bn}`: it is FINAL"),
                                );
                            }
                            if base.kind != cl.kind {
                                let n = self.name(b.sym);
                                self.err(
                                    Code::E200,
                                    b.span,
                                    format!(
                                        "`{n}` is a {} and cannot be the base of a {}",
                                        kind_name(base.kind),
                                        kind_name(cl.kind)
                                    ),
                                );
                            }
                        }
                        seen.push(b.sym);
                        cur = base;
                    }
                }
            }
            if !self.broken.contains(&c) && self.chain(c).len() > MAX_INHERITANCE + 1 {
                let n = self.name(c);
                self.err(
                    Code::E213,
                    cl.name.span,
                    format!("`{n}` has more than {MAX_INHERITANCE} levels of bases"),
                );
                self.broken.insert(c);
            }
            // Methods and properties of the class itself.
            let mut names: HashSet<Symbol> = HashSet::new();
            for b in &cl.var_blocks {
                for decl in &b.decls {
                    names.extend(decl.names.iter().map(|n| n.sym));
                }
            }
            for m in &cl.methods {
                if !names.insert(m.name.sym) {
                    let n = self.name(m.name.sym);
                    self.err(
                        Code::E209,
                        m.name.span,
                        format!("`{n}` is declared twice in `{}`", self.name(c)),
                    );
                }
                if m.is_abstract && !m.body.is_empty() {
                    let n = self.name(m.name.sym);
                    self.err(
                        Code::E203,
                        m.name.span,
                        format!("the ABSTRACT method `{n}` cannot have a body"),
                    );
                }
                if m.is_abstract && !cl.is_abstract {
                    let n = self.name(m.name.sym);
                    self.err(
                        Code::E203,
                        m.name.span,
                        format!(
                            "`{}` declares the ABSTRACT method `{n}` but is not ABSTRACT itself",
                            self.name(c)
                        ),
                    );
                }
                let base = cl
                    .extends
                    .map(|b| b.sym)
                    .filter(|_| !self.broken.contains(&c));
                let inherited = base.and_then(|b| self.method_of(b, m.name.sym));
                match inherited {
                    Some((k, bm)) if bm.is_final => {
                        let n = self.name(m.name.sym);
                        self.err(
                            Code::E201,
                            m.name.span,
                            format!(
                                "`{n}` cannot be overridden: it is FINAL in `{}`",
                                self.name(k)
                            ),
                        );
                    }
                    Some(_) => {}
                    None if m.is_override => {
                        let n = self.name(m.name.sym);
                        self.err(
                            Code::E211,
                            m.name.span,
                            format!(
                                "`{n}` is marked OVERRIDE but no base of `{}` declares it",
                                self.name(c)
                            ),
                        );
                    }
                    None => {}
                }
            }
            for p in &cl.properties {
                if !names.insert(p.name.sym) {
                    let n = self.name(p.name.sym);
                    self.err(
                        Code::E209,
                        p.name.span,
                        format!("`{n}` is declared twice in `{}`", self.name(c)),
                    );
                }
            }
            if self.broken.contains(&c) {
                continue;
            }
            // Inherited abstract methods must be implemented.
            if !cl.is_abstract {
                for (m, k, meth) in self.all_methods(c) {
                    if meth.is_abstract && k != c {
                        let n = self.name(m);
                        self.err(
                            Code::E203,
                            cl.name.span,
                            format!(
                                "`{}` does not implement the ABSTRACT method `{n}` of `{}`",
                                self.name(c),
                                self.name(k)
                            ),
                        );
                    }
                }
            }
            // Interfaces.
            for i in &cl.implements {
                if self.itf(i.sym).is_none() {
                    let n = self.name(i.sym);
                    self.err(Code::E200, i.span, format!("`{n}` is not an interface"));
                    continue;
                }
                for k in self.itf_chain(i.sym) {
                    let Some(it) = self.itf(k) else { continue };
                    for im in &it.methods {
                        match self.method_of(c, im.name.sym) {
                            None => {
                                let n = self.name(im.name.sym);
                                self.bad_impl.insert(c);
                                self.err(Code::E205, i.span, format!("`{}` does not implement the method `{n}` of interface `{}`", self.name(c), self.name(k)));
                            }
                            Some((_, m)) if !same_type(&m.return_type, &im.return_type) => {
                                let n = self.name(im.name.sym);
                                self.bad_impl.insert(c);
                                self.err(
                                    Code::E205,
                                    m.name.span,
                                    format!(
                                        "`{n}` must return what interface `{}` declares",
                                        self.name(k)
                                    ),
                                );
                            }
                            _ => {}
                        }
                    }
                    for ip in &it.properties {
                        if self.property_of(c, ip.name.sym).is_none() {
                            let n = self.name(ip.name.sym);
                            self.bad_impl.insert(c);
                            self.err(
                                Code::E205,
                                i.span,
                                format!(
                                    "`{}` does not implement the property `{n}` of interface `{}`",
                                    self.name(c),
                                    self.name(k)
                                ),
                            );
                        }
                    }
                }
            }
        }
    }

    fn check_interfaces(&mut self) {
        let mut list: Vec<&Interface> = self.itfs.values().map(|(_, i)| i).collect();
        list.sort_by_key(|i| i.span.start);
        for it in list {
            for e in &it.extends {
                if self.itf(e.sym).is_none() {
                    let n = self.name(e.sym);
                    self.err(Code::E200, e.span, format!("`{n}` is not an interface"));
                } else if e.sym == it.name.sym || self.itf_chain(e.sym).contains(&it.name.sym) {
                    let n = self.name(it.name.sym);
                    self.err(
                        Code::E202,
                        e.span,
                        format!("interface `{n}` extends itself"),
                    );
                }
            }
            let mut names = HashSet::new();
            for m in &it.methods {
                if !names.insert(m.name.sym) {
                    let n = self.name(m.name.sym);
                    self.err(
                        Code::E209,
                        m.name.span,
                        format!(
                            "`{n}` is declared twice in interface `{}`",
                            self.name(it.name.sym)
                        ),
                    );
                }
            }
        }
    }

    // ---- types of expressions ----

    fn spec_t(&self, ty: &TypeSpec) -> T {
        match ty {
            TypeSpec::Named(id) => {
                if self.classes.contains_key(&id.sym) {
                    T::Class(id.sym)
                } else if self.itfs.contains_key(&id.sym) {
                    T::Itf(id.sym)
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
            TypeSpec::Ref { target, .. } => T::Ref((**target).clone()),
            _ => T::Other,
        }
    }

    fn class_var(&self, c: Symbol, n: Symbol) -> Option<TypeSpec> {
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

    fn type_of(&self, e: &Expr, cx: &Ctx) -> T {
        match &e.kind {
            ExprKind::Paren(i) => self.type_of(i, cx),
            ExprKind::Name(id) => {
                if let Some(t) = cx.locals.get(&id.sym) {
                    return self.spec_t(t);
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
            _ => T::Other,
        }
    }

    /// `THIS` / `SUPER`, unless a variable of that name is in scope.
    fn is_kw(&self, e: &Expr, w: &str, cx: &Ctx) -> bool {
        match &e.kind {
            ExprKind::Name(id) => {
                !cx.locals.contains_key(&id.sym)
                    && self.interner.name(id.sym).eq_ignore_ascii_case(w)
            }
            _ => false,
        }
    }

    fn is_word(&self, e: &Expr, w: &str) -> bool {
        matches!(&e.kind, ExprKind::Name(id) if self.interner.name(id.sym).eq_ignore_ascii_case(w))
    }

    // ---- declarations ----

    fn retype_block(&mut self, b: &mut VarBlock) {
        let kind = b.kind;
        for decl in &mut b.decls {
            self.retype_decl(decl, kind);
        }
    }

    /// Interface types become their structures; an instance of an abstract
    /// class is refused.
    fn retype_decl(&mut self, decl: &mut VarDecl, kind: VarKind) {
        self.retype_spec(&mut decl.ty, kind);
    }

    fn retype_spec(&mut self, ty: &mut TypeSpec, kind: VarKind) {
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
            // A reference may designate an instance of a derived class.
            TypeSpec::Ref { .. } => {}
            _ => {}
        }
    }

    fn locals_of(blocks: &[VarBlock]) -> HashMap<Symbol, TypeSpec> {
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

    fn rewrite_pou(&mut self, p: &mut Pou) {
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
        };
        for b in &mut p.var_blocks {
            self.retype_block(b);
        }
        if let Some(r) = &mut p.return_type {
            self.retype_spec(r, VarKind::Output);
        }
        let Body::St(stmts) = &mut p.body;
        self.stmts(stmts, &cx);
    }

    // ---- generated items ----

    fn class_items(&mut self, c: Symbol) -> Vec<Item> {
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

    fn collect_props(&mut self, c: Symbol) -> Vec<Vec<Item>> {
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

    fn method_fn(&mut self, c: Symbol, m: Symbol) -> Symbol {
        let n = format!("__M_{}__{}", self.name(c), self.name(m));
        self.sym(&n)
    }

    fn super_fn(&mut self, c: Symbol, base: Symbol, m: Symbol) -> Symbol {
        let n = format!(
            "__MS_{}__{}__{}",
            self.name(c),
            self.name(base),
            self.name(m)
        );
        self.sym(&n)
    }

    fn prop_fn(&mut self, c: Symbol, p: Symbol, get: bool) -> Symbol {
        let n = format!(
            "__P{}_{}__{}",
            if get { 'G' } else { 'S' },
            self.name(c),
            self.name(p)
        );
        self.sym(&n)
    }

    /// The FUNCTION for method `meth` (written in class `k`) compiled for class `c`.
    fn method_fn_item(&mut self, c: Symbol, k: Symbol, meth: &Method, fname: Symbol) -> Item {
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
        var_blocks.extend(meth.var_blocks.iter().cloned());
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
        let mut locals = Self::locals_of(&meth.var_blocks);
        for (n, t) in Self::locals_of(&externals) {
            locals.entry(n).or_insert(t);
        }
        let own = Self::locals_of(&meth.var_blocks);
        for b in &mut externals {
            b.decls
                .retain(|d| d.names.iter().all(|n| !own.contains_key(&n.sym)));
        }
        externals.retain(|b| !b.decls.is_empty());
        var_blocks.extend(externals);
        for b in var_blocks.iter_mut().skip(1) {
            self.retype_block(b);
        }
        let cx = Ctx {
            class: Some(c),
            defined_in: Some(k),
            in_method: true,
            locals,
            result: meth.return_type.as_ref().map(|_| (meth.name.sym, fname)),
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

    fn interface_items(&mut self, i: Symbol) -> Vec<Item> {
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
            let mut first = None;
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
                if first.is_none() {
                    first = Some(stmt.clone());
                }
                arms.push(CaseArm {
                    labels: vec![CaseLabel::Value(int_e(i128::from(
                        self.ids.get(c).copied().unwrap_or(0),
                    )))],
                    body: vec![stmt],
                    span,
                });
            }
            let body = if arms.is_empty() {
                Vec::new()
            } else {
                vec![Stmt {
                    kind: StmtKind::Case {
                        selector: member_e(name_e(osym), id_sym),
                        arms,
                        // No instance: the first class's reference is NULL,
                        // and dereferencing it is the runtime's fault.
                        else_body: first.map(|s| vec![s]),
                    },
                    span,
                }]
            };
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
            var_blocks.extend(
                m.var_blocks
                    .iter()
                    .filter(|b| b.kind != VarKind::Local && b.kind != VarKind::Temp)
                    .cloned(),
            );
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

    // ---- bodies ----

    fn stmts(&mut self, list: &mut Vec<Stmt>, cx: &Ctx) {
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
            if let Some(s) = list.get_mut(i) {
                self.stmt(s, cx);
            }
            i += 1;
        }
    }

    fn stmt(&mut self, s: &mut Stmt, cx: &Ctx) {
        if self.depth > crate::MAX_DEPTH * 2 {
            return;
        }
        self.depth += 1;
        let span = s.span;
        match &mut s.kind {
            StmtKind::Assign { target, value } => {
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
                if let T::Itf(i) = tt {
                    self.wrap_itf(value, i, cx);
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
    fn prop_target(&mut self, target: &Expr, cx: &Ctx) -> Option<(Symbol, Expr, Ident)> {
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

    fn this_expr(&self, cx: &Ctx, span: Span) -> Expr {
        let sym = if cx.in_method { self.this } else { self.self_ };
        Expr {
            kind: ExprKind::Name(Ident { sym, span }),
            span,
        }
    }

    /// Wraps `value` (of a class or another interface) into interface `i`.
    fn wrap_itf(&mut self, value: &mut Expr, i: Symbol, cx: &Ctx) {
        let span = value.span;
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
    fn type_of_rewritten(&self, e: &Expr, cx: &Ctx) -> Option<T> {
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

    fn check_access(&mut self, owner_seen: Symbol, vis: Visibility, name: Ident, cx: &Ctx) {
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
        let ok = match vis {
            Visibility::Public | Visibility::Internal => true,
            Visibility::Private => cx.defined_in == Some(owner),
            Visibility::Protected => cx.defined_in.is_some_and(|k| self.derives_from(k, owner)),
        };
        if !ok {
            let (n, o) = (self.name(name.sym), self.name(owner));
            let v = match vis {
                Visibility::Private => "PRIVATE",
                _ => "PROTECTED",
            };
            self.err(Code::E207, name.span, format!("`{n}` is {v} in `{o}`"));
        }
    }

    fn expr(&mut self, e: &mut Expr, cx: &Ctx) {
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

    fn expr_inner(&mut self, e: &mut Expr, cx: &Ctx) {
        let span = e.span;
        match &mut e.kind {
            ExprKind::Name(id) => {
                let id = *id;
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
                    if matches!(lt, T::Itf(_)) && self.is_nothing(rhs) {
                        self.expr(lhs, cx);
                        self.itf_id(lhs, rhs);
                        return;
                    }
                    if matches!(rt, T::Itf(_)) && self.is_nothing(lhs) {
                        self.expr(rhs, cx);
                        self.itf_id(rhs, lhs);
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

    /// `NULL` or the literal 0 (CODESYS writes `itf <> 0`).
    fn is_nothing(&self, e: &Expr) -> bool {
        match &e.kind {
            ExprKind::Paren(i) => self.is_nothing(i),
            ExprKind::Literal(l) => matches!(l.kind, LitKind::Int(0)) && l.ty.is_none(),
            ExprKind::Name(_) => self.is_word(e, "NULL"),
            _ => false,
        }
    }

    /// `itf` becomes `itf.__id`, `nothing` the literal 0.
    fn itf_id(&mut self, itf: &mut Expr, nothing: &mut Expr) {
        let t = std::mem::replace(
            itf,
            Expr {
                kind: ExprKind::Error,
                span: itf.span,
            },
        );
        self.itf_id_expr(t, nothing, itf);
    }

    fn itf_id_expr(&mut self, t: Expr, nothing: &mut Expr, into: &mut Expr) {
        let span = t.span;
        let id = self.sym("__id");
        *into = Expr {
            kind: ExprKind::Member {
                base: Box::new(t),
                member: Ident { sym: id, span },
            },
            span,
        };
        *nothing = Expr {
            kind: ExprKind::Literal(Box::new(Literal {
                kind: LitKind::Int(0),
                ty: None,
            })),
            span: nothing.span,
        };
    }

    /// Replaces `e` by a call of the GET of property `p` of class `c` on `this`.
    fn read_property(&mut self, e: &mut Expr, c: Symbol, this: Expr, p: Ident, cx: &Ctx) {
        let Some((_, prop)) = self.property_of(c, p.sym) else {
            return;
        };
        self.check_access(c, prop.visibility, p, cx);
        if prop.get.is_none() {
            let n = self.name(p.sym);
            self.err(Code::E210, p.span, format!("the property `{n}` has no GET"));
            return;
        }
        let f = self.prop_fn(c, p.sym, true);
        let span = e.span;
        e.kind = ExprKind::Call {
            callee: Box::new(Expr {
                kind: ExprKind::Name(Ident {
                    sym: f,
                    span: p.span,
                }),
                span: p.span,
            }),
            args: vec![Arg {
                name: Some(Ident {
                    sym: self.this,
                    span,
                }),
                dir: ArgDir::In,
                value: Some(this),
                span,
            }],
        };
    }

    fn call(&mut self, e: &mut Expr, cx: &Ctx) {
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
        let (fname, this, params): (Symbol, Option<Expr>, Vec<(Symbol, TypeSpec)>) = match target {
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
                        // An instance call of an FB-typed variable.
                        if let Some(ps) = self.pou_params.get(&fb.sym).cloned() {
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
                let Some(meth) = self.itf_method(i, m.sym) else {
                    let (n, iname) = (self.name(m.sym), self.name(i));
                    self.err(
                        Code::E206,
                        m.span,
                        format!("interface `{iname}` has no method `{n}`"),
                    );
                    return;
                };
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

    fn member_target(&mut self, base: &Expr, member: Ident, cx: &Ctx) -> Target2 {
        match self.type_of(base, cx) {
            T::Class(c) => {
                if self.class_var(c, member.sym).is_some() {
                    return Target2::Plain;
                }
                Target2::Method(c, base.clone(), member)
            }
            T::Itf(i) => Target2::Itf(i, base.clone(), member),
            _ => Target2::Plain,
        }
    }

    /// Named inputs whose parameter is an interface take class instances.
    fn convert_args(&mut self, args: &mut [Arg], params: &[(Symbol, TypeSpec)], cx: &Ctx) {
        for (k, a) in args.iter_mut().enumerate() {
            let ty = match &a.name {
                Some(n) => params
                    .iter()
                    .find(|(p, _)| *p == n.sym)
                    .map(|(_, t)| t.clone()),
                None => params.get(k).map(|(_, t)| t.clone()),
            };
            if let (Some(TypeSpec::Named(t)), Some(v), ArgDir::In) = (ty, &mut a.value, a.dir) {
                if self.itfs.contains_key(&t.sym) {
                    self.wrap_itf(v, t.sym, cx);
                }
            }
        }
    }
}

enum Target2 {
    Method(Symbol, Expr, Ident),
    Super(Symbol, Ident),
    Itf(Symbol, Expr, Ident),
    Plain,
}

fn params_of(m: &Method) -> Vec<(Symbol, TypeSpec)> {
    let mut v = Vec::new();
    for b in &m.var_blocks {
        if matches!(b.kind, VarKind::Input | VarKind::InOut) {
            for decl in &b.decls {
                for n in &decl.names {
                    v.push((n.sym, decl.ty.clone()));
                }
            }
        }
    }
    v
}

fn same_type(a: &Option<TypeSpec>, b: &Option<TypeSpec>) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(TypeSpec::Named(x)), Some(TypeSpec::Named(y))) => x.sym == y.sym,
        (Some(_), Some(_)) => true,
        _ => false,
    }
}

fn kind_name(k: ClassKind) -> &'static str {
    match k {
        ClassKind::Class => "CLASS",
        ClassKind::FunctionBlock => "FUNCTION_BLOCK",
    }
}

/// A symbol never looked up (a placeholder where a class is required but
/// the checks already reported its absence).
fn id_none() -> Symbol {
    Symbol(u32::MAX)
}
