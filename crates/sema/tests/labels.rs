//! Labels and jumps (`StmtKind::Label` / `Goto`, produced by the IL
//! desugaring): E105, E106, E107, and W002 after an unconditional jump.

use automat_base::{FileId, Interner};
use automat_sema::check;
use automat_syntax::ast::*;

/// The codes of the diagnostics of `src`, after `edit` changed its first POU's body.
fn codes_after(src: &str, edit: impl FnOnce(&mut Vec<Stmt>)) -> Vec<&'static str> {
    let mut i = Interner::new();
    let mut parsed = automat_syntax::parse(FileId(0), src, &mut i);
    assert!(parsed.diagnostics.is_empty(), "{:?}", parsed.diagnostics);
    if let Some(Item::Pou(p)) = parsed.unit.items.first_mut() {
        let Body::St(b) = &mut p.body;
        edit(b);
    }
    let a = check(std::slice::from_ref(&parsed.unit), &mut i);
    a.diagnostics.iter().map(|d| d.code.as_str()).collect()
}

const IL: &str = "PROGRAM P\nVAR x : BOOL; END_VAR\n    LD x\n    JMPC L1\n    LD TRUE\n    ST x\nL1:\n    LD x\n    ST x\nEND_PROGRAM\n";

#[test]
fn il_labels_and_jumps_check_clean() {
    assert_eq!(codes_after(IL, |_| {}), Vec::<&str>::new());
}

#[test]
fn a_jump_into_nested_statements_is_e107() {
    // Move the label into an IF: the jump would enter it.
    let codes = codes_after(IL, |b| {
        let pos = b
            .iter()
            .position(|s| matches!(s.kind, StmtKind::Label(_)))
            .expect("the IL body has a label");
        let label = b.remove(pos);
        let cond = Expr {
            kind: ExprKind::Literal(Box::new(Literal {
                kind: LitKind::Bool(true),
                ty: None,
            })),
            span: label.span,
        };
        b.push(Stmt {
            span: label.span,
            kind: StmtKind::If {
                branches: vec![CondBlock {
                    cond,
                    body: vec![label],
                    span: b[0].span,
                }],
                else_body: None,
            },
        });
    });
    assert_eq!(codes, vec!["E107"]);
}

#[test]
fn a_jump_out_of_nested_statements_is_fine() {
    let codes = codes_after(IL, |b| {
        // Wrap the conditional jump (an IF) in another IF.
        let jump = b.remove(0);
        let cond = Expr {
            kind: ExprKind::Literal(Box::new(Literal {
                kind: LitKind::Bool(true),
                ty: None,
            })),
            span: jump.span,
        };
        b.insert(
            0,
            Stmt {
                span: jump.span,
                kind: StmtKind::If {
                    branches: vec![CondBlock {
                        cond,
                        body: vec![jump],
                        span: b[0].span,
                    }],
                    else_body: None,
                },
            },
        );
    });
    assert_eq!(codes, Vec::<&str>::new());
}

#[test]
fn code_after_an_unconditional_jump_is_unreachable_until_a_label() {
    let src = "PROGRAM P\nVAR x : BOOL; END_VAR\n    JMP L1\n    LD TRUE\n    ST x\nL1:\n    LD x\n    ST x\n    JMP L1\nEND_PROGRAM\n";
    assert_eq!(codes_after(src, |_| {}), vec!["W002"]);
}

#[test]
fn duplicate_and_unknown_labels() {
    let src = "PROGRAM P\nVAR x : BOOL; END_VAR\nA:\n    LD x\n    JMPC B\nA:\n    LD x\n    ST x\nEND_PROGRAM\n";
    let mut codes = codes_after(src, |_| {});
    codes.sort_unstable();
    assert_eq!(codes, vec!["E105", "E106"]);
}
