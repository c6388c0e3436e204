//! Time and date arithmetic (IEC 61131-3 3rd edition, tables 30 to 35).
//!
//! Representation (see [`crate::value`]): TIME and LTIME are signed `i64`
//! nanoseconds; DATE is `i64` days since 1970-01-01; TOD is nanoseconds since
//! midnight (0 ≤ tod < 24 h); DT is `i64` nanoseconds since
//! 1970-01-01-00:00:00, which covers 1677-09-21 to 2262-04-11. The
//! calendar is the proleptic Gregorian one (1900 is not a leap year, 2000
//! is), in UTC: no time zones, no leap seconds.
//!
//! Rules:
//! - `ADD_TIME`, `SUB_TIME`, `ADD_DT_TIME`, `SUB_DT_TIME`, `SUB_DT_DT`,
//!   `SUB_DATE_DATE`, `MUL_TIME`, `DIV_TIME`, `CONCAT_DATE_TOD`: a result
//!   outside 64-bit nanoseconds is an [`ErrorKind::Overflow`] error, never a
//!   wrap or a panic.
//! - `ADD_TOD_TIME` and `SUB_TOD_TIME` wrap at 24 h, as a clock does:
//!   TOD#23:00:00 + T#2h = TOD#01:00:00, TOD#01:00:00 − T#2h = TOD#23:00:00.
//! - `SUB_TOD_TOD` and `SUB_DT_DT` may be negative (T#-1h).
//! - `MUL_TIME` and `DIV_TIME` by an integer are exact and truncate toward
//!   zero; by a real, the result is rounded to the nearest nanosecond,
//!   halves to even. Division by zero (integer or real) is an
//!   [`ErrorKind::DivisionByZero`] error; a NaN or infinite factor is an
//!   overflow error.
//! - `DAY_OF_WEEK` is 0 for Sunday to 6 for Saturday.
//! - `CONCAT_DATE`, `CONCAT_TOD` and `CONCAT_DT` check their parts (month
//!   1..=12, day within the month, hour 0..=23, minute and second 0..=59,
//!   millisecond 0..=999) and report the first bad one as an
//!   [`ErrorKind::InvalidDate`] error naming it. `SPLIT_*` are their
//!   inverses; `SPLIT_TOD` truncates to the millisecond.

mod civil;
mod split;
#[cfg(test)]
mod tests;

pub use civil::{civil_from_days, day_of_week, days_from_civil, days_in_month, is_leap_year};
pub use split::{
    concat_date, concat_dt, concat_tod, split_date, split_dt, split_ltod, split_tod, DateTimeParts,
};

use crate::error::{ErrorKind, IecError};

pub const NS_PER_US: i64 = 1_000;
pub const NS_PER_MS: i64 = 1_000_000;
pub const NS_PER_SEC: i64 = 1_000_000_000;
pub const NS_PER_MIN: i64 = 60 * NS_PER_SEC;
pub const NS_PER_HOUR: i64 = 60 * NS_PER_MIN;
pub const NS_PER_DAY: i64 = 24 * NS_PER_HOUR;

fn checked(v: Option<i64>, function: &str) -> Result<i64, IecError> {
    v.ok_or_else(|| IecError::overflow(function))
}

/// ADD_TIME (also `+` on TIME/LTIME).
pub fn add_time(a: i64, b: i64) -> Result<i64, IecError> {
    checked(a.checked_add(b), "ADD_TIME")
}

/// SUB_TIME (also `-` on TIME/LTIME).
pub fn sub_time(a: i64, b: i64) -> Result<i64, IecError> {
    checked(a.checked_sub(b), "SUB_TIME")
}

/// ADD_TOD_TIME: wraps at 24 h.
pub fn add_tod_time(tod: i64, t: i64) -> i64 {
    (i128::from(tod) + i128::from(t)).rem_euclid(i128::from(NS_PER_DAY)) as i64
}

/// SUB_TOD_TIME: wraps at 24 h.
pub fn sub_tod_time(tod: i64, t: i64) -> i64 {
    (i128::from(tod) - i128::from(t)).rem_euclid(i128::from(NS_PER_DAY)) as i64
}

