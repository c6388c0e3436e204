//! A closed stdout or stderr (`automat check x.st | head -1`) never makes
//! a command panic (exit 101): the output is dropped and the command exits
//! with the code it returns when every line is read (`out.rs`).
//!
//! Every command runs four ways: stdout closed before it writes anything,
//! stdout closed after its first line (what `head -1` does), stderr
//! closed, and both closed. A reader that is gone before the first write
//! makes every write fail, so the test does not depend on timing.

use std::io::{BufRead, BufReader, Read};
use std::path::PathBuf;
use std::process::{Command, Stdio};

#[derive(Clone, Copy, Debug)]
enum Closed {
    Stdout,
    StdoutAfterOneLine,
    Stderr,
    Both,
}

/// Runs automat with the given stream(s) closed; the exit code and what it
/// wrote to stderr (when that is open).
fn run(args: &[&str], closed: Closed) -> (Option<i32>, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_automat"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run automat");
    let stdout = child.stdout.take().expect("stdout");
    let mut stderr = child.stderr.take().expect("stderr");
    match closed {
        Closed::Stdout | Closed::Both => drop(stdout),
        Closed::StdoutAfterOneLine => {
            let mut first = String::new();
            let mut r = BufReader::new(stdout);
            let _ = r.read_line(&mut first);
            drop(r);
        }
        Closed::Stderr => {
            // Keep reading stdout so only stderr is closed.
            std::thread::spawn(move || {
                let _ = std::io::copy(&mut { stdout }, &mut std::io::sink());
            });
        }
    }
    let mut err = String::new();
    if matches!(closed, Closed::Stderr | Closed::Both) {
        drop(stderr);
    } else {
        let _ = stderr.read_to_string(&mut err);
    }
    let status = child.wait().expect("wait");
    (status.code(), err)
}

fn root(rel: &str) -> String {
    concat!(env!("CARGO_MANIFEST_DIR"), "/../../").to_string() + rel
}

fn temp_file(name: &str, text: &str) -> String {
    let dir: PathBuf = std::env::temp_dir().join(format!("automat-pipe-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write");
    path.display().to_string()
}

#[test]
fn every_command_survives_a_closed_stdout_or_stderr() {
    let bad = temp_file(
        "bad.st",
        "PROGRAM p\nVAR i : INT; d : DINT; END_VAR\ni := d;\nundefined := 1;\nEND_PROGRAM\n",
    );
    let good = temp_file(
        "good.st",
        "PROGRAM p\nVAR x : INT; END_VAR\nx := x + 1;\nEND_PROGRAM\n",
    );
    let trace = temp_file("trace.csv", "time,p.x\nT#0ms,1\nT#10ms,2\n");
    let svg = temp_file("trace.svg", "");
    let fault = root("tests/conformance/fault_div_zero.st");
    let conformance = root("tests/conformance/arith_std.st");
    let crane = root("examples/crane");
    let failing = root("crates/cli/tests/fixtures/failing_crane");
    let failing_out = temp_file("failing-out", "");
    let _ = std::fs::remove_file(&failing_out);
    // (arguments, the documented exit code)
    let cases: Vec<(Vec<&str>, i32)> = vec![
        (vec!["check", &bad], 1),
        (vec!["check", "--format", "json", &bad], 1),
        (vec!["check", &good], 0),
        (vec!["check", &crane], 0),
        (vec!["check", "/nonexistent/automat"], 2),
        (
            vec!["run", &good, "--cycles", "3", "--print", "x", "--stats"],
            0,
        ),
        (vec!["run", &good, "--cycles", "3", "--print", "nope"], 2),
        (vec!["run", &bad, "--cycles", "3"], 1),
        (
            vec!["run", &fault, "--cycles", "5", "--engine", "interp"],
            3,
        ),
        (vec!["run", &crane, "--duration", "100ms", "--stats"], 0),
        (vec!["explain", "E030"], 0),
        (vec!["explain", "--list"], 0),
        (vec!["explain", "E9999"], 2),
        (vec!["test", &conformance], 0),
        (vec!["test", &failing, "--out", &failing_out], 1),
        (vec!["plot", &trace, "-o", &svg], 0),
        (vec!["plot", "/nonexistent/trace.csv", "-o", &svg], 2),
        (vec!["plant", "crane", "--map"], 0),
        (vec!["plant", "kran", "--map"], 2),
        (
            vec![
                "plant",
                "crane",
                "--modbus-server",
                "127.0.0.1:0",
                "--duration",
                "100ms",
            ],
            0,
        ),
        (vec!["--help"], 0),
        (vec!["check", "--help"], 0),
        (vec!["run", "--help"], 0),
        (vec!["test", "--help"], 0),
        (vec!["plot", "--help"], 0),
        (vec!["plant", "--help"], 0),
        (vec!["explain", "--help"], 0),
        (vec!["--version"], 0),
        (vec!["check"], 2),
        (vec!["frobnicate"], 2),
    ];
    let mut failures = Vec::new();
    for (args, code) in &cases {
        for closed in [
            Closed::Stdout,
            Closed::StdoutAfterOneLine,
            Closed::Stderr,
            Closed::Both,
        ] {
            let (got, err) = run(args, closed);
            if got != Some(*code) || err.contains("panicked") {
                failures.push(format!(
                    "automat {} with {closed:?} closed: exit {got:?} (want {code}); stderr: {err}",
                    args.join(" ")
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
