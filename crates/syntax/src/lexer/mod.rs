//! The lexer: source bytes → a vector of [`Token`]s plus a table of decoded
//! literals. Hand-written over bytes: keywords are recognised by upper-casing
//! into a stack buffer, and the only allocations per token are the interning
//! of new identifiers and the decoded text of string literals.
//!
//! Invariant: the position only ever moves forward, over whole chars, so every
//! token boundary is a char boundary and the loop ends on any input.

mod literals;
mod token;
mod trivia;

pub use token::{Kw, Tok, Token};

use crate::ast::Literal;
use automat_base::{Code, Diagnostic, FileId, Interner, Span, Symbol};

/// What the lexer produced for one file.
pub struct Lexed {
    /// Always ends with one [`Tok::Eof`].
    pub toks: Vec<Token>,
    /// Decoded literals, indexed by [`Tok::Lit`].
    pub lits: Vec<Literal>,
    /// The `{ ... }` pragmas skipped: how many, and the first one's bytes.
    pub pragmas: u32,
    pub first_pragma: Option<(u32, u32)>,
}

/// The longest keyword or time/date prefix is 18 bytes (`END_FUNCTION_BLOCK`).
const MAX_WORD: usize = 20;

/// Splits `text` into tokens, reporting lexical errors (E001–E004, E006) into `diags`.
pub fn lex(
    file: FileId,
    text: &str,
    interner: &mut Interner,
    diags: &mut Vec<Diagnostic>,
) -> Lexed {
    lex_with(file, text, interner, diags, true)
}

/// [`lex`], choosing whether `(* *)` comments nest (IEC: they do; CODESYS:
/// the first `*)` ends the comment).
pub fn lex_with(
    file: FileId,
    text: &str,
    interner: &mut Interner,
    diags: &mut Vec<Diagnostic>,
    nest_comments: bool,
) -> Lexed {
    let mut lx = Lexer {
        nest_comments,
        pragmas: 0,
        first_pragma: None,
        text,
        b: text.as_bytes(),
        pos: 0,
        file,
        interner,
        diags,
        toks: Vec::with_capacity(text.len() / 4 + 16),
        lits: Vec::new(),
        recent: [RecentIdent::EMPTY; RECENT_SLOTS],
    };
    // A UTF-8 byte order mark is not part of the program.
    if lx.b.starts_with(&[0xEF, 0xBB, 0xBF]) {
        lx.pos = 3;
    }
    lx.run();
    Lexed {
        toks: lx.toks,
        lits: lx.lits,
        pragmas: lx.pragmas,
        first_pragma: lx.first_pragma,
    }
}

pub(crate) struct Lexer<'a> {
    /// Whether `(*` inside a `(* *)` comment opens a nested one.
    nest_comments: bool,
    /// Pragmas skipped so far, and the first one's bytes.
    pragmas: u32,
    first_pragma: Option<(u32, u32)>,
    text: &'a str,
    b: &'a [u8],
    pos: usize,
    file: FileId,
    interner: &'a mut Interner,
    diags: &'a mut Vec<Diagnostic>,
    toks: Vec<Token>,
    lits: Vec<Literal>,
    /// Identifiers seen recently, by hash: a hit skips the interner (which
    /// copies and upper-cases the name before its own lookup).
    recent: [RecentIdent; RECENT_SLOTS],
}

const RECENT_SLOTS: usize = 256;

/// An identifier at `start..start + len` of this file and its symbol.
#[derive(Clone, Copy)]
struct RecentIdent {
    start: u32,
    len: u32,
    sym: Symbol,
}

impl RecentIdent {
    const EMPTY: RecentIdent = RecentIdent {
        start: 0,
        len: 0,
        sym: Symbol(0),
    };
}

const IDENT: u8 = 1;
const SPACE: u8 = 2;

/// Character classes by byte: one table load instead of a chain of compares
/// in the innermost scanning loops.
static CLASS: [u8; 256] = {
    let mut t = [0u8; 256];
    let mut c = 0;
    while c < 256 {
        let b = c as u8;
        if b.is_ascii_alphanumeric() || b == b'_' {
            t[c] = IDENT;
        } else if matches!(b, b' ' | b'\t' | b'\r' | b'\n' | 0x0B | 0x0C) {
            t[c] = SPACE;
        }
        c += 1;
    }
    t
};

pub(crate) fn is_ident_start(c: u8) -> bool {
    c.is_ascii_alphabetic() || c == b'_'
}

#[inline]
pub(crate) fn is_ident_char(c: u8) -> bool {
    CLASS[usize::from(c)] & IDENT != 0
}

#[inline]
pub(crate) fn is_space(c: u8) -> bool {
    CLASS[usize::from(c)] & SPACE != 0
}

/// Bytes that can begin a token or trivia; anything else is an invalid character.
fn starts_something(c: u8) -> bool {
    is_ident_char(c)
        || matches!(
            c,
            b' ' | b'\t'
                | b'\r'
                | b'\n'
                | 0x0B
                | 0x0C
                | b'\''
                | b'"'
                | b'%'
                | b'{'
                | b':'
                | b'='
                | b';'
                | b','
                | b'.'
                | b'('
                | b')'
                | b'['
                | b']'
                | b'+'
                | b'-'
                | b'*'
                | b'/'
                | b'<'
                | b'>'
                | b'&'
                | b'^'
        )
}

