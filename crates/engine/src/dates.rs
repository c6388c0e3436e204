//! CONCAT_DATE / CONCAT_TOD / CONCAT_DT, DAY_OF_WEEK and the parts that
//! SPLIT_DATE / SPLIT_TOD / SPLIT_DT give, over register values (DATE in
//! days, TOD and DT in nanoseconds).

use automat_iec::time as tm;
use automat_iec::IecError;
use automat_ir::code::{DateFn, DatePart, DateSrc};

/// Runs one date function on its (up to seven) integer arguments.
pub fn call(f: DateFn, x: &[i64; 7]) -> Result<i64, IecError> {
    let [a, b, c, d, e, g, h] = *x;
    match f {
        DateFn::ConcatDate => tm::concat_date(a, b, c),
        DateFn::ConcatTod => tm::concat_tod(a, b, c, d),
        DateFn::ConcatDt => tm::concat_dt(a, b, c, d, e, g, h),
        DateFn::DayOfWeek => Ok(i64::from(tm::day_of_week(a))),
        DateFn::Part(p, src) => Ok(part(p, src, a)),
    }
}

fn part(p: DatePart, src: DateSrc, v: i64) -> i64 {
    let (year, month, day, hour, minute, second, ms) = match src {
        DateSrc::Date => {
            let (y, m, d) = tm::split_date(v);
            (y, m, d, 0, 0, 0, 0)
        }
        DateSrc::Tod => {
            let (h, mi, s, ms) = tm::split_tod(v);
            (0, 0, 0, h, mi, s, ms)
        }
        DateSrc::Dt => {
            let t = tm::split_dt(v);
            (
                t.year,
                t.month,
                t.day,
                t.hour,
                t.minute,
                t.second,
                t.millisecond,
            )
        }
    };
    match p {
        DatePart::Year => year,
        DatePart::Month => i64::from(month),
        DatePart::Day => i64::from(day),
        DatePart::Hour => i64::from(hour),
        DatePart::Minute => i64::from(minute),
        DatePart::Second => i64::from(second),
        DatePart::Millisecond => i64::from(ms),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_and_concat() {
        let z = [0i64; 7];
        let date = call(DateFn::ConcatDate, &[2024, 2, 29, 0, 0, 0, 0]).unwrap_or(-1);
        assert_eq!(date, 19_782);
        assert_eq!(call(DateFn::DayOfWeek, &[date, 0, 0, 0, 0, 0, 0]), Ok(4));
        let dt = call(DateFn::ConcatDt, &[2024, 2, 29, 13, 14, 15, 16]).unwrap_or(-1);
        let p = |q| call(DateFn::Part(q, DateSrc::Dt), &[dt, 0, 0, 0, 0, 0, 0]);
        assert_eq!(p(DatePart::Year), Ok(2024));
        assert_eq!(p(DatePart::Month), Ok(2));
        assert_eq!(p(DatePart::Day), Ok(29));
        assert_eq!(p(DatePart::Hour), Ok(13));
        assert_eq!(p(DatePart::Minute), Ok(14));
        assert_eq!(p(DatePart::Second), Ok(15));
        assert_eq!(p(DatePart::Millisecond), Ok(16));
        assert!(call(DateFn::ConcatTod, &[24, 0, 0, 0, 0, 0, 0]).is_err());
        assert_eq!(call(DateFn::ConcatTod, &z), Ok(0));
    }
}
