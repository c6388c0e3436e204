//! FST STL text → words. Layout is free: keywords, operands and constants
//! are separated by blanks or line breaks (an instruction may span lines),
//! `;` and `"` start a comment to the end of the line, commas are
//! separators (the lab writes `LOAD FW1, SHL, +V1, TO FW1`).

/// One word of the text with its byte range.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Tok {
    /// As written.
    pub text: String,
    /// Upper case, for keywords and operands.
    pub up: String,
    pub start: u32,
    pub end: u32,
}

pub fn lex(text: &str) -> Vec<Tok> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    let word = |c: u8| c.is_ascii_alphanumeric() || c == b'_' || c == b'.';
    while i < b.len() {
        let c = b[i];
        let start = i;
        if c == b';' || c == b'"' {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
            continue;
        } else if c.is_ascii_whitespace() || c == b',' || c == b':' {
            i += 1;
            continue;
        } else if word(c) {
            while i < b.len() && word(b[i]) {
                i += 1;
            }
            // V$0F, V%0101, V-5: the constant's prefix glues to its digits.
            if i - start == 1
                && (c == b'V' || c == b'v')
                && matches!(b.get(i), Some(b'$' | b'%' | b'-'))
            {
                i += 1;
                while i < b.len() && b[i].is_ascii_alphanumeric() {
                    i += 1;
                }
            }
        } else if (c == b'<' && matches!(b.get(i + 1), Some(b'=' | b'>')))
            || (c == b'>' && b.get(i + 1) == Some(&b'='))
        {
            i += 2;
        } else {
            // One character: an operator, a parenthesis, or something the
            // parser refuses with its location. Whole UTF-8 characters.
            i += 1;
            while i < b.len() && !text.is_char_boundary(i) {
                i += 1;
            }
        }
        let t = &text[start..i];
        out.push(Tok {
            text: t.to_string(),
            up: t.to_ascii_uppercase(),
            start: start as u32,
            end: i as u32,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_operators_constants_comments() {
        let t: Vec<String> = lex("IF I0.1 ; c\n AND N (IW0<>V$0F), TO V-5 \"x\n<=")
            .into_iter()
            .map(|t| t.text)
            .collect();
        assert_eq!(
            t,
            ["IF", "I0.1", "AND", "N", "(", "IW0", "<>", "V$0F", ")", "TO", "V-5", "<="]
        );
    }
}
