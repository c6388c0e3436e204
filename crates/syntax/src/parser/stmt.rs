//! Statement lists, simple statements, and statement-level recovery.
//! Compound statements (IF, CASE, loops) are in `control.rs`.
//!
//! Statements nest by recursion (`stmt_list` → `stmt` → `if_stmt` →
//! `stmt_list`); the functions on that path push finished nodes straight
//! into the list and build them in `#[inline(never)]` helpers, so a nesting
//! level costs little stack (see `MAX_DEPTH`).

use super::Parser;
use crate::ast::{ExprKind, Stmt, StmtKind};
use crate::lexer::{Kw, Tok};
use automat_base::Span;

/// The statement a closer belongs to, for messages.
fn opener_of(k: Kw) -> &'static str {
    match k {
        Kw::EndIf | Kw::Elsif => "`IF`",
        Kw::Else => "`IF` or `CASE`",
        Kw::EndCase => "`CASE`",
        Kw::EndFor => "`FOR`",
        Kw::EndWhile => "`WHILE`",
        Kw::Until | Kw::EndRepeat => "`REPEAT`",
        _ => "statement",
    }
}

pub(super) fn is_end_kw(k: Kw) -> bool {
    matches!(
        k,
        Kw::EndIf | Kw::EndCase | Kw::EndFor | Kw::EndWhile | Kw::EndRepeat
    )
}

