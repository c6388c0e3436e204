//! Small constructors for the ST nodes the rewrites produce. Every node gets
//! the span of the text it stands for, so a diagnostic about generated code
//! points at what the user wrote.

use automat_base::{Interner, Span};
use automat_syntax::ast::{
    Arg, BinaryOp, CondBlock, Expr, ExprKind, Ident, LitKind, Literal, Stmt, StmtKind, TypeSpec,
    VarDecl,
};

pub fn ident(interner: &mut Interner, name: &str, span: Span) -> Ident {
    Ident {
        sym: interner.intern(name),
        span,
    }
}

pub fn name(id: Ident) -> Expr {
    Expr {
        kind: ExprKind::Name(id),
        span: id.span,
    }
}

pub fn bool_lit(v: bool, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Literal(Box::new(Literal {
            kind: LitKind::Bool(v),
            ty: None,
        })),
        span,
    }
}

pub fn binary(op: BinaryOp, lhs: Expr, rhs: Expr, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Binary {
            op,
            lhs: Box::new(lhs),
            rhs: Box::new(rhs),
        },
        span,
    }
}

/// `f()` with no argument (used for `__SCAN_TIME()`).
pub fn call0(callee: Ident) -> Expr {
    Expr {
        kind: ExprKind::Call {
            callee: Box::new(name(callee)),
            args: Vec::<Arg>::new(),
        },
        span: callee.span,
    }
}

pub fn assign(target: Expr, value: Expr, span: Span) -> Stmt {
    Stmt {
        kind: StmtKind::Assign { target, value },
        span,
    }
}

pub fn if_then(cond: Expr, body: Vec<Stmt>, span: Span) -> Stmt {
    Stmt {
        kind: StmtKind::If {
            branches: vec![CondBlock { cond, body, span }],
            else_body: None,
        },
        span,
    }
}

/// `IF cond THEN body ELSE else_body END_IF`
pub fn if_else(cond: Expr, body: Vec<Stmt>, else_body: Vec<Stmt>, span: Span) -> Stmt {
    Stmt {
        kind: StmtKind::If {
            branches: vec![CondBlock { cond, body, span }],
            else_body: Some(else_body),
        },
        span,
    }
}

/// `name : ty;`
pub fn var(id: Ident, ty: Ident) -> VarDecl {
    VarDecl {
        names: vec![id],
        location: None,
        ty: TypeSpec::Named(ty),
        edge: None,
        init: None,
        span: id.span,
    }
}

pub fn int_lit(v: i128, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Literal(Box::new(Literal {
            kind: LitKind::Int(v),
            ty: None,
        })),
        span,
    }
}

/// `base.member`
pub fn member(interner: &mut Interner, base: Ident, member: &str, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Member {
            base: Box::new(name(Ident { span, ..base })),
            member: ident(interner, member, span),
        },
        span,
    }
}

pub fn not(e: Expr, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Unary {
            op: automat_syntax::ast::UnaryOp::Not,
            operand: Box::new(e),
        },
        span,
    }
}

/// `inst(a := x, b := y);`
pub fn call_stmt(
    interner: &mut Interner,
    inst: Ident,
    args: Vec<(&str, Expr)>,
    span: Span,
) -> Stmt {
    let args = args
        .into_iter()
        .map(|(n, value)| Arg {
            name: Some(ident(interner, n, span)),
            dir: automat_syntax::ast::ArgDir::In,
            value: Some(value),
            span,
        })
        .collect();
    Stmt {
        kind: StmtKind::Expr(Expr {
            kind: ExprKind::Call {
                callee: Box::new(name(Ident { span, ..inst })),
                args,
            },
            span,
        }),
        span,
    }
}

/// `IF c1 THEN b1 ELSIF c2 THEN b2 ... END_IF`
pub fn if_chain(branches: Vec<(Expr, Vec<Stmt>)>, span: Span) -> Stmt {
    Stmt {
        kind: StmtKind::If {
            branches: branches
                .into_iter()
                .map(|(cond, body)| CondBlock { cond, body, span })
                .collect(),
            else_body: None,
        },
        span,
    }
}
