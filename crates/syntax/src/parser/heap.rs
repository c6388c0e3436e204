//! CODESYS V3 `__NEW(T)` and `__NEW(T, n)` (`--lib codesys`): the first
//! argument is a type, not an expression. It becomes a hidden global of
//! that type, `__NEW_<file>_<k>` (its initial values are those a new
//! object gets), written in its place: `SIZEOF` and `ADR` of it are what the
//! `codesys` dialect's rewrite passes to the allocator
//! (`automat_dialect`, `program_access`'s neighbour `heap`).

use super::Parser;
use crate::ast::{Arg, ArgDir, Expr, ExprKind, Ident, Retain, VarBlock, VarDecl, VarKind};
use crate::lexer::Tok;

impl Parser<'_> {
    /// At `__NEW` followed by `(`.
    pub(super) fn at_heap_new(&self) -> bool {
        self.opts.codesys && self.is_word("__NEW") && self.nth(1) == Tok::LParen
    }

    /// `__NEW(T [, n])`, at `__NEW`.
    pub(super) fn heap_new(&mut self) -> Expr {
        let t = self.bump();
        let callee_span = self.tok_span(t);
        let callee = Ident {
            sym: self.interner.intern(self.text(t)),
            span: callee_span,
        };
        self.bump();
        let ty_start = self.cur().start;
        let ty = self.type_spec();
        let ty_span = self.span_from(ty_start);
        let mut args = Vec::new();
        if let Some(ty) = ty {
            let name = format!("__NEW_{}_{}", self.file.0, self.heap_templates.len());
            let sym = self.interner.intern(&name);
            let id = Ident { sym, span: ty_span };
            self.heap_templates.push(VarBlock {
                kind: VarKind::Global,
                constant: false,
                retain: Retain::Unspecified,
                decls: vec![VarDecl {
                    names: vec![id],
                    location: None,
                    ty,
                    edge: None,
                    init: None,
                    span: ty_span,
                }],
                span: ty_span,
            });
            args.push(Arg {
                name: None,
                dir: ArgDir::In,
                value: Some(Expr {
                    kind: ExprKind::Name(id),
                    span: ty_span,
                }),
                span: ty_span,
            });
        }
        while self.eat(Tok::Comma) {
            let value = self.expr();
            args.push(Arg {
                name: None,
                dir: ArgDir::In,
                span: value.span,
                value: Some(value),
            });
        }
        self.expect(Tok::RParen, "to close the argument list");
        let span = self.span_from(callee_span.start);
        Expr {
            kind: ExprKind::Call {
                callee: Box::new(Expr {
                    kind: ExprKind::Name(callee),
                    span: callee_span,
                }),
                args,
            },
            span,
        }
    }
}
