//! TIME, DATE, TOD and DT text.

use crate::time::{civil_from_days, NS_PER_DAY, NS_PER_HOUR, NS_PER_MIN, NS_PER_SEC};

/// Duration units, largest first, with their suffixes.
pub(crate) const UNITS: [(&str, u64); 7] = [
    ("d", 86_400_000_000_000),
    ("h", 3_600_000_000_000),
    ("m", 60_000_000_000),
    ("s", 1_000_000_000),
    ("ms", 1_000_000),
    ("us", 1_000),
    ("ns", 1),
];

/// `T#1d2h3m4s5ms`, `T#-5s`, `T#0s`, `T#1ms500us`; `LTIME#...` when `long`.
/// Zero units are left out; the sign comes first.
pub fn format_duration(ns: i64, long: bool) -> String {
    let mut out = String::from(if long { "LTIME#" } else { "T#" });
    if ns == 0 {
        out.push_str("0s");
        return out;
    }
    if ns < 0 {
        out.push('-');
    }
    // unsigned_abs handles i64::MIN.
    let mut rest = ns.unsigned_abs();
    for (name, size) in UNITS {
        let n = rest / size;
        rest %= size;
        if n > 0 {
            out.push_str(&n.to_string());
            out.push_str(name);
        }
    }
    out
}

/// `2024-01-31` (a negative year as `-0044-03-15`).
pub(crate) fn date_text(days: i64) -> String {
    let (y, m, d) = civil_from_days(days);
    let sign = if y < 0 { "-" } else { "" };
    format!("{sign}{:04}-{m:02}-{d:02}", y.unsigned_abs())
}

/// `12:30:00`, `12:30:00.5`, `00:00:00.000000001`: the fraction without
/// trailing zeros. Out-of-day values are taken modulo 24 h.
pub(crate) fn tod_text(ns: i64) -> String {
    let t = ns.rem_euclid(NS_PER_DAY);
    let h = t / NS_PER_HOUR;
    let m = t % NS_PER_HOUR / NS_PER_MIN;
    let s = t % NS_PER_MIN / NS_PER_SEC;
    let frac = t % NS_PER_SEC;
    let mut out = format!("{h:02}:{m:02}:{s:02}");
    if frac != 0 {
        let digits = format!("{frac:09}");
        out.push('.');
        out.push_str(digits.trim_end_matches('0'));
    }
    out
}

/// `D#2024-01-31`, or `LDATE#...`.
pub fn format_date(days: i64, long: bool) -> String {
    format!("{}#{}", if long { "LDATE" } else { "D" }, date_text(days))
}

/// `TOD#12:30:00.5`, or `LTOD#...`.
pub fn format_tod(ns: i64, long: bool) -> String {
    format!("{}#{}", if long { "LTOD" } else { "TOD" }, tod_text(ns))
}

/// `DT#2024-01-31-12:30:00`, or `LDT#...`.
pub fn format_dt(ns: i64, long: bool) -> String {
    format!(
        "{}#{}-{}",
        if long { "LDT" } else { "DT" },
        date_text(ns.div_euclid(NS_PER_DAY)),
        tod_text(ns.rem_euclid(NS_PER_DAY))
    )
}
