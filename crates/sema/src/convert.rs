//! Whether a typed value may be stored into a variable of a type (assignment,
//! argument passing, initial values): the implicit conversions of
//! [`crate::lattice`] applied to expression types, constants checked
//! against ranges.

use crate::lattice::{implicit, int_fits, real_fits};
use crate::ops::{Ty, Typed};
use crate::types::{TypeId, TypeKind, TypeTable};
use crate::value::Value;

/// The verdict of [`fits`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fit {
    Ok,
    /// A typed constant converted to a narrower type; its value fits (W003).
    NarrowedConstant,
    /// An untyped constant whose value the type cannot hold (E030 naming the value).
    OutOfRange,
    /// A constant outside the limits of a subrange (E038).
    OutOfSubrange {
        lo: i128,
        hi: i128,
    },
    /// No implicit conversion (E030 naming both types).
    Mismatch,
}

/// CODESYS pointers (`--lib codesys`): a pointer converts to a pointer of
/// any other type and to and from the unsigned integers and bit strings
/// of 32 and 64 bits (`ADR` results in a DWORD, as V2.3 code keeps
/// them); the constant 0 is the null pointer. A pointer is a 32-bit image offset: a 64-bit value keeps its
/// low 32 bits, and every dereference is checked against the image.
pub fn pointer_cast(types: &TypeTable, from: &Typed, to: TypeId) -> bool {
    use crate::types::Elem;
    let is_ref = |id: TypeId| matches!(types.get(id), TypeKind::Ref(_));
    let addr_int = |id: TypeId| {
        matches!(
            types.get(id),
            TypeKind::Elem(Elem::Udint | Elem::Dword | Elem::Ulint | Elem::Lword)
        )
    };
    // `p := 0;`: the null pointer, as CODESYS code clears one.
    if is_ref(to) && from.value.as_ref().and_then(Value::as_int) == Some(0) {
        return true;
    }
    match from.ty {
        Ty::Of(f) => (is_ref(f) && (is_ref(to) || addr_int(to))) || (addr_int(f) && is_ref(to)),
        Ty::RefOf(_) => is_ref(to) || addr_int(to),
        _ => false,
    }
}

/// Checks that `from` converts implicitly to `to`.
pub fn fits(types: &TypeTable, from: &Typed, to: TypeId) -> Fit {
    if from.ty == Ty::Error || to == TypeId::ERROR {
        return Fit::Ok;
    }
    match types.get(to) {
        TypeKind::Error => Fit::Ok,
        TypeKind::Subrange { base, lo, hi } => {
            let base_fit = fits(types, from, TypeId::elem(*base));
            if matches!(base_fit, Fit::Ok | Fit::NarrowedConstant) {
                if let Some(v) = from.value.as_ref().and_then(Value::as_int) {
                    if v < *lo || v > *hi {
                        return Fit::OutOfSubrange { lo: *lo, hi: *hi };
                    }
                }
            }
            base_fit
        }
        TypeKind::Elem(e) => {
            let e = *e;
            match (from.ty, &from.value) {
                (Ty::AnyInt, Some(v)) => match v.as_int() {
                    Some(v) if int_fits(v, e) => Fit::Ok,
                    Some(_) if e.is_num() || e.is_bit() => Fit::OutOfRange,
                    _ => Fit::Mismatch,
                },
                (Ty::AnyReal, Some(Value::Real(r))) => {
                    if real_fits(*r, e) {
                        Fit::Ok
                    } else if e.is_real() {
                        Fit::OutOfRange
                    } else {
                        Fit::Mismatch
                    }
                }
                (Ty::AnyStr { wide }, Some(Value::Str(s))) => {
                    let want = if wide {
                        crate::types::Elem::Wchar
                    } else {
                        crate::types::Elem::Char
                    };
                    if e == want && s.chars().count() == 1 {
                        Fit::Ok
                    } else {
                        Fit::Mismatch
                    }
                }
                (Ty::Of(id), value) => match types.elem(id) {
                    Some(f) if implicit(f, e) => Fit::Ok,
                    Some(f) if (f.is_int() || f.is_bit()) && (e.is_int() || e.is_bit()) => {
                        match value.as_ref().and_then(Value::as_int) {
                            Some(v) if f != crate::types::Elem::Bool && int_fits(v, e) => {
                                Fit::NarrowedConstant
                            }
                            _ => Fit::Mismatch,
                        }
                    }
                    _ => Fit::Mismatch,
                },
                _ => Fit::Mismatch,
            }
        }
        TypeKind::String { wide, .. } => {
            let ok = match from.ty {
                Ty::AnyStr { wide: w } => w == *wide,
                Ty::Of(id) => {
                    matches!(types.get(id), TypeKind::String { wide: w, .. } if w == wide)
                }
                _ => false,
            };
            if ok {
                Fit::Ok
            } else {
                Fit::Mismatch
            }
        }
        TypeKind::Ref(target) => match from.ty {
            Ty::Of(id) if id == to => Fit::Ok,
            Ty::RefOf(t) if t == *target => Fit::Ok,
            _ => Fit::Mismatch,
        },
        _ => match from.ty {
            Ty::Of(id) if id == to => Fit::Ok,
            _ => Fit::Mismatch,
        },
    }
}

