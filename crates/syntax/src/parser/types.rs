//! Type specifications: names, `STRING[n]`, arrays, subranges, enumerations,
//! structures, `REF_TO` / `POINTER TO`.

use super::expr::is_identish;
use super::Parser;
use crate::ast::{ArrayDim, EnumValue, Ident, TypeSpec};
use crate::lexer::{Kw, Tok};
use automat_base::Span;

impl Parser<'_> {
    pub(super) fn can_start_type(&self) -> bool {
        match self.peek() {
            Tok::LParen => true,
            Tok::Kw(Kw::Array | Kw::String | Kw::WString | Kw::RefTo | Kw::Struct) => true,
            t => is_identish(t),
        }
    }

    /// A type; `None` (after an error) when none could be parsed.
    pub(super) fn type_spec(&mut self) -> Option<TypeSpec> {
        if !self.enter() {
            self.skip_too_deep();
            return None;
        }
        let t = self.type_spec_inner();
        self.leave();
        t
    }

    /// Only the kinds that contain types recurse from here; the others are
    /// parsed in `#[inline(never)]` helpers to keep this frame small.
    fn type_spec_inner(&mut self) -> Option<TypeSpec> {
        let start = self.cur().start;
        match self.peek() {
            Tok::Kw(Kw::Array) => self.array_type(),
            Tok::Kw(Kw::RefTo) => {
                self.bump();
                self.ref_target(start, false)
            }
            Tok::Kw(Kw::Pointer) if self.nth(1) == Tok::Kw(Kw::To) => {
                self.bump();
                self.bump();
                self.ref_target(start, false)
            }
            _ if self.is_word("REFERENCE") && self.nth(1) == Tok::Kw(Kw::To) => {
                self.codesys_reference_word("`REFERENCE TO` is a CODESYS reference type");
                self.bump();
                self.bump();
                self.ref_target(start, true)
            }
            Tok::Kw(Kw::Struct) => Some(self.struct_type()),
            _ => self.simple_type(),
        }
    }

    /// Names, strings, enumerations and subranges.
    #[inline(never)]
    fn simple_type(&mut self) -> Option<TypeSpec> {
        let start = self.cur().start;
        match self.peek() {
            Tok::Kw(k @ (Kw::String | Kw::WString)) => {
                self.bump();
                let len = if self.eat(Tok::LBracket) {
                    let e = self.expr();
                    self.expect(Tok::RBracket, "to close the string length");
                    Some(Box::new(e))
                } else if self.eat(Tok::LParen) {
                    let e = self.expr();
                    self.expect(Tok::RParen, "to close the string length");
                    Some(Box::new(e))
                } else {
                    None
                };
                Some(TypeSpec::String {
                    wide: k == Kw::WString,
                    len,
                    span: self.span_from(start),
                })
            }
            Tok::LParen => Some(self.enum_type(None, start)),
            _ => {
                let Some(name) = self.qualified_ident_here() else {
                    self.expected("a type");
                    return None;
                };
                if !self.at(Tok::LParen) {
                    return Some(TypeSpec::Named(name));
                }
                // `INT (A := 1, B)` is an enumeration with a base type,
                // `INT (0..100)` a subrange.
                if is_identish(self.nth(1))
                    && matches!(self.nth(2), Tok::Comma | Tok::RParen | Tok::ColonEq)
                {
                    return Some(self.enum_type(Some(name), start));
                }
                self.bump();
                let lo = self.expr();
                self.expect(Tok::DotDot, "between the bounds of the subrange");
                let hi = self.expr();
                self.expect(Tok::RParen, "to close the subrange");
                Some(TypeSpec::Subrange {
                    base: name,
                    lo: Box::new(lo),
                    hi: Box::new(hi),
                    span: self.span_from(start),
                })
            }
        }
    }

    fn ref_target(&mut self, start: u32, reference: bool) -> Option<TypeSpec> {
        let target = self.type_spec()?;
        Some(TypeSpec::Ref {
            target: Box::new(target),
            span: self.span_from(start),
            reference,
        })
    }

    /// `ARRAY [1..10, 0..N-1] OF elem`, `ARRAY [*] OF INT`.
    fn array_type(&mut self) -> Option<TypeSpec> {
        let start = self.bump().start;
        let dims = self.array_dims();
        let elem = self.type_spec()?;
        Some(TypeSpec::Array {
            dims,
            elem: Box::new(elem),
            span: self.span_from(start),
        })
    }

    /// `[1..10, *] OF`, after `ARRAY`.
    #[inline(never)]
    fn array_dims(&mut self) -> Vec<ArrayDim> {
        self.expect(Tok::LBracket, "after `ARRAY`");
        let mut dims = Vec::new();
        loop {
            let t = self.cur();
            if self.eat(Tok::Star) {
                dims.push(ArrayDim::Star(self.tok_span(t)));
            } else {
                let lo = self.expr();
                self.expect(Tok::DotDot, "between the bounds of the array dimension");
                let hi = self.expr();
                dims.push(ArrayDim::Range {
                    span: lo.span.to(hi.span),
                    lo,
                    hi,
                });
            }
            if !self.eat(Tok::Comma) {
                break;
            }
        }
        self.expect(Tok::RBracket, "to close the array dimensions");
        self.expect_kw(Kw::Of, "after the array dimensions");
        dims
    }

    /// `(Red, Green := 5)` with an optional base type before (`INT (...)`)
    /// or after (`(...) INT`, CODESYS). At `(`.
    fn enum_type(&mut self, base: Option<Ident>, start: u32) -> TypeSpec {
        self.bump();
        let mut values = Vec::new();
        while let Some(name) = self.expect_ident("an enumeration value") {
            let value = if self.eat(Tok::ColonEq) {
                Some(self.expr())
            } else {
                None
            };
            values.push(EnumValue { name, value });
            if !self.eat(Tok::Comma) {
                break;
            }
        }
        self.expect(Tok::RParen, "to close the enumeration");
        let base = match base {
            Some(b) => Some(b),
            // A name on the next line is the next declaration, not a base type.
            None if !self.newline_before_cur() => self.ident_here(),
            None => None,
        };
        TypeSpec::Enum {
            base,
            values,
            span: self.span_from(start),
        }
    }

    /// `STRUCT member; ... END_STRUCT`, at `STRUCT`.
    fn struct_type(&mut self) -> TypeSpec {
        let opener = self.bump();
        let mut members = Vec::new();
        loop {
            let before = self.pos;
            match self.peek() {
                Tok::Kw(Kw::EndStruct) => {
                    self.bump();
                    break;
                }
                t if is_identish(t) => {
                    if let Some(m) = self.var_decl() {
                        members.push(m);
                    }
                }
                _ if self.at_decl_sync() => {
                    self.report_unclosed(Kw::EndStruct, opener);
                    break;
                }
                _ => {
                    self.expected("a member declaration or `END_STRUCT`");
                    self.recover_decl();
                }
            }
            if self.pos == before {
                self.bump();
            }
        }
        TypeSpec::Struct {
            members,
            span: Span::new(self.file, opener.start, self.prev_end.max(opener.start)),
        }
    }
}
