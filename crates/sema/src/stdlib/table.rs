//! The standard functions with fixed names: numeric, arithmetic, bit,
//! selection, comparison, string, time/date, array and reference functions.
//! Formal parameter names are the standard's (IN, IN1, IN2, G, K, MN, MX, N,
//! L, P, ...).

use super::{Ext, Kind, PDir, PTy, Param, RTy, Sig, StdOp};
use crate::types::Elem::{self, *};

const fn p(name: &'static str, ty: PTy) -> Param {
    Param {
        name,
        ty,
        dir: PDir::In,
    }
}

const fn out(name: &'static str, ty: PTy) -> Param {
    Param {
        name,
        ty,
        dir: PDir::Out,
    }
}

const G_NUM: PTy = PTy::Gen(Kind::AnyNum);
const G_REAL: PTy = PTy::Gen(Kind::AnyReal);
const G_MAG: PTy = PTy::Gen(Kind::AnyMagnitude);
const G_LOGIC: PTy = PTy::Gen(Kind::AnyLogic);
const G_ELEM: PTy = PTy::Gen(Kind::AnyElementary);
const G_STR: PTy = PTy::Gen(Kind::AnyString);
const G_ANY: PTy = PTy::Gen(Kind::Any);
const F_INT: PTy = PTy::Free(Kind::AnyInt);
const F_ANY: PTy = PTy::Free(Kind::Any);

fn e(x: Elem) -> PTy {
    PTy::Elem(x)
}

fn sig(name: &str, op: StdOp, params: &[Param], ret: RTy) -> Sig {
    Sig {
        name: name.to_string(),
        op,
        params: params.to_vec(),
        ext: None,
        ret,
    }
}

/// `IN1, IN2, ...` of one generic type.
fn ext(
    name: &str,
    op: StdOp,
    fixed: &[Param],
    prefix: &'static str,
    first: u32,
    ty: PTy,
    ret: RTy,
) -> Sig {
    Sig {
        ext: Some(Ext {
            prefix,
            first,
            min: 2,
            ty,
        }),
        ..sig(name, op, fixed, ret)
    }
}

fn unary(name: &str, op: StdOp, ty: PTy) -> Sig {
    sig(name, op, &[p("IN", ty)], RTy::Gen)
}

fn pair(name: &str, op: StdOp, a: Elem, b: PTy, ret: Elem) -> Sig {
    sig(name, op, &[p("IN1", e(a)), p("IN2", b)], RTy::Elem(ret))
}

