//! `parse_literal`: the accepted forms and the errors.

use super::*;
use crate::elementary::Elementary as E;
use crate::error::ErrorKind;
use crate::value::Value;

fn ok(text: &str, ty: E) -> Value {
    match parse_literal(text, ty) {
        Ok(v) => v,
        Err(e) => panic!("{text} as {ty}: {e}"),
    }
}

fn err(text: &str, ty: E) -> (ErrorKind, String) {
    match parse_literal(text, ty) {
        Ok(v) => panic!("{text} as {ty} gave {v:?}"),
        Err(e) => (e.kind, e.message),
    }
}

#[test]
fn booleans() {
    assert_eq!(ok("TRUE", E::Bool), Value::Bool(true));
    assert_eq!(ok(" false ", E::Bool), Value::Bool(false));
    assert_eq!(ok("1", E::Bool), Value::Bool(true));
    assert_eq!(ok("bool#0", E::Bool), Value::Bool(false));
    assert_eq!(
        err("yes", E::Bool),
        (
            ErrorKind::Parse,
            "`yes` is not a valid BOOL literal: expected TRUE, FALSE, 1 or 0".to_string()
        )
    );
}

#[test]
fn integers_in_every_form() {
    assert_eq!(ok("42", E::Int), Value::Int(42, E::Int));
    assert_eq!(ok("-32768", E::Int), Value::Int(-32768, E::Int));
    assert_eq!(ok("+7", E::Sint), Value::Int(7, E::Sint));
    assert_eq!(ok("1_000_000", E::Dint), Value::Int(1_000_000, E::Dint));
    assert_eq!(ok("16#FF", E::Byte), Value::Int(255, E::Byte));
    assert_eq!(ok("16#ff_ff", E::Word), Value::Int(65535, E::Word));
    assert_eq!(ok("2#1010", E::Usint), Value::Int(10, E::Usint));
    assert_eq!(ok("8#777", E::Uint), Value::Int(511, E::Uint));
    assert_eq!(ok("INT#-5", E::Int), Value::Int(-5, E::Int));
    assert_eq!(
        ok("dword#16#DEADBEEF", E::Dword),
        Value::Int(0xDEAD_BEEF, E::Dword)
    );
    assert_eq!(ok("INT#16#FFFF", E::Int), Value::Int(-1, E::Int));
    assert_eq!(ok("16#80", E::Sint), Value::Int(-128, E::Sint));
    assert_eq!(
        ok("18446744073709551615", E::Ulint),
        Value::Int(18446744073709551615, E::Ulint)
    );
    assert_eq!(
        ok("-9223372036854775808", E::Lint),
        Value::Int(-9223372036854775808, E::Lint)
    );
}

#[test]
fn integer_errors() {
    assert_eq!(
        err("256", E::Usint),
        (
            ErrorKind::OutOfRange,
            "`256` is not a valid USINT literal: 256 is out of range 0..=255".to_string()
        )
    );
    assert_eq!(err("-1", E::Word).0, ErrorKind::OutOfRange);
    assert_eq!(err("32768", E::Int).0, ErrorKind::OutOfRange);
    assert_eq!(err("16#10000", E::Int).0, ErrorKind::OutOfRange);
    assert_eq!(
        err("18446744073709551616", E::Ulint).0,
        ErrorKind::OutOfRange
    );
    assert_eq!(err(&"9".repeat(100), E::Lint).0, ErrorKind::OutOfRange);
    assert_eq!(
        err("16#G0", E::Word).1,
        "`16#G0` is not a valid WORD literal: `G` is not a base-16 digit"
    );
    assert_eq!(
        err("7#1", E::Int).1,
        "`7#1` is not a valid INT literal: the base must be 2, 8 or 16, not `7`"
    );
    assert_eq!(
        err("DINT#5", E::Int).1,
        "`DINT#5` is not a valid INT literal: the prefix `DINT#` does not name INT"
    );
    for bad in [
        "", "   ", "1__0", "_1", "1_", "16#", "1.5", "abc", "--1", "INT#",
    ] {
        assert_eq!(err(bad, E::Int).0, ErrorKind::Parse, "{bad:?}");
    }
}

