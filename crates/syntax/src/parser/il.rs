//! Instruction List: one instruction per line, `[label:] operator [operand]`.
//!
//! The lexer drops line breaks, so the end of an instruction is found from
//! the text between two tokens (`il_line_break`, which looks through
//! comments). An IL body is recognised by its first line (`at_il_start`);
//! `il_list` parses instructions up to a closing keyword and is also the
//! entry SFC uses for IL transition conditions and action bodies.
//!
//! Errors: E102 (operand missing), E103 (operand not taken, or more text on
//! the line: the rest of the line is skipped), E104 (not an operator),
//! E108 (a label inside parentheses), E109 (unbalanced parentheses), E110
//! (an operand the operator cannot use).

use super::expr::is_identish;
use super::Parser;
use crate::ast::il::{IlBody, Instr, InstrKind, Op, When};
use crate::ast::{Expr, ExprKind, Ident, UnaryOp};
use crate::lexer::{Kw, Tok};
use automat_base::{Code, Diagnostic, Span};

/// The FB input operators (IEC 61131-3 table of IL operators): `PT t1`
/// calls `t1(PT := current result)`.
const FB_INPUTS: &[&str] = &["S1", "R1", "CLK", "CU", "CD", "PV", "IN", "PT"];

/// What the word at the start of an instruction is.
enum Word {
    Op(Op),
    Jump(When),
    Cal(When),
    Ret(When),
    FbInput,
    /// Any other name: a function call.
    Func,
    /// An operator with a modifier it does not take (`STC`, `JMPN`).
    BadModifier,
}

fn classify(word: &str) -> Word {
    if let Some(op) = Op::from_word(word) {
        return Word::Op(op);
    }
    match word {
        "JMP" => return Word::Jump(When::Always),
        "JMPC" => return Word::Jump(When::IfTrue),
        "JMPCN" => return Word::Jump(When::IfFalse),
        "CAL" => return Word::Cal(When::Always),
        "CALC" => return Word::Cal(When::IfTrue),
        "CALCN" => return Word::Cal(When::IfFalse),
        "RET" => return Word::Ret(When::Always),
        "RETC" => return Word::Ret(When::IfTrue),
        "RETCN" => return Word::Ret(When::IfFalse),
        _ => {}
    }
    if FB_INPUTS.contains(&word) {
        return Word::FbInput;
    }
    // Modifiers on operators that do not take them. (`S` and `R` are left
    // out: `SC`, `RN` are plausible function names.)
    const BASES: &[&str] = &[
        "LD", "ST", "AND", "OR", "XOR", "NOT", "ADD", "SUB", "MUL", "DIV", "MOD", "GT", "GE", "EQ",
        "NE", "LE", "LT", "JMP", "CAL", "RET",
    ];
    for b in BASES {
        if let Some(rest) = word.strip_prefix(b) {
            if matches!(rest, "N" | "C" | "CN" | "NC") {
                return Word::BadModifier;
            }
        }
    }
    Word::Func
}

/// Whether `word` (upper case) is an IL operator: a body starting with one
/// is IL.
fn is_il_operator(word: &str) -> bool {
    !matches!(classify(word), Word::Func | Word::BadModifier)
}

