use super::*;
use crate::io::{InputSource, NoIo, OutputSink};
use crate::testutil::{inst, program, task, Fake, COUNT, FAULT_ON_THIRD, SET_OUTPUT};
use automat_ir::ProgramInstance;
use std::cell::Cell;
use std::rc::Rc;

const MS: i64 = 1_000_000;

/// A clock that only moves when slept or when a [`Slow`] program runs.
struct FakeClock {
    now: Rc<Cell<i64>>,
    sleeps: Vec<i64>,
}

impl Monotonic for FakeClock {
    fn now_ns(&mut self) -> i64 {
        self.now.get()
    }
    fn sleep_until(&mut self, deadline_ns: i64) {
        self.sleeps.push(deadline_ns);
        self.now.set(self.now.get().max(deadline_ns));
    }
}

/// A fake backend whose runs take time on a [`FakeClock`]: run k costs
/// `costs[k]` (the last one repeats).
struct Slow {
    inner: Fake,
    now: Rc<Cell<i64>>,
    costs: Vec<i64>,
    runs: usize,
}

impl Executor for Slow {
    fn program(&self) -> &automat_ir::Program {
        self.inner.program()
    }
    fn image(&self) -> &[u8] {
        self.inner.image()
    }
    fn image_mut(&mut self) -> &mut [u8] {
        self.inner.image_mut()
    }
    fn cold_start(&mut self) {
        self.inner.cold_start()
    }
    fn run_program(&mut self, inst: &ProgramInstance, now_ns: i64) -> Result<(), Fault> {
        let cost = self
            .costs
            .get(self.runs)
            .or(self.costs.last())
            .copied()
            .unwrap_or(0);
        self.runs += 1;
        self.now.set(self.now.get() + cost);
        self.inner.run_program(inst, now_ns)
    }
    fn interrupt(&self) -> automat_ir::Interrupt {
        self.inner.interrupt()
    }
}

#[derive(Default)]
struct Outputs(Vec<(i64, Vec<u8>)>);

impl OutputSink for Outputs {
    fn write(&mut self, t: i64, output: &[u8]) {
        self.0.push((t / MS, output.to_vec()));
    }
}

fn run_virtual<E: Executor>(
    exec: &mut E,
    limit: Limit,
    observer: &mut dyn ScanObserver,
) -> RunReport {
    let stop = AtomicBool::new(false);
    let mut clock = crate::SystemClock::new();
    let mut env = Env {
        clock: &mut clock,
        inputs: &mut NoIo,
        outputs: &mut NoIo,
        observer,
        stop: &stop,
    };
    let cfg = RunConfig {
        cycle_time_ns: 10 * MS,
        clock: ClockMode::Virtual,
        limit,
    };
    run(exec, &cfg, &mut env).unwrap()
}

fn times(log: &[(String, i64)]) -> Vec<(&str, i64)> {
    log.iter().map(|(n, t)| (n.as_str(), t / MS)).collect()
}

#[test]
fn cycles_of_the_implicit_task_at_exact_virtual_times() {
    let mut f = Fake::new(program(vec![task(
        "MAIN",
        None,
        0,
        vec![inst("MAIN", COUNT, 0)],
    )]));
    let r = run_virtual(&mut f, Limit::Cycles(5), &mut ());
    assert_eq!(r.end, RunEnd::Limit);
    assert_eq!(r.last_scan_ns, Some(40 * MS));
    assert_eq!(
        times(&f.log),
        [
            ("MAIN", 0),
            ("MAIN", 10),
            ("MAIN", 20),
            ("MAIN", 30),
            ("MAIN", 40)
        ]
    );
    assert_eq!(f.counter(0), 5);
    assert_eq!(r.stats.scans, 5);
    assert_eq!(r.stats.task_runs, [("MAIN".to_string(), 5)]);
    assert_eq!(r.stats.overruns, 0);
}

fn two_tasks() -> Fake {
    Fake::new(program(vec![
        task("SLOW", Some(15), 1, vec![inst("S", COUNT, 0)]),
        task("FAST", Some(10), 2, vec![inst("F", COUNT, 4)]),
    ]))
}

