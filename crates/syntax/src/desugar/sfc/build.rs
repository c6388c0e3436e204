//! Small constructors of ST nodes for the generated code: every node gets
//! the span of the chart text it comes from.

use crate::ast::{
    Arg, ArgDir, BinaryOp, CondBlock, Expr, ExprKind, Ident, LitKind, Literal, Stmt, StmtKind,
    TypeSpec, UnaryOp, VarDecl,
};
use automat_base::{Interner, Span, Symbol};

pub(super) struct Builder<'a> {
    pub interner: &'a mut Interner,
}

impl Builder<'_> {
    pub fn sym(&mut self, name: &str) -> Symbol {
        self.interner.intern(name)
    }

    pub fn ident(&mut self, name: &str, span: Span) -> Ident {
        Ident {
            sym: self.sym(name),
            span,
        }
    }

    /// `inst.member`
    pub fn member(&mut self, inst: Symbol, member: &str, span: Span) -> Expr {
        let member = self.ident(member, span);
        Expr {
            kind: ExprKind::Member {
                base: Box::new(var(inst, span)),
                member,
            },
            span,
        }
    }

    /// A call of a standard function without arguments (`__SCAN_TIME()`).
    pub fn call0(&mut self, name: &str, span: Span) -> Expr {
        let callee = self.ident(name, span);
        Expr {
            kind: ExprKind::Call {
                callee: Box::new(Expr {
                    kind: ExprKind::Name(callee),
                    span,
                }),
                args: Vec::new(),
            },
            span,
        }
    }

    /// `inst(a := x, b := y);`
    pub fn call_stmt(&mut self, inst: Symbol, args: Vec<(&str, Expr)>, span: Span) -> Stmt {
        let args = args
            .into_iter()
            .map(|(name, value)| Arg {
                name: Some(self.ident(name, span)),
                dir: ArgDir::In,
                value: Some(value),
                span,
            })
            .collect();
        let call = Expr {
            kind: ExprKind::Call {
                callee: Box::new(var(inst, span)),
                args,
            },
            span,
        };
        Stmt {
            kind: StmtKind::Expr(call),
            span,
        }
    }

    /// `name : ty [:= init];`
    pub fn decl(&mut self, name: Symbol, ty: &str, init: Option<Expr>, span: Span) -> VarDecl {
        let ty = TypeSpec::Named(self.ident(ty, span));
        VarDecl {
            names: vec![Ident { sym: name, span }],
            location: None,
            ty,
            edge: None,
            init: init.map(crate::ast::Initializer::Expr),
            span,
        }
    }
}

/// A variable read by symbol.
pub(super) fn var(sym: Symbol, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Name(Ident { sym, span }),
        span,
    }
}

pub(super) fn bool_lit(b: bool, span: Span) -> Expr {
    lit(LitKind::Bool(b), span)
}

/// `a OR b OR ...`, `FALSE` when empty.
pub(super) fn or_all(terms: Vec<Expr>, span: Span) -> Expr {
    chain(terms, BinaryOp::Or, span).unwrap_or_else(|| bool_lit(false, span))
}

/// `a AND b AND ...`, `None` when empty.
pub(super) fn and_all(terms: Vec<Expr>, span: Span) -> Option<Expr> {
    chain(terms, BinaryOp::And, span)
}

fn chain(terms: Vec<Expr>, op: BinaryOp, span: Span) -> Option<Expr> {
    terms.into_iter().reduce(|lhs, rhs| Expr {
        kind: ExprKind::Binary {
            op,
            lhs: Box::new(lhs),
            rhs: Box::new(rhs),
        },
        span,
    })
}

pub(super) fn not(e: Expr, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Unary {
            op: UnaryOp::Not,
            operand: Box::new(e),
        },
        span,
    }
}

pub(super) fn binary(op: BinaryOp, lhs: Expr, rhs: Expr, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Binary {
            op,
            lhs: Box::new(lhs),
            rhs: Box::new(rhs),
        },
        span,
    }
}

pub(super) fn assign(target: Expr, value: Expr, span: Span) -> Stmt {
    Stmt {
        kind: StmtKind::Assign { target, value },
        span,
    }
}

pub(super) fn if_then(cond: Expr, body: Vec<Stmt>, span: Span) -> Stmt {
    Stmt {
        kind: StmtKind::If {
            branches: vec![CondBlock { cond, body, span }],
            else_body: None,
        },
        span,
    }
}

fn lit(kind: LitKind, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Literal(Box::new(Literal { kind, ty: None })),
        span,
    }
}
