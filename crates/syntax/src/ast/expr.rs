//! Expressions of Structured Text.

use super::{AddrSize, DirectAddress, Ident};
use automat_base::Span;

#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    /// Boxed, like the address below, to keep `Expr` small: trees are
    /// mostly names and operators, and a smaller node is a faster parse.
    Literal(Box<Literal>),
    /// A variable, constant, enumeration value or POU name.
    Name(Ident),
    /// A direct address used as a value: `%IX0.1`.
    Address(Box<DirectAddress>),
    /// `base.member`
    Member {
        base: Box<Expr>,
        member: Ident,
    },
    /// `base.3` (size `None`) or `base.%X3` / `base.%B1` / `base.%W0` / `base.%D0`
    /// (partial access to a bit string).
    Partial {
        base: Box<Expr>,
        size: AddrSize,
        index: u32,
        index_span: Span,
    },
    /// `base[i, j]`
    Index {
        base: Box<Expr>,
        indices: Vec<Expr>,
    },
    /// `p^`
    Deref(Box<Expr>),
    Unary {
        op: UnaryOp,
        operand: Box<Expr>,
    },
    Binary {
        op: BinaryOp,
        lhs: Box<Expr>,
        rhs: Box<Expr>,
    },
    /// `f(a, b)`, `fb(IN := x, Q => y)`, `inst.fb(...)`.
    Call {
        callee: Box<Expr>,
        args: Vec<Arg>,
    },
    Paren(Box<Expr>),
    /// Text that could not be parsed; a diagnostic was already reported.
    Error,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum UnaryOp {
    Neg,
    Plus,
    Not,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BinaryOp {
    Pow,
    Mul,
    Div,
    Mod,
    Add,
    Sub,
    Lt,
    Gt,
    Le,
    Ge,
    Eq,
    Ne,
    /// `AND` and `&`
    And,
    Xor,
    Or,
}

impl BinaryOp {
    pub fn symbol(self) -> &'static str {
        match self {
            BinaryOp::Pow => "**",
            BinaryOp::Mul => "*",
            BinaryOp::Div => "/",
            BinaryOp::Mod => "MOD",
            BinaryOp::Add => "+",
            BinaryOp::Sub => "-",
            BinaryOp::Lt => "<",
            BinaryOp::Gt => ">",
            BinaryOp::Le => "<=",
            BinaryOp::Ge => ">=",
            BinaryOp::Eq => "=",
            BinaryOp::Ne => "<>",
            BinaryOp::And => "AND",
            BinaryOp::Xor => "XOR",
            BinaryOp::Or => "OR",
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ArgDir {
    /// `name := value` or a positional argument.
    In,
    /// `name => variable`
    Out,
    /// `NOT name => variable`
    OutNot,
}

/// One argument of a call. `name` is `None` for a positional (non-formal) one.
#[derive(Clone, Debug, PartialEq)]
pub struct Arg {
    pub name: Option<Ident>,
    pub dir: ArgDir,
    /// `None` only for an output left unbound: `fb(Q => )`.
    pub value: Option<Expr>,
    pub span: Span,
}

/// A literal with its optional type prefix (`INT#5`, `Color#Red`).
#[derive(Clone, Debug, PartialEq)]
pub struct Literal {
    pub kind: LitKind,
    /// The `T` of `T#...` when it names a type (`INT`, `WORD`, `REAL`,
    /// `Color`); `None` for untyped literals and for the time/date prefixes,
    /// which are implied by the kind.
    pub ty: Option<Ident>,
}

#[derive(Clone, Debug, PartialEq)]
pub enum LitKind {
    /// Integer value (sign included for `INT#-5`; `-5` alone is a unary minus).
    Int(i128),
    Real(f64),
    Bool(bool),
    /// `T#..`/`TIME#..` (long = false) or `LT#..`/`LTIME#..` (long = true), in ns.
    Duration {
        nanos: i128,
        long: bool,
    },
    /// `D#2024-01-31`: days since 1970-01-01.
    Date {
        days: i64,
        long: bool,
    },
    /// `TOD#12:30:00.5`: ns since midnight.
    TimeOfDay {
        nanos: i64,
        long: bool,
    },
    /// `DT#2024-01-31-12:30:00`: ns since 1970-01-01T00:00:00.
    DateTime {
        nanos: i128,
        long: bool,
    },
    /// `'text'` (wide = false) or `"text"` (wide = true), escapes decoded.
    /// Each `$hh` of a STRING becomes the char U+00hh.
    String {
        value: String,
        wide: bool,
    },
    /// `Color#Red`: the value name (the type is in [`Literal::ty`]).
    Enum(Ident),
}
