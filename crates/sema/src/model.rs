//! The semantic model: what the checker learned about a project, in the form
//! the lowering stage needs (resolved types, ordered variables, folded
//! constants, configurations).
//!
//! Invariants:
//! - Every `TypeId` in the model is valid in [`Model::types`]; a declaration
//!   whose type could not be resolved has [`TypeId::ERROR`] (and a diagnostic).
//! - Variables of a POU are in declaration order, the function's return
//!   variable (section [`Section::Return`]) first, which is also memory order
//!   for lowering. `by_name` maps each name to its index; a duplicate
//!   declaration (reported) is left out.
//! - Initial values are folded ([`Init`]); a variable without an explicit one
//!   inherits its alias type's initial value; `None` means the type's default.
//! - POUs keep a reference to their AST ([`AstRef`]) instead of copies of it.

use crate::names::Syms;
use crate::types::{PouId, TypeId, TypeTable};
use crate::value::Init;
use automat_base::{Span, Symbol};
use automat_syntax::ast::{self, DirectAddress, Edge, PouKind, Retain, SourceUnit};
use rustc_hash::FxHashMap;

/// Where a variable is declared.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Section {
    /// The return value of a function (named like the function).
    Return,
    Input,
    Output,
    InOut,
    Local,
    Temp,
    External,
    Global,
}

impl Section {
    pub fn of(kind: ast::VarKind) -> Section {
        match kind {
            ast::VarKind::Local => Section::Local,
            ast::VarKind::Input => Section::Input,
            ast::VarKind::Output => Section::Output,
            ast::VarKind::InOut => Section::InOut,
            ast::VarKind::External => Section::External,
            ast::VarKind::Global => Section::Global,
            ast::VarKind::Temp => Section::Temp,
            // Left only where the dialect reported it (E160): checked as VAR.
            ast::VarKind::Static | ast::VarKind::Inst => Section::Local,
        }
    }

    pub fn keyword(self) -> &'static str {
        match self {
            Section::Return => "return value",
            Section::Input => "VAR_INPUT",
            Section::Output => "VAR_OUTPUT",
            Section::InOut => "VAR_IN_OUT",
            Section::Local => "VAR",
            Section::Temp => "VAR_TEMP",
            Section::External => "VAR_EXTERNAL",
            Section::Global => "VAR_GLOBAL",
        }
    }

    /// Parameters: visible from outside a function block, bound in calls.
    pub fn is_param(self) -> bool {
        matches!(self, Section::Input | Section::Output | Section::InOut)
    }
}

/// One declared variable.
#[derive(Clone, Debug, PartialEq)]
pub struct Var {
    pub name: Symbol,
    pub span: Span,
    pub section: Section,
    pub ty: TypeId,
    pub init: Option<Init>,
    pub constant: bool,
    pub retain: Retain,
    pub location: Option<DirectAddress>,
    pub edge: Option<Edge>,
}

/// Variables in declaration order with a name index.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VarTable {
    pub vars: Vec<Var>,
    pub by_name: FxHashMap<Symbol, u32>,
}

impl VarTable {
    pub fn get(&self, name: Symbol) -> Option<&Var> {
        self.by_name
            .get(&name)
            .and_then(|&i| self.vars.get(i as usize))
    }

    pub fn index(&self, name: Symbol) -> Option<u32> {
        self.by_name.get(&name).copied()
    }

    /// Adds a variable; a name already present keeps its first declaration.
    pub fn push(&mut self, var: Var) {
        let idx = self.vars.len() as u32;
        self.by_name.entry(var.name).or_insert(idx);
        self.vars.push(var);
    }
}

/// Which parsed file a POU comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum UnitRef {
    /// `units[i]` as passed to [`crate::check`].
    User(u32),
    /// [`Model::stdlib`].
    Std,
}

/// An item of a source unit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct AstRef {
    pub unit: UnitRef,
    pub item: u32,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Pou {
    pub name: Symbol,
    pub kind: PouKind,
    pub span: Span,
    pub vars: VarTable,
    /// Functions: the return type (`None` for a function without one).
    pub return_type: Option<TypeId>,
    /// The instance type of a function block or program.
    pub instance_type: Option<TypeId>,
    /// Declared in the standard library.
    pub builtin: bool,
    pub ast: AstRef,
}

