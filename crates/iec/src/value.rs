//! [`Value`]: one value of an elementary type, as plain Rust data.
//!
//! Representation (the same everywhere in this crate):
//! - BOOL: `Bool`.
//! - Integers and bit strings (SINT..ULINT, BYTE..LWORD): `Int(v, ty)` with
//!   `v` in the range of `ty` (an `i128` holds every width, signed or not).
//! - REAL, LREAL: `Real(v, ty)`; a REAL is an `f64` that is exactly an
//!   `f32` (constructors round it).
//! - TIME, LTIME: `Duration(ns, ty)`, signed nanoseconds.
//! - DATE, LDATE: `Date(days, ty)`, days since 1970-01-01 (proleptic
//!   Gregorian calendar). LDATE has the same representation: a whole day.
//! - TOD, LTOD: `Tod(ns, ty)`, nanoseconds since midnight, 0 ≤ ns < 24 h.
//! - DT, LDT: `Dt(ns, ty)`, nanoseconds since 1970-01-01-00:00:00 (the
//!   range of `i64`: years 1677 to 2262).
//! - STRING: `Str(bytes)` (one byte a character, Latin-1), WSTRING:
//!   `WStr(units)` (UCS-2 code units), CHAR: `Char`, WCHAR: `WChar`.
//!
//! The short and long time types share a representation: TIME holds
//! nanoseconds too, so `TIME` and `LTIME` differ only in how they convert to
//! numbers and print (see `crate::convert` and `crate::format`).

use crate::elementary::Elementary;

/// A value of an elementary type.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Bool(bool),
    Int(i128, Elementary),
    Real(f64, Elementary),
    Duration(i64, Elementary),
    Date(i64, Elementary),
    Tod(i64, Elementary),
    Dt(i64, Elementary),
    Str(Vec<u8>),
    WStr(Vec<u16>),
    Char(u8),
    WChar(u16),
}

impl Value {
    /// The type of the value.
    pub fn ty(&self) -> Elementary {
        match self {
            Value::Bool(_) => Elementary::Bool,
            Value::Int(_, t)
            | Value::Real(_, t)
            | Value::Duration(_, t)
            | Value::Date(_, t)
            | Value::Tod(_, t)
            | Value::Dt(_, t) => *t,
            Value::Str(_) => Elementary::String,
            Value::WStr(_) => Elementary::Wstring,
            Value::Char(_) => Elementary::Char,
            Value::WChar(_) => Elementary::Wchar,
        }
    }

    /// An integer or bit string of type `ty`, wrapped into its range (two's
    /// complement, as [`crate::convert::wrap_int`]). A `ty` that is not an
    /// integer or bit string gives a LINT.
    pub fn int(v: i128, ty: Elementary) -> Value {
        let ty = if ty.is_integral() {
            ty
        } else {
            Elementary::Lint
        };
        Value::Int(crate::convert::wrap_int(v, ty), ty)
    }

    /// A REAL (rounded to `f32`) or, for any other `ty`, an LREAL.
    pub fn real(v: f64, ty: Elementary) -> Value {
        if ty == Elementary::Real {
            Value::Real(f64::from(v as f32), ty)
        } else {
            Value::Real(v, Elementary::Lreal)
        }
    }

    /// A TIME of `ns` nanoseconds.
    pub fn time(ns: i64) -> Value {
        Value::Duration(ns, Elementary::Time)
    }

    /// An LTIME of `ns` nanoseconds.
    pub fn ltime(ns: i64) -> Value {
        Value::Duration(ns, Elementary::Ltime)
    }

    /// A DATE `days` after 1970-01-01.
    pub fn date(days: i64) -> Value {
        Value::Date(days, Elementary::Date)
    }

    /// A TOD `ns` after midnight, brought into one day (modulo 24 h).
    pub fn tod(ns: i64) -> Value {
        Value::Tod(ns.rem_euclid(crate::time::NS_PER_DAY), Elementary::Tod)
    }

    /// A DT `ns` after 1970-01-01-00:00:00.
    pub fn dt(ns: i64) -> Value {
        Value::Dt(ns, Elementary::Dt)
    }

    /// A STRING from Rust text: characters up to U+00FF become one byte,
    /// any other becomes `?` (STRING holds one byte a character).
    pub fn string(text: &str) -> Value {
        Value::Str(text.chars().map(crate::convert::char_to_byte).collect())
    }

    /// A WSTRING from Rust text (UTF-16 code units).
    pub fn wstring(text: &str) -> Value {
        Value::WStr(text.encode_utf16().collect())
    }

    /// The default (initial) value of a type: 0, FALSE, T#0s, D#1970-01-01,
    /// TOD#00:00:00, DT#1970-01-01-00:00:00, empty strings, NUL characters.
    pub fn default_of(ty: Elementary) -> Value {
        use Elementary as E;
        match ty {
            E::Bool => Value::Bool(false),
            E::Real | E::Lreal => Value::Real(0.0, ty),
            E::Time | E::Ltime => Value::Duration(0, ty),
            E::Date | E::Ldate => Value::Date(0, ty),
            E::Tod | E::Ltod => Value::Tod(0, ty),
            E::Dt | E::Ldt => Value::Dt(0, ty),
            E::String => Value::Str(Vec::new()),
            E::Wstring => Value::WStr(Vec::new()),
            E::Char => Value::Char(0),
            E::Wchar => Value::WChar(0),
            _ => Value::Int(0, ty),
        }
    }

