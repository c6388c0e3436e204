//! Durations (`T#1h2m3s`), dates (`D#2024-01-31`), times of day
//! (`TOD#12:30:00.5`) and date-and-times (`DT#2024-01-31-12:30:00`).

use super::LitError;
use crate::ast::LitKind;

const NS_PER_SEC: i128 = 1_000_000_000;
const NS_PER_DAY: i128 = 86_400 * NS_PER_SEC;

/// Units of a duration, largest first; the order they must appear in.
const UNITS: [(&str, i128); 7] = [
    ("D", NS_PER_DAY),
    ("H", 3_600 * NS_PER_SEC),
    ("M", 60 * NS_PER_SEC),
    ("S", NS_PER_SEC),
    ("MS", 1_000_000),
    ("US", 1_000),
    ("NS", 1),
];

fn malformed(what: &str, body: &str, why: &str) -> LitError {
    LitError::Malformed(format!("malformed {what} literal `{body}`: {why}"))
}

/// `1h2m3s4ms`, `-5s`, `1.5s`, `1d_2h` → nanoseconds.
pub fn duration(body: &str, long: bool) -> Result<LitKind, LitError> {
    let what = "duration";
    let (neg, rest) = match body.as_bytes().first() {
        Some(b'-') => (true, &body[1..]),
        Some(b'+') => (false, &body[1..]),
        _ => (false, body),
    };
    let b = rest.as_bytes();
    let mut i = 0;
    let mut total: i128 = 0;
    // Index into UNITS of the last unit seen: the next must be smaller.
    let mut last_unit: Option<usize> = None;
    let mut saw_fraction = false;
    while i < b.len() {
        if b[i] == b'_' {
            i += 1;
            continue;
        }
        let num_start = i;
        while i < b.len() && (b[i].is_ascii_digit() || b[i] == b'_') {
            i += 1;
        }
        let int_text = &rest[num_start..i];
        if int_text.is_empty() {
            return Err(malformed(what, body, "expected a number"));
        }
        let mut frac_text = "";
        if i < b.len() && b[i] == b'.' {
            i += 1;
            let f = i;
            while i < b.len() && b[i].is_ascii_digit() {
                i += 1;
            }
            frac_text = &rest[f..i];
            if frac_text.is_empty() {
                return Err(malformed(what, body, "expected digits after `.`"));
            }
        }
        let unit_start = i;
        while i < b.len() && b[i].is_ascii_alphabetic() {
            i += 1;
        }
        let unit = rest[unit_start..i].to_ascii_uppercase();
        let Some(u) = UNITS.iter().position(|(name, _)| *name == unit) else {
            let why = if unit.is_empty() {
                "expected a unit (d, h, m, s, ms, us or ns) after the number".to_string()
            } else {
                format!(
                    "`{}` is not a unit (d, h, m, s, ms, us or ns)",
                    &rest[unit_start..i]
                )
            };
            return Err(malformed(what, body, &why));
        };
        if last_unit.is_some_and(|l| u <= l) {
            return Err(malformed(
                what,
                body,
                "units must go from days down to nanoseconds, each at most once",
            ));
        }
        if saw_fraction {
            return Err(malformed(
                what,
                body,
                "only the last unit may have a fraction",
            ));
        }
        saw_fraction = !frac_text.is_empty();
        last_unit = Some(u);
        let scale = UNITS[u].1;
        let whole = parse_digits(int_text).ok_or_else(|| too_long(body))?;
        let part = whole
            .checked_mul(scale)
            .and_then(|v| v.checked_add(fraction(frac_text, scale)))
            .ok_or_else(|| too_long(body))?;
        total = total.checked_add(part).ok_or_else(|| too_long(body))?;
    }
    if last_unit.is_none() {
        return Err(malformed(
            what,
            body,
            "expected a number and a unit, as in `T#5s`",
        ));
    }
    let nanos = if neg { -total } else { total };
    // TIME and LTIME are both 64-bit nanoseconds: a longer literal would
    // wrap to a wrong (often negative) duration in the image.
    if i64::try_from(nanos).is_err() {
        return Err(too_long(body));
    }
    Ok(LitKind::Duration { nanos, long })
}

fn too_long(body: &str) -> LitError {
    LitError::OutOfRange(format!(
        "duration literal `{body}` is too long: TIME and LTIME hold \
         -106751d23h47m16s854ms775us808ns to 106751d23h47m16s854ms775us807ns"
    ))
}

/// Digits (underscores ignored) as an integer, `None` on overflow.
fn parse_digits(text: &str) -> Option<i128> {
    let mut v: i128 = 0;
    for b in text.bytes().filter(|&b| b != b'_') {
        v = v.checked_mul(10)?.checked_add(i128::from(b - b'0'))?;
    }
    Some(v)
}

/// `0.fff × scale`, truncated to whole nanoseconds. Digits past the 18th
/// cannot change the result for any unit (a day is < 10^14 ns).
fn fraction(digits: &str, scale: i128) -> i128 {
    let digits = &digits[..digits.len().min(18)];
    let mut num: i128 = 0;
    let mut den: i128 = 1;
    for b in digits.bytes() {
        num = num * 10 + i128::from(b - b'0');
        den *= 10;
    }
    num * scale / den
}

