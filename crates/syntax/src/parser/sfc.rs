//! Textual Sequential Function Charts (IEC 61131-3 §2.6 / 3rd ed. §6.7):
//! a POU body made of `INITIAL_STEP`/`STEP`, `TRANSITION` and `ACTION`
//! elements, parsed into an [`ast::sfc::Chart`](crate::ast::sfc::Chart).
//! Checking the chart and rewriting it into ST is `desugar::sfc`'s job.
//!
//! `STEP`, `TRANSITION` and `ACTION` are contextual keywords (common
//! variable names in ST); `FROM` and `PRIORITY` are plain identifiers
//! recognised by their spelling. A body is a chart when it starts with
//! `INITIAL_STEP`, `STEP name :`, `ACTION name :` or `TRANSITION` followed
//! by a name, `FROM` or `(PRIORITY`.
//!
//! Transition conditions (`: <IL>`) and action bodies may be written in
//! IL: the IL parser's entry point (`il_desugared`) parses and rewrites
//! them, and their hidden variables are declared once for the POU.
//!
//! Recovery: an element that does not parse is skipped up to the start of
//! the next element or the end of the POU. A POU body that starts with
//! statements and then has a chart is one error (E005 over the statements,
//! which are dropped); the chart is parsed and checked as usual.

use super::expr::is_identish;
use super::Parser;
use crate::ast::sfc::{Action, ActionBody, Assoc, Chart, Condition, Qualifier, Step, Transition};
use crate::ast::{ExprKind, Ident, Lang, LitKind, Literal, PouKind, Stmt, VarBlock, VarDecl};
use crate::lexer::{Kw, Tok};
use automat_base::{Code, Diagnostic};

pub(super) const END_ACTION: &[Kw] = &[Kw::EndAction];