impl Parser<'_> {
    /// Whether the current token is a place to resume after an error:
    /// the start of a statement or anything that ends a statement list.
    pub(super) fn at_stmt_sync(&self) -> bool {
        match self.peek() {
            Tok::Eof => true,
            Tok::Kw(k) => {
                k.starts_stmt()
                    || k.is_stmt_closer()
                    || k.is_item_start()
                    || k.is_decl_end()
                    || k.is_var_block()
            }
            _ => false,
        }
    }

    /// Skips to just after the next `;`, or to the next sync point.
    pub(super) fn recover_stmt(&mut self) {
        while !self.at_stmt_sync() {
            if self.bump().tok == Tok::Semi {
                return;
            }
        }
    }

    /// Requires the `;` that ends a statement. A missing one is reported;
    /// the rest of the line is skipped only when the next token cannot
    /// start anything (so `x := 1` newline `y := 2;` gives one error).
    pub(super) fn end_stmt(&mut self, context: &str) {
        if self.eat(Tok::Semi) {
            return;
        }
        if self.newline_before_cur() {
            // The line that lacks it is the one to point at, not the next
            // statement's.
            let msg = format!(
                "expected `;` {context}, at the end of this line (the next line starts with {})",
                self.found()
            );
            self.error_at_prev_end(msg);
        } else {
            self.expected_word(";", context);
        }
        if !(self.newline_before_cur() || self.at_stmt_sync()) {
            self.recover_stmt();
        }
    }

    /// Statements up to a keyword that closes an open construct.
    pub(super) fn stmt_list(&mut self, case_arm: bool) -> Vec<Stmt> {
        let mut out = Vec::new();
        loop {
            match self.peek() {
                Tok::Eof => break,
                Tok::Kw(k) if k.is_item_start() || k.is_decl_end() || k.is_var_block() => break,
                Tok::Kw(k) if k.is_stmt_closer() => {
                    if self.in_frames(k) {
                        break;
                    }
                    self.stray_closer(k);
                    continue;
                }
                _ => {}
            }
            if self.at_oop_boundary() {
                break;
            }
            if case_arm && self.looks_like_case_label() {
                break;
            }
            if self.at_chart_after_statements() {
                break;
            }
            let before = self.pos;
            self.stmt(&mut out);
            if self.pos == before {
                self.bump();
            }
        }
        out
    }

    /// A closer that closes nothing open: reported and skipped.
    #[cold]
    #[inline(never)]
    fn stray_closer(&mut self, k: Kw) {
        let msg = format!(
            "unexpected `{}` here: it does not continue an open {}",
            k.name(),
            opener_of(k)
        );
        self.error_here(msg);
        self.bump();
        if is_end_kw(k) {
            self.eat(Tok::Semi);
        }
    }

    /// One statement, pushed onto `out` (nothing after an error).
    fn stmt(&mut self, out: &mut Vec<Stmt>) {
        let f: fn(&mut Self, &mut Vec<Stmt>) = match self.peek() {
            Tok::Kw(Kw::If) => Self::if_stmt,
            Tok::Kw(Kw::Case) => Self::case_stmt,
            Tok::Kw(Kw::For) => Self::for_stmt,
            Tok::Kw(Kw::While) => Self::while_stmt,
            Tok::Kw(Kw::Repeat) => Self::repeat_stmt,
            _ => return self.simple_stmt(out),
        };
        // A statement that contains statements: one nesting level deeper.
        if !self.enter() {
            return self.skip_balanced();
        }
        f(self, out);
        self.leave();
    }

    /// Any statement that contains no statements.
    #[inline(never)]
    fn simple_stmt(&mut self, out: &mut Vec<Stmt>) {
        let t = self.cur();
        let kind = match t.tok {
            Tok::Semi => {
                self.bump();
                StmtKind::Empty
            }
            Tok::Kw(k @ (Kw::Exit | Kw::Continue | Kw::Return)) => {
                self.bump();
                self.end_stmt(&format!("after `{}`", k.name()));
                match k {
                    Kw::Exit => StmtKind::Exit,
                    Kw::Continue => StmtKind::Continue,
                    _ => StmtKind::Return,
                }
            }
            _ if self.can_start_expr() => return out.push(self.assign_or_call()),
            _ => {
                self.expected("a statement");
                return self.recover_stmt();
            }
        };
        out.push(Stmt {
            kind,
            span: self.tok_span(t),
        });
    }

    /// `target := value;` or `call(...);`
    fn assign_or_call(&mut self) -> Stmt {
        let start = self.cur().start;
        let target = self.expr();
        if self.eat(Tok::ColonEq) {
            let value = self.expr();
            let span = self.span_from(start);
            self.end_stmt("after the assignment");
            return Stmt {
                kind: StmtKind::Assign { target, value },
                span,
            };
        }
        if self.is_word("REF") && self.nth(1) == Tok::Eq {
            return self.ref_bind(start, target);
        }
        let span = self.span_from(start);
        if matches!(target.kind, ExprKind::Call { .. } | ExprKind::Error) {
            self.end_stmt("after the call");
        } else if !self.eat(Tok::Semi) {
            // `x y;`, `x = 1` newline: most likely a `:=` was meant.
            self.expected("`:=` or `;` after the expression");
            if !(self.newline_before_cur() || self.at_stmt_sync()) {
                self.recover_stmt();
            }
        }
        Stmt {
            kind: StmtKind::Expr(target),
            span,
        }
    }

    /// Pushes a finished compound statement spanning `start..end`.
    #[inline(never)]
    pub(super) fn push_stmt(&self, out: &mut Vec<Stmt>, kind: StmtKind, start: u32, end: u32) {
        out.push(Stmt {
            kind,
            span: Span::new(self.file, start, end.max(start)),
        });
    }

    /// Skips a whole compound statement (too deeply nested to parse),
    /// counting openers and `END_x` closers.
    #[cold]
    #[inline(never)]
    fn skip_balanced(&mut self) {
        let mut depth = 0usize;
        loop {
            match self.peek() {
                Tok::Eof => return,
                Tok::Kw(Kw::If | Kw::Case | Kw::For | Kw::While | Kw::Repeat) => depth += 1,
                Tok::Kw(k) if is_end_kw(k) => {
                    depth = depth.saturating_sub(1);
                    if depth == 0 {
                        self.bump();
                        self.eat(Tok::Semi);
                        return;
                    }
                }
                Tok::Kw(k) if k.is_item_start() || k.is_decl_end() => return,
                _ => {}
            }
            self.bump();
        }
    }

    /// Whether the tokens ahead are CASE labels (`1, 2..5:`, `Red:`,
    /// `Color#Red:`) rather than a statement of the current arm.
    pub(super) fn looks_like_case_label(&self) -> bool {
        for i in 0..64 {
            match self.nth(i) {
                Tok::Colon => return i > 0,
                Tok::Ident(_)
                | Tok::Lit(_)
                | Tok::BadLit
                | Tok::Minus
                | Tok::Plus
                | Tok::Comma
                | Tok::DotDot
                | Tok::Dot
                | Tok::Kw(Kw::True | Kw::False) => {}
                Tok::Kw(k) if k.is_contextual() => {}
                _ => return false,
            }
        }
        false
    }
}
