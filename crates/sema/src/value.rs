//! Compile-time values: the results of constant folding and the initial
//! values recorded in the model.
//!
//! Invariants:
//! - A [`Value`] carries no type; the type is the one the checker computed
//!   for the expression or declared for the variable. Integer-like types
//!   (integers, bit strings, enumerations) are `Int`, BOOL is `Bool`.
//! - Folding uses exact arithmetic on `i128` and reports overflow of that
//!   range; range checks against a declared type are the caller's job
//!   ([`crate::lattice::int_fits`]).
//! - Folding never panics: division by zero and overflow are errors.

use crate::types::{Elem, TypeId, TypeKind, TypeTable};
use automat_base::Symbol;
use automat_syntax::ast::{BinaryOp, UnaryOp};

#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Bool(bool),
    Int(i128),
    Real(f64),
    /// TIME / LTIME, in nanoseconds.
    Duration(i128),
    /// DATE / LDATE, days since 1970-01-01.
    Date(i64),
    /// TOD / LTOD, nanoseconds since midnight.
    Tod(i64),
    /// DT / LDT, nanoseconds since 1970-01-01T00:00:00.
    DateTime(i128),
    /// STRING, WSTRING, CHAR, WCHAR.
    Str(String),
    /// The numeric value of an enumeration value.
    Enum(i128),
}

impl Value {
    pub fn as_int(&self) -> Option<i128> {
        match self {
            Value::Int(v) | Value::Enum(v) => Some(*v),
            Value::Bool(b) => Some(*b as i128),
            _ => None,
        }
    }

    /// The value as written in a message (`300`, `2.5`, `TRUE`, `'abc'`).
    pub fn show(&self) -> String {
        match self {
            Value::Bool(b) => if *b { "TRUE" } else { "FALSE" }.to_string(),
            Value::Int(v) | Value::Enum(v) => v.to_string(),
            Value::Real(r) => format!("{r:?}"),
            Value::Duration(ns) => format!("T#{}ms", ns / 1_000_000),
            Value::Date(d) => format!("D#{d}"),
            Value::Tod(ns) => format!("TOD#{}ms", ns / 1_000_000),
            Value::DateTime(ns) => format!("DT#{}s", ns / 1_000_000_000),
            Value::Str(s) => format!("'{s}'"),
        }
    }

    /// The value stored as type `e` (an integer stored into a real becomes a
    /// real, 0/1 into BOOL a boolean). The caller checked that it fits.
    pub fn coerce(self, e: Elem) -> Value {
        match (self, e) {
            (Value::Int(v), e) if e.is_real() => Value::Real(v as f64),
            (Value::Int(v), Elem::Bool) => Value::Bool(v != 0),
            (Value::Real(r), Elem::Real) => Value::Real(r as f32 as f64),
            (v, _) => v,
        }
    }
}

/// An initial value: a scalar, or the shape of an array or structure initialiser.
#[derive(Clone, Debug, PartialEq)]
pub enum Init {
    Value(Value),
    /// Elements in order; each may repeat. `value: None` is `n()`: the default.
    Array(Vec<ArrayInit>),
    Struct(Vec<FieldInit>),
    /// A `REF_TO` variable's initial value: `NULL` (`None`) or `REF(x)` of
    /// the variable `x`, a variable of the same PROGRAM or FUNCTION_BLOCK
    /// instance or else a global, resolved to its address in the image.
    Ref(Option<automat_base::Symbol>),
}

#[derive(Clone, Debug, PartialEq)]
pub struct ArrayInit {
    pub repeat: u64,
    pub value: Option<Init>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct FieldInit {
    pub name: Symbol,
    pub value: Init,
}

impl Init {
    pub fn as_value(&self) -> Option<&Value> {
        match self {
            Init::Value(v) => Some(v),
            _ => None,
        }
    }
}

/// The value a variable of a scalar type starts with when nothing else is
/// said: zero, FALSE, the empty string, the first enumeration value, the
/// lower limit of a subrange. `None` for arrays, structures and instances.
pub fn default_value(types: &TypeTable, ty: TypeId) -> Option<Value> {
    Some(match types.get(ty) {
        TypeKind::Elem(e) => match e {
            Elem::Bool => Value::Bool(false),
            e if e.is_real() => Value::Real(0.0),
            Elem::Time | Elem::Ltime => Value::Duration(0),
            Elem::Date | Elem::Ldate => Value::Date(0),
            Elem::Tod | Elem::Ltod => Value::Tod(0),
            Elem::Dt | Elem::Ldt => Value::DateTime(0),
            Elem::Char | Elem::Wchar => Value::Str(String::new()),
            _ => Value::Int(0),
        },
        TypeKind::String { .. } => Value::Str(String::new()),
        TypeKind::Enum { values, .. } => Value::Enum(values.first().map_or(0, |v| v.value)),
        TypeKind::Subrange { lo, .. } => Value::Int(*lo),
        _ => return None,
    })
}

/// Why folding failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FoldError {
    DivByZero,
    Overflow,
}

