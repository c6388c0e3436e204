//! `automat run`: the command-line contract of issue 3 point 6 on small ST
//! programs (cycles, duration, printed forms, traces, retain, exit codes).

use std::path::PathBuf;
use std::process::{Command, Output};

fn automat(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_automat"))
        .args(args)
        .output()
        .expect("run automat")
}

fn dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("automat-run-test-{}", std::process::id()));
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn temp_file(name: &str, text: &str) -> String {
    let path = dir().join(name);
    std::fs::write(&path, text).expect("write temp file");
    path.display().to_string()
}

/// Runs `automat run FILE ARGS...`; returns (exit code, stdout, stderr).
fn run(file: &str, args: &[&str]) -> (i32, String, String) {
    let mut all = vec!["run", file];
    all.extend_from_slice(args);
    let out = automat(&all);
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

const COUNTER: &str = "PROGRAM main
VAR
    n : INT;
    t : TIME;
END_VAR
    n := n + 1;
    t := t + T#10ms;
END_PROGRAM
";

#[test]
fn cycles_and_duration() {
    let f = temp_file("counter.st", COUNTER);
    let (code, out, err) = run(&f, &["--cycles", "5", "--print", "n", "--print", "main.t"]);
    assert_eq!(
        (code, out.as_str()),
        (0, "n = 5\nmain.t = T#50ms\n"),
        "{err}"
    );
    let (code, out, _) = run(&f, &["--duration", "100ms", "--print", "n"]);
    assert_eq!((code, out.as_str()), (0, "n = 10\n"));
    let (code, out, _) = run(
        &f,
        &[
            "--duration",
            "T#100ms",
            "--cycle-time",
            "T#20ms",
            "--print",
            "N",
        ],
    );
    assert_eq!((code, out.as_str()), (0, "N = 5\n"));
    let (code, out, _) = run(&f, &["--duration", "101ms", "--print", "n"]);
    assert_eq!((code, out.as_str()), (0, "n = 11\n"));
    let (code, out, _) = run(&f, &["--cycles", "0", "--print", "n"]);
    assert_eq!((code, out.as_str()), (0, "n = 0\n"));
}

const FORMATS: &str = "TYPE Point : STRUCT x : INT; y : REAL; END_STRUCT; END_TYPE
VAR_GLOBAL
    g : DINT := -7;
END_VAR
PROGRAM main
VAR
    b : BOOL;
    r : REAL;
    l : LREAL;
    d : TIME;
    s : STRING;
    w : WORD;
    a : ARRAY[1..2, 0..1] OF Point;
    o AT %QX0.1 : BOOL;
END_VAR
    b := TRUE;
    r := 3.5;
    l := 4.0;
    d := T#1s500ms;
    s := 'abc';
    w := 16#FFFF;
    a[2, 1].x := 42;
    a[2, 1].y := 0.1;
    o := TRUE;
END_PROGRAM
";

#[test]
fn printed_forms() {
    let f = temp_file("formats.st", FORMATS);
    let vars = [
        "b",
        "r",
        "l",
        "d",
        "s",
        "w",
        "a[2, 1].x",
        "a[2,1].y",
        "a[1, 0].x",
        "g",
        "%QX0.1",
        "o",
    ];
    let mut args = vec!["--cycles", "1"];
    for v in &vars {
        args.push("--print");
        args.push(v);
    }
    let (code, out, err) = run(&f, &args);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        out,
        "b = TRUE\nr = 3.5\nl = 4.0\nd = T#1s500ms\ns = 'abc'\nw = 65535\n\
         a[2, 1].x = 42\na[2,1].y = 0.1\na[1, 0].x = 0\ng = -7\n%QX0.1 = TRUE\no = TRUE\n"
    );
}

