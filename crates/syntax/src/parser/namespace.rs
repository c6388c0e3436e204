//! `NAMESPACE ... END_NAMESPACE`, `USING` and qualified names in type
//! positions (IEC 61131-3 3rd edition, 6.9). The words are contextual, like
//! the object-oriented ones. Resolution is `desugar::namespace`'s job: the
//! parser only records what was written.

use super::Parser;
use crate::ast::{Expr, ExprKind, Ident, Item, LitKind, Literal, Namespace, Using};
use crate::lexer::Tok;
use automat_base::Span;

impl Parser<'_> {
    /// Whether the current token opens or closes a namespace (error
    /// recovery between items stops there).
    pub(super) fn at_namespace_word(&self) -> bool {
        (self.is_word("NAMESPACE") && matches!(self.nth(1), Tok::Ident(_)))
            || self.is_word("END_NAMESPACE")
    }

    /// A name, possibly qualified by namespaces (`Motion.Axis`): one
    /// [`Ident`] spelled with its dots as written, spanning the whole. A
    /// plain name is returned as [`Parser::ident_here`] reads it.
    pub(super) fn qualified_ident_here(&mut self) -> Option<Ident> {
        let first = self.ident_here()?;
        if !(self.at(Tok::Dot) && matches!(self.nth(1), Tok::Ident(_))) {
            return Some(first);
        }
        let mut text = self.spelling(first.span).to_string();
        let mut span = first.span;
        while self.at(Tok::Dot) && matches!(self.nth(1), Tok::Ident(_)) {
            self.bump();
            let Some(next) = self.ident_here() else { break };
            text.push('.');
            text.push_str(self.spelling(next.span));
            span = Span::new(span.file, span.start, next.span.end);
        }
        Some(Ident {
            sym: self.interner.intern(&text),
            span,
        })
    }

    /// `Ns.Color#Red`: the enumeration literal `Color#Red` (token `lit`)
    /// after the names `Ns.` (`base`), as one literal whose type is the
    /// qualified `Ns.Color`. `None` (nothing taken) for anything else.
    pub(super) fn qualified_enum(&mut self, base: &Expr, lit: u32) -> Option<Literal> {
        let Some(Literal {
            kind: LitKind::Enum(_),
            ty: Some(ty),
        }) = self.lits.get(lit as usize)
        else {
            return None;
        };
        let ty = *ty;
        let mut parts = Vec::new();
        let mut cur = base;
        loop {
            match &cur.kind {
                ExprKind::Member { base, member } => {
                    parts.push(member.span);
                    cur = base;
                }
                ExprKind::Name(id) => {
                    parts.push(id.span);
                    break;
                }
                _ => return None,
            }
        }
        let mut text = String::new();
        for s in parts.iter().rev() {
            text.push_str(self.spelling(*s));
            text.push('.');
        }
        text.push_str(self.spelling(ty.span));
        let slot = self.lits.get_mut(lit as usize)?;
        let mut taken = std::mem::replace(
            slot,
            Literal {
                kind: LitKind::Bool(false),
                ty: None,
            },
        );
        taken.ty = Some(Ident {
            sym: self.interner.intern(&text),
            span: base.span.to(ty.span),
        });
        Some(taken)
    }

    fn spelling(&self, span: Span) -> &str {
        self.src
            .get(span.start as usize..span.end as usize)
            .unwrap_or("")
    }

    /// `A.B.C` as its parts (a namespace's name, a USING's).
    fn dotted_path(&mut self, what: &str) -> Vec<Ident> {
        let mut path = Vec::new();
        while let Some(i) = self.expect_ident(what) {
            path.push(i);
            if !(self.at(Tok::Dot) && matches!(self.nth(1), Tok::Ident(_))) {
                break;
            }
            self.bump();
        }
        path
    }

    /// `USING A.B, C;` clauses, any number of them (none: empty).
    pub(super) fn usings(&mut self) -> Vec<Using> {
        let mut out = Vec::new();
        while self.is_word("USING") && matches!(self.nth(1), Tok::Ident(_)) {
            self.bump();
            loop {
                let start = self.cur().start;
                let path = self.dotted_path("the name of a namespace after `USING`");
                if path.is_empty() {
                    break;
                }
                out.push(Using {
                    path,
                    span: self.span_from(start),
                });
                if !self.eat(Tok::Comma) {
                    break;
                }
            }
            self.expect(Tok::Semi, "after the namespaces of `USING`");
        }
        out
    }

    /// A POU whose header had USING clauses becomes the one item of a
    /// namespace without a name that carries them.
    pub(super) fn with_pou_usings(&mut self, item: Item) -> Item {
        let usings = std::mem::take(&mut self.pou_usings);
        if usings.is_empty() {
            return item;
        }
        let span = match &item {
            Item::Pou(p) => p.span,
            Item::Class(c) => c.span,
            _ => return item,
        };
        Item::Namespace(Box::new(Namespace {
            name: Vec::new(),
            internal: false,
            usings,
            items: vec![item],
            span,
        }))
    }

    /// `NAMESPACE [INTERNAL] A.B [USING ...;] items END_NAMESPACE`.
    pub(super) fn namespace(&mut self) -> Option<Item> {
        let opener = self.bump();
        if !self.enter() {
            // Too deep: the rest of the file is not read as items.
            while !self.at_eof() {
                self.bump();
            }
            return None;
        }
        let internal = self.is_word("INTERNAL") && matches!(self.nth(1), Tok::Ident(_));
        if internal {
            self.bump();
        }
        let name = self.dotted_path("the name of the namespace");
        let usings = self.usings();
        let items = self.items_in(true);
        if self.is_word("END_NAMESPACE") {
            self.bump();
            self.eat(Tok::Semi);
        } else {
            self.expected("`END_NAMESPACE`");
        }
        self.leave();
        if name.is_empty() {
            return None;
        }
        Some(Item::Namespace(Box::new(Namespace {
            name,
            internal,
            usings,
            items,
            span: self.span_from(opener.start),
        })))
    }
}