/// SUB_TOD_TOD: the signed difference as a TIME.
pub fn sub_tod_tod(a: i64, b: i64) -> Result<i64, IecError> {
    checked(a.checked_sub(b), "SUB_TOD_TOD")
}

/// ADD_DT_TIME.
pub fn add_dt_time(dt: i64, t: i64) -> Result<i64, IecError> {
    checked(dt.checked_add(t), "ADD_DT_TIME")
}

/// SUB_DT_TIME.
pub fn sub_dt_time(dt: i64, t: i64) -> Result<i64, IecError> {
    checked(dt.checked_sub(t), "SUB_DT_TIME")
}

/// SUB_DT_DT: the signed difference as a TIME.
pub fn sub_dt_dt(a: i64, b: i64) -> Result<i64, IecError> {
    checked(a.checked_sub(b), "SUB_DT_DT")
}

/// SUB_DATE_DATE: the difference of two dates (in days) as a TIME.
pub fn sub_date_date(a: i64, b: i64) -> Result<i64, IecError> {
    checked(
        a.checked_sub(b).and_then(|d| d.checked_mul(NS_PER_DAY)),
        "SUB_DATE_DATE",
    )
}

/// MUL_TIME by an integer.
pub fn mul_time(t: i64, k: i64) -> Result<i64, IecError> {
    checked(t.checked_mul(k), "MUL_TIME")
}

/// MUL_TIME by a real: rounded to the nearest nanosecond, halves to even.
pub fn mul_time_real(t: i64, k: f64) -> Result<i64, IecError> {
    real_result(t as f64 * k, "MUL_TIME")
}

/// DIV_TIME by an integer: truncates toward zero.
pub fn div_time(t: i64, k: i64) -> Result<i64, IecError> {
    if k == 0 {
        return Err(IecError::div_zero("DIV_TIME"));
    }
    // Only i64::MIN / -1 overflows here.
    checked(t.checked_div(k), "DIV_TIME")
}

/// DIV_TIME by a real: rounded to the nearest nanosecond, halves to even.
pub fn div_time_real(t: i64, k: f64) -> Result<i64, IecError> {
    if k == 0.0 {
        return Err(IecError::div_zero("DIV_TIME"));
    }
    real_result(t as f64 / k, "DIV_TIME")
}

fn real_result(x: f64, function: &str) -> Result<i64, IecError> {
    let r = x.round_ties_even();
    // 2^63 is exactly representable; i64::MAX is not, hence `<`.
    if (-9_223_372_036_854_775_808.0..9_223_372_036_854_775_808.0).contains(&r) {
        Ok(r as i64)
    } else {
        Err(IecError::overflow(function))
    }
}

/// CONCAT_DATE_TOD: the DT at time of day `tod` on date `days`.
pub fn concat_date_tod(days: i64, tod: i64) -> Result<i64, IecError> {
    checked(date_tod_ns(days, tod), "CONCAT_DATE_TOD")
}

/// `days` × 24 h + `tod` when it fits in 64 bits. Computed wide: the first
/// day of the DT range starts before i64::MIN.
pub(crate) fn date_tod_ns(days: i64, tod: i64) -> Option<i64> {
    i64::try_from(i128::from(days) * i128::from(NS_PER_DAY) + i128::from(tod)).ok()
}

/// DATE_TO_DT: midnight of the date.
pub fn date_to_dt(days: i64) -> Result<i64, IecError> {
    checked(days.checked_mul(NS_PER_DAY), "DATE_TO_DT")
}

/// DT_TO_DATE: the day the instant falls in.
pub fn dt_to_date(dt: i64) -> i64 {
    dt.div_euclid(NS_PER_DAY)
}

/// DT_TO_TOD: the time of day of the instant.
pub fn dt_to_tod(dt: i64) -> i64 {
    dt.rem_euclid(NS_PER_DAY)
}

/// DAY_OF_WEEK of a DT (0 = Sunday).
pub fn dt_day_of_week(dt: i64) -> u8 {
    day_of_week(dt_to_date(dt))
}

pub(crate) fn invalid(function: &str, why: &str) -> IecError {
    IecError::new(ErrorKind::InvalidDate, format!("{function}: {why}"))
}