/// `2024-01-31` → days since 1970-01-01.
pub fn date(body: &str, long: bool) -> Result<LitKind, LitError> {
    let days = parse_date(body, body, "date")?;
    Ok(LitKind::Date { days, long })
}

/// `12:30:00.5` → nanoseconds since midnight.
pub fn time_of_day(body: &str, long: bool) -> Result<LitKind, LitError> {
    let nanos = parse_tod(body, body, "time-of-day")?;
    Ok(LitKind::TimeOfDay {
        nanos: nanos as i64,
        long,
    })
}

/// `2024-01-31-12:30:00` → nanoseconds since 1970-01-01T00:00:00.
pub fn date_time(body: &str, long: bool) -> Result<LitKind, LitError> {
    let what = "date-and-time";
    // The date has exactly two dashes; the third separates the time.
    let split = body
        .match_indices('-')
        .nth(2)
        .map(|(i, _)| i)
        .ok_or_else(|| malformed(what, body, "expected `YYYY-MM-DD-hh:mm:ss`"))?;
    let days = parse_date(&body[..split], body, what)?;
    let nanos = parse_tod(&body[split + 1..], body, what)?;
    Ok(LitKind::DateTime {
        nanos: i128::from(days) * NS_PER_DAY + nanos,
        long,
    })
}

fn all_digits(s: &str) -> bool {
    !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit())
}

fn parse_date(text: &str, body: &str, what: &str) -> Result<i64, LitError> {
    let mut parts = text.split('-');
    let (Some(y), Some(m), Some(d), None) =
        (parts.next(), parts.next(), parts.next(), parts.next())
    else {
        return Err(malformed(what, body, "expected a date as `YYYY-MM-DD`"));
    };
    if !all_digits(y)
        || !all_digits(m)
        || !all_digits(d)
        || y.len() > 4
        || m.len() > 2
        || d.len() > 2
    {
        return Err(malformed(what, body, "expected a date as `YYYY-MM-DD`"));
    }
    let (year, month, day) = (
        y.parse::<i64>().unwrap_or(0),
        m.parse::<u32>().unwrap_or(0),
        d.parse::<u32>().unwrap_or(0),
    );
    if !(1..=12).contains(&month) {
        return Err(malformed(
            what,
            body,
            &format!("month {month} is not 1..12"),
        ));
    }
    let max_day = days_in_month(year, month);
    if day < 1 || day > max_day {
        return Err(malformed(
            what,
            body,
            &format!("day {day} is not 1..{max_day} for month {month} of {year}"),
        ));
    }
    Ok(days_from_civil(year, month, day))
}

fn parse_tod(text: &str, body: &str, what: &str) -> Result<i128, LitError> {
    let shape = "expected a time of day as `hh:mm:ss` or `hh:mm:ss.fff`";
    let mut parts = text.split(':');
    let (Some(h), Some(m), s, None) = (parts.next(), parts.next(), parts.next(), parts.next())
    else {
        return Err(malformed(what, body, shape));
    };
    let (sec, frac) = match s {
        Some(s) => match s.split_once('.') {
            // A dot needs digits after it: `12:00:00.` is malformed.
            Some((_, "")) => return Err(malformed(what, body, shape)),
            Some((sec, frac)) => (sec, frac),
            None => (s, ""),
        },
        None => ("0", ""),
    };
    let fraction_ok = frac.is_empty() || all_digits(frac);
    if !all_digits(h) || !all_digits(m) || !all_digits(sec) || !fraction_ok {
        return Err(malformed(what, body, shape));
    }
    if h.len() > 2 || m.len() > 2 || sec.len() > 2 {
        return Err(malformed(what, body, shape));
    }
    let (hh, mm, ss) = (
        h.parse::<i128>().unwrap_or(0),
        m.parse::<i128>().unwrap_or(0),
        sec.parse::<i128>().unwrap_or(0),
    );
    if hh >= 24 {
        return Err(malformed(what, body, &format!("hour {hh} is not 0..23")));
    }
    if mm >= 60 {
        return Err(malformed(what, body, &format!("minute {mm} is not 0..59")));
    }
    if ss >= 60 {
        return Err(malformed(what, body, &format!("second {ss} is not 0..59")));
    }
    Ok(((hh * 60 + mm) * 60 + ss) * NS_PER_SEC + fraction(frac, NS_PER_SEC))
}

fn is_leap(y: i64) -> bool {
    (y % 4 == 0 && y % 100 != 0) || y % 400 == 0
}

fn days_in_month(y: i64, m: u32) -> u32 {
    match m {
        2 if is_leap(y) => 29,
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    }
}

