//! One STL program or module: words → sentences with their ST code.
//!
//! Conditions and LOAD sequences are evaluated left to right (FST has no
//! operator precedence; parentheses group), each part typed bit or word;
//! instructions become ST statements over the operand globals, except the
//! ones that need the whole project (JMP TO, SET/RESET Pn, CMP n), kept as
//! [`Instr`] variants for the emitter.

use super::lex::Tok;
use super::operand::{self, Kind, Operand};
use automat_base::{Code, Diagnostic, FileId, Span};
use std::collections::{BTreeMap, BTreeSet};

/// An instruction of a THEN / OTHRW part or an executive program.
#[derive(Clone, Debug)]
pub enum Instr {
    /// ST statements.
    Code(String),
    /// JMP TO step (label as written, upper case) at a span.
    Jmp(String, Span),
    /// SET (true) / RESET (false) Pn.
    Program(u32, bool),
    /// CMP n WITH p...: the module number and the parameters' ST values.
    Call(u32, Vec<String>, Span),
}

#[derive(Clone, Debug)]
pub struct Sentence {
    /// `None`: an incomplete sentence (`THEN ...` only), always runs.
    pub cond: Option<String>,
    pub then: Vec<Instr>,
    pub othrw: Option<Vec<Instr>>,
}

#[derive(Clone, Debug)]
pub struct Step {
    /// The label as written (`init`, `20`).
    pub label: String,
    pub sentences: Vec<Sentence>,
}

#[derive(Clone, Debug)]
pub enum Body {
    Steps(Vec<Step>),
    Parallel(Vec<Sentence>),
    Executive(Vec<Instr>),
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Ty {
    Bit,
    Word,
}

const KEYWORDS: &[&str] = &[
    "STEP", "IF", "THEN", "OTHRW", "AND", "OR", "EXOR", "N", "NOP", "LOAD", "TO", "SET", "RESET",
    "JMP", "INC", "DEC", "SHL", "SHR", "ROL", "ROR", "INV", "CPL", "SWAP", "BID", "DEB", "SHIFT",
    "CMP", "CFM", "WITH", "PSE",
];

pub fn is_keyword(up: &str) -> bool {
    KEYWORDS.contains(&up)
}

/// Accumulator operations: the ST function applied to a word.
fn acc_op(up: &str) -> Option<&'static str> {
    Some(match up {
        "SHL" => "__FST_SHL",
        "SHR" => "__FST_SHR",
        "ROL" => "__FST_ROL",
        "ROR" => "__FST_ROR",
        "INV" => "__FST_INV",
        "CPL" => "__FST_CPL",
        "SWAP" => "__FST_SWAP",
        "BID" => "__FST_BID",
        "DEB" => "__FST_DEB",
        _ => return None,
    })
}

pub struct Parser<'a> {
    toks: &'a [Tok],
    i: usize,
    file: FileId,
    symbols: &'a BTreeMap<String, Operand>,
    pub used: BTreeSet<Operand>,
    pub diags: Vec<Diagnostic>,
}

