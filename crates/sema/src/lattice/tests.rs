use super::*;
use crate::types::Elem::{self, *};

/// Every implicit conversion between distinct elementary types, written out.
const ALLOWED: &[(Elem, &[Elem])] = &[
    (Sint, &[Int, Dint, Lint, Real, Lreal]),
    (Int, &[Dint, Lint, Real, Lreal]),
    (Dint, &[Lint, Lreal]),
    (Lint, &[]),
    (Usint, &[Uint, Udint, Ulint, Int, Dint, Lint, Real, Lreal]),
    (Uint, &[Udint, Ulint, Dint, Lint, Real, Lreal]),
    (Udint, &[Ulint, Lint, Lreal]),
    (Ulint, &[]),
    (Real, &[Lreal]),
    (Lreal, &[]),
    (Bool, &[]),
    (Byte, &[Word, Dword, Lword]),
    (Word, &[Dword, Lword]),
    (Dword, &[Lword]),
    (Lword, &[]),
    (Time, &[Ltime]),
    (Ltime, &[]),
    (Date, &[Ldate]),
    (Ldate, &[]),
    (Tod, &[Ltod]),
    (Ltod, &[]),
    (Dt, &[Ldt]),
    (Ldt, &[]),
    (Char, &[]),
    (Wchar, &[]),
];

#[test]
fn every_implicit_conversion_pair() {
    assert_eq!(ALLOWED.len(), Elem::ALL.len());
    for from in Elem::ALL {
        let allowed = ALLOWED
            .iter()
            .find(|(f, _)| *f == from)
            .map(|(_, to)| *to)
            .unwrap_or(&[]);
        for to in Elem::ALL {
            let expected = from == to || allowed.contains(&to);
            assert_eq!(
                implicit(from, to),
                expected,
                "{} -> {}",
                from.name(),
                to.name()
            );
        }
    }
}

#[test]
fn least_upper_bounds() {
    let cases = [
        (Sint, Int, Some(Int)),
        (Int, Sint, Some(Int)),
        (Sint, Usint, Some(Int)),
        (Int, Uint, Some(Dint)),
        (Dint, Udint, Some(Lint)),
        (Lint, Ulint, None),
        (Int, Real, Some(Real)),
        (Dint, Real, Some(Lreal)),
        (Lint, Real, None),
        (Byte, Word, Some(Word)),
        (Byte, Sint, None),
        (Bool, Byte, None),
        (Bool, Bool, Some(Bool)),
        (Time, Ltime, Some(Ltime)),
        (Time, Dint, None),
        (Dt, Ldt, Some(Ldt)),
        (Char, Wchar, None),
    ];
    for (a, b, want) in cases {
        assert_eq!(lub(a, b), want, "{} ⊔ {}", a.name(), b.name());
    }
}

#[test]
fn lub_is_symmetric_and_an_upper_bound() {
    for a in Elem::ALL {
        for b in Elem::ALL {
            assert_eq!(lub(a, b), lub(b, a));
            if let Some(c) = lub(a, b) {
                assert!(implicit(a, c) && implicit(b, c));
            }
        }
    }
}

#[test]
fn literal_fit_and_natural_types() {
    assert!(int_fits(127, Sint));
    assert!(!int_fits(128, Sint));
    assert!(int_fits(1, Bool));
    assert!(!int_fits(2, Bool));
    assert!(!int_fits(-1, Byte));
    assert!(int_fits(u64::MAX as i128, Lword));
    assert!(int_fits(1 << 100, Real));
    assert!(!int_fits(1, Time));
    assert_eq!(natural_int(5), Some(Sint));
    assert_eq!(natural_int(300), Some(Int));
    assert_eq!(natural_int(1 << 40), Some(Lint));
    assert_eq!(natural_int(u64::MAX as i128), Some(Ulint));
    assert_eq!(natural_int(1 << 70), None);
    assert!(real_fits(1e38, Real));
    assert!(!real_fits(1e39, Real));
    assert!(real_fits(1e300, Lreal));
    assert_eq!(literal_chain(Int), &[Int, Dint, Lint]);
    assert_eq!(literal_chain(Time), &[] as &[Elem]);
}

#[test]
fn elementary_names_round_trip() {
    for e in Elem::ALL {
        assert_eq!(Elem::from_name(e.name()), Some(e));
    }
    assert_eq!(Elem::from_name("time_of_day"), Some(Tod));
    assert_eq!(Elem::from_name("Date_And_Time"), Some(Dt));
    assert_eq!(Elem::from_name("STRING"), None);
}
