//! Direct addresses written in code (`%QW3 := x;`) rather than declared
//! (`v AT %QW3 : WORD`): the areas must cover them too, so they are
//! collected from every POU body before the layout sizes the areas.

use automat_syntax::ast::{Body, CaseLabel, DirectAddress, Expr, ExprKind, Item, SourceUnit};
use automat_syntax::ast::{Stmt, StmtKind};

/// Every direct address used in an expression of any POU body.
pub fn in_bodies(units: &[SourceUnit]) -> Vec<DirectAddress> {
    let mut out = Vec::new();
    for u in units {
        for item in &u.items {
            if let Item::Pou(p) = item {
                let Body::St(stmts) = &p.body;
                block(stmts, &mut out);
            }
        }
    }
    out
}

fn block(stmts: &[Stmt], out: &mut Vec<DirectAddress>) {
    for s in stmts {
        stmt(s, out);
    }
}

fn stmt(s: &Stmt, out: &mut Vec<DirectAddress>) {
    match &s.kind {
        StmtKind::Assign { target, value } => {
            expr(target, out);
            expr(value, out);
        }
        StmtKind::Expr(e) => expr(e, out),
        StmtKind::If {
            branches,
            else_body,
        } => {
            for b in branches {
                expr(&b.cond, out);
                block(&b.body, out);
            }
            block(else_body.as_deref().unwrap_or(&[]), out);
        }
        StmtKind::Case {
            selector,
            arms,
            else_body,
        } => {
            expr(selector, out);
            for a in arms {
                for l in &a.labels {
                    match l {
                        CaseLabel::Value(v) => expr(v, out),
                        CaseLabel::Range(lo, hi) => {
                            expr(lo, out);
                            expr(hi, out);
                        }
                    }
                }
                block(&a.body, out);
            }
            block(else_body.as_deref().unwrap_or(&[]), out);
        }
        StmtKind::For {
            from, to, by, body, ..
        } => {
            expr(from, out);
            expr(to, out);
            if let Some(b) = by {
                expr(b, out);
            }
            block(body, out);
        }
        StmtKind::While { cond, body } | StmtKind::Repeat { body, until: cond } => {
            expr(cond, out);
            block(body, out);
        }
        StmtKind::Return
        | StmtKind::Exit
        | StmtKind::Continue
        | StmtKind::Empty
        | StmtKind::Label(_)
        | StmtKind::Goto(_) => {}
    }
}

fn expr(e: &Expr, out: &mut Vec<DirectAddress>) {
    match &e.kind {
        ExprKind::Address(a) => out.push((**a).clone()),
        ExprKind::Member { base, .. }
        | ExprKind::Partial { base, .. }
        | ExprKind::Deref(base)
        | ExprKind::Paren(base)
        | ExprKind::Unary { operand: base, .. } => expr(base, out),
        ExprKind::Index { base, indices } => {
            expr(base, out);
            for i in indices {
                expr(i, out);
            }
        }
        ExprKind::Binary { lhs, rhs, .. } => {
            expr(lhs, out);
            expr(rhs, out);
        }
        ExprKind::Call { callee, args } => {
            expr(callee, out);
            for a in args {
                if let Some(v) = &a.value {
                    expr(v, out);
                }
            }
        }
        ExprKind::Literal(_) | ExprKind::Name(_) | ExprKind::Error => {}
    }
}
