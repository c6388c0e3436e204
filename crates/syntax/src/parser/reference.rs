//! CODESYS references: the type `REFERENCE TO T` (in `types.rs`) and the
//! binding statement `r REF= x;`. Both are the `codesys` dialect's; without
//! it they are still parsed (so the rest of the file checks) and reported.

use super::Parser;
use crate::ast::{Arg, ArgDir, Expr, ExprKind, Ident, Initializer, Stmt, StmtKind};
use automat_base::{Code, Diagnostic};

/// The hidden callee `r REF= x` is parsed into (`r := __REFBIND(x)`):
/// `desugar::reference` turns it into `r := REF(x)` without dereferencing `r`.
pub(crate) const REF_BIND: &str = "__REFBIND";

impl Parser<'_> {
    /// E005 at the current token when the dialect is not CODESYS.
    pub(super) fn codesys_reference_word(&mut self, what: &str) {
        if self.opts.codesys {
            return;
        }
        let span = self.tok_span(self.cur());
        self.report(
            Diagnostic::error(Code::E005, span, what.to_string())
                .with_note("check with `--lib codesys` (or `libraries = [\"codesys\"]` in automat.toml) to read CODESYS code"),
        );
    }

    /// `r : REFERENCE TO T REF= x;`, at `REF`: the initial value `REF(x)`.
    pub(super) fn ref_bind_init(&mut self) -> Initializer {
        self.codesys_reference_word("`REF=` binds a CODESYS reference");
        let op = self.bump();
        self.bump();
        let value = self.expr();
        let span = value.span;
        let callee = Expr {
            kind: ExprKind::Name(Ident {
                sym: self.interner.intern("REF"),
                span: self.tok_span(op),
            }),
            span: self.tok_span(op),
        };
        Initializer::Expr(Expr {
            kind: ExprKind::Call {
                callee: Box::new(callee),
                args: vec![Arg {
                    name: None,
                    dir: ArgDir::In,
                    value: Some(value),
                    span,
                }],
            },
            span,
        })
    }

    /// `target REF= value;`, at `REF`.
    pub(super) fn ref_bind(&mut self, start: u32, target: Expr) -> Stmt {
        self.codesys_reference_word("`REF=` binds a CODESYS reference");
        let op = self.bump();
        self.bump();
        let value = self.expr();
        let span = self.span_from(start);
        self.end_stmt("after the assignment");
        let callee = Expr {
            kind: ExprKind::Name(Ident {
                sym: self.interner.intern(REF_BIND),
                span: self.tok_span(op),
            }),
            span: self.tok_span(op),
        };
        let vspan = value.span;
        let value = Expr {
            kind: ExprKind::Call {
                callee: Box::new(callee),
                args: vec![Arg {
                    name: None,
                    dir: ArgDir::In,
                    value: Some(value),
                    span: vspan,
                }],
            },
            span: vspan,
        };
        Stmt {
            kind: StmtKind::Assign { target, value },
            span,
        }
    }
}
