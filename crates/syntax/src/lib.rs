//! Lexer, AST and error-recovering parser for IEC 61131-3 Structured Text.
//!
//! Invariant: parsing never fails. [`parse`] returns a tree and the list of
//! diagnostics; later stages work on whatever parsed. This crate knows nothing
//! of types or of the stages above it.

pub mod ast;

use automat_base::{Diagnostic, FileId, Interner};

/// The result of parsing one file: always a tree, plus what went wrong.
#[derive(Debug)]
pub struct Parsed {
    pub unit: ast::SourceUnit,
    pub diagnostics: Vec<Diagnostic>,
}

/// Parses one Structured Text file. Never panics, never fails: errors are
/// returned as diagnostics (codes E001–E007) next to the tree of what parsed.
pub fn parse(file: FileId, text: &str, interner: &mut Interner) -> Parsed {
    let _ = (text, interner);
    Parsed {
        unit: ast::SourceUnit {
            file,
            items: Vec::new(),
        },
        diagnostics: Vec::new(),
    }
}
