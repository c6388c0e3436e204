use super::*;
use crate::types::Elem::*;
use automat_syntax::ast::BinaryOp::*;

fn t(e: Elem) -> Typed {
    Typed::elem(e)
}

fn int(v: i128) -> Typed {
    Typed::with(Ty::AnyInt, Value::Int(v))
}

fn real(v: f64) -> Typed {
    Typed::with(Ty::AnyReal, Value::Real(v))
}

fn bin(op: BinaryOp, l: Typed, r: Typed) -> Option<Ty> {
    binary(&TypeTable::new(), op, &l, &r)
}

#[test]
fn arithmetic_widens_to_the_upper_bound() {
    let cases = [
        (Add, t(Int), t(Dint), Some(Ty::elem(Dint))),
        (Add, t(Sint), t(Usint), Some(Ty::elem(Int))),
        (Mul, t(Int), t(Real), Some(Ty::elem(Real))),
        (Mul, t(Dint), t(Real), Some(Ty::elem(Lreal))),
        (Sub, t(Lint), t(Ulint), None),
        (Add, t(Bool), t(Int), None),
        (Add, t(Byte), t(Byte), None),
        (Mod, t(Int), t(Dint), Some(Ty::elem(Dint))),
        (Mod, t(Real), t(Real), None),
        (Div, t(Lreal), t(Int), Some(Ty::elem(Lreal))),
    ];
    for (op, l, r, want) in cases {
        assert_eq!(bin(op, l.clone(), r.clone()), want, "{l:?} {op:?} {r:?}");
    }
}

#[test]
fn untyped_literals_adapt_to_the_other_operand() {
    assert_eq!(bin(Add, t(Int), int(1)), Some(Ty::elem(Int)));
    assert_eq!(bin(Add, int(1), t(Sint)), Some(Ty::elem(Sint)));
    assert_eq!(bin(Add, t(Int), int(100_000)), Some(Ty::elem(Dint)));
    assert_eq!(bin(Add, t(Uint), int(-1)), Some(Ty::elem(Dint)));
    assert_eq!(bin(Add, t(Byte), int(300)), None);
    assert_eq!(bin(Mul, t(Int), real(1.5)), Some(Ty::elem(Real)));
    assert_eq!(bin(Mul, t(Dint), real(1.5)), Some(Ty::elem(Lreal)));
    assert_eq!(bin(Mul, t(Lint), real(1.5)), None);
    assert_eq!(bin(And, t(Bool), int(1)), Some(Ty::elem(Bool)));
    assert_eq!(bin(And, t(Bool), int(5)), None);
    assert_eq!(bin(Add, int(300), int(100)), Some(Ty::AnyInt));
    assert_eq!(bin(Add, int(3), real(0.5)), Some(Ty::AnyReal));
    assert_eq!(bin(Mod, int(3), real(0.5)), None);
    assert_eq!(bin(Pow, int(2), int(3)), Some(Ty::AnyReal));
}

#[test]
fn logic_on_bits_booleans_and_integers() {
    assert_eq!(bin(And, t(Bool), t(Bool)), Some(Ty::elem(Bool)));
    assert_eq!(bin(Or, t(Byte), t(Word)), Some(Ty::elem(Word)));
    assert_eq!(bin(Xor, t(Int), t(Int)), Some(Ty::elem(Int)));
    assert_eq!(bin(And, t(Bool), t(Byte)), None);
    assert_eq!(bin(And, t(Int), t(Word)), None);
    assert_eq!(bin(And, t(Real), t(Real)), None);
}

