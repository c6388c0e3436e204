//! Durations given on the command line: `10ms`, `T#10ms`, `TIME#1s500ms`,
//! `1.5s` — the IEC duration syntax with or without its prefix.

use automat_iec::{parse_literal, Elementary, Value};

/// Nanoseconds of a duration argument; negative durations are refused.
pub fn parse_duration(text: &str) -> Result<i64, String> {
    match parse_literal(text, Elementary::Time) {
        Ok(Value::Duration(ns, _)) if ns >= 0 => Ok(ns),
        Ok(_) => Err(format!(
            "`{text}` is negative; a duration must be 0 or more"
        )),
        Err(e) => Err(format!(
            "{} (write a duration like `10ms` or `T#1s500ms`)",
            e.message
        )),
    }
}

/// Greatest common divisor of two positive numbers.
pub fn gcd(mut a: i64, mut b: i64) -> i64 {
    while b != 0 {
        let r = a % b;
        a = b;
        b = r;
    }
    a.abs()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn accepted_forms() {
        assert_eq!(parse_duration("10ms"), Ok(10_000_000));
        assert_eq!(parse_duration("T#10ms"), Ok(10_000_000));
        assert_eq!(parse_duration("t#1s500ms"), Ok(1_500_000_000));
        assert_eq!(parse_duration("TIME#2s"), Ok(2_000_000_000));
        assert_eq!(parse_duration("1.5s"), Ok(1_500_000_000));
        assert_eq!(parse_duration("0s"), Ok(0));
    }

    #[test]
    fn refused_forms() {
        assert!(parse_duration("T#-5s").is_err_and(|e| e.contains("negative")));
        assert!(
            parse_duration("10").is_err_and(|e| e.starts_with("`10` is not a valid TIME literal"))
        );
        assert!(parse_duration("").is_err());
        assert!(parse_duration("ms").is_err());
    }

    #[test]
    fn gcd_values() {
        assert_eq!(gcd(10, 15), 5);
        assert_eq!(gcd(20, 10), 10);
        assert_eq!(gcd(7, 1), 1);
        assert_eq!(gcd(12, 0), 12);
    }
}