#[test]
fn bad_command_lines_exit_2() {
    let f = temp_file("counter2.st", COUNTER);
    let (code, out, err) = run(&f, &["--cycles", "1", "--print", "nope"]);
    assert_eq!(code, 2);
    assert!(out.is_empty());
    assert_eq!(
        err,
        "error: --print nope: unknown variable `nope`: no program variable or global named `NOPE`\n"
    );
    let (code, _, err) = run(&f, &["--cycles", "1", "--print", "n[1]"]);
    assert_eq!(
        (code, err.as_str()),
        (2, "error: --print n[1]: `N` is INT, not an array\n")
    );
    let (code, _, err) = run(&f, &["--cycle-time", "10", "--cycles", "1"]);
    assert_eq!(code, 2);
    assert!(err.contains("`10` is not a valid TIME literal"), "{err}");
    let (code, _, err) = run(&f, &["--cycle-time", "0ms", "--cycles", "1"]);
    assert_eq!(
        (code, err.as_str()),
        (2, "error: --cycle-time must be longer than 0\n")
    );
    let (code, _, _) = run(&f, &["--cycles", "1", "--duration", "1s"]);
    assert_eq!(code, 2);
    let (code, _, _) = run(&f, &["--trace", "n"]);
    assert_eq!(code, 2);
    let (code, _, err) = run(&f, &["--cycles", "1", "--program", "other"]);
    assert_eq!(code, 2);
    assert!(err.contains("no PROGRAM named other"), "{err}");
    let (code, _, _) = run("/nonexistent/x.st", &["--cycles", "1"]);
    assert_eq!(code, 2);
}

#[test]
fn compile_errors_exit_1_with_diagnostics() {
    let f = temp_file(
        "broken.st",
        "PROGRAM main\nVAR i : INT; END_VAR\n    i := undefined;\nEND_PROGRAM\n",
    );
    let (code, out, err) = run(&f, &["--cycles", "1", "--print", "i"]);
    assert_eq!(code, 1);
    assert!(out.is_empty());
    assert!(err.contains("broken.st:3:10: error[E020]"), "{err}");
}

#[test]
fn runtime_fault_exits_3_in_the_safe_state() {
    let src = "PROGRAM main
VAR
    n : INT;
    q AT %QX0.0 : BOOL;
    z : INT;
END_VAR
VAR_OUTPUT
    y : INT;
    on : BOOL;
END_VAR
    q := TRUE;
    y := 7;
    on := TRUE;
    n := n + 1;
    IF n = 3 THEN
        z := n / (n - 3);
    END_IF;
END_PROGRAM
";
    let f = temp_file("fault.st", src);
    let (code, out, err) = run(
        &f,
        &[
            "--cycles", "10", "--print", "n", "--print", "%QX0.0", "--print", "y", "--print", "on",
        ],
    );
    assert_eq!(code, 3, "{err}");
    assert_eq!(out, "n = 3\n%QX0.0 = FALSE\ny = 0\non = FALSE\n");
    assert!(err.starts_with("error: runtime fault: "), "{err}");
    assert!(
        err.contains("fault.st:16:14: fault in main: division by zero"),
        "{err}"
    );
    assert!(
        err.contains("(task main, program instance main, PLC time T#20ms)\n"),
        "{err}"
    );
    assert!(
        err.ends_with(
            "note: the PLC stopped in its safe state: the %Q area (1 byte) and 2 outputs \
             (main.on, main.y) set to 0/FALSE\n"
        ),
        "{err}"
    );
}

#[test]
fn trace_writes_one_row_per_cycle() {
    let f = temp_file("trace.st", COUNTER);
    let csv = dir().join("trace.csv");
    let csv_s = csv.display().to_string();
    let (code, _, err) = run(
        &f,
        &["--cycles", "3", "--trace", "n,t", "--trace-file", &csv_s],
    );
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&csv).expect("trace file");
    assert_eq!(
        text,
        "time,n,t\nT#0s,1,T#10ms\nT#10ms,2,T#20ms\nT#20ms,3,T#30ms\n"
    );
}

const RETAINED: &str = "PROGRAM main
VAR RETAIN
    r : INT;
