//! Numeric, time and BCD conversions.

use super::*;
use crate::elementary::Elementary as E;
use crate::error::ErrorKind;
use crate::value::Value;

fn conv(v: Value, to: E) -> Value {
    match convert(&v, to) {
        Ok(r) => r,
        Err(e) => panic!("{v:?} to {to}: {e}"),
    }
}

fn int(v: i128, ty: E) -> Value {
    Value::Int(v, ty)
}

#[test]
fn real_to_integer_rounds_half_to_even() {
    let cases: [(f64, i128); 12] = [
        (2.5, 2),
        (3.5, 4),
        (-1.5, -2),
        (-2.5, -2),
        (0.5, 0),
        (-0.5, 0),
        (1.4999999999999998, 1),
        (2.5000000000000004, 3),
        (-0.0, 0),
        (7.0, 7),
        (-7.6, -8),
        (1e-300, 0),
    ];
    for (x, n) in cases {
        assert_eq!(
            conv(Value::real(x, E::Lreal), E::Dint),
            int(n, E::Dint),
            "{x}"
        );
    }
    assert_eq!(round_to::<i16>(2.5), 2);
    assert_eq!(round_to::<i16>(-1.5), -2);
    assert_eq!(round_to::<u8>(3.5), 4);
    assert_eq!(conv(Value::real(2.5, E::Real), E::Int), int(2, E::Int));
}

#[test]
fn real_to_integer_saturates_and_nan_is_zero() {
    assert_eq!(
        conv(Value::real(1e10, E::Lreal), E::Dint),
        int(2147483647, E::Dint)
    );
    assert_eq!(
        conv(Value::real(-1e10, E::Lreal), E::Dint),
        int(-2147483648, E::Dint)
    );
    assert_eq!(
        conv(Value::real(300.0, E::Real), E::Usint),
        int(255, E::Usint)
    );
    assert_eq!(conv(Value::real(-3.0, E::Lreal), E::Uint), int(0, E::Uint));
    assert_eq!(
        conv(Value::real(127.5, E::Lreal), E::Sint),
        int(127, E::Sint)
    );
    assert_eq!(
        conv(Value::real(f64::INFINITY, E::Lreal), E::Lint),
        int(i64::MAX.into(), E::Lint)
    );
    assert_eq!(
        conv(Value::real(f64::NEG_INFINITY, E::Lreal), E::Ulint),
        int(0, E::Ulint)
    );
    assert_eq!(
        conv(Value::real(f64::NAN, E::Lreal), E::Int),
        int(0, E::Int)
    );
    assert_eq!(
        conv(Value::real(1e30, E::Lreal), E::Lword),
        int(u64::MAX.into(), E::Lword)
    );
    assert_eq!(round_to::<i32>(f64::NAN), 0);
    assert_eq!(round_to::<i8>(-1000.0), -128);
}

#[test]
fn trunc_truncates_toward_zero() {
    let t = |x: f64, ty: E| trunc(&Value::real(x, E::Lreal), ty);
    assert_eq!(t(2.9, E::Int), Ok(int(2, E::Int)));
    assert_eq!(t(-2.9, E::Int), Ok(int(-2, E::Int)));
    assert_eq!(t(-0.5, E::Dint), Ok(int(0, E::Dint)));
    assert_eq!(t(1e20, E::Dint), Ok(int(2147483647, E::Dint)));
    assert_eq!(t(f64::NAN, E::Usint), Ok(int(0, E::Usint)));
    assert_eq!(trunc_to::<i64>(-7.99), -7);
    assert_eq!(trunc_to::<u16>(65535.9), 65535);
    let e = trunc(&int(5, E::Int), E::Dint);
    assert_eq!(
        e.map_err(|e| e.message),
        Err("INT_TRUNC_DINT: TRUNC takes a REAL or LREAL and gives an integer type".to_string())
    );
    assert_eq!(
        trunc(&Value::real(1.0, E::Real), E::Word).map_err(|e| e.kind),
        Err(ErrorKind::NotConvertible)
    );
}

