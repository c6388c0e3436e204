//! Expressions. Precedence, lowest first: OR; XOR; AND `&`; `=` `<>`;
//! `<` `>` `<=` `>=`; `+` `-`; `*` `/` MOD; unary `-` `+` NOT; `**`;
//! postfix (member, index, call, deref, partial access). Binary operators
//! are left-associative; `**` binds tighter than unary minus (`-2**2` is
//! `-(2**2)`) and its right operand may be negated (`2 ** -1`).

use super::address::{decode_address, decode_partial};
use super::Parser;
use crate::ast::{Arg, ArgDir, BinaryOp, Expr, ExprKind, Ident, LitKind, Literal, UnaryOp};
use crate::lexer::{Kw, Tok};
use automat_base::{Code, Diagnostic, Span};

fn binop(t: Tok) -> Option<(BinaryOp, u8)> {
    Some(match t {
        Tok::Kw(Kw::Or) => (BinaryOp::Or, 1),
        Tok::Kw(Kw::Xor) => (BinaryOp::Xor, 2),
        Tok::Kw(Kw::And) | Tok::Amp => (BinaryOp::And, 3),
        Tok::Eq => (BinaryOp::Eq, 4),
        Tok::Ne => (BinaryOp::Ne, 4),
        Tok::Lt => (BinaryOp::Lt, 5),
        Tok::Gt => (BinaryOp::Gt, 5),
        Tok::Le => (BinaryOp::Le, 5),
        Tok::Ge => (BinaryOp::Ge, 5),
        Tok::Plus => (BinaryOp::Add, 6),
        Tok::Minus => (BinaryOp::Sub, 6),
        Tok::Star => (BinaryOp::Mul, 7),
        Tok::Slash => (BinaryOp::Div, 7),
        Tok::Kw(Kw::Mod) => (BinaryOp::Mod, 7),
        _ => return None,
    })
}

fn unop(t: Tok) -> Option<UnaryOp> {
    match t {
        Tok::Minus => Some(UnaryOp::Neg),
        Tok::Plus => Some(UnaryOp::Plus),
        Tok::Kw(Kw::Not) => Some(UnaryOp::Not),
        _ => None,
    }
}

pub(super) fn is_identish(t: Tok) -> bool {
    match t {
        Tok::Ident(_) => true,
        Tok::Kw(k) => k.is_contextual(),
        _ => false,
    }
}

fn mk(kind: ExprKind, span: Span) -> Expr {
    Expr { kind, span }
}

