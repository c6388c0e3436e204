//! The scenario language (line-oriented; `#` starts a comment; keywords
//! case-insensitive). The grammar is documented in `crates/plant/README.md`
//! and in `lib.rs`; errors are E320 (syntax) and E323 (no duration).
//!
//! Conditions follow IEC operator precedence: NOT, then comparisons, then
//! AND, XOR, OR; a bare reference means `= TRUE`.

use crate::ast::*;
use crate::lex::{tokens, Tok, Token};
use automat_base::{Code, Diagnostic, FileId, Span};
use automat_runtime::timearg::parse_duration;

struct Line<'a> {
    toks: Vec<Token>,
    pos: usize,
    file: FileId,
    /// Byte offset of the line in the file.
    base: usize,
    text: &'a str,
    number: u32,
    /// Operands read by `unary` on this line so far (see [`MAX_TERMS`]).
    terms: usize,
    /// NOTs and parentheses open around the current operand.
    depth: usize,
}

/// The most operands (names, values, NOTs and parentheses) one line's
/// condition may have, and how deeply NOT and parentheses may nest. The
/// parser and the checker recurse once per nesting level and per operator
/// (each level is about 10 KB of stack in a debug build), so without a
/// bound a line of 100 000 `NOT` or `(`, or a long `a AND a AND ...`
/// chain, overflowed the stack; real conditions have a few dozen operands
/// and a handful of levels.
pub const MAX_TERMS: usize = 256;
pub const MAX_NESTING: usize = 32;

type Res<T> = Result<T, Diagnostic>;

fn kw(t: Option<&Token>, word: &str) -> bool {
    matches!(t, Some(Token { tok: Tok::Word(w), .. }) if w.eq_ignore_ascii_case(word))
}

impl<'a> Line<'a> {
    fn span(&self, start: usize, end: usize) -> Span {
        let c = |x: usize| u32::try_from(self.base + x).unwrap_or(u32::MAX);
        Span::new(self.file, c(start), c(end))
    }
    fn peek(&self) -> Option<&Token> {
        self.toks.get(self.pos)
    }
    /// The span of the next token (or the end of the line).
    fn here(&self) -> Span {
        match self.peek() {
            Some(t) => self.span(t.start, t.end),
            None => self.span(self.text.len(), self.text.len()),
        }
    }
    fn err(&self, msg: impl Into<String>) -> Diagnostic {
        Diagnostic::error(Code::E320, self.here(), msg)
    }
    fn at_end(&self) -> bool {
        self.pos >= self.toks.len()
    }
    fn end(&self) -> Res<()> {
        if self.at_end() {
            Ok(())
        } else {
            Err(self.err("unexpected text at the end of the line"))
        }
    }
    fn eat_kw(&mut self, word: &str) -> bool {
        if kw(self.peek(), word) {
            self.pos += 1;
            true
        } else {
            false
        }
    }
    fn expect_kw(&mut self, word: &str) -> Res<()> {
        if self.eat_kw(word) {
            Ok(())
        } else {
            Err(self.err(format!("expected `{word}`")))
        }
    }
    fn eat_op(&mut self, op: &str) -> bool {
        if matches!(self.peek(), Some(Token { tok: Tok::Op(o), .. }) if *o == op) {
            self.pos += 1;
            true
        } else {
            false
        }
    }
    fn word(&mut self, what: &str) -> Res<(String, Span)> {
        match self.peek() {
            Some(Token {
                tok: Tok::Word(w),
                start,
                end,
            }) => {
                let r = (w.clone(), self.span(*start, *end));
                self.pos += 1;
                Ok(r)
            }
            _ => Err(self.err(format!("expected {what}"))),
        }
    }
    fn name(&mut self, what: &str) -> Res<Name> {
        let (text, span) = self.word(what)?;
        Ok(Name { text, span })
    }
    fn time(&mut self) -> Res<i64> {
        let span = self.here();
        let (w, _) = self.word("a time such as `200ms`, `1.5s` or `T#1m30s`")?;
        parse_duration(&w).map_err(|e| Diagnostic::error(Code::E320, span, e))
    }
    /// A `-` sign before a number: its span.
    fn minus(&mut self) -> Option<Span> {
        let span = self.here();
        self.eat_op("-").then_some(span)
    }
    fn number(&mut self) -> Res<f64> {
        let neg = self.minus();
        let span = self.here();
        let (w, _) = self.word("a number")?;
        let span = neg.map_or(span, |m| m.to(span));
        w.parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .filter(|_| neg.is_none() || !w.starts_with(['-', '+']))
            .map(|x| if neg.is_some() { -x } else { x })
            .ok_or_else(|| Diagnostic::error(Code::E320, span, format!("`{w}` is not a number")))
    }
    fn value(&mut self) -> Res<(Lit, Span)> {
        let neg = self.minus();
        let (w, span) = self.word("a value (TRUE, FALSE, a number, a TIME or Type#Value)")?;
        let span = neg.map_or(span, |m| m.to(span));
        let lit = match (literal(&w), neg) {
            (l, None) => l,
            (Some(Lit::Int(i)), Some(_)) if i != i64::MIN => Some(Lit::Int(-i)),
            (Some(Lit::Real(r)), Some(_)) => Some(Lit::Real(-r)),
            (Some(Lit::Time(t)), Some(_)) if t != i64::MIN => Some(Lit::Time(-t)),
            _ => None,
        };
        lit.map(|l| (l, span))
            .ok_or_else(|| Diagnostic::error(Code::E320, span, format!("`{w}` is not a value")))
    }