impl Parser<'_> {
    /// Whether the current token's text is `word` (any case).
    fn at_word(&self, n: usize, word: &str) -> bool {
        let t = self.toks.get(self.pos + n);
        t.is_some_and(|t| is_identish(t.tok) && self.text(*t).eq_ignore_ascii_case(word))
    }

    /// Whether the body starting here is a chart (see the module comment).
    pub(super) fn at_sfc_start(&self) -> bool {
        match self.peek() {
            Tok::Kw(Kw::InitialStep) => true,
            Tok::Kw(Kw::Step | Kw::Action) => is_identish(self.nth(1)) && self.nth(2) == Tok::Colon,
            Tok::Kw(Kw::Transition) => {
                (is_identish(self.nth(1)) && !matches!(self.nth(2), Tok::ColonEq | Tok::Semi))
                    || (self.nth(1) == Tok::LParen && self.at_word(2, "PRIORITY"))
            }
            _ => false,
        }
    }

    /// Whether a chart starts here in the statement list of a POU body
    /// itself (only the POU's frame is open: a nested statement list never
    /// stops here). Lets a body of statements followed by a chart give one
    /// error instead of one per chart keyword.
    pub(super) fn at_chart_after_statements(&self) -> bool {
        self.frames.len() == 1 && self.at_sfc_start()
    }

    /// E005 for the statements that precede a chart in a POU body (at the
    /// chart's start when none parsed).
    pub(super) fn statements_before_chart(&mut self, stmts: &[Stmt]) {
        let span = match (stmts.first(), stmts.last()) {
            (Some(f), Some(l)) => f.span.to(l.span),
            _ => self.cur_span(),
        };
        self.report(Diagnostic::error(
            Code::E005,
            span,
            "a POU body is either statements or a chart, not both: move these statements into an ACTION of the chart (or into another program called before it)",
        ));
    }

    /// Whether the current token starts a chart element.
    fn at_sfc_element(&self) -> bool {
        matches!(
            self.peek(),
            Tok::Kw(Kw::InitialStep | Kw::Step | Kw::Transition | Kw::Action)
        )
    }

    /// Whether the current token ends the chart (the POU's end or anything
    /// that cannot be inside a POU body).
    fn at_sfc_end(&self) -> bool {
        match self.peek() {
            Tok::Eof => true,
            Tok::Kw(k) => k.is_item_start() || k.is_decl_end() || k.is_var_block(),
            _ => false,
        }
    }

    /// Skips to the next chart element or the end of the chart.
    fn recover_sfc(&mut self) {
        while !(self.at_sfc_element() || self.at_sfc_end()) {
            self.bump();
        }
    }

    /// A chart body: the chart (kept for tools) and its ST rewriting, whose
    /// hidden declarations are appended to `var_blocks`.
    pub(super) fn sfc_body(
        &mut self,
        kind: PouKind,
        var_blocks: &mut Vec<VarBlock>,
    ) -> (Vec<Stmt>, Lang) {
        let start = self.cur().start;
        let mut hidden = Vec::new();
        let chart = self.sfc_chart(&mut hidden);
        let span = self.span_from(start);
        let (stmts, block) = crate::desugar::sfc::desugar(
            &chart,
            kind,
            var_blocks,
            span,
            self.interner,
            &mut self.diags,
        );
        var_blocks.extend(block);
        var_blocks.extend(crate::desugar::il::hidden_block(hidden));
        (stmts, Lang::Sfc(Box::new(chart)))
    }

    /// The elements of a chart body, up to the POU's end.
    /// `hidden` collects the hidden variables of IL texts (actions and
    /// conditions written in IL).
    pub(super) fn sfc_chart(&mut self, hidden: &mut Vec<VarDecl>) -> Chart {
        let mut chart = Chart::default();
        loop {
            let before = self.pos;
            match self.peek() {
                _ if self.at_sfc_end() => break,
                Tok::Kw(k @ (Kw::InitialStep | Kw::Step)) => {
                    if let Some(s) = self.sfc_step(k == Kw::InitialStep) {
                        chart.steps.push(s);
                    }
                }
                Tok::Kw(Kw::Transition) => chart.transitions.push(self.sfc_transition(hidden)),
                Tok::Kw(Kw::Action) => {
                    if let Some(a) = self.sfc_action(hidden) {
                        chart.actions.push(a);
                    }
                }
                _ => {
                    self.expected("`STEP`, `TRANSITION` or `ACTION` in a chart");
                    self.bump();
                    self.recover_sfc();
                }
            }
            if self.pos == before {
                self.bump();
            }
        }
        chart
    }

    /// Closes an element with `end` (and an optional `;`); on a missing
    /// closer, reports it and skips to the next element.
    fn sfc_close(&mut self, end: Kw, opener: crate::lexer::Token) {
        if self.eat_kw(end) {
            self.eat(Tok::Semi);
        } else {
            self.report_unclosed(end, opener);
            self.recover_sfc();
        }
    }

    /// `[INITIAL_]STEP name: {assoc;} END_STEP`, at the keyword.
    fn sfc_step(&mut self, initial: bool) -> Option<Step> {
        let opener = self.bump();
        let name = self.expect_ident("the name of the step");
        self.expect(Tok::Colon, "after the step name");
        let mut assocs = Vec::new();
        while is_identish(self.peek()) {
            let before = self.pos;
            match self.sfc_assoc() {
                Some(a) => assocs.push(a),
                None => {
                    while !(self.at(Tok::Semi)
                        || self.at_sfc_element()
                        || self.at_sfc_end()
                        || self.at_kw(Kw::EndStep))
                    {
                        self.bump();
                    }
                    self.eat(Tok::Semi);
                }
            }
            if self.pos == before {
                self.bump();
            }
        }
        self.sfc_close(Kw::EndStep, opener);
        let span = self.span_from(opener.start);
        Some(Step {
            name: name?,
            initial,
            assocs,
            macro_body: None,
            span,
        })
    }

    /// `name(qualifier [, time] {, indicator});`, at the name.
    fn sfc_assoc(&mut self) -> Option<Assoc> {
        let start = self.cur().start;
        let name = self.ident_here()?;
        if !self.expect(Tok::LParen, "after the action name") {
            return None;
        }
        let mut qualifier = Qualifier::N;
        let mut time = None;
        let mut indicators = Vec::new();
        if !self.at(Tok::RParen) {
            let t = self.cur();
            let q =
                self.expect_ident("an action qualifier (N, R, S, P, P1, P0, L, D, SD, DS, SL)")?;
            let text = self.text(t);
            match Qualifier::parse(text) {
                Some(q) => qualifier = q,
                None => self.report(Diagnostic::error(
                    Code::E126,
                    q.span,
                    format!(
                        "unknown action qualifier `{text}`: expected N, R, S, P, P1, P0, L, D, SD, DS or SL"
                    ),
                )),
            }
            if qualifier.is_timed() && self.eat(Tok::Comma) {
                time = Some(self.expr());
            }
            while self.eat(Tok::Comma) {
                match self.peek() {
                    t if is_identish(t) && matches!(self.nth(1), Tok::Comma | Tok::RParen) => {
                        if let Some(i) = self.ident_here() {
                            indicators.push(i);
                        }
                    }
                    // A duration after an untimed qualifier: parsed, then
                    // reported by the chart checks.
                    _ if time.is_none() => time = Some(self.expr()),
                    _ => {
                        self.expected("an indicator variable");
                        return None;
                    }
                }
            }
        }
        if !self.expect(Tok::RParen, "to close the action association") {
            return None;
        }
        let span = self.span_from(start);
        self.expect(Tok::Semi, "after the action association");
        Some(Assoc {
            name,
            qualifier,
            time,
            indicators,
            span,
        })
    }

    /// `s` or `(s1, s2, ...)` in FROM/TO.
    fn sfc_step_list(&mut self, what: &str) -> Vec<Ident> {
        let mut out = Vec::new();
        if self.eat(Tok::LParen) {
            while let Some(i) = self.expect_ident(&format!("a step name in the {what} list")) {
                out.push(i);
                if !self.eat(Tok::Comma) {
                    break;
                }
            }
            self.expect(Tok::RParen, &format!("to close the {what} list"));
        } else if let Some(i) = self.expect_ident(&format!("a step name after `{what}`")) {
            out.push(i);
        }
        out
    }

    /// `TRANSITION [name] [(PRIORITY := n)] FROM steps TO steps cond END_TRANSITION`.
    fn sfc_transition(&mut self, hidden: &mut Vec<VarDecl>) -> Transition {
        let opener = self.bump();
        let name = if is_identish(self.peek()) && !self.at_word(0, "FROM") {
            self.ident_here()
        } else {
            None
        };
        let priority = if self.at(Tok::LParen) {
            self.sfc_priority()
        } else {
            None
        };
        let mut from = Vec::new();
        if self.at_word(0, "FROM") {
            self.bump();
            from = self.sfc_step_list("FROM");
        } else {
            self.expected("`FROM` and the steps the transition leaves");
        }
        let mut to = Vec::new();
        if self.expect_kw(Kw::To, "and the steps the transition enters") {
            to = self.sfc_step_list("TO");
        }
        let cond = if self.eat(Tok::ColonEq) {
            let e = self.expr();
            self.expect(Tok::Semi, "after the transition condition");
            if matches!(e.kind, ExprKind::Error) {
                Condition::Missing
            } else {
                Condition::St(e)
            }
        } else if self.eat(Tok::Colon) {
            let (il, mut out) = self.il_desugared(&[Kw::EndTransition], true, hidden);
            let scope = match name {
                Some(n) => self.interner.name(n.sym).to_string(),
                None => format!("__t{}", opener.start),
            };
            crate::desugar::sfc::scope::scope_labels(&mut out.stmts, &scope, self.interner);
            match out.result {
                Some(result) => Condition::Il {
                    il: Box::new(il),
                    stmts: out.stmts,
                    result,
                },
                None => {
                    self.report(Diagnostic::error(
                        Code::E005,
                        self.span_from(opener.start),
                        "the IL transition condition leaves no current result: end it with an instruction that computes one (`LD x`, `AND y`, `GT 5`)",
                    ));
                    Condition::Missing
                }
            }
        } else {
            self.expected("`:=` (ST) or `:` (IL) and the transition condition");
            Condition::Missing
        };
        self.sfc_close(Kw::EndTransition, opener);
        Transition {
            name,
            priority,
            from,
            to,
            jump: false,
            cond,
            span: self.span_from(opener.start),
        }
    }

    /// `(PRIORITY := n)`, at `(`.
    fn sfc_priority(&mut self) -> Option<u32> {
        self.bump();
        if !self.at_word(0, "PRIORITY") {
            self.expected("`PRIORITY` in the transition's parentheses");
            return None;
        }
        self.bump();
        self.expect(Tok::ColonEq, "after `PRIORITY`");
        let e = self.expr();
        self.expect(Tok::RParen, "to close `(PRIORITY := ...)`");
        let value = match &e.kind {
            ExprKind::Literal(l) => match **l {
                Literal {
                    kind: LitKind::Int(v),
                    ty: None,
                } => u32::try_from(v).ok(),
                _ => None,
            },
            ExprKind::Error => return None,
            _ => None,
        };
        if value.is_none() {
            self.report(Diagnostic::error(
                Code::E130,
                e.span,
                "the PRIORITY of a transition must be a non-negative integer literal",
            ));
        }
        value
    }

    /// `ACTION name: statements END_ACTION`, at `ACTION`.
    fn sfc_action(&mut self, hidden: &mut Vec<VarDecl>) -> Option<Action> {
        let opener = self.bump();
        let name = self.expect_ident("the name of the action");
        self.expect(Tok::Colon, "after the action name");
        let body = if self.at_il_start() {
            let (il, mut out) = self.il_desugared(END_ACTION, false, hidden);
            // Each IL action has its own labels (see `desugar::sfc::scope`).
            let scope = match name {
                Some(n) => self.interner.name(n.sym).to_string(),
                None => format!("__a{}", opener.start),
            };
            crate::desugar::sfc::scope::scope_labels(&mut out.stmts, &scope, self.interner);
            ActionBody::Il {
                il: Box::new(il),
                stmts: out.stmts,
            }
        } else {
            self.frames.push(END_ACTION);
            let stmts = self.stmt_list(false);
            self.frames.pop();
            ActionBody::St(stmts)
        };
        self.sfc_close(Kw::EndAction, opener);
        Some(Action {
            name: name?,
            body,
            span: self.span_from(opener.start),
        })
    }
}

#[cfg(test)]
#[path = "sfc_tests.rs"]
mod tests;
