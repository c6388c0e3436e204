//! The watchdog thread alone, then in the scan loop with fake backends
//! whose runs spin until interrupted or sleep a set wall time. Times are
//! lower bounds or generous upper bounds (a loaded 2-core machine).

use super::*;
use crate::io::NoIo;
use crate::scan::{run, Env, Limit, RunConfig, RunEnd};
use crate::testutil::{inst, program, task, Fake, COUNT, SLEEP, SPIN};
use crate::ClockMode;
use automat_ir::{FaultKind, TaskWatchdog};
use std::time::Instant;

const MS: i64 = 1_000_000;

/// Runs `f` with a watchdog thread serving `dog` and the stop flag `stop`.
fn with_thread<R>(dog: &mut Watchdog, stop: &AtomicBool, f: impl FnOnce(&mut Watchdog) -> R) -> R {
    std::thread::scope(|s| {
        s.spawn(dog.watcher(stop));
        let r = f(dog);
        dog.quit();
        r
    })
}

/// Waits (at most 20 s) for the flag; returns the wall time it took.
fn wait_raised(flag: &Interrupt) -> Duration {
    let t = Instant::now();
    while !flag.is_raised() && t.elapsed() < Duration::from_secs(20) {
        std::thread::sleep(Duration::from_millis(1));
    }
    t.elapsed()
}

#[test]
fn an_armed_run_past_its_deadline_is_interrupted() {
    let flag = Interrupt::new();
    let mut dog = Watchdog::new(flag.clone());
    let stop = AtomicBool::new(false);
    let (waited, (ns, cause)) = with_thread(&mut dog, &stop, |d| {
        d.arm(Some(50 * MS));
        let waited = wait_raised(&flag);
        (waited, d.disarm())
    });
    assert!(flag.is_raised());
    assert_eq!(cause, Some(Cause::Time));
    assert!(waited >= Duration::from_millis(50), "{waited:?}");
    assert!(ns >= 50 * MS);
}

#[test]
fn short_runs_are_never_interrupted_and_the_next_arm_clears_the_flag() {
    let flag = Interrupt::new();
    let mut dog = Watchdog::new(flag.clone());
    let stop = AtomicBool::new(false);
    with_thread(&mut dog, &stop, |d| {
        for _ in 0..2000 {
            d.arm(Some(5_000 * MS));
            assert!(!flag.is_raised());
            assert_eq!(d.disarm().1, None);
        }
        flag.raise();
        d.arm(Some(5_000 * MS));
        assert!(!flag.is_raised());
        d.disarm();
    });
}

#[test]
fn a_stop_request_interrupts_a_long_run_within_a_second() {
    let flag = Interrupt::new();
    let mut dog = Watchdog::new(flag.clone());
    let stop = AtomicBool::new(false);
    let (waited, cause) = with_thread(&mut dog, &stop, |d| {
        d.arm(None);
        std::thread::sleep(Duration::from_millis(20));
        stop.store(true, Ordering::Relaxed);
        let waited = wait_raised(&flag);
        (waited, d.disarm().1)
    });
    assert_eq!(cause, Some(Cause::Stop));
    assert!(waited >= Duration::from_nanos(STOP_GRACE_NS), "{waited:?}");
    // Within a second of the request, plus slack for a loaded machine.
    assert!(waited < Duration::from_secs(3), "{waited:?}");
}

fn run_virtual(f: &mut Fake, limit: Limit, stop: &AtomicBool) -> crate::RunReport {
    let mut clock = crate::SystemClock::new();
    let mut env = Env {
        clock: &mut clock,
        inputs: &mut NoIo,
        outputs: &mut NoIo,
        observer: &mut (),
        stop,
    };
    let cfg = RunConfig {
        cycle_time_ns: 10 * MS,
        clock: ClockMode::Virtual,
        limit,
    };
    run(f, &cfg, &mut env).unwrap()
}

fn fake(func: u32, watchdog: TaskWatchdog) -> Fake {
    let mut t = task("Fast", None, 0, vec![inst("MAIN", func, 0)]);
    t.watchdog = watchdog;
    let mut p = program(vec![t]);
    // Something in %Q, to see the safe state.
    p.initial_image[44] = 0xFF;
    Fake::new(p)
}