#[test]
fn integer_narrowing_wraps() {
    assert_eq!(conv(int(300, E::Int), E::Usint), int(44, E::Usint));
    assert_eq!(conv(int(128, E::Int), E::Sint), int(-128, E::Sint));
    assert_eq!(conv(int(40000, E::Dint), E::Int), int(-25536, E::Int));
    assert_eq!(conv(int(-1, E::Sint), E::Byte), int(255, E::Byte));
    assert_eq!(conv(int(-1, E::Int), E::Udint), int(4294967295, E::Udint));
    assert_eq!(
        conv(int(-1, E::Lint), E::Ulint),
        int(u64::MAX.into(), E::Ulint)
    );
    assert_eq!(
        conv(int(u64::MAX.into(), E::Lword), E::Lint),
        int(-1, E::Lint)
    );
    assert_eq!(conv(int(65536 + 7, E::Udint), E::Word), int(7, E::Word));
    assert_eq!(conv(int(255, E::Byte), E::Sint), int(-1, E::Sint));
    assert_eq!(conv(int(-32768, E::Int), E::Dint), int(-32768, E::Dint));
    assert_eq!(int_to::<i32, i16>(40000), -25536);
    assert_eq!(int_to::<i8, u32>(-1), u32::MAX);
    assert_eq!(int_to::<u64, i8>(0x1FF), -1);
    assert_eq!(
        wrap_int(i128::from(i64::MAX) + 1, E::Lint),
        i128::from(i64::MIN)
    );
}

#[test]
fn to_real_and_between_reals() {
    assert_eq!(
        conv(int(16777217, E::Dint), E::Real),
        Value::Real(16777216.0, E::Real)
    );
    assert_eq!(
        conv(int(16777217, E::Dint), E::Lreal),
        Value::Real(16777217.0, E::Lreal)
    );
    assert_eq!(
        conv(int(u64::MAX.into(), E::Ulint), E::Lreal),
        Value::Real(18446744073709551615.0, E::Lreal)
    );
    assert_eq!(
        conv(Value::real(0.1, E::Lreal), E::Real),
        Value::Real(f64::from(0.1f32), E::Real)
    );
    assert_eq!(
        conv(Value::real(1e39, E::Lreal), E::Real),
        Value::Real(f64::INFINITY, E::Real)
    );
    assert_eq!(
        conv(Value::real(1e-50, E::Lreal), E::Real),
        Value::Real(0.0, E::Real)
    );
    assert_eq!(
        conv(Value::real(0.1, E::Real), E::Lreal),
        Value::Real(0.10000000149011612, E::Lreal)
    );
    assert_eq!(int_to_f32(16777217i32), 16777216.0);
    assert_eq!(int_to_f64(-5i8), -5.0);
    assert_eq!(lreal_to_real(3.4028235e38), f32::MAX);
    assert_eq!(lreal_to_real(3.5e38), f32::INFINITY);
}

#[test]
fn booleans() {
    assert_eq!(conv(Value::Bool(true), E::Int), int(1, E::Int));
    assert_eq!(conv(Value::Bool(false), E::Byte), int(0, E::Byte));
    assert_eq!(
        conv(Value::Bool(true), E::Lreal),
        Value::Real(1.0, E::Lreal)
    );
    assert_eq!(conv(int(-7, E::Int), E::Bool), Value::Bool(true));
    assert_eq!(conv(int(0, E::Dword), E::Bool), Value::Bool(false));
    assert_eq!(conv(int(256, E::Word), E::Bool), Value::Bool(true));
    assert_eq!(
        conv(Value::real(0.001, E::Real), E::Bool),
        Value::Bool(true)
    );
    assert_eq!(
        conv(Value::real(-0.0, E::Lreal), E::Bool),
        Value::Bool(false)
    );
    assert_eq!(
        conv(Value::real(f64::NAN, E::Lreal), E::Bool),
        Value::Bool(true)
    );
    assert_eq!(bool_to::<u8>(true), 1);
    assert!(!real_to_bool(0.0));
}

