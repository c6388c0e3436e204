//! Phase 1: declarations. Collects every POU, type and global of the
//! project, resolves written types to [`TypeId`]s, folds the constants that
//! declarations depend on, checks initial values and locations, and builds
//! the declaration part of the [`Model`].
//!
//! Invariants:
//! - Resolution is on demand and memoised: a named type, or a variable whose
//!   value an array bound needs, is resolved when first asked for, so
//!   declarations may appear in any order and in any file.
//! - A slot being resolved is marked in progress; asking for it again is a
//!   cycle and is reported (E027 for types, E070 for constants), never a
//!   stack overflow. Recursion depth is bounded ([`MAX_DEPTH`]).
//! - Every declaration is resolved exactly once, whatever asks first, so
//!   every diagnostic about it is emitted once.

mod collect;
mod cycles;
mod fold;
mod init;
pub(crate) mod location;
mod typeres;
mod vars;

use crate::model::{AstRef, Config, Model, Pou, Resource, Section, Var, VarTable};
use crate::names::Syms;
use crate::types::{PouId, TypeId, TypeTable};
use crate::value::Init;
use automat_base::{Diagnostic, Interner, Symbol};
use automat_syntax::ast::{self, Ident, SourceUnit};
use rustc_hash::FxHashMap;

/// The last name of a path (`Res.Inst.var` → `var`), for messages.
fn path_ident(e: &ast::Expr) -> Option<Ident> {
    match &e.kind {
        ast::ExprKind::Name(i) => Some(*i),
        ast::ExprKind::Member { member, .. } => Some(*member),
        ast::ExprKind::Index { base, .. } => path_ident(base),
        _ => None,
    }
}

/// Deepest chain of declarations resolved through one another.
pub(crate) const MAX_DEPTH: u32 = 100;

/// A named type declaration and its resolution state.
pub(crate) struct TypeSlot<'a> {
    decl: &'a ast::TypeDecl,
    state: TypeState,
}

#[derive(Clone)]
enum TypeState {
    Pending,
    /// Being resolved; structures and enumerations already have their id
    /// (so `REF_TO` the type itself works).
    InProgress(Option<TypeId>),
    Done(TypeId, Option<Init>),
}

/// Who declares the variables of a scope.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Owner {
    Project,
    Pou(PouId),
    Config(usize),
    Resource(usize, usize),
}

/// The variables of one POU, global list, configuration or resource.
pub(crate) struct Scope<'a> {
    parent: Option<usize>,
    owner: Owner,
    slots: Vec<VarSlot<'a>>,
    /// The resolved variables, index for index with `slots`.
    vars: Vec<Option<Var>>,
    by_name: FxHashMap<Symbol, u32>,
}

pub(crate) struct VarSlot<'a> {
    name: Ident,
    block: &'a ast::VarBlock,
    decl: &'a ast::VarDecl,
    /// The slot of the first name of the same declaration (`a, b : T`
    /// resolve `T` once).
    first: u32,
    state: SlotState,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum SlotState {
    Pending,
    InProgress,
    /// Resolved (the variable is in [`Scope::vars`]); `poisoned` when its
    /// initial value was in error.
    Done {
        poisoned: bool,
    },
}

pub(crate) struct PouEntry<'a> {
    ast: &'a ast::Pou,
    aref: AstRef,
    builtin: bool,
    scope: usize,
    instance_type: Option<TypeId>,
    return_type: Option<TypeId>,
}

pub(crate) struct ConfigEntry<'a> {
    pub ast: &'a ast::Configuration,
    pub scope: usize,
    pub resources: Vec<usize>,
    /// The declared types of the VAR_ACCESS entries.
    pub access_types: Vec<TypeId>,
    /// The declared types and initial values of the VAR_CONFIG entries.
    pub var_config: Vec<(TypeId, Option<Init>)>,
}

/// What phase 3 needs of a configuration besides the model.
pub(crate) struct ConfigDecls<'a> {
    pub ast: &'a ast::Configuration,
    pub access_types: Vec<TypeId>,
    pub var_config: Vec<(TypeId, Option<Init>)>,
}

