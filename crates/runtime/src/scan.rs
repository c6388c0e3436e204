//! The scan loop: inputs → tasks due → outputs, paced by the clock, until a
//! limit, a stop request or a fault.
//!
//! Stop conditions:
//! - [`Limit::Cycles`]`(n)`: after the scan in which the fastest periodic
//!   task ran for the n-th time (without periodic tasks: after n base ticks).
//! - [`Limit::Duration`]`(d)`: before the first scan due at PLC time ≥ d,
//!   so a task of interval I runs at 0, I, 2I, … < d.
//! - the `stop` flag (Ctrl-C, SIGTERM, SIGHUP): checked between scans and
//!   while sleeping, so a scan always completes; the PLC then goes to its
//!   safe state ([`SafeState`]: the %Q area, every program VAR_OUTPUT and
//!   the caller's extra places), written to the outputs once more, and the
//!   run ends with [`RunEnd::Stopped`].
//! - a fault: the safe state likewise, and the run ends with
//!   [`RunEnd::Fault`].
//!
//! A run that reaches its limit (`--cycles`, `--duration`) ends as it is:
//! the image is the end of its last scan, for printing and checking.
//!
//! The watchdog (`watchdog.rs`, wall time, a thread for the run) is armed
//! around every task run with the task's [`TaskWatchdog`]: a run still
//! going after its time × sensitivity is interrupted where it is, and
//! `sensitivity` consecutive runs longer than its time fault after the
//! last; a stop request during a long scan interrupts it within a second.
//! Both are faults of kind `Watchdog` whose message names the task and the
//! time.

use crate::clock::{ClockMode, Monotonic};
use crate::executor::Executor;
use crate::io::{InputSource, OutputSink};
use crate::safe::SafeState;
use crate::schedule::Schedule;
use crate::stats::Stats;
use crate::watchdog::{Cause, Watchdog, STOP_WITHIN_NS};
use automat_ir::{Fault, FaultKind, Site, TaskDef, TaskWatchdog};
use std::fmt;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};

/// When a run stops by itself.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Limit {
    Cycles(u64),
    Duration(i64),
    /// Until the stop flag is set.
    Unbounded,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RunConfig {
    /// Base period when no task has an interval (`--cycle-time`).
    pub cycle_time_ns: i64,
    pub clock: ClockMode,
    pub limit: Limit,
}

/// Sees the image after every scan in which a task ran (tracing,
/// monitoring). An error ends the run with [`RunEnd::Observer`].
pub trait ScanObserver {
    fn after_scan(&mut self, plc_time_ns: i64, image: &[u8]) -> Result<(), String>;
    /// The cycle statistics after each scan that ran a task (scan time
    /// measured on the run's clock, overruns counted): for live views.
    fn stats(&mut self, _stats: &Stats) {}
    /// Between two scans (after each scan that ran a task, its statistics
    /// recorded): the image may be changed (one-shot writes of an online
    /// session) and the observer may wait here (a stopped session).
    /// `false` ends the run with [`RunEnd::Stopped`].
    fn between_scans(&mut self, _image: &mut [u8]) -> bool {
        true
    }
}

impl ScanObserver for () {
    fn after_scan(&mut self, _plc_time_ns: i64, _image: &[u8]) -> Result<(), String> {
        Ok(())
    }
}

/// The things at the edges of the scan loop.
pub struct Env<'a> {
    pub clock: &'a mut dyn Monotonic,
    pub inputs: &'a mut dyn InputSource,
    pub outputs: &'a mut dyn OutputSink,
    pub observer: &'a mut dyn ScanObserver,
    /// Set (e.g. by a Ctrl-C handler) to stop at the end of the scan.
    pub stop: &'a AtomicBool,
}

/// A fault with the task and program instance it happened in.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FaultReport {
    pub fault: Fault,
    pub task: String,
    pub instance: String,
    pub plc_time_ns: i64,
}

impl fmt::Display for FaultReport {
    /// `main.st:4:10: fault in MAIN: division by zero (task T1, program instance MAIN, PLC time T#20ms)`
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} (task {}, program instance {}, PLC time {})",
            self.fault,
            self.task,
            self.instance,
            automat_iec::format::format_duration(self.plc_time_ns, false)
        )
    }
}