#[test]
fn an_endless_scan_faults_at_the_task_watchdog_with_its_site() {
    let mut f = fake(
        SPIN,
        TaskWatchdog::Limit {
            time_ns: 100 * MS,
            sensitivity: 1,
        },
    );
    let t = Instant::now();
    let r = run_virtual(&mut f, Limit::Cycles(3), &AtomicBool::new(false));
    assert!(t.elapsed() >= Duration::from_millis(100));
    let RunEnd::Fault(report) = r.end else {
        panic!("{:?}", r.end)
    };
    assert_eq!(report.fault.kind, FaultKind::Watchdog);
    assert_eq!(
        report.to_string(),
        "main.st:7:5: fault in MAIN: watchdog: task Fast ran longer than its watchdog T#100ms \
         (task Fast, program instance MAIN, PLC time T#0s)"
    );
    assert_eq!(f.image[44], 0, "the safe state");
}

#[test]
fn sensitivity_times_the_watchdog_bounds_one_run() {
    let mut f = fake(
        SPIN,
        TaskWatchdog::Limit {
            time_ns: 20 * MS,
            sensitivity: 3,
        },
    );
    let t = Instant::now();
    let r = run_virtual(&mut f, Limit::Cycles(3), &AtomicBool::new(false));
    assert!(t.elapsed() >= Duration::from_millis(60));
    let RunEnd::Fault(report) = r.end else {
        panic!("{:?}", r.end)
    };
    assert_eq!(
        report.fault.message,
        "watchdog: task Fast ran longer than T#60ms (its watchdog T#20ms × sensitivity 3)"
    );
}

#[test]
fn sensitivity_consecutive_overruns_fault_after_the_last() {
    // Each run sleeps 15 ms: an overrun of 10 ms, within 3 × 10 ms.
    let mut f = fake(
        SLEEP + 15,
        TaskWatchdog::Limit {
            time_ns: 10 * MS,
            sensitivity: 3,
        },
    );
    let r = run_virtual(&mut f, Limit::Cycles(10), &AtomicBool::new(false));
    let RunEnd::Fault(report) = r.end else {
        panic!("{:?}", r.end)
    };
    assert_eq!(f.log.len(), 3, "faulted after the third run");
    assert_eq!(report.plc_time_ns, 20 * MS);
    assert!(
        report.fault.message.starts_with(
            "watchdog: task Fast overran its watchdog T#10ms in 3 consecutive runs (the last took T#"
        ),
        "{}",
        report.fault.message
    );
    assert_eq!(report.fault.site.location, "(end of the run)");
}

#[test]
fn runs_within_the_watchdog_and_watchdog_off_run_normally() {
    for w in [
        TaskWatchdog::Off,
        TaskWatchdog::Default,
        TaskWatchdog::Limit {
            time_ns: 2_000 * MS,
            sensitivity: 1,
        },
    ] {
        let mut f = fake(COUNT, w);
        let r = run_virtual(&mut f, Limit::Cycles(50), &AtomicBool::new(false));
        assert_eq!(r.end, RunEnd::Limit, "{w:?}");
        assert_eq!(f.log.len(), 50);
    }
}

#[test]
fn a_stop_during_an_endless_scan_ends_it_as_a_fault_within_a_second() {
    let mut f = fake(SPIN, TaskWatchdog::Off);
    let stop = AtomicBool::new(false);
    let t = Instant::now();
    let r = std::thread::scope(|s| {
        s.spawn(|| {
            std::thread::sleep(Duration::from_millis(100));
            stop.store(true, Ordering::Relaxed);
        });
        run_virtual(&mut f, Limit::Unbounded, &stop)
    });
    let took = t.elapsed();
    assert!(took >= Duration::from_millis(100 + STOP_GRACE_NS / 1_000_000));
    assert!(took < Duration::from_secs(5), "{took:?}");
    let RunEnd::Fault(report) = r.end else {
        panic!("{:?}", r.end)
    };
    assert_eq!(
        report.fault.message,
        "stopped: the scan was still running T#1s after the stop request"
    );
    assert_eq!(report.fault.site.location, "main.st:7:5");
    assert_eq!(f.image[44], 0, "the safe state");
}

#[test]
fn watchdog_arguments() {
    assert_eq!(parse_watchdog("off"), Ok(TaskWatchdog::Off));
    assert_eq!(parse_watchdog("OFF"), Ok(TaskWatchdog::Off));
    assert_eq!(
        parse_watchdog("100ms"),
        Ok(TaskWatchdog::Limit {
            time_ns: 100 * MS,
            sensitivity: 1
        })
    );
    assert_eq!(
        parse_watchdog("T#1s500ms"),
        Ok(TaskWatchdog::Limit {
            time_ns: 1_500 * MS,
            sensitivity: 1
        })
    );
    assert_eq!(
        parse_watchdog("0ms"),
        Err("a watchdog must be longer than 0 (or `off`)".into())
    );
    assert!(parse_watchdog("soon").unwrap_err().ends_with(", or `off`"));
}
