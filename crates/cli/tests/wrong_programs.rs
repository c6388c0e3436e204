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

#[test]
fn crane_driven_into_its_right_end_stop() {
    // l4 at 9.9 m (10.42 s); the end 0.1 m later at 2 m/s: 50 ms
    caught(
        "examples/crane",
        "crane_end_stop",
        "normal.scn",
        &["examples/crane/scenarios/normal.scn:97: expect always plant.end_stops = 0\n  failed at T#10s470ms: it is FALSE\n  values: plant.end_stops = 1\n"],
    );
}

#[test]
fn oscillating_carriage_driven_into_its_right_end() {
    caught(
        "examples/oscillating",
        "oscillating_end_stop",
        "normal.scn",
        &["examples/oscillating/scenarios/normal.scn:92: expect always plant.end_stops = 0\n  failed at T#5s510ms: it is FALSE\n  values: plant.end_stops = 1\n"],
    );
}

#[test]
fn sorter_platform_lowered_onto_an_extended_pusher() {
    caught(
        "examples/sorter",
        "sorter_collision",
        "normal.scn",
        &["examples/sorter/scenarios/normal.scn:109: expect always plant.collisions = 0 AND plant.jams = 0\n  failed at T#12s610ms: it is FALSE\n  values: plant.collisions = 1, plant.jams = 0\n"],
    );
}

#[test]
fn sorter_belt_2_stopped_jams_the_second_small_package() {
    caught(
        "examples/sorter",
        "sorter_belt_2_off",
        "normal.scn",
        &["examples/sorter/scenarios/normal.scn:109: expect always plant.collisions = 0 AND plant.jams = 0\n  failed at T#32s340ms: it is FALSE\n  values: plant.collisions = 0, plant.jams = 1\n"],
    );
}

#[test]
fn carwash_barrier_lowered_onto_a_vehicle() {
    caught(
        "examples/carwash",
        "carwash_barrier_hit",
        "normal.scn",
        &[
            "examples/carwash/scenarios/normal.scn:177: expect always plant.barrier_hits = 0\n  failed at T#31s50ms: it is FALSE\n  values: plant.barrier_hits = 1\n",
            "plant.washed = 5, plant.unwashed = 0, plant.barrier_hits = 1",
        ],
    );
}

#[test]
fn tank_2_overfilled_by_a_pump_that_never_stops() {
    // 7 L + 0.06 L/s net: the 10 L rim after 50 s
    caught(
        "examples/tank-temperature",
        "tank_overflow",
        "normal.scn",
        &["examples/tank-temperature/scenarios/normal.scn:54: expect always plant.overflows = 0 AND plant.spilled = 0\n  failed at T#50s20ms: it is FALSE\n  values: plant.overflows = 1, plant.spilled = 0.0002\n"],
    );
}
