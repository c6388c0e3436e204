//! Time for the scan loop.
//!
//! PLC time (what programs and timers see) always comes from the schedule:
//! the instant a scan was due, so it is exact in both modes. The
//! [`Monotonic`] clock is only used to measure scan times and, in real time,
//! to sleep until absolute deadlines (start + due instant), so sleeping
//! never accumulates drift.

use std::time::Duration;

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

/// The operating system's monotonic clock (CLOCK_MONOTONIC on Linux, what
/// `Instant` reads), counting from its creation.
pub struct SystemClock {
    origin_ns: i64,
}

impl SystemClock {
    pub fn new() -> SystemClock {
        SystemClock {
            origin_ns: monotonic_ns(),
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
        monotonic_ns().saturating_sub(self.origin_ns)
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

/// The monotonic clock in ns from its own origin. Read a few times per
/// scan (scan time, watchdog), so it is one `clock_gettime` with integer
/// arithmetic rather than `Instant` and `Duration` (u128 nanoseconds).
#[cfg(unix)]
// `time_t` and `c_long` are i64 here but i32 on 32-bit targets.
#[allow(clippy::useless_conversion)]
pub fn monotonic_ns() -> i64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid, writable timespec; CLOCK_MONOTONIC exists
    // on every unix this builds for, so the call cannot fail.
    unsafe { libc::clock_gettime(libc::CLOCK_MONOTONIC, &mut ts) };
    i64::from(ts.tv_sec)
        .saturating_mul(1_000_000_000)
        .saturating_add(i64::from(ts.tv_nsec))
}

/// The monotonic clock in ns from the first call.
#[cfg(not(unix))]
pub fn monotonic_ns() -> i64 {
    use std::sync::OnceLock;
    use std::time::Instant;
    static ORIGIN: OnceLock<Instant> = OnceLock::new();
    let origin = *ORIGIN.get_or_init(Instant::now);
    i64::try_from(origin.elapsed().as_nanos()).unwrap_or(i64::MAX)
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
