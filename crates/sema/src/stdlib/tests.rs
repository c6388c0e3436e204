use super::*;
use crate::types::Elem::*;

fn sig(n: &str) -> Sig {
    lookup(n).unwrap_or_else(|| panic!("{n} is a standard function"))
}

#[test]
fn fixed_functions_have_standard_formal_names() {
    let limit = sig("limit");
    assert_eq!(limit.op, StdOp::Limit);
    let names: Vec<&str> = limit.params.iter().map(|p| p.name).collect();
    assert_eq!(names, ["MN", "IN", "MX"]);
    assert_eq!(limit.min_args(), 3);
    assert_eq!(limit.max_args(), Some(3));
    let sel = sig("SEL");
    assert_eq!(sel.params[0].ty, PTy::Elem(Bool));
    assert_eq!(sig("SHL").params[1].name, "N");
    assert_eq!(sig("MID").params.len(), 3);
    assert_eq!(sig("LEN").ret, RTy::Elem(Int));
    assert_eq!(sig("SPLIT_DATE").ret, RTy::Void);
    assert_eq!(sig("SPLIT_DT").params[7].dir, PDir::Out);
    assert_eq!(sig("CONCAT_DATE_TOD").ret, RTy::Elem(Dt));
    assert_eq!(sig("SUB_DT_DT").ret, RTy::Elem(Time));
    assert_eq!(sig("UPPER_BOUND").params[0].ty, PTy::Array);
    assert!(lookup("FROB").is_none());
    assert!(lookup("").is_none());
}

#[test]
fn extensible_functions_take_two_or_more() {
    for n in [
        "ADD", "MUL", "AND", "OR", "XOR", "MAX", "MIN", "MUX", "CONCAT", "GT", "GE", "EQ", "LE",
        "LT", "NE",
    ] {
        let s = sig(n);
        assert!(s.ext.is_some(), "{n}");
        assert_eq!(s.max_args(), None, "{n}");
    }
    let add = sig("ADD");
    assert_eq!(add.min_args(), 2);
    assert_eq!(add.position_of("IN1"), Some(0));
    assert_eq!(add.position_of("in7"), Some(6));
    assert_eq!(add.position_of("IN0"), None);
    assert_eq!(add.position_of("IN"), None);
    assert_eq!(add.position_of("INx"), None);
    assert_eq!(add.name_at(3), "IN4");
    let mux = sig("MUX");
    assert_eq!(mux.min_args(), 3);
    assert_eq!(mux.position_of("K"), Some(0));
    assert_eq!(mux.position_of("IN0"), Some(1));
    assert_eq!(mux.name_at(2), "IN1");
    assert_eq!(sig("SUB").ext, None);
}

#[test]
fn conversions_are_recognised_by_name() {
    let c = sig("INT_TO_REAL");
    assert_eq!(
        c.op,
        StdOp::Convert {
            from: ConvTy::Elem(Int),
            to: ConvTy::Elem(Real)
        }
    );
    assert_eq!(c.params[0].ty, PTy::Elem(Int));
    assert_eq!(c.ret, RTy::Elem(Real));
    assert_eq!(sig("time_of_day_to_dint").ret, RTy::Elem(Dint));
    assert_eq!(sig("DT_TO_DATE").ret, RTy::Elem(Date));
    assert_eq!(sig("DT_TO_TOD").ret, RTy::Elem(Tod));
    assert_eq!(sig("REAL_TO_STRING").ret, RTy::Str(false));
    assert_eq!(sig("STRING_TO_WSTRING").ret, RTy::Str(true));
    assert_eq!(sig("TIME_TO_DINT").ret, RTy::Elem(Dint));
    assert_eq!(sig("DWORD_TO_TIME").ret, RTy::Elem(Time));
    assert_eq!(sig("BOOL_TO_INT").ret, RTy::Elem(Int));
    assert_eq!(sig("BYTE_TO_CHAR").ret, RTy::Elem(Char));
    assert_eq!(sig("TO_INT").params[0].ty, PTy::Free(Kind::AnyElementary));
    assert_eq!(sig("TO_INT").op, StdOp::ToType(ConvTy::Elem(Int)));
    assert!(lookup("REAL_TO_DATE").is_none());
    assert!(lookup("TIME_TO_DATE").is_none());
    assert!(lookup("CHAR_TO_REAL").is_none());
    assert!(lookup("INT_TO_FOO").is_none());
    assert!(lookup("_TO_").is_none());
}

#[test]
fn trunc_and_bcd_forms() {
    assert_eq!(sig("TRUNC").op, StdOp::Trunc(Dint));
    assert_eq!(sig("TRUNC_INT").ret, RTy::Elem(Int));
    assert_eq!(sig("LREAL_TRUNC_LINT").params[0].ty, PTy::Elem(Lreal));
    assert!(lookup("INT_TRUNC_INT").is_none());
    assert_eq!(sig("BCD_TO_INT").op, StdOp::BcdToInt(Int));
    assert_eq!(sig("WORD_BCD_TO_UINT").params[0].ty, PTy::Elem(Word));
    assert_eq!(sig("INT_TO_BCD").ret, RTy::Elem(Word));
    assert_eq!(sig("UDINT_TO_BCD_DWORD").op, StdOp::IntToBcd(Dword));
    assert!(lookup("REAL_TO_BCD").is_none());
}

#[test]
fn conversion_table_is_symmetric() {
    let all: Vec<ConvTy> = crate::types::Elem::ALL
        .iter()
        .map(|&e| ConvTy::Elem(e))
        .chain([ConvTy::Str(false), ConvTy::Str(true)])
        .collect();
    for &a in &all {
        for &b in &all {
            assert_eq!(conv::allowed(a, b), conv::allowed(b, a), "{a:?} {b:?}");
        }
    }
}

#[test]
fn kinds() {
    assert!(Kind::AnyNum.has_elem(Real));
    assert!(!Kind::AnyNum.has_elem(Byte));
    assert!(Kind::AnyLogic.has_elem(Int));
    assert!(Kind::AnyLogic.has_elem(Bool));
    assert!(Kind::AnyMagnitude.has_elem(Time));
    assert!(!Kind::AnyString.has_elem(Char));
    assert!(Kind::AnyString.has_string());
    assert!(!Kind::AnyNum.has_string());
    assert_eq!(Kind::AnyReal.widen_targets(), &[Real, Lreal]);
}
