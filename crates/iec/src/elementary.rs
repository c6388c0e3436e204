//! The elementary data types of IEC 61131-3 (3rd edition, table 10).
//!
//! Rules:
//! - Names are case-insensitive. `TIME_OF_DAY`, `DATE_AND_TIME`,
//!   `LTIME_OF_DAY` and `LDATE_AND_TIME` are aliases of `TOD`, `DT`, `LTOD`
//!   and `LDT`; [`Elementary::name`] gives the short spelling.
//! - Widths are the storage widths automat uses: BOOL is 1 bit (stored in a
//!   byte), integers and bit strings their IEC width, every time and date
//!   type 64 bits (signed nanosecond or day counts, see `crate::time`),
//!   CHAR 8 and WCHAR 16 bits. STRING and WSTRING have no fixed width.
//! - Categories follow the standard's generic types: ANY_INT, ANY_BIT
//!   (BOOL included), ANY_REAL, ANY_NUM, ANY_DURATION, ANY_DATE (DATE, TOD,
//!   DT and their long forms), ANY_CHAR, ANY_STRING.

use std::fmt;
use std::str::FromStr;

/// An IEC 61131-3 elementary type.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Elementary {
    Bool,
    Sint,
    Int,
    Dint,
    Lint,
    Usint,
    Uint,
    Udint,
    Ulint,
    Real,
    Lreal,
    Byte,
    Word,
    Dword,
    Lword,
    Time,
    Ltime,
    Date,
    Ldate,
    Tod,
    Ltod,
    Dt,
    Ldt,
    Char,
    Wchar,
    String,
    Wstring,
}

use Elementary as E;

impl Elementary {
    /// Every elementary type, in the order of the enum.
    pub const ALL: [Elementary; 27] = [
        E::Bool,
        E::Sint,
        E::Int,
        E::Dint,
        E::Lint,
        E::Usint,
        E::Uint,
        E::Udint,
        E::Ulint,
        E::Real,
        E::Lreal,
        E::Byte,
        E::Word,
        E::Dword,
        E::Lword,
        E::Time,
        E::Ltime,
        E::Date,
        E::Ldate,
        E::Tod,
        E::Ltod,
        E::Dt,
        E::Ldt,
        E::Char,
        E::Wchar,
        E::String,
        E::Wstring,
    ];

