//! Conversions to and from STRING, WSTRING, CHAR and WCHAR.

use super::*;
use crate::elementary::Elementary as E;
use crate::error::ErrorKind;
use crate::value::Value;

fn to_s(v: Value) -> String {
    match convert(&v, E::String) {
        Ok(Value::Str(s)) => latin1_text(&s),
        other => panic!("{v:?}: {other:?}"),
    }
}

fn from_s(text: &str, to: E) -> Result<Value, (ErrorKind, String)> {
    convert(&Value::string(text), to).map_err(|e| (e.kind, e.message))
}

#[test]
fn numbers_times_and_dates_to_string() {
    assert_eq!(to_s(Value::Int(-42, E::Int)), "-42");
    assert_eq!(to_s(Value::Int(255, E::Byte)), "255");
    assert_eq!(to_s(Value::real(0.1, E::Real)), "0.1");
    assert_eq!(to_s(Value::real(4.0, E::Lreal)), "4.0");
    assert_eq!(to_s(Value::real(1e-7, E::Lreal)), "1e-07");
    assert_eq!(to_s(Value::Bool(true)), "TRUE");
    assert_eq!(to_s(Value::time(1_500_000_000)), "T#1s500ms");
    assert_eq!(to_s(Value::ltime(5)), "LTIME#5ns");
    assert_eq!(to_s(Value::date(19_753)), "D#2024-01-31");
    assert_eq!(to_s(Value::tod(500_000_000)), "TOD#00:00:00.5");
    assert_eq!(to_s(Value::dt(0)), "DT#1970-01-01-00:00:00");
    assert_eq!(to_s(Value::Char(b'x')), "x");
    assert_eq!(to_s(Value::WChar(0x20AC)), "?");
    assert_eq!(to_s(Value::string("it's")), "it's");
    assert_eq!(
        convert(&Value::Int(7, E::Int), E::Wstring),
        Ok(Value::WStr(vec![0x37]))
    );
}

#[test]
fn string_to_numbers() {
    assert_eq!(from_s("  42 ", E::Int), Ok(Value::Int(42, E::Int)));
    assert_eq!(from_s("16#FF", E::Byte), Ok(Value::Int(255, E::Byte)));
    assert_eq!(from_s("16#FF", E::Dint), Ok(Value::Int(255, E::Dint)));
    assert_eq!(from_s("-5", E::Sint), Ok(Value::Int(-5, E::Sint)));
    assert_eq!(from_s("INT#7", E::Int), Ok(Value::Int(7, E::Int)));
    assert_eq!(from_s("2.5", E::Int), Ok(Value::Int(2, E::Int)));
    assert_eq!(from_s("3.5", E::Uint), Ok(Value::Int(4, E::Uint)));
    assert_eq!(from_s("1e3", E::Dint), Ok(Value::Int(1000, E::Dint)));
    assert_eq!(from_s("1.5e3", E::Lreal), Ok(Value::Real(1500.0, E::Lreal)));
    assert_eq!(
        from_s("0.1", E::Real),
        Ok(Value::Real(f64::from(0.1f32), E::Real))
    );
    assert_eq!(from_s("7", E::Real), Ok(Value::Real(7.0, E::Real)));
    assert_eq!(from_s("TRUE", E::Bool), Ok(Value::Bool(true)));
    assert_eq!(from_s("0", E::Bool), Ok(Value::Bool(false)));
    assert_eq!(
        from_s("70000", E::Int),
        Err((
            ErrorKind::OutOfRange,
            "STRING_TO_INT: `70000` is not a valid INT literal: 70000 is out of range -32768..=32767"
                .to_string()
        ))
    );
    assert_eq!(
        from_s("300.2", E::Usint),
        Err((
            ErrorKind::OutOfRange,
            "STRING_TO_USINT: `300.2` is out of range for USINT (0..=255)".to_string()
        ))
    );
    assert_eq!(
        from_s("abc", E::Int),
        Err((
            ErrorKind::Parse,
            "STRING_TO_INT: `abc` is not a valid INT literal: `a` is not a base-10 digit"
                .to_string()
        ))
    );
    assert_eq!(from_s("", E::Dint).map_err(|e| e.0), Err(ErrorKind::Parse));
    assert_eq!(
        from_s("nan", E::Dint).map_err(|e| e.0),
        Err(ErrorKind::OutOfRange)
    );
    assert_eq!(
        from_s("12abc", E::Lreal).map_err(|e| e.0),
        Err(ErrorKind::Parse)
    );
}

