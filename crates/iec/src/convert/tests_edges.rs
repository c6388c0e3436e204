//! Edge cases at the limits of every width.

use super::*;
use crate::elementary::Elementary as E;
use crate::value::Value;

fn conv(v: Value, to: E) -> Value {
    match convert(&v, to) {
        Ok(r) => r,
        Err(e) => panic!("{v:?} to {to}: {e}"),
    }
}

#[test]
fn signed_limits_plus_one_wrap_to_the_minimum() {
    for ty in [E::Sint, E::Int, E::Dint, E::Lint] {
        let (lo, hi) = ty.int_range().unwrap_or((0, 0));
        assert_eq!(wrap_int(hi + 1, ty), lo, "{ty}");
        assert_eq!(wrap_int(lo - 1, ty), hi, "{ty}");
        assert_eq!(wrap_int(hi, ty), hi, "{ty}");
        assert_eq!(wrap_int(lo, ty), lo, "{ty}");
    }
}

#[test]
fn unsigned_and_bit_string_limits_wrap_to_zero() {
    for ty in [
        E::Usint,
        E::Uint,
        E::Udint,
        E::Ulint,
        E::Byte,
        E::Word,
        E::Dword,
        E::Lword,
    ] {
        let (_, hi) = ty.int_range().unwrap_or((0, 0));
        assert_eq!(wrap_int(hi + 1, ty), 0, "{ty}");
        assert_eq!(wrap_int(-1, ty), hi, "{ty}");
        assert_eq!(
            conv(Value::Int(-1, E::Lint), ty),
            Value::Int(hi, ty),
            "{ty}"
        );
    }
}

#[test]
fn widening_keeps_the_value() {
    assert_eq!(
        conv(Value::Int(-128, E::Sint), E::Lint),
        Value::Int(-128, E::Lint)
    );
    assert_eq!(
        conv(Value::Int(255, E::Usint), E::Int),
        Value::Int(255, E::Int)
    );
    assert_eq!(
        conv(Value::Int(65535, E::Word), E::Udint),
        Value::Int(65535, E::Udint)
    );
    assert_eq!(
        conv(Value::Int(4294967295, E::Udint), E::Lint),
        Value::Int(4294967295, E::Lint)
    );
}

#[test]
fn real_halves_at_single_precision() {
    assert_eq!(
        conv(Value::real(0.5, E::Real), E::Sint),
        Value::Int(0, E::Sint)
    );
    assert_eq!(
        conv(Value::real(1.5, E::Real), E::Sint),
        Value::Int(2, E::Sint)
    );
    assert_eq!(
        conv(Value::real(-2.5, E::Real), E::Sint),
        Value::Int(-2, E::Sint)
    );
    assert_eq!(
        conv(Value::real(-128.5, E::Real), E::Sint),
        Value::Int(-128, E::Sint)
    );
    assert_eq!(
        conv(Value::real(254.5, E::Real), E::Usint),
        Value::Int(254, E::Usint)
    );
    assert_eq!(
        conv(Value::real(255.5, E::Real), E::Usint),
        Value::Int(255, E::Usint)
    );
    // REAL 2147483647 is 2^31 after rounding to f32: saturates.
    assert_eq!(
        conv(Value::real(2147483647.0, E::Real), E::Dint),
        Value::Int(2147483647, E::Dint)
    );
    assert_eq!(
        conv(Value::real(-2147483648.0, E::Real), E::Dint),
        Value::Int(-2147483648, E::Dint)
    );
}

#[test]
fn integer_limits_to_real() {
    assert_eq!(
        conv(Value::Int(i64::MAX.into(), E::Lint), E::Lreal),
        Value::Real(9223372036854775808.0, E::Lreal)
    );
    assert_eq!(
        conv(Value::Int(i64::MIN.into(), E::Lint), E::Real),
        Value::Real(-9223372036854775808.0, E::Real)
    );
    assert_eq!(
        conv(Value::Int(2147483647, E::Dint), E::Real),
        Value::Real(2147483648.0, E::Real)
    );
    assert_eq!(
        conv(Value::Int(-32768, E::Int), E::Real),
        Value::Real(-32768.0, E::Real)
    );
    assert_eq!(int_to_real(9007199254740993, E::Lreal), 9007199254740992.0);
}