#[test]
fn reals() {
    assert_eq!(ok("1.5", E::Lreal), Value::Real(1.5, E::Lreal));
    assert_eq!(ok("-2", E::Lreal), Value::Real(-2.0, E::Lreal));
    assert_eq!(ok("1e3", E::Real), Value::Real(1000.0, E::Real));
    assert_eq!(ok("1.5E-3", E::Lreal), Value::Real(0.0015, E::Lreal));
    assert_eq!(ok("1_000.25", E::Lreal), Value::Real(1000.25, E::Lreal));
    assert_eq!(
        ok("REAL#0.1", E::Real),
        Value::Real(f64::from(0.1f32), E::Real)
    );
    assert_eq!(ok("-inf", E::Real), Value::Real(f64::NEG_INFINITY, E::Real));
    assert_eq!(
        ok("INFINITY", E::Lreal),
        Value::Real(f64::INFINITY, E::Lreal)
    );
    assert_eq!(ok("-0.0", E::Lreal), Value::Real(-0.0, E::Lreal));
    assert!(ok("-0.0", E::Lreal) != Value::Real(f64::NAN, E::Lreal));
    assert!(matches!(ok("NaN", E::Real), Value::Real(x, E::Real) if x.is_nan()));
    assert_eq!(
        err("1e39", E::Real),
        (
            ErrorKind::OutOfRange,
            "`1e39` is not a valid REAL literal: the number is too large for REAL".to_string()
        )
    );
    assert_eq!(ok("1e39", E::Lreal), Value::Real(1e39, E::Lreal));
    for bad in [
        ".5", "5.", "1e", "1.5.2", "1e+", "0x10", "1,5", "e5", "--1.0",
    ] {
        assert_eq!(err(bad, E::Lreal).0, ErrorKind::Parse, "{bad:?}");
    }
}

#[test]
fn durations() {
    let s = 1_000_000_000;
    assert_eq!(ok("T#1s", E::Time), Value::time(s));
    assert_eq!(ok("t#1.5s", E::Time), Value::time(s + s / 2));
    assert_eq!(ok("TIME#-250ms", E::Time), Value::time(-250_000_000));
    assert_eq!(ok("1d_2h", E::Time), Value::time(26 * 3600 * s));
    assert_eq!(ok("LTIME#1us5ns", E::Ltime), Value::ltime(1_005));
    assert_eq!(ok("LT#1MS", E::Time), Value::time(1_000_000));
    assert_eq!(ok("T#25h", E::Time), Value::time(25 * 3600 * s));
    assert_eq!(ok("T#0.000000001s", E::Time), Value::time(1));
    assert_eq!(ok("T#0.0000000009s", E::Time), Value::time(0));
    assert_eq!(
        ok("T#1.999999999999999999999s", E::Time),
        Value::time(2 * s - 1)
    );
    assert_eq!(
        ok("T#106751d23h47m16s854ms775us807ns", E::Time),
        Value::time(i64::MAX)
    );
    assert_eq!(
        err("T#106751d23h47m16s854ms775us808ns", E::Time).0,
        ErrorKind::OutOfRange
    );
    assert_eq!(
        err(&format!("T#{}d", "9".repeat(40)), E::Time).0,
        ErrorKind::OutOfRange
    );
    assert_eq!(
        err("T#1s2h", E::Time).1,
        "`T#1s2h` is not a valid TIME literal: units must go from d down to ns, each at most once"
    );
    assert_eq!(
        err("T#1.5h2m", E::Time).1,
        "`T#1.5h2m` is not a valid TIME literal: only the last unit may have a fraction"
    );
    assert_eq!(
        err("T#5x", E::Time).1,
        "`T#5x` is not a valid TIME literal: `x` is not a unit (d, h, m, s, ms, us, ns)"
    );
    for bad in [
        "T#",
        "T#s",
        "T#5",
        "T#1s1s",
        "T#_1s",
        "T#1.s",
        "D#1s",
        "T#1s\u{e9}",
    ] {
        assert_eq!(err(bad, E::Time).0, ErrorKind::Parse, "{bad:?}");
    }
}

