//! `ENO` assigned in the body of a function or function block that does
//! not declare it (IEC 61131-3 §6.6.1.2.3: every function and FB has the
//! execution-control output ENO; the body may set it FALSE). Such a POU
//! gets `VAR_OUTPUT ENO : BOOL := TRUE; END_VAR` and its body starts with
//! `ENO := TRUE;`, so each call that runs the body begins with ENO TRUE
//! and the caller's `ENO => x` reads what the body left. POUs that never
//! assign ENO are left alone (no byte, no store).

use crate::ast::{
    Expr, ExprKind, Ident, Initializer, Item, LitKind, Literal, Pou, PouKind, SourceUnit, Stmt,
    StmtKind, TypeSpec, VarBlock, VarDecl, VarKind,
};
use automat_base::{Interner, Symbol};

/// Adds the implicit ENO output where a body assigns an undeclared ENO.
pub fn implicit_eno(units: &mut [SourceUnit], interner: &mut Interner) {
    let eno = interner.intern("ENO");
    let bool_ty = interner.intern("BOOL");
    for unit in units.iter_mut() {
        for item in &mut unit.items {
            if let Item::Pou(p) = item {
                if matches!(p.kind, PouKind::Function | PouKind::FunctionBlock)
                    && !declares(p, eno)
                    && assigns(body(p), eno)
                {
                    add(p, eno, bool_ty);
                }
            }
        }
    }
}

fn body(p: &Pou) -> &[Stmt] {
    match &p.body {
        crate::ast::Body::St(s) => s,
    }
}

fn declares(p: &Pou, eno: Symbol) -> bool {
    p.var_blocks
        .iter()
        .flat_map(|b| &b.decls)
        .flat_map(|d| &d.names)
        .any(|n| n.sym == eno)
}

/// Whether a statement of `stmts` (at any depth) assigns `eno`.
fn assigns(stmts: &[Stmt], eno: Symbol) -> bool {
    stmts.iter().any(|s| match &s.kind {
        StmtKind::Assign { target, .. } => {
            matches!(&target.kind, ExprKind::Name(id) if id.sym == eno)
        }
        StmtKind::If {
            branches,
            else_body,
        } => {
            branches.iter().any(|b| assigns(&b.body, eno))
                || else_body.as_deref().is_some_and(|e| assigns(e, eno))
        }
        StmtKind::Case {
            arms, else_body, ..
        } => {
            arms.iter().any(|a| assigns(&a.body, eno))
                || else_body.as_deref().is_some_and(|e| assigns(e, eno))
        }
        StmtKind::For { body, .. }
        | StmtKind::While { body, .. }
        | StmtKind::Repeat { body, .. } => assigns(body, eno),
        _ => false,
    })
}

fn add(p: &mut Pou, eno: Symbol, bool_ty: Symbol) {
    // The declaration and the reset point at the POU's name: that is where
    // a message about them belongs.
    let span = p.name.span;
    let yes = || Expr {
        kind: ExprKind::Literal(Box::new(Literal {
            kind: LitKind::Bool(true),
            ty: None,
        })),
        span,
    };
    let name = Ident { sym: eno, span };
    p.var_blocks.push(VarBlock {
        kind: VarKind::Output,
        constant: false,
        retain: Default::default(),
        decls: vec![VarDecl {
            names: vec![name],
            location: None,
            ty: TypeSpec::Named(Ident { sym: bool_ty, span }),
            edge: None,
            init: Some(Initializer::Expr(yes())),
            span,
        }],
        span,
    });
    let crate::ast::Body::St(stmts) = &mut p.body;
    stmts.insert(
        0,
        Stmt {
            kind: StmtKind::Assign {
                target: Expr {
                    kind: ExprKind::Name(name),
                    span,
                },
                value: yes(),
            },
            span,
        },
    );
}
