//! Graphical jumps and labels in generated Structured Text.
//!
//! ST has no jump syntax, so the lowering writes a jump as the marker
//! assignment `__PLCOPEN_GOTO := L;` and a label as `__PLCOPEN_LABEL := L;`;
//! after parsing they become the internal `Goto`/`Label` statements, which
//! the checker verifies (E105–E107) and lowering compiles as IL jumps.

use crate::ast::{Expr, ExprKind, Stmt, StmtKind};
use automat_base::{Interner, Symbol};

/// Marker assignments [`rewrite`] turns into jumps and labels.
pub const GOTO_MARK: &str = "__PLCOPEN_GOTO";
pub const LABEL_MARK: &str = "__PLCOPEN_LABEL";

/// Turns the marker assignments of `stmts` (and of the `IF`s in them) into
/// `Goto`/`Label` statements.
pub fn rewrite(stmts: &mut [Stmt], interner: &mut Interner) {
    let marks = Marks {
        goto: interner.intern(GOTO_MARK),
        label: interner.intern(LABEL_MARK),
    };
    marks.rewrite(stmts);
}

struct Marks {
    goto: Symbol,
    label: Symbol,
}

impl Marks {
    fn rewrite(&self, stmts: &mut [Stmt]) {
        for s in stmts {
            let marker = match &s.kind {
                StmtKind::Assign {
                    target:
                        Expr {
                            kind: ExprKind::Name(t),
                            ..
                        },
                    value:
                        Expr {
                            kind: ExprKind::Name(v),
                            ..
                        },
                } if t.sym == self.goto || t.sym == self.label => Some((t.sym == self.goto, *v)),
                _ => None,
            };
            match marker {
                Some((true, l)) => s.kind = StmtKind::Goto(l),
                Some((false, l)) => s.kind = StmtKind::Label(l),
                None => {
                    if let StmtKind::If {
                        branches,
                        else_body,
                    } = &mut s.kind
                    {
                        for b in branches {
                            self.rewrite(&mut b.body);
                        }
                        if let Some(e) = else_body {
                            self.rewrite(e);
                        }
                    }
                }
            }
        }
    }
}
