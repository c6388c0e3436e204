//! Real-time runs: the real-time mode (`--realtime`: memory locked, the
//! scan thread at SCHED_FIFO, pinned CPUs) as the kernel sees it in
//! /proc, its refusals with their reasons, `--stats` with the scan-start
//! jitter, and a fault that ends a real-time run nobody could restart.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_automat")
}

fn scratch(name: &str, program: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("automat-rt-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    std::fs::write(dir.join("main.st"), program).expect("main.st");
    dir
}

const BLINK: &str = "PROGRAM Main
VAR t : TON; lamp : BOOL; END_VAR
    t(IN := NOT t.Q, PT := T#100ms);
    IF t.Q THEN lamp := NOT lamp; END_IF;
END_PROGRAM
";

const LONG: &str = "PROGRAM Main
VAR x : DINT; i : DINT; END_VAR
    FOR i := 0 TO 2000000000 DO x := x + 1; END_FOR;
END_PROGRAM
";

fn spawn(dir: &Path, args: &[&str]) -> Child {
    Command::new(bin())
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start automat")
}

/// Waits for the child at most `limit`, killing it if it is still running.
fn finish(mut child: Child, limit: Duration) -> (Option<i32>, String, Duration) {
    let start = Instant::now();
    loop {
        if let Ok(Some(status)) = child.try_wait() {
            let mut err = String::new();
            if let Some(mut e) = child.stderr.take() {
                let _ = e.read_to_string(&mut err);
            }
            return (status.code(), err, start.elapsed());
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!("automat still ran after {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn sigterm(child: &Child) {
    let _ = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status();
}

fn run(dir: &Path, args: &[&str]) -> Output {
    Command::new(bin())
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .output()
        .expect("run automat")
}

/// `(thread name, policy, real-time priority)` of every thread of `pid`.
fn threads(pid: u32) -> Vec<(String, u32, u32)> {
    let mut out = Vec::new();
    let Ok(tasks) = std::fs::read_dir(format!("/proc/{pid}/task")) else {
        return out;
    };
    for t in tasks.flatten() {
        let comm = std::fs::read_to_string(t.path().join("comm")).unwrap_or_default();
        let stat = std::fs::read_to_string(t.path().join("stat")).unwrap_or_default();
        // Fields after the `(comm)`: state is field 3; rt_priority 40, policy 41.
        let after = stat.rsplit_once(')').map_or("", |(_, r)| r);
        let f: Vec<&str> = after.split_whitespace().collect();
        let num = |i: usize| f.get(i - 3).and_then(|v| v.parse().ok()).unwrap_or(0);
        out.push((comm.trim().to_string(), num(41), num(40)));
    }
    out
}

#[test]
fn a_fault_ends_a_real_time_run_that_nobody_could_restart() {
    let dir = scratch("fault", LONG);
    let child = spawn(&dir, &["run", "main.st", "--watchdog", "100ms"]);
    let (code, err, took) = finish(child, Duration::from_secs(20));
    assert_eq!(code, Some(3), "{err}");
    assert!(
        err.contains("watchdog: task Main ran longer than its watchdog T#100ms"),
        "{err}"
    );
    assert!(took < Duration::from_secs(10), "{took:?}");
}

#[test]
fn stats_of_a_real_time_run_show_the_scan_start_jitter() {
    let dir = scratch("stats", BLINK);
    let child = spawn(&dir, &["run", "main.st", "--stats"]);
    std::thread::sleep(Duration::from_millis(400));
    sigterm(&child);
    let (code, err, _) = finish(child, Duration::from_secs(20));
    assert_eq!(code, Some(0), "{err}");
    let line = err
        .lines()
        .find(|l| l.starts_with("scans: "))
        .unwrap_or_else(|| panic!("no statistics: {err}"));
    assert!(
        line.contains("overruns: 0") || line.contains("overruns: "),
        "{line}"
    );
    assert!(err.contains("\nscan start jitter: p50 "), "{err}");
    assert!(err.contains(", p99 ") && err.contains(", max "), "{err}");
    assert!(err.contains("; histogram: "), "{err}");
}

#[test]
fn the_real_time_mode_as_the_kernel_sees_it() {
    let dir = scratch("fifo", BLINK);
    let child = spawn(
        &dir,
        &[
            "run",
            "main.st",
            "--realtime",
            "--rt-priority",
            "70",
            "--cpus",
            "0",
            "--stats",
        ],
    );
    std::thread::sleep(Duration::from_millis(500));
    let seen = threads(child.id());
    let status =
        std::fs::read_to_string(format!("/proc/{}/status", child.id())).unwrap_or_default();
    let allowed: Vec<String> = std::fs::read_dir(format!("/proc/{}/task", child.id()))
        .map(|d| {
            d.flatten()
                .filter_map(|t| std::fs::read_to_string(t.path().join("status")).ok())
                .filter(|s| s.contains("automat-scan"))
                .filter_map(|s| {
                    s.lines()
                        .find(|l| l.starts_with("Cpus_allowed_list:"))
                        .map(|l| l.split_whitespace().last().unwrap_or_default().to_string())
                })
                .collect()
        })
        .unwrap_or_default();
    sigterm(&child);
    let (code, err, _) = finish(child, Duration::from_secs(20));
    if code == Some(2) {
        // A machine that does not grant real-time scheduling: the refusal
        // must say why and how to grant it.
        assert!(
            err.contains("real-time mode: cannot")
                && (err.contains("CAP_") || err.contains("ulimit")),
            "{err}"
        );
        return;
    }
    assert_eq!(code, Some(0), "{err}");
    assert!(
        err.contains("note: real-time mode: SCHED_FIFO priority 70, memory locked, on CPU 0"),
        "{err}"
    );
    // SCHED_FIFO is policy 1: the scan thread at 70, its watchdog's timer
    // one above (it must preempt a looping scan on the same CPU); the
    // other threads keep the normal policy.
    assert!(seen.contains(&("automat-scan".into(), 1, 70)), "{seen:?}");
    assert!(
        seen.contains(&("automat-watchdo".into(), 1, 71)),
        "{seen:?}"
    );
    assert!(
        seen.iter().any(|(n, p, _)| n == "automat" && *p == 0),
        "{seen:?}"
    );
    assert_eq!(allowed, ["0"], "{seen:?}");
    let locked: u64 = status
        .lines()
        .find(|l| l.starts_with("VmLck:"))
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|v| v.parse().ok())
        .unwrap_or(0);
    assert!(locked > 0, "{status}");
    assert!(err.contains("scan start jitter: p50 "), "{err}");
}

#[test]
fn a_looping_scan_in_real_time_mode_is_still_stopped_by_its_watchdog() {
    let dir = scratch("fifo-dog", LONG);
    let child = spawn(
        &dir,
        &[
            "run",
            "main.st",
            "--realtime",
            "--cpus",
            "0",
            "--watchdog",
            "100ms",
        ],
    );
    let (code, err, took) = finish(child, Duration::from_secs(20));
    if code == Some(2) && err.contains("real-time mode: cannot") {
        return; // not granted here: the test above checks the message
    }
    assert_eq!(code, Some(3), "{err}");
    assert!(
        err.contains("ran longer than its watchdog T#100ms"),
        "{err}"
    );
    assert!(took < Duration::from_secs(10), "{took:?}");
}

#[test]
fn without_the_right_the_error_says_why() {
    // Only where this test can drop root: as `nobody`, locking memory
    // beyond the small default limit is refused.
    let root = std::fs::read_to_string("/proc/self/status")
        .unwrap_or_default()
        .lines()
        .any(|l| l.starts_with("Uid:") && l.split_whitespace().nth(1) == Some("0"));
    let setpriv = Path::new("/usr/bin/setpriv").exists();
    if !(root && setpriv) {
        eprintln!("not root or no setpriv: the refusal is checked by the_real_time_mode_as_the_kernel_sees_it");
        return;
    }
    let dir = scratch("nobody", BLINK);
    let _ = Command::new("chmod")
        .args(["-R", "a+rwX"])
        .arg(&dir)
        .status();
    let out = Command::new("/usr/bin/setpriv")
        .args([
            "--reuid=65534",
            "--regid=65534",
            "--clear-groups",
            "--inh-caps=-all",
            bin(),
            "run",
            "main.st",
            "--realtime",
        ])
        .current_dir(&dir)
        .stdin(Stdio::null())
        .output()
        .expect("setpriv");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("error: real-time mode: cannot lock the process's memory (mlockall: ")
            || err.contains(
                "error: real-time mode: cannot run the scan thread at SCHED_FIFO priority 80"
            ),
        "{err}"
    );
    assert!(err.contains("CAP_"), "{err}");
}

#[test]
fn real_time_options_that_do_not_apply_are_refused() {
    let dir = scratch("refused", BLINK);
    for (args, says) in [
        (
            vec!["--realtime", "--duration", "1s"],
            "--realtime applies to real-time runs; this one is on the virtual clock",
        ),
        (
            vec!["--rt-priority", "50"],
            "--rt-priority and --cpus apply with --realtime",
        ),
        (
            vec!["--realtime", "--rt-priority", "0"],
            "real-time priority 0 is out of range: SCHED_FIFO priorities are 1 to 99",
        ),
        (
            vec!["--realtime", "--cpus", "x"],
            "--cpus: `x` is not a CPU number or range",
        ),
    ] {
        let mut all = vec!["run", "main.st"];
        all.extend(args.iter());
        let out = run(&dir, &all);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
    }
}

#[test]
fn the_runtime_table_of_a_project_is_checked() {
    let dir = scratch("project", BLINK);
    std::fs::write(
        dir.join("automat.toml"),
        "[project]\nname = \"rt\"\n\n[runtime]\nrealtime = true\npriority = 120\ncpus = \"1-\"\n",
    )
    .expect("automat.toml");
    let out = run(&dir, &["check", "."]);
    let text =
        String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{text}");
    assert!(
        text.contains("./automat.toml:6:12: error[E300]: priority: 120 is out of range: SCHED_FIFO priorities are 1 to 99"),
        "{text}"
    );
    assert!(
        text.contains("./automat.toml:7:8: error[E300]: cpus: `1-` is not a CPU number or range"),
        "{text}"
    );
    // Valid, on the virtual clock: the project's real-time mode is for its
    // real-time runs; a scenario or --duration run ignores it.
    let crane = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/crane");
    for f in ["crane.st", "config.st"] {
        std::fs::copy(crane.join(f), dir.join(f)).expect("copy the crane");
    }
    let _ = std::fs::remove_file(dir.join("main.st"));
    let toml = std::fs::read_to_string(crane.join("automat.toml")).expect("crane toml");
    std::fs::write(
        dir.join("automat.toml"),
        format!("{toml}\n[runtime]\nrealtime = true\npriority = 60\n"),
    )
    .expect("automat.toml");
    let out = run(
        &dir,
        &["run", ".", "--duration", "1s", "--print", "Ctrl.GS1.x"],
    );
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(String::from_utf8_lossy(&out.stdout), "Ctrl.GS1.x = TRUE\n");
}