/// Days since 1970-01-01 of a proleptic Gregorian date (Howard Hinnant's
/// well-known civil-from-days inverse).
fn days_from_civil(y: i64, m: u32, d: u32) -> i64 {
    let y = if m <= 2 { y - 1 } else { y };
    let era = if y >= 0 { y } else { y - 399 } / 400;
    let yoe = y - era * 400;
    let mp = i64::from((m + 9) % 12);
    let doy = (153 * mp + 2) / 5 + i64::from(d) - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    era * 146_097 + doe - 719_468
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dur(s: &str) -> i128 {
        match duration(s, false) {
            Ok(LitKind::Duration { nanos, .. }) => nanos,
            other => panic!("{s}: {other:?}"),
        }
    }

    #[test]
    fn durations() {
        assert_eq!(dur("1h2m3s4ms"), ((3600 + 120 + 3) * 1000 + 4) * 1_000_000);
        assert_eq!(dur("-5s"), -5_000_000_000);
        assert_eq!(dur("1.5s"), 1_500_000_000);
        assert_eq!(dur("1d_2h"), 26 * 3600 * NS_PER_SEC);
        assert_eq!(dur("100ms"), 100_000_000);
        assert_eq!(dur("5us"), 5_000);
        assert_eq!(dur("3ns"), 3);
        assert_eq!(dur("25h"), 25 * 3600 * NS_PER_SEC);
        assert_eq!(dur("1M30S"), 90 * NS_PER_SEC);
        assert_eq!(dur("1_000ms"), NS_PER_SEC);
    }

    #[test]
    fn bad_durations() {
        for s in ["5x", "5", "", "s", "1s2h", "1s1s", "1.5s2ms", "1.s", "-"] {
            assert!(
                matches!(duration(s, false), Err(LitError::Malformed(_))),
                "{s}"
            );
        }
        assert!(matches!(
            duration(&"9".repeat(60), false),
            Err(LitError::Malformed(_))
        ));
        assert!(matches!(
            duration(&format!("{}d", "9".repeat(60)), false),
            Err(LitError::OutOfRange(_))
        ));
    }

    #[test]
    fn durations_fit_in_64_bit_nanoseconds() {
        let max = "106751d23h47m16s854ms775us807ns";
        assert_eq!(dur(max), i128::from(i64::MAX));
        assert_eq!(
            dur("-106751d23h47m16s854ms775us808ns"),
            i128::from(i64::MIN)
        );
        for s in [
            "106751d23h47m16s854ms775us808ns",
            "-106751d23h47m16s854ms775us809ns",
            "106752d",
            "9223372036854775808ns",
            "2562048h",
        ] {
            for long in [false, true] {
                match duration(s, long) {
                    Err(LitError::OutOfRange(m)) => assert_eq!(
                        m,
                        format!(
                            "duration literal `{s}` is too long: TIME and LTIME hold \
                             -106751d23h47m16s854ms775us808ns to {max}"
                        )
                    ),
                    other => panic!("{s}: {other:?}"),
                }
            }
        }
    }

    #[test]
    fn dates() {
        assert_eq!(
            date("1970-01-01", false),
            Ok(LitKind::Date {
                days: 0,
                long: false
            })
        );
        assert_eq!(
            date("2024-01-31", true),
            Ok(LitKind::Date {
                days: 19753,
                long: true
            })
        );
        assert_eq!(
            date("2024-02-29", false),
            Ok(LitKind::Date {
                days: 19782,
                long: false
            })
        );
        assert_eq!(
            date("1969-12-31", false),
            Ok(LitKind::Date {
                days: -1,
                long: false
            })
        );
        for s in [
            "2023-02-29",
            "2024-13-01",
            "2024-00-10",
            "2024-04-31",
            "2024-1",
            "x",
            "1900-02-29",
        ] {
            assert!(matches!(date(s, false), Err(LitError::Malformed(_))), "{s}");
        }
        assert!(date("2000-02-29", false).is_ok());
    }

    #[test]
    fn times_of_day() {
        let ns = |h: i64, m: i64, s: i64| ((h * 60 + m) * 60 + s) * 1_000_000_000;
        assert_eq!(
            time_of_day("12:30:00.5", false),
            Ok(LitKind::TimeOfDay {
                nanos: ns(12, 30, 0) + 500_000_000,
                long: false
            })
        );
        assert_eq!(
            time_of_day("23:59:59", true),
            Ok(LitKind::TimeOfDay {
                nanos: ns(23, 59, 59),
                long: true
            })
        );
        assert_eq!(
            time_of_day("08:15", false),
            Ok(LitKind::TimeOfDay {
                nanos: ns(8, 15, 0),
                long: false
            })
        );
        for s in [
            "24:00:00",
            "12:60:00",
            "12:00:60",
            "12",
            "1:2:3:4",
            "12:00:00.",
            "a:b:c",
        ] {
            assert!(
                matches!(time_of_day(s, false), Err(LitError::Malformed(_))),
                "{s}"
            );
        }
    }

    #[test]
    fn date_and_time() {
        assert_eq!(
            date_time("2024-01-31-12:30:00", false),
            Ok(LitKind::DateTime {
                nanos: 19753 * NS_PER_DAY + (12 * 3600 + 30 * 60) * NS_PER_SEC,
                long: false
            })
        );
        assert!(matches!(
            date_time("2024-01-31", false),
            Err(LitError::Malformed(_))
        ));
        assert!(matches!(
            date_time("2024-02-30-00:00:00", false),
            Err(LitError::Malformed(_))
        ));
    }
}
