//! The crane example (problem 1 of the sources) runs end to end against its
//! stand-in plant: the README's main command, with the digest's acceptance
//! checks in virtual time.

use std::process::Command;

fn run_crane(duration: &str, vars: &[&str]) -> Vec<String> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/crane");
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_automat"));
    cmd.args(["run", dir, "--duration", duration]);
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
    let at = |t: &str| run_crane(t, &["Ctrl.step", "Sim.cycles"]);
    assert_eq!(
        at("400ms"),
        ["Ctrl.step = CraneStep#Rest1", "Sim.cycles = 0"]
    );
    assert_eq!(at("1s"), ["Ctrl.step = CraneStep#Up1", "Sim.cycles = 0"]);
    assert_eq!(at("8s"), ["Ctrl.step = CraneStep#Right", "Sim.cycles = 0"]);
    assert_eq!(at("13s"), ["Ctrl.step = CraneStep#Down1", "Sim.cycles = 0"]);
    assert_eq!(at("17s"), ["Ctrl.step = CraneStep#Wait", "Sim.cycles = 0"]);
    assert_eq!(at("20s"), ["Ctrl.step = CraneStep#Up2", "Sim.cycles = 0"]);
    assert_eq!(at("26s"), ["Ctrl.step = CraneStep#Left", "Sim.cycles = 0"]);
    assert_eq!(at("31s"), ["Ctrl.step = CraneStep#Down2", "Sim.cycles = 0"]);
    // No new cycle without a new press.
    assert_eq!(at("60s"), ["Ctrl.step = CraneStep#Rest1", "Sim.cycles = 1"]);
}

#[test]
fn crane_outputs_are_off_at_rest_and_never_collide() {
    let out = run_crane(
        "60s",
        &[
            "Ctrl.M1S",
            "Ctrl.M1D",
            "Ctrl.M2S",
            "Ctrl.M2J",
            "Sim.collision",
        ],
    );
    assert_eq!(
        out,
        [
            "Ctrl.M1S = FALSE",
            "Ctrl.M1D = FALSE",
            "Ctrl.M2S = FALSE",
            "Ctrl.M2J = FALSE",
            "Sim.collision = FALSE"
        ]
    );
}