    /// The canonical upper-case spelling (`TOD`, not `TIME_OF_DAY`).
    pub fn name(self) -> &'static str {
        match self {
            E::Bool => "BOOL",
            E::Sint => "SINT",
            E::Int => "INT",
            E::Dint => "DINT",
            E::Lint => "LINT",
            E::Usint => "USINT",
            E::Uint => "UINT",
            E::Udint => "UDINT",
            E::Ulint => "ULINT",
            E::Real => "REAL",
            E::Lreal => "LREAL",
            E::Byte => "BYTE",
            E::Word => "WORD",
            E::Dword => "DWORD",
            E::Lword => "LWORD",
            E::Time => "TIME",
            E::Ltime => "LTIME",
            E::Date => "DATE",
            E::Ldate => "LDATE",
            E::Tod => "TOD",
            E::Ltod => "LTOD",
            E::Dt => "DT",
            E::Ldt => "LDT",
            E::Char => "CHAR",
            E::Wchar => "WCHAR",
            E::String => "STRING",
            E::Wstring => "WSTRING",
        }
    }

    /// The type named `name`, in any case, canonical spelling or long alias.
    pub fn from_name(name: &str) -> Option<Elementary> {
        let alias = [
            ("TIME_OF_DAY", E::Tod),
            ("LTIME_OF_DAY", E::Ltod),
            ("DATE_AND_TIME", E::Dt),
            ("LDATE_AND_TIME", E::Ldt),
        ];
        if let Some(&(_, e)) = alias.iter().find(|(a, _)| a.eq_ignore_ascii_case(name)) {
            return Some(e);
        }
        E::ALL
            .iter()
            .copied()
            .find(|e| e.name().eq_ignore_ascii_case(name))
    }

    /// Storage width in bits; `None` for STRING and WSTRING.
    pub fn bit_width(self) -> Option<u32> {
        Some(match self {
            E::Bool => 1,
            E::Sint | E::Usint | E::Byte | E::Char => 8,
            E::Int | E::Uint | E::Word | E::Wchar => 16,
            E::Dint | E::Udint | E::Dword | E::Real => 32,
            E::Lint | E::Ulint | E::Lword | E::Lreal => 64,
            E::Time | E::Ltime | E::Date | E::Ldate => 64,
            E::Tod | E::Ltod | E::Dt | E::Ldt => 64,
            E::String | E::Wstring => return None,
        })
    }

    /// SINT, INT, DINT, LINT.
    pub fn is_signed_int(self) -> bool {
        matches!(self, E::Sint | E::Int | E::Dint | E::Lint)
    }

    /// USINT, UINT, UDINT, ULINT.
    pub fn is_unsigned_int(self) -> bool {
        matches!(self, E::Usint | E::Uint | E::Udint | E::Ulint)
    }

    /// Whether values of the type can be negative (signed integers, reals,
    /// durations).
    pub fn is_signed(self) -> bool {
        self.is_signed_int() || self.is_real() || self.is_duration()
    }

    /// ANY_INT.
    pub fn is_int(self) -> bool {
        self.is_signed_int() || self.is_unsigned_int()
    }

    /// ANY_BIT: BOOL, BYTE, WORD, DWORD, LWORD.
    pub fn is_bit(self) -> bool {
        matches!(self, E::Bool | E::Byte | E::Word | E::Dword | E::Lword)
    }

    /// ANY_BIT without BOOL: the types SHL/SHR/ROL/ROR work on.
    pub fn is_bit_string(self) -> bool {
        matches!(self, E::Byte | E::Word | E::Dword | E::Lword)
    }

    /// ANY_REAL.
    pub fn is_real(self) -> bool {
        matches!(self, E::Real | E::Lreal)
    }

    /// ANY_NUM.
    pub fn is_num(self) -> bool {
        self.is_int() || self.is_real()
    }

    /// ANY_MAGNITUDE: numbers and durations.
    pub fn is_magnitude(self) -> bool {
        self.is_num() || self.is_duration()
    }

    /// Integers and bit strings: the types held as a plain integer.
    pub fn is_integral(self) -> bool {
        self.is_int() || self.is_bit_string()
    }

    /// ANY_DURATION: TIME, LTIME.
    pub fn is_duration(self) -> bool {
        matches!(self, E::Time | E::Ltime)
    }

    /// ANY_DATE: DATE, LDATE, TOD, LTOD, DT, LDT.
    pub fn is_date(self) -> bool {
        matches!(self, E::Date | E::Ldate | E::Tod | E::Ltod | E::Dt | E::Ldt)
    }

    /// ANY_CHAR: CHAR, WCHAR.
    pub fn is_char(self) -> bool {
        matches!(self, E::Char | E::Wchar)
    }

    /// ANY_STRING: STRING, WSTRING.
    pub fn is_string(self) -> bool {
        matches!(self, E::String | E::Wstring)
    }

    /// ANY_CHARS: characters and strings.
    pub fn is_chars(self) -> bool {
        self.is_char() || self.is_string()
    }

    /// The 64-bit-range variants the 3rd edition added: LTIME, LDATE, LTOD, LDT.
    pub fn is_long_time(self) -> bool {
        matches!(self, E::Ltime | E::Ldate | E::Ltod | E::Ldt)
    }

    /// Wide character types (WCHAR, WSTRING).
    pub fn is_wide(self) -> bool {
        matches!(self, E::Wchar | E::Wstring)
    }

    /// Smallest and largest value of BOOL (0, 1), integers, bit strings and
    /// characters (their codes); `None` for other types.
    pub fn int_range(self) -> Option<(i128, i128)> {
        Some(match self {
            E::Bool => (0, 1),
            E::Sint => (i8::MIN.into(), i8::MAX.into()),
            E::Int => (i16::MIN.into(), i16::MAX.into()),
            E::Dint => (i32::MIN.into(), i32::MAX.into()),
            E::Lint => (i64::MIN.into(), i64::MAX.into()),
            E::Usint | E::Byte | E::Char => (0, u8::MAX.into()),
            E::Uint | E::Word | E::Wchar => (0, u16::MAX.into()),
            E::Udint | E::Dword => (0, u32::MAX.into()),
            E::Ulint | E::Lword => (0, u64::MAX.into()),
            _ => return None,
        })
    }

    /// The smallest value, for integers, bit strings, BOOL and characters.
    pub fn min_int(self) -> Option<i128> {
        self.int_range().map(|r| r.0)
    }

    /// The largest value, for integers, bit strings, BOOL and characters.
    pub fn max_int(self) -> Option<i128> {
        self.int_range().map(|r| r.1)
    }

    /// The most negative and most positive finite values of REAL and LREAL.
    pub fn real_range(self) -> Option<(f64, f64)> {
        match self {
            E::Real => Some((f64::from(f32::MIN), f64::from(f32::MAX))),
            E::Lreal => Some((f64::MIN, f64::MAX)),
            _ => None,
        }
    }
}

impl fmt::Display for Elementary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The error of parsing a type name: the text that names no elementary type.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownType(pub String);

impl fmt::Display for UnknownType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "`{}` is not an elementary type", self.0)
    }
}

impl std::error::Error for UnknownType {}

impl FromStr for Elementary {
    type Err = UnknownType;

