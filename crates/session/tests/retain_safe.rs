//! The session's RETAIN file and safe state: saves from end-of-scan
//! snapshots only (also after a fault), a warm restart from the last
//! completed scan, the safe state on a `stop` command and at the end.

mod support;

use automat_ir::Program;
use automat_runtime::retain::{self, Loaded};
use automat_session::{Control, RetainFile};
use support::*;

/// `r` (RETAIN) counts scans; `q := 10 / d` faults when `d` is written 0,
/// after `r` was incremented in that scan.
const COUNTED: &str = "PROGRAM Main
VAR RETAIN
    r : INT;
END_VAR
VAR
    d : INT := 1;
    q : INT;
END_VAR
VAR_OUTPUT
    lamp : BOOL;
END_VAR
    r := r + 1;
    lamp := TRUE;
    q := 10 / d;
END_PROGRAM
";

/// The value of `r` in a RETAIN file, loaded into a fresh image.
fn saved_r(program: &Program, file: &std::path::Path) -> String {
    let mut image = program.initial_image.clone();
    assert_eq!(retain::load(program, file, &mut image), Loaded::Warm);
    let place = automat_runtime::resolve(program, "r").expect("r");
    automat_runtime::value::format(&image, &place)
}

#[test]
fn the_retain_file_holds_the_last_completed_scan_also_after_a_fault() {
    let file = temp_dir("retain-fault").join("plc.retain");
    let _ = std::fs::remove_file(&file);
    let mut cfg = config();
    cfg.retain = Some(RetainFile {
        path: file.clone(),
        every_ns: None,
    });
    let s = source_with(COUNTED, cfg);
    step(&s, 2);
    s.write("d", "0").unwrap();
    assert!(s.control(Control::Step(1)).is_err());
    // The faulted scan incremented r before its division.
    assert_eq!(get(&s, "r"), "3");
    let program = s.program().clone();
    let end = s.shutdown().unwrap();
    let saves = end.retain.expect("a RETAIN file was kept");
    assert_eq!(saves.last, Ok(()));
    assert_eq!((saves.failures, saves.last_error), (0, None));
    assert!(end
        .fault
        .as_deref()
        .is_some_and(|f| f.contains("division by zero")));
    assert_eq!(saved_r(&program, &file), "2");
}

#[test]
fn periodic_saves_follow_plc_time_and_the_final_save_the_last_scan() {
    let file = temp_dir("retain-periodic").join("plc.retain");
    let _ = std::fs::remove_file(&file);
    let mut cfg = config();
    cfg.retain = Some(RetainFile {
        path: file.clone(),
        every_ns: Some(30_000_000),
    });
    let s = source_with(COUNTED, cfg);
    let program = s.program().clone();
    // Scans at 0, 10, 20 ms: not yet 30 ms after the first.
    step(&s, 3);
    assert!(!file.exists());
    // The scan at 30 ms saves (the virtual clock saves in the scan).
    step(&s, 1);
    assert_eq!(saved_r(&program, &file), "4");
    step(&s, 2);
    assert_eq!(saved_r(&program, &file), "4");
    let end = s.shutdown().unwrap();
    assert_eq!(end.retain.map(|r| r.last), Some(Ok(())));
    assert_eq!(end.fault, None);
    assert_eq!(saved_r(&program, &file), "6");
}

#[test]
fn a_warm_restart_after_a_fault_keeps_the_last_completed_scans_retain_values() {
    let s = source(COUNTED);
    step(&s, 2);
    s.write("d", "0").unwrap();
    assert!(s.control(Control::Step(1)).is_err());
    assert_eq!(get(&s, "r"), "3");
    s.control(Control::WarmRestart).unwrap();
    assert_eq!((get(&s, "r"), get(&s, "d")), ("2".into(), "1".into()));
    // A write between scans is a consistent state: a warm restart keeps it.
    s.write("r", "40").unwrap();
    s.control(Control::WarmRestart).unwrap();
    assert_eq!(get(&s, "r"), "40");
    step(&s, 1);
    assert_eq!(get(&s, "r"), "41");
}

#[test]
fn a_stop_command_holds_the_outputs_in_the_safe_state_and_a_step_does_not() {
    let s = source(COUNTED);
    step(&s, 1);
    // A step is a debugging pause: the outputs stay as the scan left them.
    assert_eq!(get(&s, "lamp"), "TRUE");
    s.control(Control::Stop).unwrap();
    assert_eq!(get(&s, "lamp"), "FALSE");
    step(&s, 1);
    assert_eq!(get(&s, "lamp"), "TRUE");
    // The session's end is a stop too: the final image is safe.
    let program = s.program().clone();
    let end = s.shutdown().unwrap();
    let place = automat_runtime::resolve(&program, "lamp").expect("lamp");
    assert_eq!(automat_runtime::value::format(&end.image, &place), "FALSE");
    assert_eq!(end.retain.map(|r| r.last), None);
}

/// `lamp`, `valve` and `level` are set once, when `go` comes: stored
/// outputs, as a step's S action or an edge-driven output is.
const LATCHED: &str = "PROGRAM Main
VAR_OUTPUT
    lamp : BOOL;
    valve : BOOL;
    level : INT;
END_VAR
VAR
    go : BOOL;
    done : BOOL;
END_VAR
    IF go AND NOT done THEN
        lamp := TRUE;
        valve := TRUE;
        level := 42;
        done := TRUE;
    END_IF;
END_PROGRAM
";

#[test]
fn leaving_a_stop_gives_the_outputs_back_their_program_values() {
    let s = source(LATCHED);
    s.write("go", "TRUE").unwrap();
    step(&s, 3);
    let outputs = ["lamp", "valve", "level"];
    let now = |s: &automat_session::Session| outputs.map(|p| get(s, p));
    assert_eq!(now(&s), ["TRUE", "TRUE", "42"]);
    s.control(Control::Stop).unwrap();
    assert_eq!(now(&s), ["FALSE", "FALSE", "0"]);
    // A second stop keeps the values held at the first.
    s.control(Control::Stop).unwrap();
    // A write made while stopped wins over the held value.
    s.write("valve", "FALSE").unwrap();
    step(&s, 1);
    // The program did not set lamp again (done is TRUE): the STOP did not
    // change the program's memory, only what the outside saw meanwhile.
    assert_eq!(now(&s), ["TRUE", "FALSE", "42"]);
    // The same through start.
    s.control(Control::Stop).unwrap();
    assert_eq!(get(&s, "lamp"), "FALSE");
    s.control(Control::Start).unwrap();
    s.control(Control::Stop).unwrap();
    step(&s, 1);
    assert_eq!(get(&s, "lamp"), "TRUE");
}

#[test]
fn a_restart_while_stopped_forgets_the_held_outputs() {
    let s = source(LATCHED);
    s.write("go", "TRUE").unwrap();
    step(&s, 2);
    s.control(Control::Stop).unwrap();
    s.control(Control::ColdRestart).unwrap();
    step(&s, 1);
    // Cold: go is FALSE again, nothing sets lamp.
    assert_eq!(get(&s, "lamp"), "FALSE");
    assert_eq!(get(&s, "level"), "0");
}
