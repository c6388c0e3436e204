//! Decoding literal text into values. The lexer finds where a literal ends;
//! these functions turn its text into a [`LitKind`] or say what is wrong with
//! it. They are pure: no spans, no interner, so they are easy to test alone.

mod string;
mod time;

pub use string::decode_string;
pub use time::{date, date_time, duration, time_of_day};

use crate::ast::LitKind;

/// Why a literal could not be decoded.
#[derive(Clone, Debug, PartialEq)]
pub enum LitError {
    /// Does not follow the syntax (E004).
    Malformed(String),
    /// Well-formed but does not fit (E006).
    OutOfRange(String),
    /// A string with a bad `$` escape (E003).
    BadEscape(String),
}

/// What a `Name#` prefix introduces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Prefix {
    Duration {
        long: bool,
    },
    Date {
        long: bool,
    },
    TimeOfDay {
        long: bool,
    },
    DateTime {
        long: bool,
    },
    /// Any other name: a type (`INT#5`, `Color#Red`).
    Type,
}

impl Prefix {
    /// Classifies an upper-cased prefix.
    pub fn of_upper(upper: &[u8]) -> Prefix {
        match upper {
            b"T" | b"TIME" => Prefix::Duration { long: false },
            b"LT" | b"LTIME" => Prefix::Duration { long: true },
            b"D" | b"DATE" => Prefix::Date { long: false },
            b"LD" | b"LDATE" => Prefix::Date { long: true },
            b"TOD" | b"TIME_OF_DAY" => Prefix::TimeOfDay { long: false },
            b"LTOD" | b"LTIME_OF_DAY" => Prefix::TimeOfDay { long: true },
            b"DT" | b"DATE_AND_TIME" => Prefix::DateTime { long: false },
            b"LDT" | b"LDATE_AND_TIME" => Prefix::DateTime { long: true },
            _ => Prefix::Type,
        }
    }

    /// Decodes the text after `#` for a time or date prefix.
    pub fn decode(self, body: &str) -> Result<LitKind, LitError> {
        match self {
            Prefix::Duration { long } => duration(body, long),
            Prefix::Date { long } => date(body, long),
            Prefix::TimeOfDay { long } => time_of_day(body, long),
            Prefix::DateTime { long } => date_time(body, long),
            Prefix::Type => number(body),
        }
    }
}

/// The largest magnitude an integer literal may have: ULINT's maximum.
const INT_MAX: u128 = u64::MAX as u128;

/// Decodes an unsigned numeric literal: `123_456`, `2#1010`, `16#FF`,
/// `1.5E-3`, `1e6`. A sign is not part of it (see [`signed_number`]).
pub fn number(text: &str) -> Result<LitKind, LitError> {
    if let Some((base, digits)) = text.split_once('#') {
        return based(text, base, digits);
    }
    let bytes = text.as_bytes();
    let is_real = bytes.iter().any(|&b| matches!(b, b'.' | b'e' | b'E'));
    if !is_real {
        return decimal(text).map(LitKind::Int);
    }
    real(text)
}

/// A number with an optional leading sign (the body of `INT#-5`).
pub fn signed_number(text: &str) -> Result<LitKind, LitError> {
    let (neg, rest) = match text.as_bytes().first() {
        Some(b'-') => (true, &text[1..]),
        Some(b'+') => (false, &text[1..]),
        _ => (false, text),
    };
    match number(rest)? {
        LitKind::Int(v) if neg => {
            // i64::MIN is the most negative value any integer type holds.
            if v > (i64::MAX as i128) + 1 {
                Err(LitError::OutOfRange(format!(
                    "integer literal `{text}` does not fit in 64 bits"
                )))
            } else {
                Ok(LitKind::Int(-v))
            }
        }
        LitKind::Real(f) if neg => Ok(LitKind::Real(-f)),
        other => Ok(other),
    }
}

/// Digits with single underscores between them, as IEC allows.
fn check_underscores(text: &str, digits: &str) -> Result<(), LitError> {
    if digits.is_empty()
        || digits.starts_with('_')
        || digits.ends_with('_')
        || digits.contains("__")
    {
        return Err(LitError::Malformed(format!(
            "malformed number `{text}`: expected digits"
        )));
    }
    Ok(())
}

fn decimal(text: &str) -> Result<i128, LitError> {
    check_underscores(text, text)?;
    let mut v: u128 = 0;
    for b in text.bytes() {
        match b {
            b'0'..=b'9' => {
                v = v * 10 + u128::from(b - b'0');
                if v > INT_MAX {
                    return Err(too_big(text));
                }
            }
            b'_' => {}
            _ => return Err(bad_digit(text, b, 10)),
        }
    }
    Ok(v as i128)
}

