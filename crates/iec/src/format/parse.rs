//! [`parse_literal`]: text → value of a given type.

use super::parse_time::{parse_date, parse_dt, parse_duration, parse_tod};
use crate::convert::wrap_int;
use crate::elementary::Elementary as E;
use crate::error::{ErrorKind, IecError};
use crate::value::Value;

/// Why a body did not parse: the error kind and the reason.
pub(crate) type Why = (ErrorKind, String);

pub(crate) fn bad(why: impl Into<String>) -> Why {
    (ErrorKind::Parse, why.into())
}

pub(crate) fn too_big(why: impl Into<String>) -> Why {
    (ErrorKind::OutOfRange, why.into())
}

/// Reads `text` as a literal of type `ty` (see the module rules).
pub fn parse_literal(text: &str, ty: E) -> Result<Value, IecError> {
    let t = text.trim();
    let fail =
        |(kind, why): Why| IecError::new(kind, format!("`{t}` is not a valid {ty} literal: {why}"));
    let (prefix, body) = split_prefix(t);
    if let Some(p) = prefix {
        if !prefix_names(p, ty) {
            return Err(fail(bad(format!("the prefix `{p}#` does not name {ty}"))));
        }
    }
    if body.is_empty() {
        return Err(fail(bad("the text is empty")));
    }
    let value = match ty {
        E::Bool => parse_bool(body).map(Value::Bool),
        t if t.is_integral() => parse_int(body, t).map(|v| Value::Int(v, t)),
        t if t.is_real() => parse_real(body, t).map(|v| Value::Real(v, t)),
        E::Time | E::Ltime => parse_duration(body).map(|ns| Value::Duration(ns, ty)),
        E::Date | E::Ldate => parse_date(body).map(|d| Value::Date(d, ty)),
        E::Tod | E::Ltod => parse_tod(body).map(|ns| Value::Tod(ns, ty)),
        E::Dt | E::Ldt => parse_dt(body).map(|ns| Value::Dt(ns, ty)),
        E::String => unquote(body, false).map(|u| Value::Str(narrow(&u))),
        E::Wstring => unquote(body, true).map(Value::WStr),
        E::Char => single(unquote(body, false)).map(|u| Value::Char(u as u8)),
        // Every elementary type is covered above; WCHAR is the last.
        _ => single(unquote(body, true)).map(Value::WChar),
    };
    value.map_err(fail)
}

/// `NAME#body` → (Some(NAME), body) when NAME is an identifier; a based
/// number (`16#FF`) or a quoted string has no prefix.
fn split_prefix(t: &str) -> (Option<&str>, &str) {
    if let Some((p, body)) = t.split_once('#') {
        let ident = p.starts_with(|c: char| c.is_ascii_alphabetic())
            && p.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
        if ident {
            return (Some(p), body);
        }
    }
    (None, t)
}

/// Whether typed-literal prefix `p` may introduce a literal of `ty`.
fn prefix_names(p: &str, ty: E) -> bool {
    let family: &[&str] = match ty {
        E::Time | E::Ltime => &["T", "TIME", "LT", "LTIME"],
        E::Date | E::Ldate => &["D", "DATE", "LD", "LDATE"],
        E::Tod | E::Ltod => &["TOD", "TIME_OF_DAY", "LTOD", "LTIME_OF_DAY"],
        E::Dt | E::Ldt => &["DT", "DATE_AND_TIME", "LDT", "LDATE_AND_TIME"],
        _ => return E::from_name(p) == Some(ty),
    };
    family.iter().any(|f| f.eq_ignore_ascii_case(p))
}

fn parse_bool(body: &str) -> Result<bool, Why> {
    match body.to_ascii_uppercase().as_str() {
        "TRUE" | "1" => Ok(true),
        "FALSE" | "0" => Ok(false),
        _ => Err(bad("expected TRUE, FALSE, 1 or 0")),
    }
}

/// A leading `-` or `+`.
pub(crate) fn sign(body: &str) -> (bool, &str) {
    match body.as_bytes().first() {
        Some(b'-') => (true, &body[1..]),
        Some(b'+') => (false, &body[1..]),
        _ => (false, body),
    }
}

/// Digits with single underscores between them (`1_000`), in `radix`.
fn digits_value(digits: &str, radix: u32) -> Result<u128, Why> {
    if digits.is_empty()
        || digits.starts_with('_')
        || digits.ends_with('_')
        || digits.contains("__")
    {
        return Err(bad("expected digits, with single `_` only between them"));
    }
    let mut v: u128 = 0;
    for c in digits.chars().filter(|&c| c != '_') {
        let d = c
            .to_digit(radix)
            .ok_or_else(|| bad(format!("`{c}` is not a base-{radix} digit")))?;
        v = v * u128::from(radix) + u128::from(d);
        if v > u128::from(u64::MAX) {
            return Err(too_big("the number does not fit in 64 bits"));
        }
    }
    Ok(v)
}