impl Parser<'_> {
    /// Whether the tokens ahead begin an IL instruction list: an IL
    /// operator (after an optional `label:`) followed by an operand on the
    /// same line, or by the end of the line. Never an ST assignment or call
    /// (`LD := 1;`, `S(x)`), which continue differently.
    pub(crate) fn at_il_start(&self) -> bool {
        let mut i = 0;
        if is_identish(self.nth(0)) && self.nth(1) == Tok::Colon {
            i = 2;
        }
        let Some(t) = self.toks.get(self.pos + i).copied() else {
            return false;
        };
        let word = match t.tok {
            Tok::Ident(_) | Tok::Kw(Kw::And | Kw::Or | Kw::Xor | Kw::Not | Kw::Mod) => {
                self.text(t).to_ascii_uppercase()
            }
            Tok::Kw(k) if k.is_contextual() => self.text(t).to_ascii_uppercase(),
            _ => return false,
        };
        if !is_il_operator(&word) {
            return false;
        }
        let Some(next) = self.toks.get(self.pos + i + 1).copied() else {
            return true;
        };
        if self.gap_has_line_break(t.end, next.start) {
            return true;
        }
        // `r REF= x;` binds a CODESYS reference named like `R` or `S`.
        if self.word_at(i + 1, "REF") && self.nth(i + 2) == Tok::Eq {
            return false;
        }
        matches!(
            next.tok,
            Tok::Ident(_)
                | Tok::Lit(_)
                | Tok::BadLit
                | Tok::Addr
                | Tok::Minus
                | Tok::Kw(Kw::True | Kw::False)
                | Tok::Eof
        ) || matches!(next.tok, Tok::Kw(k) if k.is_contextual() || k.is_decl_end())
    }

    /// Parses IL instructions up to (not including) one of `ends`, the end
    /// of a POU, a VAR block or the end of the file.
    pub(crate) fn il_list(&mut self, ends: &[Kw]) -> IlBody {
        let (instrs, _) = self.il_instrs(ends, None);
        IlBody { instrs }
    }

    fn at_il_end(&self, ends: &[Kw]) -> bool {
        match self.peek() {
            Tok::Eof => true,
            Tok::Kw(k) => {
                ends.contains(&k)
                    || k.is_decl_end()
                    || k.is_item_start()
                    || k.is_var_block()
                    || k.is_stmt_closer()
            }
            _ => false,
        }
    }

    /// Instructions up to an end (top level, `group` = `None`) or up to the
    /// `)` closing a group opened at `group`. The flag: whether the `)` came.
    fn il_instrs(&mut self, ends: &[Kw], group: Option<Span>) -> (Vec<Instr>, bool) {
        let mut out = Vec::new();
        loop {
            if self.at_il_end(ends) {
                if let Some(open) = group {
                    self.report(Diagnostic::error(
                        Code::E109,
                        open,
                        "this parenthesis is never closed: a `)` on its own line must end the group",
                    ));
                }
                return (out, false);
            }
            if self.at(Tok::RParen) {
                if group.is_some() {
                    self.bump();
                    return (out, true);
                }
                let sp = self.cur_span();
                self.report(Diagnostic::error(
                    Code::E109,
                    sp,
                    "this `)` closes no parenthesised group",
                ));
                self.bump();
                self.il_skip_line();
                continue;
            }
            let before = self.pos;
            let instr = self.il_instr(ends, group.is_some());
            out.push(instr);
            if self.pos == before {
                self.bump();
            }
        }
    }

    /// One line: `[label:] [operator [operand]]`.
    fn il_instr(&mut self, ends: &[Kw], nested: bool) -> Instr {
        let start = self.cur().start;
        let mut label = None;
        if is_identish(self.peek()) && self.nth(1) == Tok::Colon {
            label = self.ident_here();
            self.bump();
            if nested {
                if let Some(l) = label {
                    self.report(Diagnostic::error(
                        Code::E108,
                        l.span,
                        "a label cannot stand inside a parenthesised group: nothing may jump into an expression",
                    ));
                }
                label = None;
            }
            if self.il_line_break() || self.at_il_end(ends) || self.at(Tok::RParen) {
                return Instr {
                    label,
                    kind: InstrKind::Nothing,
                    span: self.span_from(start),
                };
            }
        }
        let kind = self.il_op(ends);
        // One instruction per line (a group's `)` may close the line).
        if !(self.il_line_break() || self.at_il_end(ends) || (nested && self.at(Tok::RParen))) {
            let msg = format!(
                "unexpected {} after the instruction: IL has one instruction per line",
                self.found()
            );
            let sp = self.cur_span();
            self.report(Diagnostic::error(Code::E103, sp, msg));
            self.il_skip_line();
        }
        Instr {
            label,
            kind,
            span: self.span_from(start),
        }
    }

    /// The operator and its operand.
    fn il_op(&mut self, ends: &[Kw]) -> InstrKind {
        let t = self.cur();
        let op_span = self.tok_span(t);
        let word = match t.tok {
            Tok::Amp => {
                self.bump();
                // `&N` is ANDN (written without a space).
                let n = self.cur();
                let negated = n.start == t.end
                    && matches!(n.tok, Tok::Ident(_))
                    && self.text(n).eq_ignore_ascii_case("N");
                if negated {
                    self.bump();
                }
                let op = if negated { Op::Andn } else { Op::And };
                return self.il_simple(op, self.span_from(t.start), ends);
            }
            Tok::Ident(_) | Tok::Kw(Kw::And | Kw::Or | Kw::Xor | Kw::Not | Kw::Mod) => {
                self.text(t).to_ascii_uppercase()
            }
            Tok::Kw(k) if k.is_contextual() => self.text(t).to_ascii_uppercase(),
            _ => {
                let msg = format!("expected an IL operator, found {}", self.found());
                self.report(Diagnostic::error(Code::E104, op_span, msg));
                self.il_skip_line();
                return InstrKind::Error;
            }
        };
        match classify(&word) {
            Word::Op(op) => {
                self.bump();
                self.il_simple(op, op_span, ends)
            }
            Word::Jump(when) => {
                self.bump();
                match self.il_label_operand(op_span, ends) {
                    Some(label) => InstrKind::Jump {
                        when,
                        op_span,
                        label,
                    },
                    None => InstrKind::Error,
                }
            }
            Word::Ret(when) => {
                self.bump();
                InstrKind::Ret { when, op_span }
            }
            Word::Cal(when) => {
                self.bump();
                if !self.il_operand_here(ends) {
                    self.il_missing(op_span, "the function block instance to call");
                    return InstrKind::Error;
                }
                let e = self.postfix();
                let (fb, args) = match e.kind {
                    ExprKind::Call { callee, args } => (*callee, args),
                    _ => (e, Vec::new()),
                };
                if !is_place(&fb) {
                    self.il_bad_operand(fb.span, "CAL needs a function block instance");
                    return InstrKind::Error;
                }
                InstrKind::Cal {
                    when,
                    op_span,
                    fb,
                    args,
                }
            }
            Word::FbInput => {
                let input = self.ident_here().unwrap_or(Ident {
                    sym: self.interner.intern(&word),
                    span: op_span,
                });
                if !self.il_operand_here(ends) {
                    self.il_missing(op_span, "the function block instance");
                    return InstrKind::Error;
                }
                let fb = self.postfix();
                if !is_place(&fb) {
                    let msg = format!("`{word}` needs a function block instance");
                    self.il_bad_operand(fb.span, &msg);
                    return InstrKind::Error;
                }
                InstrKind::FbInput { input, fb }
            }
            Word::BadModifier => {
                let msg = format!(
                    "unknown IL operator `{word}`: this operator does not take that modifier (N negates an operand: LDN, STN, ANDN, ORN, XORN; C makes a jump, call or return conditional: JMPC, CALC, RETC, JMPCN, ...)"
                );
                self.report(Diagnostic::error(Code::E104, op_span, msg));
                self.il_skip_line();
                InstrKind::Error
            }
            Word::Func => self.il_call(),
        }
    }

    /// `op operand`, `op( [operand]` ... `)`, or `NOT`.
    fn il_simple(&mut self, op: Op, op_span: Span, ends: &[Kw]) -> InstrKind {
        if op == Op::Not {
            return InstrKind::Simple {
                op,
                op_span,
                operand: None,
            };
        }
        if op.is_binary() && self.at(Tok::LParen) && !self.il_line_break() {
            return self.il_group(op, op_span, ends);
        }
        if !self.il_operand_here(ends) {
            self.il_missing(op_span, "an operand");
            return InstrKind::Error;
        }
        let operand = self.il_operand();
        // `R ctr` on a CTU is its input R (IEC 61131-3, IL operators on
        // function block inputs), not a reset of the instance.
        if let ExprKind::Name(id) = &operand.kind {
            let (set, word) = match op {
                Op::R => (&self.il_fb_r, "R"),
                Op::S => (&self.il_fb_s, "S"),
                _ => (&Vec::new(), ""),
            };
            if set.contains(&id.sym) {
                let input = Ident {
                    sym: self.interner.intern(word),
                    span: op_span,
                };
                return InstrKind::FbInput { input, fb: operand };
            }
        }
        if matches!(op, Op::St | Op::Stn | Op::S | Op::R) && !is_place(&operand) {
            let msg = format!("`{}` needs a variable to write", op.name());
            self.il_bad_operand(operand.span, &msg);
            return InstrKind::Error;
        }
        InstrKind::Simple {
            op,
            op_span,
            operand: Some(operand),
        }
    }

    /// `op(` at `(`: the optional short-form operand, then lines up to `)`.
    fn il_group(&mut self, op: Op, op_span: Span, ends: &[Kw]) -> InstrKind {
        let open = self.bump();
        let open_span = op_span.to(self.tok_span(open));
        // `AND( LD b` with the first instruction on the opening line.
        let mut lead = None;
        let first = if self.at_inline_load() {
            lead = Some(self.il_instr(ends, true));
            None
        } else if self.il_operand_here(ends) && !self.at(Tok::RParen) {
            Some(self.il_operand())
        } else {
            None
        };
        if lead.is_none() && !(self.il_line_break() || self.at_il_end(ends) || self.at(Tok::RParen))
        {
            let msg = format!(
                "unexpected {} after `{}(`: the group's instructions start on the next line",
                self.found(),
                op.name()
            );
            let sp = self.cur_span();
            self.report(Diagnostic::error(Code::E103, sp, msg));
            self.il_skip_line();
        }
        if !self.enter() {
            self.il_skip_group();
            return InstrKind::Error;
        }
        let (mut body, _) = self.il_instrs(ends, Some(open_span));
        self.leave();
        if let Some(l) = lead {
            body.insert(0, l);
        }
        InstrKind::Group {
            op,
            op_span,
            first,
            body,
        }
    }

    /// Whether `LD x` / `LDN x` follows on this line (after `op(`).
    fn at_inline_load(&self) -> bool {
        if self.il_line_break() {
            return false;
        }
        let t = self.cur();
        let load = matches!(t.tok, Tok::Ident(_))
            && (self.text(t).eq_ignore_ascii_case("LD")
                || self.text(t).eq_ignore_ascii_case("LDN"));
        let next = self.toks.get(self.pos + 1).copied();
        load && next.is_some_and(|n| {
            !self.gap_has_line_break(t.end, n.start)
                && !matches!(
                    n.tok,
                    Tok::Comma | Tok::LParen | Tok::RParen | Tok::Dot | Tok::LBracket
                )
        })
    }

    /// A function call: `F a, b` or `F(formal := args)`, at the name.
    fn il_call(&mut self) -> InstrKind {
        let Some(name) = self.ident_here() else {
            return InstrKind::Error;
        };
        let mut args = Vec::new();
        let mut formal = false;
        if self.at(Tok::LParen) && self.cur().start == name.span.end {
            self.bump();
            args = self.call_args();
            formal = args.first().is_some_and(|a| a.name.is_some());
        } else if !self.il_line_break() && self.can_start_expr() {
            loop {
                let v = self.il_operand();
                args.push(crate::ast::Arg {
                    name: None,
                    dir: crate::ast::ArgDir::In,
                    span: v.span,
                    value: Some(v),
                });
                if !self.eat(Tok::Comma) {
                    break;
                }
            }
        }
        InstrKind::Call { name, args, formal }
    }

    /// The label name after a jump.
    fn il_label_operand(&mut self, op_span: Span, ends: &[Kw]) -> Option<Ident> {
        if !self.il_operand_here(ends) {
            self.il_missing(op_span, "the label to jump to");
            return None;
        }
        match self.ident_here() {
            Some(l) => Some(l),
            None => {
                let sp = self.cur_span();
                self.il_bad_operand(sp, "a jump needs a label name");
                self.il_skip_line();
                None
            }
        }
    }

    /// An operand: a variable (with member, index, bit accesses), a literal,
    /// or a negative literal.
    fn il_operand(&mut self) -> Expr {
        if matches!(self.peek(), Tok::Minus | Tok::Plus) {
            let t = self.bump();
            let op = if t.tok == Tok::Minus {
                UnaryOp::Neg
            } else {
                UnaryOp::Plus
            };
            let inner = self.postfix();
            let span = Span::new(self.file, t.start, inner.span.end.max(t.start));
            return Expr {
                kind: ExprKind::Unary {
                    op,
                    operand: Box::new(inner),
                },
                span,
            };
        }
        self.postfix()
    }

    /// Whether an operand follows on this line.
    fn il_operand_here(&self, ends: &[Kw]) -> bool {
        !self.il_line_break() && !self.at_il_end(ends) && self.can_start_expr()
    }

    #[cold]
    #[inline(never)]
    fn il_missing(&mut self, op_span: Span, what: &str) {
        let msg = format!(
            "missing operand: expected {what} on the same line, found {}",
            if self.il_line_break() {
                "the end of the line".to_string()
            } else {
                self.found()
            }
        );
        self.report(Diagnostic::error(Code::E102, op_span, msg));
        if !self.il_line_break() {
            self.il_skip_line();
        }
    }

    #[cold]
    #[inline(never)]
    fn il_bad_operand(&mut self, span: Span, msg: &str) {
        self.report(Diagnostic::error(Code::E110, span, msg.to_string()));
    }

    /// Skips the rest of the current line (never past a closing keyword).
    fn il_skip_line(&mut self) {
        while !self.il_line_break() && !self.at_eof() {
            match self.peek() {
                Tok::Kw(k) if k.is_decl_end() || k.is_item_start() || k.is_var_block() => return,
                _ => {
                    self.bump();
                }
            }
        }
    }

    /// Skips a group too deeply nested to parse, up to its `)` line.
    #[cold]
    #[inline(never)]
    fn il_skip_group(&mut self) {
        let mut depth = 1usize;
        loop {
            match self.peek() {
                Tok::Eof => return,
                Tok::Kw(k) if k.is_decl_end() || k.is_item_start() => return,
                Tok::LParen => depth += 1,
                Tok::RParen => {
                    depth -= 1;
                    if depth == 0 {
                        self.bump();
                        return;
                    }
                }
                _ => {}
            }
            self.bump();
        }
    }

    /// Whether a line break separates the last consumed token from the
    /// current one (comments spanning lines do not count as one, a `//`
    /// comment does: it runs to the end of its line).
    fn il_line_break(&self) -> bool {
        if self.pos == 0 {
            return true;
        }
        self.gap_has_line_break(self.prev_end, self.cur().start)
    }

    /// Whether the text `from..to` (whitespace and comments only) holds a
    /// line break outside any block comment.
    fn gap_has_line_break(&self, from: u32, to: u32) -> bool {
        let b = self.src.as_bytes();
        let end = (to as usize).min(b.len());
        let mut i = (from as usize).min(end);
        while i < end {
            match (b.get(i), b.get(i + 1)) {
                (Some(b'\n'), _) => return true,
                (Some(b'/'), Some(b'/')) => return true,
                (Some(b'('), Some(b'*')) => i = skip_block(b, i + 2, end, b"(*", b"*)", true),
                (Some(b'/'), Some(b'*')) => i = skip_block(b, i + 2, end, b"/*", b"*/", false),
                (Some(b'{'), _) => i = skip_block(b, i + 1, end, b"{", b"}", false),
                _ => i += 1,
            }
        }
        false
    }
}

