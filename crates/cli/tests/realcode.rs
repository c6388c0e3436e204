//! `automat corpus` on the in-repo real-code corpus `tests/realcode/`
//! (docs/realcode.md): the figures per source are pinned exactly, on both
//! engines, and a wrong documented value fails the run.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Runs `automat ARGS` in the repository root: (exit code, stdout, stderr).
fn automat(args: &[&str]) -> (Option<i32>, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_automat"))
        .current_dir(root())
        .args(args)
        .output()
        .expect("run automat");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

const IEC_SOURCES: [&str; 3] = [
    "tests/realcode/annex-f",
    "tests/realcode/matiec-style",
    "tests/realcode/openplc",
];

const IEC_REPORT: &str = "\
tests/realcode/annex-f: 5 files, 5 clean; 11 POUs, 11 clean; examples: 5 passed, 0 failed
tests/realcode/matiec-style: 4 files, 4 clean; 6 POUs, 6 clean; examples: 3 passed, 0 failed
tests/realcode/openplc: 1 file, 1 clean; 1 POU, 1 clean; examples: 1 passed, 0 failed
total: 10 files, 10 clean; 18 POUs, 18 clean; examples: 9 passed, 0 failed
";

const CODESYS_SOURCES: [&str; 2] = ["tests/realcode/codesys-v23", "tests/realcode/oscat-style"];

const CODESYS_REPORT: &str = "\
tests/realcode/codesys-v23: 5 files, 5 clean; 9 POUs, 9 clean; examples: 2 passed, 0 failed
tests/realcode/oscat-style: 2 files, 2 clean; 4 POUs, 4 clean; examples: 1 passed, 0 failed
total: 7 files, 7 clean; 13 POUs, 13 clean; examples: 3 passed, 0 failed
";

#[test]
fn the_iec_sources_check_and_run_as_pinned_on_both_engines() {
    for engine in ["jit", "interp"] {
        let mut args = vec!["corpus", "--engine", engine];
        args.extend(IEC_SOURCES);
        let (code, out, err) = automat(&args);
        assert_eq!(
            (code, out.as_str(), err.as_str()),
            (Some(0), IEC_REPORT, ""),
            "{engine}"
        );
    }
}

#[test]
fn the_codesys_export_checks_and_runs_as_pinned_with_its_dialect() {
    for engine in ["jit", "interp"] {
        let mut args = vec!["corpus", "--lib", "codesys", "--engine", engine];
        args.extend(CODESYS_SOURCES);
        let (code, out, err) = automat(&args);
        assert_eq!(
            (code, out.as_str(), err.as_str()),
            (Some(0), CODESYS_REPORT, ""),
            "{engine}"
        );
    }
    // Without the dialect the export is IEC text it does not follow: only
    // the example's program checks (its run still has the dialect its
    // header names, `libraries: codesys`).
    let (code, out, _) = automat(&["corpus", "tests/realcode/codesys-v23"]);
    assert_eq!(code, Some(0));
    assert!(
        out.starts_with(
            "tests/realcode/codesys-v23: 5 files, 2 clean; 9 POUs, 2 clean; examples: 2 passed"
        ),
        "{out}"
    );
    // The OSCAT-style blocks need the dialect's clock, bit-string index and
    // `END_IF` without `;`; only the example's program checks without it.
    let (code, out, _) = automat(&["corpus", "tests/realcode/oscat-style"]);
    assert_eq!(code, Some(0));
    assert!(
        out.starts_with(
            "tests/realcode/oscat-style: 2 files, 1 clean; 4 POUs, 1 clean; examples: 1 passed"
        ),
        "{out}"
    );
}

#[test]
fn json_gives_the_same_figures() {
    let mut args = vec!["corpus", "--json", "--lib", "codesys"];
    args.push("tests/realcode/codesys-v23");
    let (code, out, _) = automat(&args);
    assert_eq!(code, Some(0));
    let v: serde_json::Value = serde_json::from_str(&out).expect("JSON report");
    let s = &v["sources"][0];
    assert_eq!(s["source"], "tests/realcode/codesys-v23");
    assert_eq!(
        (&s["files"], &s["files_clean"], &s["pous"], &s["pous_clean"]),
        (&5.into(), &5.into(), &9.into(), &9.into())
    );
    assert_eq!(s["codes"], serde_json::json!({}));
    assert_eq!(s["not_clean"], serde_json::json!([]));
    assert_eq!(
        s["example_results"],
        serde_json::json!([
            {"file": "tests/realcode/codesys-v23/queue/examples.st", "verdict": "passed", "details": ""},
            {"file": "tests/realcode/codesys-v23/util/examples.st", "verdict": "passed", "details": ""}
        ])
    );
    assert_eq!(v["total"]["examples"]["passed"], 2);
}

#[test]
fn a_wrong_documented_value_fails_and_a_bad_path_is_refused() {
    let dir = std::env::temp_dir().join(format!("automat-realcode-{}", std::process::id()));
    let lib = dir.join("lib");
    std::fs::create_dir_all(&lib).expect("temp dir");
    std::fs::write(
        lib.join("twice.st"),
        "FUNCTION Twice : INT VAR_INPUT x : INT; END_VAR Twice := 2 * x; END_FUNCTION\n",
    )
    .expect("write");
    std::fs::write(
        lib.join("example.st"),
        "(* expect: Main.y = 7 *)\nPROGRAM Main VAR y : INT; END_VAR y := Twice(3); END_PROGRAM\n",
    )
    .expect("write");
    let d = dir.to_string_lossy().into_owned();
    let (code, out, _) = automat(&["corpus", &d]);
    assert_eq!(code, Some(1));
    assert_eq!(
        out,
        format!(
            "{d}: 2 files, 2 clean; 2 POUs, 2 clean; examples: 0 passed, 1 failed\n  \
             FAILED {d}/lib/example.st:\n      line 1: Main.y: expected 7, got 6\n"
        )
    );
    // --whole: the folder is one project, the same figures.
    let (code, whole, _) = automat(&["corpus", "--whole", &d]);
    assert_eq!((code, whole), (Some(1), out));
    let (code, _, err) = automat(&["corpus", "no/such/folder"]);
    assert_eq!(code, Some(2));
    assert!(err.starts_with("error: no/such/folder: "), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}
