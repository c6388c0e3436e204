//! Scan statistics: scan times, overruns, runs per task.

use std::fmt;

/// Statistics of one run. Scan times are measured on the monotonic clock
/// from reading the inputs to writing the outputs of scans in which at
/// least one task ran.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    pub scans: u64,
    pub min_ns: Option<i64>,
    pub max_ns: Option<i64>,
    pub total_ns: i128,
    /// Scans that ended after the next deadline (real time only).
    pub overruns: u64,
    /// Task names with how many times each ran, in declaration order.
    pub task_runs: Vec<(String, u64)>,
    /// Real time only: how late each scan started after its deadline.
    pub start_late: Histogram,
    /// Scan times, for percentiles and the decade histogram.
    pub scan_times: Histogram,
}

/// A distribution of durations in ns: counts by decade (exact), and
/// log-linear buckets (16 per power of two, so a percentile is within
/// 1/16 of the true value) for percentiles; the maximum is exact.
/// Fixed size once the first value is recorded: recording never allocates
/// again, so it costs the scan nothing measurable.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Histogram {
    pub count: u64,
    pub max_ns: i64,
    /// `< 1us, < 10us, < 100us, < 1ms, < 10ms, < 100ms, < 1s, >= 1s`.
    pub decades: [u64; 8],
    buckets: Vec<u64>,
}

/// Sub-buckets per power of two (a power of two itself).
const SUB: u32 = 16;
const SUB_BITS: u32 = SUB.trailing_zeros();
const BUCKETS: usize = ((64 - SUB_BITS + 1) * SUB) as usize;

fn bucket_of(v: u64) -> usize {
    if v < u64::from(SUB) {
        return v as usize;
    }
    let k = 63 - v.leading_zeros(); // 2^k <= v < 2^(k+1), k >= SUB_BITS
    let sub = (v >> (k - SUB_BITS)) & u64::from(SUB - 1);
    ((k - SUB_BITS + 1) * SUB) as usize + sub as usize
}

/// The smallest value of a bucket.
fn bucket_floor(i: usize) -> u64 {
    let i = i as u64;
    let sub = u64::from(SUB);
    if i < sub {
        return i;
    }
    let k = i / sub - 1 + u64::from(SUB_BITS);
    let within = i % sub;
    (1u64 << k) + (within << (k - u64::from(SUB_BITS)))
}

impl Histogram {
    pub fn record(&mut self, ns: i64) {
        let v = u64::try_from(ns).unwrap_or(0);
        if self.buckets.is_empty() {
            self.buckets = vec![0; BUCKETS];
        }
        if let Some(b) = self.buckets.get_mut(bucket_of(v)) {
            *b += 1;
        }
        let mut d = 0;
        let mut limit = 1_000u64;
        while d < 7 && v >= limit {
            d += 1;
            limit = limit.saturating_mul(10);
        }
        self.decades[d] += 1;
        self.count += 1;
        self.max_ns = self.max_ns.max(ns.max(0));
    }

    /// The value below which a fraction `q` (0..=1) of the recorded values
    /// lie, to within 1/16 (the floor of its bucket, never above the
    /// maximum); `None` when empty.
    pub fn percentile(&self, q: f64) -> Option<i64> {
        if self.count == 0 {
            return None;
        }
        let rank = ((q.clamp(0.0, 1.0) * self.count as f64).ceil() as u64).max(1);
        let mut seen = 0u64;
        for (i, n) in self.buckets.iter().enumerate() {
            seen += n;
            if seen >= rank {
                let floor = i64::try_from(bucket_floor(i)).unwrap_or(i64::MAX);
                return Some(floor.min(self.max_ns));
            }
        }
        Some(self.max_ns)
    }

    /// Adds the values of `other`.
    pub fn merge(&mut self, other: &Histogram) {
        if other.count == 0 {
            return;
        }
        if self.buckets.is_empty() {
            self.buckets = vec![0; BUCKETS];
        }
        for (a, b) in self.buckets.iter_mut().zip(&other.buckets) {
            *a += b;
        }
        for (a, b) in self.decades.iter_mut().zip(&other.decades) {
            *a += b;
        }
        self.count += other.count;
        self.max_ns = self.max_ns.max(other.max_ns);
    }

