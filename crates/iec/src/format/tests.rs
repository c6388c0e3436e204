//! The print contract, case by case.

use super::*;
use crate::elementary::Elementary as E;
use crate::value::Value;

fn p(v: Value) -> String {
    format_value(&v)
}

#[test]
fn booleans_and_integers() {
    assert_eq!(p(Value::Bool(true)), "TRUE");
    assert_eq!(p(Value::Bool(false)), "FALSE");
    assert_eq!(p(Value::Int(-128, E::Sint)), "-128");
    assert_eq!(p(Value::Int(255, E::Byte)), "255");
    assert_eq!(p(Value::Int(65535, E::Word)), "65535");
    assert_eq!(
        p(Value::Int(i64::MIN.into(), E::Lint)),
        "-9223372036854775808"
    );
    assert_eq!(
        p(Value::Int(u64::MAX.into(), E::Lword)),
        "18446744073709551615"
    );
    assert_eq!(p(Value::Int(0, E::Udint)), "0");
}

#[test]
fn lreal_positional_forms() {
    let cases: [(f64, &str); 12] = [
        (3.5, "3.5"),
        (4.0, "4.0"),
        (-0.0, "-0.0"),
        (0.0, "0.0"),
        (0.1, "0.1"),
        (-2.75, "-2.75"),
        (100.0, "100.0"),
        (0.0001, "0.0001"),
        (0.00012345, "0.00012345"),
        (1234567890123456.0, "1234567890123456.0"),
        (123.456, "123.456"),
        (1.0 / 3.0, "0.3333333333333333"),
    ];
    for (x, s) in cases {
        assert_eq!(format_lreal(x), s, "{x:?}");
    }
}

#[test]
fn lreal_exponent_forms() {
    let cases: [(f64, &str); 10] = [
        (1e-7, "1e-07"),
        (1.5e20, "1.5e+20"),
        (1e16, "1e+16"),
        (-1e16, "-1e+16"),
        (0.00001, "1e-05"),
        (1.2345e-5, "1.2345e-05"),
        (1e100, "1e+100"),
        (5e-324, "5e-324"),
        (f64::MAX, "1.7976931348623157e+308"),
        (123456789012345680.0, "1.2345678901234568e+17"),
    ];
    for (x, s) in cases {
        assert_eq!(format_lreal(x), s, "{x:?}");
    }
}

#[test]
fn real_uses_single_precision_digits() {
    assert_eq!(format_real(0.1), "0.1");
    assert_eq!(format_real(1.0 / 3.0), "0.33333334");
    assert_eq!(format_real(16777216.0), "16777216.0");
    assert_eq!(format_real(f32::MAX), "3.4028235e+38");
    assert_eq!(format_real(f32::MIN_POSITIVE), "1.1754944e-38");
    assert_eq!(format_real(-1e-7), "-1e-07");
    assert_eq!(format_real(2.5), "2.5");
    // Through a Value: the f64 inside a REAL prints at f32 precision.
    assert_eq!(p(Value::real(0.1, E::Real)), "0.1");
    assert_eq!(p(Value::real(0.1, E::Lreal)), "0.1");
    assert_eq!(
        p(Value::Real(f64::from(0.1f32), E::Lreal)),
        "0.10000000149011612"
    );
}

#[test]
fn non_finite_reals() {
    assert_eq!(format_lreal(f64::INFINITY), "inf");
    assert_eq!(format_lreal(f64::NEG_INFINITY), "-inf");
    assert_eq!(format_lreal(f64::NAN), "nan");
    assert_eq!(format_lreal(-f64::NAN), "nan");
    assert_eq!(format_real(f32::INFINITY), "inf");
    assert_eq!(format_real(f32::NAN), "nan");
}

#[test]
fn durations() {
    let ms = 1_000_000;
    let s = 1_000 * ms;
    let cases: [(i64, &str); 10] = [
        (0, "T#0s"),
        (1_500 * ms, "T#1s500ms"),
        (-5 * s, "T#-5s"),
        (
            86_400 * s + 2 * 3600 * s + 3 * 60 * s + 4 * s + 5 * ms,
            "T#1d2h3m4s5ms",
        ),
        (ms + 500_000, "T#1ms500us"),
        (250, "T#250ns"),
        (1_001, "T#1us1ns"),
        (3600 * s, "T#1h"),
        (i64::MAX, "T#106751d23h47m16s854ms775us807ns"),
        (i64::MIN, "T#-106751d23h47m16s854ms775us808ns"),
    ];
    for (ns, text) in cases {
        assert_eq!(format_duration(ns, false), text);
    }
    assert_eq!(p(Value::ltime(1_500)), "LTIME#1us500ns");
    assert_eq!(p(Value::ltime(0)), "LTIME#0s");
    assert_eq!(p(Value::time(-1)), "T#-1ns");
}

