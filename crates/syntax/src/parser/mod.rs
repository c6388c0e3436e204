//! The recursive-descent parser: tokens → AST, with error recovery.
//!
//! Recovery rules, shared by every part:
//! - An `expect` that fails reports and consumes nothing, so the caller can
//!   go on as if the token had been there (one missing `;` gives one error).
//! - At most one error is reported per token position; further complaints
//!   about the same token are the same mistake seen from an outer rule.
//! - Loops over lists guarantee progress: an iteration that consumed nothing
//!   skips a token (after an error was reported).
//! - Nesting is capped at [`MAX_DEPTH`] so no input can overflow the stack;
//!   each link of a left-associative chain (`a + b + c`, `a.b.c`) counts as
//!   a level too, as it deepens the tree that later stages walk. Past the
//!   limit: one error, and the rest of the statement is skipped.
//! - `frames` holds the closing keywords of the statements and POUs being
//!   parsed: a statement list stops at a closer that belongs to an enclosing
//!   construct (that construct is then reported as unclosed), and skips a
//!   closer that belongs to none.

mod address;
mod config;
mod control;
mod decl;
mod expr;
mod heap;
mod il;
mod init;
mod items;
mod namespace;
mod oop;
pub(crate) mod reference;
mod sfc;
mod stmt;
mod types;

use crate::ast::{Ident, Literal, SourceUnit};
use crate::lexer::{Kw, Lexed, Tok, Token};
use automat_base::{Code, Diagnostic, FileId, Interner, Span};

/// How deeply expressions, statements, types and initial values may nest
/// (counting operator and access chains, see the module comment).
pub const MAX_DEPTH: u32 = 256;

pub struct Parser<'a> {
    src: &'a str,
    file: FileId,
    toks: Vec<Token>,
    lits: Vec<Literal>,
    pos: usize,
    /// End of the last consumed token.
    prev_end: u32,
    interner: &'a mut Interner,
    diags: Vec<Diagnostic>,
    depth: u32,
    /// Token index of the last reported error (see the module comment).
    last_error: Option<usize>,
    /// Whether "nesting too deep" was reported (once per file is enough).
    deep_reported: bool,
    frames: Vec<&'static [Kw]>,
    /// Sorted end offsets of the lexer's errors: a syntax error right after
    /// one (`x := 5 @ 3`, an unterminated string eating the `;`) is a
    /// consequence of it and is not reported again.
    lex_error_ends: Vec<u32>,
    /// Inside a method, property or class: statement lists stop at their
    /// contextual closers (`END_METHOD`, ...).
    oop_depth: u32,
    /// The CODESYS actions read so far after the current PROGRAM or
    /// FUNCTION (each with the others it calls already in place).
    pou_actions: Vec<(
        automat_base::Symbol,
        Vec<crate::ast::Stmt>,
        automat_base::Span,
    )>,
    /// In an IL body: the variables declared as standard function blocks
    /// with an input `R` (CTU, CTUD, SR) and with an input `S` (RS), so
    /// that `R ctr` and `S ff` set those inputs as the other FB input
    /// operators do, instead of resetting the instance itself.
    il_fb_r: Vec<automat_base::Symbol>,
    /// The `USING` clauses read in the current POU's header (`namespace.rs`
    /// wraps the POU in a namespace without a name for them).
    pou_usings: Vec<crate::ast::Using>,
    /// In a VAR_EXTERNAL block: names may be qualified (`Motion.MaxPos`,
    /// a global of a namespace).
    qualified_names: bool,
    il_fb_s: Vec<automat_base::Symbol>,
    /// The dialect's reading rules (`--lib codesys`).
    opts: crate::Options,
    /// The hidden globals of the `__NEW(T)` calls read (`heap.rs`).
    heap_templates: Vec<crate::ast::VarBlock>,
    /// While reading the VAR sections of a CLASS or FUNCTION_BLOCK: an
    /// access specifier (`VAR PUBLIC`) is allowed; the variables it marks
    /// are gathered in `var_access` for the class.
    var_access_ok: bool,
    var_access: Vec<(automat_base::Symbol, crate::ast::oop::Visibility)>,
}

