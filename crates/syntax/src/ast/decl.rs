//! Declarations: POUs, variables, types, configurations.

use super::{Arg, Expr, Ident, Stmt};
use automat_base::Span;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PouKind {
    Function,
    FunctionBlock,
    Program,
}

/// A FUNCTION, FUNCTION_BLOCK or PROGRAM.
#[derive(Clone, Debug, PartialEq)]
pub struct Pou {
    pub kind: PouKind,
    pub name: Ident,
    /// `FUNCTION f : INT` (functions only; `None` for a function without one).
    pub return_type: Option<TypeSpec>,
    pub var_blocks: Vec<VarBlock>,
    /// The code every later stage checks and lowers: always Structured Text
    /// (IL and SFC bodies are desugared into it by the parser, see `lang`).
    pub body: Body,
    /// The language the body was written in, with its own tree when that is
    /// not ST: tools that show the source's view (SFC animation, IL
    /// monitoring, graphical editors) read it; checking and lowering do not.
    pub lang: Lang,
    pub span: Span,
}

/// The checked and lowered code of a POU.
#[derive(Clone, Debug, PartialEq)]
pub enum Body {
    St(Vec<Stmt>),
}

/// The language of a POU body as written.
#[derive(Clone, Debug, PartialEq, Default)]
pub enum Lang {
    #[default]
    St,
    Il(Box<super::il::IlBody>),
    Sfc(Box<super::sfc::Chart>),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum VarKind {
    /// `VAR`
    Local,
    Input,
    Output,
    InOut,
    External,
    Global,
    Temp,
    /// `VAR_STAT` (CODESYS): one copy for every call and every instance;
    /// the `codesys` dialect turns it into hidden globals before checking.
    Static,
    /// `VAR_INST` (CODESYS, in a METHOD): kept in the function block's
    /// instance; the `codesys` dialect moves it there before checking.
    Inst,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Retain {
    #[default]
    Unspecified,
    Retain,
    NonRetain,
}

/// `VAR_xxx [CONSTANT] [RETAIN|NON_RETAIN] decl; ... END_VAR`
#[derive(Clone, Debug, PartialEq)]
pub struct VarBlock {
    pub kind: VarKind,
    pub constant: bool,
    pub retain: Retain,
    pub decls: Vec<VarDecl>,
    pub span: Span,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Edge {
    Rising,
    Falling,
}

/// `a, b AT %IX0.1 : INT := 5;` (also a structure member).
#[derive(Clone, Debug, PartialEq)]
pub struct VarDecl {
    pub names: Vec<Ident>,
    pub location: Option<Location>,
    pub ty: TypeSpec,
    /// `R_EDGE` / `F_EDGE` on a BOOL input.
    pub edge: Option<Edge>,
    pub init: Option<Initializer>,
    pub span: Span,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Area {
    /// `%I`
    Input,
    /// `%Q`
    Output,
    /// `%M`
    Memory,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AddrSize {
    /// No size letter: a bit (`%I0.1`) — same as X.
    None,
    /// `X`: 1 bit
    Bit,
    /// `B`: 8 bits
    Byte,
    /// `W`: 16 bits
    Word,
    /// `D`: 32 bits
    DWord,
    /// `L`: 64 bits
    LWord,
}

/// A direct (located) address: `%IX1.2.3`, `%QW4`, `%MD48`, `%I*`.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct DirectAddress {
    pub area: Area,
    pub size: AddrSize,
    /// The dotted numbers, outermost first; empty when `partial`.
    pub path: Vec<u32>,
    /// `%I*`, `%QW*`: the address is given later in VAR_CONFIG.
    pub partial: bool,
    pub span: Span,
}

/// `AT %IX0.1`
#[derive(Clone, Debug, PartialEq)]
pub struct Location {
    pub addr: DirectAddress,
    pub span: Span,
}

/// `TYPE ... END_TYPE` (one or more type declarations).
#[derive(Clone, Debug, PartialEq)]
pub struct TypeBlock {
    pub decls: Vec<TypeDecl>,
    pub span: Span,
}

/// `Name : spec [:= init];`
#[derive(Clone, Debug, PartialEq)]
pub struct TypeDecl {
    pub name: Ident,
    pub spec: TypeSpec,
    pub init: Option<Initializer>,
    pub span: Span,
}

/// A type as written in a declaration.
#[derive(Clone, Debug, PartialEq)]
pub enum TypeSpec {
    /// Elementary, derived, function block or program type name.
    Named(Ident),
    /// `STRING`, `STRING[20]`, `STRING(20)`, `WSTRING[n]`.
    String {
        wide: bool,
        len: Option<Box<Expr>>,
        span: Span,
    },
    /// `ARRAY [1..10, 0..N-1] OF elem` (`[*]` for variable-length VAR_IN_OUT).
    Array {
        dims: Vec<ArrayDim>,
        elem: Box<TypeSpec>,
        span: Span,
    },
    /// `INT (0..100)`
    Subrange {
        base: Ident,
        lo: Box<Expr>,
        hi: Box<Expr>,
        span: Span,
    },
    /// `(Red, Green := 5, Blue)`, optionally with a base type: `INT (A := 1, B := 2)`
    /// or `(A := 1, B := 2) INT`.
    Enum {
        base: Option<Ident>,
        values: Vec<EnumValue>,
        span: Span,
    },
    /// `STRUCT a : INT := 1; b : BOOL; END_STRUCT`
    Struct { members: Vec<VarDecl>, span: Span },
    /// `REF_TO T` (IEC 61131-3 3rd edition) or `POINTER TO T` (CODESYS);
    /// `reference`: CODESYS's `REFERENCE TO T`, used without `^`
    /// (`desugar::reference` makes it a plain `REF_TO` before checking).
    Ref {
        target: Box<TypeSpec>,
        span: Span,
        reference: bool,
    },
}

impl TypeSpec {
    pub fn span(&self) -> Span {
        match self {
            TypeSpec::Named(i) => i.span,
            TypeSpec::String { span, .. }
            | TypeSpec::Array { span, .. }
            | TypeSpec::Subrange { span, .. }
            | TypeSpec::Enum { span, .. }
            | TypeSpec::Struct { span, .. }
            | TypeSpec::Ref { span, .. } => *span,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum ArrayDim {
    Range {
        lo: Expr,
        hi: Expr,
        span: Span,
    },
    /// `*`
    Star(Span),
}

#[derive(Clone, Debug, PartialEq)]
pub struct EnumValue {
    pub name: Ident,
    pub value: Option<Expr>,
}

/// An initial value.
#[derive(Clone, Debug, PartialEq)]
pub enum Initializer {
    Expr(Expr),
    /// `[1, 2, 3(7), 2([1, 2])]`
    Array {
        elems: Vec<ArrayInitElem>,
        span: Span,
    },
    /// `(a := 1, b := [1, 2], c := (x := TRUE))`
    Struct {
        fields: Vec<FieldInit>,
        span: Span,
    },
}

impl Initializer {
    pub fn span(&self) -> Span {
        match self {
            Initializer::Expr(e) => e.span,
            Initializer::Array { span, .. } | Initializer::Struct { span, .. } => *span,
        }
    }
}

/// One element of an array initialiser: `v` or `n(v)` (n repetitions) or `n()`.
#[derive(Clone, Debug, PartialEq)]
pub struct ArrayInitElem {
    pub repeat: Option<Expr>,
    pub value: Option<Initializer>,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub struct FieldInit {
    pub name: Ident,
    pub value: Initializer,
    pub span: Span,
}

/// `CONFIGURATION name ... END_CONFIGURATION`
#[derive(Clone, Debug, PartialEq)]
pub struct Configuration {
    pub name: Ident,
    pub globals: Vec<VarBlock>,
    /// A configuration without `RESOURCE` has one implicit resource holding
    /// its tasks and program instances (`Resource::implicit`).
    pub resources: Vec<Resource>,
    pub access: Vec<AccessDecl>,
    pub var_config: Vec<ConfigInit>,
    pub span: Span,
}

/// `RESOURCE name ON processor ... END_RESOURCE`
#[derive(Clone, Debug, PartialEq)]
pub struct Resource {
    pub name: Ident,
    pub on: Option<Ident>,
    pub implicit: bool,
    pub globals: Vec<VarBlock>,
    pub tasks: Vec<TaskDecl>,
    pub programs: Vec<ProgramConfig>,
    pub span: Span,
}

/// `TASK name (INTERVAL := T#10ms, PRIORITY := 1, SINGLE := trig);`
#[derive(Clone, Debug, PartialEq)]
pub struct TaskDecl {
    pub name: Ident,
    pub props: Vec<TaskProp>,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub struct TaskProp {
    pub name: Ident,
    pub value: Expr,
    pub span: Span,
}

/// `PROGRAM [RETAIN|NON_RETAIN] inst [WITH task] : Type [(in := x, out => y)];`
#[derive(Clone, Debug, PartialEq)]
pub struct ProgramConfig {
    pub retain: Retain,
    pub name: Ident,
    pub task: Option<Ident>,
    pub ty: Ident,
    pub conns: Vec<Arg>,
    pub span: Span,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AccessDirection {
    ReadWrite,
    ReadOnly,
}

/// `VAR_ACCESS name : path : type [READ_WRITE|READ_ONLY]; END_VAR`
#[derive(Clone, Debug, PartialEq)]
pub struct AccessDecl {
    pub name: Ident,
    /// `Res.Inst.var`, `GlobalVar`, `%IX1.0`: an expression of names, members,
    /// indexes or a direct address.
    pub path: Expr,
    pub ty: TypeSpec,
    pub direction: Option<AccessDirection>,
    pub span: Span,
}

/// `VAR_CONFIG Res.Inst.var [AT %QX1.0] : type [:= init]; END_VAR`
#[derive(Clone, Debug, PartialEq)]
pub struct ConfigInit {
    pub path: Expr,
    pub location: Option<Location>,
    pub ty: TypeSpec,
    pub init: Option<Initializer>,
    pub span: Span,
}