fn based(text: &str, base: &str, digits: &str) -> Result<LitKind, LitError> {
    let radix: u32 = match base {
        "2" => 2,
        "8" => 8,
        "16" => 16,
        _ => {
            return Err(LitError::Malformed(format!(
                "malformed number `{text}`: the base must be 2, 8 or 16, not `{base}`"
            )))
        }
    };
    check_underscores(text, digits)?;
    let mut v: u128 = 0;
    for b in digits.bytes() {
        if b == b'_' {
            continue;
        }
        let d = match (b as char).to_digit(radix) {
            Some(d) => d,
            None => return Err(bad_digit(text, b, radix)),
        };
        v = v * u128::from(radix) + u128::from(d);
        if v > INT_MAX {
            return Err(too_big(text));
        }
    }
    Ok(LitKind::Int(v as i128))
}

fn real(text: &str) -> Result<LitKind, LitError> {
    // Shape check first so that `1.5.2` or `1e` are reported as malformed
    // rather than trusted to the float parser's idea of syntax.
    let (mantissa, exponent) = match text.find(['e', 'E']) {
        Some(i) => (&text[..i], Some(&text[i + 1..])),
        None => (text, None),
    };
    let (int_part, frac) = match mantissa.split_once('.') {
        Some((i, f)) => (i, Some(f)),
        None => (mantissa, None),
    };
    let digits_ok = |s: &str| {
        !s.is_empty()
            && !s.starts_with('_')
            && !s.ends_with('_')
            && !s.contains("__")
            && s.bytes().all(|b| b.is_ascii_digit() || b == b'_')
    };
    let exp_ok = exponent.is_none_or(|e| {
        let e = e.strip_prefix(['+', '-']).unwrap_or(e);
        digits_ok(e)
    });
    if !digits_ok(int_part) || !frac.is_none_or(digits_ok) || !exp_ok {
        return Err(LitError::Malformed(format!(
            "malformed real number `{text}`"
        )));
    }
    let clean: String = text.chars().filter(|&c| c != '_').collect();
    match clean.parse::<f64>() {
        Ok(f) if f.is_finite() => Ok(LitKind::Real(f)),
        Ok(_) => Err(LitError::OutOfRange(format!(
            "real literal `{text}` is too large for LREAL"
        ))),
        Err(_) => Err(LitError::Malformed(format!(
            "malformed real number `{text}`"
        ))),
    }
}

/// The range of an elementary type named by an upper-cased prefix, for
/// typed literals: `SINT#300` does not fit. `None` for other names (user
/// types, REAL, strings), whose literals the checker types.
fn int_range(upper: &[u8]) -> Option<(i128, i128)> {
    Some(match upper {
        b"SINT" => (i8::MIN.into(), i8::MAX.into()),
        b"INT" => (i16::MIN.into(), i16::MAX.into()),
        b"DINT" => (i32::MIN.into(), i32::MAX.into()),
        b"LINT" => (i64::MIN.into(), i64::MAX.into()),
        b"USINT" | b"BYTE" => (0, u8::MAX.into()),
        b"UINT" | b"WORD" => (0, u16::MAX.into()),
        b"UDINT" | b"DWORD" => (0, u32::MAX.into()),
        b"ULINT" | b"LWORD" => (0, u64::MAX.into()),
        b"BOOL" => (0, 1),
        _ => return None,
    })
}

/// Checks a decoded typed literal against its elementary type (E006).
pub fn check_typed(upper_ty: &[u8], whole: &str, kind: &LitKind) -> Result<(), LitError> {
    let name = String::from_utf8_lossy(upper_ty);
    match kind {
        LitKind::Int(v) => match int_range(upper_ty) {
            Some((lo, hi)) if *v < lo || *v > hi => Err(LitError::OutOfRange(format!(
                "literal `{whole}` does not fit in {name} ({lo}..{hi})"
            ))),
            _ => Ok(()),
        },
        LitKind::Real(r) if upper_ty == b"REAL" && r.abs() > f64::from(f32::MAX) => Err(
            LitError::OutOfRange(format!("literal `{whole}` does not fit in REAL")),
        ),
        _ => Ok(()),
    }
}

fn too_big(text: &str) -> LitError {
    LitError::OutOfRange(format!("integer literal `{text}` does not fit in 64 bits"))
}

