//! Tokens of one scenario line.
//!
//! A word is a run of anything but white space, `(`, `)`, `=`, `<`, `>`,
//! `"`, the operators `+ - * /`, `,` and `#`-comments; a `[` inside a word
//! extends it to the matching `]` (so `arr[1, 2].x` is one word), and `#`
//! right after a letter is part of the word (`T#1s`, `CraneStep#Rest1`). A
//! `#` elsewhere starts a comment. A `+` or `-` stays in a word after `#`
//! (`T#-1s`) and after the `e` of a number's exponent (`1e-3`); a `-`
//! before a number is the parser's unary minus. A `/` inside an SLC-500
//! address (`B3:0/1`, `T4:0/DN`, `I:1/1`: a word with `:` after a file
//! letter) is part of the word; write the flat form `B3/18` as `B3:1/2`,
//! and a division of such an address with spaces (`N7:0 / 2`).

#[derive(Clone, Debug, PartialEq)]
pub enum Tok {
    Word(String),
    Str(String),
    Op(&'static str),
    LParen,
    RParen,
}

/// A token and its byte range in the line.
#[derive(Clone, Debug, PartialEq)]
pub struct Token {
    pub tok: Tok,
    pub start: usize,
    pub end: usize,
}

/// The tokens of `line`; an error is (byte offset, message).
pub fn tokens(line: &str) -> Result<Vec<Token>, (usize, String)> {
    let b = line.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while let Some(&c) = b.get(i) {
        let start = i;
        match c {
            b' ' | b'\t' | b'\r' => {
                i += 1;
                continue;
            }
            // `#N7:5`, an indexed SLC-500 address, is a word; any other
            // `#` starts a comment.
            b'#' if !indexed_slc(b, i) => break,
            b'(' | b')' => {
                i += 1;
                out.push(Token {
                    tok: if c == b'(' { Tok::LParen } else { Tok::RParen },
                    start,
                    end: i,
                });
                continue;
            }
            b'"' => {
                let rest = line.get(i + 1..).unwrap_or("");
                let close = rest
                    .find('"')
                    .ok_or((i, "string without closing `\"`".to_string()))?;
                out.push(Token {
                    tok: Tok::Str(rest.get(..close).unwrap_or("").to_string()),
                    start,
                    end: i + close + 2,
                });
                i += close + 2;
                continue;
            }
            b'+' | b'-' | b'*' | b'/' | b',' => {
                i += 1;
                out.push(Token {
                    tok: Tok::Op(match c {
                        b'+' => "+",
                        b'-' => "-",
                        b'*' => "*",
                        b'/' => "/",
                        _ => ",",
                    }),
                    start,
                    end: i,
                });
                continue;
            }
            b'=' | b'<' | b'>' => {
                let two = line.get(i..i + 2).unwrap_or("");
                let op = match two {
                    "<=" => "<=",
                    ">=" => ">=",
                    "<>" => "<>",
                    _ => match c {
                        b'=' => "=",
                        b'<' => "<",
                        _ => ">",
                    },
                };
                i += op.len();
                out.push(Token {
                    tok: Tok::Op(op),
                    start,
                    end: i,
                });
                continue;
            }
            _ => {}
        }
        let mut depth = 0usize;
        while let Some(&c) = b.get(i) {
            match c {
                b'[' => depth += 1,
                b']' => depth = depth.saturating_sub(1),
                _ if depth > 0 => {}
                // `B3:0/1`, `T4:0/DN`, `I:1/1`: the bit of an SLC-500
                // address (a word with `:` after a file letter) is part of it.
                b'/' if slc_bit(b, start, i) => {}
                // `B3/[N7:1]`: the indirect flat bit is part of the word.
                b'/' if b.get(i + 1) == Some(&b'[') && slc_file(b.get(start..i)) => {}
                b' ' | b'\t' | b'\r' | b'(' | b')' | b'=' | b'<' | b'>' | b'"' | b'*' | b'/'
                | b',' => break,
                b'+' | b'-' if !sign_in_word(b, start, i) => break,
                b'#' if i == start && !indexed_slc(b, i) => break,
                _ => {}
            }
            i += 1;
        }
        if depth > 0 {
            return Err((start, "`[` without `]`".to_string()));
        }
        out.push(Token {
            tok: Tok::Word(line.get(start..i).unwrap_or("").to_string()),
            start,
            end: i,
        });
    }
    Ok(out)
}

/// Whether the `/` at `i` is the bit separator of an SLC-500 address: the
/// word so far is a file letter, digits, `:` and an element (`B3:0`,
/// `I:1.2`, `T4:0`), and a bit number or name follows.
fn slc_bit(b: &[u8], start: usize, i: usize) -> bool {
    let word = b.get(start..i).unwrap_or(&[]);
    word.first()
        .is_some_and(|c| b"OISBTCRNFoisbtcrnf".contains(c))
        && word.contains(&b':')
        && word[1..]
            .iter()
            .all(|c| c.is_ascii_alphanumeric() || b":.[]".contains(c))
        && b.get(i + 1)
            .is_some_and(|c| c.is_ascii_alphanumeric() || *c == b'[')
}

/// A data file's name: a file letter and digits (`B3`, `N10`).
fn slc_file(word: Option<&[u8]>) -> bool {
    word.is_some_and(|w| {
        w.first().is_some_and(|c| b"BNSbns".contains(c))
            && w.len() > 1
            && w[1..].iter().all(u8::is_ascii_digit)
    })
}

/// Whether the `#` at `i` starts an indexed SLC-500 address (`#N7:5`,
/// `#F8:0`, `#B3:2`): a B, N or F file, its number and `:`.
fn indexed_slc(b: &[u8], i: usize) -> bool {
    let rest = b.get(i + 1..).unwrap_or(&[]);
    let digits = rest
        .get(1..)
        .map_or(0, |r| r.iter().take_while(|c| c.is_ascii_digit()).count());
    rest.first().is_some_and(|c| b"BNFbnf".contains(c))
        && digits > 0
        && rest.get(1 + digits) == Some(&b':')
}

/// Whether the `+`/`-` at `i` belongs to the word that started at `start`:
/// right after `#` (`T#-1s`), or the sign of an exponent (`1.5e-3`).
fn sign_in_word(b: &[u8], start: usize, i: usize) -> bool {
    let prev = i.checked_sub(1).and_then(|p| b.get(p)).copied();
    match prev {
        Some(b'#') => true,
        Some(b'e' | b'E') => b.get(start).is_some_and(u8::is_ascii_digit),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn words(line: &str) -> Vec<Tok> {
        tokens(line).unwrap().into_iter().map(|t| t.tok).collect()
    }

    #[test]
    fn slc_indexed_and_indirect_addresses_are_one_word() {
        let w = |s: &str| Tok::Word(s.to_string());
        assert_eq!(
            words("expect at 1s #N7:5 = N7:[N7:0] # a comment"),
            [
                w("expect"),
                w("at"),
                w("1s"),
                w("#N7:5"),
                Tok::Op("="),
                w("N7:[N7:0]")
            ]
        );
        assert_eq!(
            words("B3/[N7:1] B3:[N7:0]/5 B3:0/[N7:2] T4:[N7:0]/DN N[N7:3]:1"),
            [
                w("B3/[N7:1]"),
                w("B3:[N7:0]/5"),
                w("B3:0/[N7:2]"),
                w("T4:[N7:0]/DN"),
                w("N[N7:3]:1")
            ]
        );
        assert_eq!(words("#N7 x"), Vec::<Tok>::new());
    }

    #[test]
    fn slc_bit_addresses_are_one_word() {
        let w = |s: &str| Tok::Word(s.into());
        assert_eq!(
            words("B3:0/1 AND T4:0/DN OR I:1.2/3 AND N7:0 / 2 = x/y"),
            [
                w("B3:0/1"),
                w("AND"),
                w("T4:0/DN"),
                w("OR"),
                w("I:1.2/3"),
                w("AND"),
                w("N7:0"),
                Tok::Op("/"),
                w("2"),
                Tok::Op("="),
                w("x"),
                Tok::Op("/"),
                w("y"),
            ]
        );
        // The flat form stays a division: `B3/18` is written `B3:1/2`.
        assert_eq!(words("B3/18"), [w("B3"), Tok::Op("/"), w("18")]);
    }

    #[test]
    fn words_operators_strings_comments() {
        assert_eq!(
            words(r#"name "a # b" # comment"#),
            [Tok::Word("name".into()), Tok::Str("a # b".into())]
        );
        assert_eq!(
            words("expect at 40s Ctrl.step = CraneStep#Rest1 AND plant.x<0.05"),
            [
                Tok::Word("expect".into()),
                Tok::Word("at".into()),
                Tok::Word("40s".into()),
                Tok::Word("Ctrl.step".into()),
                Tok::Op("="),
                Tok::Word("CraneStep#Rest1".into()),
                Tok::Word("AND".into()),
                Tok::Word("plant.x".into()),
                Tok::Op("<"),
                Tok::Word("0.05".into()),
            ]
        );
        assert_eq!(
            words("NOT (a[1, 2].x <> T#1s)"),
            [
                Tok::Word("NOT".into()),
                Tok::LParen,
                Tok::Word("a[1, 2].x".into()),
                Tok::Op("<>"),
                Tok::Word("T#1s".into()),
                Tok::RParen
            ]
        );
        assert_eq!(
            words("plant.T-Reg.T_sp < -1.5e-3*2"),
            [
                Tok::Word("plant.T".into()),
                Tok::Op("-"),
                Tok::Word("Reg.T_sp".into()),
                Tok::Op("<"),
                Tok::Op("-"),
                Tok::Word("1.5e-3".into()),
                Tok::Op("*"),
                Tok::Word("2".into()),
            ]
        );
        assert_eq!(
            words("min(a[1, 2],T#-1s)/x"),
            [
                Tok::Word("min".into()),
                Tok::LParen,
                Tok::Word("a[1, 2]".into()),
                Tok::Op(","),
                Tok::Word("T#-1s".into()),
                Tok::RParen,
                Tok::Op("/"),
                Tok::Word("x".into()),
            ]
        );
        assert!(tokens("a[1").is_err());
        assert!(tokens("name \"x").is_err());
    }
}
