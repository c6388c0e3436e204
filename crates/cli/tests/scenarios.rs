//! `automat test` on the examples and the conformance corpus, the failure
//! report of a deliberately failing scenario, and `automat plot`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn automat(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_automat"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("run automat")
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("automat-scn-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

#[test]
fn every_example_scenario_and_conformance_program_passes() {
    let out_dir = tmp("all");
    let out = automat(
        &root(),
        &[
            "test",
            "examples",
            "tests/conformance",
            "--out",
            out_dir.to_str().unwrap_or("."),
        ],
    );
    let stdout = text(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{stdout}{}", text(&out.stderr));
    let last = stdout.lines().last().unwrap_or("");
    assert!(last.ends_with(" passed, 0 failed"), "{last}");
    assert!(stdout.contains(
        "ok examples/crane/scenarios/normal.scn (normal cycle: both cycles, then rest)\n"
    ));
    assert!(stdout.contains("ok tests/conformance/tp.st\n"));
}

#[test]
fn a_failing_scenario_names_assertion_time_and_values_and_writes_trace_and_diagram() {
    let out_dir = tmp("fail");
    let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures");
    let o = out_dir.to_str().unwrap_or(".");
    let out = automat(&fixtures, &["test", "failing_crane", "--out", o]);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(
        text(&out.stdout),
        format!(
            "FAILED failing_crane/scenarios/wrong.scn (wrong expectations)
    failing_crane/scenarios/wrong.scn:4: expect at 2s M1D
      failed at T#2s: it is FALSE
      values: M1D = FALSE
    failing_crane/scenarios/wrong.scn:6: expect always plant.y < 2
      failed at T#2s500ms: it is FALSE
      values: plant.y = 2
    failing_crane/scenarios/wrong.scn:5: expect M1S within 3s after 1s
      failed at T#4s: it did not become TRUE in (T#1s, T#4s]
      values: M1S = FALSE
    trace: {o}/wrong.fail.csv
    diagram: {o}/wrong.fail.svg
0 passed, 1 failed
"
        )
    );
    let csv = std::fs::read_to_string(out_dir.join("wrong.fail.csv")).expect("trace");
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some(
            "time,Pornire,l1,l2,l3,l4,M1S,M1D,M2S,M2J,plant.x,plant.y,plant.cycles,plant.conflicts"
        )
    );
    assert_eq!(
        lines.next(),
        Some("T#0s,FALSE,TRUE,FALSE,TRUE,FALSE,FALSE,FALSE,FALSE,FALSE,0,0,0,0")
    );
    // the press at 500 ms is seen by the scan at 500 ms; up from the next scan
    assert_eq!(
        csv.lines().nth(51),
        Some("T#500ms,TRUE,TRUE,FALSE,TRUE,FALSE,FALSE,FALSE,TRUE,FALSE,0,0,0,0")
    );
    assert_eq!(
        csv.lines().nth(52),
        Some("T#510ms,TRUE,TRUE,FALSE,TRUE,FALSE,FALSE,FALSE,TRUE,FALSE,0,0.01,0,0")
    );
    assert_eq!(csv.lines().count(), 1 + 1000);
    let svg = std::fs::read_to_string(out_dir.join("wrong.fail.svg")).expect("diagram");
    assert_eq!(svg.matches("<text class=\"name\"").count(), 13);
}

#[test]
fn plot_writes_an_svg_of_chosen_signals() {
    let dir = tmp("plot");
    let csv = dir.join("t.csv");
    std::fs::write(&csv, "time,b,x\nT#0s,FALSE,1\nT#10ms,TRUE,3\n").expect("write");
    let svg = dir.join("t.svg");
    let out = automat(&dir, &["plot", "t.csv", "-o", "t.svg", "--signals", "x"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let s = std::fs::read_to_string(&svg).expect("svg");
    assert_eq!(s.matches("<path").count(), 1);
    assert!(
        s.contains(r#"<path class="analog" d="M140 75 L510 15""#),
        "{s}"
    );
    let out = automat(&dir, &["plot", "t.csv", "-o", "t.svg", "--signals", "y"]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        text(&out.stderr),
        "error: no column `y` in the trace (it has: b, x)\n"
    );
}