    /// The smallest value of a type; `None` for STRING and WSTRING. For REAL
    /// and LREAL it is the most negative finite value. TOD's is midnight.
    pub fn min_of(ty: Elementary) -> Option<Value> {
        Self::limit(ty, false)
    }

    /// The largest value of a type; `None` for STRING and WSTRING. TOD's is
    /// one nanosecond before midnight; DATE's is the date of the last DT.
    pub fn max_of(ty: Elementary) -> Option<Value> {
        Self::limit(ty, true)
    }

    fn limit(ty: Elementary, max: bool) -> Option<Value> {
        use Elementary as E;
        let pick = |lo: i64, hi: i64| if max { hi } else { lo };
        Some(match ty {
            E::Bool => Value::Bool(max),
            E::Real | E::Lreal => {
                let (lo, hi) = ty.real_range()?;
                Value::Real(if max { hi } else { lo }, ty)
            }
            E::Time | E::Ltime => Value::Duration(pick(i64::MIN, i64::MAX), ty),
            E::Date | E::Ldate => Value::Date(
                pick(
                    i64::MIN.div_euclid(crate::time::NS_PER_DAY),
                    i64::MAX.div_euclid(crate::time::NS_PER_DAY),
                ),
                ty,
            ),
            E::Tod | E::Ltod => Value::Tod(pick(0, crate::time::NS_PER_DAY - 1), ty),
            E::Dt | E::Ldt => Value::Dt(pick(i64::MIN, i64::MAX), ty),
            E::Char => Value::Char(if max { u8::MAX } else { 0 }),
            E::Wchar => Value::WChar(if max { u16::MAX } else { 0 }),
            E::String | E::Wstring => return None,
            _ => {
                let (lo, hi) = ty.int_range()?;
                Value::Int(if max { hi } else { lo }, ty)
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Elementary as E;

    #[test]
    fn constructors_normalise() {
        assert_eq!(Value::int(300, E::Usint), Value::Int(44, E::Usint));
        assert_eq!(Value::int(-1, E::Word), Value::Int(65535, E::Word));
        assert_eq!(Value::int(5, E::Time), Value::Int(5, E::Lint));
        assert_eq!(
            Value::real(0.1, E::Real),
            Value::Real(0.10000000149011612, E::Real)
        );
        assert_eq!(Value::real(0.1, E::Lreal), Value::Real(0.1, E::Lreal));
        assert_eq!(Value::tod(-1), Value::Tod(86_399_999_999_999, E::Tod));
        assert_eq!(
            Value::string("a\u{e9}\u{20ac}"),
            Value::Str(vec![b'a', 0xE9, b'?'])
        );
        assert_eq!(Value::wstring("a\u{20ac}"), Value::WStr(vec![0x61, 0x20AC]));
    }

    #[test]
    fn types_defaults_and_limits() {
        for e in Elementary::ALL {
            assert_eq!(Value::default_of(e).ty(), e);
            if let Some(v) = Value::min_of(e) {
                assert_eq!(v.ty(), e);
            }
        }
        assert_eq!(Value::min_of(E::Sint), Some(Value::Int(-128, E::Sint)));
        assert_eq!(
            Value::max_of(E::Udint),
            Some(Value::Int(4294967295, E::Udint))
        );
        assert_eq!(Value::max_of(E::Bool), Some(Value::Bool(true)));
        assert_eq!(
            Value::max_of(E::Tod),
            Some(Value::Tod(86_399_999_999_999, E::Tod))
        );
        assert_eq!(Value::max_of(E::Date), Some(Value::Date(106_751, E::Date)));
        assert_eq!(Value::min_of(E::Date), Some(Value::Date(-106_752, E::Date)));
        assert_eq!(Value::max_of(E::Wchar), Some(Value::WChar(65535)));
        assert_eq!(Value::max_of(E::String), None);
    }

    #[test]
    fn defaults_are_zero_like() {
        assert_eq!(Value::default_of(E::Bool), Value::Bool(false));
        assert_eq!(Value::default_of(E::Lword), Value::Int(0, E::Lword));
        assert_eq!(Value::default_of(E::Real), Value::Real(0.0, E::Real));
        assert_eq!(Value::default_of(E::Ltime), Value::Duration(0, E::Ltime));
        assert_eq!(Value::default_of(E::Ldt), Value::Dt(0, E::Ldt));
        assert_eq!(Value::default_of(E::String), Value::Str(Vec::new()));
        assert_eq!(Value::default_of(E::Wchar), Value::WChar(0));
        assert_eq!(
            Value::min_of(E::Lreal),
            Some(Value::Real(f64::MIN, E::Lreal))
        );
        assert_eq!(
            Value::min_of(E::Time),
            Some(Value::Duration(i64::MIN, E::Time))
        );
        assert_eq!(Value::min_of(E::Tod), Some(Value::Tod(0, E::Tod)));
    }
}
