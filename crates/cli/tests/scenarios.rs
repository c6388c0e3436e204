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
    assert!(stdout.contains(
        "ok examples/crane-slc/scenarios/normal.scn (normal cycle: both cycles, then rest)\n"
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
            "time,Pornire,l1,l2,l3,l4,M1S,M1D,M2S,M2J,plant.x,plant.y,plant.cycles,plant.conflicts,plant.end_stops"
        )
    );
    assert_eq!(
        lines.next(),
        Some("T#0s,FALSE,TRUE,FALSE,TRUE,FALSE,FALSE,FALSE,FALSE,FALSE,0,0,0,0,0")
    );
    // the press at 500 ms is seen by the scan at 500 ms; up from the next scan
    assert_eq!(
        csv.lines().nth(51),
        Some("T#500ms,TRUE,TRUE,FALSE,TRUE,FALSE,FALSE,FALSE,TRUE,FALSE,0,0,0,0,0")
    );
    assert_eq!(
        csv.lines().nth(52),
        Some("T#510ms,TRUE,TRUE,FALSE,TRUE,FALSE,FALSE,FALSE,TRUE,FALSE,0,0.01,0,0,0")
    );
    assert_eq!(csv.lines().count(), 1 + 1000);
    let svg = std::fs::read_to_string(out_dir.join("wrong.fail.svg")).expect("diagram");
    assert_eq!(svg.matches("<text class=\"name\"").count(), 14);
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

#[test]
fn plot_writes_a_png_of_the_same_drawing() {
    let dir = tmp("png");
    std::fs::write(dir.join("t.csv"), "time,b\nT#0s,FALSE\nT#10ms,TRUE\n").expect("write");
    let out = automat(&dir, &["plot", "t.csv", "-o", "t.png"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let png = std::fs::read(dir.join("t.png")).expect("png");
    let pm = tiny_skia::Pixmap::decode_png(&png).expect("decode");
    // One boolean row: 10 + 36 + 30 + 10 high, as the SVG.
    assert_eq!((pm.width(), pm.height()), (900, 86));
    let px = |x, y| pm.pixel(x, y).map(|c| (c.red(), c.alpha()));
    // The rising edge at x 510 (10 ms of 20 ms over 140..880).
    assert_eq!(px(505, 25), Some((255, 255)));
    assert_eq!(px(509, 25), Some((63, 255)));
    assert_eq!(px(510, 25), Some((63, 255)));
    // The name `b` ends at x 132: its stem is the column 127.
    assert_eq!(px(127, 25), Some((0, 255)));
    let out = automat(&dir, &["plot", "t.csv", "-o", "t.gif"]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        text(&out.stderr),
        "error: t.gif: the diagram is written as SVG or PNG; name the output `*.svg` or `*.png`\n"
    );
}

/// Folders marked with `.automat-test-skip` (the deliberately failing
/// fixtures), hidden folders and `target` are not searched; a marked
/// folder named on the command line is.
#[test]
fn test_skips_marked_hidden_and_target_folders() {
    let dir = tmp("skip");
    let wrong = "name wrong\nduration 1s\nexpect at 1s M1D\n";
    for sub in [".hidden", "target", "marked"] {
        let p = dir.join(sub);
        std::fs::create_dir_all(&p).expect("dir");
        std::fs::write(p.join("wrong.scn"), wrong).expect("write");
    }
    std::fs::write(dir.join("marked/.automat-test-skip"), "").expect("write");
    let out = automat(&dir, &["test"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert_eq!(
        text(&out.stdout),
        "skipped ./marked (.automat-test-skip)\n0 passed, 0 failed\n"
    );
    // Named on the command line, the marked folder is searched (and its
    // scenario cannot run: it is in no project).
    let out = automat(&dir, &["test", "marked"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stdout).starts_with("ERROR marked/wrong.scn\n"));
    // The rule is in the help.
    let help = text(&automat(&dir, &["test", "--help"]).stdout);
    assert!(
        help.contains("every folder holding a file named `.automat-test-skip`"),
        "{help}"
    );
    // From the repository root, the failing fixtures are left out.
    let out = automat(&root(), &["test", "crates/cli/tests"]);
    assert_eq!(
        text(&out.stdout),
        "skipped crates/cli/tests/fixtures (.automat-test-skip)\n\
         skipped crates/cli/tests/projects (.automat-test-skip)\n\
         0 passed, 0 failed\n"
    );
}

/// A chart's step flags are ordinary paths for `--trace` and `--print` in
/// a project run (the SFC desugaring makes each step an instance with `X`).
#[test]
fn project_runs_trace_sfc_step_flags() {
    let dir = tmp("sfc");
    std::fs::write(
        dir.join("automat.toml"),
        "[project]\nname = \"sfc\"\n[plant]\nmodel = \"crane\"\n",
    )
    .expect("write");
    std::fs::write(
        dir.join("ctrl.st"),
        "PROGRAM Ctrl
VAR Pornire, l1, l2, l3, l4 : BOOL; M1S, M1D, M2S, M2J : BOOL; END_VAR
    INITIAL_STEP Rest: END_STEP
    TRANSITION FROM Rest TO Up := TRUE; END_TRANSITION
    STEP Up: M2S(N); END_STEP
    TRANSITION FROM Up TO Rest := Up.T >= T#10ms; END_TRANSITION
END_PROGRAM
",
    )
    .expect("write");
    let out = automat(
        &dir,
        &[
            "run",
            ".",
            "--cycles",
            "4",
            "--trace",
            "Ctrl.Rest.X,Ctrl.Up.X,M2S,steps(Ctrl)",
            "--trace-file",
            "t.csv",
            "--print",
            "Ctrl.Up.X",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert_eq!(text(&out.stdout), "Ctrl.Up.X = FALSE\n");
    // Scan 1: Rest -> Up. Scan 2: Up.T is 10 ms, M2S (N) is set, then
    // Up -> Rest. Scan 3: M2S falls, Rest -> Up; and so on. `steps(Ctrl)`
    // is the chart's active steps as one cell (a band in `automat plot`).
    let csv = std::fs::read_to_string(dir.join("t.csv")).expect("trace");
    assert_eq!(
        csv,
        "time,Ctrl.Rest.X,Ctrl.Up.X,M2S,steps(Ctrl)\n\
         T#0s,FALSE,TRUE,FALSE,Up\n\
         T#10ms,TRUE,FALSE,TRUE,Rest\n\
         T#20ms,FALSE,TRUE,FALSE,Up\n\
         T#30ms,TRUE,FALSE,TRUE,Rest\n"
    );
}
