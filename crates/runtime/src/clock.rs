//! Time for the scan loop.
//!
//! PLC time (what programs and timers see) always comes from the schedule:
//! the instant a scan was due, so it is exact in both modes. The
//! [`Monotonic`] clock is only used to measure scan times and, in real time,
//! to sleep until absolute deadlines (start + due instant), so sleeping
//! never accumulates drift.

use std::time::{Duration, Instant};

/// How the scan loop paces scans.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ClockMode {
    /// Scans run back to back; PLC time advances by the schedule only.
    Virtual,
    /// Each scan starts at its deadline on the monotonic clock.
    RealTime,
}

/// A monotonic clock counting ns from an arbitrary origin.
pub trait Monotonic {
    fn now_ns(&mut self) -> i64;
    /// Sleeps until `now_ns()` reaches `deadline_ns` (returns at once if it
    /// has). May return early; callers loop.
    fn sleep_until(&mut self, deadline_ns: i64);
}

/// The operating system's monotonic clock (`Instant`, CLOCK_MONOTONIC on
/// Linux), counting from its creation.
pub struct SystemClock {
    origin: Instant,
}

impl SystemClock {
    pub fn new() -> SystemClock {
        SystemClock {
            origin: Instant::now(),
        }
    }
}

impl Default for SystemClock {
    fn default() -> Self {
        SystemClock::new()
    }
}

impl Monotonic for SystemClock {
    fn now_ns(&mut self) -> i64 {
        i64::try_from(self.origin.elapsed().as_nanos()).unwrap_or(i64::MAX)
    }

    fn sleep_until(&mut self, deadline_ns: i64) {
        let now = self.now_ns();
        if let Ok(wait) = u64::try_from(deadline_ns.saturating_sub(now)) {
            if wait > 0 {
                std::thread::sleep(Duration::from_nanos(wait));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn system_clock_is_monotonic_and_sleeps_to_a_deadline() {
        let mut c = SystemClock::new();
        let a = c.now_ns();
        c.sleep_until(a + 2_000_000);
        let b = c.now_ns();
        assert!(b >= a + 2_000_000, "slept from {a} to {b}");
        // A deadline in the past returns at once.
        c.sleep_until(0);
        assert!(c.now_ns() >= b);
    }
}