    /// `p50 12.000us, p99 40.000us, max 180.000us`.
    pub fn summary(&self) -> String {
        match (self.percentile(0.5), self.percentile(0.99)) {
            (Some(p50), Some(p99)) => format!(
                "p50 {}, p99 {}, max {}",
                human(p50),
                human(p99),
                human(self.max_ns)
            ),
            _ => "none".to_string(),
        }
    }

    /// `<1us: 0, 1-10us: 12, 10-100us: 988, ...`: the decades with a count,
    /// and those between them.
    pub fn decades_text(&self) -> String {
        const NAMES: [&str; 8] = [
            "<1us",
            "1-10us",
            "10-100us",
            "100us-1ms",
            "1-10ms",
            "10-100ms",
            "100ms-1s",
            ">=1s",
        ];
        let first = self.decades.iter().position(|&n| n > 0);
        let last = self.decades.iter().rposition(|&n| n > 0);
        match (first, last) {
            (Some(a), Some(b)) => (a..=b)
                .map(|i| format!("{}: {}", NAMES[i], self.decades[i]))
                .collect::<Vec<_>>()
                .join(", "),
            _ => "none".to_string(),
        }
    }
}

impl Stats {
    pub fn record(&mut self, scan_ns: i64) {
        self.scans += 1;
        self.min_ns = Some(self.min_ns.map_or(scan_ns, |m| m.min(scan_ns)));
        self.max_ns = Some(self.max_ns.map_or(scan_ns, |m| m.max(scan_ns)));
        self.total_ns += i128::from(scan_ns);
        self.scan_times.record(scan_ns);
    }

    /// Adds the scans of a later run of the same program (a session that
    /// was stopped and started again); task runs are the later run's.
    pub fn merge(&mut self, later: &Stats) {
        self.scans += later.scans;
        self.min_ns = match (self.min_ns, later.min_ns) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
        self.max_ns = match (self.max_ns, later.max_ns) {
            (Some(a), Some(b)) => Some(a.max(b)),
            (a, b) => a.or(b),
        };
        self.total_ns += later.total_ns;
        self.overruns += later.overruns;
        for (name, runs) in &later.task_runs {
            match self.task_runs.iter_mut().find(|(n, _)| n == name) {
                Some((_, r)) => *r += runs,
                None => self.task_runs.push((name.clone(), *runs)),
            }
        }
        self.start_late.merge(&later.start_late);
        self.scan_times.merge(&later.scan_times);
    }

    /// The mean scan time in ns (rounded down); `None` before any scan.
    pub fn avg_ns(&self) -> Option<i64> {
        if self.scans == 0 {
            return None;
        }
        i64::try_from(self.total_ns / i128::from(self.scans)).ok()
    }
}

/// `12.5us` style: the largest unit that keeps the number ≥ 1.
fn human(ns: i64) -> String {
    let f = ns as f64;
    if ns.abs() >= 1_000_000_000 {
        format!("{:.3}s", f / 1e9)
    } else if ns.abs() >= 1_000_000 {
        format!("{:.3}ms", f / 1e6)
    } else if ns.abs() >= 1_000 {
        format!("{:.3}us", f / 1e3)
    } else {
        format!("{ns}ns")
    }
}

