use super::*;

const S: i64 = NS_PER_SEC;
const MS: i64 = NS_PER_MS;
const H: i64 = NS_PER_HOUR;
const DAY: i64 = NS_PER_DAY;

#[test]
fn leap_years() {
    assert!(is_leap_year(2000));
    assert!(!is_leap_year(1900));
    assert!(is_leap_year(2024));
    assert!(!is_leap_year(2023));
    assert!(!is_leap_year(2100));
    assert!(is_leap_year(1600));
    assert!(is_leap_year(0));
    assert!(is_leap_year(-4));
    assert!(!is_leap_year(-100));
    assert_eq!(days_in_month(2000, 2), Some(29));
    assert_eq!(days_in_month(1900, 2), Some(28));
    assert_eq!(days_in_month(2023, 4), Some(30));
    assert_eq!(days_in_month(2023, 12), Some(31));
    assert_eq!(days_in_month(2023, 13), None);
    assert_eq!(days_in_month(2023, 0), None);
}

#[test]
fn civil_dates() {
    let cases: [(i64, (i64, u32, u32)); 10] = [
        (0, (1970, 1, 1)),
        (-1, (1969, 12, 31)),
        (19_753, (2024, 1, 31)),
        (19_782, (2024, 2, 29)),
        (11_016, (2000, 2, 29)),
        (-25_509, (1900, 2, 28)),
        (-25_508, (1900, 3, 1)),
        (-719_528, (0, 1, 1)),
        (2_932_896, (9999, 12, 31)),
        (-141_427, (1582, 10, 15)),
    ];
    for (days, (y, m, d)) in cases {
        assert_eq!(civil_from_days(days), (y, m, d), "{days}");
        assert_eq!(days_from_civil(y, m, d), Ok(days), "{y}-{m}-{d}");
    }
    // Every day of 1896..2104 (a non-leap century year inside) round-trips
    // and follows the previous one.
    let mut prev = civil_from_days(days_from_civil(1895, 12, 31).unwrap_or(0));
    for days in days_from_civil(1896, 1, 1).unwrap_or(0)..days_from_civil(2104, 1, 1).unwrap_or(0) {
        let (y, m, d) = civil_from_days(days);
        assert_eq!(days_from_civil(y, m, d), Ok(days));
        let next_ok = (y, m, d) == (prev.0, prev.1, prev.2 + 1)
            || (d == 1
                && ((y, m) == (prev.0, prev.1 + 1) || (y, m, prev.1) == (prev.0 + 1, 1, 12)));
        assert!(next_ok, "{prev:?} -> {:?}", (y, m, d));
        prev = (y, m, d);
    }
    for extreme in [i64::MAX, i64::MIN] {
        let (y, m, d) = civil_from_days(extreme);
        assert_eq!(days_from_civil(y, m, d), Ok(extreme));
    }
}

#[test]
fn invalid_dates() {
    let e = |y, m, d| days_from_civil(y, m, d).map_err(|e| e.message);
    assert_eq!(
        e(2023, 2, 29),
        Err("day 29 is not in 1..=28 for 2023-02".to_string())
    );
    assert_eq!(
        e(1900, 2, 29),
        Err("day 29 is not in 1..=28 for 1900-02".to_string())
    );
    assert_eq!(e(2023, 13, 1), Err("month 13 is not in 1..=12".to_string()));
    assert_eq!(
        e(2023, 4, 31),
        Err("day 31 is not in 1..=30 for 2023-04".to_string())
    );
    assert_eq!(
        e(2023, 1, 0),
        Err("day 0 is not in 1..=31 for 2023-01".to_string())
    );
    assert!(days_from_civil(i64::MAX, 1, 1).is_err());
}

#[test]
fn day_of_week_starts_on_sunday() {
    assert_eq!(day_of_week(0), 4); // 1970-01-01, Thursday
    assert_eq!(day_of_week(3), 0); // 1970-01-04, Sunday
    assert_eq!(day_of_week(19_753), 3); // 2024-01-31, Wednesday
    assert_eq!(day_of_week(-1), 3); // 1969-12-31, Wednesday
    assert_eq!(day_of_week(11_016), 2); // 2000-02-29, Tuesday
    assert_eq!(day_of_week(i64::MIN), 3);
    assert_eq!(day_of_week(i64::MAX), 4);
    assert_eq!(dt_day_of_week(19_753 * DAY + 23 * H), 3);
}

