//! Phase 2: bodies. Types every statement and expression of every POU
//! against the finished declaration model, with the rules of
//! [`crate::lattice`].
//!
//! Invariants:
//! - The model is read-only here; a [`Checker`] can type any expression of
//!   any POU at any time (lowering uses [`crate::type_of`]).
//! - A silent checker (no diagnostics wanted) never formats a message.
//! - Expression recursion is bounded ([`MAX_EXPR_DEPTH`]).

mod call;
mod expr;
mod isvalidref;
mod labels;
pub mod resolve;
mod stdcall;
mod stmt;

use crate::model::{Model, Pou, Section, Var};
use crate::names::ty_name;
use crate::ops::Ty;
use crate::stdlib::{self, Sig};
use crate::types::{PouId, TypeId, TypeKind};
use automat_base::{Code, Diagnostic, Interner, Span, Symbol};
use automat_syntax::ast::{self, PouKind};
use rustc_hash::FxHashMap;
use std::cell::Cell;
use std::rc::Rc;

/// Deepest expression nesting typed, and deepest statement nesting checked
/// (deeper ones are reported, not overflowed).
pub const MAX_EXPR_DEPTH: u32 = 256;

/// Where names are looked up.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scope {
    /// Inside a POU body: its variables, then the project's globals.
    Pou(PouId),
    /// In a configuration (resource `None`) or one of its resources: the
    /// resource's globals, the configuration's, then the project's.
    Config(usize, Option<usize>),
}

/// What a name denotes in a scope.
pub(crate) enum Named<'m> {
    Var,
    Pou(PouId, &'m Pou),
    Type,
    StdFn,
    Unknown,
}

/// How an expression is used.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Access {
    Read,
    /// The target of `:=`.
    Assign,
    /// The target of an output binding `=>`.
    Output,
    /// Passed to a VAR_IN_OUT (may be written).
    InOut,
    /// The control variable of FOR.
    ForVar,
}

impl Access {
    fn writes(self) -> bool {
        self != Access::Read
    }
}

/// Types bodies; collects diagnostics unless silent.
pub struct Checker<'m> {
    pub(crate) model: &'m Model,
    pub(crate) interner: &'m Interner,
    pub(crate) scope: Scope,
    pub(crate) diags: Vec<Diagnostic>,
    silent: bool,
    std_cache: FxHashMap<Symbol, Option<Rc<Sig>>>,
    pub(crate) loop_depth: u32,
    /// Nesting of the expression being typed.
    pub(crate) depth: u32,
    /// Nesting of the statement being checked.
    pub(crate) stmt_depth: u32,
    /// "Nested too deeply" was reported for this POU (once is enough).
    pub(crate) deep_reported: bool,
    /// Which variables of the current POU a name in its body refers to
    /// (indexed like its `VarTable`), for W001.
    used: Vec<Cell<bool>>,
}