    // ---- conditions ----
    fn expr(&mut self) -> Res<Expr> {
        self.binary(0)
    }
    /// Levels: 0 OR, 1 XOR, 2 AND.
    fn binary(&mut self, level: u8) -> Res<Expr> {
        let (word, op) = match level {
            0 => ("OR", LogicOp::Or),
            1 => ("XOR", LogicOp::Xor),
            2 => ("AND", LogicOp::And),
            _ => return self.comparison(),
        };
        let mut left = self.binary(level + 1)?;
        while self.eat_kw(word) || (op == LogicOp::And && self.eat_op("&")) {
            let right = self.binary(level + 1)?;
            left = Expr::Logic(op, Box::new(left), Box::new(right));
        }
        Ok(left)
    }
    fn comparison(&mut self) -> Res<Expr> {
        let left = self.additive()?;
        let op = match self.peek() {
            Some(Token {
                tok: Tok::Op(o), ..
            }) => match *o {
                "=" => CmpOp::Eq,
                "<>" => CmpOp::Ne,
                "<" => CmpOp::Lt,
                "<=" => CmpOp::Le,
                ">" => CmpOp::Gt,
                ">=" => CmpOp::Ge,
                _ => return Ok(left),
            },
            _ => return Ok(left),
        };
        self.pos += 1;
        let right = self.additive()?;
        Ok(Expr::Cmp(op, Box::new(left), Box::new(right)))
    }
    fn additive(&mut self) -> Res<Expr> {
        let mut left = self.multiplicative()?;
        loop {
            let op = if self.eat_op("+") {
                ArithOp::Add
            } else if self.eat_op("-") {
                ArithOp::Sub
            } else {
                return Ok(left);
            };
            let right = self.multiplicative()?;
            left = Expr::Arith(op, Box::new(left), Box::new(right));
        }
    }
    fn multiplicative(&mut self) -> Res<Expr> {
        let mut left = self.unary()?;
        loop {
            let op = if self.eat_op("*") {
                ArithOp::Mul
            } else if self.eat_op("/") {
                ArithOp::Div
            } else if self.eat_kw("MOD") {
                ArithOp::Mod
            } else {
                return Ok(left);
            };
            let right = self.unary()?;
            left = Expr::Arith(op, Box::new(left), Box::new(right));
        }
    }
    /// `f` one level deeper (a NOT, a minus, a parenthesis or a function
    /// call), within [`MAX_NESTING`].
    fn nested(&mut self, f: impl FnOnce(&mut Self) -> Res<Expr>) -> Res<Expr> {
        if self.depth >= MAX_NESTING {
            return Err(self.err(format!(
                "NOT, minus signs, parentheses and function calls nest too deeply (at most {MAX_NESTING} levels)"
            )));
        }
        self.depth += 1;
        let r = f(self);
        self.depth -= 1;
        r
    }
    fn close(&mut self) -> Res<usize> {
        match self.peek() {
            Some(Token {
                tok: Tok::RParen,
                end,
                ..
            }) => {
                let end = *end;
                self.pos += 1;
                Ok(end)
            }
            _ => Err(self.err("expected `)`")),
        }
    }
    fn unary(&mut self) -> Res<Expr> {
        // Every operand of a condition is read here: counting the calls
        // bounds the size of the tree (and so the checker's recursion on a
        // long `a AND b AND ...` chain).
        self.terms += 1;
        if self.terms > MAX_TERMS {
            return Err(self.err(format!(
                "the condition is too long (more than {MAX_TERMS} names, values, operators and parentheses)"
            )));
        }
        if self.eat_kw("NOT") {
            return self.nested(|l| Ok(Expr::Not(Box::new(l.unary()?))));
        }
        if let Some(Token {
            tok: Tok::Op("-"),
            start,
            end,
        }) = self.peek().cloned()
        {
            self.pos += 1;
            let span = self.span(start, end);
            return self.nested(|l| {
                Ok(match l.unary()? {
                    // `-5` is the literal -5 (so `set`-like uses and
                    // messages show it as written).
                    Expr::Lit(Lit::Int(i), s) if i != i64::MIN => {
                        Expr::Lit(Lit::Int(-i), span.to(s))
                    }
                    Expr::Lit(Lit::Real(r), s) => Expr::Lit(Lit::Real(-r), span.to(s)),
                    x => Expr::Neg(Box::new(x), span),
                })
            });
        }
        match self.peek().cloned() {
            Some(Token {
                tok: Tok::LParen, ..
            }) => {
                self.pos += 1;
                let e = self.nested(Self::expr)?;
                self.close()?;
                Ok(e)
            }
            Some(Token {
                tok: Tok::Word(w),
                start,
                end,
            }) if !is_stop_word(&w) => {
                self.pos += 1;
                let span = self.span(start, end);
                let call = Func::by_name(&w).filter(|_| {
                    matches!(
                        self.peek(),
                        Some(Token {
                            tok: Tok::LParen,
                            ..
                        })
                    )
                });
                if let Some(f) = call {
                    self.pos += 1;
                    return self.nested(|l| {
                        let mut args = vec![l.expr()?];
                        while args.len() < f.arity() {
                            if !l.eat_op(",") {
                                return Err(l.err(format!(
                                    "expected `,`: {}(...) takes {} arguments",
                                    f.name(),
                                    f.arity()
                                )));
                            }
                            args.push(l.expr()?);
                        }
                        let end = l.close()?;
                        Ok(Expr::Call(f, args, span.to(l.span(end, end))))
                    });
                }
                Ok(match literal(&w) {
                    Some(l) => Expr::Lit(l, span),
                    None => Expr::Ref(Name { text: w, span }),
                })
            }
            _ => Err(self.err(
                "expected a condition or value (a name, a value, NOT, `-`, `(` or a function such as rise(x))",
            )),
        }
    }