END_VAR
VAR
    n : INT;
END_VAR
    r := r + 1;
    n := n + 1;
END_PROGRAM
";

#[test]
fn retain_survives_a_warm_start_and_cold_resets_it() {
    let f = temp_file("retain.st", RETAINED);
    let file = dir().join("plc.retain");
    let _ = std::fs::remove_file(&file);
    let file_s = file.display().to_string();
    let args = [
        "--cycles", "3", "--retain", &file_s, "--print", "r", "--print", "n",
    ];
    let (code, out, err) = run(&f, &args);
    assert_eq!(
        (code, out.as_str(), err.as_str()),
        (0, "r = 3\nn = 3\n", "")
    );
    let (_, out, _) = run(&f, &args);
    assert_eq!(out, "r = 6\nn = 3\n");
    let mut cold = args.to_vec();
    cold.push("--cold");
    let (_, out, _) = run(&f, &cold);
    assert_eq!(out, "r = 3\nn = 3\n");
    let (_, out, _) = run(&f, &args);
    assert_eq!(out, "r = 6\nn = 3\n");
    // A damaged file: warning and cold start, never a crash.
    std::fs::write(&file, b"AUTOMATR\x01\x00").expect("write");
    let (code, out, err) = run(&f, &args);
    assert_eq!((code, out.as_str()), (0, "r = 3\nn = 3\n"));
    assert_eq!(
        err,
        format!(
            "warning: {file_s}: the file is truncated; the file was moved to {file_s}.bad; cold start\n"
        )
    );
    assert_eq!(
        std::fs::read(format!("{file_s}.bad")).expect("moved aside"),
        b"AUTOMATR\x01\x00"
    );
    // A changed program: warning and cold start.
    let changed = temp_file(
        "retain.st",
        &RETAINED.replace("r : INT;", "r : INT;\n    r2 : DINT;"),
    );
    let (code, out, err) = run(&changed, &args);
    assert_eq!((code, out.as_str()), (0, "r = 3\nn = 3\n"));
    assert!(err.contains("RETAIN variables changed"), "{err}");
}

