//! Finding the dialect pragmas in a file's text.
//!
//! The lexer skips pragmas (`{ ... }`) as trivia, so the dialects read the
//! ones they care about here, with the same idea of what is a comment or a
//! string: a `{` inside `(* *)`, `/* */`, `//` or a string literal is not a
//! pragma. Only pragmas whose first word is `section` are returned.

use automat_base::{FileId, Span};

/// `{section begin}`: the word after `section` and the pragma's span.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SectionMark {
    pub word: String,
    pub span: Span,
}

/// Every `{section ...}` pragma of a file, in text order.
pub fn sections(file: FileId, text: &str) -> Vec<SectionMark> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        match (b[i], b.get(i + 1).copied()) {
            (b'(', Some(b'*')) => i = skip_past(b, i + 2, b"*)"),
            (b'/', Some(b'*')) => i = skip_past(b, i + 2, b"*/"),
            (b'/', Some(b'/')) => i = skip_past(b, i + 2, b"\n"),
            (q @ (b'\'' | b'"'), _) => i = skip_string(b, i + 1, q),
            (b'{', _) => {
                let end = skip_past(b, i + 1, b"}");
                let closed = end > i + 1 && b.get(end - 1) == Some(&b'}');
                let inner_end = if closed { end - 1 } else { end };
                let inner = text.get(i + 1..inner_end).unwrap_or("");
                let mut words = inner.split_whitespace();
                if words
                    .next()
                    .is_some_and(|w| w.eq_ignore_ascii_case("section"))
                {
                    out.push(SectionMark {
                        word: words.collect::<Vec<_>>().join(" "),
                        span: Span::new(file, i as u32, end as u32),
                    });
                }
                i = end;
            }
            _ => i += 1,
        }
    }
    out
}

/// The index just past the first `close` at or after `from` (the end of the
/// text when there is none).
fn skip_past(b: &[u8], from: usize, close: &[u8]) -> usize {
    let mut i = from;
    while i < b.len() {
        if b[i..].starts_with(close) {
            return i + close.len();
        }
        i += 1;
    }
    b.len()
}

/// Past the closing quote (`$'` is an escaped quote inside a string).
fn skip_string(b: &[u8], from: usize, quote: u8) -> usize {
    let mut i = from;
    while i < b.len() {
        if b[i] == b'$' {
            i += 2;
            continue;
        }
        if b[i] == quote {
            return i + 1;
        }
        i += 1;
    }
    b.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_section_pragmas_outside_comments_and_strings() {
        let text = "{section Begin}\nPROGRAM a END_PROGRAM\n(* {section end} *)\n\
                    s := '{section end} $' x';\n// {section end}\n{ SECTION  End }\n{attribute 'x'}";
        let marks = sections(FileId(0), text);
        let words: Vec<&str> = marks.iter().map(|m| m.word.as_str()).collect();
        assert_eq!(words, ["Begin", "End"]);
        assert_eq!(marks[0].span, Span::new(FileId(0), 0, 15));
    }

    #[test]
    fn unterminated_things_end_at_the_end() {
        assert!(sections(FileId(0), "(* {section begin}").is_empty());
        assert_eq!(sections(FileId(0), "{section begin").len(), 1);
        assert!(sections(FileId(0), "'abc").is_empty());
    }
}
