//! STRING(n) and WSTRING(n) functions (IEC 61131-3 3rd edition, table 43).
//!
//! Every function is generic over the character unit: `u8` for STRING
//! (one byte a character) and `u16` for WSTRING (one UCS-2 code unit a
//! character), so both types share one implementation.
//!
//! Rules:
//! - Positions are 1-based: the first character is at P = 1.
//! - A declared STRING(n) holds at most n characters; assigning a longer
//!   value keeps the first n ([`assign`]). The functions here return their
//!   full result; the engine truncates it when it stores it.
//! - `LEFT(IN, L)`, `RIGHT(IN, L)`: L < 0 is an error; L > LEN(IN) gives
//!   the whole string.
//! - `MID(IN, L, P)`: L characters from position P. P must be in
//!   1..=LEN+1 (P = LEN+1 gives ''), L ≥ 0; a range running past the end
//!   stops at the end.
//! - `INSERT(IN1, IN2, P)`: IN2 inserted after the P-th character of IN1;
//!   P in 0..=LEN(IN1) (0 inserts at the front).
//! - `DELETE(IN, L, P)`: removes L characters from position P; P in
//!   1..=LEN+1, L ≥ 0, stopping at the end.
//! - `REPLACE(IN1, IN2, L, P)`: L characters of IN1 from position P replaced
//!   by IN2; P in 1..=LEN+1, L ≥ 0, stopping at the end.
//! - `FIND(IN1, IN2)`: the position of the first occurrence of IN2 in IN1,
//!   0 when absent; an empty IN2 is never found (0).
//! - `CONCAT` takes any number of inputs.
//! - Comparisons are lexicographic by character code; a prefix is smaller
//!   ('AB' < 'ABC' < 'B').
//! - A position or length out of range is an [`ErrorKind::StringIndex`]
//!   error whose message names the function, the argument and its value,
//!   e.g. `MID: P = 5 is out of range 1..=4 (IN has 3 characters)`. The
//!   engine turns it into a runtime fault.

#[cfg(test)]
mod tests;

use crate::error::{ErrorKind, IecError};
use std::cmp::Ordering;

/// The value a STRING(`max_len`) holds after assigning `src`: its first
/// `max_len` characters.
pub fn assign<C: Copy>(src: &[C], max_len: usize) -> Vec<C> {
    src[..src.len().min(max_len)].to_vec()
}

/// Cuts `s` to at most `max_len` characters in place.
pub fn truncate<C>(s: &mut Vec<C>, max_len: usize) {
    s.truncate(max_len);
}

/// The characters of a NUL-terminated buffer (as a STRING(n) lies in
/// memory: n + 1 units, the text ending at the first NUL).
pub fn until_nul<C: Copy + Default + PartialEq>(buf: &[C]) -> &[C] {
    let end = buf
        .iter()
        .position(|&c| c == C::default())
        .unwrap_or(buf.len());
    &buf[..end]
}

/// The memory image of `s` in a STRING(`max_len`): `max_len + 1` units, the
/// text truncated to `max_len`, then NUL padding.
pub fn to_buffer<C: Copy + Default>(s: &[C], max_len: usize) -> Vec<C> {
    let mut buf = assign(s, max_len);
    buf.resize(max_len.saturating_add(1), C::default());
    buf
}

/// LEN.
pub fn len<C>(s: &[C]) -> usize {
    s.len()
}

fn index_error(function: &str, argument: &str, value: i64, why: &str, len: usize) -> IecError {
    let input = if matches!(function, "INSERT" | "REPLACE") {
        "IN1"
    } else {
        "IN"
    };
    let plural = if len == 1 { "" } else { "s" };
    IecError::new(
        ErrorKind::StringIndex,
        format!("{function}: {argument} = {value} {why} ({input} has {len} character{plural})"),
    )
}

