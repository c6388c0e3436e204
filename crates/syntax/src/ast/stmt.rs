//! Statements of Structured Text.

use super::{Expr, Ident};
use automat_base::Span;

#[derive(Clone, Debug, PartialEq)]
pub struct Stmt {
    pub kind: StmtKind,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum StmtKind {
    /// `target := value;`
    Assign {
        target: Expr,
        value: Expr,
    },
    /// An expression statement; valid only when it is a call (`fb(...)`, `f(x)`).
    Expr(Expr),
    Return,
    /// `IF c THEN ... ELSIF c THEN ... ELSE ... END_IF`
    If {
        branches: Vec<CondBlock>,
        else_body: Option<Vec<Stmt>>,
    },
    Case {
        selector: Expr,
        arms: Vec<CaseArm>,
        else_body: Option<Vec<Stmt>>,
    },
    /// The bounds are boxed so that this rare statement does not make
    /// every `Stmt` large.
    For {
        var: Ident,
        from: Box<Expr>,
        to: Box<Expr>,
        by: Option<Box<Expr>>,
        body: Vec<Stmt>,
    },
    While {
        cond: Expr,
        body: Vec<Stmt>,
    },
    Repeat {
        body: Vec<Stmt>,
        until: Expr,
    },
    Exit,
    Continue,
    /// A lone `;`.
    Empty,
    /// `name:` — a jump target. Never written in ST: produced by the IL
    /// desugaring (`desugar::il`), so later stages see IL jumps as ST.
    Label(Ident),
    /// A jump to a [`StmtKind::Label`] of the same body, in the same
    /// statement list or an enclosing one (never into a nested block).
    /// Like `Label`, only produced by desugaring.
    Goto(Ident),
}

#[derive(Clone, Debug, PartialEq)]
pub struct CondBlock {
    pub cond: Expr,
    pub body: Vec<Stmt>,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub struct CaseArm {
    pub labels: Vec<CaseLabel>,
    pub body: Vec<Stmt>,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum CaseLabel {
    /// A constant: integer, enumeration value (`Red`, `Color#Red`), constant name.
    Value(Expr),
    /// `lo..hi`
    Range(Expr, Expr),
}
