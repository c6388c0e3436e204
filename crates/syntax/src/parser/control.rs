//! Compound statements: IF, CASE, FOR, WHILE, REPEAT. Each pushes the
//! closers it accepts onto `frames` while its bodies are parsed, and builds
//! its node in `push_stmt` (off the recursion path, see `stmt.rs`).

use super::stmt::is_end_kw;
use super::Parser;
use crate::ast::{CaseArm, CaseLabel, CondBlock, Stmt, StmtKind};
use crate::lexer::{Kw, Tok, Token};
use automat_base::{Code, Diagnostic};

const IF_CLOSERS: &[Kw] = &[Kw::Elsif, Kw::Else, Kw::EndIf];
const CASE_CLOSERS: &[Kw] = &[Kw::Else, Kw::EndCase];
const FOR_CLOSERS: &[Kw] = &[Kw::EndFor];
const WHILE_CLOSERS: &[Kw] = &[Kw::EndWhile];
const REPEAT_CLOSERS: &[Kw] = &[Kw::Until, Kw::EndRepeat];

impl Parser<'_> {
    /// Expects a keyword; if it is missing but appears a few tokens later in
    /// the same statement (`IF a b THEN`), skips to just after it.
    fn expect_kw_skip(&mut self, kw: Kw, context: &str) {
        if self.eat_kw(kw) {
            return;
        }
        let mut found = None;
        for i in 0..16 {
            match self.nth(i) {
                Tok::Kw(k) if k == kw => {
                    found = Some(i);
                    break;
                }
                Tok::Semi | Tok::Eof => break,
                Tok::Kw(k)
                    if k.starts_stmt()
                        || k.is_stmt_closer()
                        || k.is_item_start()
                        || k.is_decl_end() =>
                {
                    break
                }
                _ => {}
            }
        }
        self.expected_word(kw.name(), context);
        if let Some(n) = found {
            for _ in 0..=n {
                self.bump();
            }
        }
    }

    /// Consumes `END_x ;` and returns the end of the statement. When the
    /// closer is missing, reports it once, pointing at the opener too.
    fn close(&mut self, end: Kw, opener: Token) -> u32 {
        if self.eat_kw(end) {
            let stop = self.prev_end;
            if self.opts.codesys && self.peek() != Tok::Semi {
                // CODESYS accepts `END_IF` without its `;`.
                return stop;
            }
            let before = self.diags.len();
            self.end_stmt(&format!("after `{}`", end.name()));
            if self.diags.len() > before && self.newline_before_cur() {
                if let Some(d) = self.diags.pop() {
                    self.diags.push(d.with_note(format!(
                        "CODESYS accepts `{}` without `;`: check with `--lib codesys` (or `libraries = [\"codesys\"]` in automat.toml) to read CODESYS code",
                        end.name()
                    )));
                }
            }
            return stop;
        }
        self.unclosed_stmt(end, opener);
        self.prev_end
    }

    #[cold]
    #[inline(never)]
    fn unclosed_stmt(&mut self, end: Kw, opener: Token) {
        let open = match opener.tok {
            Tok::Kw(k) => k.name(),
            _ => "statement",
        };
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
        // A closer of another kind that closes nothing open (`END_WHILE`
        // for `END_IF`) is taken as a misspelling of this one.
        if let Tok::Kw(k) = self.peek() {
            if is_end_kw(k) && !self.in_frames(k) {
                self.bump();
                self.eat(Tok::Semi);
            }
        }
    }

    /// Replaces the closers of the innermost construct.
    fn narrow_frame(&mut self, closers: &'static [Kw]) {
        if let Some(top) = self.frames.last_mut() {
            *top = closers;
        }
    }

    /// A body parsed with `closers` as the innermost frame.
    fn body_in(&mut self, closers: &'static [Kw]) -> Vec<Stmt> {
        self.frames.push(closers);
        let body = self.stmt_list(false);
        self.frames.pop();
        body
    }

    pub(super) fn if_stmt(&mut self, out: &mut Vec<Stmt>) {
        let opener = self.bump();
        let mut branches = Vec::new();
        let mut else_body = None;
        self.frames.push(IF_CLOSERS);
        let mut kw_start = opener.start;
        loop {
            self.if_branch(kw_start, &mut branches);
            if !self.at_kw(Kw::Elsif) {
                break;
            }
            kw_start = self.bump().start;
        }
        if self.eat_kw(Kw::Else) {
            // After ELSE only END_IF closes: a second ELSE is stray.
            self.narrow_frame(&[Kw::EndIf]);
            else_body = Some(self.stmt_list(false));
        }
        self.frames.pop();
        let end = self.close(Kw::EndIf, opener);
        let kind = StmtKind::If {
            branches,
            else_body,
        };
        self.push_stmt(out, kind, opener.start, end);
    }

    /// `cond THEN body` of an IF or ELSIF starting at `start`.
    fn if_branch(&mut self, start: u32, branches: &mut Vec<CondBlock>) {
        let cond = self.expr();
        let ctx = if branches.is_empty() {
            "after the IF condition"
        } else {
            "after the ELSIF condition"
        };
        self.expect_kw_skip(Kw::Then, ctx);
        let body = self.stmt_list(false);
        branches.push(CondBlock {
            cond,
            body,
            span: self.span_from(start),
        });
    }

    pub(super) fn case_stmt(&mut self, out: &mut Vec<Stmt>) {
        let opener = self.bump();
        let selector = self.expr();
        self.expect_kw_skip(Kw::Of, "after the CASE selector");
        let mut arms = Vec::new();
        let mut else_body = None;
        self.frames.push(CASE_CLOSERS);
        loop {
            match self.peek() {
                Tok::Eof | Tok::Kw(Kw::Else | Kw::EndCase) => break,
                Tok::Kw(k) if k.is_item_start() || k.is_decl_end() || k.is_var_block() => break,
                Tok::Kw(k) if k.is_stmt_closer() && self.in_frames(k) => break,
                _ => {}
            }
            let before = self.pos;
            self.case_arm(&mut arms);
            if self.pos == before {
                self.bump();
            }
        }
        if self.eat_kw(Kw::Else) {
            self.narrow_frame(&[Kw::EndCase]);
            else_body = Some(self.stmt_list(false));
        }
        self.frames.pop();
        let end = self.close(Kw::EndCase, opener);
        let kind = StmtKind::Case {
            selector,
            arms,
            else_body,
        };
        self.push_stmt(out, kind, opener.start, end);
    }

    /// `labels: statements`
    fn case_arm(&mut self, arms: &mut Vec<CaseArm>) {
        let start = self.cur().start;
        let labels = self.case_labels();
        self.expect(Tok::Colon, "after the CASE labels");
        let body = self.stmt_list(true);
        arms.push(CaseArm {
            labels,
            body,
            span: self.span_from(start),
        });
    }

    fn case_labels(&mut self) -> Vec<CaseLabel> {
        let mut labels = Vec::new();
        loop {
            let lo = self.expr();
            if self.eat(Tok::DotDot) {
                let hi = self.expr();
                labels.push(CaseLabel::Range(lo, hi));
            } else {
                labels.push(CaseLabel::Value(lo));
            }
            if !self.eat(Tok::Comma) {
                return labels;
            }
        }
    }

    pub(super) fn for_stmt(&mut self, out: &mut Vec<Stmt>) {
        let opener = self.bump();
        let var = self.expect_ident("the name of the FOR loop variable");
        self.expect(Tok::ColonEq, "after the FOR loop variable");
        let from = self.expr();
        self.expect_kw(Kw::To, "after the start value of the FOR loop");
        let to = self.expr();
        let by = if self.eat_kw(Kw::By) {
            Some(self.expr())
        } else {
            None
        };
        self.expect_kw_skip(Kw::Do, "after the FOR loop header");
        let body = self.body_in(FOR_CLOSERS);
        let end = self.close(Kw::EndFor, opener);
        // Without a loop variable there is no FOR to check; the error was
        // reported, and so were the body's own errors.
        if let Some(var) = var {
            let kind = StmtKind::For {
                var,
                from: Box::new(from),
                to: Box::new(to),
                by: by.map(Box::new),
                body,
            };
            self.push_stmt(out, kind, opener.start, end);
        }
    }

    pub(super) fn while_stmt(&mut self, out: &mut Vec<Stmt>) {
        let opener = self.bump();
        let cond = self.expr();
        self.expect_kw_skip(Kw::Do, "after the WHILE condition");
        let body = self.body_in(WHILE_CLOSERS);
        let end = self.close(Kw::EndWhile, opener);
        self.push_stmt(out, StmtKind::While { cond, body }, opener.start, end);
    }

    pub(super) fn repeat_stmt(&mut self, out: &mut Vec<Stmt>) {
        let opener = self.bump();
        let body = self.body_in(REPEAT_CLOSERS);
        let until = if self.expect_kw(Kw::Until, "after the REPEAT body") {
            self.expr()
        } else {
            self.error_expr()
        };
        let end = self.close(Kw::EndRepeat, opener);
        self.push_stmt(out, StmtKind::Repeat { body, until }, opener.start, end);
    }
}
