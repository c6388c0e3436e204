//! Types of expressions and of operator applications (the rules are written
//! down in [`crate::lattice`]).
//!
//! Invariants:
//! - [`Ty::AnyInt`], [`Ty::AnyReal`] and [`Ty::AnyStr`] are untyped constants:
//!   their [`Typed::value`] is always known.
//! - [`Ty::Error`] is poison: every rule here maps it to `Error` without
//!   complaint, so one mistake gives one diagnostic.

use crate::lattice::{implicit, int_fits, literal_chain, long_of, lub, natural_int, real_fits};
use crate::types::{Elem, TypeId, TypeKind, TypeTable};
use crate::value::Value;
use automat_syntax::ast::{BinaryOp, UnaryOp};

/// The type of an expression.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Ty {
    /// Already reported: silences follow-on errors.
    Error,
    Of(TypeId),
    /// An untyped integer literal or a folded expression of them.
    AnyInt,
    /// An untyped real literal or a folded expression of them.
    AnyReal,
    /// A string literal (`'..'` narrow, `".."` wide).
    AnyStr {
        wide: bool,
    },
    /// A reference to a variable of this type (`REF(x)`, `ADR(x)`), whether
    /// or not the project declares that `REF_TO` type.
    RefOf(TypeId),
}

impl Ty {
    pub fn elem(e: Elem) -> Ty {
        Ty::Of(TypeId::elem(e))
    }

    pub fn is_error(self) -> bool {
        self == Ty::Error
    }
}

/// An expression's type and, when known at compile time, its value.
#[derive(Clone, Debug, PartialEq)]
pub struct Typed {
    pub ty: Ty,
    pub value: Option<Value>,
}

impl Typed {
    pub const ERROR: Typed = Typed {
        ty: Ty::Error,
        value: None,
    };

    pub fn of(id: TypeId) -> Typed {
        Typed {
            ty: Ty::Of(id),
            value: None,
        }
    }

    pub fn elem(e: Elem) -> Typed {
        Typed::of(TypeId::elem(e))
    }

    pub fn with(ty: Ty, value: Value) -> Typed {
        Typed {
            ty,
            value: Some(value),
        }
    }
}

/// What an operand looks like to the operator rules.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Shape {
    Error,
    Elem(Elem),
    Str(bool),
    Enum(TypeId),
    Int(i128),
    Real(f64),
    /// A reference, by the type it designates.
    Ref(TypeId),
    Other,
}

fn shape(types: &TypeTable, t: &Typed) -> Shape {
    match t.ty {
        Ty::Error => Shape::Error,
        Ty::AnyInt => Shape::Int(t.value.as_ref().and_then(Value::as_int).unwrap_or(0)),
        Ty::AnyReal => Shape::Real(match t.value {
            Some(Value::Real(r)) => r,
            _ => 0.0,
        }),
        Ty::AnyStr { wide } => Shape::Str(wide),
        Ty::RefOf(t) => Shape::Ref(t),
        Ty::Of(id) => match types.get(id) {
            TypeKind::Error => Shape::Error,
            TypeKind::Elem(e) | TypeKind::Subrange { base: e, .. } => Shape::Elem(*e),
            TypeKind::String { wide, .. } => Shape::Str(*wide),
            TypeKind::Enum { .. } => Shape::Enum(id),
            TypeKind::Ref(t) => Shape::Ref(*t),
            _ => Shape::Other,
        },
    }
}

/// The elementary type an untyped literal takes next to an operand of type `other`.
fn adapt(lit: Shape, other: Elem) -> Option<Elem> {
    match lit {
        Shape::Int(v) => literal_chain(other)
            .iter()
            .copied()
            .find(|&e| int_fits(v, e))
            .or_else(|| natural_int(v)),
        Shape::Real(r) => Some(if other.is_real() {
            if real_fits(r, other) {
                other
            } else {
                Elem::Lreal
            }
        } else if implicit(other, Elem::Real) && real_fits(r, Elem::Real) {
            Elem::Real
        } else {
            Elem::Lreal
        }),
        Shape::Elem(e) => Some(e),
        _ => None,
    }
}

