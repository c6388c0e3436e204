//! Project-file and scenario diagnostics (E300–E349): one fixture per code
//! under `tests/projects/` (named after the codes it triggers), and every
//! E3xx code of the table has one (the front-end corpus leaves them to us).

use automat_base::Code;
use std::path::{Path, PathBuf};
use std::process::Command;

fn projects() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/projects")
}

fn automat(args: &[&str]) -> (Option<i32>, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_automat"))
        .current_dir(projects())
        .args(args)
        .output()
        .expect("run automat");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn project_file_errors_point_into_automat_toml() {
    let cases = [
        ("e300_bad_toml", "e300_bad_toml/automat.toml:2:8: error[E300]: invalid project file: invalid type: integer `5`, expected a string"),
        ("e301_unknown_model", "e301_unknown_model/automat.toml:6:9: error[E301]: unknown plant model `kran`"),
        ("e302_unknown_signal", "e302_unknown_signal/automat.toml:9:1: error[E302]: the crane model has no signal `Start`"),
        ("e303_unknown_variable", "e303_unknown_variable/automat.toml:9:7: error[E303]: signal `M1S` is bound to `Ctrl.nothing`: "),
        ("e304_type_mismatch", "e304_type_mismatch/automat.toml:9:7: error[E304]: signal `M1S` is BOOL but `Ctrl.GS5.t` is TIME"),
        ("e305_e306_unbound", "e305_e306_unbound/automat.toml:5:9: error[E305]: actuator `M2J` of the crane model is bound to nothing"),
        ("e305_e306_unbound", "e305_e306_unbound/automat.toml:5:9: warning[E306]: sensor `l4` of the crane model is bound to nothing"),
        ("e307_bad_param", "e307_bad_param/automat.toml:9:1: error[E307]: plant parameter `depth` refused: crane: unknown parameter `depth`"),
        ("e308_no_sources", "e308_no_sources/automat.toml:3:12: error[E308]: source `nothing.st`: no such file or folder"),
        ("e340_bad_modbus", "e340_bad_modbus/automat.toml:9:10: error[E340]: listen: `nowhere` is not PORT or ADDR:PORT"),
        ("e341_modbus_unknown", "e341_modbus_unknown/automat.toml:12:7: error[E341]: unknown variable `Ctrl.nothing`"),
        ("e342_modbus_type", "e342_modbus_type/automat.toml:12:7: error[E342]: `Ctrl.l1` is BOOL: registers take one elementary value of 8 to 64 bits"),
        ("e343_modbus_overlap", "e343_modbus_overlap/automat.toml:19:11: error[E343]: discrete_inputs address 100 is mapped twice: to `Ctrl.l1` and to `Ctrl.l2`"),
        ("e344_modbus_constant", "e344_modbus_constant/automat.toml:12:7: error[E344]: `Ctrl.DWELL_TIME` is a CONSTANT: clients would write it as holding_registers"),
        ("e345_modbus_serial", "e345_modbus_serial/automat.toml:10:8: error[E345]: baud 10 is outside 50..=4000000"),
        ("e346_bad_opcua", "e346_bad_opcua/automat.toml:9:10: error[E346]: listen: `nowhere` is not PORT or ADDR:PORT"),
    ];
    for (dir, want) in cases {
        let (code, _, err) = automat(&["run", dir, "--cycles", "1"]);
        assert_eq!(code, Some(1), "{dir}: {err}");
        assert!(
            err.lines().any(|l| l.starts_with(want)),
            "{dir}: want `{want}` in\n{err}"
        );
    }
}

/// A plant written in ST (E310–E315): each error at its place, in
/// automat.toml or in the plant's own file.
#[test]
fn st_plant_errors_point_into_their_files() {
    let cases = [
        ("e310_plant_unreadable", "e310_plant_unreadable/automat.toml:6:11: error[E310]: cannot read the plant program `e310_plant_unreadable/missing.st`: "),
        ("e311_no_plant_program", "e311_no_plant_program/plant.st:1:1: error[E311]: the plant program `plant.st` has no PROGRAM"),
        ("e312_e313_unbound_plant_signals", "e312_e313_unbound_plant_signals/plant.st:3:5: error[E312]: VAR_INPUT `pump` of the plant program `plant.st` is bound to nothing: the controller has no variable `pump` and [bind] has no entry for it"),
        ("e312_e313_unbound_plant_signals", "e312_e313_unbound_plant_signals/plant.st:6:5: warning[E313]: VAR_OUTPUT `level` of the plant program `plant.st` is bound to nothing: the controller does not see it"),
        ("e314_plant_signal_type", "e314_plant_signal_type/plant.st:7:5: error[E314]: plant signal `state` is no BOOL, integer, bit string, enumeration or real"),
        ("e315_plant_operator", "e315_plant_operator/automat.toml:7:14: error[E315]: operator `Start` is no VAR_OUTPUT of `plant.st`"),
    ];
    for (dir, want) in cases {
        let (code, _, err) = automat(&["run", dir, "--cycles", "1"]);
        assert_eq!(code, Some(1), "{dir}: {err}");
        assert!(
            err.lines().any(|l| l.starts_with(want)),
            "{dir}: want `{want}` in\n{err}"
        );
    }
}

/// A plant program that faults freezes the plant, and the scenario fails
/// on it with the fault's place in the plant file.
#[test]
fn a_faulting_plant_program_fails_the_scenario() {
    let out_dir = std::env::temp_dir().join(format!("automat-stfault-{}", std::process::id()));
    let (code, out, _) = automat(&[
        "test",
        "st_plant_fault",
        "--out",
        out_dir.to_str().unwrap_or("."),
    ]);
    assert_eq!(code, Some(1), "{out}");
    assert!(
        out.contains("    st_plant_fault/scenarios/fault.scn: the plant\n      failed at T#500ms: the plant program stopped at plant time 500 ms: st_plant_fault/plant.st:14:10: fault in Tank: division by zero (50 / 0)\n"),
        "{out}"
    );
    assert_eq!(out.lines().last(), Some("0 passed, 1 failed"));
}

#[test]
fn scenario_errors_point_into_the_scenario() {
    let (code, out, _) = automat(&["test", "scenarios_e32x", "orphan_e324"]);
    // Scenarios that cannot run are errors: exit 2.
    assert_eq!(code, Some(2));
    for want in [
        "scenarios_e32x/scenarios/e320_syntax.scn:2:7: error[E320]: unknown action `jump`",
        "scenarios_e32x/scenarios/e321_unknown.scn:2:14: error[E321]: `Nothing` is no signal of the crane model",
        "scenarios_e32x/scenarios/e322_mismatch.scn:2:13: error[E322]: `l1` is not a BOOL operator signal",
        "scenarios_e32x/scenarios/e323_no_duration.scn:1:1: error[E323]: the scenario has no `duration` line",
        "orphan_e324/e324_orphan.scn:1:1: error[E324]: the scenario is in no project folder",
    ] {
        assert!(out.lines().any(|l| l.trim_start().starts_with(want)), "want `{want}` in\n{out}");
    }
    assert_eq!(out.lines().last(), Some("0 passed, 0 failed, 5 errors"));
}

/// A project without [plant]: what needs a plant is E325, functions out of
/// place E326, arithmetic on the wrong types E322; every diagnostic of a
/// file is reported, in the file's order.
#[test]
fn scenario_errors_without_a_plant() {
    let (code, out, _) = automat(&["test", "no_plant_e325_e326", "--jobs", "3"]);
    assert_eq!(code, Some(2), "{out}");
    let mut last = 0;
    for want in [
        "ERROR no_plant_e325_e326/scenarios/e322_arith.scn",
        "no_plant_e325_e326/scenarios/e322_arith.scn:2:15: error[E322]: `+` does not apply to a TIME and a number",
        "no_plant_e325_e326/scenarios/e322_arith.scn:3:6: error[E322]: `+` does not apply to BOOL and a number",
        "ERROR no_plant_e325_e326/scenarios/e325_needs_plant.scn",
        "no_plant_e325_e326/scenarios/e325_needs_plant.scn:2:13: error[E325]: `stuck` needs a plant model, and the project has no [plant]",
        "no_plant_e325_e326/scenarios/e325_needs_plant.scn:3:14: error[E325]: `plant.x` needs a plant model, and the project has no [plant]",
        "no_plant_e325_e326/scenarios/e326_misplaced.scn:2:8: error[E326]: count(...) counts over a window: use it in `expect C during A..B`, `expect at T C` or `expect always C [during A..B]`",
        "no_plant_e325_e326/scenarios/e326_misplaced.scn:3:20: error[E326]: prev(...) inside rise, fall, change or prev",
    ] {
        let at = out.lines().position(|l| l.trim_start().starts_with(want));
        assert!(at.is_some_and(|i| i >= last), "want `{want}` (in this order) in\n{out}");
        last = at.unwrap_or(0);
    }
    assert_eq!(out.lines().last(), Some("0 passed, 0 failed, 3 errors"));
}

#[test]
fn every_project_code_has_a_fixture() {
    let mut names = Vec::new();
    let mut stack = vec![projects()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).expect("fixtures").flatten() {
            let p = e.path();
            names.push(
                p.file_name()
                    .map(|n| n.to_string_lossy().to_lowercase())
                    .unwrap_or_default(),
            );
            if p.is_dir() {
                stack.push(p);
            }
        }
    }
    let missing: Vec<&str> = Code::ALL
        .iter()
        .map(|c| c.as_str())
        .filter(|c| c.starts_with("E3"))
        .filter(|c| !names.iter().any(|n| n.contains(&c.to_lowercase())))
        .collect();
    assert!(
        missing.is_empty(),
        "no fixture under tests/projects for {missing:?}"
    );
}