#[test]
fn times_to_numbers_and_back() {
    let ms = 1_000_000;
    assert_eq!(conv(Value::time(1_000 * ms), E::Dint), int(1000, E::Dint));
    assert_eq!(conv(Value::time(1_900_000), E::Dint), int(1, E::Dint));
    assert_eq!(conv(Value::time(-1_900_000), E::Dint), int(-1, E::Dint));
    assert_eq!(
        conv(Value::ltime(1_000 * ms), E::Lint),
        int(1_000_000_000, E::Lint)
    );
    assert_eq!(
        conv(Value::time(1_500_000), E::Lreal),
        Value::Real(1.5, E::Lreal)
    );
    assert_eq!(conv(Value::time(70_000 * ms), E::Uint), int(4464, E::Uint));
    assert_eq!(conv(int(1000, E::Dint), E::Time), Value::time(1_000 * ms));
    assert_eq!(conv(int(-5, E::Int), E::Time), Value::time(-5 * ms));
    assert_eq!(conv(int(5, E::Lint), E::Ltime), Value::ltime(5));
    assert_eq!(
        conv(Value::real(1.5, E::Lreal), E::Time),
        Value::time(2 * ms)
    );
    assert_eq!(
        conv(Value::real(f64::NAN, E::Lreal), E::Time),
        Value::time(0)
    );
    assert_eq!(conv(Value::time(5), E::Ltime), Value::ltime(5));
    assert_eq!(conv(Value::ltime(5), E::Time), Value::time(5));
    // The nanosecond total wraps into 64 bits like a LINT.
    assert_eq!(
        conv(int(u64::MAX.into(), E::Ulint), E::Time),
        Value::time((i128::from(u64::MAX) * 1_000_000) as i64)
    );
}

#[test]
fn dates_to_numbers_and_back() {
    let day = 86_400_000_000_000i64;
    assert_eq!(conv(Value::date(1), E::Udint), int(86_400, E::Udint));
    assert_eq!(
        conv(Value::Date(1, E::Ldate), E::Lint),
        int(day.into(), E::Lint)
    );
    assert_eq!(conv(Value::tod(1_500_000), E::Udint), int(1, E::Udint));
    assert_eq!(
        conv(Value::Tod(1_500_000, E::Ltod), E::Ulint),
        int(1_500_000, E::Ulint)
    );
    assert_eq!(
        conv(Value::dt(day + 1_500_000_000), E::Udint),
        int(86_401, E::Udint)
    );
    assert_eq!(conv(Value::dt(-500_000_000), E::Dint), int(-1, E::Dint));
    assert_eq!(conv(Value::Dt(42, E::Ldt), E::Lint), int(42, E::Lint));
    assert_eq!(
        conv(Value::dt(1_500_000_000), E::Lreal),
        Value::Real(1.5, E::Lreal)
    );
    assert_eq!(conv(int(86_399, E::Udint), E::Date), Value::date(0));
    assert_eq!(conv(int(86_400, E::Udint), E::Date), Value::date(1));
    assert_eq!(conv(int(-1, E::Dint), E::Date), Value::date(-1));
    assert_eq!(
        conv(int(86_401, E::Udint), E::Dt),
        Value::dt(day + 1_000_000_000)
    );
    assert_eq!(
        conv(int(1_000, E::Udint), E::Tod),
        Value::tod(1_000_000_000)
    );
    assert_eq!(
        conv(int(86_400_001, E::Udint), E::Tod),
        Value::tod(1_000_000)
    );
    assert_eq!(conv(int(-1, E::Dint), E::Tod), Value::tod(day - 1_000_000));
    assert_eq!(conv(int(7, E::Lint), E::Ldt), Value::Dt(7, E::Ldt));
}

