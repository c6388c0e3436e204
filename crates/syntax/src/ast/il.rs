//! Instruction List as written (IEC 61131-3 IL). Desugared into ST statements
//! by the parser; this tree is kept for tools that show the IL view.

/// An IL body: its instructions in source order.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct IlBody {}
