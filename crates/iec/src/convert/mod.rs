//! Type conversions: every `*_TO_*` function of IEC 61131-3 (3rd edition,
//! tables 22 to 27), `TRUNC` and the BCD conversions.
//!
//! [`convert`] works on [`Value`]s; the typed helpers ([`round_to`],
//! [`trunc_to`], [`int_to`], [`int_to_f32`], [`lreal_to_real`], ...) are the
//! fast paths an engine calls on plain Rust numbers. Both follow these rules:
//!
//! - **Integer → narrower integer or bit string, and between bit strings:**
//!   two's-complement wrap, the low bits are kept (INT 300 → USINT 44,
//!   DINT 40000 → INT −25536, SINT −1 → BYTE 255), as CODESYS and TwinCAT do.
//! - **REAL/LREAL → integer:** rounded to nearest, halves to even (IEC 60559):
//!   2.5 → 2, 3.5 → 4, −1.5 → −2. Out of the target's range it saturates at
//!   the type's minimum or maximum (1e10 → DINT 2147483647); NaN gives 0.
//!   `TRUNC` and `*_TRUNC_*` truncate toward zero, with the same saturation.
//! - **Integer → REAL/LREAL:** rounded to nearest even (16777217 → REAL
//!   16777216.0); LREAL → REAL the same, beyond REAL's range it is ±inf.
//! - **BOOL → number:** 0 or 1. **Number → BOOL:** TRUE when ≠ 0 (NaN
//!   is ≠ 0, so TRUE).
//! - **Time and date ↔ numbers:** the number counts TIME and TOD in
//!   milliseconds, DATE and DT in seconds since 1970-01-01-00:00:00, and the
//!   long types (LTIME, LTOD, LDATE, LDT) in nanoseconds, as CODESYS does
//!   (TIME_TO_DINT(T#1s) = 1000, LTIME_TO_LINT(LTIME#1s) = 1000000000,
//!   DT_TO_UDINT(DT#1970-01-02-00:00:00) = 86400). Toward a number,
//!   durations truncate toward zero and instants round down; the count then
//!   wraps into the integer type. To REAL/LREAL the fraction is kept.
//!   From a number, the count is a LINT first (reals rounded as above), the
//!   nanosecond total wraps into 64 bits, a DATE keeps the day the instant
//!   falls in and a TOD is taken modulo 24 h.
//! - **Between time types:** TIME ↔ LTIME, TOD ↔ LTOD, DATE ↔ LDATE,
//!   DT ↔ LDT keep the value (all are nanoseconds here). DT_TO_DATE and
//!   DT_TO_TOD split the instant (rounding down before 1970); DATE_TO_DT is
//!   midnight of that day (overflow of 64-bit nanoseconds is an error).
//! - **BCD:** `BCD_TO_*` and `*_BCD_TO_*` read one decimal digit a nibble;
//!   a nibble above 9 is an [`ErrorKind::Bcd`] error. `*_TO_BCD` of a
//!   negative number or one with too many digits for the target (BYTE: 99,
//!   WORD: 9999, ...) is the same error.
//! - **To STRING/WSTRING:** the printed form of [`crate::format`] without
//!   quotes: `42`, `-7`, `0.1` (shortest text that reads back to the same
//!   REAL), `TRUE`, `T#1s500ms`, `D#2024-01-31`, `TOD#12:30:00.5`,
//!   `DT#2024-01-31-12:30:00`; a CHAR becomes a one-character string.
//! - **From STRING/WSTRING:** the text, with surrounding spaces ignored, must
//!   be a literal of the target type as [`crate::format::parse_literal`]
//!   reads it (`16#FF`, `-5`, `INT#7`, `1.5e3`, `T#1s`, `D#2024-01-31`,
//!   `TRUE`); integer targets accept a real number and round it. Anything
//!   else is an [`ErrorKind::Parse`] error, a number that does not fit the
//!   target an [`ErrorKind::OutOfRange`] error (no wrap for text).
//!   STRING_TO_CHAR gives the first character (NUL for an empty string).
//! - **STRING ↔ WSTRING, CHAR ↔ WCHAR:** bytes are Latin-1, zero-extended to
//!   UCS-2; units above 16#FF become `?`.
//! - **CHAR/WCHAR ↔ integers and bit strings:** the character code, wrapped.
//! - Conversions the standard does not define (TIME ↔ DATE, BOOL → TIME,
//!   REAL → CHAR, TOD → DT, ...) are [`ErrorKind::NotConvertible`] errors;
//!   [`is_convertible`] answers without a value.

mod bcd;
mod names;
mod numeric;
mod text;
mod timeconv;

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_edges;
#[cfg(test)]
mod tests_text;

pub use bcd::{bcd_decode, bcd_encode, bcd_to_int, int_to_bcd};
pub use names::{conversion_by_name, Conversion};
pub use numeric::{
    bool_to, int_to, int_to_f32, int_to_f64, int_to_real, lreal_to_real, real_to_bool, real_to_int,
    round_to, trunc_to, wrap_int,
};
pub use text::{
    char_to_byte, latin1_text, str_to_wstr, to_text_bytes, to_text_units, ucs2_text, unit_to_byte,
    wstr_to_str,
};
pub use timeconv::unit_ns;

use crate::elementary::Elementary as E;
use crate::error::{ErrorKind, IecError};
use crate::value::Value;