#[test]
fn cycles_count_the_fastest_task() {
    let mut f = two_tasks();
    let r = run_virtual(&mut f, Limit::Cycles(3), &mut ());
    assert_eq!(
        times(&f.log),
        [("S", 0), ("F", 0), ("F", 10), ("S", 15), ("F", 20)]
    );
    assert_eq!(
        r.stats.task_runs,
        [("SLOW".to_string(), 2), ("FAST".to_string(), 3)]
    );
    assert_eq!(r.stats.scans, 4);
}

#[test]
fn duration_runs_every_instant_before_it() {
    let mut f = two_tasks();
    let r = run_virtual(&mut f, Limit::Duration(30 * MS), &mut ());
    assert_eq!(r.end, RunEnd::Limit);
    assert_eq!(
        times(&f.log),
        [("S", 0), ("F", 0), ("F", 10), ("S", 15), ("F", 20)]
    );
    let mut f = two_tasks();
    run_virtual(&mut f, Limit::Duration(30 * MS + 1), &mut ());
    assert_eq!(f.log.len(), 7);
    let mut f = two_tasks();
    let r = run_virtual(&mut f, Limit::Duration(0), &mut ());
    assert_eq!((f.log.len(), r.last_scan_ns), (0, None));
    let mut f = two_tasks();
    run_virtual(&mut f, Limit::Cycles(0), &mut ());
    assert!(f.log.is_empty());
}

#[test]
fn a_fault_stops_in_the_safe_state() {
    let mut f = Fake::new(program(vec![task(
        "MAIN",
        None,
        0,
        vec![inst("OUT", SET_OUTPUT, 0), inst("BAD", FAULT_ON_THIRD, 8)],
    )]));
    let stop = AtomicBool::new(false);
    let mut clock = crate::SystemClock::new();
    let mut outputs = Outputs::default();
    let mut env = Env {
        clock: &mut clock,
        inputs: &mut NoIo,
        outputs: &mut outputs,
        observer: &mut (),
        stop: &stop,
    };
    let cfg = RunConfig {
        cycle_time_ns: 10 * MS,
        clock: ClockMode::Virtual,
        limit: Limit::Cycles(10),
    };
    let r = run(&mut f, &cfg, &mut env).unwrap();
    let RunEnd::Fault(report) = &r.end else {
        panic!("{:?}", r.end)
    };
    assert_eq!(
        report.to_string(),
        "main.st:4:10: fault in MAIN: division by zero (task MAIN, program instance BAD, PLC time T#20ms)"
    );
    assert_eq!(f.image[44..48], [0, 0, 0, 0]);
    assert_eq!(
        outputs.0,
        [
            (0, vec![0xFF, 0, 0, 0]),
            (10, vec![0xFF, 0, 0, 0]),
            (20, vec![0, 0, 0, 0])
        ]
    );
    assert_eq!(r.stats.scans, 2);
    assert_eq!(r.last_scan_ns, Some(10 * MS));
}

struct StopAfter<'a> {
    n: u32,
    stop: &'a AtomicBool,
    seen: Vec<i64>,
}

impl ScanObserver for StopAfter<'_> {
    fn after_scan(&mut self, t: i64, _image: &[u8]) -> Result<(), String> {
        self.seen.push(t / MS);
        if self.seen.len() as u32 == self.n {
            self.stop.store(true, Ordering::Relaxed);
        }
        if self.seen.len() > 10 {
            return Err("disk full".into());
        }
        Ok(())
    }
}

#[test]
fn stop_flag_ends_after_the_scan_and_observer_errors_end_the_run() {
    let stop = AtomicBool::new(false);
    let mut obs = StopAfter {
        n: 3,
        stop: &stop,
        seen: Vec::new(),
    };
    let mut f = Fake::new(program(vec![task(
        "MAIN",
        None,
        0,
        vec![inst("MAIN", COUNT, 0)],
    )]));
    let mut clock = crate::SystemClock::new();
    let mut env = Env {
        clock: &mut clock,
        inputs: &mut NoIo,
        outputs: &mut NoIo,
        observer: &mut obs,
        stop: &stop,
    };
    let cfg = RunConfig {
        cycle_time_ns: 10 * MS,
        clock: ClockMode::Virtual,
        limit: Limit::Unbounded,
    };
    let r = run(&mut f, &cfg, &mut env).unwrap();
    assert_eq!(r.end, RunEnd::Stopped);
    assert_eq!(obs.seen, [0, 10, 20]);
    assert_eq!(f.counter(0), 3);

    let never = AtomicBool::new(false);
    let mut obs = StopAfter {
        n: 0,
        stop: &never,
        seen: Vec::new(),
    };
    let mut f = Fake::new(program(vec![task(
        "MAIN",
        None,
        0,
        vec![inst("MAIN", COUNT, 0)],
    )]));
    let r = run_virtual(&mut f, Limit::Unbounded, &mut obs);
    assert_eq!(r.end, RunEnd::Observer("disk full".into()));
    assert_eq!(f.counter(0), 11);
}