#[test]
fn dates_times_of_day_and_date_times() {
    assert_eq!(p(Value::date(0)), "D#1970-01-01");
    assert_eq!(p(Value::date(19_753)), "D#2024-01-31");
    assert_eq!(p(Value::date(-25_509)), "D#1900-02-28");
    assert_eq!(p(Value::date(-25_508)), "D#1900-03-01");
    assert_eq!(p(Value::date(-719_528)), "D#0000-01-01");
    assert_eq!(p(Value::date(-719_529)), "D#-0001-12-31");
    assert_eq!(p(Value::Date(19_753, E::Ldate)), "LDATE#2024-01-31");
    let h = 3_600_000_000_000i64;
    assert_eq!(p(Value::tod(12 * h + h / 2)), "TOD#12:30:00");
    assert_eq!(
        p(Value::tod(12 * h + h / 2 + 500_000_000)),
        "TOD#12:30:00.5"
    );
    assert_eq!(p(Value::tod(1)), "TOD#00:00:00.000000001");
    assert_eq!(p(Value::tod(0)), "TOD#00:00:00");
    assert_eq!(p(Value::tod(24 * h - 1)), "TOD#23:59:59.999999999");
    assert_eq!(p(Value::Tod(123_000_000, E::Ltod)), "LTOD#00:00:00.123");
    let dt = 19_753 * 24 * h + 12 * h + h / 2;
    assert_eq!(p(Value::dt(dt)), "DT#2024-01-31-12:30:00");
    assert_eq!(p(Value::dt(dt + 250_000_000)), "DT#2024-01-31-12:30:00.25");
    assert_eq!(p(Value::dt(-1_000_000_000)), "DT#1969-12-31-23:59:59");
    assert_eq!(p(Value::Dt(0, E::Ldt)), "LDT#1970-01-01-00:00:00");
    assert_eq!(p(Value::dt(i64::MAX)), "DT#2262-04-11-23:47:16.854775807");
    assert_eq!(p(Value::dt(i64::MIN)), "DT#1677-09-21-00:12:43.145224192");
}

#[test]
fn strings_and_characters() {
    assert_eq!(p(Value::string("abc")), "'abc'");
    assert_eq!(p(Value::string("")), "''");
    assert_eq!(p(Value::string("it's $5")), "'it$'s $$5'");
    assert_eq!(p(Value::Str(b"a\nb\r\tc\x0C".to_vec())), "'a$Nb$R$Tc$P'");
    assert_eq!(p(Value::Str(vec![0, 0x7F, 0xE9, b'"'])), "'$00$7F$E9\"'");
    assert_eq!(p(Value::wstring("abc")), "\"abc\"");
    assert_eq!(
        p(Value::wstring("say \"hi\" it's")),
        "\"say $\"hi$\" it's\""
    );
    assert_eq!(
        p(Value::wstring("caf\u{e9} \u{20ac}5 \u{65e5}")),
        "\"caf\u{e9} \u{20ac}5 \u{65e5}\""
    );
    assert_eq!(
        p(Value::WStr(vec![0x2028, 0xD800, 0x00A0, 0x24])),
        "\"$2028$D800$00A0$$\""
    );
    assert_eq!(p(Value::Char(b'a')), "'a'");
    assert_eq!(p(Value::Char(b'\'')), "'$''");
    assert_eq!(p(Value::Char(0)), "'$00'");
    assert_eq!(p(Value::WChar(0x41)), "\"A\"");
    assert_eq!(p(Value::WChar(0x0A)), "\"$N\"");
}

#[test]
fn every_printed_form_reads_back() {
    let values = [
        Value::Bool(true),
        Value::Bool(false),
        Value::Int(-128, E::Sint),
        Value::Int(127, E::Sint),
        Value::Int(i64::MIN.into(), E::Lint),
        Value::Int(u64::MAX.into(), E::Ulint),
        Value::Int(255, E::Byte),
        Value::real(0.1, E::Real),
        Value::real(f64::from(f32::MAX), E::Real),
        Value::real(1e-45, E::Real),
        Value::real(-0.0, E::Lreal),
        Value::real(5e-324, E::Lreal),
        Value::real(f64::MAX, E::Lreal),
        Value::real(f64::INFINITY, E::Lreal),
        Value::real(f64::NEG_INFINITY, E::Real),
        Value::time(0),
        Value::time(1_500_000_000),
        Value::time(i64::MIN),
        Value::ltime(i64::MAX),
        Value::date(-719_529),
        Value::Date(19_753, E::Ldate),
        Value::tod(1),
        Value::Tod(86_399_999_999_999, E::Ltod),
        Value::dt(i64::MIN),
        Value::Dt(i64::MAX, E::Ldt),
        Value::Str((0..=255).collect()),
        Value::WStr(vec![
            0, 0x22, 0x27, 0x24, 0xE9, 0x2028, 0xD83D, 0xDE00, 0xFFFF,
        ]),
        Value::Char(b'$'),
        Value::WChar(0xFFFF),
    ];
    for v in values {
        let text = format_value(&v);
        assert_eq!(parse_literal(&text, v.ty()), Ok(v.clone()), "{text}");
    }
    let nan = parse_literal(&format_lreal(f64::NAN), E::Lreal);
    assert!(matches!(nan, Ok(Value::Real(x, E::Lreal)) if x.is_nan()));
}

#[test]
fn reals_round_trip_through_text_bit_for_bit() {
    // A spread of awkward values: powers, thirds, subnormals, near-ties.
    let mut x = 1.0e-310f64;
    while x < 1e300 {
        for v in [x, -x, x / 3.0, x * 0.7] {
            let back = parse_literal(&format_lreal(v), E::Lreal);
            assert_eq!(back, Ok(Value::Real(v, E::Lreal)), "{v:e}");
            let f = v as f32;
            if f.is_finite() {
                let back = parse_literal(&format_real(f), E::Real);
                assert_eq!(back, Ok(Value::Real(f64::from(f), E::Real)), "{f:e}");
            }
        }
        x *= 7.3;
    }
}
