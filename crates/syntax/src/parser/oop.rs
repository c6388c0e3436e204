//! Object orientation (IEC 61131-3 3rd edition): `CLASS`, `INTERFACE`,
//! `METHOD`, `PROPERTY` and the `EXTENDS`/`IMPLEMENTS`/`ABSTRACT`/`FINAL`
//! parts of a FUNCTION_BLOCK. Their words are contextual (identifiers
//! elsewhere), so code that names a variable `GET` or `FINAL` still parses.

use super::Parser;
use crate::ast::oop::{Accessor, Class, ClassKind, Interface, Method, Property, Visibility};
use crate::ast::{Ident, Stmt, VarBlock};
use crate::lexer::{Tok, Token};
use automat_base::Span;

/// The object-oriented parts read after a FUNCTION_BLOCK's name.
#[derive(Default)]
pub(super) struct FbHead {
    pub is_abstract: bool,
    pub is_final: bool,
    pub extends: Option<Ident>,
    pub implements: Vec<Ident>,
    pub any: bool,
}

impl Parser<'_> {
    /// Whether the current token is the identifier `w` (any case).
    pub(super) fn is_word(&self, w: &str) -> bool {
        self.word_at(0, w)
    }

    pub(super) fn word_at(&self, n: usize, w: &str) -> bool {
        match self.nth(n) {
            Tok::Ident(s) => self.interner.name(s).eq_ignore_ascii_case(w),
            _ => false,
        }
    }

    pub(super) fn eat_word(&mut self, w: &str) -> bool {
        if self.is_word(w) {
            self.bump();
            true
        } else {
            false
        }
    }

    /// A statement list stops at these words when they open or close an
    /// object-oriented part (`METHOD m`, `END_METHOD`, ...).
    pub(super) fn at_oop_boundary(&self) -> bool {
        if self.oop_depth == 0 {
            return false;
        }
        const ENDS: [&str; 7] = [
            "END_METHOD",
            "END_PROPERTY",
            "END_GET",
            "END_SET",
            "END_CLASS",
            "END_INTERFACE",
            "END_NAMESPACE",
        ];
        if ENDS.iter().any(|w| self.is_word(w)) {
            return true;
        }
        if (self.is_word("METHOD") || self.is_word("PROPERTY")) && self.name_follows() {
            return true;
        }
        (self.is_word("GET") || self.is_word("SET"))
            && (self.newline_after_cur() || matches!(self.nth(1), Tok::Kw(k) if k.is_var_block()))
    }

    fn newline_after_cur(&self) -> bool {
        let end = self.cur().end as usize;
        let next = self
            .toks
            .get(self.pos + 1)
            .map_or(self.src.len(), |t| t.start as usize);
        self.src.get(end..next).is_some_and(|g| g.contains('\n'))
    }

    /// `[ABSTRACT|FINAL]` before a function block's name.
    pub(super) fn fb_modifiers_before_name(&mut self, head: &mut FbHead) {
        loop {
            let followed_by_name = self.name_follows();
            if followed_by_name && self.is_word("ABSTRACT") {
                self.bump();
                head.is_abstract = true;
                head.any = true;
            } else if followed_by_name && self.is_word("FINAL") {
                self.bump();
                head.is_final = true;
                head.any = true;
            } else {
                break;
            }
        }
    }

    /// `[EXTENDS base] [IMPLEMENTS i1, i2]` after a function block's or class's name.
    pub(super) fn fb_head_after_name(&mut self, head: &mut FbHead) {
        if self.eat_word("EXTENDS") {
            head.any = true;
            head.extends = self.qualified_ident_here();
            if head.extends.is_none() {
                self.expected("the name of the base after `EXTENDS`");
            }
        }
        if self.eat_word("IMPLEMENTS") {
            head.any = true;
            head.implements = self.ident_list("an interface name after `IMPLEMENTS`");
        }
    }

    fn ident_list(&mut self, what: &str) -> Vec<Ident> {
        let mut out = Vec::new();
        loop {
            // CODESYS's `__System.IQueryInterface`, the base its
            // `__QUERYINTERFACE` asks for: every interface here can be
            // queried, so it names nothing to inherit.
            if self.is_word("__System")
                && self.nth(1) == Tok::Dot
                && self.word_at(2, "IQueryInterface")
            {
                self.bump();
                self.bump();
                self.bump();
                if !self.eat(Tok::Comma) {
                    break;
                }
                continue;
            }
            let Some(i) = self.qualified_ident_here() else {
                self.expected(what);
                break;
            };
            out.push(i);
            if !self.eat(Tok::Comma) {
                break;
            }
        }
        out
    }

    /// Methods and properties at the current position (inside a class,
    /// function block or interface).
    pub(super) fn members(&mut self, methods: &mut Vec<Method>, props: &mut Vec<Property>) {
        loop {
            if self.is_word("METHOD") {
                methods.push(self.method());
            } else if self.is_word("PROPERTY") {
                if let Some(p) = self.property() {
                    props.push(p);
                }
            } else {
                break;
            }
        }
    }

    /// Whether the token after the current one can be a name: modifiers are
    /// words too, so `METHOD PUBLIC Step` is read by looking one word ahead
    /// (a contextual keyword such as `STEP` is a name there).
    pub(super) fn name_follows(&self) -> bool {
        match self.nth(1) {
            Tok::Ident(_) => true,
            Tok::Kw(k) => k.is_contextual(),
            _ => false,
        }
    }

    fn visibility(&mut self) -> (Visibility, Option<Span>) {
        let sp = self.cur_span();
        for (w, v) in [
            ("PUBLIC", Visibility::Public),
            ("PRIVATE", Visibility::Private),
            ("PROTECTED", Visibility::Protected),
            ("INTERNAL", Visibility::Internal),
        ] {
            if self.name_follows() && self.eat_word(w) {
                return (v, Some(sp));
            }
        }
        (Visibility::Public, None)
    }

    fn var_blocks_here(&mut self) -> Vec<VarBlock> {
        let mut blocks = Vec::new();
        while let Tok::Kw(k) = self.peek() {
            if k.is_var_block() {
                blocks.push(self.var_block());
            } else {
                break;
            }
        }
        blocks
    }

    fn oop_body(&mut self) -> Vec<Stmt> {
        self.oop_depth += 1;
        let stmts = self.stmt_list(false);
        self.oop_depth -= 1;
        stmts
    }

    /// Consumes `END_x`, or reports it missing (the construct is kept).
    fn close_word(&mut self, end: &str, opener: Token) {
        if !self.eat_word(end) {
            let open = self.text(opener).to_ascii_uppercase();
            self.expected(&format!("`{end}` to close this `{open}`"));
        }
    }

    /// `METHOD [access] [ABSTRACT|FINAL] [OVERRIDE] name [: type] vars body END_METHOD`.
    fn method(&mut self) -> Method {
        let opener = self.bump();
        let (visibility, visibility_span) = self.visibility();
        let (mut is_abstract, mut is_final, mut is_override) = (false, false, false);
        loop {
            if !self.name_follows() {
                break;
            }
            if self.eat_word("ABSTRACT") {
                is_abstract = true;
            } else if self.eat_word("FINAL") {
                is_final = true;
            } else if self.eat_word("OVERRIDE") {
                is_override = true;
            } else {
                break;
            }
        }
        let name = self
            .expect_ident("the name of the method")
            .unwrap_or(Ident {
                sym: self.interner.intern("__missing"),
                span: self.cur_span(),
            });
        let return_type = if self.eat(Tok::Colon) {
            self.type_spec()
        } else {
            None
        };
        self.eat(Tok::Semi);
        let usings = self.usings();
        let var_blocks = self.var_blocks_here();
        let body = self.oop_body();
        self.close_word("END_METHOD", opener);
        Method {
            name,
            visibility,
            visibility_span,
            is_abstract,
            is_final,
            is_override,
            return_type,
            var_blocks,
            body,
            usings,
            span: self.span_from(opener.start),
        }
    }

    fn accessor(&mut self, end: &str) -> Accessor {
        let opener = self.bump();
        let var_blocks = self.var_blocks_here();
        let body = self.oop_body();
        self.close_word(end, opener);
        Accessor {
            var_blocks,
            body,
            span: self.span_from(opener.start),
        }
    }

    /// `PROPERTY [access] name : type [GET ... END_GET] [SET ... END_SET] END_PROPERTY`.
    fn property(&mut self) -> Option<Property> {
        let opener = self.bump();
        let (visibility, _) = self.visibility();
        let name = self.expect_ident("the name of the property");
        self.expect(Tok::Colon, "after the property name");
        let ty = self.type_spec();
        self.eat(Tok::Semi);
        let (mut get, mut set) = (None, None);
        loop {
            if self.is_word("GET") {
                get = Some(self.accessor("END_GET"));
            } else if self.is_word("SET") {
                set = Some(self.accessor("END_SET"));
            } else {
                break;
            }
        }
        self.close_word("END_PROPERTY", opener);
        Some(Property {
            name: name?,
            visibility,
            ty: ty?,
            get,
            set,
            span: self.span_from(opener.start),
        })
    }

    /// `CLASS [ABSTRACT|FINAL] name [EXTENDS b] [IMPLEMENTS i] vars methods END_CLASS`.
    pub(super) fn class(&mut self) -> Option<Class> {
        let opener = self.bump();
        let mut head = FbHead::default();
        self.fb_modifiers_before_name(&mut head);
        let name = self.expect_ident("the name of the class");
        self.fb_head_after_name(&mut head);
        self.pou_usings = self.usings();
        self.var_access_ok = true;
        let var_blocks = self.var_blocks_here();
        self.var_access_ok = false;
        let var_access = std::mem::take(&mut self.var_access);
        let (mut methods, mut properties) = (Vec::new(), Vec::new());
        self.oop_depth += 1;
        self.members(&mut methods, &mut properties);
        self.oop_depth -= 1;
        if !self.eat_word("END_CLASS") {
            self.expected("`METHOD`, `PROPERTY` or `END_CLASS`");
            while !(self.at_eof() || self.is_word("END_CLASS")) {
                if matches!(self.peek(), Tok::Kw(k) if k.is_item_start()) {
                    break;
                }
                self.bump();
            }
            self.eat_word("END_CLASS");
        }
        Some(Class {
            kind: ClassKind::Class,
            name: name?,
            is_abstract: head.is_abstract,
            is_final: head.is_final,
            extends: head.extends,
            implements: head.implements,
            var_blocks,
            var_access,
            methods,
            properties,
            body: Vec::new(),
            span: self.span_from(opener.start),
            desugared: false,
        })
    }

    /// `INTERFACE name [EXTENDS i1, i2] METHOD ... END_METHOD ... END_INTERFACE`.
    pub(super) fn interface(&mut self) -> Option<Interface> {
        let opener = self.bump();
        let name = self.expect_ident("the name of the interface");
        let extends = if self.eat_word("EXTENDS") {
            self.ident_list("an interface name after `EXTENDS`")
        } else {
            Vec::new()
        };
        let (mut methods, mut properties) = (Vec::new(), Vec::new());
        self.oop_depth += 1;
        self.members(&mut methods, &mut properties);
        self.oop_depth -= 1;
        if !self.eat_word("END_INTERFACE") {
            self.expected("`METHOD`, `PROPERTY` or `END_INTERFACE`");
            while !(self.at_eof() || self.is_word("END_INTERFACE")) {
                if matches!(self.peek(), Tok::Kw(k) if k.is_item_start()) {
                    break;
                }
                self.bump();
            }
            self.eat_word("END_INTERFACE");
        }
        Some(Interface {
            name: name?,
            extends,
            methods,
            properties,
            span: self.span_from(opener.start),
            desugared: false,
        })
    }
}