impl<'a> Parser<'a> {
    pub fn new(
        toks: &'a [Tok],
        file: FileId,
        symbols: &'a BTreeMap<String, Operand>,
    ) -> Parser<'a> {
        Parser {
            toks,
            i: 0,
            file,
            symbols,
            used: BTreeSet::new(),
            diags: Vec::new(),
        }
    }

    fn peek(&self) -> Option<&'a Tok> {
        self.toks.get(self.i)
    }

    fn at(&self, kw: &str) -> bool {
        self.peek().is_some_and(|t| t.up == kw)
    }

    fn span(&self, t: &Tok) -> Span {
        Span::new(self.file, t.start, t.end)
    }

    /// The span of the current word, or of the end of the text.
    fn here(&self) -> Span {
        match self.peek().or(self.toks.last()) {
            Some(t) => self.span(t),
            None => Span::new(self.file, 0, 0),
        }
    }

    fn error(&mut self, code: Code, span: Span, msg: impl Into<String>) {
        self.diags.push(Diagnostic::error(code, span, msg));
    }

    /// The whole program.
    pub fn program(&mut self) -> Body {
        if self.at("STEP") {
            let mut steps: Vec<Step> = Vec::new();
            let mut seen: Vec<String> = Vec::new();
            while let Some(t) = self.peek() {
                if t.up != "STEP" {
                    self.error(
                        Code::E186,
                        self.span(t),
                        format!("`{}`: a step begins with STEP", t.text),
                    );
                    self.i += 1;
                    continue;
                }
                self.i += 1;
                let Some(label) = self.peek().filter(|l| !is_keyword(&l.up)) else {
                    self.error(Code::E186, self.here(), "STEP needs a name or number");
                    continue;
                };
                self.i += 1;
                if !label
                    .text
                    .bytes()
                    .all(|b| b.is_ascii_alphanumeric() || b == b'_')
                {
                    self.error(
                        Code::E186,
                        self.span(label),
                        format!(
                            "step `{}`: a step is named by letters, digits and `_`",
                            label.text
                        ),
                    );
                }
                if seen.contains(&label.up) {
                    self.error(
                        Code::E186,
                        self.span(label),
                        format!("step `{}` is defined twice", label.text),
                    );
                }
                seen.push(label.up.clone());
                let sentences = self.sentences();
                steps.push(Step {
                    label: label.text.clone(),
                    sentences,
                });
            }
            Body::Steps(steps)
        } else if self.at("IF") || self.at("THEN") {
            let s = self.sentences();
            if let Some(t) = self.peek() {
                self.error(
                    Code::E186,
                    self.span(t),
                    "STEP in a parallel program (it has no steps)",
                );
                self.i = self.toks.len();
            }
            Body::Parallel(s)
        } else {
            let list = self.instrs();
            while let Some(t) = self.peek() {
                let why = match t.up.as_str() {
                    "IF" => "IF in an executive program: it is a plain list of instructions",
                    "THEN" | "OTHRW" => {
                        "THEN / OTHRW in an executive program: it is a plain list of instructions"
                    }
                    _ => "STEP in an executive program: it is a plain list of instructions",
                };
                let code = if t.up == "IF" { Code::E185 } else { Code::E186 };
                self.error(code, self.span(t), why);
                self.i += 1;
                // The rest of an IF sentence is not reported again.
                if code == Code::E185 {
                    while self
                        .peek()
                        .is_some_and(|t| !matches!(t.up.as_str(), "THEN" | "STEP"))
                    {
                        self.i += 1;
                    }
                    if self.at("THEN") {
                        self.i += 1;
                    }
                }
                let _ = self.instrs();
            }
            Body::Executive(list)
        }
    }

    /// Sentences up to the next STEP or the end.
    fn sentences(&mut self) -> Vec<Sentence> {
        let mut out: Vec<Sentence> = Vec::new();
        while let Some(t) = self.peek() {
            match t.up.as_str() {
                "STEP" => break,
                "IF" => {
                    self.i += 1;
                    let cond = self.expr(false).map(|(c, ty)| {
                        if ty != Ty::Bit {
                            self.error(
                                Code::E189,
                                self.span(t),
                                "the condition is a word: compare it (`(CW1 = V5)`)",
                            );
                        }
                        c
                    });
                    if cond.is_none() {
                        // The condition's error is reported: go on at its THEN.
                        while self
                            .peek()
                            .is_some_and(|t| !matches!(t.up.as_str(), "THEN" | "IF" | "STEP"))
                        {
                            self.i += 1;
                        }
                    }
                    if !self.at("THEN") {
                        self.error(Code::E186, self.here(), "THEN expected after the condition");
                        self.skip_to_sentence();
                        continue;
                    }
                    self.i += 1;
                    let then = self.instrs();
                    let othrw = self.othrw();
                    out.push(Sentence {
                        cond: Some(cond.unwrap_or_else(|| "FALSE".into())),
                        then,
                        othrw,
                    });
                }
                "THEN" => {
                    if !out.is_empty() {
                        self.error(Code::E186, self.span(t), "only the first sentence of a step or program may be incomplete (THEN without IF)");
                    }
                    self.i += 1;
                    let then = self.instrs();
                    let othrw = self.othrw();
                    out.push(Sentence {
                        cond: None,
                        then,
                        othrw,
                    });
                }
                _ => {
                    self.error(
                        Code::E186,
                        self.span(t),
                        format!("`{}`: a sentence begins with IF (or THEN)", t.text),
                    );
                    self.i += 1;
                    self.skip_to_sentence();
                }
            }
        }
        out
    }

    fn othrw(&mut self) -> Option<Vec<Instr>> {
        if self.at("OTHRW") {
            self.i += 1;
            Some(self.instrs())
        } else {
            None
        }
    }

    fn skip_to_sentence(&mut self) {
        while let Some(t) = self.peek() {
            if matches!(t.up.as_str(), "IF" | "STEP") {
                break;
            }
            self.i += 1;
        }
    }

    /// An operand or symbol word (marked used), or why not.
    fn operand(&mut self, t: &Tok) -> Option<Operand> {
        let o = match operand::parse(&t.up) {
            Some(Ok(o)) => o,
            Some(Err(why)) => {
                self.error(Code::E183, self.span(t), why);
                return None;
            }
            None => {
                match self.symbols.get(&t.up) {
                    Some(o) => *o,
                    None => {
                        let code = if t
                            .text
                            .starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
                        {
                            Code::E182
                        } else {
                            Code::E186
                        };
                        let msg = if code == Code::E182 {
                            format!("unknown symbol `{}`: not an operand and not in the allocation list", t.text)
                        } else {
                            format!("`{}` is not an operand", t.text)
                        };
                        self.error(code, self.span(t), msg);
                        return None;
                    }
                }
            }
        };
        self.used.insert(o);
        Some(o)
    }

    /// A constant word `V100`, `V-5`, `V$0F`, `V%101`: its ST literal.
    fn constant(&mut self, t: &Tok) -> Option<Option<String>> {
        let rest = t.up.strip_prefix('V')?;
        let (radix, digits) = if let Some(h) = rest.strip_prefix('$') {
            (16, h)
        } else if let Some(b) = rest.strip_prefix('%') {
            (2, b)
        } else {
            (10, rest)
        };
        if digits.is_empty()
            || !digits
                .chars()
                .next()
                .is_some_and(|c| c.is_ascii_digit() || c == '-' || radix == 16)
        {
            return None;
        }
        let v = i64::from_str_radix(digits, radix).ok();
        match v {
            Some(v) if (-32768..=65535).contains(&v) => {
                Some(Some(format!("WORD#{}", v.rem_euclid(65536))))
            }
            _ => {
                self.error(
                    Code::E183,
                    self.span(t),
                    format!(
                        "constant out of range, {}: a word is 0 to 65535 (or -32768 to 32767)",
                        t.text
                    ),
                );
                Some(None)
            }
        }
    }

    /// A primary: `[N] operand | constant | NOP | ( expr )`.
    fn primary(&mut self, in_load: bool) -> Option<(String, Ty)> {
        let Some(t) = self.peek() else {
            self.error(Code::E186, self.here(), "an operand is missing at the end");
            return None;
        };
        self.i += 1;
        match t.up.as_str() {
            "N" => {
                let (c, ty) = self.primary(in_load)?;
                if ty != Ty::Bit {
                    self.error(
                        Code::E189,
                        self.span(t),
                        "N negates a bit; for a word use INV",
                    );
                    return None;
                }
                Some((format!("NOT {c}"), Ty::Bit))
            }
            "NOP" => Some(("TRUE".into(), Ty::Bit)),
            "(" => {
                let inner = self.expr(in_load);
                if self.at(")") {
                    self.i += 1;
                } else {
                    self.error(Code::E186, self.here(), "`)` expected");
                }
                inner.map(|(c, ty)| (format!("({c})"), ty))
            }
            _ if is_keyword(&t.up) => {
                self.error(
                    Code::E186,
                    self.span(t),
                    format!("an operand expected, found `{}`", t.text),
                );
                None
            }
            _ => {
                if let Some(c) = self.constant(t) {
                    return c.map(|c| (c, Ty::Word));
                }
                let o = self.operand(t)?;
                Some((o.st(), if o.is_bit() { Ty::Bit } else { Ty::Word }))
            }
        }
    }

    /// A left-to-right sequence of operations.
    fn expr(&mut self, in_load: bool) -> Option<(String, Ty)> {
        let (mut code, mut ty) = self.primary(in_load)?;
        while let Some(t) = self.peek() {
            let up = t.up.as_str();
            if in_load {
                if let Some(f) = acc_op(up) {
                    self.i += 1;
                    if ty != Ty::Word {
                        self.error(
                            Code::E189,
                            self.span(t),
                            format!("{up} works on the word accumulator"),
                        );
                        return None;
                    }
                    code = format!("{f}({code})");
                    continue;
                }
            }
            let logic = match up {
                "AND" => Some("AND"),
                "OR" => Some("OR"),
                "EXOR" => Some("XOR"),
                _ => None,
            };
            let arith = match up {
                "+" => Some("__FST_ADD"),
                "-" => Some("__FST_SUB"),
                "*" => Some("__FST_MUL"),
                "/" => Some("__FST_DIV"),
                _ => None,
            };
            let cmp = matches!(up, "=" | "<>" | "<" | ">" | "<=" | ">=");
            if logic.is_none() && arith.is_none() && !cmp {
                break;
            }
            self.i += 1;
            let (rhs, rty) = self.primary(in_load)?;
            if rty != ty {
                self.error(
                    Code::E189,
                    self.span(t),
                    format!("`{}` between a bit and a word", t.text),
                );
                return None;
            }
            if let Some(op) = logic {
                code = format!("({code} {op} {rhs})");
            } else if let Some(f) = arith {
                if ty != Ty::Word {
                    self.error(
                        Code::E189,
                        self.span(t),
                        format!("`{}` works on words", t.text),
                    );
                    return None;
                }
                code = format!("{f}({code}, {rhs})");
            } else {
                code = format!("({code} {up} {rhs})");
                ty = Ty::Bit;
            }
        }
        Some((code, ty))
    }

    /// A destination: writable, of the type wanted.
    fn dest(&mut self, what: &str, ty: Option<Ty>) -> Option<Operand> {
        let Some(t) = self.peek() else {
            self.error(Code::E186, self.here(), format!("{what} needs an operand"));
            return None;
        };
        if is_keyword(&t.up) {
            self.error(
                Code::E186,
                self.span(t),
                format!("{what} needs an operand, found `{}`", t.text),
            );
            return None;
        }
        self.i += 1;
        let o = self.operand(t)?;
        if o.is_input() {
            let shown = if t.up == o.name() {
                o.name()
            } else {
                format!("{} ({})", t.text, o.name())
            };
            self.error(
                Code::E180,
                self.span(t),
                format!("invalid operand, {shown}: an input cannot be written"),
            );
            return None;
        }
        let oty = if o.is_bit() { Ty::Bit } else { Ty::Word };
        if ty.is_some_and(|w| w != oty) {
            let want = if oty == Ty::Bit { "a word" } else { "a bit" };
            self.error(
                Code::E180,
                self.span(t),
                format!("invalid operand, {}: {what} needs {want} operand", t.text),
            );
            return None;
        }
        Some(o)
    }

    /// The counter's done rule after a write to CWn.
    fn store(o: Operand, value: &str) -> String {
        let mut s = format!("{} := {value};", o.st());
        if o.kind == Kind::Cw {
            s.push_str(&format!(
                " IF CW{0} = CP{0} THEN C{0} := FALSE; END_IF;",
                o.n
            ));
        }
        s
    }

    /// Instructions up to IF, THEN, OTHRW, STEP or the end.
    fn instrs(&mut self) -> Vec<Instr> {
        let mut out = Vec::new();
        while let Some(t) = self.peek() {
            let up = t.up.as_str();
            if matches!(up, "IF" | "THEN" | "OTHRW" | "STEP") {
                break;
            }
            self.i += 1;
            let sp = self.span(t);
            match up {
                "SET" | "RESET" => {
                    let on = up == "SET";
                    let Some(o) = self.dest(up, Some(Ty::Bit)) else {
                        continue;
                    };
                    let n = o.n;
                    out.push(match o.kind {
                        Kind::P => Instr::Program(n, on),
                        Kind::T if on => Instr::Code(format!("TW{n} := TP{n}; T{n} := TRUE;")),
                        Kind::C if on => Instr::Code(format!("CW{n} := 0; C{n} := TRUE;")),
                        _ => Instr::Code(format!(
                            "{} := {};",
                            o.st(),
                            if on { "TRUE" } else { "FALSE" }
                        )),
                    });
                }
                "LOAD" => {
                    let Some((code, ty)) = self.expr(true) else {
                        self.skip_instr();
                        continue;
                    };
                    let acc = if ty == Ty::Bit { "SBA" } else { "MBA" };
                    let mut s = format!("{acc} := {code};");
                    if !self.at("TO") {
                        self.error(
                            Code::E186,
                            self.here(),
                            "LOAD ... needs TO and a destination",
                        );
                    }
                    while self.at("TO") {
                        self.i += 1;
                        if let Some(o) = self.dest("TO", Some(ty)) {
                            s.push(' ');
                            s.push_str(&Self::store(o, acc));
                        }
                    }
                    out.push(Instr::Code(s));
                }
                "INC" | "DEC" => {
                    let f = if up == "INC" {
                        "__FST_ADD"
                    } else {
                        "__FST_SUB"
                    };
                    let operand_next = self.peek().is_some_and(|n| !is_keyword(&n.up));
                    if operand_next {
                        if let Some(o) = self.dest(up, Some(Ty::Word)) {
                            out.push(Instr::Code(Self::store(
                                o,
                                &format!("{f}({}, WORD#1)", o.st()),
                            )));
                        }
                    } else {
                        out.push(Instr::Code(format!("MBA := {f}(MBA, WORD#1);")));
                    }
                }
                "SHIFT" => {
                    if let Some(o) = self.dest(up, Some(Ty::Bit)) {
                        out.push(Instr::Code(format!(
                            "__fst_bit := {0}; {0} := SBA; SBA := __fst_bit;",
                            o.st()
                        )));
                    }
                }
                "NOP" => {}
                "JMP" => {
                    if self.at("TO") {
                        self.i += 1;
                    } else {
                        self.error(Code::E186, self.here(), "JMP needs TO");
                    }
                    match self.peek() {
                        Some(l) if !is_keyword(&l.up) => {
                            self.i += 1;
                            out.push(Instr::Jmp(l.up.clone(), self.span(l)));
                        }
                        _ => self.error(Code::E186, self.here(), "JMP TO needs a step"),
                    }
                }
                "PSE" => self.error(
                    Code::E187,
                    sp,
                    "PSE (program section end) is not usable on the FEC",
                ),
                "CMP" | "CFM" => {
                    let num = self
                        .peek()
                        .and_then(|n| n.up.parse::<u32>().ok().map(|v| (v, n)));
                    let Some((n, nt)) = num else {
                        self.error(
                            Code::E186,
                            self.here(),
                            format!("{up} needs a module number"),
                        );
                        continue;
                    };
                    self.i += 1;
                    let mut params = Vec::new();
                    while self.at("WITH") {
                        self.i += 1;
                        if let Some((c, ty)) = self.primary(false) {
                            if ty != Ty::Word {
                                self.error(Code::E189, self.here(), "a module parameter is a word");
                            }
                            params.push(c);
                        }
                    }
                    if up == "CFM" {
                        self.error(Code::E188, self.span(nt), format!("CFM {n}: no manufacturer function module is available (only CMP modules B0-B99)"));
                    } else if n > 99 {
                        self.error(
                            Code::E183,
                            self.span(nt),
                            format!("module out of range, CMP {n}: modules are 0 to 99"),
                        );
                    } else if params.len() > 7 {
                        self.error(
                            Code::E188,
                            sp,
                            "a module takes at most 7 parameters (FU32-FU38)",
                        );
                    } else {
                        out.push(Instr::Call(
                            n,
                            params,
                            Span::new(self.file, t.start, nt.end),
                        ));
                    }
                }
                "WITH" => self.error(Code::E186, sp, "WITH passes a parameter to CMP or CFM"),
                _ if acc_op(up).is_some() => {
                    out.push(Instr::Code(format!(
                        "MBA := {}(MBA);",
                        acc_op(up).unwrap_or_default()
                    )));
                }
                _ if is_keyword(up) => self.error(
                    Code::E186,
                    sp,
                    format!("`{}` is not an instruction", t.text),
                ),
                _ => {
                    self.i -= 1;
                    let before = self.diags.len();
                    let o = self.peek().and_then(|t| {
                        self.i += 1;
                        self.operand(t)
                    });
                    if self.diags.len() == before {
                        match o {
                            Some(o) if o.is_bit() => self.error(
                                Code::E181,
                                sp,
                                format!("SET or RESET is missing before `{}`", t.text),
                            ),
                            _ => self.error(
                                Code::E186,
                                sp,
                                format!(
                                    "`{}`: an instruction expected (LOAD ... TO for a word)",
                                    t.text
                                ),
                            ),
                        }
                    }
                }
            }
        }
        out
    }

    fn skip_instr(&mut self) {
        while let Some(t) = self.peek() {
            if matches!(
                t.up.as_str(),
                "IF" | "THEN" | "OTHRW" | "STEP" | "SET" | "RESET" | "LOAD" | "JMP"
            ) {
                break;
            }
            self.i += 1;
        }
    }
}
