//! The PL7 spellings that the IEC lexer does not accept, rewritten in the
//! text before parsing, byte for byte the same length so every span (and
//! every diagnostic's excerpt of the original text) stays right:
//! - `%Xi` (step i), `%Si` (system bit), `%SWi` (system word) become
//!   `_Xi`, `_Si`, `_SWi`: plain identifiers (`%X3.T` is then `_X3.T`, the
//!   step time). Not after a `.`, where `%X3` is the IEC bit access
//!   `word.%X3`;
//! - the qualifier `N1` (continuous action section) inside a step's
//!   associations becomes `N ` (IEC's non-stored action).
//!
//! Comments, strings and pragmas are left alone.

/// The rewritten text, or `None` when nothing needed rewriting.
pub fn rewrite(text: &str) -> Option<String> {
    let b = text.as_bytes();
    let mut out: Vec<u8> = b.to_vec();
    let mut changed = false;
    let mut in_step = false;
    let mut i = 0;
    while i < b.len() {
        match (b[i], b.get(i + 1).copied()) {
            (b'(', Some(b'*')) => i = skip_past(b, i + 2, b"*)"),
            (b'/', Some(b'*')) => i = skip_past(b, i + 2, b"*/"),
            (b'/', Some(b'/')) => i = skip_past(b, i + 2, b"\n"),
            (b'{', _) => i = skip_past(b, i + 1, b"}"),
            (q @ (b'\'' | b'"'), _) => i = skip_string(b, i + 1, q),
            (b'%', Some(c)) if is_pl7_object(b, i, c) => {
                out[i] = b'_';
                changed = true;
                i += 1;
            }
            (c, _) if is_word_start(c) && (i == 0 || !is_word_byte(b[i - 1])) => {
                let end = word_end(b, i);
                let word = &b[i..end];
                if word.eq_ignore_ascii_case(b"STEP") || word.eq_ignore_ascii_case(b"INITIAL_STEP")
                {
                    in_step = true;
                } else if word.eq_ignore_ascii_case(b"END_STEP") {
                    in_step = false;
                } else if in_step && word.eq_ignore_ascii_case(b"N1") {
                    out[i + 1] = b' ';
                    changed = true;
                }
                i = end;
            }
            _ => i += 1,
        }
    }
    if !changed {
        return None;
    }
    // Only ASCII bytes were replaced by ASCII bytes: still UTF-8.
    String::from_utf8(out).ok()
}

/// `%X<digit>`, `%S<digit>`, `%SW<digit>` not preceded by a `.`.
fn is_pl7_object(b: &[u8], i: usize, c: u8) -> bool {
    let prev = b[..i].iter().rev().find(|x| !x.is_ascii_whitespace());
    if prev == Some(&b'.') {
        return false;
    }
    let digit_at = |k: usize| b.get(k).is_some_and(u8::is_ascii_digit);
    match c.to_ascii_uppercase() {
        b'X' => digit_at(i + 2),
        b'S' => {
            digit_at(i + 2)
                || (b.get(i + 2).is_some_and(|w| w.eq_ignore_ascii_case(&b'W')) && digit_at(i + 3))
        }
        _ => false,
    }
}

fn is_word_start(c: u8) -> bool {
    c.is_ascii_alphabetic() || c == b'_'
}

fn is_word_byte(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_'
}

fn word_end(b: &[u8], from: usize) -> usize {
    let mut i = from;
    while i < b.len() && is_word_byte(b[i]) {
        i += 1;
    }
    i
}

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
    use super::rewrite;

    #[test]
    fn objects_and_n1_keep_their_length() {
        let src = "STEP %X1: a(N1); b(P1); END_STEP\nx := %X1.T > T#1s AND %S21 OR %SW20 > 2;\n\
                   y := w.%X3; (* %X2 *) s := '%X4'; N1 := 1;";
        let out = rewrite(src).unwrap_or_default();
        assert_eq!(out.len(), src.len());
        assert_eq!(
            out,
            "STEP _X1: a(N ); b(P1); END_STEP\nx := _X1.T > T#1s AND _S21 OR _SW20 > 2;\n\
             y := w.%X3; (* %X2 *) s := '%X4'; N1 := 1;"
        );
    }

    #[test]
    fn nothing_to_do() {
        assert_eq!(rewrite("x := %IX0.1 AND %MW3 > 2;"), None);
        assert_eq!(rewrite("%X"), None);
        assert_eq!(rewrite("%"), None);
    }
}
