//! A scenario as written: timed actions and expectations, with spans.

use automat_base::Span;

/// A name as written (`Pornire`, `Ctrl.fb.Q`, `%QX3.1`, `plant.x`).
#[derive(Clone, Debug, PartialEq)]
pub struct Name {
    pub text: String,
    pub span: Span,
}

/// A literal value.
#[derive(Clone, Debug, PartialEq)]
pub enum Lit {
    Bool(bool),
    Int(i64),
    Real(f64),
    /// A TIME in ns.
    Time(i64),
    /// `Type#Value`.
    Enum(String, String),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CmpOp {
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
}

impl CmpOp {
    pub fn text(self) -> &'static str {
        match self {
            CmpOp::Eq => "=",
            CmpOp::Ne => "<>",
            CmpOp::Lt => "<",
            CmpOp::Le => "<=",
            CmpOp::Gt => ">",
            CmpOp::Ge => ">=",
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LogicOp {
    And,
    Or,
    Xor,
}

/// A condition.
#[derive(Clone, Debug, PartialEq)]
pub enum Expr {
    Ref(Name),
    Lit(Lit, Span),
    Not(Box<Expr>),
    Logic(LogicOp, Box<Expr>, Box<Expr>),
    Cmp(CmpOp, Box<Expr>, Box<Expr>),
}

/// What an `at TIME ...` line does.
#[derive(Clone, Debug, PartialEq)]
pub enum ActionKind {
    /// `press SIG [for TIME]`
    Press(Name, Option<i64>),
    Release(Name),
    /// `set TARGET = VALUE`
    Set(Name, Lit, Span),
    /// `stuck SIG = VALUE`
    Stuck(Name, Lit, Span),
    Unstick(Name),
    /// `noise SIG AMPLITUDE`
    Noise(Name, f64),
    /// `plant COMMAND key=value ...`
    Plant(Name, Vec<(String, f64)>),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Action {
    pub at_ns: i64,
    pub kind: ActionKind,
    pub line: u32,
}

/// When an expectation is checked.
#[derive(Clone, Debug, PartialEq)]
pub enum When {
    /// `expect at T C`: after the first scan at PLC time >= T.
    At(i64),
    /// `expect C within W after A`: true after some scan in (A, A + W].
    Within { after: i64, within: i64 },
    /// `expect always C [during A..B]`; `never C` is `always NOT C`.
    Always { from: i64, to: Option<i64> },
}

#[derive(Clone, Debug, PartialEq)]
pub struct Expect {
    pub when: When,
    pub cond: Expr,
    /// The line as written, after `expect`, for messages.
    pub text: String,
    pub line: u32,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    pub name: String,
    pub duration_ns: i64,
    pub seed: Option<u64>,
    pub actions: Vec<Action>,
    pub expects: Vec<Expect>,
}
