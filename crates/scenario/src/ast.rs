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

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArithOp {
    Add,
    Sub,
    Mul,
    Div,
    Mod,
}

impl ArithOp {
    pub fn text(self) -> &'static str {
        match self {
            ArithOp::Add => "+",
            ArithOp::Sub => "-",
            ArithOp::Mul => "*",
            ArithOp::Div => "/",
            ArithOp::Mod => "MOD",
        }
    }
}

/// The functions of a condition: `rise(C)`, `fall(C)`, `change(X)` (events:
/// TRUE in the scan where they happen), `prev(X)` (the value after the
/// previous scan), `count(C)` (scans of the expectation's window where C
/// held), `abs(X)`, `min(X, Y)`, `max(X, Y)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Func {
    Rise,
    Fall,
    Change,
    Prev,
    Count,
    Abs,
    Min,
    Max,
}

impl Func {
    pub const ALL: [Func; 8] = [
        Func::Rise,
        Func::Fall,
        Func::Change,
        Func::Prev,
        Func::Count,
        Func::Abs,
        Func::Min,
        Func::Max,
    ];
    pub fn name(self) -> &'static str {
        match self {
            Func::Rise => "rise",
            Func::Fall => "fall",
            Func::Change => "change",
            Func::Prev => "prev",
            Func::Count => "count",
            Func::Abs => "abs",
            Func::Min => "min",
            Func::Max => "max",
        }
    }
    pub fn by_name(w: &str) -> Option<Func> {
        Func::ALL
            .iter()
            .copied()
            .find(|f| f.name().eq_ignore_ascii_case(w))
    }
    /// How many arguments it takes.
    pub fn arity(self) -> usize {
        match self {
            Func::Min | Func::Max => 2,
            _ => 1,
        }
    }
    /// `rise`, `fall` and `change`.
    pub fn is_event(self) -> bool {
        matches!(self, Func::Rise | Func::Fall | Func::Change)
    }
}

/// A condition or value expression.
#[derive(Clone, Debug, PartialEq)]
pub enum Expr {
    Ref(Name),
    Lit(Lit, Span),
    Not(Box<Expr>),
    Logic(LogicOp, Box<Expr>, Box<Expr>),
    Cmp(CmpOp, Box<Expr>, Box<Expr>),
    Arith(ArithOp, Box<Expr>, Box<Expr>),
    /// Unary minus; the span is the `-`.
    Neg(Box<Expr>, Span),
    /// `f(args)`; the span covers the call.
    Call(Func, Vec<Expr>, Span),
}

impl Expr {
    /// Whether a `count(...)` occurs in it.
    pub fn has_count(&self) -> bool {
        match self {
            Expr::Call(Func::Count, ..) => true,
            Expr::Call(_, args, _) => args.iter().any(Expr::has_count),
            Expr::Not(x) | Expr::Neg(x, _) => x.has_count(),
            Expr::Logic(_, a, b) | Expr::Cmp(_, a, b) | Expr::Arith(_, a, b) => {
                a.has_count() || b.has_count()
            }
            Expr::Ref(_) | Expr::Lit(..) => false,
        }
    }
}

/// What a window of an expectation starts from: a PLC time, or every
/// occurrence of an event (`after rise(l2)`; a plain condition C means
/// `rise(C)`).
#[derive(Clone, Debug, PartialEq)]
pub enum Anchor {
    Time(i64),
    Event(Expr),
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
    /// `expect C within W after A`: true after some scan in (A, A + W]
    /// (a time), in [E, E + W] after every occurrence E of an event.
    Within { after: Anchor, within: i64 },
    /// `expect always C [during A..B]`; `never C` is `always NOT C`.
    Always { from: i64, to: Option<i64> },
    /// `expect C during A..B`: C (with its `count(...)` over [A, B]) judged
    /// once, at B.
    During { from: i64, to: i64 },
    /// `expect X stable for D after A` (or `stable during A..B`): the value
    /// of X never changes in (A, A + D].
    Stable { after: Anchor, for_ns: i64 },
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

/// `when E [after D] then ACTION`: the action at every occurrence of the
/// event E (a plain condition: each time it becomes TRUE), D later.
#[derive(Clone, Debug, PartialEq)]
pub struct Reaction {
    pub event: Expr,
    pub delay_ns: i64,
    pub kind: ActionKind,
    pub line: u32,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    pub name: String,
    pub duration_ns: i64,
    pub seed: Option<u64>,
    pub actions: Vec<Action>,
    pub reactions: Vec<Reaction>,
    pub expects: Vec<Expect>,
}