#[test]
fn lreal_to_real_rounds_to_nearest_even() {
    // 1 + 2^-24 lies halfway between two REALs: ties to even (1.0).
    let tie = 1.0 + 2f64.powi(-24);
    assert_eq!(
        conv(Value::real(tie, E::Lreal), E::Real),
        Value::Real(1.0, E::Real)
    );
    let above = 1.0 + 2f64.powi(-24) + 2f64.powi(-40);
    assert_eq!(
        conv(Value::real(above, E::Lreal), E::Real),
        Value::Real(1.0 + 2f64.powi(-23), E::Real)
    );
    assert_eq!(
        conv(Value::real(-0.0, E::Lreal), E::Real),
        Value::Real(-0.0, E::Real)
    );
    assert!(matches!(
        conv(Value::real(f64::NAN, E::Lreal), E::Real),
        Value::Real(x, E::Real) if x.is_nan()
    ));
}

#[test]
fn negative_times_and_dates_to_numbers() {
    assert_eq!(
        conv(Value::time(i64::MIN), E::Lint),
        Value::Int(-9223372036854, E::Lint)
    );
    assert_eq!(
        conv(Value::ltime(i64::MIN), E::Lint),
        Value::Int(i64::MIN.into(), E::Lint)
    );
    assert_eq!(conv(Value::time(-1), E::Dint), Value::Int(0, E::Dint));
    assert_eq!(conv(Value::date(-1), E::Dint), Value::Int(-86_400, E::Dint));
    assert_eq!(
        conv(Value::date(-1), E::Udint),
        Value::Int(4294880896, E::Udint)
    );
    assert_eq!(
        conv(Value::time(-2_500_000), E::Lreal),
        Value::Real(-2.5, E::Lreal)
    );
}

#[test]
fn unit_sizes() {
    assert_eq!(unit_ns(E::Time), Some(1_000_000));
    assert_eq!(unit_ns(E::Tod), Some(1_000_000));
    assert_eq!(unit_ns(E::Date), Some(1_000_000_000));
    assert_eq!(unit_ns(E::Dt), Some(1_000_000_000));
    assert_eq!(unit_ns(E::Ltime), Some(1));
    assert_eq!(unit_ns(E::Ldt), Some(1));
    assert_eq!(unit_ns(E::Int), None);
}

#[test]
fn identity_conversions() {
    for ty in E::ALL {
        let v = Value::max_of(ty).unwrap_or_else(|| Value::default_of(ty));
        assert_eq!(convert(&v, ty), Ok(v.clone()), "{ty}");
    }
}

#[test]
fn conversion_names_ignore_case_and_check_pairs() {
    assert_eq!(
        conversion_by_name("Time_To_Dint"),
        Some(Conversion::Plain {
            from: Some(E::Time),
            to: E::Dint
        })
    );
    assert_eq!(
        conversion_by_name("ldt_to_ltod"),
        Some(Conversion::Plain {
            from: Some(E::Ldt),
            to: E::Ltod
        })
    );
    assert_eq!(
        conversion_by_name("DATE_TO_DATE_AND_TIME"),
        Some(Conversion::Plain {
            from: Some(E::Date),
            to: E::Dt
        })
    );
    assert_eq!(conversion_by_name("BOOL_TO_TIME"), None);
    assert_eq!(conversion_by_name("CHAR_TO_REAL"), None);
    assert_eq!(conversion_by_name("INT_TO_BCD_INT"), None);
}

#[test]
fn typed_helpers_match_value_conversions() {
    for x in [-129.5, -128.5, -0.5, 0.5, 1.5, 126.5, 127.5, 1e9, f64::NAN] {
        let via_value = conv(Value::real(x, E::Lreal), E::Sint);
        assert_eq!(
            via_value,
            Value::Int(i128::from(round_to::<i8>(x)), E::Sint),
            "{x}"
        );
        let truncated = trunc(&Value::real(x, E::Lreal), E::Sint);
        assert_eq!(
            truncated,
            Ok(Value::Int(i128::from(trunc_to::<i8>(x)), E::Sint)),
            "{x}"
        );
    }
    for n in [i64::MIN, -1, 0, 255, 256, 65_536, i64::MAX] {
        let via_value = conv(Value::Int(n.into(), E::Lint), E::Word);
        assert_eq!(
            via_value,
            Value::Int(int_to::<i64, u16>(n).into(), E::Word),
            "{n}"
        );
    }
}