#[test]
fn dates_times_of_day_and_date_times() {
    assert_eq!(ok("D#2024-01-31", E::Date), Value::date(19_753));
    assert_eq!(ok("date#1970-01-01", E::Date), Value::date(0));
    assert_eq!(ok("2000-02-29", E::Date), Value::date(11_016));
    assert_eq!(
        ok("LDATE#2024-01-31", E::Ldate),
        Value::Date(19_753, E::Ldate)
    );
    assert_eq!(
        err("D#1900-02-29", E::Date),
        (
            ErrorKind::InvalidDate,
            "`D#1900-02-29` is not a valid DATE literal: day 29 is not in 1..=28 for 1900-02"
                .to_string()
        )
    );
    assert_eq!(err("D#2023-13-01", E::Date).0, ErrorKind::InvalidDate);
    assert_eq!(err("D#2023-1-1-1", E::Date).0, ErrorKind::Parse);
    assert_eq!(err("D#2023/01/01", E::Date).0, ErrorKind::Parse);
    let h = 3_600_000_000_000i64;
    assert_eq!(
        ok("TOD#12:30:00.5", E::Tod),
        Value::tod(12 * h + h / 2 + 500_000_000)
    );
    assert_eq!(
        ok("TIME_OF_DAY#1:2:3", E::Tod),
        Value::tod(h + 2 * 60_000_000_000 + 3_000_000_000)
    );
    assert_eq!(
        ok("LTOD#23:59:59.999999999", E::Ltod),
        Value::Tod(24 * h - 1, E::Ltod)
    );
    assert_eq!(
        err("TOD#24:00:00", E::Tod),
        (
            ErrorKind::InvalidDate,
            "`TOD#24:00:00` is not a valid TOD literal: hour 24 is not in 0..=23".to_string()
        )
    );
    assert_eq!(err("TOD#12:60:00", E::Tod).0, ErrorKind::InvalidDate);
    assert_eq!(err("TOD#12:00:60", E::Tod).0, ErrorKind::InvalidDate);
    assert_eq!(err("TOD#12:00", E::Tod).0, ErrorKind::Parse);
    assert_eq!(err("TOD#12:00:00.", E::Tod).0, ErrorKind::Parse);
    assert_eq!(
        ok("DT#2024-01-31-12:30:00", E::Dt),
        Value::dt(19_753 * 24 * h + 12 * h + h / 2)
    );
    assert_eq!(
        ok("DATE_AND_TIME#1969-12-31-23:59:59", E::Dt),
        Value::dt(-1_000_000_000)
    );
    assert_eq!(
        ok("LDT#1970-01-01-00:00:00.000000001", E::Ldt),
        Value::Dt(1, E::Ldt)
    );
    assert_eq!(
        err("DT#2263-01-01-00:00:00", E::Dt).0,
        ErrorKind::OutOfRange
    );
    assert_eq!(err("DT#2024-01-31", E::Dt).0, ErrorKind::Parse);
    assert_eq!(
        err("DT#2024-02-30-00:00:00", E::Dt).0,
        ErrorKind::InvalidDate
    );
}

#[test]
fn strings_and_characters() {
    assert_eq!(ok("'abc'", E::String), Value::string("abc"));
    assert_eq!(ok("''", E::String), Value::string(""));
    assert_eq!(ok("STRING#'x'", E::String), Value::string("x"));
    assert_eq!(
        ok("'a$'b$$c$l$n$p$r$t'", E::String),
        Value::Str(b"a'b$c\n\n\x0C\r\t".to_vec())
    );
    assert_eq!(
        ok("'$41$e9\u{e9}'", E::String),
        Value::Str(vec![0x41, 0xE9, 0xE9])
    );
    assert_eq!(ok("'a\"b'", E::String), Value::string("a\"b"));
    assert_eq!(ok("\"$0041$\"'\"", E::Wstring), Value::wstring("A\"'"));
    assert_eq!(
        ok("\"\u{1F600}\"", E::Wstring),
        Value::WStr(vec![0xD83D, 0xDE00])
    );
    assert_eq!(ok("'a'", E::Char), Value::Char(b'a'));
    assert_eq!(ok("'$''", E::Char), Value::Char(b'\''));
    assert_eq!(ok("\"$20AC\"", E::Wchar), Value::WChar(0x20AC));
    assert_eq!(
        err("'\u{20ac}'", E::String).1,
        "`'\u{20ac}'` is not a valid STRING literal: `\u{20ac}` is not a STRING character (above U+00FF)"
    );
    assert_eq!(
        err("'it's'", E::String).1,
        "`'it's'` is not a valid STRING literal: a ' inside the text must be written $'"
    );
    for bad in [
        "abc", "'abc", "'", "\"abc\"", "'$'", "'$4'", "'$q'", "'$4G'",
    ] {
        assert_eq!(err(bad, E::String).0, ErrorKind::Parse, "{bad:?}");
    }
    assert_eq!(err("\"$004\"", E::Wstring).0, ErrorKind::Parse);
    assert_eq!(
        err("'ab'", E::Char).1,
        "`'ab'` is not a valid CHAR literal: a character literal holds exactly one character"
    );
    assert_eq!(err("''", E::Char).0, ErrorKind::Parse);
    assert_eq!(err("'a'", E::Wchar).0, ErrorKind::Parse);
}