#[test]
fn string_to_times_and_dates() {
    assert_eq!(from_s("T#1s", E::Time), Ok(Value::time(1_000_000_000)));
    assert_eq!(from_s(" 1h ", E::Time), Ok(Value::time(3_600_000_000_000)));
    assert_eq!(from_s("D#2024-01-31", E::Date), Ok(Value::date(19_753)));
    assert_eq!(
        from_s("TOD#00:00:01", E::Tod),
        Ok(Value::tod(1_000_000_000))
    );
    assert_eq!(
        from_s("DT#1970-01-02-00:00:00", E::Dt),
        Ok(Value::dt(86_400_000_000_000))
    );
    assert_eq!(
        from_s("T#1q", E::Time).map_err(|e| e.1),
        Err("STRING_TO_TIME: `T#1q` is not a valid TIME literal: `q` is not a unit (d, h, m, s, ms, us, ns)".to_string())
    );
    assert_eq!(
        from_s("D#2023-02-29", E::Date).map_err(|e| e.0),
        Err(ErrorKind::InvalidDate)
    );
}

#[test]
fn string_wstring_and_characters() {
    let w = convert(&Value::Str(vec![b'a', 0xE9]), E::Wstring);
    assert_eq!(w, Ok(Value::WStr(vec![0x61, 0xE9])));
    let s = convert(&Value::WStr(vec![0x61, 0xE9, 0x20AC]), E::String);
    assert_eq!(s, Ok(Value::Str(vec![0x61, 0xE9, b'?'])));
    assert_eq!(
        convert(&Value::string("xyz"), E::Char),
        Ok(Value::Char(b'x'))
    );
    assert_eq!(convert(&Value::string(""), E::Char), Ok(Value::Char(0)));
    assert_eq!(
        convert(&Value::WStr(vec![0x20AC]), E::Wchar),
        Ok(Value::WChar(0x20AC))
    );
    assert_eq!(
        convert(&Value::WStr(vec![0x20AC]), E::Char),
        Ok(Value::Char(b'?'))
    );
    assert_eq!(convert(&Value::WStr(vec![]), E::Wchar), Ok(Value::WChar(0)));
    assert_eq!(
        convert(&Value::string("a"), E::Wchar),
        Ok(Value::WChar(0x61))
    );
    assert_eq!(
        convert(&Value::wstring("16#10"), E::Int),
        Ok(Value::Int(16, E::Int))
    );
    assert_eq!(
        convert(&Value::WStr(vec![0xD800]), E::Int).map_err(|e| e.message),
        Err("WSTRING_TO_INT: `\u{fffd}` is not a valid INT literal: `\u{fffd}` is not a base-10 digit".to_string())
    );
    assert_eq!(
        convert(&Value::Char(b'A'), E::Int),
        Ok(Value::Int(65, E::Int))
    );
    assert_eq!(
        convert(&Value::WChar(0x20AC), E::Byte),
        Ok(Value::Int(0xAC, E::Byte))
    );
    assert_eq!(
        convert(&Value::Int(0x141, E::Word), E::Char),
        Ok(Value::Char(0x41))
    );
    assert_eq!(
        convert(&Value::Int(-1, E::Int), E::Wchar),
        Ok(Value::WChar(0xFFFF))
    );
    assert_eq!(
        convert(&Value::Char(0xE9), E::Wchar),
        Ok(Value::WChar(0xE9))
    );
    assert_eq!(
        convert(&Value::WChar(0x100), E::Char),
        Ok(Value::Char(b'?'))
    );
    assert_eq!(
        convert(&Value::Char(b'q'), E::Wstring),
        Ok(Value::WStr(vec![0x71]))
    );
    assert_eq!(char_to_byte('\u{ff}'), 0xFF);
    assert_eq!(char_to_byte('\u{100}'), b'?');
    assert_eq!(ucs2_text(&[0x41, 0xD83D, 0xDE00]), "A\u{1F600}");
}

#[test]
fn text_round_trips_through_string() {
    let values = [
        Value::Int(-32768, E::Int),
        Value::Int(u64::MAX.into(), E::Lword),
        Value::real(0.1, E::Real),
        Value::real(-1.5e300, E::Lreal),
        Value::Bool(false),
        Value::time(-1),
        Value::Tod(86_399_999_999_999, E::Ltod),
        Value::Dt(-1, E::Ldt),
        Value::Date(-1, E::Ldate),
    ];
    for v in values {
        let s = convert(&v, E::String);
        let back = s.and_then(|s| convert(&s, v.ty()));
        assert_eq!(back, Ok(v.clone()), "{v:?}");
    }
}

#[test]
fn booleans_and_times_to_wstring() {
    assert_eq!(
        convert(&Value::Bool(false), E::Wstring),
        Ok(Value::wstring("FALSE"))
    );
    assert_eq!(
        convert(&Value::time(-5_000_000_000), E::Wstring),
        Ok(Value::wstring("T#-5s"))
    );
    assert_eq!(
        convert(&Value::wstring(" T#-5s "), E::Time),
        Ok(Value::time(-5_000_000_000))
    );
    assert_eq!(
        convert(&Value::wstring("FALSE"), E::Bool),
        Ok(Value::Bool(false))
    );
    assert_eq!(
        convert(&Value::wstring("maybe"), E::Bool).map_err(|e| e.message),
        Err(
            "WSTRING_TO_BOOL: `maybe` is not a valid BOOL literal: expected TRUE, FALSE, 1 or 0"
                .to_string()
        )
    );
}