/// Folds a binary operator over two known operand values. `None` when the
/// combination has no compile-time meaning here (the checker still types it).
pub fn binary(op: BinaryOp, l: &Value, r: &Value) -> Result<Option<Value>, FoldError> {
    use BinaryOp::*;
    use Value::*;
    Ok(Some(match (op, l, r) {
        (Add | Sub | Mul | Div | Mod, Int(a), Int(b)) => Int(int_arith(op, *a, *b)?),
        (Add | Sub | Mul | Div, Int(_) | Real(_), Int(_) | Real(_)) => {
            let (a, b) = (to_f64(l), to_f64(r));
            if op == Div && b == 0.0 {
                return Err(FoldError::DivByZero);
            }
            Real(match op {
                Add => a + b,
                Sub => a - b,
                Mul => a * b,
                _ => a / b,
            })
        }
        (Pow, Int(_) | Real(_), Int(_) | Real(_)) => Real(to_f64(l).powf(to_f64(r))),
        (Add | Sub, Duration(a), Duration(b)) => Duration(int_arith(op, *a, *b)?),
        (Mul | Div, Duration(a), Int(b)) => Duration(int_arith(op, *a, *b)?),
        (Mul, Int(a), Duration(b)) => Duration(int_arith(op, *a, *b)?),
        (Mul | Div, Duration(a), Real(b)) => {
            if op == Div && *b == 0.0 {
                return Err(FoldError::DivByZero);
            }
            let x = if op == Mul {
                *a as f64 * b
            } else {
                *a as f64 / b
            };
            Duration(x as i128)
        }
        (And, Bool(a), Bool(b)) => Bool(*a && *b),
        (Or, Bool(a), Bool(b)) => Bool(*a || *b),
        (Xor, Bool(a), Bool(b)) => Bool(*a != *b),
        (And, Int(a), Int(b)) => Int(a & b),
        (Or, Int(a), Int(b)) => Int(a | b),
        (Xor, Int(a), Int(b)) => Int(a ^ b),
        (Lt | Gt | Le | Ge | Eq | Ne, _, _) => match compare(l, r) {
            Some(ord) => Bool(match op {
                Lt => ord.is_lt(),
                Gt => ord.is_gt(),
                Le => ord.is_le(),
                Ge => ord.is_ge(),
                Eq => ord.is_eq(),
                _ => ord.is_ne(),
            }),
            None => return Ok(None),
        },
        _ => return Ok(None),
    }))
}

fn int_arith(op: BinaryOp, a: i128, b: i128) -> Result<i128, FoldError> {
    use BinaryOp::*;
    let r = match op {
        Add => a.checked_add(b),
        Sub => a.checked_sub(b),
        Mul => a.checked_mul(b),
        Div | Mod if b == 0 => return Err(FoldError::DivByZero),
        Div => a.checked_div(b),
        Mod => a.checked_rem(b),
        _ => None,
    };
    r.ok_or(FoldError::Overflow)
}

fn to_f64(v: &Value) -> f64 {
    match v {
        Value::Int(i) => *i as f64,
        Value::Real(r) => *r,
        _ => 0.0,
    }
}

fn compare(l: &Value, r: &Value) -> Option<std::cmp::Ordering> {
    use Value::*;
    match (l, r) {
        (Int(a), Int(b)) | (Enum(a), Enum(b)) | (Duration(a), Duration(b)) => Some(a.cmp(b)),
        (DateTime(a), DateTime(b)) => Some(a.cmp(b)),
        (Date(a), Date(b)) | (Tod(a), Tod(b)) => Some(a.cmp(b)),
        (Bool(a), Bool(b)) => Some(a.cmp(b)),
        (Str(a), Str(b)) => Some(a.cmp(b)),
        (Int(_) | Real(_), Int(_) | Real(_)) => to_f64(l).partial_cmp(&to_f64(r)),
        _ => None,
    }
}

