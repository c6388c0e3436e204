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
//! - Base-class polymorphism: every class some other class EXTENDS gets a
//!   hidden interface `<B>^` (`poly_bases`; its methods are B's, with its
//!   base's `^` as EXTENDS), implemented by B and every class derived from
//!   it. A `REF_TO B` becomes that interface's structure, and so does a
//!   `VAR_IN_OUT x : B` (made an input in the same place); `r^.m()` and
//!   `x.m()` are interface calls (the override of the instance's class),
//!   `r^.f` / `x.f` of an input or output is `__BR_<B^>__f(r)^`, a CASE on
//!   the class number returning the reference to that instance's field;
//!   a property's GET/SET through them is `__BG_`/`__BS_<B^>__p`, the
//!   same CASE calling the class's `__PG_`/`__PS_`.
//!   `r^(IN := a, Q => b);` is `r^.IN := a; r^.__BODY(); b := r^.Q;`
//!   (`body_call.rs`: the root of the family has the hidden method
//!   `__BODY`, whose copy in each class runs that class's body).
//!   `REF(d)` and a reference to a derived class convert (`__IC_`); a
//!   reference to a base does not go into a reference to a derived class.
//! - Variable access: a VAR is PROTECTED unless its section says `PUBLIC`,
//!   `PRIVATE` or `INTERNAL` (`Class::var_access`). Code that may reach an
//!   PROTECTED or PRIVATE variable of another instance (`x.v`, `r^.v`)
//!   reads it as `__PF_<C>__<v>(__THIS := x)^` (`private.rs`); a PUBLIC or
//!   INTERNAL one stays `x.v`, which the checker lets any code see. A
//!   PRIVATE or INTERNAL one out of reach is E207, any other the checker's
//!   E024.
//!
//! Every misuse is reported here, at the source's names (E200–E213).