pub(crate) struct Builder<'a> {
    interner: &'a Interner,
    syms: Syms,
    types: TypeTable,
    diags: Vec<Diagnostic>,
    type_slots: FxHashMap<Symbol, TypeSlot<'a>>,
    type_order: Vec<Symbol>,
    /// Enumeration value → the named enumerations declaring it (resolved on demand).
    enum_decls: FxHashMap<Symbol, Vec<Symbol>>,
    /// Enumeration value → every enumeration built so far declaring it.
    enum_values: FxHashMap<Symbol, Vec<TypeId>>,
    /// Values of the enumeration being built, usable in its later values.
    enum_in_progress: Vec<(Symbol, i128, crate::types::Elem)>,
    pous: Vec<PouEntry<'a>>,
    pou_names: FxHashMap<Symbol, PouId>,
    scopes: Vec<Scope<'a>>,
    /// Every global variable by name: project, configuration and resource
    /// globals, and the VAR_GLOBAL of programs (built after collection).
    globals_by_name: FxHashMap<Symbol, Vec<(usize, u32)>>,
    configs: Vec<ConfigEntry<'a>>,
    depth: u32,
    /// The section of the variable whose initial value is being checked
    /// (a `REF(x)` initial value is refused in VAR_TEMP and VAR_IN_OUT).
    init_section: Option<Section>,
    /// Names of the `CLASS`es (see `Model::classes`).
    classes: rustc_hash::FxHashSet<automat_base::Symbol>,
    /// See `Model::public_vars`.
    public_vars: rustc_hash::FxHashSet<(automat_base::Symbol, automat_base::Symbol)>,
}

/// The result of phase 1: the model without bodies checked, the
/// configurations' ASTs for phase 3, and the diagnostics so far.
pub(crate) struct Declared<'a> {
    pub model: Model,
    pub configs: Vec<ConfigDecls<'a>>,
    pub diags: Vec<Diagnostic>,
}

/// Runs phase 1 over the user units and the parsed standard library.
pub(crate) fn declare<'a>(
    units: &'a [SourceUnit],
    stdlib: &'a SourceUnit,
    interner: &'a Interner,
    syms: Syms,
) -> Declared<'a> {
    let mut b = Builder {
        interner,
        syms,
        types: TypeTable::new(),
        diags: Vec::new(),
        type_slots: FxHashMap::default(),
        type_order: Vec::new(),
        enum_decls: FxHashMap::default(),
        enum_values: FxHashMap::default(),
        enum_in_progress: Vec::new(),
        pous: Vec::new(),
        pou_names: FxHashMap::default(),
        scopes: vec![Scope {
            parent: None,
            owner: Owner::Project,
            slots: Vec::new(),
            vars: Vec::new(),
            by_name: FxHashMap::default(),
        }],
        globals_by_name: FxHashMap::default(),
        configs: Vec::new(),
        depth: 0,
        init_section: None,
        classes: rustc_hash::FxHashSet::default(),
        public_vars: rustc_hash::FxHashSet::default(),
    };
    b.collect(units, stdlib);
    b.index_globals();
    for i in 0..b.type_order.len() {
        if let Some(&name) = b.type_order.get(i) {
            b.resolve_named(name, None, false);
        }
    }
    for p in 0..b.pous.len() {
        b.resolve_return_type(p);
    }
    for s in 0..b.scopes.len() {
        let n = b.scopes.get(s).map_or(0, |sc| sc.slots.len());
        for i in 0..n {
            b.resolve_slot(s, i as u32);
        }
    }
    b.match_externals();
    b.resolve_config_decls();
    b.finish()
}

impl<'a> Builder<'a> {
    fn index_globals(&mut self) {
        for (s, sc) in self.scopes.iter().enumerate() {
            let in_pou = matches!(sc.owner, Owner::Pou(_));
            for (i, slot) in sc.slots.iter().enumerate() {
                if !in_pou || slot.block.kind == ast::VarKind::Global {
                    self.globals_by_name
                        .entry(slot.name.sym)
                        .or_default()
                        .push((s, i as u32));
                }
            }
        }
    }

    /// Types of VAR_ACCESS and VAR_CONFIG entries (their paths are checked in phase 3).
    fn resolve_config_decls(&mut self) {
        for c in 0..self.configs.len() {
            let Some(entry) = self.configs.get(c) else {
                continue;
            };
            let (ast, scope) = (entry.ast, entry.scope);
            let access: Vec<TypeId> = ast
                .access
                .iter()
                .map(|a| {
                    self.resolve_spec(&a.ty, scope, typeres::SpecCtx::default())
                        .0
                })
                .collect();
            let mut var_config = Vec::with_capacity(ast.var_config.len());
            for vc in &ast.var_config {
                let (t, _) = self.resolve_spec(&vc.ty, scope, typeres::SpecCtx::default());
                let name = path_ident(&vc.path);
                let init = match (&vc.init, name) {
                    (Some(i), Some(n)) => self.check_init(i, t, scope, n),
                    _ => None,
                };
                if let (Some(loc), Some(n)) = (&vc.location, name) {
                    if loc.addr.partial {
                        self.emit(Diagnostic::error(
                            automat_base::Code::E084,
                            loc.addr.span,
                            "VAR_CONFIG must give a complete address, not a partly specified one",
                        ));
                    } else {
                        self.check_location(loc, t, Owner::Config(c), n);
                    }
                }
                var_config.push((t, init));
            }
            if let Some(e) = self.configs.get_mut(c) {
                e.access_types = access;
                e.var_config = var_config;
            }
        }
    }