/// A standard function with a fixed name, by its upper-case name.
pub(super) fn fixed(n: &str) -> Option<Sig> {
    use StdOp as O;
    let date_parts = [
        ("YEAR", F_INT),
        ("MONTH", F_INT),
        ("DAY", F_INT),
        ("HOUR", F_INT),
        ("MINUTE", F_INT),
        ("SECOND", F_INT),
        ("MILLISECOND", F_INT),
    ];
    let parts = |r: std::ops::Range<usize>, dir_out: bool| -> Vec<Param> {
        date_parts
            .get(r)
            .unwrap_or(&[])
            .iter()
            .map(|&(name, ty)| if dir_out { out(name, ty) } else { p(name, ty) })
            .collect()
    };
    Some(match n {
        "ABS" => unary(n, O::Abs, G_NUM),
        "SQRT" => unary(n, O::Sqrt, G_REAL),
        "LN" => unary(n, O::Ln, G_REAL),
        "LOG" => unary(n, O::Log, G_REAL),
        "EXP" => unary(n, O::Exp, G_REAL),
        "SIN" => unary(n, O::Sin, G_REAL),
        "COS" => unary(n, O::Cos, G_REAL),
        "TAN" => unary(n, O::Tan, G_REAL),
        "ASIN" => unary(n, O::Asin, G_REAL),
        "ACOS" => unary(n, O::Acos, G_REAL),
        "ATAN" => unary(n, O::Atan, G_REAL),
        "ATAN2" => sig(n, O::Atan2, &[p("Y", G_REAL), p("X", G_REAL)], RTy::Gen),
        "EXPT" => sig(
            n,
            O::Expt,
            &[p("IN1", G_REAL), p("IN2", PTy::Free(Kind::AnyNum))],
            RTy::Gen,
        ),
        "ADD" => ext(n, O::Add, &[], "IN", 1, G_MAG, RTy::Gen),
        "MUL" => ext(n, O::Mul, &[], "IN", 1, G_NUM, RTy::Gen),
        "SUB" => sig(n, O::Sub, &[p("IN1", G_MAG), p("IN2", G_MAG)], RTy::Gen),
        "DIV" => sig(n, O::Div, &[p("IN1", G_NUM), p("IN2", G_NUM)], RTy::Gen),
        "MOD" => {
            let g = PTy::Gen(Kind::AnyInt);
            sig(n, O::Mod, &[p("IN1", g), p("IN2", g)], RTy::Gen)
        }
        "MOVE" => unary(n, O::Move, G_ANY),
        "SHL" => sig(n, O::Shl, &[p("IN", G_LOGIC), p("N", F_INT)], RTy::Gen),
        "SHR" => sig(n, O::Shr, &[p("IN", G_LOGIC), p("N", F_INT)], RTy::Gen),
        "ROL" => sig(n, O::Rol, &[p("IN", G_LOGIC), p("N", F_INT)], RTy::Gen),
        "ROR" => sig(n, O::Ror, &[p("IN", G_LOGIC), p("N", F_INT)], RTy::Gen),
        "AND" => ext(n, O::And, &[], "IN", 1, G_LOGIC, RTy::Gen),
        "OR" => ext(n, O::Or, &[], "IN", 1, G_LOGIC, RTy::Gen),
        "XOR" => ext(n, O::Xor, &[], "IN", 1, G_LOGIC, RTy::Gen),
        "NOT" => unary(n, O::Not, G_LOGIC),
        "SEL" => sig(
            n,
            O::Sel,
            &[p("G", e(Bool)), p("IN0", G_ANY), p("IN1", G_ANY)],
            RTy::Gen,
        ),
        "MAX" => ext(n, O::Max, &[], "IN", 1, G_ELEM, RTy::Gen),
        "MIN" => ext(n, O::Min, &[], "IN", 1, G_ELEM, RTy::Gen),
        "LIMIT" => sig(
            n,
            O::Limit,
            &[p("MN", G_ELEM), p("IN", G_ELEM), p("MX", G_ELEM)],
            RTy::Gen,
        ),
        "MUX" => ext(n, O::Mux, &[p("K", F_INT)], "IN", 0, G_ANY, RTy::Gen),
        "GT" => ext(n, O::Gt, &[], "IN", 1, G_ELEM, RTy::Elem(Bool)),
        "GE" => ext(n, O::Ge, &[], "IN", 1, G_ELEM, RTy::Elem(Bool)),
        "EQ" => ext(n, O::Eq, &[], "IN", 1, G_ELEM, RTy::Elem(Bool)),
        "LE" => ext(n, O::Le, &[], "IN", 1, G_ELEM, RTy::Elem(Bool)),
        "LT" => ext(n, O::Lt, &[], "IN", 1, G_ELEM, RTy::Elem(Bool)),
        "NE" => ext(n, O::Ne, &[], "IN", 1, G_ELEM, RTy::Elem(Bool)),
        "LEN" => sig(n, O::Len, &[p("IN", G_STR)], RTy::Elem(Int)),
        "LEFT" => sig(n, O::Left, &[p("IN", G_STR), p("L", F_INT)], RTy::Gen),
        "RIGHT" => sig(n, O::Right, &[p("IN", G_STR), p("L", F_INT)], RTy::Gen),
        "MID" => sig(
            n,
            O::Mid,
            &[p("IN", G_STR), p("L", F_INT), p("P", F_INT)],
            RTy::Gen,
        ),
        "CONCAT" => ext(n, O::Concat, &[], "IN", 1, G_STR, RTy::Gen),
        "INSERT" => sig(
            n,
            O::Insert,
            &[p("IN1", G_STR), p("IN2", G_STR), p("P", F_INT)],
            RTy::Gen,
        ),
        "DELETE" => sig(
            n,
            O::Delete,
            &[p("IN", G_STR), p("L", F_INT), p("P", F_INT)],
            RTy::Gen,
        ),
        "REPLACE" => sig(
            n,
            O::Replace,
            &[
                p("IN1", G_STR),
                p("IN2", G_STR),
                p("L", F_INT),
                p("P", F_INT),
            ],
            RTy::Gen,
        ),
        "FIND" => sig(
            n,
            O::Find,
            &[p("IN1", G_STR), p("IN2", G_STR)],
            RTy::Elem(Int),
        ),
        "ADD_TIME" => pair(n, O::Add, Time, e(Time), Time),
        "ADD_LTIME" => pair(n, O::Add, Ltime, e(Ltime), Ltime),
        "ADD_TOD_TIME" => pair(n, O::Add, Tod, e(Time), Tod),
        "ADD_LTOD_LTIME" => pair(n, O::Add, Ltod, e(Ltime), Ltod),
        "ADD_DT_TIME" => pair(n, O::Add, Dt, e(Time), Dt),
        "ADD_LDT_LTIME" => pair(n, O::Add, Ldt, e(Ltime), Ldt),
        "SUB_TIME" => pair(n, O::Sub, Time, e(Time), Time),
        "SUB_LTIME" => pair(n, O::Sub, Ltime, e(Ltime), Ltime),
        "SUB_DATE_DATE" => pair(n, O::Sub, Date, e(Date), Time),
        "SUB_LDATE_LDATE" => pair(n, O::Sub, Ldate, e(Ldate), Ltime),
        "SUB_TOD_TIME" => pair(n, O::Sub, Tod, e(Time), Tod),
        "SUB_LTOD_LTIME" => pair(n, O::Sub, Ltod, e(Ltime), Ltod),
        "SUB_TOD_TOD" => pair(n, O::Sub, Tod, e(Tod), Time),
        "SUB_LTOD_LTOD" => pair(n, O::Sub, Ltod, e(Ltod), Ltime),
        "SUB_DT_TIME" => pair(n, O::Sub, Dt, e(Time), Dt),
        "SUB_LDT_LTIME" => pair(n, O::Sub, Ldt, e(Ltime), Ldt),
        "SUB_DT_DT" => pair(n, O::Sub, Dt, e(Dt), Time),
        "SUB_LDT_LDT" => pair(n, O::Sub, Ldt, e(Ldt), Ltime),
        "MUL_TIME" => pair(n, O::Mul, Time, PTy::Free(Kind::AnyNum), Time),
        "MUL_LTIME" => pair(n, O::Mul, Ltime, PTy::Free(Kind::AnyNum), Ltime),
        "DIV_TIME" => pair(n, O::Div, Time, PTy::Free(Kind::AnyNum), Time),
        "DIV_LTIME" => pair(n, O::Div, Ltime, PTy::Free(Kind::AnyNum), Ltime),
        "CONCAT_DATE_TOD" => pair(n, O::ConcatDateTod, Date, e(Tod), Dt),
        "CONCAT_LDATE_LTOD" => pair(n, O::ConcatDateTod, Ldate, e(Ltod), Ldt),
        "CONCAT_DATE" => sig(n, O::ConcatDate, &parts(0..3, false), RTy::Elem(Date)),
        "CONCAT_TOD" => sig(n, O::ConcatTod, &parts(3..7, false), RTy::Elem(Tod)),
        "CONCAT_DT" => sig(n, O::ConcatDt, &parts(0..7, false), RTy::Elem(Dt)),
        "SPLIT_DATE" => split(n, O::SplitDate, Date, parts(0..3, true)),
        "SPLIT_TOD" => split(n, O::SplitTod, Tod, parts(3..7, true)),
        "SPLIT_DT" => split(n, O::SplitDt, Dt, parts(0..7, true)),
        "DAY_OF_WEEK" => sig(n, O::DayOfWeek, &[p("IN", e(Date))], RTy::Elem(Int)),
        "LOWER_BOUND" => sig(
            n,
            O::LowerBound,
            &[p("ARR", PTy::Array), p("DIM", F_INT)],
            RTy::Elem(Dint),
        ),
        "UPPER_BOUND" => sig(
            n,
            O::UpperBound,
            &[p("ARR", PTy::Array), p("DIM", F_INT)],
            RTy::Elem(Dint),
        ),
        "TRUNC" => sig(
            n,
            O::Trunc(Dint),
            &[p("IN", PTy::Free(Kind::AnyReal))],
            RTy::Elem(Dint),
        ),
        "REF" => sig(n, O::Ref, &[p("IN", F_ANY)], RTy::RefToArg),
        "ADR" => sig(n, O::Adr, &[p("IN", F_ANY)], RTy::RefToArg),
        "SIZEOF" => sig(n, O::Sizeof, &[p("IN", F_ANY)], RTy::Elem(Udint)),
        "__SCAN_TIME" => sig(n, O::ScanTime, &[], RTy::Elem(Time)),
        _ => return None,
    })
}

/// SPLIT_DATE and friends: one input and outputs, no return value (the
/// result type is BOOL-less: such a call is a statement).
fn split(n: &str, op: StdOp, input: Elem, outs: Vec<Param>) -> Sig {
    let mut params = vec![p("IN", e(input))];
    params.extend(outs);
    Sig {
        name: n.to_string(),
        op,
        params,
        ext: None,
        ret: RTy::Void,
    }
}