/// Parses a lexed file into a [`SourceUnit`]; diagnostics are appended to `diags`.
pub fn parse_tokens(
    file: FileId,
    src: &str,
    lexed: Lexed,
    interner: &mut Interner,
    diags: &mut Vec<Diagnostic>,
    opts: crate::Options,
) -> SourceUnit {
    let mut p = Parser {
        opts,
        src,
        file,
        toks: lexed.toks,
        lits: lexed.lits,
        pos: 0,
        prev_end: 0,
        interner,
        diags: Vec::new(),
        depth: 0,
        last_error: None,
        deep_reported: false,
        frames: Vec::new(),
        lex_error_ends: diags.iter().map(|d| d.span.end).collect(),
        oop_depth: 0,
        pou_usings: Vec::new(),
        qualified_names: false,
        pou_actions: Vec::new(),
        il_fb_r: Vec::new(),
        il_fb_s: Vec::new(),
        heap_templates: Vec::new(),
        var_access_ok: false,
        var_access: Vec::new(),
    };
    p.lex_error_ends.sort_unstable();
    if p.toks.last().map(|t| t.tok) != Some(Tok::Eof) {
        let end = src.len() as u32;
        p.toks.push(Token {
            tok: Tok::Eof,
            start: end,
            end,
        });
    }
    let items = p.items();
    diags.append(&mut p.diags);
    SourceUnit { file, items }
}

impl<'a> Parser<'a> {
    // ---- looking at tokens ----

    fn cur(&self) -> Token {
        match self.toks.get(self.pos) {
            Some(t) => *t,
            None => Token {
                tok: Tok::Eof,
                start: self.src.len() as u32,
                end: self.src.len() as u32,
            },
        }
    }

    fn peek(&self) -> Tok {
        self.cur().tok
    }

    /// The token `n` places ahead (0 = current); `Eof` past the end.
    fn nth(&self, n: usize) -> Tok {
        self.toks.get(self.pos + n).map_or(Tok::Eof, |t| t.tok)
    }

    /// `=` right after another `=` (C's `==`).
    fn at_doubled_equals(&self) -> bool {
        let prev = self.pos.checked_sub(1).and_then(|i| self.toks.get(i));
        self.at(Tok::Eq) && prev.is_some_and(|p| p.tok == Tok::Eq && p.end == self.cur().start)
    }

    fn at(&self, t: Tok) -> bool {
        self.peek() == t
    }

    fn at_kw(&self, k: Kw) -> bool {
        self.peek() == Tok::Kw(k)
    }

    fn at_eof(&self) -> bool {
        self.peek() == Tok::Eof
    }

    fn tok_span(&self, t: Token) -> Span {
        Span::new(self.file, t.start, t.end)
    }

    fn cur_span(&self) -> Span {
        self.tok_span(self.cur())
    }

    /// From `start` to the end of the last consumed token.
    fn span_from(&self, start: u32) -> Span {
        Span::new(self.file, start, self.prev_end.max(start))
    }

