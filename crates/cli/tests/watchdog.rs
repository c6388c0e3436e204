//! The watchdog in time and the stop of a long scan, through the real
//! binary: `--watchdog`, `[tasks.NAME]` in automat.toml,
//! `--max-instructions`, and SIGTERM/SIGINT sent to a process whose scan
//! never ends (issue 15 point 1, issue 18 point 9). Every time bound is
//! generous: the machine may be loaded.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "automat-watchdog-test-{}-{name}",
        std::process::id()
    ));
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).expect("write");
    p.display().to_string()
}

fn automat(args: &[&str]) -> (i32, String, String) {
    let out: Output = Command::new(env!("CARGO_BIN_EXE_automat"))
        .args(args)
        .output()
        .expect("run automat");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Scan 1 counts; from scan 2 on, the loop on line 6 never ends.
const ENDLESS: &str = "PROGRAM Main
VAR
    n : DINT;
    scans : INT;
END_VAR
IF scans > 0 THEN WHILE TRUE DO n := n + 1; END_WHILE; END_IF;
scans := scans + 1;
END_PROGRAM
";

#[test]
fn watchdog_option_stops_an_endless_scan_on_both_engines() {
    let d = dir("option");
    let f = write(&d, "endless.st", ENDLESS);
    for engine in ["jit", "interp"] {
        let t = Instant::now();
        let (code, out, err) = automat(&[
            "run",
            &f,
            "--cycles",
            "3",
            "--watchdog",
            "200ms",
            "--engine",
            engine,
            "--print",
            "scans",
        ]);
        assert!(t.elapsed() >= Duration::from_millis(200));
        assert_eq!(code, 3, "{engine}: {err}");
        assert!(
            // The site is the loop's line (the poll may come in its condition or its body).
            err.contains("endless.st:6:")
                && err.contains(
                    ": fault in Main: watchdog: task Main ran longer than its watchdog T#200ms \
                     (task Main, program instance Main, PLC time T#10ms)"
                ),
            "{engine}: {err}"
        );
        assert!(err.contains("note: the PLC stopped"), "{err}");
        // The image as the fault left it: the first scan had completed.
        assert_eq!(out, "scans = 1\n", "{engine}");
    }
}

#[test]
fn max_instructions_faults_at_an_exact_instruction() {
    let d = dir("budget");
    let f = write(&d, "endless.st", ENDLESS);
    let mut outs = Vec::new();
    for engine in ["jit", "interp"] {
        let (code, out, err) = automat(&[
            "run",
            &f,
            "--cycles",
            "3",
            "--max-instructions",
            "10000",
            "--engine",
            engine,
            "--print",
            "n",
        ]);
        assert_eq!(code, 3, "{err}");
        assert!(
            err.contains("watchdog: more than 10000 instructions in one run"),
            "{err}"
        );
        assert!(err.contains("endless.st:6:"), "{err}");
        outs.push(out);
    }
    // Deterministic: both engines stop at the same instruction.
    assert_eq!(outs[0], outs[1]);
}

#[test]
fn bad_watchdog_arguments_exit_2() {
    let d = dir("args");
    let f = write(&d, "endless.st", ENDLESS);
    for bad in ["0ms", "soon", "-5ms"] {
        let arg = format!("--watchdog={bad}");
        let (code, _, err) = automat(&["run", &f, "--cycles", "1", &arg]);
        assert_eq!(code, 2, "{bad}: {err}");
        assert!(err.contains("--watchdog"), "{err}");
    }
    let (code, _, err) = automat(&["run", &f, "--cycles", "1", "--max-instructions", "0"]);
    assert_eq!(code, 2, "{err}");
    // `off` is accepted (the first scan ends; the second would not, so 1 cycle).
    let (code, out, err) = automat(&[
        "run",
        &f,
        "--cycles",
        "1",
        "--watchdog",
        "off",
        "--print",
        "scans",
    ]);
    assert_eq!((code, out.as_str()), (0, "scans = 1\n"), "{err}");
}

const CRANE_TOML: &str = "[project]
name = \"watchdog\"

[plant]
model = \"crane\"
";

/// A crane controller whose scans become endless at 200 ms.
const CRANE_ST: &str = "PROGRAM Ctrl
VAR
    Pornire, l1, l2, l3, l4 : BOOL;
    M1S, M1D, M2S, M2J : BOOL;
    t : TON;
    n : DINT;
END_VAR
M2S := TRUE;
t(IN := TRUE, PT := T#200ms);
IF t.Q THEN WHILE TRUE DO n := n + 1; END_WHILE; END_IF;
END_PROGRAM
";

#[test]
fn project_tasks_table_sets_the_watchdog_and_sensitivity() {
    let d = dir("project");
    write(
        &d,
        "automat.toml",
        &format!("{CRANE_TOML}\n[tasks.ctrl]\nwatchdog = \"100ms\"\nsensitivity = 2\n"),
    );
    write(&d, "ctrl.st", CRANE_ST);
    let (code, _, err) = automat(&["run", &d.display().to_string(), "--duration", "1s"]);
    assert_eq!(code, 3, "{err}");
    assert!(
        err.contains(
            "ctrl.st:10:13: fault in Ctrl: watchdog: task Ctrl ran longer than T#200ms (its \
             watchdog T#100ms × sensitivity 2) (task Ctrl, program instance Ctrl, PLC time T#200ms)"
        ),
        "{err}"
    );
    // The command line does not override the project's own setting.
    let (code, _, err) = automat(&[
        "run",
        &d.display().to_string(),
        "--duration",
        "1s",
        "--watchdog",
        "off",
    ]);
    assert_eq!(code, 3, "{err}");
    assert!(err.contains("× sensitivity 2"), "{err}");
}

#[test]
fn project_tasks_table_errors_point_into_the_file() {
    let d = dir("project-errors");
    write(&d, "ctrl.st", CRANE_ST);
    for (table, want) in [
        (
            "[tasks.Fast]\nwatchdog = \"100ms\"\n",
            "automat.toml:7:8: error[E300]: [tasks.Fast]: the program has no task `Fast`",
        ),
        (
            "[tasks.Ctrl]\nwatchdog = \"never\"\n",
            "automat.toml:8:12: error[E300]: [tasks.Ctrl] watchdog:",
        ),
        (
            "[tasks.Ctrl]\nsensitivity = 3\n",
            "automat.toml:8:15: error[E300]: [tasks.Ctrl] sensitivity needs a watchdog time",
        ),
        (
            "[tasks.Ctrl]\nwatchdog = \"1s\"\nsensitivity = 0\n",
            "automat.toml:9:15: error[E300]: [tasks.Ctrl] sensitivity must be a whole number",
        ),
        (
            "[tasks.Ctrl]\nwatchdog = \"1s\"\ntimeout = 3\n",
            "error[E300]: invalid project file: unknown field `timeout`",
        ),
    ] {
        write(&d, "automat.toml", &format!("{CRANE_TOML}\n{table}"));
        let (code, _, err) = automat(&["run", &d.display().to_string(), "--cycles", "1"]);
        assert_eq!(code, 1, "{table}: {err}");
        assert!(err.contains(want), "{table}\nwant {want}\ngot {err}");
    }
}

/// Starts a real-time run of the endless program, waits until it is in
/// its endless scan, sends `signal`; returns (exit code, stderr, the time
/// from the signal to the exit).
fn signalled(engine: &str, signal: &str) -> (i32, String, Duration) {
    let d = dir(&format!("signal-{engine}-{signal}"));
    let f = write(&d, "endless.st", ENDLESS);
    let child = Command::new(env!("CARGO_BIN_EXE_automat"))
        .args(["run", &f, "--engine", engine, "--print", "scans"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start automat");
    // Compile and first scan: well under a second even when loaded.
    std::thread::sleep(Duration::from_millis(1500));
    let sent = Instant::now();
    let killed = Command::new("kill")
        .args([&format!("-{signal}"), &child.id().to_string()])
        .status()
        .expect("kill");
    assert!(killed.success());
    let out = child.wait_with_output().expect("wait");
    let took = sent.elapsed();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        took,
    )
}

#[test]
fn sigterm_and_sigint_stop_an_endless_scan_within_a_second() {
    let runs: Vec<_> = [("jit", "TERM"), ("interp", "INT")]
        .into_iter()
        .map(|(e, s)| std::thread::spawn(move || (e, s, signalled(e, s))))
        .collect();
    for r in runs {
        let (engine, signal, (code, err, took)) = r.join().expect("thread");
        assert_eq!(code, 3, "{engine} SIG{signal}: {err}");
        assert!(
            err.contains("endless.st:6:")
                && err.contains(
                    ": fault in Main: stopped: the scan was still running T#1s after the stop \
                     request (task Main, program instance Main, PLC time T#10ms)"
                ),
            "{engine} SIG{signal}: {err}"
        );
        // About a second; the bound leaves room for a loaded machine.
        assert!(took >= Duration::from_millis(900), "{took:?}");
        assert!(
            took < Duration::from_secs(4),
            "{engine} SIG{signal}: {took:?}"
        );
    }
}

#[test]
fn sigterm_stops_a_normal_run_at_the_end_of_the_scan() {
    let d = dir("sigterm-normal");
    let f = write(
        &d,
        "count.st",
        "PROGRAM Main VAR n : INT; END_VAR n := n + 1; END_PROGRAM\n",
    );
    let child = Command::new(env!("CARGO_BIN_EXE_automat"))
        .args(["run", &f, "--cycle-time", "20ms", "--print", "n"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start automat");
    std::thread::sleep(Duration::from_millis(600));
    let killed = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .expect("kill");
    assert!(killed.success());
    let out = child.wait_with_output().expect("wait");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(String::from_utf8_lossy(&out.stdout).starts_with("n = "));
}