    fn emit(&mut self, d: Diagnostic) {
        self.diags.push(d);
    }

    fn name(&self, s: Symbol) -> &'a str {
        self.interner.name(s)
    }

    fn type_name(&self, t: TypeId) -> String {
        crate::names::type_name(&self.types, self.interner, t)
    }

    /// Moves the resolved declarations into a [`Model`].
    fn finish(mut self) -> Declared<'a> {
        // Every slot is resolved by now; slot order is the name index's order.
        let mut scopes: Vec<VarTable> = Vec::with_capacity(self.scopes.len());
        for sc in self.scopes.iter_mut() {
            let vars = std::mem::take(&mut sc.vars)
                .into_iter()
                .zip(sc.slots.iter())
                .map(|(v, slot)| match v {
                    Some(v) => v,
                    None => Var {
                        name: slot.name.sym,
                        span: slot.name.span,
                        section: Section::of(slot.block.kind),
                        ty: TypeId::ERROR,
                        init: None,
                        constant: slot.block.constant,
                        retain: slot.block.retain,
                        location: None,
                        edge: None,
                    },
                })
                .collect();
            scopes.push(VarTable {
                vars,
                by_name: std::mem::take(&mut sc.by_name),
            });
        }
        let mut take = |i: usize| scopes.get_mut(i).map(std::mem::take).unwrap_or_default();
        let mut pous = Vec::with_capacity(self.pous.len());
        for p in &self.pous {
            let mut vars = take(p.scope);
            if let (ast::PouKind::Function, Some(rt)) = (p.ast.kind, p.return_type) {
                // The return value comes first: shift the name index.
                for i in vars.by_name.values_mut() {
                    *i += 1;
                }
                vars.by_name.insert(p.ast.name.sym, 0);
                vars.vars.insert(
                    0,
                    Var {
                        name: p.ast.name.sym,
                        span: p.ast.name.span,
                        section: Section::Return,
                        ty: rt,
                        init: None,
                        constant: false,
                        retain: ast::Retain::Unspecified,
                        location: None,
                        edge: None,
                    },
                );
            }
            pous.push(Pou {
                name: p.ast.name.sym,
                kind: p.ast.kind,
                span: p.ast.span,
                vars,
                return_type: p.return_type,
                instance_type: p.instance_type,
                builtin: p.builtin,
                ast: p.aref,
            });
        }
        let mut configs = Vec::new();
        let mut config_asts = Vec::new();
        for c in self.configs.iter_mut() {
            let resources = c
                .ast
                .resources
                .iter()
                .zip(&c.resources)
                .map(|(r, &s)| Resource {
                    name: r.name.sym,
                    span: r.span,
                    implicit: r.implicit,
                    globals: take(s),
                    tasks: Vec::new(),
                    programs: Vec::new(),
                })
                .collect();
            configs.push(Config {
                name: c.ast.name.sym,
                span: c.ast.span,
                globals: take(c.scope),
                resources,
                access: Vec::new(),
                var_config: Vec::new(),
            });
            config_asts.push(ConfigDecls {
                ast: c.ast,
                access_types: std::mem::take(&mut c.access_types),
                var_config: std::mem::take(&mut c.var_config),
            });
        }
        let type_names = self
            .type_slots
            .iter()
            .filter_map(|(&n, s)| match s.state {
                TypeState::Done(t, _) => Some((n, t)),
                _ => None,
            })
            .collect();
        let globals = take(0);
        let model = Model {
            types: self.types,
            type_names,
            enum_values: self.enum_values,
            pous,
            pou_names: self.pou_names,
            globals,
            configs,
            stdlib: SourceUnit {
                file: crate::stdlib::STD_FILE,
                items: Vec::new(),
            },
            syms: self.syms,
            codesys: false,
            classes: self.classes,
            public_vars: self.public_vars,
        };
        let mut diags = self.diags;
        diags.extend(cycles::instance_cycles(&model, self.interner));
        Declared {
            model,
            configs: config_asts,
            diags,
        }
    }
}