    fn from_str(s: &str) -> Result<Elementary, UnknownType> {
        Elementary::from_name(s).ok_or_else(|| UnknownType(s.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_round_trips_in_any_case() {
        for e in Elementary::ALL {
            assert_eq!(Elementary::from_name(e.name()), Some(e));
            assert_eq!(Elementary::from_name(&e.name().to_lowercase()), Some(e));
            assert_eq!(e.to_string(), e.name());
        }
    }

    #[test]
    fn aliases_and_unknown_names() {
        assert_eq!(Elementary::from_name("time_of_day"), Some(E::Tod));
        assert_eq!(Elementary::from_name("Date_And_Time"), Some(E::Dt));
        assert_eq!(Elementary::from_name("LTIME_OF_DAY"), Some(E::Ltod));
        assert_eq!(Elementary::from_name("ldate_and_time"), Some(E::Ldt));
        assert_eq!(Elementary::from_name("dInT"), Some(E::Dint));
        assert_eq!(Elementary::from_name("INTEGER"), None);
        assert_eq!(Elementary::from_name(""), None);
        assert_eq!("wstring".parse::<Elementary>(), Ok(E::Wstring));
        assert_eq!(
            "FOO".parse::<Elementary>().map_err(|e| e.to_string()),
            Err("`FOO` is not an elementary type".to_string())
        );
    }

    #[test]
    fn widths() {
        let expect = [
            (E::Bool, Some(1)),
            (E::Sint, Some(8)),
            (E::Usint, Some(8)),
            (E::Byte, Some(8)),
            (E::Char, Some(8)),
            (E::Int, Some(16)),
            (E::Wchar, Some(16)),
            (E::Dword, Some(32)),
            (E::Real, Some(32)),
            (E::Lreal, Some(64)),
            (E::Ulint, Some(64)),
            (E::Time, Some(64)),
            (E::Ldt, Some(64)),
            (E::String, None),
            (E::Wstring, None),
        ];
        for (e, w) in expect {
            assert_eq!(e.bit_width(), w, "{e}");
        }
    }

    #[test]
    fn ranges_of_every_integer_width() {
        assert_eq!(E::Sint.int_range(), Some((-128, 127)));
        assert_eq!(E::Int.int_range(), Some((-32768, 32767)));
        assert_eq!(E::Dint.int_range(), Some((-2147483648, 2147483647)));
        assert_eq!(
            E::Lint.int_range(),
            Some((-9223372036854775808, 9223372036854775807))
        );
        assert_eq!(E::Usint.int_range(), Some((0, 255)));
        assert_eq!(E::Uint.int_range(), Some((0, 65535)));
        assert_eq!(E::Udint.int_range(), Some((0, 4294967295)));
        assert_eq!(E::Ulint.int_range(), Some((0, 18446744073709551615)));
        assert_eq!(E::Lword.max_int(), Some(18446744073709551615));
        assert_eq!(E::Bool.int_range(), Some((0, 1)));
        assert_eq!(E::Wchar.max_int(), Some(65535));
        assert_eq!(E::Real.int_range(), None);
        assert_eq!(E::Time.min_int(), None);
        assert_eq!(
            E::Real.real_range(),
            Some((-3.4028234663852886e38, 3.4028234663852886e38))
        );
        assert_eq!(E::Lreal.real_range(), Some((f64::MIN, f64::MAX)));
        assert_eq!(E::Int.real_range(), None);
    }

    #[test]
    fn categories() {
        let ints: Vec<_> = Elementary::ALL.iter().filter(|e| e.is_int()).collect();
        assert_eq!(ints.len(), 8);
        let bits: Vec<_> = Elementary::ALL.iter().filter(|e| e.is_bit()).collect();
        assert_eq!(bits, [&E::Bool, &E::Byte, &E::Word, &E::Dword, &E::Lword]);
        let dates: Vec<_> = Elementary::ALL.iter().filter(|e| e.is_date()).collect();
        assert_eq!(dates.len(), 6);
        assert!(E::Lreal.is_real() && E::Lreal.is_num() && E::Lreal.is_magnitude());
        assert!(E::Time.is_magnitude() && !E::Time.is_num());
        assert!(!E::Bool.is_bit_string() && E::Byte.is_integral());
        assert!(E::Int.is_signed() && E::Time.is_signed() && !E::Uint.is_signed());
        assert!(!E::Word.is_signed() && !E::Date.is_signed());
        assert!(E::Wchar.is_char() && E::Wchar.is_chars() && E::Wchar.is_wide());
        assert!(E::String.is_string() && !E::String.is_char() && !E::String.is_wide());
        assert!(E::Ltod.is_long_time() && !E::Tod.is_long_time());
        assert!(!E::Char.is_int() && !E::Time.is_int() && !E::Bool.is_num());
    }

    #[test]
    fn integral_types_and_long_time_types() {
        let integral: Vec<_> = Elementary::ALL.iter().filter(|e| e.is_integral()).collect();
        assert_eq!(integral.len(), 12);
        assert!(!E::Bool.is_integral() && !E::Char.is_integral());
        let long: Vec<_> = Elementary::ALL
            .iter()
            .filter(|e| e.is_long_time())
            .collect();
        assert_eq!(long, [&E::Ltime, &E::Ldate, &E::Ltod, &E::Ldt]);
        assert_eq!(Elementary::from_name(" INT"), None);
        assert_eq!(Elementary::from_name("TIME_OF_DAY_"), None);
        assert_eq!(Elementary::ALL.len(), 27);
        assert_eq!(Elementary::ALL.iter().filter(|e| e.is_string()).count(), 2);
    }
}
