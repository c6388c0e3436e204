//! The printed form of values — the output contract of `automat run
//! --print` — and its inverse, [`parse_literal`], used by forcing and
//! scenario files. `parse_literal(&format_value(v), v.ty())` gives `v` back
//! for every valid value (REAL/LREAL bit for bit, NaN as some NaN).
//!
//! Printed forms (exact):
//! - BOOL: `TRUE`, `FALSE`.
//! - Integers and bit strings: decimal, `-` for negatives (`255` for
//!   BYTE 16#FF).
//! - REAL/LREAL: the shortest decimal that reads back to the same value at
//!   the type's precision (REAL 0.1 prints `0.1`, not
//!   `0.100000001490116`), always with a `.` or an exponent, Python-`repr`
//!   style: `3.5`, `4.0`, `-0.0`, `0.0001`, `1e-05`, `1.5e+20`,
//!   `1234567890123456.0`, `1e+16`. Exponent form is used when the decimal
//!   exponent is below −4 or at least 16, with a sign and at least two
//!   digits. Infinities and NaN print as `inf`, `-inf` and `nan` (IEC has
//!   no literal for them; these read back with `parse_literal`, any case).
//! - TIME: `T#` then the non-zero units from days down to nanoseconds:
//!   `T#1s500ms`, `T#1d2h3m4s5ms`, `T#1ms500us`, `T#250ns`, `T#-5s`
//!   (sign first), `T#0s` for zero. LTIME the same with `LTIME#`.
//! - DATE: `D#2024-01-31` (LDATE: `LDATE#...`); years before 1 print with a
//!   sign and at least four digits.
//! - TOD: `TOD#12:30:00`, with a fraction of the second when there is one,
//!   without trailing zeros: `TOD#12:30:00.5`, `TOD#00:00:00.000000001`
//!   (LTOD: `LTOD#...`).
//! - DT: `DT#2024-01-31-12:30:00`, fraction as for TOD (LDT: `LDT#...`).
//! - STRING: `'abc'` in single quotes; `$'` for a quote, `$$` for a dollar,
//!   `$N` `$R` `$T` `$P` for line feed, carriage return, tab and form feed,
//!   and `$hh` (two upper-case hex digits) for every other byte outside
//!   printable ASCII. CHAR: the same, one character: `'a'`.
//! - WSTRING: `"abc"` in double quotes; `$"` for a double quote, the same
//!   named escapes, letters and digits of any script, the visible Latin-1
//!   signs and `€` as themselves, and `$hhhh` for other code units. WCHAR: `"a"`.
//!
//! Accepted by [`parse_literal`] (surrounding spaces ignored, keywords and
//! prefixes in any case): everything above, and
//! - a typed prefix naming the type: `INT#-5`, `BYTE#16#FF`, `BOOL#1`,
//!   `STRING#'a'`; for time types any prefix of the same family (`T#`,
//!   `TIME#`, `LT#`, `LTIME#` for TIME and LTIME; `D#`/`DATE#`/`LD#`/
//!   `LDATE#`; `TOD#`/`TIME_OF_DAY#`/`LTOD#`/`LTIME_OF_DAY#`;
//!   `DT#`/`DATE_AND_TIME#`/`LDT#`/`LDATE_AND_TIME#`), or no prefix at all
//!   (`1s500ms`, `2024-01-31`);
//! - integers in base 2, 8, 16 (`2#1010`, `8#17`, `16#FF`) with single
//!   underscores between digits; for a signed type a based literal may give
//!   the bit pattern (`INT#16#FFFF` is −1);
//! - BOOL `0` and `1`; reals with or without fraction or exponent (`5`,
//!   `1e3`, `1.5E-3`), `inf`, `infinity`, `nan` with an optional sign;
//! - durations with a fraction on the last unit (`T#1.5s`) and `_` between
//!   units (`T#1d_2h`); units must decrease and appear once;
//! - string escapes `$L` (line feed) and lower-case escape letters.
//!
//! A value that does not fit the type (`USINT#256`, `REAL#1e39`,
//! `T#200000d`) is an [`ErrorKind::OutOfRange`] error, an impossible date or
//! time an [`ErrorKind::InvalidDate`] error, anything else malformed an
//! [`ErrorKind::Parse`] error; each message quotes the text and says why.

mod datetime;
mod parse;
mod parse_time;
mod quote;
mod real;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_edges;
#[cfg(test)]
mod tests_parse;

pub use datetime::{format_date, format_dt, format_duration, format_tod};
pub use parse::parse_literal;
pub use quote::{quote_char, quote_string, quote_wchar, quote_wstring};
pub use real::{format_lreal, format_real};

use crate::elementary::Elementary as E;
#[cfg(doc)]
use crate::error::ErrorKind;
use crate::value::Value;

/// The printed form of a value (see the module rules).
pub fn format_value(v: &Value) -> String {
    match v {
        Value::Bool(b) => if *b { "TRUE" } else { "FALSE" }.to_string(),
        Value::Int(i, _) => i.to_string(),
        // A REAL holds an f32 value exactly, so the cast is lossless.
        Value::Real(r, E::Real) => format_real(*r as f32),
        Value::Real(r, _) => format_lreal(*r),
        Value::Duration(ns, ty) => format_duration(*ns, *ty == E::Ltime),
        Value::Date(days, ty) => format_date(*days, *ty == E::Ldate),
        Value::Tod(ns, ty) => format_tod(*ns, *ty == E::Ltod),
        Value::Dt(ns, ty) => format_dt(*ns, *ty == E::Ldt),
        Value::Str(s) => quote_string(s),
        Value::WStr(w) => quote_wstring(w),
        Value::Char(c) => quote_char(*c),
        Value::WChar(c) => quote_wchar(*c),
    }
}