    /// `after TIME` or `after EVENT`.
    fn anchor(&mut self) -> Res<Anchor> {
        if let Some(Token {
            tok: Tok::Word(w), ..
        }) = self.peek()
        {
            if let Ok(t) = parse_duration(w) {
                self.pos += 1;
                return Ok(Anchor::Time(t));
            }
        }
        Ok(Anchor::Event(self.expr()?))
    }
}

fn is_stop_word(w: &str) -> bool {
    [
        "within", "during", "after", "stable", "for", "then", "AND", "OR", "XOR", "MOD",
    ]
    .iter()
    .any(|k| w.eq_ignore_ascii_case(k))
}

/// A literal, or `None` when the word is a name.
pub fn literal(w: &str) -> Option<Lit> {
    if w.eq_ignore_ascii_case("TRUE") {
        return Some(Lit::Bool(true));
    }
    if w.eq_ignore_ascii_case("FALSE") {
        return Some(Lit::Bool(false));
    }
    let starts_numeric = w.starts_with(|c: char| c.is_ascii_digit() || c == '-' || c == '+');
    if starts_numeric {
        if let Ok(i) = w.parse::<i64>() {
            return Some(Lit::Int(i));
        }
        if let Some(r) = w.parse::<f64>().ok().filter(|r| r.is_finite()) {
            return Some(Lit::Real(r));
        }
    }
    if let Ok(t) = parse_duration(w) {
        return Some(Lit::Time(t));
    }
    if let Some((ty, v)) = w.split_once('#') {
        let ident = |s: &str| {
            !s.is_empty()
                && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
                && !s.starts_with(|c: char| c.is_ascii_digit())
        };
        if ident(ty) && ident(v) {
            return Some(Lit::Enum(ty.to_string(), v.to_string()));
        }
    }
    None
}

