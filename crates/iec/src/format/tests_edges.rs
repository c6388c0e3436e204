//! Boundaries of the print contract.

use super::*;
use crate::elementary::Elementary as E;
use crate::value::Value;

#[test]
fn exponent_switch_points() {
    assert_eq!(format_lreal(1e15), "1000000000000000.0");
    assert_eq!(format_lreal(9999999999999998.0), "9999999999999998.0");
    assert_eq!(format_lreal(1e16), "1e+16");
    assert_eq!(format_lreal(0.0001), "0.0001");
    assert_eq!(format_lreal(0.000099), "9.9e-05");
    assert_eq!(format_real(1e15), "1000000000000000.0");
    assert_eq!(format_real(1e16), "1e+16");
    assert_eq!(format_real(123456790.0), "123456790.0");
    assert_eq!(format_real(0.0001), "0.0001");
    assert_eq!(format_real(0.00001), "1e-05");
}

#[test]
fn integers_at_every_limit() {
    for ty in E::ALL.iter().copied().filter(|t| t.is_integral()) {
        let (lo, hi) = ty.int_range().unwrap_or((0, 0));
        assert_eq!(format_value(&Value::Int(lo, ty)), lo.to_string());
        assert_eq!(format_value(&Value::Int(hi, ty)), hi.to_string());
        assert_eq!(parse_literal(&hi.to_string(), ty), Ok(Value::Int(hi, ty)));
        assert_eq!(parse_literal(&lo.to_string(), ty), Ok(Value::Int(lo, ty)));
    }
}

#[test]
fn every_single_duration_unit() {
    let cases: [(i64, &str); 7] = [
        (86_400_000_000_000, "T#1d"),
        (3_600_000_000_000, "T#1h"),
        (60_000_000_000, "T#1m"),
        (1_000_000_000, "T#1s"),
        (1_000_000, "T#1ms"),
        (1_000, "T#1us"),
        (1, "T#1ns"),
    ];
    for (ns, text) in cases {
        assert_eq!(format_duration(ns, false), text);
        assert_eq!(parse_literal(text, E::Time), Ok(Value::time(ns)));
    }
    assert_eq!(
        format_duration(90_061_001_001_001, false),
        "T#1d1h1m1s1ms1us1ns"
    );
    assert_eq!(
        format_duration(-59_999_999_999, true),
        "LTIME#-59s999ms999us999ns"
    );
}

#[test]
fn leap_days_print() {
    assert_eq!(format_date(11_016, false), "D#2000-02-29");
    assert_eq!(format_date(19_782, false), "D#2024-02-29");
    assert_eq!(format_date(19_783, false), "D#2024-03-01");
    assert_eq!(format_date(-25_509, true), "LDATE#1900-02-28");
    assert_eq!(
        format_dt(11_016 * 86_400_000_000_000 + 1, false),
        "DT#2000-02-29-00:00:00.000000001"
    );
    assert_eq!(format_tod(86_400_000_000_000, false), "TOD#00:00:00");
    assert_eq!(format_tod(-1, true), "LTOD#23:59:59.999999999");
}

#[test]
fn quoting_helpers() {
    assert_eq!(quote_string(b"$"), "'$$'");
    assert_eq!(quote_string(b"~ "), "'~ '");
    assert_eq!(quote_string(&[0x1B]), "'$1B'");
    assert_eq!(quote_wstring(&[0x27]), "\"'\"");
    assert_eq!(quote_wstring(&[0x09, 0x0D]), "\"$T$R\"");
    assert_eq!(quote_wstring(&[0x00AD, 0x00D7]), "\"$00AD\u{d7}\"");
    assert_eq!(quote_char(b'"'), "'\"'");
    assert_eq!(quote_wchar(0x0416), "\"\u{416}\"");
}

#[test]
fn prefixes_and_spaces() {
    assert_eq!(
        parse_literal("  lTiMe#1S ", E::Time),
        Ok(Value::time(1_000_000_000))
    );
    assert_eq!(
        parse_literal("T#1s", E::Ltime),
        Ok(Value::ltime(1_000_000_000))
    );
    assert_eq!(parse_literal("ld#1970-01-02", E::Date), Ok(Value::date(1)));
    assert_eq!(
        parse_literal("ltod#00:00:01", E::Tod),
        Ok(Value::tod(1_000_000_000))
    );
    assert_eq!(
        parse_literal("ldate_and_time#1970-01-01-00:00:01", E::Dt),
        Ok(Value::dt(1_000_000_000))
    );
    assert_eq!(
        parse_literal("wstring#\"a\"", E::Wstring),
        Ok(Value::wstring("a"))
    );
    assert_eq!(parse_literal("char#'a'", E::Char), Ok(Value::Char(b'a')));
    assert!(parse_literal("T# 1s", E::Time).is_err());
    assert!(parse_literal("TOD#1s", E::Time).is_err());
    assert!(parse_literal("DT#1970-01-01", E::Date).is_err());
    assert!(parse_literal("LREAL#1.0", E::Real).is_err());
}

#[test]
fn nan_and_infinity_spellings() {
    for text in ["nan", "NaN", "+nan", "-NAN"] {
        let v = parse_literal(text, E::Lreal);
        assert!(
            matches!(v, Ok(Value::Real(x, E::Lreal)) if x.is_nan()),
            "{text}"
        );
    }
    assert_eq!(
        parse_literal("+inf", E::Real),
        Ok(Value::Real(f64::INFINITY, E::Real))
    );
    assert_eq!(
        parse_literal("-Infinity", E::Lreal),
        Ok(Value::Real(f64::NEG_INFINITY, E::Lreal))
    );
    assert!(parse_literal("infin", E::Lreal).is_err());
    assert!(parse_literal("inf", E::Int).is_err());
}

#[test]
fn negative_zero_and_tiny_values() {
    assert_eq!(format_real(-0.0), "-0.0");
    assert_eq!(format_real(1e-45), "1e-45");
    assert_eq!(format_lreal(-5e-324), "-5e-324");
    assert_eq!(
        format_lreal(2.2250738585072014e-308),
        "2.2250738585072014e-308"
    );
    let back = parse_literal("-0.0", E::Real);
    assert!(matches!(back, Ok(Value::Real(x, E::Real)) if x == 0.0 && x.is_sign_negative()));
}
