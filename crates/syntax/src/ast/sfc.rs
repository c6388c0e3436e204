//! Sequential Function Charts as written (IEC 61131-3 textual SFC, and the
//! model graphical importers build). Desugared into ST statements and hidden
//! variables by the parser; this tree is kept for tools (chart animation).

/// A chart: steps, transitions and actions of one POU body.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Chart {}
