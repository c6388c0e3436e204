//! The watchdog in time: a timer thread that raises the backend's
//! [`Interrupt`] when a task run goes on too long, or when a stop was
//! requested and the scan in progress has not ended within
//! [`STOP_GRACE_NS`].
//!
//! The scan loop arms it before each task run ([`Watchdog::arm`]) and
//! disarms it after ([`Watchdog::disarm`], which returns the run's wall
//! time). Both are a mutex lock; the thread is woken only when it sleeps
//! past the new deadline (the first arm, or a shorter watchdog), so a
//! sequence of short runs costs no system call per run. While a run is
//! armed the thread also looks at the stop flag every
//! [`STOP_POLL_NS`]: a stop request during a long scan turns into an
//! interrupt [`STOP_GRACE_NS`] after the thread saw it, so the PLC stops
//! within a second of the signal.
//!
//! This is wall time whatever the run's clock: the watchdog guards the
//! machine running the PLC, not PLC time.

use crate::clock::monotonic_ns;
use automat_ir::{Interrupt, TaskWatchdog};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::time::Duration;

/// How often an armed watchdog looks at the stop flag.
pub const STOP_POLL_NS: u64 = 50_000_000;

/// A scan still running this long after a stop request is interrupted.
pub const STOP_WITHIN_NS: u64 = 1_000_000_000;

/// How long a scan may go on after the stop flag was seen; with the poll,
/// the interrupt comes at most [`STOP_WITHIN_NS`] after the request.
pub const STOP_GRACE_NS: u64 = STOP_WITHIN_NS - STOP_POLL_NS;

/// Why the watchdog raised the flag.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cause {
    /// The armed run passed its deadline.
    Time,
    /// A stop was requested and the run was still going after the grace.
    Stop,
}

#[derive(Default)]
struct State {
    /// The run in progress: its raise deadline (`None`: no time limit,
    /// only the stop flag is watched). Times are [`monotonic_ns`].
    armed: Option<Option<i64>>,
    /// When the thread wakes next; `None` while it waits for an arm.
    sleeping_until: Option<i64>,
    /// When the thread first saw the stop flag during a run.
    stop_seen: Option<i64>,
    cause: Option<Cause>,
    quit: bool,
}

struct Shared {
    state: Mutex<State>,
    wake: Condvar,
    interrupt: Interrupt,
}

impl Shared {
    fn lock(&self) -> MutexGuard<'_, State> {
        // A panic while holding this lock cannot leave the state invalid
        // (plain fields), so a poisoned lock is used as is.
        self.state
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }
}

/// The handle the scan loop holds; [`Watchdog::watch`] is the thread.
pub struct Watchdog {
    shared: Arc<Shared>,
    /// When the armed run started ([`monotonic_ns`]).
    started: Option<i64>,
}

impl Watchdog {
    /// A watchdog raising `interrupt` (the backend's flag).
    pub fn new(interrupt: Interrupt) -> Watchdog {
        Watchdog {
            shared: Arc::new(Shared {
                state: Mutex::new(State::default()),
                wake: Condvar::new(),
                interrupt,
            }),
            started: None,
        }
    }

    /// The timer: the body of the thread that serves this watchdog; runs
    /// until [`Watchdog::quit`]. `stop` is the run's stop flag.
    pub fn watcher<'a>(&self, stop: &'a AtomicBool) -> impl FnOnce() + Send + use<'a> {
        let shared = Arc::clone(&self.shared);
        move || watch(&shared, stop)
    }

    /// A task run starts now; raise the flag if it still runs after
    /// `limit_ns` (`None`: only a stop request can interrupt it).
    pub fn arm(&mut self, limit_ns: Option<i64>) {
        let now = monotonic_ns();
        let deadline = limit_ns.map(|ns| now.saturating_add(ns.max(0)));
        let mut s = self.shared.lock();
        self.shared.interrupt.clear();
        s.cause = None;
        s.armed = Some(deadline);
        let wake = match (s.sleeping_until, deadline) {
            (None, _) => true,
            (Some(until), Some(d)) => until > d,
            (Some(_), None) => false,
        };
        drop(s);
        if wake {
            self.shared.wake.notify_one();
        }
        self.started = Some(now);
    }

    /// The run ended; returns its wall time in ns and why the flag was
    /// raised meanwhile, if it was.
    pub fn disarm(&mut self) -> (i64, Option<Cause>) {
        let mut s = self.shared.lock();
        s.armed = None;
        let cause = s.cause;
        drop(s);
        let ns = self
            .started
            .take()
            .map_or(0, |t| monotonic_ns().saturating_sub(t).max(0));
        (ns, cause)
    }

    /// Ends the thread of [`Watchdog::watcher`].
    pub fn quit(&self) {
        self.shared.lock().quit = true;
        self.shared.wake.notify_one();
    }
}

/// `--watchdog` and `[tasks.NAME] watchdog`: a duration longer than 0
/// (`100ms`, `T#2s`) or `off`; the sensitivity is given apart (1 here).
pub fn parse_watchdog(text: &str) -> Result<TaskWatchdog, String> {
    if text.trim().eq_ignore_ascii_case("off") {
        return Ok(TaskWatchdog::Off);
    }
    match crate::timearg::parse_duration(text.trim()) {
        Ok(0) => Err("a watchdog must be longer than 0 (or `off`)".into()),
        Ok(time_ns) => Ok(TaskWatchdog::Limit {
            time_ns,
            sensitivity: 1,
        }),
        Err(e) => Err(format!("{e}, or `off`")),
    }
}

fn watch(shared: &Shared, stop: &AtomicBool) {
    let mut s = shared.lock();
    loop {
        if s.quit {
            return;
        }
        let Some(deadline) = s.armed else {
            s.sleeping_until = None;
            s = shared.wake.wait(s).unwrap_or_else(|p| p.into_inner());
            continue;
        };
        let now = monotonic_ns();
        if stop.load(Ordering::Relaxed) && s.stop_seen.is_none() {
            s.stop_seen = Some(now);
        }
        let stop_at = s.stop_seen.map(|t| t.saturating_add(STOP_GRACE_NS as i64));
        let cause = if stop_at.is_some_and(|t| now >= t) {
            Some(Cause::Stop)
        } else if deadline.is_some_and(|d| now >= d) {
            Some(Cause::Time)
        } else {
            None
        };
        if let Some(c) = cause {
            s.cause = Some(c);
            s.armed = None;
            shared.interrupt.raise();
            continue;
        }
        let mut until = now.saturating_add(STOP_POLL_NS as i64);
        for t in [deadline, stop_at].into_iter().flatten() {
            until = until.min(t);
        }
        s.sleeping_until = Some(until);
        let wait = Duration::from_nanos(u64::try_from(until.saturating_sub(now)).unwrap_or(0));
        s = shared
            .wake
            .wait_timeout(s, wait)
            .map(|(g, _)| g)
            .unwrap_or_else(|p| p.into_inner().0);
    }
}

#[cfg(test)]
#[path = "watchdog_tests.rs"]
mod tests;
