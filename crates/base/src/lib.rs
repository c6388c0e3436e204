//! Shared vocabulary of every automat stage: source files and spans, interned
//! case-insensitive names, and diagnostics with stable codes.
//!
//! Invariant: this crate does no I/O. Files are handed in as text; diagnostics
//! are rendered into strings or any `WriteColor`, never straight to a terminal.

pub mod codes;
pub mod diag;
pub mod intern;
pub mod render;
pub mod slc;
pub mod slc_indirect;
pub mod source;
pub mod span;

pub use codes::Code;
pub use diag::{Diagnostic, Label, Severity};
pub use intern::{Interner, Symbol};
pub use source::{SourceFile, SourceMap};
pub use span::{FileId, Span};
