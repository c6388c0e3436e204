//! Instruction List as written (IEC 61131-3 IL). Desugared into ST statements
//! by the parser (`desugar::il`); this tree is kept for tools that show the
//! IL view (monitoring the current result line by line, editors).
//!
//! One [`Instr`] per source line: an optional label and at most one
//! operation. A parenthesised group (`AND( ... )`) holds its own lines.

use super::{Arg, Expr, Ident};
use automat_base::Span;

/// An IL body: its instructions in source order.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct IlBody {
    pub instrs: Vec<Instr>,
}

/// One line of IL.
#[derive(Clone, Debug, PartialEq)]
pub struct Instr {
    /// `L1:` in front of the operation (or alone on its line).
    pub label: Option<Ident>,
    pub kind: InstrKind,
    /// The whole line from the label (or operator) to its last token.
    pub span: Span,
}

/// The operators that take the current result and at most one operand
/// (the N forms apply the Boolean negation to the operand, or for `STN`
/// to the stored value; `LDN` loads the negated operand).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Op {
    Ld,
    Ldn,
    St,
    Stn,
    /// `S x`: set `x` to TRUE when the current result is TRUE.
    S,
    /// `R x`: reset `x` to FALSE when the current result is TRUE.
    R,
    And,
    Andn,
    Or,
    Orn,
    Xor,
    Xorn,
    /// `NOT`: negates the current result; takes no operand.
    Not,
    Add,
    Sub,
    Mul,
    Div,
    Mod,
    Gt,
    Ge,
    Eq,
    Ne,
    Le,
    Lt,
}

impl Op {
    /// The operator spelled `word` (upper case), if any. `&` and `&N` are
    /// matched by the parser (they are not words).
    pub fn from_word(word: &str) -> Option<Op> {
        Some(match word {
            "LD" => Op::Ld,
            "LDN" => Op::Ldn,
            "ST" => Op::St,
            "STN" => Op::Stn,
            "S" => Op::S,
            "R" => Op::R,
            "AND" => Op::And,
            "ANDN" => Op::Andn,
            "OR" => Op::Or,
            "ORN" => Op::Orn,
            "XOR" => Op::Xor,
            "XORN" => Op::Xorn,
            "NOT" => Op::Not,
            "ADD" => Op::Add,
            "SUB" => Op::Sub,
            "MUL" => Op::Mul,
            "DIV" => Op::Div,
            "MOD" => Op::Mod,
            "GT" => Op::Gt,
            "GE" => Op::Ge,
            "EQ" => Op::Eq,
            "NE" => Op::Ne,
            "LE" => Op::Le,
            "LT" => Op::Lt,
            _ => return None,
        })
    }

    /// The canonical spelling.
    pub fn name(self) -> &'static str {
        match self {
            Op::Ld => "LD",
            Op::Ldn => "LDN",
            Op::St => "ST",
            Op::Stn => "STN",
            Op::S => "S",
            Op::R => "R",
            Op::And => "AND",
            Op::Andn => "ANDN",
            Op::Or => "OR",
            Op::Orn => "ORN",
            Op::Xor => "XOR",
            Op::Xorn => "XORN",
            Op::Not => "NOT",
            Op::Add => "ADD",
            Op::Sub => "SUB",
            Op::Mul => "MUL",
            Op::Div => "DIV",
            Op::Mod => "MOD",
            Op::Gt => "GT",
            Op::Ge => "GE",
            Op::Eq => "EQ",
            Op::Ne => "NE",
            Op::Le => "LE",
            Op::Lt => "LT",
        }
    }

    /// Operators that combine the current result with an operand and may
    /// open a parenthesised group instead (`AND( ... )`).
    pub fn is_binary(self) -> bool {
        !matches!(
            self,
            Op::Ld | Op::Ldn | Op::St | Op::Stn | Op::S | Op::R | Op::Not
        )
    }

    /// Whether the operand is negated (`ANDN x` is `AND NOT x`).
    pub fn negated(self) -> bool {
        matches!(self, Op::Ldn | Op::Stn | Op::Andn | Op::Orn | Op::Xorn)
    }
}

/// When a jump, return or FB call happens.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum When {
    /// `JMP`, `RET`, `CAL`
    Always,
    /// `JMPC`, `RETC`, `CALC`: when the current result is TRUE.
    IfTrue,
    /// `JMPCN`, `RETCN`, `CALCN`: when the current result is FALSE.
    IfFalse,
}

#[derive(Clone, Debug, PartialEq)]
pub enum InstrKind {
    /// A label alone on its line.
    Nothing,
    /// `op [operand]`. `operand` is `None` only for `NOT` (or after an
    /// error was reported).
    Simple {
        op: Op,
        op_span: Span,
        operand: Option<Expr>,
    },
    /// `op( [operand]` lines `)`: the group's value is computed by its own
    /// instructions from `first` (the short form `AND( b`) or from their
    /// leading `LD`, then combined with the current result by `op`.
    Group {
        op: Op,
        op_span: Span,
        first: Option<Expr>,
        body: Vec<Instr>,
    },
    /// A function call: `LIMIT 0, 10` (the current result is the first
    /// argument) or `LIMIT(MN := 0, IN := x, MX := 10)` (formal: the
    /// current result is not passed).
    Call {
        name: Ident,
        args: Vec<Arg>,
        formal: bool,
    },
    /// `CAL fb`, `CAL fb(IN := x)`, `CALC`, `CALCN`.
    Cal {
        when: When,
        op_span: Span,
        fb: Expr,
        args: Vec<Arg>,
    },
    /// An FB input operator: `PT t1` calls `t1(PT := current result)`
    /// (`S1 R1 CLK CU CD PV IN PT`).
    FbInput { input: Ident, fb: Expr },
    /// `JMP L`, `JMPC L`, `JMPCN L`.
    Jump {
        when: When,
        op_span: Span,
        label: Ident,
    },
    /// `RET`, `RETC`, `RETCN`.
    Ret { when: When, op_span: Span },
    /// A line that could not be parsed (reported).
    Error,
}
