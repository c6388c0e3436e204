//! The command-line contract: exit codes, output formats, help.

use std::path::PathBuf;
use std::process::{Command, Output};

fn automat(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_automat"))
        .args(args)
        .output()
        .expect("run automat")
}

fn temp_file(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("automat-cli-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write temp file");
    path
}

const BAD: &str = "PROGRAM p\nVAR\n    i : INT;\n    d : DINT;\nEND_VAR\n    i := d;\n    undefined := 1;\nEND_PROGRAM\n";

#[test]
fn clean_project_exits_0_and_prints_nothing() {
    let crane = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/crane");
    let out = automat(&["check", crane]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    assert!(out.stdout.is_empty());
}

#[test]
fn a_project_folder_is_checked_with_its_libraries() {
    // `libraries = ["isagraf"]` in automat.toml: TIMER, TSTART and the
    // section pragmas are known without `--lib`, as for `run` and `test`.
    let dir = std::env::temp_dir().join(format!("automat-cli-lib-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    std::fs::write(
        dir.join("automat.toml"),
        "[project]\nname = \"lib\"\nlibraries = [\"isagraf\"]\n",
    )
    .expect("write project");
    std::fs::write(
        dir.join("main.st"),
        "PROGRAM Main\nVAR t : TIMER; END_VAR\nTSTART(t);\nEND_PROGRAM\n",
    )
    .expect("write source");
    let d = dir.to_str().unwrap();
    let out = automat(&["check", d]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    // A broken project file is reported with its location, exit 1.
    std::fs::write(dir.join("automat.toml"), "[project]\nname = 3\n").expect("write");
    let out = automat(&["check", d]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("automat.toml:2:"), "{err}");
}

#[test]
fn errors_exit_1_with_location_code_and_caret() {
    let path = temp_file("bad.st", BAD);
    let out = automat(&["check", path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let text = String::from_utf8_lossy(&out.stdout);
    let first = text.lines().next().unwrap_or("");
    assert!(
        first.ends_with(
            "bad.st:6:10: error[E030]: cannot assign a value of type DINT to `i` of type INT; convert it with `DINT_TO_INT(...)`"
        ),
        "{text}"
    );
    assert!(text.contains("6 |     i := d;\n  |          ^"), "{text}");
    assert!(text.contains("bad.st:7:5: error[E020]"), "{text}");
    assert!(text.contains("2 errors, 0 warnings"), "{text}");
}

#[test]
fn json_format_is_machine_readable() {
    let path = temp_file("bad_json.st", BAD);
    let out = automat(&["check", "--format", "json", path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("valid JSON");
    let arr = v.as_array().expect("array");
    assert_eq!(arr.len(), 2);
    assert_eq!(arr[0]["code"], "E030");
    assert_eq!(arr[0]["severity"], "error");
    assert_eq!(arr[0]["line"], 6);
    assert_eq!(arr[0]["column"], 10);
    assert_eq!(arr[1]["code"], "E020");
    assert_eq!(arr[1]["line"], 7);
}

#[test]
fn missing_path_and_bad_flags_exit_2() {
    let out = automat(&["check", "/definitely/not/here.st"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("/definitely/not/here.st"));
    assert_eq!(automat(&["check"]).status.code(), Some(2));
    assert_eq!(
        automat(&["check", "--format", "xml", "x.st"]).status.code(),
        Some(2)
    );
    assert_eq!(automat(&["frobnicate"]).status.code(), Some(2));
}

#[test]
fn help_documents_every_command_and_flag() {
    let top = String::from_utf8_lossy(&automat(&["--help"]).stdout).to_string();
    for cmd in ["check", "run", "explain"] {
        assert!(top.contains(cmd), "{top}");
    }
    let check = String::from_utf8_lossy(&automat(&["check", "--help"]).stdout).to_string();
    for flag in ["--format", "--deny-warnings", "--no-warnings", "PATH"] {
        assert!(check.contains(flag), "{check}");
    }
    let explain = automat(&["explain", "E030"]);
    assert_eq!(explain.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&explain.stdout).starts_with("E030: type mismatch"));
    assert_eq!(automat(&["explain", "E999"]).status.code(), Some(2));
}

#[test]
fn non_utf8_source_is_read_not_rejected() {
    let dir = std::env::temp_dir().join(format!("automat-cli-latin1-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let path = dir.join("latin1.st");
    // A Latin-1 'é' (0xE9) inside a comment.
    std::fs::write(
        &path,
        b"(* caf\xe9 *)\nPROGRAM p\nVAR x : INT; END_VAR\n x := 1;\nEND_PROGRAM\n",
    )
    .expect("write");
    let out = automat(&["check", path.to_str().unwrap()]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
}

#[test]
fn diagnostics_stop_after_200_in_text_and_json() {
    // 300 undefined names: the first 200 are shown, the rest counted.
    let body: String = (0..300).map(|i| format!("    u{i} := 1;\n")).collect();
    let path = temp_file("many.st", &format!("PROGRAM p\n{body}END_PROGRAM\n"));
    let out = automat(&["check", path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(text.matches(": error[").count(), 200, "{text}");
    assert!(text.contains(":201:5: error["), "{text}");
    assert!(!text.contains(":202:5: error["), "{text}");
    assert!(
        text.ends_with(
            "and 100 more (100 errors, 0 warnings) not shown\n\n300 errors, 0 warnings\n"
        ),
        "{text}"
    );
    let out = automat(&["check", "--format", "json", path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    let items = v.as_array().expect("array");
    assert_eq!(items.len(), 201);
    assert_eq!(items[200]["severity"], "note");
    assert_eq!(
        items[200]["message"],
        "and 100 more (100 errors, 0 warnings) not shown"
    );
}

#[test]
fn check_reports_what_run_refuses_at_compile_time() {
    // Recursion (E092) and an image too large (E091, with the exact bytes:
    // 2^34 of the array, twice with its template, plus what every program
    // has) are compile-time refusals of `run`: `check` reports them the same.
    let rec = temp_file(
        "recursive.st",
        "FUNCTION Fact : INT\nVAR_INPUT n : INT; END_VAR\nIF n <= 1 THEN Fact := 1; ELSE Fact := n * Fact(n - 1); END_IF;\nEND_FUNCTION\nPROGRAM Main\nVAR x : INT; END_VAR\nx := Fact(5);\nEND_PROGRAM\n",
    );
    let big = temp_file(
        "big.st",
        "PROGRAM Main\nVAR a : ARRAY[0..2047] OF ARRAY[0..1048575] OF LREAL; END_VAR\na[0][0] := 1.0;\nEND_PROGRAM\n",
    );
    for (path, first) in [
        (&rec, "recursive.st:1:1: error[E092]: recursive call: Fact -> Fact"),
        (
            &big,
            "big.st:1:1: error[E091]: the program needs 34359739448 bytes of memory, more than the 268435456 bytes supported",
        ),
    ] {
        let p = path.to_str().unwrap();
        let check = automat(&["check", p]);
        assert_eq!(check.status.code(), Some(1));
        let text = String::from_utf8_lossy(&check.stdout).into_owned();
        assert!(text.lines().next().unwrap_or("").ends_with(first), "{text}");
        assert!(text.ends_with("\n1 error, 0 warnings\n"), "{text}");
        let run = automat(&["run", p, "--cycles", "1"]);
        assert_eq!(run.status.code(), Some(1));
        // run prints the same report on stderr.
        assert_eq!(String::from_utf8_lossy(&run.stderr), text);
    }
    // Several PROGRAMs without a CONFIGURATION: each is checked as the one a
    // run may choose; which one is not check's question (no E090).
    let two = temp_file(
        "two.st",
        "PROGRAM A\nVAR x : INT; END_VAR\nx := x + 1;\nEND_PROGRAM\nPROGRAM B\nVAR y : INT; END_VAR\ny := y + 1;\nEND_PROGRAM\n",
    );
    let out = automat(&["check", two.to_str().unwrap()]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    assert!(out.stdout.is_empty());
}