/// A fault stops the PLC in its safe state, and the plant sees it: the crane
/// hoists at 1 m/s until the fault in the scan at 200 ms (the model, a scan
/// behind the outputs, is then at 0.2 m), and with every actuator off it
/// stays there until the run's end at 1 s: the safe state set the variable
/// bound to M2S (a program variable, not an output) to FALSE as well.
/// (Seeing it TRUE, the hoist would be at 1 m.)
#[test]
fn on_a_fault_the_plant_sees_every_actuator_off() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/fault_safe_state");
    let out = Command::new(env!("CARGO_BIN_EXE_automat"))
        .args(["run", dir.to_str().unwrap_or("."), "--duration", "1s"])
        .args(["--print", "plant.y", "--print", "M2S", "--print", "Ctrl.n"])
        .output()
        .expect("run automat");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{stdout}{stderr}");
    assert_eq!(
        stdout, "plant.y = 0.2\nM2S = FALSE\nCtrl.n = 0\n",
        "{stderr}"
    );
    assert!(
        stderr.ends_with(
            "note: the PLC stopped in its safe state: 4 outputs (M1S, M1D, M2S, M2J) set to 0/FALSE\n"
        ),
        "{stderr}"
    );
    assert!(
        stderr.contains("ctrl.st:12:10: fault in Ctrl: division by zero (1 / 0) (task Ctrl, program instance Ctrl, PLC time T#200ms)\n"),
        "{stderr}"
    );
}

