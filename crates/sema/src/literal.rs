//! Types and values of literals (shared by declaration folding and body checking).
//!
//! Untyped numeric and string literals get the untyped types of [`Ty`];
//! time and date literals and TRUE/FALSE have their types; a typed literal
//! (`INT#5`, `Color#Red`) has the type its prefix names (resolved by the
//! caller). The range of typed elementary literals is the parser's check (E006).

use crate::names::type_name;
use crate::ops::{Ty, Typed};
use crate::types::{Elem, TypeId, TypeKind, TypeTable};
use crate::value::Value;
use automat_base::{Code, Diagnostic, Interner, Span};
use automat_syntax::ast::LitKind;

/// The type and value of a literal. `ty` is the resolved prefix type, if any.
pub fn literal(
    types: &TypeTable,
    interner: &Interner,
    kind: &LitKind,
    ty: Option<TypeId>,
    span: Span,
) -> Result<Typed, Diagnostic> {
    let long = |l: bool, short: Elem, long: Elem| Ty::elem(if l { long } else { short });
    let untyped = match kind {
        LitKind::Int(v) => Typed::with(Ty::AnyInt, Value::Int(*v)),
        LitKind::Real(r) => Typed::with(Ty::AnyReal, Value::Real(*r)),
        LitKind::Bool(b) => Typed::with(Ty::elem(Elem::Bool), Value::Bool(*b)),
        LitKind::Duration { nanos, long: l } => {
            Typed::with(long(*l, Elem::Time, Elem::Ltime), Value::Duration(*nanos))
        }
        LitKind::Date { days, long: l } => {
            Typed::with(long(*l, Elem::Date, Elem::Ldate), Value::Date(*days))
        }
        LitKind::TimeOfDay { nanos, long: l } => {
            Typed::with(long(*l, Elem::Tod, Elem::Ltod), Value::Tod(*nanos))
        }
        LitKind::DateTime { nanos, long: l } => {
            Typed::with(long(*l, Elem::Dt, Elem::Ldt), Value::DateTime(*nanos))
        }
        LitKind::String { value, wide } => {
            Typed::with(Ty::AnyStr { wide: *wide }, Value::Str(value.clone()))
        }
        LitKind::Enum(_) => Typed::ERROR,
    };
    let Some(ty) = ty else {
        return match kind {
            LitKind::Enum(v) => Err(Diagnostic::error(
                Code::E020,
                v.span,
                format!("unknown enumeration value `{}`", interner.name(v.sym)),
            )),
            _ => Ok(untyped),
        };
    };
    if ty == TypeId::ERROR {
        return Ok(Typed::ERROR);
    }
    let mismatch = || {
        Diagnostic::error(
            Code::E030,
            span,
            format!(
                "a literal of this kind cannot have type {}",
                type_name(types, interner, ty)
            ),
        )
    };
    match (kind, types.get(ty)) {
        (LitKind::Enum(v), TypeKind::Enum { values, .. }) => {
            match values.iter().find(|x| x.name == v.sym) {
                Some(x) => Ok(Typed::with(Ty::Of(ty), Value::Enum(x.value))),
                None => Err(Diagnostic::error(
                    Code::E020,
                    v.span,
                    format!(
                        "enumeration `{}` has no value `{}`",
                        type_name(types, interner, ty),
                        interner.name(v.sym)
                    ),
                )),
            }
        }
        (LitKind::Enum(_), _) => Err(mismatch()),
        (_, _) => {
            let Some(e) = types.elem(ty) else {
                return match (kind, types.get(ty)) {
                    (LitKind::String { wide, .. }, TypeKind::String { wide: w, .. })
                        if wide == w =>
                    {
                        Ok(Typed {
                            ty: Ty::Of(ty),
                            value: untyped.value,
                        })
                    }
                    _ => Err(mismatch()),
                };
            };
            let ok = match kind {
                LitKind::Int(_) => e.is_num() || e.is_bit(),
                LitKind::Real(_) => e.is_real(),
                LitKind::Bool(_) => e == Elem::Bool,
                LitKind::String { wide, value } => {
                    e == if *wide { Elem::Wchar } else { Elem::Char } && value.chars().count() == 1
                }
                LitKind::Duration { .. } => e.is_duration(),
                LitKind::Date { .. } => matches!(e, Elem::Date | Elem::Ldate),
                LitKind::TimeOfDay { .. } => matches!(e, Elem::Tod | Elem::Ltod),
                LitKind::DateTime { .. } => matches!(e, Elem::Dt | Elem::Ldt),
                LitKind::Enum(_) => false,
            };
            if !ok {
                return Err(mismatch());
            }
            Ok(Typed {
                ty: Ty::Of(ty),
                value: untyped.value.map(|v| v.coerce(e)),
            })
        }
    }
}
