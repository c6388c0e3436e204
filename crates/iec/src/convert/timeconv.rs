//! Conversions between time/date values and numbers, and among time types.

use crate::elementary::Elementary as E;
use crate::error::IecError;
use crate::time::{NS_PER_DAY, NS_PER_MS, NS_PER_SEC};
use crate::value::Value;

/// Nanoseconds in one unit of a time type's number form: TIME and TOD
/// count milliseconds, DATE and DT seconds, the long types nanoseconds.
pub fn unit_ns(ty: E) -> Option<i64> {
    match ty {
        E::Time | E::Tod => Some(NS_PER_MS),
        E::Date | E::Dt => Some(NS_PER_SEC),
        E::Ltime | E::Ltod | E::Ldate | E::Ldt => Some(1),
        _ => None,
    }
}

/// A time or date value as an exact nanosecond count from its zero
/// (0 s, 1970-01-01, midnight). `None` for other values.
fn nanos(v: &Value) -> Option<i128> {
    match v {
        Value::Duration(ns, _) | Value::Tod(ns, _) | Value::Dt(ns, _) => Some(i128::from(*ns)),
        Value::Date(days, _) => Some(i128::from(*days) * i128::from(NS_PER_DAY)),
        _ => None,
    }
}

/// The number form of a time or date value, in its type's unit. Durations
/// truncate toward zero (T#1.9ms → 1, T#-1.9ms → −1); points in time
/// (DATE, TOD, DT) round down, so a DT before 1970 with a fraction of a
/// second gives the second it falls in.
pub fn count(v: &Value) -> Option<i128> {
    let ns = nanos(v)?;
    let unit = i128::from(unit_ns(v.ty())?);
    Some(if v.ty().is_duration() {
        ns / unit
    } else {
        ns.div_euclid(unit)
    })
}

/// The number form with its fraction, for conversions to REAL/LREAL.
pub fn count_real(v: &Value) -> Option<f64> {
    let ns = nanos(v)?;
    let unit = unit_ns(v.ty())?;
    Some(ns as f64 / unit as f64)
}

/// A time or date of type `to` from a number `count` in `to`'s unit: the
/// nanosecond total wraps into 64 bits like a LINT; a DATE keeps the day the
/// instant falls in; a TOD is taken modulo 24 h.
pub fn from_count(count: i128, to: E) -> Value {
    let unit = i128::from(unit_ns(to).unwrap_or(1));
    // |count| < 2^65 and unit ≤ 10^9 < 2^30: no i128 overflow.
    let ns = count.saturating_mul(unit);
    let day = i128::from(NS_PER_DAY);
    match to {
        E::Date | E::Ldate => Value::Date(ns.div_euclid(day) as i64, to),
        E::Tod | E::Ltod => Value::Tod(ns.rem_euclid(day) as i64, to),
        E::Dt | E::Ldt => Value::Dt(ns as i64, to),
        _ => Value::Duration(ns as i64, to),
    }
}

/// Time/date value → another time/date type (DT_TO_DATE, DATE_TO_DT,
/// TIME_TO_LTIME, ...). The caller checked the pair is convertible.
pub fn between(v: &Value, to: E, function: &str) -> Result<Value, IecError> {
    Ok(match (v, to) {
        (Value::Duration(ns, _), _) => Value::Duration(*ns, to),
        (Value::Tod(ns, _), _) => Value::Tod(*ns, to),
        (Value::Date(days, _), E::Date | E::Ldate) => Value::Date(*days, to),
        (Value::Date(days, _), _) => Value::Dt(
            days.checked_mul(NS_PER_DAY)
                .ok_or_else(|| IecError::overflow(function))?,
            to,
        ),
        (Value::Dt(ns, _), E::Date | E::Ldate) => Value::Date(ns.div_euclid(NS_PER_DAY), to),
        (Value::Dt(ns, _), E::Tod | E::Ltod) => Value::Tod(ns.rem_euclid(NS_PER_DAY), to),
        (Value::Dt(ns, _), _) => Value::Dt(*ns, to),
        _ => return Err(super::not_convertible(v.ty(), to)),
    })
}