/// Why a run ended.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RunEnd {
    /// `--cycles` or `--duration` reached.
    Limit,
    /// The stop flag was set.
    Stopped,
    /// PLC time reached the end of its range: nothing can be due any more.
    TimeExhausted,
    Fault(Box<FaultReport>),
    Observer(String),
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RunReport {
    pub end: RunEnd,
    pub stats: Stats,
    /// PLC time of the last scan that ran (`None` when none did).
    pub last_scan_ns: Option<i64>,
}

/// How long the real-time loop sleeps at most before looking at the stop
/// flag again, so Ctrl-C is served quickly even with long task intervals.
const STOP_POLL_NS: i64 = 50_000_000;

fn usize_range(r: &Range<u32>) -> Option<Range<usize>> {
    Some(usize::try_from(r.start).ok()?..usize::try_from(r.end).ok()?)
}

/// The watchdog time of a task run on the virtual clock when nothing is
/// configured: far above any legitimate scan, short enough to end a test.
pub const VIRTUAL_DEFAULT_WATCHDOG_NS: i64 = 10_000_000_000;

/// A task's watchdog as this run applies it (`None`: off).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct TaskDog {
    time_ns: i64,
    sensitivity: u32,
    /// The virtual clock's default, not configured.
    default: bool,
}

fn task_dog(w: TaskWatchdog, clock: ClockMode) -> Option<TaskDog> {
    match (w, clock) {
        (TaskWatchdog::Default, ClockMode::Virtual) => Some(TaskDog {
            time_ns: VIRTUAL_DEFAULT_WATCHDOG_NS,
            sensitivity: 1,
            default: true,
        }),
        (TaskWatchdog::Default, ClockMode::RealTime) | (TaskWatchdog::Off, _) => None,
        (
            TaskWatchdog::Limit {
                time_ns,
                sensitivity,
            },
            _,
        ) => Some(TaskDog {
            time_ns,
            sensitivity: sensitivity.max(1),
            default: false,
        }),
    }
}

fn dur(ns: i64) -> String {
    automat_iec::format::format_duration(ns, false)
}

impl TaskDog {
    /// How long one run may go on before it is interrupted.
    fn limit_ns(&self) -> i64 {
        self.time_ns.saturating_mul(i64::from(self.sensitivity))
    }

    /// What the watchdog says when it interrupts a run of `task`.
    fn interrupted(&self, task: &str) -> String {
        if self.default {
            format!(
                "watchdog: task {task} ran longer than {} of wall time (the default watchdog of a \
                 virtual-clock run; set `[tasks.{task}] watchdog` or --watchdog)",
                dur(self.time_ns)
            )
        } else if self.sensitivity > 1 {
            format!(
                "watchdog: task {task} ran longer than {} (its watchdog {} × sensitivity {})",
                dur(self.limit_ns()),
                dur(self.time_ns),
                self.sensitivity
            )
        } else {
            format!(
                "watchdog: task {task} ran longer than its watchdog {}",
                dur(self.time_ns)
            )
        }
    }
}

/// After a completed run of `task` that took `wall_ns`: counts an overrun
/// of its watchdog time in `row`, and faults on the `sensitivity`-th in a
/// row (a fault with no source line: the run had ended).
fn count_overrun(
    row: &mut u32,
    d: TaskDog,
    wall_ns: i64,
    task: &TaskDef,
) -> Option<(Fault, String)> {
    if wall_ns <= d.time_ns {
        *row = 0;
        return None;
    }
    *row += 1;
    if *row < d.sensitivity {
        return None;
    }
    let instance = task
        .programs
        .last()
        .map_or(String::new(), |p| p.name.clone());
    let message = if d.sensitivity > 1 {
        format!(
            "watchdog: task {} overran its watchdog {} in {} consecutive runs (the last took {})",
            task.name,
            dur(d.time_ns),
            d.sensitivity,
            dur(wall_ns)
        )
    } else {
        format!(
            "watchdog: task {} took {}, longer than its watchdog {}",
            task.name,
            dur(wall_ns),
            dur(d.time_ns)
        )
    };
    let fault = Fault {
        kind: FaultKind::Watchdog,
        message,
        site: Site {
            pou: instance.clone(),
            location: "(end of the run)".into(),
            meaning: None,
        },
    };
    Some((fault, instance))
}