#[test]
fn additions_and_subtractions() {
    assert_eq!(add_time(S, 500 * MS), Ok(1_500 * MS));
    assert_eq!(sub_time(S, 2 * S), Ok(-S));
    assert_eq!(
        add_time(i64::MAX, 1).map_err(|e| e.message),
        Err("ADD_TIME: the result does not fit in 64-bit nanoseconds".to_string())
    );
    assert!(sub_time(i64::MIN, 1).is_err());
    assert_eq!(add_tod_time(23 * H, 2 * H), H);
    assert_eq!(add_tod_time(H, -2 * H), 23 * H);
    assert_eq!(add_tod_time(0, i64::MAX), i64::MAX % DAY);
    assert_eq!(sub_tod_time(H, 2 * H), 23 * H);
    assert_eq!(
        sub_tod_time(H, i64::MIN),
        (i128::from(H) - i128::from(i64::MIN)).rem_euclid(DAY.into()) as i64
    );
    assert_eq!(sub_tod_tod(H, 2 * H), Ok(-H));
    assert_eq!(add_dt_time(DAY, H), Ok(DAY + H));
    assert!(add_dt_time(i64::MAX, 1).is_err());
    assert_eq!(sub_dt_time(DAY, H), Ok(23 * H));
    assert!(sub_dt_time(i64::MIN, 1).is_err());
    assert_eq!(sub_dt_dt(DAY, DAY + S), Ok(-S));
    assert!(sub_dt_dt(i64::MAX, -1).is_err());
    assert_eq!(sub_date_date(19_782, 19_753), Ok(29 * DAY));
    assert_eq!(sub_date_date(0, 1), Ok(-DAY));
    assert!(sub_date_date(200_000, 0).is_err());
}

#[test]
fn multiplication_and_division() {
    assert_eq!(mul_time(1_500 * MS, 3), Ok(4_500 * MS));
    assert_eq!(mul_time(S, -2), Ok(-2 * S));
    assert!(mul_time(i64::MAX, 2).is_err());
    assert_eq!(mul_time_real(S, 1.5), Ok(1_500 * MS));
    assert_eq!(mul_time_real(3, 0.5), Ok(2));
    assert_eq!(mul_time_real(5, 0.5), Ok(2));
    assert!(mul_time_real(S, f64::NAN).is_err());
    assert!(mul_time_real(S, 1e30).is_err());
    assert_eq!(div_time(7 * S, 2), Ok(3_500 * MS));
    assert_eq!(div_time(-7, 2), Ok(-3));
    assert_eq!(
        div_time(S, 0).map_err(|e| (e.kind, e.message)),
        Err((
            crate::ErrorKind::DivisionByZero,
            "DIV_TIME: division by zero".to_string()
        ))
    );
    assert!(div_time(i64::MIN, -1).is_err());
    assert_eq!(div_time_real(S, 4.0), Ok(250 * MS));
    assert!(div_time_real(S, 0.0).is_err());
    assert!(div_time_real(S, -0.0).is_err());
    assert!(div_time_real(S, 1e-300).is_err());
}

#[test]
fn concatenation_and_splitting() {
    assert_eq!(concat_date(2024, 1, 31), Ok(19_753));
    assert_eq!(concat_date(2000, 2, 29), Ok(11_016));
    assert_eq!(
        concat_date(1900, 2, 29).map_err(|e| (e.kind, e.message)),
        Err((
            crate::ErrorKind::InvalidDate,
            "CONCAT_DATE: day 29 is not in 1..=28 for 1900-02".to_string()
        ))
    );
    assert_eq!(
        concat_date(2024, 0, 1).map_err(|e| e.message),
        Err("CONCAT_DATE: MONTH = 0 is not in 1..=12".to_string())
    );
    assert_eq!(
        concat_date(2024, 1, -3).map_err(|e| e.message),
        Err("CONCAT_DATE: DAY = -3 is not in 1..=31".to_string())
    );
    assert_eq!(
        concat_tod(12, 30, 15, 250),
        Ok(12 * H + 30 * 60 * S + 15 * S + 250 * MS)
    );
    assert_eq!(
        concat_tod(24, 0, 0, 0).map_err(|e| e.message),
        Err("CONCAT_TOD: HOUR = 24 is not in 0..=23".to_string())
    );
    assert_eq!(
        concat_tod(1, 1, 1, 1000).map_err(|e| e.message),
        Err("CONCAT_TOD: MILLISECOND = 1000 is not in 0..=999".to_string())
    );
    assert_eq!(concat_date_tod(1, H), Ok(DAY + H));
    assert!(concat_date_tod(200_000, 0).is_err());
    assert_eq!(
        concat_dt(2024, 1, 31, 12, 30, 0, 5),
        Ok(19_753 * DAY + 12 * H + 30 * 60 * S + 5 * MS)
    );
    assert_eq!(
        concat_dt(3000, 1, 1, 0, 0, 0, 0).map_err(|e| (e.kind, e.message)),
        Err((
            crate::ErrorKind::Overflow,
            "CONCAT_DT: the date 3000-01-01 is outside the DT range (1677 to 2262)".to_string()
        ))
    );
    assert_eq!(
        concat_dt(2024, 1, 31, 12, 60, 0, 0).map_err(|e| e.message),
        Err("CONCAT_DT: MINUTE = 60 is not in 0..=59".to_string())
    );
    assert_eq!(split_date(19_782), (2024, 2, 29));
    assert_eq!(
        split_tod(12 * H + 30 * 60 * S + 15 * S + 250 * MS + 999),
        (12, 30, 15, 250)
    );
    assert_eq!(split_tod(-1), (23, 59, 59, 999));
    assert_eq!(split_ltod(S + 7), (0, 0, 1, 7));
    assert_eq!(
        split_dt(19_753 * DAY + 12 * H + 5 * MS),
        DateTimeParts {
            year: 2024,
            month: 1,
            day: 31,
            hour: 12,
            minute: 0,
            second: 0,
            millisecond: 5
        }
    );
    assert_eq!(
        split_dt(-1),
        DateTimeParts {
            year: 1969,
            month: 12,
            day: 31,
            hour: 23,
            minute: 59,
            second: 59,
            millisecond: 999
        }
    );
    assert_eq!(dt_to_date(-1), -1);
    assert_eq!(dt_to_tod(-1), DAY - 1);
    assert_eq!(date_to_dt(2), Ok(2 * DAY));
    assert!(date_to_dt(-200_000).is_err());
}