/// A length argument: must be ≥ 0; returned as usize.
fn length(function: &str, l: i64, len: usize) -> Result<usize, IecError> {
    usize::try_from(l).map_err(|_| index_error(function, "L", l, "is negative", len))
}

/// A 1-based position in 1..=len+1, returned as a 0-based index.
fn position(function: &str, p: i64, len: usize) -> Result<usize, IecError> {
    match usize::try_from(p) {
        Ok(p) if p >= 1 && p <= len + 1 => Ok(p - 1),
        _ => Err(index_error(
            function,
            "P",
            p,
            &format!("is out of range 1..={}", len + 1),
            len,
        )),
    }
}

/// LEFT(IN, L): the first L characters.
pub fn left<C: Copy>(s: &[C], l: i64) -> Result<Vec<C>, IecError> {
    let l = length("LEFT", l, s.len())?;
    Ok(s[..l.min(s.len())].to_vec())
}

/// RIGHT(IN, L): the last L characters.
pub fn right<C: Copy>(s: &[C], l: i64) -> Result<Vec<C>, IecError> {
    let l = length("RIGHT", l, s.len())?;
    Ok(s[s.len() - l.min(s.len())..].to_vec())
}

/// MID(IN, L, P): L characters from position P.
///
/// ```
/// use automat_iec::strings::mid;
/// assert_eq!(mid(b"hello", 3, 2), Ok(b"ell".to_vec()));
/// assert_eq!(mid(b"hello", 9, 4), Ok(b"lo".to_vec()));
/// assert!(mid(b"hello", 1, 0).is_err());
/// ```
pub fn mid<C: Copy>(s: &[C], l: i64, p: i64) -> Result<Vec<C>, IecError> {
    let l = length("MID", l, s.len())?;
    let start = position("MID", p, s.len())?;
    let end = start.saturating_add(l).min(s.len());
    Ok(s[start..end].to_vec())
}

/// CONCAT(IN1, IN2, ...).
pub fn concat<C: Copy>(parts: &[&[C]]) -> Vec<C> {
    parts.concat()
}

/// INSERT(IN1, IN2, P): IN2 after the P-th character of IN1.
pub fn insert<C: Copy>(in1: &[C], in2: &[C], p: i64) -> Result<Vec<C>, IecError> {
    let at = match usize::try_from(p) {
        Ok(p) if p <= in1.len() => p,
        _ => {
            let range = format!("is out of range 0..={}", in1.len());
            return Err(index_error("INSERT", "P", p, &range, in1.len()));
        }
    };
    Ok([&in1[..at], in2, &in1[at..]].concat())
}

/// DELETE(IN, L, P): IN without L characters from position P.
pub fn delete<C: Copy>(s: &[C], l: i64, p: i64) -> Result<Vec<C>, IecError> {
    let l = length("DELETE", l, s.len())?;
    let start = position("DELETE", p, s.len())?;
    let end = start.saturating_add(l).min(s.len());
    Ok([&s[..start], &s[end..]].concat())
}

/// REPLACE(IN1, IN2, L, P): L characters of IN1 from position P replaced by IN2.
pub fn replace<C: Copy>(in1: &[C], in2: &[C], l: i64, p: i64) -> Result<Vec<C>, IecError> {
    let l = length("REPLACE", l, in1.len())?;
    let start = position("REPLACE", p, in1.len())?;
    let end = start.saturating_add(l).min(in1.len());
    Ok([&in1[..start], in2, &in1[end..]].concat())
}

/// FIND(IN1, IN2): 1-based position of IN2 in IN1, 0 when absent or empty.
pub fn find<C: PartialEq>(in1: &[C], in2: &[C]) -> usize {
    if in2.is_empty() {
        return 0;
    }
    in1.windows(in2.len())
        .position(|w| w == in2)
        .map_or(0, |i| i + 1)
}

/// String comparison: lexicographic by character code.
pub fn compare<C: Ord>(a: &[C], b: &[C]) -> Ordering {
    a.cmp(b)
}