#[test]
fn real_time_sleeps_to_absolute_deadlines_and_skips_after_an_overrun() {
    let now = Rc::new(Cell::new(0));
    let mut clock = FakeClock {
        now: now.clone(),
        sleeps: Vec::new(),
    };
    let mut exec = Slow {
        inner: Fake::new(program(vec![task(
            "MAIN",
            None,
            0,
            vec![inst("MAIN", COUNT, 0)],
        )])),
        now: now.clone(),
        costs: vec![MS, 25 * MS, MS],
        runs: 0,
    };
    let stop = AtomicBool::new(false);
    let mut env = Env {
        clock: &mut clock,
        inputs: &mut NoIo,
        outputs: &mut NoIo,
        observer: &mut (),
        stop: &stop,
    };
    let cfg = RunConfig {
        cycle_time_ns: 10 * MS,
        clock: ClockMode::RealTime,
        limit: Limit::Cycles(4),
    };
    let r = run(&mut exec, &cfg, &mut env).unwrap();
    // The scan at 10 ms ended at 35 ms: 20 and 30 are skipped, not caught up.
    assert_eq!(
        times(&exec.inner.log),
        [("MAIN", 0), ("MAIN", 10), ("MAIN", 40), ("MAIN", 50)]
    );
    assert_eq!(clock.sleeps, [10 * MS, 40 * MS, 50 * MS]);
    assert_eq!(r.stats.overruns, 1);
    assert_eq!(
        (r.stats.min_ns, r.stats.max_ns, r.stats.avg_ns()),
        (Some(MS), Some(25 * MS), Some(7 * MS))
    );
}

#[test]
fn long_sleeps_poll_the_stop_flag() {
    let now = Rc::new(Cell::new(0));
    let mut clock = FakeClock {
        now: now.clone(),
        sleeps: Vec::new(),
    };
    let mut f = Fake::new(program(vec![task(
        "MAIN",
        Some(120),
        0,
        vec![inst("MAIN", COUNT, 0)],
    )]));
    let stop = AtomicBool::new(false);
    let mut env = Env {
        clock: &mut clock,
        inputs: &mut NoIo,
        outputs: &mut NoIo,
        observer: &mut (),
        stop: &stop,
    };
    let cfg = RunConfig {
        cycle_time_ns: 10 * MS,
        clock: ClockMode::RealTime,
        limit: Limit::Cycles(2),
    };
    run(&mut f, &cfg, &mut env).unwrap();
    assert_eq!(clock.sleeps, [50 * MS, 100 * MS, 120 * MS]);
}

/// Sets input byte 0 bit 0 on the scans at the listed times.
struct Pulses(Vec<i64>);

impl InputSource for Pulses {
    fn read(&mut self, t: i64, input: &mut [u8]) {
        input[0] = u8::from(self.0.contains(&(t / MS)));
    }
}