#[test]
fn leap_days_in_date_and_time_arithmetic() {
    let feb28_2024 = concat_dt(2024, 2, 28, 12, 0, 0, 0).unwrap_or(0);
    let next = add_dt_time(feb28_2024, DAY).unwrap_or(0);
    assert_eq!(split_dt(next).month, 2);
    assert_eq!(split_dt(next).day, 29);
    let feb28_1900 = concat_date(1900, 2, 28).unwrap_or(0);
    assert_eq!(split_date(feb28_1900 + 1), (1900, 3, 1));
    let feb28_2000 = concat_date(2000, 2, 28).unwrap_or(0);
    assert_eq!(split_date(feb28_2000 + 1), (2000, 2, 29));
    assert_eq!(
        sub_date_date(
            concat_date(2001, 1, 1).unwrap_or(0),
            concat_date(2000, 1, 1).unwrap_or(0)
        ),
        Ok(366 * DAY)
    );
    assert_eq!(
        sub_date_date(
            concat_date(1901, 1, 1).unwrap_or(0),
            concat_date(1900, 1, 1).unwrap_or(0)
        ),
        Ok(365 * DAY)
    );
}

#[test]
fn known_weekdays() {
    let dow = |y, m, d| day_of_week(concat_date(y, m, d).unwrap_or(0));
    assert_eq!(dow(2000, 1, 1), 6); // Saturday
    assert_eq!(dow(1900, 1, 1), 1); // Monday
    assert_eq!(dow(2024, 2, 29), 4); // Thursday
    assert_eq!(dow(1969, 7, 20), 0); // Sunday
    assert_eq!(dow(2262, 4, 11), 5); // Friday
}

#[test]
fn dt_range_edges() {
    assert_eq!(
        concat_dt(1677, 9, 21, 0, 12, 43, 146),
        Ok(-9_223_372_036_854_000_000)
    );
    assert!(concat_dt(1677, 9, 21, 0, 12, 43, 145).is_err());
    assert!(concat_dt(2262, 4, 11, 23, 47, 16, 854).is_ok());
    assert!(concat_dt(2262, 4, 11, 23, 47, 16, 855).is_err());
    // The first day of the DT range starts before i64::MIN: computed wide.
    assert_eq!(
        concat_date_tod(-106_752, 44_000_000_000_000),
        Ok(-9_223_328_800_000_000_000)
    );
    assert!(concat_date_tod(-106_752, 0).is_err());
}

#[test]
fn differences_across_midnight() {
    assert_eq!(sub_tod_tod(H, 23 * H), Ok(-22 * H));
    assert_eq!(sub_tod_tod(23 * H, H), Ok(22 * H));
    assert_eq!(add_tod_time(23 * H + 59 * 60 * S, 60 * S), 0);
    assert_eq!(add_tod_time(0, -1), DAY - 1);
    assert_eq!(sub_tod_time(0, DAY), 0);
    let midnight = concat_dt(2024, 12, 31, 23, 59, 59, 999).unwrap_or(0);
    let next = add_dt_time(midnight, MS).unwrap_or(0);
    assert_eq!(split_dt(next).year, 2025);
    assert_eq!(split_dt(next).month, 1);
    assert_eq!(split_dt(next).day, 1);
    assert_eq!(split_dt(next).hour, 0);
}