mod body;
mod body_call;
mod decls;
mod interfaces;
mod items;
mod nulltest;
mod poly;
mod private;
mod rules;
mod types;

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
    crate::desugar::reference::desugar_references(units, interner);
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
    body_call::add_body_methods(units, &mut classes, interner);
    let poly = poly_bases(&classes, &order, &mut itfs, interner);
    let mut d = Oop::new(interner, &classes, &itfs, &order);
    d.poly_class = poly.iter().map(|(c, i)| (*i, *c)).collect();
    d.poly = poly;
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
    d.returns = collect_returns(units);
    collect_names(units, &mut d.types, &mut d.pou_vars, &mut d.globals);
    let global_cx = Ctx {
        class: None,
        defined_in: None,
        in_method: false,
        locals: d.globals.clone(),
        result: None,
        pou: None,
        byref: HashSet::new(),
    };
    for unit in units.iter_mut() {
        for item in &mut unit.items {
            match item {
                Item::Pou(p) => d.rewrite_pou(p),
                Item::Globals(b) => {
                    d.itf_inits(std::slice::from_mut(b), &global_cx);
                    d.retype_block(b);
                }
                Item::Config(c) => {
                    for b in &mut c.globals {
                        d.itf_inits(std::slice::from_mut(b), &global_cx);
                        d.retype_block(b);
                    }
                    for r in &mut c.resources {
                        for b in &mut r.globals {
                            d.itf_inits(std::slice::from_mut(b), &global_cx);
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
                // Flattened before (`desugar_namespaces`).
                Item::Namespace(_) => {}
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
    // After every body: the comparisons they asked for.
    let mut k = 0;
    while let Some(&(a, b)) = d.itf_equals.get(k) {
        k += 1;
        if let Some((u, _)) = itfs.get(&a) {
            out.push((*u, d.itf_equal_fn(a, b)));
        }
    }
    let mut k = 0;
    while let Some(&a) = d.itf_nulls.get(k) {
        k += 1;
        if let Some((u, _)) = itfs.get(&a) {
            out.push((*u, d.itf_null_fn(a)));
        }
    }
    let mut k = 0;
    while let Some(&(a, b)) = d.itf_queries.get(k) {
        k += 1;
        if let Some((u, _)) = itfs.get(&a) {
            out.push((*u, d.itf_query_fn(a, b)));
        }
    }
    for (a, target, f) in std::mem::take(&mut d.itf_pointers) {
        if let Some((u, _)) = itfs.get(&a) {
            out.push((*u, d.itf_pointer_fn(a, target, f)));
        }
    }
    for (i, prop, get) in std::mem::take(&mut d.poly_props) {
        if let Some((u, _)) = itfs.get(&i) {
            if let Some(item) = d.poly_prop_fn(i, prop, get) {
                out.push((*u, item));
            }
        }
    }
    for (i, field) in std::mem::take(&mut d.poly_fields) {
        if let Some((u, _)) = itfs.get(&i) {
            if let Some(item) = d.poly_field_fn(i, field) {
                out.push((*u, item));
            }
        }
    }
    // After the `__BR_` dispatchers, which may ask for some.
    for (c, v) in std::mem::take(&mut d.private_fields) {
        if let Some((u, _)) = classes.get(&c) {
            if let Some(item) = d.private_field_fn(c, v) {
                out.push((*u, item));
            }
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

/// Every class some other class EXTENDS gets a hidden interface `<B>^`
/// (the reference to it): its methods are the class's own and, through
/// EXTENDS of its base's `^` interface, the inherited ones; the classes
/// implementing it are `B` and every class derived from it. A `REF_TO B`
/// and a `VAR_IN_OUT x : B` become that interface's structure, so a call
/// through them dispatches on the instance's class number like any
/// interface call. Returns class -> interface.
fn poly_bases(
    classes: &HashMap<Symbol, (usize, Class)>,
    order: &[Symbol],
    itfs: &mut HashMap<Symbol, (usize, Interface)>,
    interner: &mut Interner,
) -> HashMap<Symbol, Symbol> {
    let mut bases: Vec<Symbol> = Vec::new();
    for c in order {
        let mut cur = *c;
        let mut seen = vec![cur];
        while let Some(b) = classes.get(&cur).and_then(|(_, x)| x.extends) {
            if seen.len() > MAX_INHERITANCE + 1 || seen.contains(&b.sym) {
                break;
            }
            if !classes.contains_key(&b.sym) {
                break;
            }
            if !bases.contains(&b.sym) {
                bases.push(b.sym);
            }
            seen.push(b.sym);
            cur = b.sym;
        }
    }
    let mut out = HashMap::new();
    for b in &bases {
        let n = format!("{}^", interner.name(*b));
        out.insert(*b, interner.intern(&n));
    }
    for b in bases {
        let (Some((u, cl)), Some(&isym)) = (classes.get(&b), out.get(&b)) else {
            continue;
        };
        let extends = cl
            .extends
            .and_then(|e| {
                out.get(&e.sym).map(|s| Ident {
                    sym: *s,
                    span: e.span,
                })
            })
            .into_iter()
            .collect();
        itfs.insert(
            isym,
            (
                *u,
                Interface {
                    name: Ident {
                        sym: isym,
                        span: cl.name.span,
                    },
                    extends,
                    methods: cl.methods.clone(),
                    properties: Vec::new(),
                    span: cl.span,
                    desugared: true,
                },
            ),
        );
    }
    out
}

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
                var_access: Vec::new(),
                methods: Vec::new(),
                properties: Vec::new(),
                body: body.clone(),
                span: p.span,
                desugared: false,
            }));
        }
    }
}

/// A parameter as written: name, type, whether it is a VAR_IN_OUT.
type Param = (Symbol, TypeSpec, bool);

/// Input and in-out parameter types of every plain POU (for interface
/// conversions of call arguments).
fn collect_params(units: &[SourceUnit]) -> HashMap<Symbol, Vec<Param>> {
    let mut out = HashMap::new();
    for unit in units {
        for item in &unit.items {
            if let Item::Pou(p) = item {
                let mut v = Vec::new();
                for b in &p.var_blocks {
                    if matches!(b.kind, VarKind::Input | VarKind::InOut) {
                        for decl in &b.decls {
                            for n in &decl.names {
                                v.push((n.sym, decl.ty.clone(), b.kind == VarKind::InOut));
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

fn collect_returns(units: &[SourceUnit]) -> HashMap<Symbol, TypeSpec> {
    let mut out = HashMap::new();
    for unit in units {
        for item in &unit.items {
            if let Item::Pou(Pou {
                kind: PouKind::Function,
                name,
                return_type: Some(t),
                ..
            }) = item
            {
                out.insert(name.sym, t.clone());
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
                Item::Class(_) | Item::Interface(_) | Item::Namespace(_) => {}
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
    /// In a plain POU's body: its name (INTERNAL members are visible in
    /// the namespace of `pou` or else of `defined_in`).
    pou: Option<Symbol>,
    /// VAR_IN_OUT of a base class (now references through `<B>^`): written
    /// as instances (`x.m()`, `x.field`).
    byref: HashSet<Symbol>,
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
    pou_params: HashMap<Symbol, Vec<Param>>,
    /// A class some other class EXTENDS -> its hidden interface `<B>^`.
    poly: HashMap<Symbol, Symbol>,
    /// The reverse: `<B>^` -> `B`.
    poly_class: HashMap<Symbol, Symbol>,
    /// `__BR_<B^>__<field>` functions asked for by `r^.field`, in the order first met.
    poly_fields: Vec<(Symbol, Symbol)>,
    /// `__BG_`/`__BS_<B^>__<prop>` accessor dispatchers asked for (interface, property, GET).
    poly_props: Vec<(Symbol, Symbol, bool)>,
    /// `__PF_<C>__<v>` functions (class, internal variable) asked for by a
    /// class's code reaching another instance's internal variable.
    private_fields: Vec<(Symbol, Symbol)>,
    /// `__ITF_<I>` -> `I` (declarations already retyped).
    itf_structs: HashMap<Symbol, Symbol>,
    /// The result type of every plain FUNCTION, as written.
    returns: HashMap<Symbol, TypeSpec>,
    /// Pairs of interfaces compared by `__IE_<A>__<B>` (values that are not
    /// two places of one interface), in the order first met.
    itf_equals: Vec<(Symbol, Symbol)>,
    /// Interfaces whose values that are not places are compared to NULL
    /// (`__IZ_<A>`), in the order first met.
    itf_nulls: Vec<Symbol>,
    /// Pairs (source, destination) of `__QUERYINTERFACE` calls (`__IQ_`).
    itf_queries: Vec<(Symbol, Symbol)>,
    /// `__QUERYPOINTER` calls: (source interface, pointer target type as
    /// written, generated function name).
    itf_pointers: Vec<(Symbol, TypeSpec, Symbol)>,
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
        let itf_structs = itfs
            .keys()
            .map(|i| {
                let n = format!("__ITF_{}", interner.name(*i));
                (interner.intern(&n), *i)
            })
            .collect();
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
            poly: HashMap::new(),
            poly_class: HashMap::new(),
            poly_fields: Vec::new(),
            poly_props: Vec::new(),
            private_fields: Vec::new(),
            itf_structs,
            returns: HashMap::new(),
            itf_equals: Vec::new(),
            itf_nulls: Vec::new(),
            itf_queries: Vec::new(),
            itf_pointers: Vec::new(),
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
    /// The VAR_INPUT and VAR_IN_OUT of a class and its bases, as written.
    fn class_inputs(&self, c: Symbol) -> Vec<Param> {
        let mut v = Vec::new();
        for k in self.chain(c).iter().rev() {
            let Some(kc) = self.class(*k) else { continue };
            for b in &kc.var_blocks {
                if matches!(b.kind, VarKind::Input | VarKind::InOut) {
                    for decl in &b.decls {
                        for n in &decl.names {
                            v.push((n.sym, decl.ty.clone(), b.kind == VarKind::InOut));
                        }
                    }
                }
            }
        }
        v
    }

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
        if let Some(b) = self.poly_class.get(&i) {
            return self.derives_from(c, *b);
        }
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
            // A class missing an ABSTRACT method's implementation (E203)
            // has no copy of it to dispatch to.
            .filter(|c| {
                !self.poly_class.contains_key(&i)
                    || self.all_methods(*c).iter().all(|(_, _, m)| !m.is_abstract)
            })
            .collect()
    }
}

enum Target2 {
    Method(Symbol, Expr, Ident),
    Super(Symbol, Ident),
    Itf(Symbol, Expr, Ident),
    Plain,
}

fn params_of(m: &Method) -> Vec<Param> {
    let mut v = Vec::new();
    for b in &m.var_blocks {
        if matches!(b.kind, VarKind::Input | VarKind::InOut) {
            for decl in &b.decls {
                for n in &decl.names {
                    v.push((n.sym, decl.ty.clone(), b.kind == VarKind::InOut));
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

/// The word of an access specifier, for messages.
fn access_word(v: Visibility) -> &'static str {
    match v {
        Visibility::Public => "PUBLIC",
        Visibility::Private => "PRIVATE",
        Visibility::Protected => "PROTECTED",
        Visibility::Internal => "INTERNAL",
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