fn is_compare(op: BinaryOp) -> bool {
    use BinaryOp::*;
    matches!(op, Lt | Gt | Le | Ge | Eq | Ne)
}

/// The result type of `l op r`; `None` when the operator is not defined for
/// these operands (E031).
pub fn binary(types: &TypeTable, op: BinaryOp, l: &Typed, r: &Typed) -> Option<Ty> {
    binary_in(types, op, l, r, false)
}

/// [`binary`]; `codesys`: `+ - * / MOD` also apply to BYTE, WORD, DWORD
/// and LWORD (the result is the wider operand's type and wraps as it).
pub fn binary_in(
    types: &TypeTable,
    op: BinaryOp,
    l: &Typed,
    r: &Typed,
    codesys: bool,
) -> Option<Ty> {
    let strict = binary_strict(types, op, l, r);
    if strict.is_some() || !codesys {
        return strict;
    }
    let word = |e: Elem| e.is_bit() && e != Elem::Bool;
    let int_like = |s: &Shape| match s {
        Shape::Int(_) => true,
        Shape::Elem(e) => e.is_int() || word(*e),
        _ => false,
    };
    let (ls, rs) = (shape(types, l), shape(types, r));
    // Pointers compare as addresses: with each other whatever they point
    // to, and with integers (`p <> 0`).
    if is_compare(op) && (matches!(ls, Shape::Ref(_)) || matches!(rs, Shape::Ref(_))) {
        let addr = |s: &Shape| matches!(s, Shape::Ref(_)) || int_like(s);
        return (addr(&ls) && addr(&rs)).then_some(Ty::elem(Elem::Bool));
    }
    if !matches!(
        op,
        BinaryOp::Add | BinaryOp::Sub | BinaryOp::Mul | BinaryOp::Div | BinaryOp::Mod
    ) {
        return strict;
    }
    match (ls, rs) {
        // Pointer arithmetic: an offset in bytes, as CODESYS counts it.
        (Shape::Ref(_), s) if int_like(&s) && matches!(op, BinaryOp::Add | BinaryOp::Sub) => {
            Some(l.ty)
        }
        (s, Shape::Ref(_)) if int_like(&s) && op == BinaryOp::Add => Some(r.ty),
        (Shape::Elem(a), Shape::Elem(b)) if word(a) && word(b) => lub(a, b).map(Ty::elem),
        (Shape::Elem(a), s @ Shape::Int(_)) if word(a) => {
            adapt(s, a).and_then(|b| lub(a, b)).map(Ty::elem)
        }
        (s @ Shape::Int(_), Shape::Elem(b)) if word(b) => {
            adapt(s, b).and_then(|a| lub(a, b)).map(Ty::elem)
        }
        _ => None,
    }
}

fn binary_strict(types: &TypeTable, op: BinaryOp, l: &Typed, r: &Typed) -> Option<Ty> {
    use BinaryOp::*;
    let (ls, rs) = (shape(types, l), shape(types, r));
    match (ls, rs) {
        (Shape::Error, _) | (_, Shape::Error) => Some(Ty::Error),
        // References are equal when they designate the same variable (or
        // are both NULL); they have no order.
        (Shape::Ref(a), Shape::Ref(b)) => {
            (a == b && matches!(op, Eq | Ne)).then_some(Ty::elem(Elem::Bool))
        }
        _ if is_compare(op) => compare(ls, rs).then_some(Ty::elem(Elem::Bool)),
        (Shape::Int(_), Shape::Int(_)) => match op {
            Pow => Some(Ty::AnyReal),
            _ => Some(Ty::AnyInt),
        },
        (Shape::Int(_) | Shape::Real(_), Shape::Int(_) | Shape::Real(_)) => {
            matches!(op, Add | Sub | Mul | Div | Pow).then_some(Ty::AnyReal)
        }
        (Shape::Elem(a), Shape::Int(_) | Shape::Real(_)) => {
            elem_binary(op, a, adapt(rs, a)?).map(Ty::elem)
        }
        (Shape::Int(_) | Shape::Real(_), Shape::Elem(b)) => {
            elem_binary(op, adapt(ls, b)?, b).map(Ty::elem)
        }
        (Shape::Elem(a), Shape::Elem(b)) => elem_binary(op, a, b).map(Ty::elem),
        _ => None,
    }
}