    fn text(&self, t: Token) -> &'a str {
        self.src.get(t.start as usize..t.end as usize).unwrap_or("")
    }

    // ---- consuming ----

    fn bump(&mut self) -> Token {
        let t = self.cur();
        if t.tok != Tok::Eof {
            self.pos += 1;
            self.prev_end = t.end;
        }
        t
    }

    fn eat(&mut self, t: Tok) -> bool {
        if self.at(t) {
            self.bump();
            true
        } else {
            false
        }
    }

    fn eat_kw(&mut self, k: Kw) -> bool {
        self.eat(Tok::Kw(k))
    }

    /// The current token as a name, if it is one (identifiers and the
    /// contextual keywords).
    fn ident_here(&mut self) -> Option<Ident> {
        let t = self.cur();
        let sym = match t.tok {
            Tok::Ident(sym) => sym,
            Tok::Kw(k) if k.is_contextual() => self.interner.intern(self.text(t)),
            _ => return None,
        };
        self.bump();
        Some(Ident {
            sym,
            span: self.tok_span(t),
        })
    }

    // ---- errors ----

    /// How a token is named in messages: ``identifier `x` ``, `` `END_IF` ``.
    fn describe(&self, t: Token) -> String {
        let text = self.text(t);
        let short = if text.chars().count() > 24 {
            let cut: String = text.chars().take(21).collect();
            format!("{cut}...")
        } else {
            text.to_string()
        };
        match t.tok {
            Tok::Eof => "end of file".to_string(),
            Tok::Ident(_) => format!("identifier `{short}`"),
            Tok::Kw(k) => format!("`{}`", k.name()),
            Tok::Lit(_) | Tok::BadLit => format!("literal `{short}`"),
            Tok::Addr => format!("address `{short}`"),
            p => format!("`{}`", p.punct_text().unwrap_or("?")),
        }
    }

    fn found(&self) -> String {
        self.describe(self.cur())
    }

    /// Reports an E005 at the current token unless one was reported there.
    /// Error paths are cold and never inlined: the recursive rules then keep
    /// small stack frames, which is what bounds the stack at `MAX_DEPTH`.
    #[cold]
    #[inline(never)]
    fn error_here(&mut self, msg: impl Into<String>) {
        let d = Diagnostic::error(Code::E005, self.cur_span(), msg);
        self.emit_here(d);
    }

    /// Reports "expected {what}, found {the current token}".
    #[cold]
    #[inline(never)]
    fn expected(&mut self, what: &str) {
        let msg = format!("expected {what}, found {}", self.found());
        self.error_here(msg);
    }

    /// Reports a diagnostic about the current token unless one was already
    /// reported there.
    #[cold]
    #[inline(never)]
    fn emit_here(&mut self, d: Diagnostic) {
        if self.last_error == Some(self.pos) {
            return;
        }
        self.last_error = Some(self.pos);
        if !self.follows_lex_error() {
            self.diags.push(d);
        }
    }

    /// Whether a lexical error lies between the previous token's start and
    /// the current token's start.
    fn follows_lex_error(&self) -> bool {
        let from = match self.pos.checked_sub(1).and_then(|i| self.toks.get(i)) {
            Some(t) => t.start,
            None => 0,
        };
        let to = self.cur().start;
        let i = self.lex_error_ends.partition_point(|&e| e < from);
        self.lex_error_ends.get(i).is_some_and(|&e| e <= to)
    }

    /// Reports a diagnostic with its own code and span (not tied to a token).
    #[cold]
    #[inline(never)]
    fn report(&mut self, d: Diagnostic) {
        self.diags.push(d);
    }

    fn expect(&mut self, t: Tok, context: &str) -> bool {
        if self.eat(t) {
            return true;
        }
        self.expected_word(t.punct_text().unwrap_or("?"), context);
        false
    }

    fn expect_kw(&mut self, k: Kw, context: &str) -> bool {
        if self.eat_kw(k) {
            return true;
        }
        self.expected_word(k.name(), context);
        false
    }

    /// Reports "expected `{word}` {context}, found ...".
    #[cold]
    #[inline(never)]
    /// An E005 just after the previous token (where a missing `;` belongs),
    /// counted as reported at the current token.
    fn error_at_prev_end(&mut self, msg: String) {
        if self.last_error == Some(self.pos) {
            return;
        }
        self.last_error = Some(self.pos);
        if !self.follows_lex_error() {
            let span = Span::new(self.file, self.prev_end, self.prev_end);
            self.diags.push(Diagnostic::error(Code::E005, span, msg));
        }
    }

    fn expected_word(&mut self, word: &str, context: &str) {
        self.expected(&format!("`{word}` {context}"));
    }

    fn expect_ident(&mut self, what: &str) -> Option<Ident> {
        let id = self.ident_here();
        if id.is_none() {
            self.expected(what);
        }
        id
    }

    /// Whether a line break separates the previous token from the current one.
    fn newline_before_cur(&self) -> bool {
        let from = (self.prev_end as usize).min(self.src.len());
        let to = (self.cur().start as usize).clamp(from, self.src.len());
        self.src.as_bytes()[from..to].contains(&b'\n')
    }

    // ---- nesting ----

    /// Enters one nesting level; false (after an error) when too deep.
    fn enter(&mut self) -> bool {
        self.enter_or(false)
    }

    /// Adds one link to a chain (`a + b + ...`, `a.b.c...`): each link is
    /// one more level of the tree, so it counts against the same limit,
    /// which bounds the depth of every tree the parser returns (consumers
    /// recurse over it, and dropping it recurses too).
    fn enter_link(&mut self) -> bool {
        self.enter_or(true)
    }

    fn enter_or(&mut self, link: bool) -> bool {
        if self.depth >= MAX_DEPTH {
            if !self.deep_reported {
                self.deep_reported = true;
                let msg = if link {
                    format!(
                        "expression too long: more than {MAX_DEPTH} levels, counting each operator or access in a row as one; split it into several statements"
                    )
                } else {
                    format!("nesting too deep: more than {MAX_DEPTH} levels")
                };
                self.error_here(msg);
            }
            return false;
        }
        self.depth += 1;
        true
    }

    /// After "nesting too deep" inside an expression, type or initial value:
    /// skips to the end of the statement or declaration (not consuming it),
    /// so the unwinding rules do not each report a missing `)` or `]`.
    fn skip_too_deep(&mut self) {
        loop {
            match self.peek() {
                Tok::Semi | Tok::Eof => break,
                Tok::Kw(k)
                    if k.starts_stmt()
                        || k.is_stmt_closer()
                        || k.is_item_start()
                        || k.is_decl_end()
                        || k.is_var_block() =>
                {
                    break
                }
                _ => {
                    self.bump();
                }
            }
        }
        self.last_error = Some(self.pos);
    }

    fn leave(&mut self) {
        self.depth = self.depth.saturating_sub(1);
    }

    /// Leaves the levels entered by `n` chain links.
    fn leave_links(&mut self, n: u32) {
        self.depth = self.depth.saturating_sub(n);
    }

    fn in_frames(&self, k: Kw) -> bool {
        self.frames.iter().any(|f| f.contains(&k))
    }
}