/// The same program with `[safe_state] M2S = true`: the hoist motor's safe
/// value is TRUE, so the plant keeps hoisting after the fault at 200 ms and
/// reaches 1 m at 1 s; every other actuator is FALSE.
#[test]
fn configured_safe_values_reach_the_plant() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/fault_safe_values");
    let out = Command::new(env!("CARGO_BIN_EXE_automat"))
        .args(["run", dir.to_str().unwrap_or("."), "--duration", "1s"])
        .args(["--print", "plant.y", "--print", "M2S", "--print", "M1S"])
        .args(["--print", "M1D", "--print", "M2J"])
        .output()
        .expect("run automat");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{stdout}{stderr}");
    assert_eq!(
        stdout, "plant.y = 1\nM2S = TRUE\nM1S = FALSE\nM1D = FALSE\nM2J = FALSE\n",
        "{stderr}"
    );
    assert!(
        stderr.ends_with(
            "note: the PLC stopped in its safe state: 3 outputs (M1S, M1D, M2J) set to 0/FALSE; M2S set to TRUE\n"
        ),
        "{stderr}"
    );
}

/// `[retain]` of a project: the file (relative to the project folder) is
/// kept across runs; a folder that does not exist stops the run before the
/// first scan (exit 2) unless `optional = true`; a bad `[safe_state]`
/// entry is E300 at its key.
#[test]
fn project_retain_table_and_safe_state_errors() {
    let dir = std::env::temp_dir().join(format!("automat-project-retain-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    let src = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/fault_safe_state/ctrl.st"),
    )
    .expect("fixture");
    // No fault, and a RETAIN counter.
    let src = src.replace("    n := 1 / zero;\n", "").replace(
        "END_VAR\nM2S",
        "END_VAR\nVAR RETAIN runs : INT; END_VAR\nruns := runs + 1;\nM2S",
    );
    std::fs::write(dir.join("ctrl.st"), src).expect("write");
    let toml = |retain: &str| {
        std::fs::write(
            dir.join("automat.toml"),
            format!("[project]\nname = \"r\"\n[plant]\nmodel = \"crane\"\n{retain}"),
        )
        .expect("write toml");
    };
    let run = || {
        let out = Command::new(env!("CARGO_BIN_EXE_automat"))
            .args([
                "run",
                dir.to_str().unwrap_or("."),
                "--cycles",
                "3",
                "--print",
                "Ctrl.runs",
            ])
            .output()
            .expect("run automat");
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stdout).into_owned(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    toml("[retain]\nfile = \"plc.retain\"\nsave_every = \"10ms\"\n");
    assert_eq!(run(), (Some(0), "Ctrl.runs = 3\n".into(), String::new()));
    assert_eq!(run(), (Some(0), "Ctrl.runs = 6\n".into(), String::new()));
    assert!(dir.join("plc.retain").is_file());

    toml("[retain]\nfile = \"missing/plc.retain\"\n");
    let (code, out, err) = run();
    assert_eq!((code, out.as_str()), (Some(2), ""), "{err}");
    assert!(err.starts_with("error: RETAIN file "), "{err}");
    toml("[retain]\nfile = \"missing/plc.retain\"\noptional = true\n");
    let (code, out, err) = run();
    assert_eq!((code, out.as_str()), (Some(0), "Ctrl.runs = 3\n"), "{err}");
    assert!(err.starts_with("warning: RETAIN file "), "{err}");

    toml("[safe_state]\n\"Ctrl.nope\" = true\n");
    let (code, _, err) = run();
    assert_eq!(code, Some(1), "{err}");
    assert!(
        err.contains("automat.toml:6:1: error[E300]: [safe_state] `Ctrl.nope`: "),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