#[test]
fn between_time_types() {
    let day = 86_400_000_000_000i64;
    let dt = 19_753 * day + 45_000_000_000_000;
    assert_eq!(conv(Value::dt(dt), E::Date), Value::date(19_753));
    assert_eq!(conv(Value::dt(dt), E::Tod), Value::tod(45_000_000_000_000));
    assert_eq!(conv(Value::dt(-1), E::Date), Value::date(-1));
    assert_eq!(conv(Value::dt(-1), E::Tod), Value::tod(day - 1));
    assert_eq!(
        conv(Value::Dt(dt, E::Ldt), E::Ldate),
        Value::Date(19_753, E::Ldate)
    );
    assert_eq!(conv(Value::date(2), E::Dt), Value::dt(2 * day));
    assert_eq!(conv(Value::date(2), E::Ldate), Value::Date(2, E::Ldate));
    assert_eq!(conv(Value::tod(5), E::Ltod), Value::Tod(5, E::Ltod));
    assert_eq!(conv(Value::dt(5), E::Ldt), Value::Dt(5, E::Ldt));
    let far = convert(&Value::date(200_000), E::Dt);
    assert_eq!(
        far,
        Err(crate::IecError::new(
            ErrorKind::Overflow,
            "DATE_TO_DT: the result does not fit in 64-bit nanoseconds"
        ))
    );
}

#[test]
fn undefined_conversions_are_errors() {
    let pairs = [
        (Value::time(1), E::Date),
        (Value::date(1), E::Time),
        (Value::tod(1), E::Dt),
        (Value::tod(1), E::Date),
        (Value::date(1), E::Tod),
        (Value::Bool(true), E::Time),
        (Value::real(1.0, E::Real), E::Char),
        (Value::Char(b'a'), E::Real),
        (Value::time(1), E::Bool),
        (Value::Char(b'a'), E::Bool),
        (Value::time(1), E::Wchar),
    ];
    for (v, to) in pairs {
        let e = convert(&v, to);
        assert_eq!(
            e.as_ref().map_err(|e| e.kind),
            Err(ErrorKind::NotConvertible),
            "{v:?} {to}"
        );
        assert!(!is_convertible(v.ty(), to));
    }
    assert_eq!(
        convert(&Value::time(1), E::Date).map_err(|e| e.message),
        Err("TIME_TO_DATE: there is no conversion from TIME to DATE".to_string())
    );
}

#[test]
fn is_convertible_agrees_with_convert() {
    for from in E::ALL {
        if from.is_string() {
            continue;
        }
        let v = Value::default_of(from);
        for to in E::ALL {
            let not = matches!(convert(&v, to), Err(e) if e.kind == ErrorKind::NotConvertible);
            assert_eq!(is_convertible(from, to), !not, "{from} -> {to}");
        }
    }
}