#[test]
fn inputs_feed_event_tasks() {
    let mut ev = task("EV", None, 0, vec![inst("E", COUNT, 8)]);
    ev.single = Some((40, Some(0)));
    let mut f = Fake::new(program(vec![
        task("CYC", Some(10), 1, vec![inst("C", COUNT, 0)]),
        ev,
    ]));
    let stop = AtomicBool::new(false);
    let mut clock = crate::SystemClock::new();
    let mut env = Env {
        clock: &mut clock,
        inputs: &mut Pulses(vec![10, 20, 40]),
        outputs: &mut NoIo,
        observer: &mut (),
        stop: &stop,
    };
    let cfg = RunConfig {
        cycle_time_ns: 10 * MS,
        clock: ClockMode::Virtual,
        limit: Limit::Cycles(6),
    };
    let r = run(&mut f, &cfg, &mut env).unwrap();
    let events: Vec<i64> = f
        .log
        .iter()
        .filter(|(n, _)| n == "E")
        .map(|(_, t)| t / MS)
        .collect();
    assert_eq!(events, [10, 40]);
    assert_eq!(
        r.stats.task_runs,
        [("CYC".to_string(), 6), ("EV".to_string(), 2)]
    );
}

#[test]
fn invalid_cycle_time_is_an_error() {
    let mut f = two_tasks();
    let stop = AtomicBool::new(false);
    let mut clock = crate::SystemClock::new();
    let mut env = Env {
        clock: &mut clock,
        inputs: &mut NoIo,
        outputs: &mut NoIo,
        observer: &mut (),
        stop: &stop,
    };
    let cfg = RunConfig {
        cycle_time_ns: 0,
        clock: ClockMode::Virtual,
        limit: Limit::Cycles(1),
    };
    assert_eq!(
        run(&mut f, &cfg, &mut env).unwrap_err(),
        "the cycle time must be longer than 0"
    );
}

/// OUT (counter at 0, sets %Q byte 0) then BAD (counter at 8, faults on its
/// third run), both counters RETAIN.
fn retained_fault() -> Fake {
    let mut p = program(vec![task(
        "MAIN",
        None,
        0,
        vec![inst("OUT", SET_OUTPUT, 0), inst("BAD", FAULT_ON_THIRD, 8)],
    )]);
    p.retain = vec![0..4, 8..12];
    Fake::new(p)
}

