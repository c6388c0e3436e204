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

/// The steps of the chart (Table 5.2: step n is `GSn`) that are active at
/// the end of a run of `duration`, and the plant's cycle count.
fn active_steps(duration: &str) -> (Vec<String>, String) {
    let flags: Vec<String> = (1..=8).map(|n| format!("Ctrl.GS{n}.x")).collect();
    let mut vars: Vec<&str> = flags.iter().map(String::as_str).collect();
    vars.push("plant.cycles");
    let out = run_crane(duration, &vars);
    assert_eq!(out.len(), 9, "{out:?}");
    let active = out[..8]
        .iter()
        .filter_map(|l| l.strip_suffix(" = TRUE"))
        .map(str::to_string)
        .collect();
    (active, out[8].clone())
}

#[test]
fn crane_runs_cycle_one_waits_then_returns() {
    // Pornire is pressed at 0.5 s: up (5 s), right (5 s), down (5 s), 3 s dwell,
    // up, left, down, back at rest 1 after about 33.1 s. One step at a time.
    let at = |t: &str, step: &str, cycles: &str| {
        assert_eq!(
            active_steps(t),
            (vec![step.to_string()], cycles.to_string()),
            "at {t}"
        );
    };
    at("400ms", "Ctrl.GS1.x", "plant.cycles = 0");
    at("1s", "Ctrl.GS2.x", "plant.cycles = 0");
    at("8s", "Ctrl.GS3.x", "plant.cycles = 0");
    at("13s", "Ctrl.GS4.x", "plant.cycles = 0");
    at("17s", "Ctrl.GS5.x", "plant.cycles = 0");
    at("20s", "Ctrl.GS6.x", "plant.cycles = 0");
    at("26s", "Ctrl.GS7.x", "plant.cycles = 0");
    at("31s", "Ctrl.GS8.x", "plant.cycles = 0");
    // No new cycle without a new press.
    at("60s", "Ctrl.GS1.x", "plant.cycles = 1");
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
            // M1S stops in the scan after l3 (a chart's step changes its
            // outputs from the next scan): 2 cm past the 0.1 m switch point.
            "plant.x = 0.08",
            "l3 = TRUE"
        ]
    );
}