#[test]
fn configuration_tasks_run_by_interval_and_priority() {
    let src = "VAR_GLOBAL
    log : DINT;
    fast_runs : INT;
    slow_runs : INT;
END_VAR
PROGRAM fastp
VAR_EXTERNAL
    log : DINT;
    fast_runs : INT;
END_VAR
    fast_runs := fast_runs + 1;
    log := log * 10 + 1;
END_PROGRAM
PROGRAM slowp
VAR_EXTERNAL
    log : DINT;
    slow_runs : INT;
END_VAR
    slow_runs := slow_runs + 1;
    log := log * 10 + 2;
END_PROGRAM
CONFIGURATION cell
    RESOURCE res ON PLC
        TASK fast (INTERVAL := T#10ms, PRIORITY := 2);
        TASK slow (INTERVAL := T#15ms, PRIORITY := 1);
        PROGRAM pf WITH fast : fastp;
        PROGRAM ps WITH slow : slowp;
    END_RESOURCE
END_CONFIGURATION
";
    let f = temp_file("tasks.st", src);
    let p = [
        "--print",
        "log",
        "--print",
        "fast_runs",
        "--print",
        "slow_runs",
    ];
    let mut args = vec!["--cycles", "3"];
    args.extend_from_slice(&p);
    let (code, out, err) = run(&f, &args);
    assert_eq!(code, 0, "{err}");
    // 0: slow then fast (priority 1 first); 10: fast; 15: slow; 20: fast.
    assert_eq!(out, "log = 21121\nfast_runs = 3\nslow_runs = 2\n");
    let mut args = vec!["--duration", "31ms"];
    args.extend_from_slice(&p);
    let (_, out, _) = run(&f, &args);
    assert_eq!(out, "log = 2112121\nfast_runs = 4\nslow_runs = 3\n");
}

#[test]
fn help_documents_every_flag() {
    let out = automat(&["run", "--help"]);
    assert_eq!(out.status.code(), Some(0));
    let text = String::from_utf8_lossy(&out.stdout);
    for flag in [
        "--program",
        "--cycles",
        "--duration",
        "--cycle-time",
        "--virtual-clock",
        "--print",
        "--trace",
        "--trace-file",
        "--retain",
        "--retain-every",
        "--retain-optional",
        "--cold",
        "--stats",
    ] {
        assert!(text.contains(flag), "{flag} missing from:\n{text}");
    }
}

/// Ctrl-C, SIGTERM (how systemd stops a service) and SIGHUP all stop a
/// real-time run at the end of a scan: exit 0, outputs in the safe state,
/// RETAIN saved.
#[test]
fn signals_stop_a_real_time_run_cleanly_and_save_retain() {
    let src = RETAINED.replace(
        "END_VAR\n    r := r + 1;",
        "END_VAR\nVAR_OUTPUT\n    lamp : BOOL;\nEND_VAR\n    lamp := TRUE;\n    r := r + 1;",
    );
    let f = temp_file("realtime.st", &src);
    for signal in ["INT", "TERM", "HUP"] {
        let file = dir().join(format!("realtime-{signal}.retain"));
        let _ = std::fs::remove_file(&file);
        let child = Command::new(env!("CARGO_BIN_EXE_automat"))
            .args(["run", &f, "--cycle-time", "20ms", "--print", "r"])
            .args(["--print", "lamp", "--retain-every", "20ms", "--retain"])
            .arg(&file)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .expect("start automat");
        // The first periodic save shows the PLC runs (its signal handler is
        // in place), however loaded the machine.
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(30);
        while !file.exists() {
            assert!(
                std::time::Instant::now() < deadline,
                "SIG{signal}: no save in 30 s"
            );
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        std::thread::sleep(std::time::Duration::from_millis(200));
        let killed = Command::new("kill")
            .args([&format!("-{signal}"), &child.id().to_string()])
            .status()
            .expect("kill");
        assert!(killed.success());
        let out = child.wait_with_output().expect("wait");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "SIG{signal}: {stderr}");
        assert_eq!(
            stderr,
            "note: stopped at the end of a scan, in the safe state: 1 output (main.lamp) set to 0/FALSE\n",
            "SIG{signal}"
        );
        let text = String::from_utf8_lossy(&out.stdout);
        // Real time: about 12 scans; the exact count depends on the machine.
        let r: i32 = text
            .strip_prefix("r = ")
            .and_then(|s| s.strip_suffix("\nlamp = FALSE\n"))
            .and_then(|s| s.trim().parse().ok())
            .unwrap_or_else(|| panic!("SIG{signal}: unexpected output {text:?}"));
        assert!((2..=10_000).contains(&r), "SIG{signal}: {r} scans");
        // The RETAIN value printed is the one saved.
        let (_, out, _) = run(
            &f,
            &[
                "--cycles",
                "1",
                "--print",
                "r",
                "--retain",
                &file.display().to_string(),
            ],
        );
        assert_eq!(out, format!("r = {}\n", r + 1), "SIG{signal}");
    }
}

/// The issue's example: `b` is incremented, the scan faults, `a := b + 1`
/// is never reached. The file keeps the end of the last completed scan
/// (a = 3, b = 2), not the half-done image (b = 3).
#[test]
fn a_fault_saves_retain_as_it_was_before_the_faulting_scan() {
    let src = "PROGRAM main
VAR RETAIN
    a : INT;
    b : INT;
END_VAR
VAR
    zero : INT;
END_VAR
    b := b + 1;
    IF b = 3 THEN
        zero := b / zero;
    END_IF;
    a := b + 1;
END_PROGRAM
";
    let f = temp_file("halfscan.st", src);
    let file = dir().join("halfscan.retain");
    let _ = std::fs::remove_file(&file);
    let file_s = file.display().to_string();
    let (code, out, err) = run(
        &f,
        &[
            "--cycles", "10", "--retain", &file_s, "--print", "a", "--print", "b",
        ],
    );
    assert_eq!(code, 3, "{err}");
    // The image at the fault, as printed...
    assert_eq!(out, "a = 3\nb = 3\n");
    // ...is not what was saved.
    let (code, out, err) = run(
        &f,
        &[
            "--cycles", "0", "--retain", &file_s, "--print", "a", "--print", "b",
        ],
    );
    assert_eq!(
        (code, out.as_str(), err.as_str()),
        (0, "a = 3\nb = 2\n", "")
    );
}

/// The RETAIN path is checked before the first scan: exit 2 and nothing
/// run, unless --retain-optional (a warning, the run goes on, the save at
/// the end a warning too).
#[test]
fn an_unwritable_retain_path_is_an_error_before_the_first_scan() {
    let f = temp_file("retain.st", RETAINED);
    let missing = dir().join("no-such-folder/plc.retain");
    let missing_s = missing.display().to_string();
    let (code, out, err) = run(
        &f,
        &["--cycles", "3", "--print", "r", "--retain", &missing_s],
    );
    assert_eq!((code, out.as_str()), (2, ""), "{err}");
    assert!(
        err.starts_with(&format!(
            "error: RETAIN file {missing_s}: the directory {}: ",
            missing
                .parent()
                .map(|p| p.display().to_string())
                .unwrap_or_default()
        )),
        "{err}"
    );
    assert!(
        err.contains("note: the PLC did not start; --retain-optional"),
        "{err}"
    );
    let (code, out, err) = run(
        &f,
        &[
            "--cycles",
            "3",
            "--print",
            "r",
            "--retain",
            &missing_s,
            "--retain-optional",
        ],
    );
    assert_eq!((code, out.as_str()), (0, "r = 3\n"), "{err}");
    assert!(
        err.starts_with(&format!("warning: RETAIN file {missing_s}: the directory ")),
        "{err}"
    );
    assert!(
        err.ends_with(&format!(
            "warning: {missing_s}: cannot save the RETAIN variables: No such file or directory (os error 2) (--retain-optional)\n"
        )),
        "{err}"
    );
    // A directory given as the file.
    let d = dir().display().to_string();
    let (code, _, err) = run(&f, &["--cycles", "1", "--retain", &d]);
    assert_eq!(code, 2, "{err}");
    assert_eq!(
        err.lines().next(),
        Some(format!("error: RETAIN file {d}: is a directory").as_str())
    );
}

const EVENTS: &str = "TYPE Color : (RED, GREEN, BLUE); END_TYPE
FUNCTION_BLOCK Acc
VAR_INPUT x : INT; END_VAR
VAR_OUTPUT total : INT; END_VAR
    total := total + x;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Outer
VAR inner : Acc; END_VAR
    inner(x := 3);
END_FUNCTION_BLOCK
VAR_GLOBAL
    trig : BOOL;
    events : INT;
END_VAR
PROGRAM pcyc
VAR_EXTERNAL trig : BOOL; END_VAR
VAR k : INT; o : Outer; c : Color := GREEN; END_VAR
    k := k + 1;
    trig := (k MOD 4) >= 2;
    o();
END_PROGRAM
PROGRAM pev
VAR_EXTERNAL events : INT; END_VAR
    events := events + 1;
END_PROGRAM
CONFIGURATION c
    RESOURCE r ON PLC
        TASK cyc (INTERVAL := T#10ms, PRIORITY := 1);
        TASK ev (SINGLE := trig, PRIORITY := 0);
        PROGRAM pc WITH cyc : pcyc;
        PROGRAM pe WITH ev : pev;
    END_RESOURCE
END_CONFIGURATION
";

#[test]
fn event_tasks_run_on_rising_edges_and_nested_paths_print() {
    let f = temp_file("events.st", EVENTS);
    let args = [
        "--cycles",
        "8",
        "--print",
        "events",
        "--print",
        "pc.k",
        "--print",
        "pc.o.inner.total",
        "--print",
        "PC.C",
    ];
    let (code, out, err) = run(&f, &args);
    assert_eq!(code, 0, "{err}");
    // trig is TRUE after the scans k = 2, 3, 6, 7: rising edges seen at 20 and 60 ms.
    assert_eq!(
        out,
        "events = 2\npc.k = 8\npc.o.inner.total = 24\nPC.C = Color#GREEN\n"
    );
}

#[test]
fn program_picks_one_of_several_programs() {
    let src = "PROGRAM a\nVAR n : INT; END_VAR\n    n := n + 1;\nEND_PROGRAM\n\
               PROGRAM b\nVAR n : INT; END_VAR\n    n := n + 2;\nEND_PROGRAM\n";
    let f = temp_file("two.st", src);
    let (code, out, _) = run(&f, &["--cycles", "2", "--program", "B", "--print", "n"]);
    assert_eq!((code, out.as_str()), (0, "n = 4\n"));
    let (code, _, err) = run(&f, &["--cycles", "2", "--print", "n"]);
    assert_eq!(code, 1);
    assert!(err.contains("choose one with --program"), "{err}");
}

#[test]
fn stats_go_to_stderr() {
    let f = temp_file("stats.st", COUNTER);
    let (code, out, err) = run(&f, &["--cycles", "5", "--stats"]);
    assert_eq!((code, out.as_str()), (0, ""));
    assert!(
        err.starts_with("scans: 5, scan time min/avg/max: "),
        "{err}"
    );
    assert!(err.ends_with(", overruns: 0, task runs: main=5\n"), "{err}");
}

#[test]
fn timers_are_exact_on_the_virtual_clock() {
    let src =
        "PROGRAM main\nVAR\n    t : TON;\nEND_VAR\n    t(IN := TRUE, PT := T#50ms);\nEND_PROGRAM\n";
    let f = temp_file("ton.st", src);
    let (code, out, err) = run(&f, &["--cycles", "5", "--print", "t.Q", "--print", "t.ET"]);
    assert_eq!(
        (code, out.as_str()),
        (0, "t.Q = FALSE\nt.ET = T#40ms\n"),
        "{err}"
    );
    let csv = dir().join("ton.csv");
    let csv_s = csv.display().to_string();
    let (code, out, _) = run(
        &f,
        &[
            "--duration",
            "T#70ms",
            "--trace",
            "t.q,t.et",
            "--trace-file",
            &csv_s,
            "--print",
            "t.Q",
        ],
    );
    assert_eq!((code, out.as_str()), (0, "t.Q = TRUE\n"));
    assert_eq!(
        std::fs::read_to_string(&csv).expect("trace"),
        "time,t.q,t.et\nT#0s,FALSE,T#0s\nT#10ms,FALSE,T#10ms\nT#20ms,FALSE,T#20ms\n\
         T#30ms,FALSE,T#30ms\nT#40ms,FALSE,T#40ms\nT#50ms,TRUE,T#50ms\nT#60ms,TRUE,T#50ms\n"
    );
}

#[test]
fn direct_addresses_in_print_agree_with_the_code() {
    // CODESYS convention: %QW2 is output bytes 4..5, so %QX4.1 is one of its bits.
    let f = temp_file(
        "addresses.st",
        "PROGRAM P\nVAR w AT %QW2 : WORD; b AT %QX4.1 : BOOL; END_VAR\n    w := 16#0100;\n    b := TRUE;\nEND_PROGRAM\n",
    );
    let (code, out, err) = run(
        &f,
        &[
            "--cycles", "1", "--print", "%QW2", "--print", "%QB4", "--print", "%QX5.0", "--print",
            "w",
        ],
    );
    assert_eq!(code, 0, "{err}");
    assert_eq!(out, "%QW2 = 258\n%QB4 = 2\n%QX5.0 = TRUE\nw = 258\n");
}