impl<'m> Checker<'m> {
    pub fn new(
        model: &'m Model,
        interner: &'m Interner,
        scope: Scope,
        silent: bool,
    ) -> Checker<'m> {
        Checker {
            model,
            interner,
            scope,
            diags: Vec::new(),
            silent,
            std_cache: FxHashMap::default(),
            loop_depth: 0,
            depth: 0,
            stmt_depth: 0,
            deep_reported: false,
            used: Vec::new(),
        }
    }

    /// Checks the body of a POU.
    pub fn check_pou(&mut self, id: PouId, pou: &ast::Pou) {
        self.scope = Scope::Pou(id);
        self.loop_depth = 0;
        self.depth = 0;
        self.stmt_depth = 0;
        self.deep_reported = false;
        let model = self.model;
        let Some(info) = model.pou(id) else {
            return;
        };
        self.used = info.vars.vars.iter().map(|_| Cell::new(false)).collect();
        match &pou.body {
            ast::Body::St(stmts) => {
                self.check_labels(stmts);
                self.stmts(stmts);
            }
        }
        self.warn_unused(info);
    }

    /// W001 for internal variables nothing refers to. Only the private state
    /// of functions and function blocks and every VAR_TEMP: a program's VAR
    /// is reachable from outside (monitoring, access paths) and parameters
    /// are an interface; located variables are I/O mappings.
    fn warn_unused(&mut self, pou: &'m Pou) {
        let private = |s: Section| match pou.kind {
            PouKind::Program => s == Section::Temp,
            _ => matches!(s, Section::Local | Section::Temp),
        };
        // A class's state is used by its generated methods (through `__THIS`).
        let this = self.model.syms.this_;
        let has_methods = pou.kind == PouKind::FunctionBlock
            && pou.instance_type.is_some_and(|t| {
                self.model
                    .pous
                    .iter()
                    .any(|p| p.vars.get(this).is_some_and(|v| v.ty == t))
            });
        if has_methods {
            return;
        }
        for (i, v) in pou.vars.vars.iter().enumerate() {
            let used = self.used.get(i).is_some_and(Cell::get);
            // A `VAR PUBLIC` / `VAR INTERNAL` one is an interface, as a parameter.
            let public = self.model.public_vars.contains(&(pou.name, v.name));
            if !used && !public && private(v.section) && v.location.is_none() && !v.constant {
                let (name, owner) = (v.name, pou.name);
                self.warn(Code::W001, v.span, |c| {
                    format!(
                        "variable `{}` of `{}` is never used",
                        c.name(name),
                        c.name(owner)
                    )
                });
            }
        }
    }

    /// Emits a diagnostic built only when someone listens.
    pub(crate) fn err(&mut self, code: Code, span: Span, msg: impl FnOnce(&Self) -> String) {
        if !self.silent {
            let m = msg(self);
            self.diags.push(Diagnostic::error(code, span, m));
        }
    }

    /// Adds to the last diagnostic the note that `--lib codesys` accepts
    /// what it reports (`what`: the CODESYS rule).
    pub(crate) fn note_codesys(&mut self, what: &str) {
        if let Some(d) = self.diags.last_mut() {
            d.notes.push(format!(
                "{what}: check with `--lib codesys` (or `libraries = [\"codesys\"]` in automat.toml) to read CODESYS code"
            ));
        }
    }

    /// Emits a diagnostic with labels or notes, built only when someone listens.
    pub(crate) fn diag(&mut self, make: impl FnOnce(&Self) -> Diagnostic) {
        if !self.silent {
            let d = make(self);
            self.diags.push(d);
        }
    }

    /// Reports nesting beyond the limits, once per POU.
    pub(crate) fn too_deep(&mut self, span: Span, what: &'static str) {
        if !self.deep_reported {
            self.deep_reported = true;
            self.err(Code::E070, span, |_| format!("{what} nested too deeply"));
        }
    }

    pub(crate) fn warn(&mut self, code: Code, span: Span, msg: impl FnOnce(&Self) -> String) {
        if !self.silent {
            let m = msg(self);
            self.diags.push(Diagnostic::warning(code, span, m));
        }
    }

    pub(crate) fn name(&self, s: Symbol) -> &'m str {
        self.interner.name(s)
    }

    /// A POU's name for messages: generated object-oriented POUs are shown
    /// as written (`__M_Motor__Start` is `Motor.Start`).
    pub(crate) fn pou_name(&self, s: Symbol) -> std::borrow::Cow<'m, str> {
        crate::names::display_name(self.interner.name(s))
    }

    pub(crate) fn tyname(&self, t: Ty) -> String {
        ty_name(&self.model.types, self.interner, t)
    }

    pub(crate) fn type_name(&self, t: TypeId) -> String {
        crate::names::type_name(&self.model.types, self.interner, t)
    }

    /// The POU being checked.
    pub(crate) fn pou(&self) -> Option<&'m Pou> {
        match self.scope {
            Scope::Pou(id) => self.model.pou(id),
            Scope::Config(..) => None,
        }
    }

    /// `in `MainProg`` / `in configuration `Cell`` for messages.
    /// What to add to "unknown variable": the nearest visible name, or
    /// that a global of that name needs a VAR_EXTERNAL here.
    pub(crate) fn var_hint(&self, sym: Symbol) -> String {
        if let Scope::Pou(_) = self.scope {
            if self.model.globals.get(sym).is_some_and(|g| !g.constant) {
                return format!(
                    "; `{}` is a global variable: declare it in a VAR_EXTERNAL section to use it here",
                    self.name(sym)
                );
            }
        }
        let mut names: Vec<&str> = Vec::new();
        match self.scope {
            Scope::Pou(id) => {
                if let Some(p) = self.model.pou(id) {
                    names.extend(p.vars.vars.iter().map(|v| self.name(v.name)));
                }
            }
            Scope::Config(c, r) => {
                if let Some(cf) = self.model.configs.get(c) {
                    names.extend(cf.globals.vars.iter().map(|v| self.name(v.name)));
                    if let Some(res) = r.and_then(|r| cf.resources.get(r)) {
                        names.extend(res.globals.vars.iter().map(|v| self.name(v.name)));
                    }
                }
            }
        }
        names.extend(
            self.model
                .globals
                .vars
                .iter()
                .filter(|g| g.constant)
                .map(|g| self.name(g.name)),
        );
        names.sort_unstable();
        crate::suggest::did_you_mean(self.name(sym), names)
    }

    /// What to add to a type mismatch from `from` to `to`: how to write a
    /// duration for an integer given to a TIME, or the conversion function
    /// that exists between the two types.
    pub(crate) fn conversion_hint(&self, from: Ty, to: TypeId) -> String {
        use crate::stdlib::conv::{allowed, ConvTy};
        use crate::types::Elem;
        let types = &self.model.types;
        let to_conv = match types.get(to) {
            TypeKind::String { wide, .. } => Some(ConvTy::Str(*wide)),
            _ => types.elem(to).map(ConvTy::Elem),
        };
        let Some(to_conv) = to_conv else {
            return String::new();
        };
        if let ConvTy::Elem(t @ (Elem::Time | Elem::Ltime)) = to_conv {
            let from_int = match from {
                Ty::AnyInt => true,
                Ty::Of(id) => types.elem(id).is_some_and(|e| e.is_int()),
                _ => false,
            };
            if from_int {
                let prefix = if t == Elem::Time { "T" } else { "LTIME" };
                return format!(
                    "; write a duration such as `{prefix}#5s` or `{prefix}#500ms`, or convert a number of milliseconds with `{}_TO_{}`",
                    match from {
                        Ty::Of(id) => types.elem(id).map_or("DINT", |e| e.name()),
                        _ => "DINT",
                    },
                    t.name()
                );
            }
        }
        let from_conv = match from {
            Ty::Of(id) => match types.get(id) {
                TypeKind::String { wide, .. } => Some(ConvTy::Str(*wide)),
                _ => types.elem(id).map(ConvTy::Elem),
            },
            _ => None,
        };
        let name = |c: ConvTy| match c {
            ConvTy::Elem(e) => e.name(),
            ConvTy::Str(false) => "STRING",
            ConvTy::Str(true) => "WSTRING",
        };
        match from_conv {
            Some(f) if f != to_conv && allowed(f, to_conv) => {
                format!("; convert it with `{}_TO_{}(...)`", name(f), name(to_conv))
            }
            _ => String::new(),
        }
    }

    /// What to add to "unknown function or function block": the nearest
    /// POU name (the standard function blocks included).
    pub(crate) fn pou_hint(&self, sym: Symbol) -> String {
        let mut names: Vec<&str> = self.model.pou_names.keys().map(|&s| self.name(s)).collect();
        names.sort_unstable();
        crate::suggest::did_you_mean(self.name(sym), names)
    }

    pub(crate) fn where_(&self) -> String {
        match self.scope {
            Scope::Pou(id) => match self.model.pou(id) {
                Some(p) => format!("in `{}`", self.name(p.name)),
                None => String::new(),
            },
            Scope::Config(c, _) => match self.model.configs.get(c) {
                Some(cf) => format!("in configuration `{}`", self.name(cf.name)),
                None => String::new(),
            },
        }
    }

    /// The variable a name denotes in the current scope.
    /// The type of `__SELF` (the current instance) in a function block
    /// body; `None` elsewhere or when a variable of that name exists.
    pub(crate) fn self_type(&self) -> Option<TypeId> {
        let Scope::Pou(id) = self.scope else {
            return None;
        };
        let p = self.model.pou(id)?;
        if p.kind != automat_syntax::ast::PouKind::FunctionBlock
            || p.vars.index(self.model.syms.self_).is_some()
        {
            return None;
        }
        p.instance_type
    }

    pub(crate) fn var(&self, sym: Symbol) -> Option<(&'m Var, bool)> {
        match self.scope {
            Scope::Pou(id) => {
                let vars = self.model.pou(id).map(|p| &p.vars);
                if let Some(i) = vars.and_then(|t| t.index(sym)) {
                    if let Some(flag) = self.used.get(i as usize) {
                        flag.set(true);
                    }
                    if let Some(v) = vars.and_then(|t| t.vars.get(i as usize)) {
                        return Some((v, true));
                    }
                }
            }
            Scope::Config(c, r) => {
                let cf = self.model.configs.get(c)?;
                if let Some(v) = r
                    .and_then(|r| cf.resources.get(r))
                    .and_then(|res| res.globals.get(sym))
                {
                    return Some((v, false));
                }
                if let Some(v) = cf.globals.get(sym) {
                    return Some((v, false));
                }
            }
        }
        // Project globals: constants are visible everywhere (they size arrays
        // and strings); variables only through VAR_EXTERNAL in a POU.
        let g = self.model.globals.get(sym)?;
        match self.scope {
            Scope::Pou(_) if !g.constant => None,
            _ => Some((g, false)),
        }
    }

    /// What a name denotes when it is not a variable.
    pub(crate) fn lookup(&mut self, sym: Symbol) -> Named<'m> {
        // (A function's return value shares the function's name: the POU wins here.)
        if self
            .var(sym)
            .is_some_and(|(v, _)| v.section != crate::model::Section::Return)
        {
            return Named::Var;
        }
        if let Some((id, p)) = self.model.pou_named(sym) {
            return Named::Pou(id, p);
        }
        if self.model.type_names.contains_key(&sym) || self.model.syms.is_elementary(sym) {
            return Named::Type;
        }
        if self.std_fn(sym).is_some() {
            return Named::StdFn;
        }
        Named::Unknown
    }

    /// What a called name denotes: a POU, a type or a standard function
    /// before a variable of the same name (see `name_calls_a_function`).
    pub(crate) fn lookup_callee(&mut self, sym: Symbol) -> Named<'m> {
        if let Some((id, p)) = self.model.pou_named(sym) {
            return Named::Pou(id, p);
        }
        if self.model.type_names.contains_key(&sym) || self.model.syms.is_elementary(sym) {
            return Named::Type;
        }
        if self.std_fn(sym).is_some() {
            return Named::StdFn;
        }
        self.lookup(sym)
    }

    /// The standard function of a name (cached per name).
    pub(crate) fn std_fn(&mut self, sym: Symbol) -> Option<Rc<Sig>> {
        let interner = self.interner;
        self.std_cache
            .entry(sym)
            .or_insert_with(|| stdlib::lookup(interner.name(sym)).map(Rc::new))
            .clone()
    }

    /// The type an expression names when it is only a type name (see
    /// [`crate::type_named`]).
    pub(crate) fn type_named(&mut self, e: &ast::Expr) -> Option<TypeId> {
        let ast::ExprKind::Name(id) = &e.kind else {
            return None;
        };
        match self.lookup(id.sym) {
            Named::Type => self.type_by_name(*id),
            // The elementary type names are keywords, not declared names.
            Named::Unknown => self
                .model
                .syms
                .elems
                .get(&id.sym)
                .map(|&el| TypeId::elem(el)),
            _ => None,
        }
    }

    /// A type named in an expression (literal prefixes).
    pub(crate) fn type_by_name(&self, id: ast::Ident) -> Option<TypeId> {
        if let Some(&e) = self.model.syms.elems.get(&id.sym) {
            return Some(TypeId::elem(e));
        }
        if id.sym == self.model.syms.string {
            return Some(TypeId::STRING);
        }
        if id.sym == self.model.syms.wstring {
            return Some(TypeId::WSTRING);
        }
        self.model.type_names.get(&id.sym).copied()
    }

    /// A message fragment for a non-variable name used as a value.
    pub(crate) fn what_is(&self, sym: Symbol, named: &Named) -> String {
        let n = self.name(sym);
        match named {
            Named::Pou(_, p) => match p.kind {
                PouKind::Function => format!("`{n}` is a function; call it as `{n}(...)`"),
                PouKind::FunctionBlock => format!("`{n}` is a function block type, not a variable"),
                PouKind::Program => format!("`{n}` is a program, not a variable"),
            },
            Named::Type => format!("`{n}` is a type, not a variable"),
            Named::StdFn => format!("`{n}` is a standard function; call it as `{n}(...)`"),
            _ => format!("`{n}` is not a variable"),
        }
    }

    /// Whether a type is a function block instance; gives its POU.
    pub(crate) fn fb_of(&self, t: TypeId) -> Option<PouId> {
        match self.model.types.get(t) {
            TypeKind::Fb { pou, .. } => Some(*pou),
            _ => None,
        }
    }
}