struct Loop<'a, 'e, E: Executor> {
    exec: &'a mut E,
    env: &'a mut Env<'e>,
    tasks: Vec<TaskDef>,
    input: Option<Range<usize>>,
    output: Option<Range<usize>>,
    sched: Schedule,
    stats: Stats,
    due: Vec<usize>,
    ticks: u64,
    last_scan_ns: Option<i64>,
    safe: &'a SafeState,
    watchdog: Watchdog,
    /// Per task: its watchdog in this run, and its overruns in a row.
    dogs: Vec<Option<TaskDog>>,
    overruns_in_row: Vec<u32>,
}

/// Runs the program of `exec` (whose image is already cold- or
/// warm-started) until a stop condition, with the default safe state of
/// its program ([`SafeState::of_program`]). Errors only on an invalid
/// configuration (a cycle time ≤ 0).
pub fn run<E: Executor>(exec: &mut E, cfg: &RunConfig, env: &mut Env) -> Result<RunReport, String> {
    let safe = SafeState::of_program(exec.program());
    run_safe(exec, cfg, env, &safe)
}

/// [`run`] with the caller's safe state (configured safe values, places
/// bound to a plant).
pub fn run_safe<E: Executor>(
    exec: &mut E,
    cfg: &RunConfig,
    env: &mut Env,
    safe: &SafeState,
) -> Result<RunReport, String> {
    let program = exec.program();
    let tasks = program.tasks.clone();
    let input = usize_range(&program.areas.input);
    let output = usize_range(&program.areas.output);
    let sched = Schedule::new(&tasks, cfg.cycle_time_ns)?;
    let due = Vec::with_capacity(tasks.len());
    let dogs = tasks
        .iter()
        .map(|t| task_dog(t.watchdog, cfg.clock))
        .collect();
    let overruns_in_row = vec![0; tasks.len()];
    let watchdog = Watchdog::new(exec.interrupt());
    let stop: &AtomicBool = env.stop;
    let mut l = Loop {
        exec,
        env,
        tasks,
        input,
        output,
        sched,
        stats: Stats::default(),
        due,
        ticks: 0,
        last_scan_ns: None,
        safe,
        watchdog,
        dogs,
        overruns_in_row,
    };
    let end = std::thread::scope(|s| {
        let timer = l.watchdog.watcher(stop);
        let (started, running) = std::sync::mpsc::sync_channel(1);
        let spawned = std::thread::Builder::new()
            .name("automat-watchdog".into())
            .spawn_scoped(s, move || {
                // In real-time mode the timer must preempt a looping scan
                // on the same CPU: one priority above the scan thread.
                crate::realtime::above_inherited();
                let _ = started.send(());
                timer()
            });
        if let Err(e) = spawned {
            return RunEnd::Observer(format!("cannot start the watchdog thread: {e}"));
        }
        // The first scan waits for the timer thread: at the scan thread's
        // SCHED_FIFO priority on its CPU, it would never get to run (and
        // raise its priority) once a scan loops.
        let _ = running.recv();
        let end = l.run(cfg);
        l.watchdog.quit();
        end
    });
    if matches!(end, RunEnd::Stopped) {
        let t = l.last_scan_ns.unwrap_or(0);
        l.safe_state(t);
    }
    l.stats.task_runs = l
        .tasks
        .iter()
        .enumerate()
        .map(|(i, t)| (t.name.clone(), l.sched.runs(i)))
        .collect();
    Ok(RunReport {
        end,
        stats: l.stats,
        last_scan_ns: l.last_scan_ns,
    })
}