impl Parser<'_> {
    pub(super) fn expr(&mut self) -> Expr {
        if !self.enter() {
            self.skip_too_deep();
            return self.error_expr();
        }
        let e = self.binary(1);
        self.leave();
        e
    }

    /// A placeholder where an expression could not be parsed: an empty span
    /// at the offending token, so it does not swallow that token's text.
    pub(super) fn error_expr(&self) -> Expr {
        let at = self.cur().start;
        mk(ExprKind::Error, Span::new(self.file, at, at))
    }

    pub(super) fn can_start_expr(&self) -> bool {
        match self.peek() {
            Tok::Ident(_)
            | Tok::Lit(_)
            | Tok::BadLit
            | Tok::Addr
            | Tok::LParen
            | Tok::Minus
            | Tok::Plus
            | Tok::Kw(Kw::Not | Kw::True | Kw::False) => true,
            Tok::Kw(k) => k.is_contextual() || self.at_operator_function(),
            _ => false,
        }
    }

    /// `AND(a, b)`, `MOD(x, 3)`, `NOT(IN := x)`: the standard functions
    /// named like operators (OpenPLC writes FBD blocks this way), called
    /// where an operand is expected.
    fn at_operator_function(&self) -> bool {
        match self.peek() {
            Tok::Kw(Kw::And | Kw::Or | Kw::Xor | Kw::Mod) => self.nth(1) == Tok::LParen,
            // `NOT(x)` is the operator on a parenthesis; only a formal
            // argument makes it a call.
            Tok::Kw(Kw::Not) => {
                self.nth(1) == Tok::LParen
                    && is_identish(self.nth(2))
                    && self.nth(3) == Tok::ColonEq
            }
            _ => false,
        }
    }

    // Every rule below is on the recursion path of nested expressions
    // (`((((x))))`): each keeps its common path tiny and moves the rest into
    // `#[inline(never)]` helpers, so one nesting level costs little stack.

    /// Precedence climbing: operators binding at least as tight as `min`.
    fn binary(&mut self, min: u8) -> Expr {
        let lhs = self.unary();
        match binop(self.peek()) {
            Some((_, prec)) if prec >= min => self.binary_tail(lhs, min),
            _ => lhs,
        }
    }

    #[inline(never)]
    fn binary_tail(&mut self, mut lhs: Expr, min: u8) -> Expr {
        let mut links: u32 = 0;
        while let Some((op, prec)) = binop(self.peek()) {
            if prec < min {
                break;
            }
            // The first link hangs off an operand whose own level was
            // counted already; every further one deepens the tree.
            if links > 0 && !self.enter_link() {
                self.skip_too_deep();
                break;
            }
            links += 1;
            self.bump();
            let rhs = self.binary(prec + 1);
            let span = lhs.span.to(rhs.span);
            lhs = mk(
                ExprKind::Binary {
                    op,
                    lhs: Box::new(lhs),
                    rhs: Box::new(rhs),
                },
                span,
            );
        }
        self.leave_links(links.saturating_sub(1));
        lhs
    }

    /// Unary operators, then `**`.
    fn unary(&mut self) -> Expr {
        if unop(self.peek()).is_some() && !self.at_operator_function() {
            return self.prefixed();
        }
        let lhs = self.postfix();
        if self.at(Tok::StarStar) {
            return self.power_tail(lhs);
        }
        lhs
    }

    /// `-x`, `+x`, `NOT x`, at the operator.
    #[inline(never)]
    fn prefixed(&mut self) -> Expr {
        let t = self.bump();
        let op = unop(t.tok).unwrap_or(UnaryOp::Plus);
        if !self.enter() {
            self.skip_too_deep();
            return self.error_expr();
        }
        let operand = self.unary();
        self.leave();
        let span = Span::new(self.file, t.start, operand.span.end.max(t.start));
        mk(
            ExprKind::Unary {
                op,
                operand: Box::new(operand),
            },
            span,
        )
    }

    /// `lhs ** rhs ** ...`; a right operand may carry a unary operator.
    #[inline(never)]
    fn power_tail(&mut self, mut lhs: Expr) -> Expr {
        let mut links: u32 = 0;
        while self.at(Tok::StarStar) {
            // The first link hangs off an operand whose own level was
            // counted already; every further one deepens the tree.
            if links > 0 && !self.enter_link() {
                self.skip_too_deep();
                break;
            }
            links += 1;
            self.bump();
            let rhs = if unop(self.peek()).is_some() {
                self.prefixed()
            } else {
                self.postfix()
            };
            let span = lhs.span.to(rhs.span);
            lhs = mk(
                ExprKind::Binary {
                    op: BinaryOp::Pow,
                    lhs: Box::new(lhs),
                    rhs: Box::new(rhs),
                },
                span,
            );
        }
        self.leave_links(links.saturating_sub(1));
        lhs
    }

    pub(super) fn postfix(&mut self) -> Expr {
        let e = self.primary();
        match self.peek() {
            Tok::Dot | Tok::LBracket | Tok::LParen | Tok::Caret => self.postfix_tail(e),
            _ => e,
        }
    }

    #[inline(never)]
    fn postfix_tail(&mut self, mut e: Expr) -> Expr {
        let mut links: u32 = 0;
        loop {
            if !matches!(
                self.peek(),
                Tok::Dot | Tok::LBracket | Tok::LParen | Tok::Caret
            ) {
                break;
            }
            // The first link hangs off an operand whose own level was
            // counted already; every further one deepens the tree.
            if links > 0 && !self.enter_link() {
                self.skip_too_deep();
                break;
            }
            links += 1;
            e = match self.peek() {
                Tok::Dot => self.after_dot(e),
                Tok::LBracket => self.index(e),
                Tok::LParen => self.call(e),
                _ => {
                    self.bump();
                    let span = self.span_from(e.span.start);
                    mk(ExprKind::Deref(Box::new(e)), span)
                }
            };
        }
        self.leave_links(links.saturating_sub(1));
        e
    }

    /// `base[i, j]`, at `[`.
    #[inline(never)]
    fn index(&mut self, base: Expr) -> Expr {
        self.bump();
        let mut indices = vec![self.expr()];
        while self.eat(Tok::Comma) {
            indices.push(self.expr());
        }
        self.expect(Tok::RBracket, "to close the index");
        let span = self.span_from(base.span.start);
        mk(
            ExprKind::Index {
                base: Box::new(base),
                indices,
            },
            span,
        )
    }

    /// `callee(args)`, at `(`.
    #[inline(never)]
    fn call(&mut self, callee: Expr) -> Expr {
        self.bump();
        let args = self.call_args();
        let span = self.span_from(callee.span.start);
        mk(
            ExprKind::Call {
                callee: Box::new(callee),
                args,
            },
            span,
        )
    }

    /// After `base.`: a member name, a bit number (`w.3`) or a partial
    /// access (`w.%X3`, `w.%B1`, `w.%W0`, `w.%D0`). At the dot.
    #[inline(never)]
    fn after_dot(&mut self, base: Expr) -> Expr {
        self.bump();
        let t = self.cur();
        if let Some(member) = self.ident_here() {
            let span = base.span.to(member.span);
            return mk(
                ExprKind::Member {
                    base: Box::new(base),
                    member,
                },
                span,
            );
        }
        if let Tok::Lit(i) = t.tok {
            if let Some(lit) = self.qualified_enum(&base, i) {
                self.bump();
                let span = base.span.to(self.tok_span(t));
                return mk(ExprKind::Literal(Box::new(lit)), span);
            }
        }
        let text = self.text(t);
        let partial = match t.tok {
            Tok::Lit(_) if text.bytes().all(|b| b.is_ascii_digit()) => match text.parse::<u32>() {
                Ok(n) => Ok((crate::ast::AddrSize::None, n)),
                Err(_) => Err(format!("bit number `{text}` is too large")),
            },
            Tok::Addr => decode_partial(text),
            _ => {
                self.expected("a member name or a bit number after `.`");
                return base;
            }
        };
        self.bump();
        let index_span = self.tok_span(t);
        match partial {
            Ok((size, index)) => {
                let span = base.span.to(index_span);
                mk(
                    ExprKind::Partial {
                        base: Box::new(base),
                        size,
                        index,
                        index_span,
                    },
                    span,
                )
            }
            Err(msg) => {
                self.report(Diagnostic::error(Code::E007, index_span, msg));
                base
            }
        }
    }

    /// Arguments after `(` up to and including `)`.
    pub(super) fn call_args(&mut self) -> Vec<Arg> {
        let mut args = Vec::new();
        if self.eat(Tok::RParen) {
            return args;
        }
        loop {
            args.push(self.arg());
            if !self.eat(Tok::Comma) {
                break;
            }
        }
        self.expect(Tok::RParen, "to close the argument list");
        args
    }

    fn arg(&mut self) -> Arg {
        let start = self.cur().start;
        let negated = self.at_kw(Kw::Not) && is_identish(self.nth(1)) && self.nth(2) == Tok::Arrow;
        if negated {
            self.bump();
        }
        if is_identish(self.peek()) && matches!(self.nth(1), Tok::ColonEq | Tok::Arrow) {
            let name = self.ident_here();
            let dir = match self.bump().tok {
                Tok::ColonEq => ArgDir::In,
                _ if negated => ArgDir::OutNot,
                _ => ArgDir::Out,
            };
            // An output may be left unbound: `fb(Q => )`.
            let value = if dir != ArgDir::In && matches!(self.peek(), Tok::Comma | Tok::RParen) {
                None
            } else {
                Some(self.expr())
            };
            return Arg {
                name,
                dir,
                value,
                span: self.span_from(start),
            };
        }
        let value = self.expr();
        Arg {
            name: None,
            dir: ArgDir::In,
            span: value.span,
            value: Some(value),
        }
    }

    pub(super) fn primary(&mut self) -> Expr {
        if self.at(Tok::LParen) {
            self.paren()
        } else if self.at_heap_new() {
            self.heap_new()
        } else {
            self.leaf()
        }
    }

    /// `(e)`, at `(`.
    #[inline(never)]
    fn paren(&mut self) -> Expr {
        let start = self.bump().start;
        let inner = self.expr();
        self.expect(Tok::RParen, "to close the parenthesis");
        let span = self.span_from(start);
        mk(ExprKind::Paren(Box::new(inner)), span)
    }

    /// A primary expression that contains no expression: literal, name, address.
    #[inline(never)]
    fn leaf(&mut self) -> Expr {
        let t = self.cur();
        let span = self.tok_span(t);
        let kind = match t.tok {
            Tok::Lit(i) => {
                self.bump();
                match self.take_literal(i) {
                    Some(lit) => ExprKind::Literal(Box::new(lit)),
                    None => ExprKind::Error,
                }
            }
            Tok::BadLit => {
                self.bump();
                ExprKind::Error
            }
            Tok::Kw(k @ (Kw::True | Kw::False)) => {
                self.bump();
                ExprKind::Literal(Box::new(Literal {
                    kind: LitKind::Bool(k == Kw::True),
                    ty: None,
                }))
            }
            Tok::Addr => {
                self.bump();
                match decode_address(self.text(t), span) {
                    Ok(addr) => ExprKind::Address(Box::new(addr)),
                    Err(msg) => {
                        self.report(Diagnostic::error(Code::E007, span, msg));
                        ExprKind::Error
                    }
                }
            }
            Tok::Kw(_) if self.at_operator_function() => {
                self.bump();
                ExprKind::Name(Ident {
                    sym: self.interner.intern(self.text(t)),
                    span,
                })
            }
            _ => match self.ident_here() {
                Some(id) => ExprKind::Name(id),
                None => {
                    if self.at_doubled_equals() {
                        self.error_here(
                            "`==` is not an ST operator: equality is a single `=` (`IF a = b THEN`), assignment is `:=`"
                                .to_string(),
                        );
                    } else {
                        self.expected("an expression");
                    }
                    return self.error_expr();
                }
            },
        };
        mk(kind, span)
    }

    /// Moves a decoded literal out of the lexer's table (each is used once).
    fn take_literal(&mut self, i: u32) -> Option<Literal> {
        let slot = self.lits.get_mut(i as usize)?;
        Some(std::mem::replace(
            slot,
            Literal {
                kind: LitKind::Bool(false),
                ty: None,
            },
        ))
    }

    /// Whether the current token is an untyped integer literal.
    pub(super) fn at_plain_int(&self) -> bool {
        match self.peek() {
            Tok::Lit(i) => matches!(
                self.lits.get(i as usize),
                Some(Literal {
                    kind: LitKind::Int(_),
                    ty: None
                })
            ),
            _ => false,
        }
    }
}