fn bad_digit(text: &str, b: u8, radix: u32) -> LitError {
    let shown = if b.is_ascii_graphic() {
        format!("`{}`", b as char)
    } else {
        "this character".to_string()
    };
    LitError::Malformed(format!(
        "malformed number `{text}`: {shown} is not a base-{radix} digit"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integers_in_every_base() {
        assert_eq!(number("123_456"), Ok(LitKind::Int(123_456)));
        assert_eq!(number("2#1010"), Ok(LitKind::Int(10)));
        assert_eq!(number("8#17"), Ok(LitKind::Int(15)));
        assert_eq!(number("16#FF"), Ok(LitKind::Int(255)));
        assert_eq!(number("16#ff_ff"), Ok(LitKind::Int(65535)));
        assert_eq!(
            number("18446744073709551615"),
            Ok(LitKind::Int(u64::MAX as i128))
        );
    }

    #[test]
    fn integer_errors() {
        assert!(matches!(number("16#G0"), Err(LitError::Malformed(_))));
        assert!(matches!(number("2#102"), Err(LitError::Malformed(_))));
        assert!(matches!(number("7#1"), Err(LitError::Malformed(_))));
        assert!(matches!(number("16#"), Err(LitError::Malformed(_))));
        assert!(matches!(number("1__"), Err(LitError::Malformed(_))));
        assert!(matches!(number("12abc"), Err(LitError::Malformed(_))));
        assert!(matches!(
            number("18446744073709551616"),
            Err(LitError::OutOfRange(_))
        ));
        assert!(matches!(
            number(&"9".repeat(200)),
            Err(LitError::OutOfRange(_))
        ));
    }

    #[test]
    fn reals() {
        assert_eq!(number("1.5E-3"), Ok(LitKind::Real(1.5e-3)));
        assert_eq!(number("1.0e6"), Ok(LitKind::Real(1.0e6)));
        assert_eq!(number("1e6"), Ok(LitKind::Real(1.0e6)));
        assert_eq!(number("12.345_6"), Ok(LitKind::Real(12.3456)));
        assert!(matches!(number("1.5e"), Err(LitError::Malformed(_))));
        assert!(matches!(number("1e999"), Err(LitError::OutOfRange(_))));
    }

    #[test]
    fn signed() {
        assert_eq!(signed_number("-5"), Ok(LitKind::Int(-5)));
        assert_eq!(signed_number("+5"), Ok(LitKind::Int(5)));
        assert_eq!(signed_number("-1.5"), Ok(LitKind::Real(-1.5)));
        assert_eq!(
            signed_number("-9223372036854775808"),
            Ok(LitKind::Int(i64::MIN as i128))
        );
        assert!(matches!(
            signed_number("-9223372036854775809"),
            Err(LitError::OutOfRange(_))
        ));
    }

    #[test]
    fn typed_ranges() {
        let fits = |ty: &str, v: i128| check_typed(ty.as_bytes(), "x", &LitKind::Int(v)).is_ok();
        assert!(fits("SINT", -128) && fits("SINT", 127));
        assert!(!fits("SINT", 128) && !fits("SINT", -129));
        assert!(!fits("USINT", -1) && fits("USINT", 255));
        assert!(!fits("INT", 40000) && !fits("BYTE", 256) && !fits("INT", 65536));
        assert!(fits("ULINT", u64::MAX as i128) && !fits("LINT", u64::MAX as i128));
        assert!(!fits("BOOL", 2) && fits("BOOL", 1));
        assert!(fits("MyType", 1_000_000));
        assert!(check_typed(b"REAL", "x", &LitKind::Real(1e39)).is_err());
        assert!(check_typed(b"LREAL", "x", &LitKind::Real(1e39)).is_ok());
    }

    #[test]
    fn double_underscores_are_malformed() {
        assert!(matches!(number("1__000"), Err(LitError::Malformed(_))));
        assert!(matches!(number("16#F__F"), Err(LitError::Malformed(_))));
        assert!(matches!(number("1.0__5"), Err(LitError::Malformed(_))));
        assert_eq!(number("1_000"), Ok(LitKind::Int(1000)));
    }

    #[test]
    fn prefixes() {
        assert_eq!(Prefix::of_upper(b"T"), Prefix::Duration { long: false });
        assert_eq!(Prefix::of_upper(b"LTIME"), Prefix::Duration { long: true });
        assert_eq!(Prefix::of_upper(b"TOD"), Prefix::TimeOfDay { long: false });
        assert_eq!(Prefix::of_upper(b"LDT"), Prefix::DateTime { long: true });
        assert_eq!(Prefix::of_upper(b"INT"), Prefix::Type);
    }
}