#[test]
fn after_a_fault_the_keeper_holds_the_image_before_the_faulting_scan() {
    let mut f = retained_fault();
    let dir = std::env::temp_dir().join(format!("automat-keeper-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("fault.retain");
    let program = f.program.clone();
    let mut inner = ();
    let mut keeper =
        crate::retain::Keeper::new(&program, &f.image, Some(path.clone()), None, &mut inner);
    let r = run_virtual(&mut f, Limit::Cycles(10), &mut keeper);
    assert!(matches!(r.end, RunEnd::Fault(_)), "{:?}", r.end);
    // The faulting scan ran OUT a third time, then BAD faulted.
    assert_eq!((f.counter(0), f.counter(8)), (3, 3));
    assert_eq!(keeper.snapshot(), [2, 0, 0, 0, 2, 0, 0, 0]);
    keeper.finish().unwrap();
    let mut img = vec![0u8; 64];
    assert_eq!(
        crate::retain::load(&program, &path, &mut img),
        crate::retain::Loaded::Warm
    );
    assert_eq!((img[0], img[8]), (2, 2));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_keeper_saves_every_period_of_plc_time_when_changed() {
    let mut f = Fake::new(program(vec![task(
        "MAIN",
        None,
        0,
        vec![inst("MAIN", COUNT, 0)],
    )]));
    f.program.retain = vec![std::ops::Range { start: 0, end: 4 }];
    let dir = std::env::temp_dir().join(format!("automat-keeper-p-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("periodic.retain");
    let program = f.program.clone();
    struct Seen(Vec<u8>, std::path::PathBuf);
    impl ScanObserver for Seen {
        fn after_scan(&mut self, _t: i64, _image: &[u8]) -> Result<(), String> {
            // What the file held when each scan ended.
            let mut img = vec![0u8; 64];
            let _ = crate::retain::load(
                &{
                    let mut p = crate::testutil::program(vec![]);
                    p.retain = vec![std::ops::Range { start: 0, end: 4 }];
                    p
                },
                &self.1,
                &mut img,
            );
            self.0.push(img[0]);
            Ok(())
        }
    }
    let mut seen = Seen(Vec::new(), path.clone());
    let mut keeper = crate::retain::Keeper::new(
        &program,
        &f.image,
        Some(path.clone()),
        Some(30 * MS),
        &mut seen,
    );
    let r = run_virtual(&mut f, Limit::Cycles(8), &mut keeper);
    assert_eq!(r.end, RunEnd::Limit);
    // Scans at 0, 10, ..., 70 ms; saves at 30 and 60 ms (counters 4, 7).
    assert_eq!(keeper.saves, 2);
    drop(keeper);
    assert_eq!(seen.0, [0, 0, 0, 4, 4, 4, 7, 7]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_stop_request_ends_in_the_configured_safe_state() {
    let stop = AtomicBool::new(false);
    let mut obs = StopAfter {
        n: 2,
        stop: &stop,
        seen: Vec::new(),
    };
    let mut f = Fake::new(program(vec![task(
        "MAIN",
        None,
        0,
        vec![inst("OUT", SET_OUTPUT, 0)],
    )]));
    f.image[45] = 0x11;
    let mut safe = crate::SafeState::of_program(&f.program);
    let valve = crate::resolve(&f.program, "%QX3.0").unwrap();
    safe.set_literal("%QX3.0", &valve, "TRUE").unwrap();
    let mut clock = crate::SystemClock::new();
    let mut outputs = Outputs::default();
    let mut env = Env {
        clock: &mut clock,
        inputs: &mut NoIo,
        outputs: &mut outputs,
        observer: &mut obs,
        stop: &stop,
    };
    let cfg = RunConfig {
        cycle_time_ns: 10 * MS,
        clock: ClockMode::Virtual,
        limit: Limit::Unbounded,
    };
    let r = run_safe(&mut f, &cfg, &mut env, &safe).unwrap();
    assert_eq!(r.end, RunEnd::Stopped);
    assert_eq!(f.image[44..48], [0, 0, 0, 1]);
    assert_eq!(
        outputs.0,
        [
            (0, vec![0xFF, 0x11, 0, 0]),
            (10, vec![0xFF, 0x11, 0, 0]),
            (10, vec![0, 0, 0, 1])
        ]
    );
}

#[test]
fn a_background_keeper_writes_periodically_and_finishes_with_the_last_scan() {
    let mut f = Fake::new(program(vec![task(
        "MAIN",
        None,
        0,
        vec![inst("MAIN", COUNT, 0)],
    )]));
    f.program.retain = vec![std::ops::Range { start: 0, end: 4 }];
    let dir = std::env::temp_dir().join(format!("automat-keeper-bg-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bg.retain");
    let program = f.program.clone();
    let mut inner = ();
    let mut keeper = crate::retain::Keeper::new(
        &program,
        &f.image,
        Some(path.clone()),
        Some(10 * MS),
        &mut inner,
    )
    .in_background();
    let r = run_virtual(&mut f, Limit::Cycles(50), &mut keeper);
    assert_eq!(r.end, RunEnd::Limit);
    keeper.finish().unwrap();
    // 49 periodic saves were handed over; the writer may have merged some.
    assert!((1..=49).contains(&keeper.saves), "{}", keeper.saves);
    assert_eq!(keeper.failures, 0);
    drop(keeper);
    let mut img = vec![0u8; 64];
    assert_eq!(
        crate::retain::load(&program, &path, &mut img),
        crate::retain::Loaded::Warm
    );
    assert_eq!(img[0], 50);
    assert!(!dir.join("bg.retain.tmp").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_unchanged_snapshot_is_not_written_again() {
    // The counter at 0 changes every scan; the RETAIN bytes at 20..24 never.
    let mut f = Fake::new(program(vec![task(
        "MAIN",
        None,
        0,
        vec![inst("MAIN", COUNT, 0)],
    )]));
    f.program.retain = vec![std::ops::Range { start: 20, end: 24 }];
    let dir = std::env::temp_dir().join(format!("automat-keeper-same-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("same.retain");
    let program = f.program.clone();
    let mut inner = ();
    let mut keeper = crate::retain::Keeper::new(
        &program,
        &f.image,
        Some(path.clone()),
        Some(10 * MS),
        &mut inner,
    );
    run_virtual(&mut f, Limit::Cycles(20), &mut keeper);
    // The first periodic save writes the file; the 18 after it find it current.
    assert_eq!(keeper.saves, 1);
    keeper.finish().unwrap();
    assert!(path.is_file());
    drop(keeper);
    std::fs::remove_dir_all(&dir).unwrap();
}