impl Lexer<'_> {
    /// The byte at `i`, or 0 past the end (0 matches no token class).
    #[inline]
    fn at(&self, i: usize) -> u8 {
        self.b.get(i).copied().unwrap_or(0)
    }

    fn span(&self, start: usize, end: usize) -> Span {
        Span::new(self.file, start as u32, end as u32)
    }

    fn error(&mut self, code: Code, start: usize, end: usize, msg: String) {
        let span = self.span(start, end);
        self.diags.push(Diagnostic::error(code, span, msg));
    }

    fn push(&mut self, tok: Tok, start: usize) {
        self.toks.push(Token {
            tok,
            start: start as u32,
            end: self.pos as u32,
        });
    }

    fn push_lit(&mut self, lit: Literal, start: usize) {
        let idx = self.lits.len() as u32;
        self.lits.push(lit);
        self.push(Tok::Lit(idx), start);
    }

    fn run(&mut self) {
        loop {
            self.skip_trivia();
            if self.pos >= self.b.len() {
                break;
            }
            self.token();
        }
        self.pos = self.b.len();
        self.push(Tok::Eof, self.b.len());
    }

    fn token(&mut self) {
        let start = self.pos;
        let c = self.at(start);
        let next = self.at(start + 1);
        let (tok, len) = match c {
            b'a'..=b'z' | b'A'..=b'Z' | b'_' => return self.word(),
            b'0'..=b'9' => return self.number(),
            b'\'' => return self.string(false),
            b'"' => return self.string(true),
            b'%' => return self.address(),
            b':' if next == b'=' => (Tok::ColonEq, 2),
            b':' => (Tok::Colon, 1),
            b'=' if next == b'>' => (Tok::Arrow, 2),
            b'=' => (Tok::Eq, 1),
            b';' => (Tok::Semi, 1),
            b',' => (Tok::Comma, 1),
            b'.' if next == b'.' => (Tok::DotDot, 2),
            b'.' => (Tok::Dot, 1),
            b'(' => (Tok::LParen, 1),
            b')' => (Tok::RParen, 1),
            b'[' => (Tok::LBracket, 1),
            b']' => (Tok::RBracket, 1),
            b'+' => (Tok::Plus, 1),
            b'-' => (Tok::Minus, 1),
            b'*' if next == b'*' => (Tok::StarStar, 2),
            b'*' => (Tok::Star, 1),
            b'/' => (Tok::Slash, 1),
            b'<' if next == b'>' => (Tok::Ne, 2),
            b'<' if next == b'=' => (Tok::Le, 2),
            b'<' => (Tok::Lt, 1),
            b'>' if next == b'=' => (Tok::Ge, 2),
            b'>' => (Tok::Gt, 1),
            b'&' => (Tok::Amp, 1),
            b'^' => (Tok::Caret, 1),
            _ => return self.invalid(),
        };
        self.pos += len;
        self.push(tok, start);
    }

    /// An identifier, a keyword, or a typed literal (`INT#5`, `T#1s`).
    fn word(&mut self) {
        let start = self.pos;
        // Scan and hash for the keyword table in one pass.
        let mut h = 0u32;
        let mut n = 0;
        for &c in &self.b[start..] {
            if !is_ident_char(c) {
                break;
            }
            h = token::kw_hash_step(h, c);
            n += 1;
        }
        let end = start + n;
        self.pos = end;
        if self.at(end) == b'#' {
            return self.typed_literal(start, end);
        }
        if let Some(kw) = Kw::lookup_hashed(&self.b[start..end], h) {
            return self.push(Tok::Kw(kw), start);
        }
        let sym = self.ident_symbol(start, end, h);
        self.push(Tok::Ident(sym), start);
    }

    /// The symbol of the identifier `start..end`, whose case-insensitive
    /// hash is `h`. Names are case-insensitive, so any spelling that matches
    /// a recent one has its symbol.
    fn ident_symbol(&mut self, start: usize, end: usize, h: u32) -> Symbol {
        let word = &self.b[start..end];
        let slot = (h.wrapping_mul(0x9E37_79B9) >> 24) as usize % RECENT_SLOTS;
        let r = self.recent[slot];
        let seen = self.b.get(r.start as usize..(r.start + r.len) as usize);
        if r.len != 0 && seen.is_some_and(|s| s.eq_ignore_ascii_case(word)) {
            return r.sym;
        }
        let sym = self.interner.intern(&self.text[start..end]);
        self.recent[slot] = RecentIdent {
            start: start as u32,
            len: (end - start) as u32,
            sym,
        };
        sym
    }

    /// A run of characters that cannot start a token: one E001 for the run.
    fn invalid(&mut self) {
        let start = self.pos;
        while let Some(c) = self.text.get(self.pos..).and_then(|s| s.chars().next()) {
            if self.pos > start && c.is_ascii() && starts_something(c as u8) {
                break;
            }
            self.pos += c.len_utf8();
        }
        let run = self.text.get(start..self.pos).unwrap_or("");
        let shown = |c: char| {
            if c.is_control() || c.is_whitespace() {
                format!("U+{:04X}", c as u32)
            } else {
                format!("`{c}`")
            }
        };
        let msg = match run.chars().count() {
            1 => format!(
                "invalid character {}: it cannot start any token of Structured Text",
                run.chars().next().map(shown).unwrap_or_default()
            ),
            n => {
                let first: Vec<String> = run.chars().take(8).map(shown).collect();
                let more = if n > 8 { " ..." } else { "" };
                format!(
                    "{n} invalid characters {}{more}: they cannot start any token of Structured Text",
                    first.join(" ")
                )
            }
        };
        self.error(Code::E001, start, self.pos, msg);
    }
}

#[cfg(test)]
mod tests;
