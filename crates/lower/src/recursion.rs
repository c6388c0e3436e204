//! IEC 61131-3 forbids recursion, and every POU has one static frame: a
//! call graph with a cycle is an error (E092).

use crate::cx::Cx;
use automat_base::{Code, Diagnostic};
use automat_sema::types::TypeKind;
use automat_sema::PouId;
use automat_syntax::ast::{Body, CaseLabel, Expr, ExprKind, Stmt, StmtKind};

/// The POUs a POU calls directly (functions by name, FB instances by type).
fn callees(cx: &Cx, pou: PouId) -> Vec<PouId> {
    let mut out = Vec::new();
    let Some(ast) = cx.model.pou_ast(cx.units, pou) else {
        return out;
    };
    let Body::St(stmts) = &ast.body;
    let mut exprs: Vec<&Expr> = Vec::new();
    collect_stmts(stmts, &mut exprs, 0);
    let Some(p) = cx.model.pou(pou) else {
        return out;
    };
    while let Some(e) = exprs.pop() {
        if let ExprKind::Call { callee, .. } = &e.kind {
            if let ExprKind::Name(id) = &callee.kind {
                let via_var = p
                    .vars
                    .get(id.sym)
                    .and_then(|v| match cx.model.types.get(v.ty) {
                        TypeKind::Fb { pou, .. } => Some(*pou),
                        _ => None,
                    });
                let via_global =
                    cx.globals
                        .get(&id.sym)
                        .and_then(|g| match cx.model.types.get(g.2) {
                            TypeKind::Fb { pou, .. } => Some(*pou),
                            _ => None,
                        });
                if let Some(c) = via_var
                    .or(via_global)
                    .or_else(|| cx.model.pou_named(id.sym).map(|(i, _)| i))
                {
                    out.push(c);
                }
            }
        }
        children(e, &mut exprs);
    }
    out
}

fn children<'e>(e: &'e Expr, out: &mut Vec<&'e Expr>) {
    match &e.kind {
        ExprKind::Member { base, .. }
        | ExprKind::Partial { base, .. }
        | ExprKind::Deref(base)
        | ExprKind::Paren(base) => out.push(base),
        ExprKind::Index { base, indices } => {
            out.push(base);
            out.extend(indices.iter());
        }
        ExprKind::Unary { operand, .. } => out.push(operand),
        ExprKind::Binary { lhs, rhs, .. } => {
            out.push(lhs);
            out.push(rhs);
        }
        ExprKind::Call { callee, args } => {
            out.push(callee);
            out.extend(args.iter().filter_map(|a| a.value.as_ref()));
        }
        _ => {}
    }
}

fn collect_stmts<'e>(stmts: &'e [Stmt], out: &mut Vec<&'e Expr>, depth: u32) {
    if depth > 200 {
        return;
    }
    for s in stmts {
        match &s.kind {
            StmtKind::Assign { target, value } => {
                out.push(target);
                out.push(value);
            }
            StmtKind::Expr(e) => out.push(e),
            StmtKind::If {
                branches,
                else_body,
            } => {
                for b in branches {
                    out.push(&b.cond);
                    collect_stmts(&b.body, out, depth + 1);
                }
                if let Some(b) = else_body {
                    collect_stmts(b, out, depth + 1);
                }
            }
            StmtKind::Case {
                selector,
                arms,
                else_body,
            } => {
                out.push(selector);
                for a in arms {
                    for l in &a.labels {
                        match l {
                            CaseLabel::Value(e) => out.push(e),
                            CaseLabel::Range(a, b) => {
                                out.push(a);
                                out.push(b);
                            }
                        }
                    }
                    collect_stmts(&a.body, out, depth + 1);
                }
                if let Some(b) = else_body {
                    collect_stmts(b, out, depth + 1);
                }
            }
            StmtKind::For {
                from, to, by, body, ..
            } => {
                out.push(from);
                out.push(to);
                out.extend(by.as_deref());
                collect_stmts(body, out, depth + 1);
            }
            StmtKind::While { cond, body } => {
                out.push(cond);
                collect_stmts(body, out, depth + 1);
            }
            StmtKind::Repeat { body, until } => {
                out.push(until);
                collect_stmts(body, out, depth + 1);
            }
            _ => {}
        }
    }
}

/// Reports the first cycle found in the call graph.
pub fn check(cx: &Cx) -> Result<(), Diagnostic> {
    let n = cx.model.pous.len();
    let graph: Vec<Vec<PouId>> = (0..n).map(|i| callees(cx, PouId(i as u32))).collect();
    // 0 = unvisited, 1 = on the path, 2 = done. Iterative DFS: no recursion on user input.
    let mut state = vec![0u8; n];
    for start in 0..n {
        if state[start] != 0 {
            continue;
        }
        let mut path: Vec<(usize, usize)> = vec![(start, 0)];
        state[start] = 1;
        while let Some(&mut (node, ref mut next)) = path.last_mut() {
            let succ = graph
                .get(node)
                .and_then(|g| g.get(*next))
                .map(|p| p.0 as usize);
            *next += 1;
            match succ {
                None => {
                    state[node] = 2;
                    path.pop();
                }
                Some(s) if s < n => match state[s] {
                    0 => {
                        state[s] = 1;
                        path.push((s, 0));
                    }
                    1 => {
                        let from = path.iter().position(|(p, _)| *p == s).unwrap_or(0);
                        let mut names: Vec<String> = path[from..]
                            .iter()
                            .filter_map(|(p, _)| cx.model.pou(PouId(*p as u32)))
                            .map(|p| {
                                automat_sema::names::display_name(cx.interner.name(p.name))
                                    .into_owned()
                            })
                            .collect();
                        names.push(names.first().cloned().unwrap_or_default());
                        let span = cx
                            .model
                            .pou(PouId(s as u32))
                            .map(|p| p.span)
                            .unwrap_or_default();
                        return Err(Diagnostic::error(
                            Code::E092,
                            span,
                            format!("recursive call: {}", names.join(" -> ")),
                        ));
                    }
                    _ => {}
                },
                Some(_) => {}
            }
        }
    }
    Ok(())
}