/// The index after the block comment that began before `i` (nested when
/// `nests`), at most `end`.
fn skip_block(b: &[u8], mut i: usize, end: usize, open: &[u8], close: &[u8], nests: bool) -> usize {
    let mut depth = 1usize;
    while i < end {
        if b.get(i..i + close.len()) == Some(close) {
            depth -= 1;
            i += close.len();
            if depth == 0 {
                return i;
            }
        } else if nests && b.get(i..i + open.len()) == Some(open) {
            depth += 1;
            i += open.len();
        } else {
            i += 1;
        }
    }
    end
}

/// Whether an operand names something that can be written or called: a
/// variable, member, element, bit, dereference or direct address.
fn is_place(e: &Expr) -> bool {
    matches!(
        e.kind,
        ExprKind::Name(_)
            | ExprKind::Member { .. }
            | ExprKind::Index { .. }
            | ExprKind::Partial { .. }
            | ExprKind::Deref(_)
            | ExprKind::Address(_)
            | ExprKind::Error
    )
}

impl Parser<'_> {
    /// Parses and desugars an IL list up to one of `ends` (see
    /// `desugar::il::desugar` for `want_result` and `hidden`). The entry
    /// for every IL text: POU bodies, SFC actions and transitions.
    pub(crate) fn il_desugared(
        &mut self,
        ends: &[Kw],
        want_result: bool,
        hidden: &mut Vec<crate::ast::VarDecl>,
    ) -> (IlBody, crate::desugar::il::IlOut) {
        let body = self.il_list(ends);
        let mut diags = Vec::new();
        let out =
            crate::desugar::il::desugar(&body, want_result, hidden, self.interner, &mut diags);
        for d in diags {
            self.report(d);
        }
        (body, out)
    }

    /// A POU body written in IL, at its first instruction: the ST
    /// statements, the IL tree, and the hidden variables appended to
    /// `var_blocks` as a VAR_TEMP block.
    pub(crate) fn il_pou_body(
        &mut self,
        end: Kw,
        var_blocks: &mut Vec<crate::ast::VarBlock>,
    ) -> (Vec<crate::ast::Stmt>, crate::ast::Lang) {
        let mut hidden = Vec::new();
        (self.il_fb_r, self.il_fb_s) = fb_input_vars(var_blocks, self.interner);
        let (body, out) = self.il_desugared(&[end], false, &mut hidden);
        self.il_fb_r.clear();
        self.il_fb_s.clear();
        if let Some(b) = crate::desugar::il::hidden_block(hidden) {
            var_blocks.push(b);
        }
        (out.stmts, crate::ast::Lang::Il(Box::new(body)))
    }
}

