//! The proleptic Gregorian calendar: days since 1970-01-01 ↔ year, month, day.

use crate::error::{ErrorKind, IecError};

/// Gregorian leap year: divisible by 4, except centuries not divisible by
/// 400 (1900 is not a leap year, 2000 is).
pub fn is_leap_year(year: i64) -> bool {
    year.rem_euclid(4) == 0 && (year.rem_euclid(100) != 0 || year.rem_euclid(400) == 0)
}

/// Days in `month` (1..=12) of `year`; `None` for another month number.
pub fn days_in_month(year: i64, month: u32) -> Option<u32> {
    Some(match month {
        1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
        4 | 6 | 9 | 11 => 30,
        2 if is_leap_year(year) => 29,
        2 => 28,
        _ => return None,
    })
}

/// Days in a 400-year cycle of the Gregorian calendar.
const DAYS_PER_ERA: i128 = 146_097;
/// Days from 0000-03-01 to 1970-01-01. Years are counted from March so the
/// leap day is the last day of a year, which makes day-of-year arithmetic
/// independent of leap years.
const EPOCH_SHIFT: i128 = 719_468;

/// Days since 1970-01-01 of a calendar date; an error for a month outside
/// 1..=12, a day outside the month, or a date too far for 64 bits.
pub fn days_from_civil(year: i64, month: u32, day: u32) -> Result<i64, IecError> {
    let Some(last) = days_in_month(year, month) else {
        return Err(IecError::new(
            ErrorKind::InvalidDate,
            format!("month {month} is not in 1..=12"),
        ));
    };
    if day < 1 || day > last {
        return Err(IecError::new(
            ErrorKind::InvalidDate,
            format!("day {day} is not in 1..={last} for {year:04}-{month:02}"),
        ));
    }
    // Shift to a March-based year; i128 keeps every i64 year safe.
    let y = i128::from(year) - i128::from(month <= 2);
    let era = y.div_euclid(400);
    let year_of_era = y - era * 400;
    let month_from_march = (i128::from(month) + 9) % 12;
    let day_of_year = (153 * month_from_march + 2) / 5 + i128::from(day) - 1;
    let day_of_era = year_of_era * 365 + year_of_era / 4 - year_of_era / 100 + day_of_year;
    let days = era * DAYS_PER_ERA + day_of_era - EPOCH_SHIFT;
    i64::try_from(days).map_err(|_| {
        IecError::new(
            ErrorKind::Overflow,
            format!("the date {year}-{month:02}-{day:02} is out of range"),
        )
    })
}

/// The calendar date (year, month 1..=12, day 1..=31) `days` after
/// 1970-01-01. Defined for every `i64`.
pub fn civil_from_days(days: i64) -> (i64, u32, u32) {
    let z = i128::from(days) + EPOCH_SHIFT;
    let era = z.div_euclid(DAYS_PER_ERA);
    let day_of_era = z - era * DAYS_PER_ERA;
    let year_of_era =
        (day_of_era - day_of_era / 1460 + day_of_era / 36_524 - day_of_era / 146_096) / 365;
    let day_of_year = day_of_era - (365 * year_of_era + year_of_era / 4 - year_of_era / 100);
    let month_from_march = (5 * day_of_year + 2) / 153;
    let day = day_of_year - (153 * month_from_march + 2) / 5 + 1;
    let month = if month_from_march < 10 {
        month_from_march + 3
    } else {
        month_from_march - 9
    };
    let year = year_of_era + era * 400 + i128::from(month <= 2);
    // |days| < 2^63 gives |year| < 2^55: the casts are exact.
    (year as i64, month as u32, day as u32)
}

/// DAY_OF_WEEK: 0 = Sunday, 1 = Monday, ..., 6 = Saturday.
pub fn day_of_week(days: i64) -> u8 {
    // 1970-01-01 was a Thursday (4).
    ((i128::from(days) + 4).rem_euclid(7)) as u8
}