/// Parses a scenario file; `default_name` is used without a `name` line.
pub fn parse(text: &str, file: FileId, default_name: &str) -> Result<Scenario, Vec<Diagnostic>> {
    let mut scn = Scenario {
        name: default_name.to_string(),
        duration_ns: 0,
        seed: None,
        actions: Vec::new(),
        reactions: Vec::new(),
        expects: Vec::new(),
    };
    let mut duration = false;
    let mut errors = Vec::new();
    let mut base = 0usize;
    for (i, raw) in text.split('\n').enumerate() {
        let number = u32::try_from(i + 1).unwrap_or(u32::MAX);
        let here = base;
        base += raw.len() + 1;
        let toks = match tokens(raw) {
            Ok(t) => t,
            Err((at, msg)) => {
                let o = u32::try_from(here + at).unwrap_or(u32::MAX);
                errors.push(Diagnostic::error(
                    Code::E320,
                    Span::new(file, o, o.saturating_add(1)),
                    msg,
                ));
                continue;
            }
        };
        if toks.is_empty() {
            continue;
        }
        let mut line = Line {
            toks,
            pos: 0,
            file,
            base: here,
            text: raw,
            number,
            terms: 0,
            depth: 0,
        };
        match statement(&mut line, &mut scn) {
            Ok(Some(())) => duration = true,
            Ok(None) => {}
            Err(d) => errors.push(d),
        }
    }
    if !duration && errors.is_empty() {
        errors.push(
            Diagnostic::error(
                Code::E323,
                Span::new(file, 0, 0),
                "the scenario has no `duration` line",
            )
            .with_note("add a line such as `duration 60s`: the PLC time to simulate"),
        );
    }
    if errors.is_empty() {
        Ok(scn)
    } else {
        Err(errors)
    }
}

/// One line; `Some(())` when it was the `duration` line.
fn statement(l: &mut Line, scn: &mut Scenario) -> Res<Option<()>> {
    let (head, _) = l.word("`name`, `duration`, `seed`, `at`, `when` or `expect`")?;
    match head.to_ascii_lowercase().as_str() {
        "name" => {
            scn.name = match l.peek() {
                Some(Token {
                    tok: Tok::Str(s), ..
                }) => {
                    let s = s.clone();
                    l.pos += 1;
                    s
                }
                _ => {
                    let start = l.peek().map_or(l.text.len(), |t| t.start);
                    l.pos = l.toks.len();
                    l.text
                        .get(start..)
                        .unwrap_or("")
                        .split('#')
                        .next()
                        .unwrap_or("")
                        .trim()
                        .to_string()
                }
            };
        }
        "duration" => {
            scn.duration_ns = l.time()?;
            l.end()?;
            return Ok(Some(()));
        }
        "seed" => {
            let span = l.here();
            let (w, _) = l.word("a seed (a whole number)")?;
            scn.seed = Some(w.parse().map_err(|_| {
                Diagnostic::error(Code::E320, span, format!("`{w}` is not a whole number"))
            })?);
        }
        "at" => {
            let at_ns = l.time()?;
            let kind = action(l)?;
            scn.actions.push(Action {
                at_ns,
                kind,
                line: l.number,
            });
        }
        "when" => {
            let event = l.expr()?;
            let delay_ns = if l.eat_kw("after") { l.time()? } else { 0 };
            l.expect_kw("then")?;
            let kind = action(l)?;
            scn.reactions.push(Reaction {
                event,
                delay_ns,
                kind,
                line: l.number,
            });
        }
        "expect" => {
            let start = l.peek().map_or(l.text.len(), |t| t.start);
            let e = expect(l)?;
            let end = l.toks.last().map_or(start, |t| t.end);
            scn.expects.push(Expect {
                text: l.text.get(start..end).unwrap_or("").to_string(),
                line: l.number,
                span: l.span(start, end),
                ..e
            });
        }
        other => {
            l.pos = 0;
            return Err(l.err(format!(
                "unknown statement `{other}` (want `name`, `duration`, `seed`, `at`, `when` or `expect`)"
            )));
        }
    }
    l.end()?;
    Ok(None)
}

