//! Object orientation of IEC 61131-3 3rd edition as written: classes
//! (function blocks with methods, and `CLASS`), interfaces, methods and
//! properties. The parser builds these; `desugar::oop` rewrites them into
//! plain POUs and types before any later stage sees the project.

use super::{Ident, Stmt, TypeSpec, VarBlock};
use automat_base::{Span, Symbol};

/// `PUBLIC` / `PRIVATE` / `PROTECTED` / `INTERNAL`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Visibility {
    #[default]
    Public,
    Private,
    Protected,
    Internal,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ClassKind {
    FunctionBlock,
    Class,
}

/// `METHOD [access] [ABSTRACT|FINAL] [OVERRIDE] name [: type] ... END_METHOD`.
#[derive(Clone, Debug, PartialEq)]
pub struct Method {
    pub name: Ident,
    pub visibility: Visibility,
    /// Where the access specifier was written (`None`: PUBLIC by default).
    pub visibility_span: Option<Span>,
    pub is_abstract: bool,
    pub is_final: bool,
    pub is_override: bool,
    pub return_type: Option<TypeSpec>,
    pub var_blocks: Vec<VarBlock>,
    pub body: Vec<Stmt>,
    /// `USING A.B;` after the method's header: namespaces its body sees.
    pub usings: Vec<crate::ast::Using>,
    pub span: Span,
}

/// `GET ... END_GET` or `SET ... END_SET` of a property.
#[derive(Clone, Debug, PartialEq)]
pub struct Accessor {
    pub var_blocks: Vec<VarBlock>,
    pub body: Vec<Stmt>,
    pub span: Span,
}

/// `PROPERTY [access] name : type GET ... END_GET SET ... END_SET END_PROPERTY`
/// (CODESYS: the value is the property's name inside both accessors).
#[derive(Clone, Debug, PartialEq)]
pub struct Property {
    pub name: Ident,
    pub visibility: Visibility,
    pub ty: TypeSpec,
    pub get: Option<Accessor>,
    pub set: Option<Accessor>,
    pub span: Span,
}

/// A function block with object-oriented parts, or a `CLASS`.
#[derive(Clone, Debug, PartialEq)]
pub struct Class {
    pub kind: ClassKind,
    pub name: Ident,
    pub is_abstract: bool,
    pub is_final: bool,
    pub extends: Option<Ident>,
    pub implements: Vec<Ident>,
    pub var_blocks: Vec<VarBlock>,
    /// The variables of `VAR PUBLIC|PRIVATE|PROTECTED|INTERNAL` sections
    /// with their access; a variable of a plain `VAR` is PROTECTED (the
    /// standard's default), inputs and outputs are visible everywhere.
    pub var_access: Vec<(Symbol, Visibility)>,
    pub methods: Vec<Method>,
    pub properties: Vec<Property>,
    /// The function block body (empty for a CLASS).
    pub body: Vec<Stmt>,
    pub span: Span,
    /// Set by `desugar_oop` once its plain items were added to the project
    /// (the class stays for tools: export refuses it, E178).
    pub desugared: bool,
}

/// `INTERFACE name [EXTENDS I1, I2] METHOD ... END_METHOD ... END_INTERFACE`.
#[derive(Clone, Debug, PartialEq)]
pub struct Interface {
    pub name: Ident,
    pub extends: Vec<Ident>,
    pub methods: Vec<Method>,
    pub properties: Vec<Property>,
    pub span: Span,
    pub desugared: bool,
}
