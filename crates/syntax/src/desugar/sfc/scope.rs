//! Label scoping for IL texts of a chart.
//!
//! Every IL action and IL transition condition of a chart is its own IL
//! list, so each has its own label names; but after desugaring they all
//! end up in one ST body, where the checker (E105) and lowering match
//! labels by name. Each text's labels are therefore renamed
//! `<scope>.<label>` (the action's or transition's name; an unnamed
//! transition gets a hidden `__t<offset>` scope). A `.` cannot occur in an
//! identifier, so a renamed label never meets a user's one; the checker
//! prints the part after the `.` of a hidden scope
//! (`sema/src/body/labels.rs`).

use crate::ast::{Stmt, StmtKind};
use automat_base::{Interner, Symbol};

/// Deeper statement nesting is refused by the checker; nothing to rename.
const MAX_DEPTH: u32 = 256;

/// Renames every `Label`/`Goto` of `stmts` (at any nesting) into `scope`.
pub(crate) fn scope_labels(stmts: &mut [Stmt], scope: &str, interner: &mut Interner) {
    walk(stmts, scope, interner, 0);
}

fn walk(stmts: &mut [Stmt], scope: &str, interner: &mut Interner, depth: u32) {
    if depth > MAX_DEPTH {
        return;
    }
    for s in stmts {
        match &mut s.kind {
            StmtKind::Label(l) | StmtKind::Goto(l) => l.sym = scoped(l.sym, scope, interner),
            StmtKind::If {
                branches,
                else_body,
            } => {
                for b in branches {
                    walk(&mut b.body, scope, interner, depth + 1);
                }
                if let Some(b) = else_body {
                    walk(b, scope, interner, depth + 1);
                }
            }
            StmtKind::Case {
                arms, else_body, ..
            } => {
                for a in arms {
                    walk(&mut a.body, scope, interner, depth + 1);
                }
                if let Some(b) = else_body {
                    walk(b, scope, interner, depth + 1);
                }
            }
            StmtKind::For { body, .. }
            | StmtKind::While { body, .. }
            | StmtKind::Repeat { body, .. } => walk(body, scope, interner, depth + 1),
            _ => {}
        }
    }
}

fn scoped(sym: Symbol, scope: &str, interner: &mut Interner) -> Symbol {
    let text = format!("{scope}.{}", interner.name(sym));
    interner.intern(&text)
}
