//! Scanning literals and direct addresses. Scanning decides where a literal
//! ends (generously: trailing letters glued to a number belong to it, so
//! `16#G0` or `12ab` is one malformed literal, not two tokens); decoding is
//! done by [`crate::literal`].

use super::{is_ident_char, is_ident_start, Lexer, Tok, MAX_WORD};
use crate::ast::{Ident, LitKind, Literal};
use crate::literal::{self, LitError, Prefix};
use automat_base::Code;

impl Lexer<'_> {
    /// An untyped number starting at a digit.
    pub(super) fn number(&mut self) {
        let start = self.pos;
        self.pos = self.scan_number(start);
        let text = &self.text[start..self.pos];
        let res = literal::number(text);
        self.finish(start, res, None, None);
    }

    /// The end of the number starting at `i`: digits, then a `#` and based
    /// digits, or a fraction and an exponent, then any glued letters.
    fn scan_number(&self, mut i: usize) -> usize {
        let digit = |c: u8| c.is_ascii_digit();
        while digit(self.at(i)) || self.at(i) == b'_' {
            i += 1;
        }
        if self.at(i) == b'#' {
            i += 1;
        } else {
            // `1..5` is a range and `w.3` a bit access: a dot is a decimal
            // point only when a digit follows it.
            if self.at(i) == b'.' && digit(self.at(i + 1)) {
                i += 1;
                while digit(self.at(i)) || self.at(i) == b'_' {
                    i += 1;
                }
            }
            if matches!(self.at(i), b'e' | b'E') {
                let sign = matches!(self.at(i + 1), b'+' | b'-');
                if digit(self.at(i + 1)) || (sign && digit(self.at(i + 2))) {
                    i += if sign { 2 } else { 1 };
                }
            }
        }
        while is_ident_char(self.at(i)) {
            i += 1;
        }
        i
    }

    /// Records a decoded literal, or reports why it is not one.
    /// `body_start`: where the text after `Prefix#` begins, if any.
    fn finish(
        &mut self,
        start: usize,
        res: Result<LitKind, LitError>,
        ty: Option<Ident>,
        body_start: Option<usize>,
    ) {
        match res {
            Ok(kind) => self.push_lit(Literal { kind, ty }, start),
            Err(e) => {
                let (code, mut msg) = match e {
                    LitError::Malformed(m) => (Code::E004, m),
                    LitError::OutOfRange(m) => (Code::E006, m),
                    LitError::BadEscape(m) => (Code::E003, m),
                };
                // The decoders quote the part after `#`; show the whole literal.
                if let (Some(b), Some(whole)) = (body_start, self.text.get(start..self.pos)) {
                    let body = format!("`{}`", self.text.get(b..self.pos).unwrap_or(""));
                    msg = msg.replacen(&body, &format!("`{whole}`"), 1);
                }
                self.error(code, start, self.pos, msg);
                self.push(Tok::BadLit, start);
            }
        }
    }

    /// `'...'` or `"..."`, closed on the same line.
    pub(super) fn string(&mut self, wide: bool) {
        let start = self.pos;
        let res = self.scan_string(wide);
        self.finish(start, res, None, None);
    }

    fn scan_string(&mut self, wide: bool) -> Result<LitKind, LitError> {
        let quote = if wide { b'"' } else { b'\'' };
        let start = self.pos;
        let mut i = start + 1;
        loop {
            match self.at(i) {
                // A `$` escapes the next byte, so `$'` does not close the string.
                b'$' if !matches!(self.at(i + 1), b'\n' | b'\r' | 0) => i += 2,
                c if c == quote => break,
                b'\n' | b'\r' => return Err(self.unterminated(i, quote)),
                _ if i >= self.b.len() => return Err(self.unterminated(i, quote)),
                _ => i += 1,
            }
        }
        self.pos = i + 1;
        let content = self.text.get(start + 1..i).unwrap_or("");
        let value = literal::decode_string(content, wide)?;
        Ok(LitKind::String { value, wide })
    }

    fn unterminated(&mut self, end: usize, quote: u8) -> LitError {
        self.pos = end.min(self.b.len());
        LitError::BadEscape(format!(
            "unterminated string literal: expected a closing `{}` before the end of the line",
            quote as char
        ))
    }

    /// `%IX0.1`, `%QW*`, `%MD48`, `%X3`: letters, then `*` or dotted numbers.
    pub(super) fn address(&mut self) {
        let start = self.pos;
        let mut i = start + 1;
        while self.at(i).is_ascii_alphabetic() {
            i += 1;
        }
        if self.at(i) == b'*' {
            i += 1;
        } else {
            while self.at(i).is_ascii_digit() {
                i += 1;
                if self.at(i) == b'.' && self.at(i + 1).is_ascii_digit() {
                    i += 1;
                }
            }
        }
        self.pos = i;
        self.push(Tok::Addr, start);
    }

    /// `Prefix#body`, with `self.pos` at the `#`.
    pub(super) fn typed_literal(&mut self, start: usize, prefix_end: usize) {
        let prefix_len = prefix_end - start;
        let mut buf = [0u8; MAX_WORD];
        let prefix = if prefix_len <= MAX_WORD {
            let upper = &mut buf[..prefix_len];
            upper.copy_from_slice(&self.b[start..prefix_end]);
            upper.make_ascii_uppercase();
            Prefix::of_upper(upper)
        } else {
            Prefix::Type
        };
        let body_start = prefix_end + 1;
        self.pos = body_start;
        if prefix != Prefix::Type {
            self.pos = self.scan_time_body(prefix, body_start);
            let body = &self.text[body_start..self.pos];
            let res = prefix.decode(body);
            return self.finish(start, res, None, Some(body_start));
        }
        let ty = Ident {
            sym: self.interner.intern(&self.text[start..prefix_end]),
            span: self.span(start, prefix_end),
        };
        let c = self.at(body_start);
        let res = match c {
            b'\'' | b'"' => self.scan_string(c == b'"'),
            b'+' | b'-' | b'0'..=b'9' => {
                let digits = body_start + usize::from(!c.is_ascii_digit());
                self.pos = if self.at(digits).is_ascii_digit() {
                    self.scan_number(digits)
                } else {
                    digits
                };
                literal::signed_number(&self.text[body_start..self.pos])
            }
            c if is_ident_start(c) => Ok(self.enum_or_bool(body_start)),
            _ => Err(LitError::Malformed(format!(
                "malformed literal: expected a value after `{}#`",
                &self.text[start..prefix_end]
            ))),
        };
        let res = match res {
            Ok(kind) if prefix_len <= MAX_WORD => {
                let whole = &self.text[start..self.pos];
                literal::check_typed(&buf[..prefix_len], whole, &kind).map(|()| kind)
            }
            other => other,
        };
        self.finish(start, res, Some(ty), Some(body_start));
    }

    /// The end of a time or date literal's body: only the characters its
    /// syntax uses, and a separator only when a digit follows it.
    fn scan_time_body(&self, prefix: Prefix, mut i: usize) -> usize {
        let seps: &[u8] = match prefix {
            Prefix::Duration { .. } => {
                if matches!(self.at(i), b'+' | b'-') {
                    i += 1;
                }
                b"."
            }
            Prefix::Date { .. } => b"-",
            Prefix::TimeOfDay { .. } => b":.",
            Prefix::DateTime { .. } | Prefix::Type => b"-:.",
        };
        loop {
            let c = self.at(i);
            if is_ident_char(c) || (seps.contains(&c) && self.at(i + 1).is_ascii_digit()) {
                i += 1;
            } else {
                return i;
            }
        }
    }

    /// `Color#Red`, `BOOL#TRUE`: the value after `#` is a name.
    fn enum_or_bool(&mut self, body_start: usize) -> LitKind {
        let mut end = body_start;
        while is_ident_char(self.at(end)) {
            end += 1;
        }
        self.pos = end;
        let name = &self.text[body_start..end];
        if name.eq_ignore_ascii_case("TRUE") {
            LitKind::Bool(true)
        } else if name.eq_ignore_ascii_case("FALSE") {
            LitKind::Bool(false)
        } else {
            LitKind::Enum(Ident {
                sym: self.interner.intern(name),
                span: self.span(body_start, end),
            })
        }
    }
}