#[test]
fn comparisons_give_bool() {
    let b = Some(Ty::elem(Bool));
    assert_eq!(bin(Lt, t(Int), t(Dint)), b);
    assert_eq!(bin(Eq, t(Time), t(Ltime)), b);
    assert_eq!(bin(Ge, t(Dt), t(Dt)), b);
    assert_eq!(bin(Eq, t(Char), t(Char)), b);
    assert_eq!(bin(Eq, t(Bool), int(1)), b);
    assert_eq!(bin(Lt, t(Int), t(Time)), None);
    assert_eq!(bin(Eq, t(Char), t(Wchar)), None);
    let s = Typed::of(TypeId::STRING);
    assert_eq!(bin(Eq, s.clone(), s.clone()), b);
    let lit = Typed::with(Ty::AnyStr { wide: false }, Value::Str("x".into()));
    assert_eq!(bin(Ne, s.clone(), lit), b);
    assert_eq!(bin(Eq, s, Typed::of(TypeId::WSTRING)), None);
}

#[test]
fn time_arithmetic() {
    let cases = [
        (Add, t(Time), t(Time), Some(Time)),
        (Sub, t(Time), t(Ltime), Some(Ltime)),
        (Mul, t(Time), t(Int), Some(Time)),
        (Mul, t(Lreal), t(Time), Some(Time)),
        (Div, t(Time), t(Real), Some(Time)),
        (Div, t(Int), t(Time), None),
        (Add, t(Dt), t(Time), Some(Dt)),
        (Add, t(Dt), t(Ltime), Some(Ldt)),
        (Sub, t(Dt), t(Time), Some(Dt)),
        (Sub, t(Dt), t(Dt), Some(Time)),
        (Sub, t(Ldt), t(Dt), Some(Ltime)),
        (Add, t(Tod), t(Time), Some(Tod)),
        (Sub, t(Tod), t(Tod), Some(Time)),
        (Sub, t(Date), t(Date), Some(Time)),
        (Add, t(Date), t(Time), None),
        (Add, t(Dt), t(Dt), None),
        (Add, t(Time), t(Dint), None),
    ];
    for (op, l, r, want) in cases {
        assert_eq!(
            bin(op, l.clone(), r.clone()),
            want.map(Ty::elem),
            "{l:?} {op:?} {r:?}"
        );
    }
    assert_eq!(bin(Mul, t(Time), int(2)), Some(Ty::elem(Time)));
    assert_eq!(bin(Div, t(Time), real(2.5)), Some(Ty::elem(Time)));
}

#[test]
fn power_results() {
    assert_eq!(bin(Pow, t(Real), t(Int)), Some(Ty::elem(Real)));
    assert_eq!(bin(Pow, t(Lreal), t(Real)), Some(Ty::elem(Lreal)));
    assert_eq!(bin(Pow, t(Int), t(Int)), Some(Ty::elem(Real)));
    assert_eq!(bin(Pow, t(Dint), int(2)), Some(Ty::elem(Lreal)));
    assert_eq!(bin(Pow, t(Bool), int(2)), None);
}

#[test]
fn unary_operators() {
    let types = TypeTable::new();
    let u = |op, x: Typed| unary(&types, op, &x);
    assert_eq!(u(UnaryOp::Neg, t(Int)), Some(Ty::elem(Int)));
    assert_eq!(u(UnaryOp::Neg, t(Uint)), None);
    assert_eq!(u(UnaryOp::Neg, t(Time)), Some(Ty::elem(Time)));
    assert_eq!(u(UnaryOp::Neg, t(Byte)), None);
    assert_eq!(u(UnaryOp::Neg, int(3)), Some(Ty::AnyInt));
    assert_eq!(u(UnaryOp::Not, t(Word)), Some(Ty::elem(Word)));
    assert_eq!(u(UnaryOp::Not, t(Real)), None);
    assert_eq!(u(UnaryOp::Plus, t(Date)), None);
}

#[test]
fn poison_is_silent() {
    assert_eq!(bin(Add, Typed::ERROR, t(Bool)), Some(Ty::Error));
    assert_eq!(bin(Lt, t(Bool), Typed::ERROR), Some(Ty::Error));
    assert_eq!(
        unary(&TypeTable::new(), UnaryOp::Neg, &Typed::ERROR),
        Some(Ty::Error)
    );
}