/// The variables of `blocks` declared as a function block with an input `R`
/// (CTU, CTUD, SR, user blocks), and with an input `S` (RS, user blocks).
fn fb_input_vars(
    blocks: &[crate::ast::VarBlock],
    interner: &automat_base::Interner,
) -> (Vec<automat_base::Symbol>, Vec<automat_base::Symbol>) {
    let (mut r, mut s) = (Vec::new(), Vec::new());
    for d in blocks.iter().flat_map(|b| &b.decls) {
        let crate::ast::TypeSpec::Named(t) = &d.ty else {
            continue;
        };
        let ty = interner.name(t.sym).to_ascii_uppercase();
        let into = match ty.as_str() {
            "CTU" | "CTUD" | "SR" | "CTU_DINT" | "CTU_LINT" | "CTU_UDINT" | "CTU_ULINT"
            | "CTUD_DINT" | "CTUD_LINT" | "CTUD_UDINT" | "CTUD_ULINT" => &mut r,
            "RS" => &mut s,
            // The other standard blocks have neither input; `S x` on an
            // elementary variable (or an alias of one) is a set.
            t if NOT_SET_RESET_FB.contains(&t) => continue,
            _ => {
                // A user function block (assumed: any other named type,
                // since its declaration may be in another file): `S fb` /
                // `R fb` set its input S / R, and the checker reports a
                // block without that input.
                r.extend(d.names.iter().map(|n| n.sym));
                &mut s
            }
        };
        into.extend(d.names.iter().map(|n| n.sym));
    }
    (r, s)
}

/// Named types that are not function blocks with an input S or R: the
/// elementary types and the standard blocks without those inputs.
const NOT_SET_RESET_FB: &[&str] = &[
    "BOOL",
    "SINT",
    "INT",
    "DINT",
    "LINT",
    "USINT",
    "UINT",
    "UDINT",
    "ULINT",
    "REAL",
    "LREAL",
    "BYTE",
    "WORD",
    "DWORD",
    "LWORD",
    "TIME",
    "LTIME",
    "DATE",
    "LDATE",
    "TIME_OF_DAY",
    "TOD",
    "LTOD",
    "LTIME_OF_DAY",
    "DATE_AND_TIME",
    "DT",
    "LDT",
    "LDATE_AND_TIME",
    "STRING",
    "WSTRING",
    "CHAR",
    "WCHAR",
    "TON",
    "TOF",
    "TP",
    "TON_LTIME",
    "TOF_LTIME",
    "TP_LTIME",
    "R_TRIG",
    "F_TRIG",
    "CTD",
    "CTD_DINT",
    "CTD_LINT",
    "CTD_UDINT",
    "CTD_ULINT",
];
