//! The crane example (problem 1 of the sources) runs end to end against its
//! virtual plant: the README's main command, with the digest's acceptance
//! checks in virtual time (the scenarios in `examples/crane/scenarios`
//! check the rest through `automat test`).

use std::process::Command;

fn run_crane(duration: &str, vars: &[&str]) -> Vec<String> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/crane");
    let scn = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/crane/scenarios/normal.scn"
    );
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_automat"));
    cmd.args(["run", dir, "--scenario", scn, "--duration", duration]);
    for v in vars {
        cmd.args(["--print", v]);
    }
    let out = cmd.output().expect("run automat");
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(str::to_string)
        .collect()
}

#[test]
fn crane_runs_cycle_one_waits_then_returns() {
    // Pornire is pressed at 0.5 s: up (5 s), right (5 s), down (5 s), 3 s dwell,
    // up, left, down, back at rest 1 after about 33.5 s.
    let at = |t: &str| run_crane(t, &["Ctrl.step", "plant.cycles"]);
    assert_eq!(
        at("400ms"),
        ["Ctrl.step = CraneStep#Rest1", "plant.cycles = 0"]
    );
    assert_eq!(at("1s"), ["Ctrl.step = CraneStep#Up1", "plant.cycles = 0"]);
    assert_eq!(
        at("8s"),
        ["Ctrl.step = CraneStep#Right", "plant.cycles = 0"]
    );
    assert_eq!(
        at("13s"),
        ["Ctrl.step = CraneStep#Down1", "plant.cycles = 0"]
    );
    assert_eq!(
        at("17s"),
        ["Ctrl.step = CraneStep#Wait", "plant.cycles = 0"]
    );
    assert_eq!(at("20s"), ["Ctrl.step = CraneStep#Up2", "plant.cycles = 0"]);
    assert_eq!(
        at("26s"),
        ["Ctrl.step = CraneStep#Left", "plant.cycles = 0"]
    );
    assert_eq!(
        at("31s"),
        ["Ctrl.step = CraneStep#Down2", "plant.cycles = 0"]
    );
    // No new cycle without a new press.
    assert_eq!(
        at("60s"),
        ["Ctrl.step = CraneStep#Rest1", "plant.cycles = 1"]
    );
}

#[test]
fn crane_outputs_are_off_at_rest_and_never_collide() {
    let out = run_crane(
        "60s",
        &[
            "M1S",
            "Ctrl.M1D",
            "M2S",
            "%QX3.4",
            "plant.conflicts",
            "plant.x",
            "l3",
        ],
    );
    assert_eq!(
        out,
        [
            "M1S = FALSE",
            "Ctrl.M1D = FALSE",
            "M2S = FALSE",
            "%QX3.4 = FALSE",
            "plant.conflicts = 0",
            "plant.x = 0.1",
            "l3 = TRUE"
        ]
    );
}