impl fmt::Display for Stats {
    /// `scans: 10, scan time min/avg/max: 1.000us/1.500us/2.000us, overruns: 0, task runs: MAIN=10`
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "scans: {}", self.scans)?;
        if let (Some(min), Some(avg), Some(max)) = (self.min_ns, self.avg_ns(), self.max_ns) {
            write!(
                f,
                ", scan time min/avg/max: {}/{}/{}",
                human(min),
                human(avg),
                human(max)
            )?;
        }
        write!(f, ", overruns: {}", self.overruns)?;
        if !self.task_runs.is_empty() {
            let runs: Vec<String> = self
                .task_runs
                .iter()
                .map(|(n, r)| format!("{n}={r}"))
                .collect();
            write!(f, ", task runs: {}", runs.join(" "))?;
        }
        // Real time: when the scans started, and how their times spread.
        if self.start_late.count > 0 {
            write!(
                f,
                "\nscan start jitter: {}\nscan time: {}; histogram: {}",
                self.start_late.summary(),
                self.scan_times.summary(),
                self.scan_times.decades_text()
            )?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn min_avg_max_and_display() {
        let mut s = Stats::default();
        assert_eq!(s.avg_ns(), None);
        assert_eq!(s.to_string(), "scans: 0, overruns: 0");
        s.record(1_000);
        s.record(3_000);
        s.record(2_500);
        s.overruns = 1;
        s.task_runs = vec![("FAST".into(), 3), ("SLOW".into(), 1)];
        assert_eq!(
            (s.min_ns, s.avg_ns(), s.max_ns),
            (Some(1_000), Some(2_166), Some(3_000))
        );
        assert_eq!(
            s.to_string(),
            "scans: 3, scan time min/avg/max: 1.000us/2.166us/3.000us, overruns: 1, task runs: FAST=3 SLOW=1"
        );
        assert_eq!(human(999), "999ns");
        assert_eq!(human(1_500_000), "1.500ms");
        assert_eq!(human(2_000_000_000), "2.000s");
    }

    #[test]
    fn buckets_cover_every_value_in_order() {
        let mut last = 0;
        for v in (0..5000u64).chain([u64::MAX / 2, u64::MAX]) {
            let b = bucket_of(v);
            assert!(b < BUCKETS, "{v}");
            assert!(b >= last, "{v}");
            last = b;
            let floor = bucket_floor(b);
            assert!(floor <= v, "{v}: {floor}");
            // Within 1/16 of the value.
            assert!(v - floor <= v / 16, "{v}: {floor}");
        }
    }

    #[test]
    fn percentiles_decades_and_merge() {
        let mut h = Histogram::default();
        assert_eq!(h.percentile(0.5), None);
        assert_eq!(h.summary(), "none");
        // 98 values of 10us, one of 50us, one of 2ms.
        for _ in 0..98 {
            h.record(10_000);
        }
        h.record(50_000);
        h.record(2_000_000);
        let p50 = h.percentile(0.5).unwrap();
        assert!((9_375..=10_000).contains(&p50), "{p50}");
        let p99 = h.percentile(0.99).unwrap();
        assert!((46_875..=50_000).contains(&p99), "{p99}");
        assert_eq!(h.percentile(1.0), Some(1_966_080));
        assert_eq!(h.max_ns, 2_000_000);
        assert_eq!(h.decades, [0, 0, 99, 0, 1, 0, 0, 0]);
        assert_eq!(h.decades_text(), "10-100us: 99, 100us-1ms: 0, 1-10ms: 1");
        let mut s = Stats::default();
        s.record(1_000);
        s.start_late.record(5_000);
        let mut t = Stats::default();
        t.record(3_000);
        t.overruns = 2;
        t.task_runs = vec![("MAIN".into(), 1)];
        t.start_late.record(7_000);
        s.merge(&t);
        assert_eq!(
            (s.scans, s.min_ns, s.max_ns, s.overruns),
            (2, Some(1_000), Some(3_000), 2)
        );
        assert_eq!(s.start_late.count, 2);
        assert_eq!(s.start_late.max_ns, 7_000);
        assert_eq!(
            s.to_string(),
            "scans: 2, scan time min/avg/max: 1.000us/2.000us/3.000us, overruns: 2, task runs: MAIN=1\n\
             scan start jitter: p50 4.864us, p99 6.912us, max 7.000us\n\
             scan time: p50 992ns, p99 2.944us, max 3.000us; histogram: 1-10us: 2"
        );
    }
}