impl Pou {
    /// Parameters in declaration order (inputs, outputs and in-outs mixed as written).
    pub fn params(&self) -> impl Iterator<Item = (u32, &Var)> {
        self.vars
            .vars
            .iter()
            .enumerate()
            .filter(|(_, v)| v.section.is_param())
            .map(|(i, v)| (i as u32, v))
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Task {
    pub name: Symbol,
    pub span: Span,
    /// INTERVAL in nanoseconds.
    pub interval: Option<i128>,
    pub priority: Option<i128>,
    /// SINGLE: the BOOL variable whose rising edge triggers the task.
    pub single: Option<Symbol>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct ProgramInstance {
    pub name: Symbol,
    pub span: Span,
    pub pou: PouId,
    /// Index into the resource's tasks.
    pub task: Option<u32>,
    pub retain: Retain,
    /// The checked connections `(input := value, output => place)`, in
    /// the configuration's scope: run around each call of the program.
    pub conns: Vec<ast::Arg>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Resource {
    pub name: Symbol,
    pub span: Span,
    pub implicit: bool,
    pub globals: VarTable,
    pub tasks: Vec<Task>,
    pub programs: Vec<ProgramInstance>,
}

/// A resolved VAR_ACCESS / VAR_CONFIG path: the names from the
/// configuration down to the variable, and its type.
#[derive(Clone, Debug, PartialEq)]
pub struct AccessPath {
    /// `VAR_ACCESS` name (`None` for a VAR_CONFIG entry).
    pub name: Option<Symbol>,
    pub path: Vec<Symbol>,
    pub ty: TypeId,
    pub read_only: bool,
    pub location: Option<DirectAddress>,
    pub init: Option<Init>,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Config {
    pub name: Symbol,
    pub span: Span,
    pub globals: VarTable,
    pub resources: Vec<Resource>,
    pub access: Vec<AccessPath>,
    pub var_config: Vec<AccessPath>,
}

/// Everything known about a checked project.
pub struct Model {
    pub types: TypeTable,
    /// User-declared type names (aliases map to their target).
    pub type_names: FxHashMap<Symbol, TypeId>,
    /// Enumeration value name → the enumerations declaring it.
    pub enum_values: FxHashMap<Symbol, Vec<TypeId>>,
    pub pous: Vec<Pou>,
    pub pou_names: FxHashMap<Symbol, PouId>,
    /// Project-level `VAR_GLOBAL` blocks (global variable lists).
    pub globals: VarTable,
    pub configs: Vec<Config>,
    /// The parsed standard library (standard function blocks).
    pub stdlib: SourceUnit,
    /// Well-known names.
    pub syms: Syms,
    /// The CODESYS dialect's checking rules (`--lib codesys`, see
    /// [`crate::Options`]); lowering reads types through the same flag.
    pub codesys: bool,
    /// The function blocks that were written as `CLASS` (desugared into
    /// function blocks): messages name them as classes.
    pub classes: rustc_hash::FxHashSet<Symbol>,
    /// (class, variable): a VAR of a class (its own or a base's) declared
    /// in a `VAR PUBLIC` or `VAR INTERNAL` section, visible from outside
    /// like an input (the desugaring refused INTERNAL ones used outside
    /// their namespace, E207).
    pub public_vars: rustc_hash::FxHashSet<(Symbol, Symbol)>,
}

impl Model {
    pub fn pou(&self, id: PouId) -> Option<&Pou> {
        self.pous.get(id.0 as usize)
    }

    pub fn pou_named(&self, name: Symbol) -> Option<(PouId, &Pou)> {
        let id = *self.pou_names.get(&name)?;
        Some((id, self.pou(id)?))
    }

    /// The AST of a POU (`units` as passed to [`crate::check`]).
    pub fn pou_ast<'a>(&'a self, units: &'a [SourceUnit], id: PouId) -> Option<&'a ast::Pou> {
        let r = self.pou(id)?.ast;
        let unit = match r.unit {
            UnitRef::User(u) => units.get(u as usize)?,
            UnitRef::Std => &self.stdlib,
        };
        match unit.items.get(r.item as usize)? {
            ast::Item::Pou(p) => Some(p),
            _ => None,
        }
    }
}
