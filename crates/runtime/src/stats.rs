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
}

impl Stats {
    pub fn record(&mut self, scan_ns: i64) {
        self.scans += 1;
        self.min_ns = Some(self.min_ns.map_or(scan_ns, |m| m.min(scan_ns)));
        self.max_ns = Some(self.max_ns.map_or(scan_ns, |m| m.max(scan_ns)));
        self.total_ns += i128::from(scan_ns);
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
}