#[test]
fn bcd() {
    assert_eq!(bcd_decode(0x1234, 16), Ok(1234));
    assert_eq!(bcd_decode(0x99, 8), Ok(99));
    assert_eq!(bcd_decode(0x0, 8), Ok(0));
    assert_eq!(
        bcd_decode(0x9999_9999_9999_9999, 64),
        Ok(9_999_999_999_999_999)
    );
    assert_eq!(
        bcd_decode(0x1A, 8).map_err(|e| (e.kind, e.message)),
        Err((
            ErrorKind::Bcd,
            "16#1A is not a BCD number: digit 2 holds A, above 9".to_string()
        ))
    );
    assert_eq!(
        bcd_decode(0xF000, 16).map_err(|e| e.kind),
        Err(ErrorKind::Bcd)
    );
    assert_eq!(bcd_encode(1234, 16), Ok(0x1234));
    assert_eq!(bcd_encode(99, 8), Ok(0x99));
    assert_eq!(bcd_encode(99_999_999, 32), Ok(0x9999_9999));
    assert_eq!(
        bcd_encode(100, 8).map_err(|e| e.message),
        Err("100 cannot be written in 2 BCD digits (0..=99)".to_string())
    );
    assert_eq!(bcd_encode(-1, 16).map_err(|e| e.kind), Err(ErrorKind::Bcd));
    assert_eq!(from_bcd(&int(0x0042, E::Word), E::Int), Ok(int(42, E::Int)));
    assert_eq!(
        from_bcd(&int(0x1F, E::Byte), E::Usint).map_err(|e| e.message),
        Err("BYTE_BCD_TO_USINT: 16#1F is not a BCD number: digit 2 holds F, above 9".to_string())
    );
    assert_eq!(to_bcd(&int(42, E::Uint), E::Word), Ok(int(0x42, E::Word)));
    assert_eq!(
        to_bcd(&int(-3, E::Int), E::Word).map_err(|e| e.message),
        Err("INT_TO_BCD_WORD: -3 cannot be written in 4 BCD digits (0..=9999)".to_string())
    );
    assert_eq!(
        from_bcd(&int(1, E::Int), E::Int).map_err(|e| e.kind),
        Err(ErrorKind::NotConvertible)
    );
    assert_eq!(
        to_bcd(&int(1, E::Int), E::Int).map_err(|e| e.kind),
        Err(ErrorKind::NotConvertible)
    );
}

#[test]
fn conversion_names() {
    use Conversion as C;
    let n = conversion_by_name;
    assert_eq!(
        n("INT_TO_REAL"),
        Some(C::Plain {
            from: Some(E::Int),
            to: E::Real
        })
    );
    assert_eq!(
        n("real_to_int"),
        Some(C::Plain {
            from: Some(E::Real),
            to: E::Int
        })
    );
    assert_eq!(
        n("TO_LREAL"),
        Some(C::Plain {
            from: None,
            to: E::Lreal
        })
    );
    assert_eq!(
        n("DATE_AND_TIME_TO_TIME_OF_DAY"),
        Some(C::Plain {
            from: Some(E::Dt),
            to: E::Tod
        })
    );
    assert_eq!(
        n("DT_TO_DATE"),
        Some(C::Plain {
            from: Some(E::Dt),
            to: E::Date
        })
    );
    assert_eq!(
        n("STRING_TO_WSTRING"),
        Some(C::Plain {
            from: Some(E::String),
            to: E::Wstring
        })
    );
    assert_eq!(
        n("TRUNC"),
        Some(C::Trunc {
            from: None,
            to: None
        })
    );
    assert_eq!(
        n("TRUNC_DINT"),
        Some(C::Trunc {
            from: None,
            to: Some(E::Dint)
        })
    );
    assert_eq!(
        n("LREAL_TRUNC_INT"),
        Some(C::Trunc {
            from: Some(E::Lreal),
            to: Some(E::Int)
        })
    );
    assert_eq!(
        n("BCD_TO_INT"),
        Some(C::FromBcd {
            from: None,
            to: E::Int
        })
    );
    assert_eq!(
        n("WORD_BCD_TO_UINT"),
        Some(C::FromBcd {
            from: Some(E::Word),
            to: E::Uint
        })
    );
    assert_eq!(
        n("INT_TO_BCD"),
        Some(C::ToBcd {
            from: E::Int,
            to: None
        })
    );
    assert_eq!(
        n("USINT_TO_BCD_BYTE"),
        Some(C::ToBcd {
            from: E::Usint,
            to: Some(E::Byte)
        })
    );
    for bad in [
        "TIME_TO_DATE",
        "INT_TO",
        "TO_",
        "FOO_TO_INT",
        "INT_TO_FOO",
        "INT_TRUNC_DINT",
        "BCD_TO_WORD",
        "TRUNC_REAL",
        "ABS",
        "",
    ] {
        assert_eq!(n(bad), None, "{bad}");
    }
}
