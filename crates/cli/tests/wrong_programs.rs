//! Plants that catch wrong programs (issue 17 point 5): each wrong
//! controller in `tests/fixtures/wrong/` runs against the scenario of its
//! example, which passes on the reference program and fails on the wrong
//! one with the plant's count of what went wrong.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn automat(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_automat"))
        .current_dir(root())
        .args(args)
        .output()
        .expect("run automat")
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// `scenario` holds on `example` and fails on the wrong controller
/// `fixture`, and the failure report contains every line of `expected`.
fn caught(example: &str, fixture: &str, scenario: &str, expected: &[&str]) {
    let scn = format!("{example}/scenarios/{scenario}");
    let good = automat(&["run", example, "--scenario", &scn]);
    assert_eq!(
        good.status.code(),
        Some(0),
        "the reference program fails: {}",
        text(&good.stderr)
    );
    let wrong = format!("crates/cli/tests/fixtures/wrong/{fixture}");
    let bad = automat(&["run", &wrong, "--scenario", &scn]);
    let report = text(&bad.stderr);
    assert_eq!(bad.status.code(), Some(1), "{report}");
    for line in expected {
        assert!(
            report.contains(line),
            "missing `{line}` in the report:\n{report}"
        );
    }
}

#[test]
fn level_tank_overflow_is_counted_by_the_plant_in_st() {
    caught(
        "examples/level-tank",
        "level_tank_overflow",
        "normal.scn",
        &[
            "examples/level-tank/scenarios/normal.scn:24: expect always plant.overflows = 0 AND plant.dry_runs = 0\n  failed at T#1m16s: it is FALSE\n  values: plant.overflows = 1, plant.dry_runs = 0\n",
            "examples/level-tank/scenarios/normal.scn:16: expect NOT pump within 10ms after rise(ls_high)\n  failed at T#59s350ms",
        ],
    );
}
