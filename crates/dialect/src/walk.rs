//! A mutable walk over statements and expressions, for the rewrites that
//! replace calls and names wherever they occur. Statements are visited
//! before their children (so a visitor may replace a whole statement),
//! expressions both before (`expr_pre`, which may stop the descent) and
//! after theirs. The plain-name callee of a call is not visited. Depth is
//! bounded by the parser's nesting limit.

use automat_syntax::ast::{CaseLabel, Expr, ExprKind, Stmt, StmtKind};

pub trait Visitor {
    fn stmt(&mut self, _s: &mut Stmt) {}
    /// Before an expression's children; `false`: do not visit them (nor
    /// call [`Visitor::expr`] on it).
    fn expr_pre(&mut self, _e: &mut Expr) -> bool {
        true
    }
    fn expr(&mut self, _e: &mut Expr) {}
}

pub fn stmts(list: &mut [Stmt], v: &mut dyn Visitor) {
    for s in list {
        stmt(s, v);
    }
}

fn stmt(s: &mut Stmt, v: &mut dyn Visitor) {
    v.stmt(s);
    match &mut s.kind {
        StmtKind::Assign { target, value } => {
            expr(target, v);
            expr(value, v);
        }
        StmtKind::Expr(e) => expr(e, v),
        StmtKind::If {
            branches,
            else_body,
        } => {
            for b in branches {
                expr(&mut b.cond, v);
                stmts(&mut b.body, v);
            }
            if let Some(e) = else_body {
                stmts(e, v);
            }
        }
        StmtKind::Case {
            selector,
            arms,
            else_body,
        } => {
            expr(selector, v);
            for a in arms {
                for l in &mut a.labels {
                    match l {
                        CaseLabel::Value(e) => expr(e, v),
                        CaseLabel::Range(a, b) => {
                            expr(a, v);
                            expr(b, v);
                        }
                    }
                }
                stmts(&mut a.body, v);
            }
            if let Some(e) = else_body {
                stmts(e, v);
            }
        }
        StmtKind::For {
            from, to, by, body, ..
        } => {
            expr(from, v);
            expr(to, v);
            if let Some(b) = by {
                expr(b, v);
            }
            stmts(body, v);
        }
        StmtKind::While { cond, body } => {
            expr(cond, v);
            stmts(body, v);
        }
        StmtKind::Repeat { body, until } => {
            stmts(body, v);
            expr(until, v);
        }
        _ => {}
    }
}

fn expr(e: &mut Expr, v: &mut dyn Visitor) {
    if !v.expr_pre(e) {
        return;
    }
    match &mut e.kind {
        ExprKind::Member { base, .. }
        | ExprKind::Partial { base, .. }
        | ExprKind::Deref(base)
        | ExprKind::Paren(base) => expr(base, v),
        ExprKind::Index { base, indices } => {
            expr(base, v);
            for i in indices {
                expr(i, v);
            }
        }
        ExprKind::Unary { operand, .. } => expr(operand, v),
        ExprKind::Binary { lhs, rhs, .. } => {
            expr(lhs, v);
            expr(rhs, v);
        }
        ExprKind::Call { callee, args } => {
            // A callee that is a plain name names a POU or an instance,
            // never a value.
            if !matches!(callee.kind, ExprKind::Name(_)) {
                expr(callee, v);
            }
            for a in args {
                if let Some(x) = &mut a.value {
                    expr(x, v);
                }
            }
        }
        _ => {}
    }
    v.expr(e);
}
