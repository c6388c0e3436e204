//! Labels and jumps of one body (`StmtKind::Label` / `StmtKind::Goto`, which
//! the IL desugaring produces): labels are unique per body (E105), a jump
//! names a label of the body (E106) in its own statement list or an
//! enclosing one — it may leave nested statements, never enter them (E107),
//! which is what lets lowering treat a jump as a plain IR jump.

use super::{Checker, MAX_EXPR_DEPTH};
use automat_base::{Code, Span, Symbol};
use automat_syntax::ast::{Ident, Stmt, StmtKind};
use rustc_hash::FxHashMap;

/// What the walk found: every label with the list it is in, every jump with
/// the lists enclosing it (innermost last).
#[derive(Default)]
struct Found {
    labels: FxHashMap<Symbol, (u32, Span)>,
    dups: Vec<Ident>,
    gotos: Vec<(Ident, Vec<u32>)>,
    next_list: u32,
}

impl Found {
    fn list(&mut self, stmts: &[Stmt], chain: &mut Vec<u32>, depth: u32) {
        // Deeper nesting was reported by the statement checker.
        if depth > MAX_EXPR_DEPTH {
            return;
        }
        let id = self.next_list;
        self.next_list += 1;
        chain.push(id);
        for s in stmts {
            match &s.kind {
                StmtKind::Label(l) => match self.labels.entry(l.sym) {
                    std::collections::hash_map::Entry::Occupied(_) => self.dups.push(*l),
                    std::collections::hash_map::Entry::Vacant(v) => {
                        v.insert((id, l.span));
                    }
                },
                StmtKind::Goto(l) => self.gotos.push((*l, chain.clone())),
                StmtKind::If {
                    branches,
                    else_body,
                } => {
                    for b in branches {
                        self.list(&b.body, chain, depth + 1);
                    }
                    if let Some(b) = else_body {
                        self.list(b, chain, depth + 1);
                    }
                }
                StmtKind::Case {
                    arms, else_body, ..
                } => {
                    for a in arms {
                        self.list(&a.body, chain, depth + 1);
                    }
                    if let Some(b) = else_body {
                        self.list(b, chain, depth + 1);
                    }
                }
                StmtKind::For { body, .. }
                | StmtKind::While { body, .. }
                | StmtKind::Repeat { body, .. } => self.list(body, chain, depth + 1),
                _ => {}
            }
        }
        chain.pop();
    }
}

/// How a label is shown: the SFC desugaring scopes the labels of each IL
/// action/transition as `<scope>.<label>` (a `.` cannot occur in a user's
/// identifier); a hidden scope (`__t12.L1`) is not shown, a named one
/// (`Fill.L1`) is, as it tells which text the label is in.
fn shown(text: &str) -> &str {
    match text.split_once('.') {
        Some((scope, rest)) if scope.starts_with("__") => rest,
        _ => text,
    }
}

/// Whether a body contains a label or a jump anywhere (cheap pre-check:
/// ST bodies have none, and most checks can then be skipped).
fn has_jumps(stmts: &[Stmt], depth: u32) -> bool {
    if depth > MAX_EXPR_DEPTH {
        return false;
    }
    stmts.iter().any(|s| match &s.kind {
        StmtKind::Label(_) | StmtKind::Goto(_) => true,
        StmtKind::If {
            branches,
            else_body,
        } => {
            branches.iter().any(|b| has_jumps(&b.body, depth + 1))
                || else_body
                    .as_deref()
                    .is_some_and(|b| has_jumps(b, depth + 1))
        }
        StmtKind::Case {
            arms, else_body, ..
        } => {
            arms.iter().any(|a| has_jumps(&a.body, depth + 1))
                || else_body
                    .as_deref()
                    .is_some_and(|b| has_jumps(b, depth + 1))
        }
        StmtKind::For { body, .. }
        | StmtKind::While { body, .. }
        | StmtKind::Repeat { body, .. } => has_jumps(body, depth + 1),
        _ => false,
    })
}

impl Checker<'_> {
    /// E105, E106, E107 for the labels and jumps of one body.
    pub(crate) fn check_labels(&mut self, body: &[Stmt]) {
        if !has_jumps(body, 0) {
            return;
        }
        let mut found = Found::default();
        found.list(body, &mut Vec::new(), 0);
        for d in &found.dups {
            let first = found.labels.get(&d.sym).map(|&(_, sp)| sp);
            let sym = d.sym;
            self.diag(|c| {
                let mut diag = automat_base::Diagnostic::error(
                    Code::E105,
                    d.span,
                    format!("the label `{}` is declared twice", shown(c.name(sym))),
                );
                if let Some(sp) = first {
                    diag = diag.with_label(sp, "first declared here");
                }
                diag
            });
        }
        for (g, chain) in &found.gotos {
            match found.labels.get(&g.sym) {
                None => {
                    let sym = g.sym;
                    self.err(Code::E106, g.span, |c| {
                        format!("unknown label `{}` {}", shown(c.name(sym)), c.where_())
                    });
                }
                Some(&(list, _)) if !chain.contains(&list) => {
                    let sym = g.sym;
                    self.err(Code::E107, g.span, |c| {
                        format!(
                            "the jump to `{}` would enter nested statements: a jump may only go to a label in its own statement list or an enclosing one",
                            shown(c.name(sym))
                        )
                    });
                }
                Some(_) => {}
            }
        }
    }
}
