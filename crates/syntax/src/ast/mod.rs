//! The abstract syntax tree of Structured Text (and, later, of every language
//! that lowers to the same semantic model).
//!
//! Invariants:
//! - Every node carries the [`Span`] of its source text; diagnostics point there.
//! - Names are [`Ident`]s: an interned, case-folded [`Symbol`] plus the span of
//!   the spelling. Elementary type names (`INT`, `TIME`, ...) are plain `Ident`s
//!   resolved by `sema`; only `STRING`/`WSTRING` have syntax of their own.
//! - The tree is what was written: no implicit conversions, no constant
//!   folding. The one desugaring: IL and SFC bodies are parsed into their own
//!   trees (`il`, `sfc`, kept in `Pou::lang`) and rewritten into ST statements
//!   (`Pou::body`) whose spans point at the IL/SFC text they came from. After a syntax error the parser still returns a tree,
//!   with [`ExprKind::Error`] or missing pieces where text could not be parsed.
//! - Statements and expressions are different types.

mod decl;
mod expr;
pub mod il;
pub mod oop;
pub mod sfc;
mod stmt;

pub use decl::*;
pub use expr::*;
pub use stmt::*;

use automat_base::{FileId, Span, Symbol};

/// A name as written: its case-folded symbol and where it was written.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Ident {
    pub sym: Symbol,
    pub span: Span,
}

/// One parsed file.
#[derive(Clone, Debug, PartialEq)]
pub struct SourceUnit {
    pub file: FileId,
    pub items: Vec<Item>,
}

/// A top-level declaration.
#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    Pou(Pou),
    /// `TYPE ... END_TYPE`
    Types(TypeBlock),
    /// A `VAR_GLOBAL ... END_VAR` block outside any configuration (how CODESYS
    /// and TwinCAT global variable lists are written).
    Globals(VarBlock),
    Config(Configuration),
    /// A function block with methods (or EXTENDS/IMPLEMENTS), or a CLASS;
    /// `desugar_oop` replaces it by plain items.
    Class(Box<oop::Class>),
    /// An INTERFACE; `desugar_oop` replaces it by plain items.
    Interface(Box<oop::Interface>),
    /// `NAMESPACE name ... END_NAMESPACE`, or the USING clauses of one POU
    /// (a namespace without a name holding that POU);
    /// `desugar_namespaces` moves its items out, renamed, and leaves it
    /// empty (for export, which refuses it).
    Namespace(Box<Namespace>),
}

/// `NAMESPACE [INTERNAL] A.B USING X; ... END_NAMESPACE` (IEC 61131-3 3rd
/// edition, 6.9). `name` is empty for the USING clauses of a POU outside
/// any namespace: they apply to its one item.
#[derive(Clone, Debug, PartialEq)]
pub struct Namespace {
    pub name: Vec<Ident>,
    pub internal: bool,
    pub usings: Vec<Using>,
    pub items: Vec<Item>,
    pub span: Span,
}

/// `USING A.B;`: the names of namespace `A.B` visible unqualified.
#[derive(Clone, Debug, PartialEq)]
pub struct Using {
    pub path: Vec<Ident>,
    pub span: Span,
}