/// Whether `<from>_TO_<to>` is defined (see the module rules).
pub fn is_convertible(from: E, to: E) -> bool {
    if from == to || from.is_string() || to.is_string() {
        return true;
    }
    let number = |e: E| e.is_integral() || e.is_real();
    match to {
        E::Bool => from == E::Bool || number(from),
        t if t.is_integral() => {
            from == E::Bool
                || number(from)
                || from.is_char()
                || from.is_duration()
                || from.is_date()
        }
        t if t.is_real() => from == E::Bool || number(from) || from.is_duration() || from.is_date(),
        E::Time | E::Ltime => number(from) || from.is_duration(),
        E::Date | E::Ldate => number(from) || matches!(from, E::Date | E::Ldate | E::Dt | E::Ldt),
        E::Tod | E::Ltod => number(from) || matches!(from, E::Tod | E::Ltod | E::Dt | E::Ldt),
        E::Dt | E::Ldt => number(from) || matches!(from, E::Date | E::Ldate | E::Dt | E::Ldt),
        E::Char | E::Wchar => from.is_integral() || from.is_char(),
        _ => false,
    }
}

pub(crate) fn not_convertible(from: E, to: E) -> IecError {
    IecError::new(
        ErrorKind::NotConvertible,
        format!("{from}_TO_{to}: there is no conversion from {from} to {to}"),
    )
}

/// `<v's type>_TO_<to>` (and the overloaded `TO_<to>`).
pub fn convert(v: &Value, to: E) -> Result<Value, IecError> {
    let from = v.ty();
    if !is_convertible(from, to) {
        return Err(not_convertible(from, to));
    }
    match v {
        Value::Str(s) => return text::from_str_bytes(s, to),
        Value::WStr(w) => return text::from_wstr_units(w, to),
        _ => {}
    }
    Ok(match to {
        E::String => Value::Str(to_text_bytes(v)),
        E::Wstring => Value::WStr(to_text_units(v)),
        E::Bool => Value::Bool(match v {
            Value::Bool(b) => *b,
            Value::Int(i, _) => *i != 0,
            Value::Real(r, _) => real_to_bool(*r),
            _ => return Err(not_convertible(from, to)),
        }),
        t if t.is_integral() => Value::Int(
            match v {
                Value::Bool(b) => i128::from(*b),
                Value::Int(i, _) => wrap_int(*i, t),
                Value::Real(r, _) => real_to_int(*r, t, false),
                Value::Char(c) => wrap_int(i128::from(*c), t),
                Value::WChar(c) => wrap_int(i128::from(*c), t),
                _ => wrap_int(
                    timeconv::count(v).ok_or_else(|| not_convertible(from, to))?,
                    t,
                ),
            },
            t,
        ),
        t if t.is_real() => Value::real(
            match v {
                Value::Bool(b) => f64::from(u8::from(*b)),
                Value::Int(i, _) => int_to_real(*i, t),
                Value::Real(r, _) => *r,
                _ => timeconv::count_real(v).ok_or_else(|| not_convertible(from, to))?,
            },
            t,
        ),
        E::Char => Value::Char(match v {
            Value::Int(i, _) => wrap_int(*i, E::Char) as u8,
            Value::Char(c) => *c,
            Value::WChar(u) => unit_to_byte(*u),
            _ => return Err(not_convertible(from, to)),
        }),
        E::Wchar => Value::WChar(match v {
            Value::Int(i, _) => wrap_int(*i, E::Wchar) as u16,
            Value::Char(c) => u16::from(*c),
            Value::WChar(u) => *u,
            _ => return Err(not_convertible(from, to)),
        }),
        // Time and date targets.
        _ => match v {
            Value::Int(i, _) => timeconv::from_count(*i, to),
            Value::Real(r, _) => timeconv::from_count(real_to_int(*r, E::Lint, false), to),
            _ => timeconv::between(v, to, &format!("{from}_TO_{to}"))?,
        },
    })
}

/// `TRUNC` / `<from>_TRUNC_<to>`: a REAL or LREAL truncated toward zero
/// into integer type `to` (saturating, NaN → 0).
pub fn trunc(v: &Value, to: E) -> Result<Value, IecError> {
    match v {
        Value::Real(r, _) if to.is_int() => Ok(Value::Int(real_to_int(*r, to, true), to)),
        _ => Err(IecError::new(
            ErrorKind::NotConvertible,
            format!(
                "{}_TRUNC_{to}: TRUNC takes a REAL or LREAL and gives an integer type",
                v.ty()
            ),
        )),
    }
}

/// `BCD_TO_<to>` / `<from>_BCD_TO_<to>` on values: a bit string read as BCD
/// into integer type `to`.
pub fn from_bcd(v: &Value, to: E) -> Result<Value, IecError> {
    match v {
        Value::Int(bits, from) if from.is_bit_string() && to.is_int() => {
            let bits = u64::try_from(*bits).unwrap_or(0);
            bcd_to_int(bits, *from, to).map(|n| Value::Int(n, to))
        }
        _ => Err(IecError::new(
            ErrorKind::NotConvertible,
            format!(
                "{}_BCD_TO_{to}: BCD conversions read a bit string (BYTE..LWORD) into an integer type",
                v.ty()
            ),
        )),
    }
}

/// `<from>_TO_BCD_<to>` on values: integer `v` as BCD in bit string `to`.
pub fn to_bcd(v: &Value, to: E) -> Result<Value, IecError> {
    match v {
        Value::Int(n, from) if from.is_int() && to.is_bit_string() => {
            int_to_bcd(*n, *from, to).map(|bits| Value::Int(i128::from(bits), to))
        }
        _ => Err(IecError::new(
            ErrorKind::NotConvertible,
            format!(
                "{}_TO_BCD_{to}: BCD conversions write an integer into a bit string (BYTE..LWORD)",
                v.ty()
            ),
        )),
    }
}
