//! `$` escapes of STRING (`'...'`) and WSTRING (`"..."`) literals.

use super::LitError;

/// Decodes the text between the quotes. STRING takes `$hh` (two hex digits,
/// the char U+00hh), WSTRING `$hhhh` (four hex digits, a UTF-16 unit that
/// must not be a surrogate). Both take `$$ $' $" $L $N $P $R $T`.
pub fn decode_string(content: &str, wide: bool) -> Result<String, LitError> {
    let mut out = String::with_capacity(content.len());
    let mut chars = content.chars();
    while let Some(c) = chars.next() {
        if c != '$' {
            out.push(c);
            continue;
        }
        let Some(e) = chars.next() else {
            return Err(bad("a `$` at the end of the string"));
        };
        let decoded = match e.to_ascii_uppercase() {
            '$' => '$',
            '\'' => '\'',
            '"' => '"',
            'L' | 'N' => '\n',
            'P' => '\u{0C}',
            'R' => '\r',
            'T' => '\t',
            h if h.is_ascii_hexdigit() => {
                let want = if wide { 4 } else { 2 };
                let mut v = h.to_digit(16).unwrap_or(0);
                for _ in 1..want {
                    match chars.next().and_then(|c| c.to_digit(16)) {
                        Some(d) => v = v * 16 + d,
                        None => {
                            return Err(bad(&format!(
                                "`$` followed by a number needs {want} hex digits in a {}",
                                if wide { "WSTRING" } else { "STRING" }
                            )))
                        }
                    }
                }
                match char::from_u32(v) {
                    Some(c) => c,
                    None => return Err(bad(&format!("`$` code {v:04X} is not a character"))),
                }
            }
            other => {
                return Err(bad(&format!(
                    "unknown escape `${other}` (use `$$`, `$'`, `$\"`, `$L`, `$N`, `$P`, `$R`, `$T` or hex digits)"
                )))
            }
        };
        out.push(decoded);
    }
    Ok(out)
}

fn bad(why: &str) -> LitError {
    LitError::BadEscape(format!("invalid string literal: {why}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes() {
        assert_eq!(
            decode_string("text $'q$' $N $24", false).as_deref(),
            Ok("text 'q' \n $")
        );
        assert_eq!(
            decode_string("$$$L$p$r$t", false).as_deref(),
            Ok("$\n\u{0C}\r\t")
        );
        assert_eq!(decode_string("$C4", false).as_deref(), Ok("\u{C4}"));
        assert_eq!(
            decode_string("wide $\"x$\" $0041", true).as_deref(),
            Ok("wide \"x\" A")
        );
        assert_eq!(
            decode_string("caf\u{e9}", false).as_deref(),
            Ok("caf\u{e9}")
        );
    }

    #[test]
    fn bad_escapes() {
        for (s, wide) in [
            ("$q", false),
            ("$", false),
            ("$4", false),
            ("$004", true),
            ("$D800", true),
            ("$4G", false),
        ] {
            assert!(
                matches!(decode_string(s, wide), Err(LitError::BadEscape(_))),
                "{s}"
            );
        }
    }
}
