//! Which tasks run when.
//!
//! Rules (IEC 61131-3 tasks, with `docs/semantics.md`):
//! - A task with an `INTERVAL` I runs at PLC times 0, I, 2I, …
//! - A task without interval and without `SINGLE` (the implicit task of a
//!   project without CONFIGURATION, or a cyclic task) runs every base tick.
//! - The base tick is the GCD of all intervals; without any interval it is
//!   the runtime's cycle time (`--cycle-time`).
//! - An event task (`SINGLE`) runs on the base tick at which its BOOL is
//!   TRUE and was FALSE at the previous base tick (the value before the first
//!   tick counts as FALSE, as for R_TRIG). Its `INTERVAL`, if any, is ignored.
//! - Several tasks due at one instant run higher priority (lower number)
//!   first, ties in declaration order.
//! - Instants missed (a real-time overrun) are skipped, not caught up: after
//!   [`Schedule::skip_to`] every task is next due at its first instant not
//!   before the given time.

use crate::timearg::gcd;
use automat_ir::TaskDef;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Trigger {
    Periodic { period: i64 },
    Event { offset: u32, bit: Option<u8> },
}

#[derive(Clone, Debug)]
struct TaskState {
    trigger: Trigger,
    next_due: i64,
    /// The value of the event BOOL at the previous base tick.
    prev: bool,
    runs: u64,
}

/// The state of the task scheduler.
#[derive(Clone, Debug)]
pub struct Schedule {
    tasks: Vec<TaskState>,
    /// Task indexes in the order they run when due at the same instant.
    order: Vec<usize>,
    base_ns: i64,
    /// The periodic task with the shortest period (first declared on ties).
    fastest: Option<usize>,
    /// Events are sampled on every base tick; so are empty configurations
    /// (the PLC idles at the base tick).
    sample_every_tick: bool,
    next_base_tick: i64,
}

/// The first multiple of `period` strictly after `now` (`i64::MAX`, never,
/// when it does not fit).
fn next_multiple_after(now: i64, period: i64) -> i64 {
    (now / period)
        .checked_add(1)
        .and_then(|k| k.checked_mul(period))
        .unwrap_or(i64::MAX)
}

/// The first multiple of `period` at or after `now`.
fn first_multiple_from(now: i64, period: i64) -> i64 {
    if now % period == 0 {
        now
    } else {
        next_multiple_after(now, period)
    }
}

impl Schedule {
    /// A schedule for `tasks`; `cycle_time_ns` is the base tick when no task
    /// has an interval. Refuses a cycle time that is not positive.
    pub fn new(tasks: &[TaskDef], cycle_time_ns: i64) -> Result<Schedule, String> {
        if cycle_time_ns <= 0 {
            return Err("the cycle time must be longer than 0".to_string());
        }
        let base_ns = tasks
            .iter()
            .filter(|t| t.single.is_none())
            .filter_map(|t| t.interval_ns.filter(|&i| i > 0))
            .reduce(gcd)
            .unwrap_or(cycle_time_ns);
        let states: Vec<TaskState> = tasks
            .iter()
            .map(|t| TaskState {
                trigger: match (t.single, t.interval_ns) {
                    (Some((offset, bit)), _) => Trigger::Event { offset, bit },
                    (None, Some(i)) if i > 0 => Trigger::Periodic { period: i },
                    (None, _) => Trigger::Periodic { period: base_ns },
                },
                next_due: 0,
                prev: false,
                runs: 0,
            })
            .collect();
        let mut order: Vec<usize> = (0..tasks.len()).collect();
        // A stable sort keeps declaration order among equal priorities.
        order.sort_by_key(|&i| tasks.get(i).map_or(u32::MAX, |t| t.priority));
        let mut fastest: Option<(usize, i64)> = None;
        for (i, s) in states.iter().enumerate() {
            if let Trigger::Periodic { period } = s.trigger {
                if fastest.is_none_or(|(_, p)| period < p) {
                    fastest = Some((i, period));
                }
            }
        }
        let sample_every_tick = states.is_empty()
            || states
                .iter()
                .any(|s| matches!(s.trigger, Trigger::Event { .. }));
        Ok(Schedule {
            tasks: states,
            order,
            base_ns,
            fastest: fastest.map(|(i, _)| i),
            sample_every_tick,
            next_base_tick: 0,
        })
    }

    /// The base tick in ns.
    pub fn base_ns(&self) -> i64 {
        self.base_ns
    }

    /// The index of the periodic task with the shortest period, whose runs
    /// `--cycles` counts; `None` when no task is periodic.
    pub fn fastest(&self) -> Option<usize> {
        self.fastest
    }

    /// How many times task `task` has run.
    pub fn runs(&self, task: usize) -> u64 {
        self.tasks.get(task).map_or(0, |t| t.runs)
    }

    /// The next instant at which something may run (`i64::MAX` when
    /// nothing ever will within the range of PLC time).
    pub fn next_tick(&self) -> i64 {
        let periodic = self
            .tasks
            .iter()
            .filter(|t| matches!(t.trigger, Trigger::Periodic { .. }))
            .map(|t| t.next_due)
            .min()
            .unwrap_or(i64::MAX);
        if self.sample_every_tick {
            periodic.min(self.next_base_tick)
        } else {
            periodic
        }
    }

    /// Puts into `out` the tasks due at `now` (an instant returned by
    /// [`Schedule::next_tick`]) in the order they must run, samples the
    /// event BOOLs from `image`, and advances every due task.
    pub fn due(&mut self, now: i64, image: &[u8], out: &mut Vec<usize>) {
        out.clear();
        let sample = self.sample_every_tick && self.next_base_tick <= now;
        if sample {
            self.next_base_tick = next_multiple_after(now, self.base_ns);
        }
        for &i in &self.order {
            let Some(t) = self.tasks.get_mut(i) else {
                continue;
            };
            let run = match t.trigger {
                Trigger::Periodic { period } => {
                    let due = t.next_due <= now;
                    if due {
                        t.next_due = next_multiple_after(now, period);
                    }
                    due
                }
                Trigger::Event { offset, bit } => {
                    if sample {
                        let v = read_bool(image, offset, bit);
                        let rising = v && !t.prev;
                        t.prev = v;
                        rising
                    } else {
                        false
                    }
                }
            };
            if run {
                t.runs += 1;
                out.push(i);
            }
        }
    }

    /// After an overrun: every instant before `now` is dropped; each task is
    /// next due at its first instant at or after `now`.
    pub fn skip_to(&mut self, now: i64) {
        for t in &mut self.tasks {
            if let Trigger::Periodic { period } = t.trigger {
                if t.next_due < now {
                    t.next_due = first_multiple_from(now, period);
                }
            }
        }
        if self.next_base_tick < now {
            self.next_base_tick = first_multiple_from(now, self.base_ns);
        }
    }
}

/// A BOOL of the image: a whole byte (non-zero) or one bit of it; FALSE
/// outside the image.
pub(crate) fn read_bool(image: &[u8], offset: u32, bit: Option<u8>) -> bool {
    let byte = usize::try_from(offset)
        .ok()
        .and_then(|o| image.get(o))
        .copied()
        .unwrap_or(0);
    match bit {
        Some(b) if b < 8 => byte >> b & 1 != 0,
        Some(_) => false,
        None => byte != 0,
    }
}

#[cfg(test)]
#[path = "schedule_tests.rs"]
mod tests;