/// Folds a unary operator. `ty` is the operand's elementary type when typed,
/// or the expected type of an untyped operand (NOT of an unsigned or
/// bit-string value keeps to its width: `NOT 16#0F` for a BYTE is 16#F0).
pub fn unary(op: UnaryOp, v: &Value, ty: Option<Elem>) -> Result<Option<Value>, FoldError> {
    Ok(Some(match (op, v) {
        (UnaryOp::Plus, v) => v.clone(),
        (UnaryOp::Neg, Value::Int(i)) => Value::Int(i.checked_neg().ok_or(FoldError::Overflow)?),
        (UnaryOp::Neg, Value::Real(r)) => Value::Real(-r),
        (UnaryOp::Neg, Value::Duration(d)) => {
            Value::Duration(d.checked_neg().ok_or(FoldError::Overflow)?)
        }
        (UnaryOp::Not, Value::Bool(b)) => Value::Bool(!b),
        (UnaryOp::Not, Value::Int(i)) => match ty {
            Some(e) if !e.is_signed() && e.bits() < 128 => {
                let mask = if e.bits() >= 64 {
                    u64::MAX as i128
                } else {
                    (1i128 << e.bits()) - 1
                };
                Value::Int(!i & mask)
            }
            _ => Value::Int(!i),
        },
        _ => return Ok(None),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folds_integer_arithmetic_exactly() {
        let b = |op, l, r| binary(op, &Value::Int(l), &Value::Int(r));
        assert_eq!(b(BinaryOp::Add, 300, 100), Ok(Some(Value::Int(400))));
        assert_eq!(b(BinaryOp::Sub, 10, 1), Ok(Some(Value::Int(9))));
        assert_eq!(b(BinaryOp::Mul, 2, 100), Ok(Some(Value::Int(200))));
        assert_eq!(b(BinaryOp::Div, 7, 2), Ok(Some(Value::Int(3))));
        assert_eq!(b(BinaryOp::Div, -7, 2), Ok(Some(Value::Int(-3))));
        assert_eq!(b(BinaryOp::Mod, -7, 3), Ok(Some(Value::Int(-1))));
        assert_eq!(b(BinaryOp::Div, 1, 0), Err(FoldError::DivByZero));
        assert_eq!(b(BinaryOp::Mod, 1, 0), Err(FoldError::DivByZero));
        assert_eq!(b(BinaryOp::Mul, i128::MAX, 2), Err(FoldError::Overflow));
        assert_eq!(b(BinaryOp::Lt, 1, 2), Ok(Some(Value::Bool(true))));
        assert_eq!(b(BinaryOp::And, 12, 10), Ok(Some(Value::Int(8))));
        assert_eq!(b(BinaryOp::Pow, 2, 10), Ok(Some(Value::Real(1024.0))));
    }

    #[test]
    fn folds_reals_times_and_booleans() {
        assert_eq!(
            binary(BinaryOp::Mul, &Value::Real(1.5), &Value::Int(2)),
            Ok(Some(Value::Real(3.0)))
        );
        assert_eq!(
            binary(BinaryOp::Div, &Value::Real(1.0), &Value::Real(0.0)),
            Err(FoldError::DivByZero)
        );
        assert_eq!(
            binary(BinaryOp::Add, &Value::Duration(5), &Value::Duration(7)),
            Ok(Some(Value::Duration(12)))
        );
        assert_eq!(
            binary(BinaryOp::Mul, &Value::Duration(5), &Value::Int(3)),
            Ok(Some(Value::Duration(15)))
        );
        assert_eq!(
            binary(BinaryOp::Xor, &Value::Bool(true), &Value::Bool(true)),
            Ok(Some(Value::Bool(false)))
        );
        assert_eq!(
            binary(
                BinaryOp::Eq,
                &Value::Str("a".into()),
                &Value::Str("a".into())
            ),
            Ok(Some(Value::Bool(true)))
        );
        assert_eq!(
            binary(BinaryOp::Add, &Value::Bool(true), &Value::Int(1)),
            Ok(None)
        );
    }

    #[test]
    fn folds_unary_operators_by_width() {
        assert_eq!(
            unary(UnaryOp::Not, &Value::Int(0), Some(Elem::Byte)),
            Ok(Some(Value::Int(255)))
        );
        assert_eq!(
            unary(UnaryOp::Not, &Value::Int(0), Some(Elem::Lword)),
            Ok(Some(Value::Int(u64::MAX as i128)))
        );
        assert_eq!(
            unary(UnaryOp::Not, &Value::Int(0), Some(Elem::Int)),
            Ok(Some(Value::Int(-1)))
        );
        assert_eq!(
            unary(UnaryOp::Neg, &Value::Int(5), None),
            Ok(Some(Value::Int(-5)))
        );
        assert_eq!(
            unary(UnaryOp::Not, &Value::Bool(true), None),
            Ok(Some(Value::Bool(false)))
        );
    }

    #[test]
    fn coerces_to_the_stored_type() {
        assert_eq!(Value::Int(2).coerce(Elem::Lreal), Value::Real(2.0));
        assert_eq!(Value::Int(1).coerce(Elem::Bool), Value::Bool(true));
        assert_eq!(Value::Int(7).coerce(Elem::Word), Value::Int(7));
    }
}