fn parse_int(body: &str, ty: E) -> Result<i128, Why> {
    let (neg, rest) = sign(body);
    let (radix, digits, based) = match rest.split_once('#') {
        Some((base, digits)) => {
            let radix = match base {
                "2" => 2,
                "8" => 8,
                "16" => 16,
                _ => return Err(bad(format!("the base must be 2, 8 or 16, not `{base}`"))),
            };
            (radix, digits, true)
        }
        None => (10, rest, false),
    };
    let magnitude = digits_value(digits, radix)? as i128;
    let v = if neg { -magnitude } else { magnitude };
    let (lo, hi) = ty.int_range().unwrap_or((0, 0));
    if (lo..=hi).contains(&v) {
        return Ok(v);
    }
    // A based literal may spell a signed type's bit pattern: INT#16#FFFF = -1.
    let bits = ty.bit_width().unwrap_or(64);
    if based && !neg && ty.is_signed_int() && v < (1i128 << bits) {
        return Ok(wrap_int(v, ty));
    }
    Err(too_big(format!("{v} is out of range {lo}..={hi}")))
}

fn parse_real(body: &str, ty: E) -> Result<f64, Why> {
    let (neg, rest) = sign(body);
    let lower = rest.to_ascii_lowercase();
    let magnitude = match lower.as_str() {
        "inf" | "infinity" => f64::INFINITY,
        "nan" => f64::NAN,
        _ => finite_real(rest, ty)?,
    };
    Ok(if neg { -magnitude } else { magnitude })
}

/// `12`, `1.5`, `1_000.25e-3`: the shape is checked here, the rounding is
/// the standard library's (correctly rounded at the type's precision).
fn finite_real(text: &str, ty: E) -> Result<f64, Why> {
    let (mantissa, exponent) = match text.find(['e', 'E']) {
        Some(i) => (&text[..i], Some(&text[i + 1..])),
        None => (text, None),
    };
    let (int_part, frac) = match mantissa.split_once('.') {
        Some((i, f)) => (i, Some(f)),
        None => (mantissa, None),
    };
    let shape = |s: &str| {
        !s.is_empty()
            && !s.starts_with('_')
            && !s.ends_with('_')
            && !s.contains("__")
            && s.bytes().all(|b| b.is_ascii_digit() || b == b'_')
    };
    let exp_ok = exponent.is_none_or(|e| shape(e.strip_prefix(['+', '-']).unwrap_or(e)));
    if !shape(int_part) || !frac.is_none_or(shape) || !exp_ok {
        return Err(bad("expected a number such as 12, 1.5 or 1.5e-3"));
    }
    let clean: String = text.chars().filter(|&c| c != '_').collect();
    let v = if ty == E::Real {
        clean.parse::<f32>().map(f64::from)
    } else {
        clean.parse::<f64>()
    };
    match v {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(too_big(format!("the number is too large for {ty}"))),
        Err(_) => Err(bad("expected a number such as 12, 1.5 or 1.5e-3")),
    }
}

/// The characters of a quoted string, `$` escapes decoded, as code units
/// (≤ 16#FF when not `wide`).
fn unquote(body: &str, wide: bool) -> Result<Vec<u16>, Why> {
    let q = if wide { '"' } else { '\'' };
    let inner = body
        .strip_prefix(q)
        .and_then(|b| b.strip_suffix(q))
        .filter(|_| body.len() >= 2)
        .ok_or_else(|| bad(format!("expected text between {q} quotes")))?;
    let mut out = Vec::with_capacity(inner.len());
    let mut chars = inner.chars();
    while let Some(c) = chars.next() {
        if c == q {
            return Err(bad(format!("a {q} inside the text must be written ${q}")));
        }
        if c != '$' {
            if wide {
                let mut buf = [0u16; 2];
                out.extend_from_slice(c.encode_utf16(&mut buf));
            } else {
                let b = u8::try_from(u32::from(c))
                    .map_err(|_| bad(format!("`{c}` is not a STRING character (above U+00FF)")))?;
                out.push(u16::from(b));
            }
            continue;
        }
        let e = chars.next().ok_or_else(|| bad("a `$` ends the text"))?;
        let unit = match e.to_ascii_uppercase() {
            '$' => u16::from(b'$'),
            '\'' => u16::from(b'\''),
            '"' => u16::from(b'"'),
            'L' | 'N' => 0x0A,
            'P' => 0x0C,
            'R' => 0x0D,
            'T' => 0x09,
            h if h.is_ascii_hexdigit() => {
                let want = if wide { 4 } else { 2 };
                let mut v = h.to_digit(16).unwrap_or(0);
                for _ in 1..want {
                    let d = chars
                        .next()
                        .and_then(|c| c.to_digit(16))
                        .ok_or_else(|| bad(format!("`$` with a code needs {want} hex digits")))?;
                    v = v * 16 + d;
                }
                // At most 4 hex digits: fits in u16.
                v as u16
            }
            other => return Err(bad(format!("`${other}` is not an escape"))),
        };
        out.push(unit);
    }
    Ok(out)
}

fn narrow(units: &[u16]) -> Vec<u8> {
    // unquote gives units ≤ 16#FF for STRING.
    units.iter().map(|&u| u as u8).collect()
}

fn single(units: Result<Vec<u16>, Why>) -> Result<u16, Why> {
    match units?.as_slice() {
        [u] => Ok(*u),
        _ => Err(bad("a character literal holds exactly one character")),
    }
}
