//! Whitespace, comments and pragmas: skipped, never tokens.

use super::Lexer;
use automat_base::Code;

impl Lexer<'_> {
    pub(super) fn skip_trivia(&mut self) {
        loop {
            match (self.at(self.pos), self.at(self.pos + 1)) {
                (c, _) if super::is_space(c) => {
                    let rest = &self.b[self.pos..];
                    self.pos += rest
                        .iter()
                        .position(|&c| !super::is_space(c))
                        .unwrap_or(rest.len());
                }
                (b'(', b'*') => self.nested_comment(),
                (b'/', b'*') => self.c_comment(),
                (b'/', b'/') => self.line_comment(),
                (b'{', _) => self.pragma(),
                _ => return,
            }
        }
    }

    /// `(* ... *)`; comments of this kind nest: `(* a (* b *) c *)`, unless
    /// the lexer was asked for CODESYS comments, which end at the first `*)`.
    fn nested_comment(&mut self) {
        let start = self.pos;
        let mut depth = 0usize;
        let mut i = start;
        let len = self.b.len();
        while i < len {
            match (self.b[i], self.at(i + 1)) {
                (b'(', b'*') if self.nest_comments || depth == 0 => {
                    depth += 1;
                    i += 2;
                }
                (b'*', b')') => {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        self.pos = i;
                        return;
                    }
                }
                _ => i += 1,
            }
        }
        self.pos = len;
        self.error(
            Code::E002,
            start,
            start + 2,
            "unterminated comment: this `(*` is not closed by `*)` before the end of the file"
                .to_string(),
        );
    }

    /// `/* ... */` (does not nest).
    fn c_comment(&mut self) {
        let start = self.pos;
        let body = &self.b[start + 2..];
        match body.windows(2).position(|w| w == b"*/") {
            Some(i) => self.pos = start + 2 + i + 2,
            None => {
                self.pos = self.b.len();
                self.error(
                    Code::E002,
                    start,
                    start + 2,
                    "unterminated comment: this `/*` is not closed by `*/` before the end of the file"
                        .to_string(),
                );
            }
        }
    }

    /// `// ...` to the end of the line.
    fn line_comment(&mut self) {
        let rest = &self.b[self.pos..];
        self.pos += rest.iter().position(|&c| c == b'\n').unwrap_or(rest.len());
    }

    /// `{ ... }`: a pragma or attribute (`{attribute 'qualified_only'}`),
    /// which this front end does not interpret.
    fn pragma(&mut self) {
        let start = self.pos;
        let rest = &self.b[start..];
        if rest.starts_with(b"{{") {
            // MatIEC's (Beremiz, OpenPLC) embedded C code, copied into its C
            // output: `{{ ... }}` up to the first `}}`. Skipping it would
            // drop what the POU does, so it is an error; the text after it
            // is read as usual.
            let close = rest
                .get(2..)
                .and_then(|r| r.windows(2).position(|w| w == b"}}"));
            self.pos = close.map_or(self.b.len(), |i| start + 2 + i + 2);
            self.error(
                Code::E191,
                start,
                start + 2,
                "embedded C code `{{ ... }}` (MatIEC, Beremiz, OpenPLC) cannot run in automat: write what it does in Structured Text".to_string(),
            );
            return;
        }
        match rest.iter().position(|&c| c == b'}') {
            Some(i) => {
                self.pos = start + i + 1;
                self.pragmas = self.pragmas.saturating_add(1);
                if self.first_pragma.is_none() {
                    self.first_pragma = Some((start as u32, self.pos as u32));
                }
            }
            None => {
                self.pos = self.b.len();
                self.error(
                    Code::E002,
                    start,
                    start + 1,
                    "unterminated pragma: this `{` is not closed by `}` before the end of the file"
                        .to_string(),
                );
            }
        }
    }
}
