//! Variable sections and variable declarations (also used for structure
//! members), with declaration-level recovery.

use super::address::decode_address;
use super::expr::is_identish;
use super::Parser;
use crate::ast::oop::Visibility;
use crate::ast::{Edge, Ident, Location, Retain, TypeSpec, VarBlock, VarDecl, VarKind};
use crate::lexer::{Kw, Tok, Token};
use automat_base::{Code, Diagnostic};

impl Parser<'_> {
    /// Whether the current token ends a run of declarations: where
    /// declaration recovery stops.
    pub(super) fn at_decl_sync(&self) -> bool {
        match self.peek() {
            Tok::Eof => true,
            Tok::Kw(k) => {
                k.is_decl_end() || k.is_item_start() || k.is_var_block() || k.starts_stmt()
            }
            _ => false,
        }
    }

    /// Skips to just after the next `;` or to the next sync point.
    pub(super) fn recover_decl(&mut self) {
        while !self.at_decl_sync() {
            if self.bump().tok == Tok::Semi {
                return;
            }
        }
    }

    /// Requires the `;` that ends a declaration (see `end_stmt`).
    pub(super) fn end_decl(&mut self, context: &str) {
        if self.eat(Tok::Semi) {
            return;
        }
        self.expected_word(";", context);
        if !(self.newline_before_cur() || self.at_decl_sync()) {
            self.recover_decl();
        }
    }

    /// Reports a block whose closing keyword is missing.
    pub(super) fn report_unclosed(&mut self, end: Kw, opener: Token) {
        let open = self.text(opener).to_ascii_uppercase();
        let d = Diagnostic::error(
            Code::E005,
            self.cur_span(),
            format!(
                "expected `{}` to close this `{open}`, found {}",
                end.name(),
                self.found()
            ),
        )
        .with_label(
            self.tok_span(opener),
            format!("this `{open}` is not closed"),
        );
        self.emit_here(d);
    }

    /// `VAR_xxx [CONSTANT] [RETAIN|NON_RETAIN] decl; ... END_VAR`, at the keyword.
    pub(super) fn var_block(&mut self) -> VarBlock {
        let opener = self.bump();
        let kind = match opener.tok {
            Tok::Kw(Kw::VarInput) => VarKind::Input,
            Tok::Kw(Kw::VarOutput) => VarKind::Output,
            Tok::Kw(Kw::VarInOut) => VarKind::InOut,
            Tok::Kw(Kw::VarExternal) => VarKind::External,
            Tok::Kw(Kw::VarGlobal) => VarKind::Global,
            Tok::Kw(Kw::VarTemp) => VarKind::Temp,
            Tok::Kw(k @ (Kw::VarStat | Kw::VarInst)) => {
                if !self.opts.codesys {
                    self.diags.push(
                        Diagnostic::error(
                            Code::E160,
                            self.tok_span(opener),
                            format!("`{}` is a CODESYS variable section", k.name()),
                        )
                        .with_note("check with `--lib codesys` (or `libraries = [\"codesys\"]` in automat.toml) to read CODESYS code"),
                    );
                }
                if k == Kw::VarStat {
                    VarKind::Static
                } else {
                    VarKind::Inst
                }
            }
            _ => VarKind::Local,
        };
        let mut constant = false;
        let mut retain = Retain::Unspecified;
        let mut access = None;
        loop {
            match self.peek() {
                Tok::Kw(Kw::Constant) => constant = true,
                Tok::Kw(Kw::Retain) => retain = Retain::Retain,
                Tok::Kw(Kw::NonRetain) => retain = Retain::NonRetain,
                Tok::Ident(_) if access.is_none() => {
                    match self.var_access_specifier(opener, kind) {
                        Some(v) => {
                            access = Some(v);
                            continue;
                        }
                        None => break,
                    }
                }
                _ => break,
            }
            self.bump();
        }
        let mut decls = Vec::new();
        let external = kind == VarKind::External;
        self.qualified_names = external;
        self.decl_list(opener, external, |p| p.var_decl(), &mut decls);
        self.qualified_names = false;
        if let Some(Some(v)) = access {
            let names = decls.iter().flat_map(|d: &VarDecl| d.names.iter());
            self.var_access.extend(names.map(|n| (n.sym, v)));
        }
        VarBlock {
            kind,
            constant,
            retain,
            decls,
            span: self.span_from(opener.start),
        }
    }

    /// `PUBLIC` / `PRIVATE` / `PROTECTED` / `INTERNAL` after `VAR` (eaten).
    /// It is a specifier only when a name, `CONSTANT`, `RETAIN` or `END_VAR` follows:
    /// `VAR public : INT; END_VAR` declares a variable named `public`.
    /// `Some(None)`: a specifier where none is allowed (reported).
    fn var_access_specifier(&mut self, opener: Token, kind: VarKind) -> Option<Option<Visibility>> {
        let word = [
            ("PUBLIC", Visibility::Public),
            ("PRIVATE", Visibility::Private),
            ("PROTECTED", Visibility::Protected),
            ("INTERNAL", Visibility::Internal),
        ]
        .into_iter()
        .find(|(w, _)| self.is_word(w))?;
        let qualifier_follows = matches!(
            self.nth(1),
            Tok::Kw(Kw::Constant | Kw::Retain | Kw::NonRetain | Kw::EndVar)
        );
        if !(self.name_follows() || qualifier_follows) {
            return None;
        }
        if kind != VarKind::Local {
            self.error_here(format!(
                "`{}` applies to a `VAR` section of a class or function block, not to `{}`",
                word.0,
                self.text(opener).to_ascii_uppercase()
            ));
        } else if !self.var_access_ok {
            self.error_here(format!(
                "`{}` applies only to a `VAR` section of a CLASS or FUNCTION_BLOCK (not of a PROGRAM, FUNCTION or METHOD)",
                word.0
            ));
        }
        let ok = kind == VarKind::Local && self.var_access_ok;
        self.bump();
        Some(ok.then_some(word.1))
    }

    /// Declarations until `END_VAR`; `decl` parses one at a name or `AT`.
    /// `paths`: declarations may begin with `a.b` or `a[1]` (VAR_CONFIG).
    pub(super) fn decl_list<T>(
        &mut self,
        opener: Token,
        paths: bool,
        mut decl: impl FnMut(&mut Self) -> Option<T>,
        out: &mut Vec<T>,
    ) {
        loop {
            let before = self.pos;
            match self.peek() {
                Tok::Kw(Kw::EndVar) => {
                    self.bump();
                    return;
                }
                // `x := 1;` cannot be a declaration: END_VAR is missing
                // and the body has begun.
                t if is_identish(t)
                    && (matches!(self.nth(1), Tok::ColonEq | Tok::LParen)
                        || (!paths && matches!(self.nth(1), Tok::LBracket | Tok::Dot))) =>
                {
                    return self.report_unclosed(Kw::EndVar, opener);
                }
                t if is_identish(t) || t == Tok::Kw(Kw::At) => {
                    if let Some(d) = decl(self) {
                        out.push(d);
                    }
                }
                _ if self.at_decl_sync() => return self.report_unclosed(Kw::EndVar, opener),
                _ => {
                    self.expected("a variable declaration or `END_VAR`");
                    self.recover_decl();
                }
            }
            if self.pos == before {
                self.bump();
            }
        }
    }

    /// `a, b AT %IX0.1 : INT R_EDGE := 5;` (names optional before `AT`).
    /// Structure members nest through here (`STRUCT s : STRUCT ...`), so
    /// the parts before and after the type are in separate functions.
    pub(super) fn var_decl(&mut self) -> Option<VarDecl> {
        let start = self.cur().start;
        let (names, location) = self.decl_head()?;
        let Some(ty) = self.type_spec() else {
            self.recover_decl();
            return None;
        };
        Some(self.decl_tail(start, names, location, ty))
    }

    /// The names, the location and the `:`.
    #[inline(never)]
    fn decl_head(&mut self) -> Option<(Vec<Ident>, Option<Location>)> {
        let mut names = Vec::new();
        let first = if self.qualified_names {
            self.qualified_ident_here()
        } else {
            self.ident_here()
        };
        if let Some(first) = first {
            names.push(first);
            while self.eat(Tok::Comma) {
                let next = if self.qualified_names && matches!(self.peek(), Tok::Ident(_)) {
                    self.qualified_ident_here()
                } else {
                    self.expect_ident("a variable name after `,`")
                };
                match next {
                    Some(n) => names.push(n),
                    None => {
                        self.recover_decl();
                        return None;
                    }
                }
            }
        }
        let location = if self.at_kw(Kw::At) {
            self.location()
        } else {
            None
        };
        if !self.eat(Tok::Colon) {
            let after = if location.is_some() {
                "the location"
            } else {
                "the variable name"
            };
            self.expected(&format!("`:` after {after}"));
            // `x INT;`: go on with the type as if the colon were there.
            if !self.can_start_type() {
                self.recover_decl();
                return None;
            }
        }
        Some((names, location))
    }

    /// The edge, the initial value and the `;`.
    #[inline(never)]
    fn decl_tail(
        &mut self,
        start: u32,
        names: Vec<Ident>,
        location: Option<Location>,
        ty: TypeSpec,
    ) -> VarDecl {
        let edge = if self.eat_kw(Kw::REdge) {
            Some(Edge::Rising)
        } else if self.eat_kw(Kw::FEdge) {
            Some(Edge::Falling)
        } else {
            None
        };
        let init = if self.eat(Tok::ColonEq) {
            Some(self.initializer())
        } else if self.is_word("REF") && self.nth(1) == Tok::Eq {
            Some(self.ref_bind_init())
        } else {
            None
        };
        let span = self.span_from(start);
        self.end_decl("after the declaration");
        VarDecl {
            names,
            location,
            ty,
            edge,
            init,
            span,
        }
    }

    /// `AT %IX0.1`, at `AT`. An invalid address is reported (E007) and dropped.
    pub(super) fn location(&mut self) -> Option<Location> {
        let at = self.bump();
        let t = self.cur();
        if t.tok != Tok::Addr {
            self.expected("a direct address such as `%IX0.1` after `AT`");
            return None;
        }
        self.bump();
        let span = self.tok_span(t);
        match decode_address(self.text(t), span) {
            Ok(addr) => Some(Location {
                addr,
                span: self.span_from(at.start),
            }),
            Err(msg) => {
                self.report(Diagnostic::error(Code::E007, span, msg));
                None
            }
        }
    }
}
