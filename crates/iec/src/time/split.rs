//! CONCAT_DATE / CONCAT_TOD / CONCAT_DT and SPLIT_DATE / SPLIT_TOD / SPLIT_DT.

use super::{civil_from_days, days_from_civil, invalid, NS_PER_DAY, NS_PER_HOUR, NS_PER_MIN};
use super::{NS_PER_MS, NS_PER_SEC};
use crate::error::{ErrorKind, IecError};

/// The parts of a DT, as SPLIT_DT gives them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DateTimeParts {
    pub year: i64,
    pub month: u32,
    pub day: u32,
    pub hour: u32,
    pub minute: u32,
    pub second: u32,
    pub millisecond: u32,
}

/// Checks `value` is in `lo..=hi` and names the argument otherwise.
fn part(function: &str, name: &str, value: i64, lo: i64, hi: i64) -> Result<i64, IecError> {
    if (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(invalid(
            function,
            &format!("{name} = {value} is not in {lo}..={hi}"),
        ))
    }
}

fn date_days(function: &str, year: i64, month: i64, day: i64) -> Result<i64, IecError> {
    let month = part(function, "MONTH", month, 1, 12)?;
    let day = part(function, "DAY", day, 1, 31)?;
    days_from_civil(year, month as u32, day as u32)
        .map_err(|e| IecError::new(e.kind, format!("{function}: {}", e.message)))
}

/// CONCAT_DATE(YEAR, MONTH, DAY): days since 1970-01-01.
///
/// ```
/// use automat_iec::time::{concat_date, day_of_week};
/// assert_eq!(concat_date(2000, 2, 29), Ok(11_016));
/// assert_eq!(concat_date(2000, 2, 29).map(day_of_week), Ok(2)); // Tuesday
/// assert!(concat_date(1900, 2, 29).is_err());
/// ```
pub fn concat_date(year: i64, month: i64, day: i64) -> Result<i64, IecError> {
    date_days("CONCAT_DATE", year, month, day)
}

fn tod_ns(function: &str, h: i64, m: i64, s: i64, ms: i64) -> Result<i64, IecError> {
    let h = part(function, "HOUR", h, 0, 23)?;
    let m = part(function, "MINUTE", m, 0, 59)?;
    let s = part(function, "SECOND", s, 0, 59)?;
    let ms = part(function, "MILLISECOND", ms, 0, 999)?;
    Ok(h * NS_PER_HOUR + m * NS_PER_MIN + s * NS_PER_SEC + ms * NS_PER_MS)
}

/// CONCAT_TOD(HOUR, MINUTE, SECOND, MILLISECOND): nanoseconds since midnight.
pub fn concat_tod(hour: i64, minute: i64, second: i64, millisecond: i64) -> Result<i64, IecError> {
    tod_ns("CONCAT_TOD", hour, minute, second, millisecond)
}

/// CONCAT_DT(YEAR, MONTH, DAY, HOUR, MINUTE, SECOND, MILLISECOND).
pub fn concat_dt(
    year: i64,
    month: i64,
    day: i64,
    hour: i64,
    minute: i64,
    second: i64,
    millisecond: i64,
) -> Result<i64, IecError> {
    let f = "CONCAT_DT";
    let days = date_days(f, year, month, day)?;
    let tod = tod_ns(f, hour, minute, second, millisecond)?;
    super::date_tod_ns(days, tod).ok_or_else(|| {
            IecError::new(
                ErrorKind::Overflow,
                format!("{f}: the date {year:04}-{month:02}-{day:02} is outside the DT range (1677 to 2262)"),
            )
        })
}

/// SPLIT_DATE: (year, month, day).
pub fn split_date(days: i64) -> (i64, u32, u32) {
    civil_from_days(days)
}

/// SPLIT_TOD: (hour, minute, second, millisecond); sub-millisecond parts
/// are dropped. A value outside one day is first taken modulo 24 h.
pub fn split_tod(tod: i64) -> (u32, u32, u32, u32) {
    let (h, m, s, ns) = split_ltod(tod);
    (h, m, s, ns / NS_PER_MS as u32)
}

/// SPLIT_LTOD: (hour, minute, second, nanosecond within the second).
pub fn split_ltod(tod: i64) -> (u32, u32, u32, u32) {
    let t = tod.rem_euclid(NS_PER_DAY);
    (
        (t / NS_PER_HOUR) as u32,
        (t % NS_PER_HOUR / NS_PER_MIN) as u32,
        (t % NS_PER_MIN / NS_PER_SEC) as u32,
        (t % NS_PER_SEC) as u32,
    )
}

/// SPLIT_DT.
pub fn split_dt(dt: i64) -> DateTimeParts {
    let (year, month, day) = civil_from_days(dt.div_euclid(NS_PER_DAY));
    let (hour, minute, second, millisecond) = split_tod(dt.rem_euclid(NS_PER_DAY));
    DateTimeParts {
        year,
        month,
        day,
        hour,
        minute,
        second,
        millisecond,
    }
}
