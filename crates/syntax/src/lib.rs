//! Lexer, AST and error-recovering parser for IEC 61131-3 Structured Text.
//!
//! Invariant: parsing never fails. [`parse`] returns a tree and the list of
//! diagnostics; later stages work on whatever parsed. This crate knows nothing
//! of types or of the stages above it.
//!
//! Layout: [`lexer`] turns bytes into tokens, decoding every literal into its
//! value on the way (`literal`: numbers, durations, dates, strings); `parser`
//! turns tokens into the [`ast`] by recursive descent, one module per area
//! (expressions, statements, declarations, types, initial values, POUs,
//! configurations).
//!
//! What the parser guarantees:
//! - No panic, no hang, no stack overflow on any input: every loop consumes
//!   a token, and nesting (and chains such as `a + b + ...`) is limited to
//!   [`MAX_DEPTH`] levels, which also bounds the depth of every returned tree.
//! - Diagnostics E001–E007 (and, for IL bodies, E100–E104 and E108–E110:
//!   see `parser/il.rs` and `desugar/il.rs`), each at the offending token with a message
//!   naming what was expected and what was found, sorted by position. One
//!   mistake gives one error: see `parser` for the recovery rules.
//! - Literals are checked here: malformed ones (E004), integers beyond 64 bits
//!   and typed literals outside their elementary type (`SINT#300`,
//!   `USINT#-1`, `BOOL#2`, `REAL#1E39`) are E006. A malformed literal becomes
//!   an [`ast::ExprKind::Error`].
//! - A typed literal keeps what was written: `REAL#1` is `LitKind::Int(1)`
//!   with `ty` REAL; giving it its type is the checker's job.

pub mod ast;
mod desugar;
pub mod graphic;
pub mod lexer;
mod literal;
mod parser;

use automat_base::{Code, Diagnostic, FileId, Interner, Span};

pub use desugar::il::LABEL_CR_VAR;
pub use desugar::namespace::desugar_namespaces;
pub use desugar::oop::desugar_oop;
pub use desugar::sfc::desugar_chart;
pub use parser::MAX_DEPTH;

/// The result of parsing one file: always a tree, plus what went wrong.
#[derive(Debug)]
pub struct Parsed {
    pub unit: ast::SourceUnit,
    pub diagnostics: Vec<Diagnostic>,
}

/// Spans are 32-bit byte offsets: text past this is not parsed.
const MAX_LEN: usize = u32::MAX as usize - 1;

/// What a dialect changes in how text is read (the default is strict IEC
/// 61131-3).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Options {
    /// CODESYS / TwinCAT text (`--lib codesys`): `(* *)` comments do not
    /// nest, and the `;` after `END_IF`, `END_FOR`, `END_CASE`,
    /// `END_WHILE` and `END_REPEAT` may be left out.
    pub codesys: bool,
    /// With `codesys`: the file's `(* *)` comments nest after all (a V2.3
    /// export whose `(* @NESTEDCOMMENTS := 'Yes' *)` marker says so).
    pub nested_comments: bool,
}

/// Parses one Structured Text file. Never panics, never fails: errors are
/// returned as diagnostics (codes E001–E007) next to the tree of what parsed,
/// sorted by position.
pub fn parse(file: FileId, text: &str, interner: &mut Interner) -> Parsed {
    parse_with(file, text, interner, Options::default())
}

/// [`parse`] with a dialect's [`Options`].
pub fn parse_with(file: FileId, text: &str, interner: &mut Interner, opts: Options) -> Parsed {
    let mut diagnostics = Vec::new();
    let text = if text.len() > MAX_LEN {
        let mut cut = MAX_LEN;
        while !text.is_char_boundary(cut) {
            cut -= 1;
        }
        diagnostics.push(Diagnostic::error(
            Code::E005,
            Span::new(file, cut as u32, cut as u32),
            "the file is larger than 4 GiB: the rest is not parsed",
        ));
        &text[..cut]
    } else {
        text
    };
    let lexed = lexer::lex_with(
        file,
        text,
        interner,
        &mut diagnostics,
        !opts.codesys || opts.nested_comments,
    );
    if let (true, Some((start, end))) = (opts.codesys, lexed.first_pragma) {
        let n = lexed.pragmas;
        let others = match n {
            1 => String::new(),
            2 => " (and 1 more in this file)".to_string(),
            _ => format!(" (and {} more in this file)", n - 1),
        };
        diagnostics.push(
            Diagnostic::warning(
                Code::W160,
                Span::new(file, start, end),
                format!("pragma ignored{others}"),
            )
            .with_note("automat does not interpret CODESYS attributes and pragmas; the code is read as if they were absent"),
        );
    }
    let unit = parser::parse_tokens(file, text, lexed, interner, &mut diagnostics, opts);
    diagnostics.sort_by_key(|d| d.span.start);
    Parsed { unit, diagnostics }
}
