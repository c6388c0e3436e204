//! Parsing the bodies of duration, date, time-of-day and date-and-time
//! literals (the text after `T#`, `D#`, `TOD#`, `DT#`).

use super::datetime::UNITS;
use super::parse::{bad, sign, too_big, Why};
use crate::time::{days_from_civil, NS_PER_HOUR, NS_PER_MIN, NS_PER_SEC};

/// `1d2h3m4s5ms`, `-5s`, `1.5s`, `1d_2h` → nanoseconds.
pub(crate) fn parse_duration(body: &str) -> Result<i64, Why> {
    let (neg, rest) = sign(body);
    let b = rest.as_bytes();
    let mut i = 0;
    let mut total: i128 = 0;
    // Index into UNITS of the last unit: the next one must be smaller.
    let mut last: Option<usize> = None;
    let mut had_fraction = false;
    while i < b.len() {
        if b[i] == b'_' && last.is_some() {
            i += 1;
            continue;
        }
        let start = i;
        while i < b.len() && (b[i].is_ascii_digit() || b[i] == b'_') {
            i += 1;
        }
        let whole = &rest[start..i];
        if !whole.starts_with(|c: char| c.is_ascii_digit()) {
            return Err(bad(
                "expected a number followed by a unit (d, h, m, s, ms, us, ns)",
            ));
        }
        let mut frac = "";
        if b.get(i) == Some(&b'.') {
            i += 1;
            let f = i;
            while i < b.len() && b[i].is_ascii_digit() {
                i += 1;
            }
            frac = &rest[f..i];
            if frac.is_empty() {
                return Err(bad("expected digits after `.`"));
            }
        }
        let u = i;
        while i < b.len() && b[i].is_ascii_alphabetic() {
            i += 1;
        }
        let unit = rest[u..i].to_ascii_lowercase();
        let Some(idx) = UNITS.iter().position(|(name, _)| *name == unit) else {
            return Err(bad(format!(
                "`{}` is not a unit (d, h, m, s, ms, us, ns)",
                &rest[u..i]
            )));
        };
        if last.is_some_and(|l| idx <= l) {
            return Err(bad("units must go from d down to ns, each at most once"));
        }
        if had_fraction {
            return Err(bad("only the last unit may have a fraction"));
        }
        had_fraction = !frac.is_empty();
        last = Some(idx);
        let size = i128::from(UNITS[idx].1);
        let part = whole_number(whole)
            .and_then(|n| n.checked_mul(size))
            .map(|n| n + fraction(frac, size))
            .ok_or_else(overflow)?;
        total = total.checked_add(part).ok_or_else(overflow)?;
        if total > i128::from(u64::MAX) {
            return Err(overflow());
        }
    }
    if last.is_none() {
        return Err(bad("expected a number followed by a unit, as in T#5s"));
    }
    i64::try_from(if neg { -total } else { total }).map_err(|_| overflow())
}

fn overflow() -> Why {
    too_big("the duration does not fit in 64-bit nanoseconds")
}

/// Decimal digits (underscores skipped); `None` on overflow.
fn whole_number(text: &str) -> Option<i128> {
    text.bytes().filter(|&b| b != b'_').try_fold(0i128, |v, b| {
        v.checked_mul(10)?.checked_add(i128::from(b - b'0'))
    })
}

/// `0.<frac>` × `size`, truncated to whole nanoseconds. Only the first 18
/// digits count: later ones are below a nanosecond for every unit.
fn fraction(frac: &str, size: i128) -> i128 {
    let digits = &frac[..frac.len().min(18)];
    let n = whole_number(digits).unwrap_or(0);
    let scale = 10i128.pow(digits.len() as u32);
    n * size / scale
}

/// An unsigned decimal field of at most `max_len` digits.
fn field(text: &str, what: &str, max_len: usize) -> Result<i64, Why> {
    if text.is_empty() || text.len() > max_len || !text.bytes().all(|b| b.is_ascii_digit()) {
        return Err(bad(format!("expected the {what} as 1 to {max_len} digits")));
    }
    text.parse::<i64>().map_err(|_| bad(format!("bad {what}")))
}

/// `2024-01-31` (a negative year as `-0044-03-15`) → days since 1970-01-01.
pub(crate) fn parse_date(body: &str) -> Result<i64, Why> {
    let (neg, rest) = match body.strip_prefix('-') {
        Some(r) => (true, r),
        None => (false, body),
    };
    let mut parts = rest.split('-');
    let (Some(y), Some(m), Some(d), None) =
        (parts.next(), parts.next(), parts.next(), parts.next())
    else {
        return Err(bad("expected a date as YYYY-MM-DD"));
    };
    let year = field(y, "year", 12)?;
    let month = field(m, "month", 2)?;
    let day = field(d, "day", 2)?;
    let year = if neg { -year } else { year };
    days_from_civil(year, month as u32, day as u32).map_err(|e| (e.kind, e.message))
}

/// `12:30:00`, `12:30:00.5` → nanoseconds since midnight.
pub(crate) fn parse_tod(body: &str) -> Result<i64, Why> {
    let mut parts = body.split(':');
    let (Some(h), Some(m), Some(s), None) =
        (parts.next(), parts.next(), parts.next(), parts.next())
    else {
        return Err(bad("expected a time of day as hh:mm:ss"));
    };
    let (s, frac) = match s.split_once('.') {
        Some((s, f)) => (s, Some(f)),
        None => (s, None),
    };
    let h = field(h, "hour", 2)?;
    let m = field(m, "minute", 2)?;
    let s = field(s, "second", 2)?;
    let invalid = |what: &str, v: i64, max: i64| {
        (
            crate::error::ErrorKind::InvalidDate,
            format!("{what} {v} is not in 0..={max}"),
        )
    };
    if h > 23 {
        return Err(invalid("hour", h, 23));
    }
    if m > 59 {
        return Err(invalid("minute", m, 59));
    }
    if s > 59 {
        return Err(invalid("second", s, 59));
    }
    let frac_ns = match frac {
        Some(f) if !f.is_empty() && f.bytes().all(|b| b.is_ascii_digit()) => {
            fraction(f, i128::from(NS_PER_SEC)) as i64
        }
        Some(_) => return Err(bad("expected digits after `.`")),
        None => 0,
    };
    Ok(h * NS_PER_HOUR + m * NS_PER_MIN + s * NS_PER_SEC + frac_ns)
}

/// `2024-01-31-12:30:00.5` → nanoseconds since 1970-01-01-00:00:00.
pub(crate) fn parse_dt(body: &str) -> Result<i64, Why> {
    let split = body
        .find(':')
        .and_then(|colon| body[..colon].rfind('-'))
        .ok_or_else(|| bad("expected a date and time as YYYY-MM-DD-hh:mm:ss"))?;
    let days = parse_date(&body[..split])?;
    let tod = parse_tod(&body[split + 1..])?;
    crate::time::date_tod_ns(days, tod)
        .ok_or_else(|| too_big("the date is outside the DT range (1677-09-21 to 2262-04-11)"))
}