/// The constant value of `from` as stored in a variable of type `to`
/// (assumes [`fits`] accepted it).
pub fn stored_value(types: &TypeTable, from: &Typed, to: TypeId) -> Option<Value> {
    let v = from.value.clone()?;
    Some(match types.elem(to) {
        Some(e) => v.coerce(e),
        None => v,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::types::Elem::*;

    fn int(v: i128) -> Typed {
        Typed::with(Ty::AnyInt, Value::Int(v))
    }

    #[test]
    fn literals_fit_by_value() {
        let t = TypeTable::new();
        assert_eq!(fits(&t, &int(127), TypeId::elem(Sint)), Fit::Ok);
        assert_eq!(fits(&t, &int(300), TypeId::elem(Sint)), Fit::OutOfRange);
        assert_eq!(fits(&t, &int(1), TypeId::elem(Bool)), Fit::Ok);
        assert_eq!(fits(&t, &int(2), TypeId::elem(Bool)), Fit::OutOfRange);
        assert_eq!(fits(&t, &int(2), TypeId::elem(Time)), Fit::Mismatch);
        assert_eq!(fits(&t, &int(2), TypeId::elem(Lreal)), Fit::Ok);
        let r = Typed::with(Ty::AnyReal, Value::Real(1e39));
        assert_eq!(fits(&t, &r, TypeId::elem(Real)), Fit::OutOfRange);
        assert_eq!(fits(&t, &r, TypeId::elem(Lreal)), Fit::Ok);
        assert_eq!(fits(&t, &r, TypeId::elem(Int)), Fit::Mismatch);
        let s = Typed::with(Ty::AnyStr { wide: false }, Value::Str("a".into()));
        assert_eq!(fits(&t, &s, TypeId::elem(Char)), Fit::Ok);
        assert_eq!(fits(&t, &s, TypeId::elem(Wchar)), Fit::Mismatch);
        assert_eq!(fits(&t, &s, TypeId::STRING), Fit::Ok);
        assert_eq!(fits(&t, &s, TypeId::WSTRING), Fit::Mismatch);
    }

    #[test]
    fn typed_values_follow_the_lattice() {
        let mut t = TypeTable::new();
        let d = Typed::elem(Dint);
        assert_eq!(fits(&t, &d, TypeId::elem(Int)), Fit::Mismatch);
        assert_eq!(fits(&t, &Typed::elem(Int), TypeId::elem(Dint)), Fit::Ok);
        let c = Typed::with(Ty::elem(Dint), Value::Int(5));
        assert_eq!(fits(&t, &c, TypeId::elem(Int)), Fit::NarrowedConstant);
        let s20 = t.string(false, 20);
        assert_eq!(fits(&t, &Typed::of(s20), TypeId::STRING), Fit::Ok);
        assert_eq!(fits(&t, &Typed::of(s20), TypeId::WSTRING), Fit::Mismatch);
        let sub = t.subrange(Int, 0, 100);
        assert_eq!(fits(&t, &int(50), sub), Fit::Ok);
        assert_eq!(
            fits(&t, &int(101), sub),
            Fit::OutOfSubrange { lo: 0, hi: 100 }
        );
        assert_eq!(fits(&t, &Typed::of(sub), TypeId::elem(Dint)), Fit::Ok);
        assert_eq!(fits(&t, &Typed::elem(Int), sub), Fit::Ok);
        let a = t.array(TypeId::elem(Int), vec![crate::types::Dim::Range(1, 3)]);
        assert_eq!(fits(&t, &Typed::of(a), a), Fit::Ok);
        assert_eq!(fits(&t, &Typed::elem(Int), a), Fit::Mismatch);
        assert_eq!(fits(&t, &Typed::ERROR, a), Fit::Ok);
    }
}
