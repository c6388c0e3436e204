//! Conversions to and from STRING/WSTRING, and between character types.

use crate::elementary::Elementary as E;
use crate::error::{ErrorKind, IecError};
use crate::format::{format_value, parse_literal};
use crate::value::Value;

/// A character as one STRING byte: U+0000..U+00FF map to themselves
/// (Latin-1), anything else to `?`.
pub fn char_to_byte(c: char) -> u8 {
    u8::try_from(u32::from(c)).unwrap_or(b'?')
}

/// A WSTRING code unit as one STRING byte: units up to 16#FF are kept, the
/// rest become `?`.
pub fn unit_to_byte(u: u16) -> u8 {
    u8::try_from(u).unwrap_or(b'?')
}

/// WSTRING_TO_STRING: each code unit through [`unit_to_byte`].
pub fn wstr_to_str(w: &[u16]) -> Vec<u8> {
    w.iter().map(|&u| unit_to_byte(u)).collect()
}

/// STRING_TO_WSTRING: each byte zero-extended (Latin-1 is the first 256
/// code points of UCS-2).
pub fn str_to_wstr(s: &[u8]) -> Vec<u16> {
    s.iter().map(|&b| u16::from(b)).collect()
}

/// STRING bytes as Rust text (Latin-1, so every byte is one char).
pub fn latin1_text(s: &[u8]) -> String {
    s.iter().map(|&b| char::from(b)).collect()
}

/// WSTRING code units as Rust text; a lone surrogate becomes U+FFFD.
pub fn ucs2_text(w: &[u16]) -> String {
    char::decode_utf16(w.iter().copied())
        .map(|c| c.unwrap_or(char::REPLACEMENT_CHARACTER))
        .collect()
}

/// The text `*_TO_STRING` gives: the printed form (`42`, `0.1`, `TRUE`,
/// `T#1s500ms`, `D#2024-01-31`) without quotes for strings and characters.
pub fn to_text_bytes(v: &Value) -> Vec<u8> {
    match v {
        Value::Str(s) => s.clone(),
        Value::WStr(w) => wstr_to_str(w),
        Value::Char(c) => vec![*c],
        Value::WChar(u) => vec![unit_to_byte(*u)],
        // Every other printed form is ASCII.
        _ => format_value(v).into_bytes(),
    }
}

/// The text `*_TO_WSTRING` gives (see [`to_text_bytes`]).
pub fn to_text_units(v: &Value) -> Vec<u16> {
    match v {
        Value::Str(s) => str_to_wstr(s),
        Value::WStr(w) => w.clone(),
        Value::Char(c) => vec![u16::from(*c)],
        Value::WChar(u) => vec![*u],
        _ => format_value(v).encode_utf16().collect(),
    }
}

/// `STRING_TO_<to>`.
pub fn from_str_bytes(s: &[u8], to: E) -> Result<Value, IecError> {
    Ok(match to {
        E::String => Value::Str(s.to_vec()),
        E::Wstring => Value::WStr(str_to_wstr(s)),
        E::Char => Value::Char(s.first().copied().unwrap_or(0)),
        E::Wchar => Value::WChar(s.first().map_or(0, |&b| u16::from(b))),
        _ => parse_text(&latin1_text(s), to, E::String)?,
    })
}

/// `WSTRING_TO_<to>`.
pub fn from_wstr_units(w: &[u16], to: E) -> Result<Value, IecError> {
    Ok(match to {
        E::String => Value::Str(wstr_to_str(w)),
        E::Wstring => Value::WStr(w.to_vec()),
        E::Char => Value::Char(w.first().map_or(0, |&u| unit_to_byte(u))),
        E::Wchar => Value::WChar(w.first().copied().unwrap_or(0)),
        _ => parse_text(&ucs2_text(w), to, E::Wstring)?,
    })
}

/// Text → a value of `to` by the literal syntax of [`parse_literal`]; for
/// integer and bit-string targets a real number is accepted too and rounded
/// (halves to even), if the result fits.
fn parse_text(text: &str, to: E, from: E) -> Result<Value, IecError> {
    let first = match parse_literal(text, to) {
        Ok(v) => return Ok(v),
        Err(e) => e,
    };
    if to.is_integral() && first.kind == ErrorKind::Parse {
        if let Ok(Value::Real(r, _)) = parse_literal(text, E::Lreal) {
            let rounded = r.round_ties_even();
            let (lo, hi) = to.int_range().unwrap_or((0, 0));
            if rounded >= lo as f64 && rounded <= hi as f64 {
                return Ok(Value::Int(rounded as i128, to));
            }
            return Err(IecError::new(
                ErrorKind::OutOfRange,
                format!(
                    "{from}_TO_{to}: `{}` is out of range for {to} ({lo}..={hi})",
                    text.trim()
                ),
            ));
        }
    }
    Err(IecError::new(
        first.kind,
        format!("{from}_TO_{to}: {}", first.message),
    ))
}