/// Whether two operands can be compared (the result is BOOL).
fn compare(l: Shape, r: Shape) -> bool {
    match (l, r) {
        (Shape::Enum(a), Shape::Enum(b)) => a == b,
        (Shape::Str(a), Shape::Str(b)) => a == b,
        (Shape::Int(_) | Shape::Real(_), Shape::Int(_) | Shape::Real(_)) => true,
        (Shape::Elem(a), Shape::Int(_) | Shape::Real(_)) => {
            adapt(r, a).and_then(|b| lub(a, b)).is_some_and(comparable)
        }
        (Shape::Int(_) | Shape::Real(_), Shape::Elem(b)) => {
            adapt(l, b).and_then(|a| lub(a, b)).is_some_and(comparable)
        }
        (Shape::Elem(a), Shape::Elem(b)) => lub(a, b).is_some_and(comparable),
        _ => false,
    }
}

fn comparable(e: Elem) -> bool {
    e.is_num() || e.is_bit() || e.is_duration() || e.is_date() || e.is_char()
}

/// Operator rules on two elementary operand types.
fn elem_binary(op: BinaryOp, a: Elem, b: Elem) -> Option<Elem> {
    use BinaryOp::*;
    use Elem::*;
    match op {
        Add | Sub if a.is_duration() && b.is_duration() => lub(a, b),
        Add | Sub if matches!(a, Dt | Ldt | Tod | Ltod) && b.is_duration() => {
            Some(if b == Ltime { long_of(a) } else { a })
        }
        Sub if matches!(a, Dt | Ldt) && matches!(b, Dt | Ldt) => Some(longer_time(a, b)),
        Sub if matches!(a, Tod | Ltod) && matches!(b, Tod | Ltod) => Some(longer_time(a, b)),
        Sub if matches!(a, Date | Ldate) && matches!(b, Date | Ldate) => Some(longer_time(a, b)),
        Mul if a.is_duration() && b.is_num() => Some(a),
        Mul if a.is_num() && b.is_duration() => Some(b),
        Div if a.is_duration() && b.is_num() => Some(a),
        Add | Sub | Mul | Div => lub(a, b).filter(|c| c.is_num()),
        Mod => lub(a, b).filter(|c| c.is_int()),
        Pow if a.is_num() && b.is_num() => Some(if a.is_real() {
            a
        } else if a.bits() <= 16 {
            Real
        } else {
            Lreal
        }),
        Pow => None,
        And | Or | Xor => lub(a, b).filter(|c| c.is_bit() || c.is_int()),
        Lt | Gt | Le | Ge | Eq | Ne => lub(a, b).filter(|&c| comparable(c)).map(|_| Bool),
    }
}

/// TIME, or LTIME when either date operand is a long one.
fn longer_time(a: Elem, b: Elem) -> Elem {
    if long_of(a) == a || long_of(b) == b {
        Elem::Ltime
    } else {
        Elem::Time
    }
}

/// The result type of a unary operator; `None` when not defined (E031).
pub fn unary(types: &TypeTable, op: UnaryOp, t: &Typed) -> Option<Ty> {
    match (op, shape(types, t)) {
        (_, Shape::Error) => Some(Ty::Error),
        (UnaryOp::Neg | UnaryOp::Plus, Shape::Int(_)) => Some(Ty::AnyInt),
        (UnaryOp::Neg | UnaryOp::Plus, Shape::Real(_)) => Some(Ty::AnyReal),
        (UnaryOp::Not, Shape::Int(_)) => Some(Ty::AnyInt),
        (UnaryOp::Neg, Shape::Elem(e)) => {
            (e.is_signed() || e.is_real() || e.is_duration()).then_some(Ty::elem(e))
        }
        (UnaryOp::Plus, Shape::Elem(e)) => (e.is_num() || e.is_duration()).then_some(Ty::elem(e)),
        (UnaryOp::Not, Shape::Elem(e)) => (e.is_bit() || e.is_int()).then_some(Ty::elem(e)),
        _ => None,
    }
}

#[cfg(test)]
mod tests;
