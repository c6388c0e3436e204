//! Desugaring: the languages that are not Structured Text (IL, SFC) are
//! rewritten into ST statements and hidden variables (names starting `__`)
//! while parsing, so that checking, lowering and every backend see ST
//! only. The trees as written are kept in `Pou::lang` for tools.

//!
//! ## IL (`il.rs`, parser side in `parser/il.rs`)
//!
//! - `Parser::at_il_start()`: whether the tokens ahead begin an IL list
//!   (an IL operator, after an optional `label:`, followed on its line by
//!   an operand or the end of the line; never `x :=` or `x(`).
//! - `Parser::il_desugared(ends, want_result, &mut hidden) -> (IlBody,
//!   IlOut)`: parses IL instructions up to one of the keywords `ends` (not
//!   consumed; a POU end, VAR block, statement closer or end of file also
//!   stops it) and desugars them. `IlOut::stmts` are the ST statements
//!   (they may contain `StmtKind::Label`/`Goto`); `IlOut::result` is the
//!   current result at the end, when defined — pass `want_result = true`
//!   when it is used (an SFC transition condition: assign it to the
//!   transition's variable). Diagnostics go to the parser's list.
//! - `hidden` collects hidden variable declarations (the BOOL `__CR`);
//!   share one vector across all IL texts of a POU (it declares each name
//!   once) and add `il::hidden_block(hidden)` to the POU's `var_blocks`.
//! - `Parser::il_pou_body(end, &mut var_blocks)` does all of this for a
//!   POU body.

//!
//! ## SFC (`sfc/`, parser side in `parser/sfc.rs`)
//!
//! - `sfc::desugar(chart, ...)`: what the parser calls for a textual chart.
//! - [`crate::desugar_chart`] (`sfc::desugar_chart`): the same for a POU
//!   whose `lang` is a chart built by an importer (macro-steps allowed).

pub(crate) mod eno;
pub(crate) mod il;
pub(crate) mod namespace;
pub(crate) mod oop;
pub(crate) mod reference;
pub(crate) mod sfc;
