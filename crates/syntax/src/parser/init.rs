//! Initial values: expressions, array initialisers `[1, 2, 3(7), 2([1, 2]), 5()]`
//! and structure initialisers `(a := 1, b := [1, 2], c := (x := TRUE))`.

use super::expr::is_identish;
use super::Parser;
use crate::ast::{ArrayInitElem, FieldInit, Initializer};
use crate::lexer::Tok;

impl Parser<'_> {
    pub(super) fn initializer(&mut self) -> Initializer {
        if !self.enter() {
            self.skip_too_deep();
            return Initializer::Expr(self.error_expr());
        }
        let init = match self.peek() {
            Tok::LBracket => self.array_init(),
            Tok::LParen if is_identish(self.nth(1)) && self.nth(2) == Tok::ColonEq => {
                self.struct_init()
            }
            _ => Initializer::Expr(self.expr()),
        };
        self.leave();
        init
    }

    fn array_init(&mut self) -> Initializer {
        let start = self.bump().start;
        let mut elems = Vec::new();
        if !self.at(Tok::RBracket) {
            loop {
                elems.push(self.array_elem());
                if !self.eat(Tok::Comma) {
                    break;
                }
            }
        }
        self.expect(Tok::RBracket, "to close the array initial value");
        Initializer::Array {
            elems,
            span: self.span_from(start),
        }
    }

    /// `v`, `n(v)` (v repeated n times) or `n()` (n default values).
    fn array_elem(&mut self) -> ArrayInitElem {
        let start = self.cur().start;
        if !(self.at_plain_int() && self.nth(1) == Tok::LParen) {
            let value = self.initializer();
            return ArrayInitElem {
                repeat: None,
                span: value.span(),
                value: Some(value),
            };
        }
        let repeat = self.primary();
        self.bump();
        let value = if self.at(Tok::RParen) {
            None
        } else {
            Some(self.initializer())
        };
        self.expect(Tok::RParen, "to close the repeated element");
        ArrayInitElem {
            repeat: Some(repeat),
            value,
            span: self.span_from(start),
        }
    }

    /// `(name := init, ...)`, at `(`.
    fn struct_init(&mut self) -> Initializer {
        let start = self.bump().start;
        let mut fields = Vec::new();
        while let Some(name) = self.expect_ident("a member name") {
            self.expect(Tok::ColonEq, "after the member name");
            let value = self.initializer();
            fields.push(FieldInit {
                span: name.span.to(value.span()),
                name,
                value,
            });
            if !self.eat(Tok::Comma) {
                break;
            }
        }
        self.expect(Tok::RParen, "to close the structure initial value");
        Initializer::Struct {
            fields,
            span: self.span_from(start),
        }
    }
}