impl<E: Executor> Loop<'_, '_, E> {
    fn run(&mut self, cfg: &RunConfig) -> RunEnd {
        let origin = self.env.clock.now_ns();
        loop {
            if self.env.stop.load(Ordering::Relaxed) {
                return RunEnd::Stopped;
            }
            if self.limit_reached(cfg.limit) {
                return RunEnd::Limit;
            }
            let t = self.sched.next_tick();
            if t == i64::MAX {
                return RunEnd::TimeExhausted;
            }
            if let Limit::Duration(d) = cfg.limit {
                if t >= d {
                    return RunEnd::Limit;
                }
            }
            let deadline = origin.saturating_add(t);
            if cfg.clock == ClockMode::RealTime && !self.wait_until(deadline) {
                return RunEnd::Stopped;
            }
            let started = self.env.clock.now_ns();
            if cfg.clock == ClockMode::RealTime {
                // Jitter: how late the scan starts after its deadline.
                self.stats
                    .start_late
                    .record(started.saturating_sub(deadline));
            }
            if let Some(end) = self.scan(t) {
                return end;
            }
            let ended = self.env.clock.now_ns();
            if !self.due.is_empty() {
                self.stats.record(ended.saturating_sub(started));
            }
            if cfg.clock == ClockMode::RealTime {
                let late = ended.saturating_sub(origin);
                if late > self.sched.next_tick() {
                    self.stats.overruns += 1;
                    self.sched.skip_to(late);
                }
            }
            if !self.due.is_empty() {
                self.env.observer.stats(&self.stats);
                if !self.env.observer.between_scans(self.exec.image_mut()) {
                    return RunEnd::Stopped;
                }
            }
        }
    }

    fn limit_reached(&self, limit: Limit) -> bool {
        match (limit, self.sched.fastest()) {
            (Limit::Cycles(n), Some(f)) => self.sched.runs(f) >= n,
            (Limit::Cycles(n), None) => self.ticks >= n,
            _ => false,
        }
    }

    /// Sleeps until `deadline` on the monotonic clock; `false` when the stop
    /// flag was set meanwhile.
    fn wait_until(&mut self, deadline: i64) -> bool {
        loop {
            if self.env.stop.load(Ordering::Relaxed) {
                return false;
            }
            let now = self.env.clock.now_ns();
            if now >= deadline {
                return true;
            }
            let step = deadline.min(now.saturating_add(STOP_POLL_NS));
            self.env.clock.sleep_until(step);
        }
    }

    /// One scan at PLC time `t`; `Some` when the run must end.
    fn scan(&mut self, t: i64) -> Option<RunEnd> {
        self.ticks += 1;
        if let Some(area) = self
            .input
            .clone()
            .and_then(|r| self.exec.image_mut().get_mut(r))
        {
            self.env.inputs.read(t, area);
        }
        self.sched.due(t, self.exec.image(), &mut self.due);
        for &i in &self.due {
            let Some(task) = self.tasks.get(i) else {
                continue;
            };
            let dog = self.dogs.get(i).copied().flatten();
            self.watchdog.arm(dog.map(|d| d.limit_ns()));
            let mut failed = None;
            for inst in &task.programs {
                if let Err(fault) = self.exec.run_program(inst, t) {
                    failed = Some((fault, inst));
                    break;
                }
            }
            let (wall_ns, cause) = self.watchdog.disarm();
            let fault = match failed {
                Some((mut fault, inst)) => {
                    if fault.message == automat_ir::interrupt::INTERRUPTED {
                        fault.message = match (cause, dog) {
                            (Some(Cause::Time), Some(d)) => d.interrupted(&task.name),
                            _ => format!(
                                "stopped: the scan was still running {} after the stop request",
                                dur(STOP_WITHIN_NS as i64)
                            ),
                        };
                    }
                    Some((fault, inst.name.clone()))
                }
                None => match (dog, self.overruns_in_row.get_mut(i)) {
                    (Some(d), Some(row)) => count_overrun(row, d, wall_ns, task),
                    _ => None,
                },
            };
            if let Some((fault, instance)) = fault {
                let report = FaultReport {
                    fault,
                    task: task.name.clone(),
                    instance,
                    plc_time_ns: t,
                };
                self.safe_state(t);
                return Some(RunEnd::Fault(Box::new(report)));
            }
        }
        self.write_outputs(t);
        if self.due.is_empty() {
            return None;
        }
        self.last_scan_ns = Some(t);
        self.env
            .observer
            .after_scan(t, self.exec.image())
            .err()
            .map(RunEnd::Observer)
    }

    fn write_outputs(&mut self, t: i64) {
        if let Some(area) = self.output.clone().and_then(|r| self.exec.image().get(r)) {
            self.env.outputs.write(t, area);
        }
    }

    /// Every output to its safe value, and the outputs told so.
    fn safe_state(&mut self, t: i64) {
        self.safe.apply(self.exec.image_mut());
        self.write_outputs(t);
    }
}

#[cfg(test)]
#[path = "scan_tests.rs"]
mod tests;