fn action(l: &mut Line) -> Res<ActionKind> {
    let (verb, span) = l.word("an action (press, release, set, stuck, unstick, noise, plant)")?;
    Ok(match verb.to_ascii_lowercase().as_str() {
        "press" => {
            let n = l.name("a signal")?;
            let d = if l.eat_kw("for") { Some(l.time()?) } else { None };
            ActionKind::Press(n, d)
        }
        "release" => ActionKind::Release(l.name("a signal")?),
        "set" | "stuck" => {
            let n = l.name("a signal or variable")?;
            l.eat_op("=");
            let (v, vs) = l.value()?;
            if verb.eq_ignore_ascii_case("set") {
                ActionKind::Set(n, v, vs)
            } else {
                ActionKind::Stuck(n, v, vs)
            }
        }
        "unstick" => ActionKind::Unstick(l.name("a signal")?),
        "noise" => {
            let n = l.name("a signal")?;
            ActionKind::Noise(n, l.number()?)
        }
        "plant" => {
            let cmd = l.name("a model command")?;
            let mut args = Vec::new();
            while !l.at_end() {
                let (k, _) = l.word("`key=value`")?;
                if !l.eat_op("=") {
                    return Err(l.err("expected `=` (arguments are `key=value`)"));
                }
                args.push((k, l.number()?));
            }
            ActionKind::Plant(cmd, args)
        }
        _ => {
            return Err(Diagnostic::error(
                Code::E320,
                span,
                format!("unknown action `{verb}` (want press, release, set, stuck, unstick, noise or plant)"),
            ))
        }
    })
}

/// A range `A..B` (one word).
fn range(l: &mut Line) -> Res<(i64, i64)> {
    let span = l.here();
    let (w, _) = l.word("a range `A..B`")?;
    let bad = |m: String| Diagnostic::error(Code::E320, span, m);
    let (a, b) = w
        .split_once("..")
        .ok_or_else(|| bad(format!("`{w}` is not a range `A..B`")))?;
    let a = parse_duration(a).map_err(&bad)?;
    let b = parse_duration(b).map_err(&bad)?;
    if b < a {
        return Err(bad(format!("the range `{w}` ends before it starts")));
    }
    Ok((a, b))
}

fn during(l: &mut Line) -> Res<(i64, Option<i64>)> {
    if !l.eat_kw("during") {
        return Ok((0, None));
    }
    let (a, b) = range(l)?;
    Ok((a, Some(b)))
}

fn expect(l: &mut Line) -> Res<Expect> {
    let span = l.here();
    let blank = |when, cond| Expect {
        when,
        cond,
        text: String::new(),
        line: 0,
        span,
    };
    if l.eat_kw("at") {
        let t = l.time()?;
        let c = l.expr()?;
        return Ok(blank(When::At(t), c));
    }
    if l.eat_kw("always") || kw(l.peek(), "never") {
        let never = l.eat_kw("never");
        let c = l.expr()?;
        let (from, to) = during(l)?;
        let c = if never { Expr::Not(Box::new(c)) } else { c };
        return Ok(blank(When::Always { from, to }, c));
    }
    let c = l.expr()?;
    if l.eat_kw("within") {
        let within = l.time()?;
        l.expect_kw("after")?;
        let after = l.anchor()?;
        return Ok(blank(When::Within { after, within }, c));
    }
    if l.eat_kw("stable") {
        if l.eat_kw("during") {
            let (a, b) = range(l)?;
            let when = When::Stable {
                after: Anchor::Time(a),
                for_ns: b - a,
            };
            return Ok(blank(when, c));
        }
        l.expect_kw("for")?;
        let for_ns = l.time()?;
        l.expect_kw("after")?;
        let after = l.anchor()?;
        return Ok(blank(When::Stable { after, for_ns }, c));
    }
    if kw(l.peek(), "during") {
        let here = l.here();
        l.pos += 1;
        let (from, to) = range(l)?;
        if !c.has_count() {
            return Err(Diagnostic::error(
                Code::E320,
                here,
                "`expect C during A..B` judges C once at B, for conditions with count(...); write `expect always C during A..B` for C at every scan",
            ));
        }
        return Ok(blank(When::During { from, to }, c));
    }
    Err(l.err(
        "expected `within`, `stable` or `during` (or write `expect at T C`, `expect always C`)",
    ))
}

#[cfg(test)]
#[path = "parse_tests.rs"]
mod tests;

/// One action typed by a person (`press Pornire`, `set l2 1`,
/// `stuck l2 = TRUE`): the `ACTION` part of an `at TIME ACTION` line.
pub fn parse_action(text: &str, file: FileId) -> Result<ActionKind, Diagnostic> {
    let toks = tokens(text).map_err(|(at, msg)| {
        let o = u32::try_from(at).unwrap_or(u32::MAX);
        Diagnostic::error(Code::E320, Span::new(file, o, o.saturating_add(1)), msg)
    })?;
    let mut l = Line {
        toks,
        pos: 0,
        file,
        base: 0,
        text,
        number: 1,
        terms: 0,
        depth: 0,
    };
    let a = action(&mut l)?;
    l.end()?;
    Ok(a)
}
