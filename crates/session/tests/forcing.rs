//! Every forcing rule with exact per-scan values: a forced variable holds
//! for the program, a forced input beats the plant, a forced output beats
//! the program and reaches the plant, a release restores normal behaviour
//! at the next scan, and what only the compiler or a chart may change is
//! refused.

mod support;

use automat_session::{Control, Error};
use support::{get, project, series, source, step};

const COUNTER: &str = "PROGRAM Main
VAR
    x : INT;
    y : INT;
    k : INT := 5;
END_VAR
VAR CONSTANT
    LIMIT : INT := 100;
END_VAR
    x := x + 1;
    y := x * 2;
END_PROGRAM
";

#[test]
fn a_forced_internal_holds_before_and_after_every_run() {
    let s = source(COUNTER);
    assert_eq!(series(&s, "x", 3), ["1", "2", "3"]);
    s.force("x", "10").unwrap();
    // Shown forced at once (between scans), before any scan ran.
    assert_eq!(get(&s, "x"), "10");
    assert_eq!(s.forces(), [("x".to_string(), "10".to_string())]);
    // The program computes from the forced value (y = 11 * 2), but its
    // own assignment x := 11 never shows: x stays 10 every scan.
    assert_eq!(series(&s, "x", 3), ["10", "10", "10"]);
    assert_eq!(get(&s, "y"), "22");
    s.unforce("x").unwrap();
    assert!(s.forces().is_empty());
    // Released: counting resumes from the forced value at the next scan.
    assert_eq!(series(&s, "x", 3), ["11", "12", "13"]);
    assert_eq!(get(&s, "y"), "26");
}

#[test]
fn a_write_is_one_shot_and_a_force_beats_it() {
    let s = source(COUNTER);
    step(&s, 2);
    s.write("x", "100").unwrap();
    assert_eq!(get(&s, "x"), "100");
    assert_eq!(series(&s, "x", 2), ["101", "102"]);
    s.force("y", "7").unwrap();
    s.write("y", "8").unwrap();
    assert_eq!(get(&s, "y"), "7");
    assert_eq!(series(&s, "y", 2), ["7", "7"]);
    s.unforce_all().unwrap();
    // x counted on meanwhile (103, 104): y = 105 * 2.
    assert_eq!(series(&s, "y", 1), ["210"]);
}

#[test]
fn constants_and_bad_values_are_refused_with_the_expected_type() {
    let s = source(COUNTER);
    assert_eq!(
        s.force("LIMIT", "1"),
        Err(Error::ReadOnly(
            "`LIMIT` is a CONSTANT and cannot be written or forced".into()
        ))
    );
    assert_eq!(
        s.write("LIMIT", "1"),
        Err(Error::ReadOnly(
            "`LIMIT` is a CONSTANT and cannot be written or forced".into()
        ))
    );
    match s.write("k", "TRUE") {
        Err(Error::Value(m)) => {
            assert!(m.starts_with("`k`: expected a value of type INT: "), "{m}")
        }
        other => panic!("{other:?}"),
    }
    match s.force("nope", "1") {
        Err(Error::Path(m)) => assert!(m.contains("unknown variable `nope`"), "{m}"),
        other => panic!("{other:?}"),
    }
    assert_eq!(
        s.unforce("k"),
        Err(Error::Refused("this location is not forced".into()))
    );
}

#[test]
fn crane_forced_input_beats_the_plant() {
    let s = project("crane");
    step(&s, 1);
    // At rest bottom-left: the plant says l1 and l3.
    assert_eq!(get(&s, "Ctrl.l1"), "TRUE");
    s.force("Ctrl.l1", "FALSE").unwrap();
    assert_eq!(series(&s, "Ctrl.l1", 3), ["FALSE", "FALSE", "FALSE"]);
    // A press of Pornire (forced for two scans: the plant writes the
    // button each scan) does not start cycle 1: the program sees l1 FALSE.
    s.force("Ctrl.Pornire", "1").unwrap();
    step(&s, 2);
    s.unforce("Ctrl.Pornire").unwrap();
    assert_eq!(series(&s, "Ctrl.GS1.X", 2), ["TRUE", "TRUE"]);
    assert_eq!(get(&s, "Ctrl.M2S"), "FALSE");
    // Released: the plant's value is back at the next scan.
    s.unforce("Ctrl.l1").unwrap();
    assert_eq!(series(&s, "Ctrl.l1", 1), ["TRUE"]);
    // The same force by address is the same location as by name.
    s.force("%IX1.2", "0").unwrap();
    s.force("Ctrl.l1", "FALSE").unwrap();
    assert_eq!(s.forces(), [("Ctrl.l1".to_string(), "FALSE".to_string())]);
    assert_eq!(get(&s, "%IX1.2"), "FALSE");
}

#[test]
fn crane_forced_output_beats_the_program_and_reaches_the_plant() {
    let s = project("crane");
    step(&s, 1);
    s.force("Ctrl.M2S", "TRUE").unwrap();
    // In step 1 the program drives M2S FALSE every scan; forced, it reads
    // TRUE after every scan, and the plant lifts the hook: it reads the
    // forced actuator at the start of each scan and moves through the 10 ms
    // before it, 1 m/s; l1 is on up to 0.05 m, so off at 60 mm, the sixth
    // scan with the motor on.
    let m2s = series(&s, "Ctrl.M2S", 1);
    assert_eq!(m2s, ["TRUE"]);
    let l1 = series(&s, "Ctrl.l1", 7);
    assert_eq!(
        l1,
        ["TRUE", "TRUE", "TRUE", "TRUE", "FALSE", "FALSE", "FALSE"]
    );
    assert_eq!(get(&s, "Ctrl.M2S"), "TRUE");
    assert_eq!(get(&s, "%QX3.3"), "TRUE");
    assert_eq!(get(&s, "Ctrl.GS1.X"), "TRUE");
    // Released: normal behaviour, and here no step writes M2S (an ISaGRAF
    // boolean action writes when its step is entered or left), so it keeps
    // its value until a one-shot write stops the hook.
    s.unforce("Ctrl.M2S").unwrap();
    assert!(s.forces().is_empty());
    assert_eq!(series(&s, "Ctrl.M2S", 1), ["TRUE"]);
    s.write("Ctrl.M2S", "FALSE").unwrap();
    assert_eq!(series(&s, "Ctrl.M2S", 2), ["FALSE", "FALSE"]);
    assert_eq!(series(&s, "Ctrl.l1", 3), ["FALSE", "FALSE", "FALSE"]);
}

#[test]
fn crane_forced_output_holds_against_the_chart() {
    let s = project("crane");
    step(&s, 1);
    s.force("Ctrl.M2S", "FALSE").unwrap();
    // A press starts cycle 1: step GS2 is entered and its action sets M2S;
    // forced FALSE, neither the program nor the plant sees it: the hook
    // stays down, l1 on, and the chart waits in GS2 for l2.
    s.force("Ctrl.Pornire", "TRUE").unwrap();
    step(&s, 2);
    s.unforce("Ctrl.Pornire").unwrap();
    assert_eq!(get(&s, "Ctrl.GS2.X"), "TRUE");
    assert_eq!(series(&s, "Ctrl.M2S", 3), ["FALSE", "FALSE", "FALSE"]);
    assert_eq!(series(&s, "Ctrl.l1", 20), vec!["TRUE"; 20]);
    assert_eq!(get(&s, "Ctrl.GS2.X"), "TRUE");
    assert_eq!(get(&s, "%QX3.3"), "FALSE");
}

#[test]
fn crane_step_flags_step_times_and_constants_are_refused() {
    let s = project("crane");
    for (path, what) in [("Ctrl.GS1.x", "a step flag"), ("Ctrl.GS5.t", "a step time")] {
        assert_eq!(
            s.force(path, "TRUE"),
            Err(Error::ReadOnly(format!(
                "`{path}` is {what}; only the program's chart changes it, it cannot be written or forced"
            )))
        );
    }
    assert_eq!(
        s.write("Ctrl.DWELL_TIME", "T#1s"),
        Err(Error::ReadOnly(
            "`Ctrl.DWELL_TIME` is a CONSTANT and cannot be written or forced".into()
        ))
    );
    match s.force("Ctrl.M1S", "2") {
        Err(Error::Value(m)) => assert!(
            m.starts_with("`Ctrl.M1S`: expected a value of type BOOL: "),
            "{m}"
        ),
        other => panic!("{other:?}"),
    }
}

#[test]
fn run_control_start_stop_step_and_restarts() {
    let s = source(COUNTER);
    assert_eq!(s.snapshot().state.name(), "stopped");
    step(&s, 5);
    let snap = s.snapshot();
    assert_eq!((snap.scans, snap.plc_time_ns), (5, 40_000_000));
    assert_eq!(get(&s, "x"), "5");
    s.write("k", "9").unwrap();
    s.control(Control::WarmRestart).unwrap();
    // No RETAIN variables: a warm restart is a cold one here; PLC time goes on.
    assert_eq!(get(&s, "x"), "0");
    assert_eq!(get(&s, "k"), "5");
    step(&s, 1);
    assert_eq!(s.snapshot().plc_time_ns, 50_000_000);
    s.control(Control::Start).unwrap();
    assert_eq!(s.snapshot().state.name(), "running");
    s.control(Control::Stop).unwrap();
    let stopped = s.snapshot().scans;
    assert_eq!(s.snapshot().state.name(), "stopped");
    std::thread::sleep(std::time::Duration::from_millis(30));
    assert_eq!(s.snapshot().scans, stopped);
    let end = s.shutdown().unwrap();
    assert_eq!(end.snapshot.scans, stopped);
}

#[test]
fn a_fault_is_reported_with_its_site_and_a_restart_recovers() {
    let s = source(
        "PROGRAM Main
VAR
    d : INT := 1;
    q : INT;
    n : INT;
END_VAR
    n := n + 1;
    q := 10 / d;
END_PROGRAM
",
    );
    step(&s, 2);
    s.write("d", "0").unwrap();
    match s.control(Control::Step(1)) {
        Err(Error::Refused(m)) => assert!(m.starts_with("runtime fault: "), "{m}"),
        other => panic!("{other:?}"),
    }
    let snap = s.snapshot();
    match &snap.state {
        automat_session::State::Fault { message, site } => {
            assert_eq!(message, "division by zero (10 / 0)");
            assert!(site.contains("main.st:8:"), "{site}");
            assert!(
                site.ends_with(":8:10 in Main (task Main, program instance Main, PLC time T#20ms)"),
                "{site}"
            );
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(
        s.control(Control::Start),
        Err(Error::Refused(
            "the PLC is in fault: cold_restart or warm_restart starts it again".into()
        ))
    );
    s.control(Control::ColdRestart).unwrap();
    assert_eq!(s.snapshot().state.name(), "stopped");
    assert_eq!(get(&s, "d"), "1");
    step(&s, 1);
    assert_eq!(get(&s, "n"), "1");
    assert_eq!(get(&s, "q"), "10");
    // PLC time went on past the fault at 20 ms.
    assert_eq!(s.snapshot().plc_time_ns, 30_000_000);
}

#[test]
fn subscriptions_get_every_scan_or_a_decimated_period() {
    let s = source(COUNTER);
    let (tx, rx) = std::sync::mpsc::channel();
    s.subscribe(
        &["x".to_string()],
        0,
        Box::new(move |u| tx.send((u.plc_time_ns, u.values[0].1.clone())).is_ok()),
    )
    .unwrap();
    let (tx2, rx2) = std::sync::mpsc::channel();
    s.subscribe(
        &["x".to_string()],
        30_000_000,
        Box::new(move |u| tx2.send(u.plc_time_ns).is_ok()),
    )
    .unwrap();
    step(&s, 7);
    let every: Vec<(i64, String)> = rx.try_iter().collect();
    assert_eq!(every.len(), 7);
    assert_eq!(every[0], (0, "1".to_string()));
    assert_eq!(every[6], (60_000_000, "7".to_string()));
    let decimated: Vec<i64> = rx2.try_iter().collect();
    assert_eq!(decimated, [0, 30_000_000, 60_000_000]);
    assert!(s
        .subscribe(&["nope".to_string()], 0, Box::new(|_| true))
        .is_err());
}

#[test]
fn symbols_are_a_tree_with_types_and_writability() {
    let s = project("crane");
    let tree = s.symbols("Ctrl").unwrap();
    assert_eq!(tree.len(), 1);
    let ctrl = &tree[0];
    let child = |n: &automat_session::Node, name: &str| {
        n.children
            .iter()
            .find(|c| c.name.eq_ignore_ascii_case(name))
            .unwrap_or_else(|| panic!("no {name} under {}", n.path))
            .clone()
    };
    let m1s = child(ctrl, "M1S");
    assert_eq!((m1s.ty.as_str(), m1s.writable), ("BOOL", true));
    let dwell = child(ctrl, "DWELL_TIME");
    assert_eq!((dwell.ty.as_str(), dwell.writable), ("TIME", false));
    let gs1 = child(ctrl, "GS1");
    assert!(gs1.children.iter().all(|c| !c.writable));
    assert_eq!(gs1.ty, "STEP");
    let x = child(&gs1, "X");
    assert_eq!(x.ty, "BOOL");
    assert!(!gs1.children.iter().any(|c| c.name.starts_with("__")));
    let edge = child(ctrl, "startEdge");
    assert_eq!(edge.ty, "R_TRIG");
    let q = child(&edge, "Q");
    assert_eq!((q.path.as_str(), q.writable), ("Ctrl.startEdge.Q", true));
    let sub = s.symbols("ctrl.startedge").unwrap();
    assert_eq!(sub[0].path, "Ctrl.startEdge");
    assert!(s.symbols("Nope").is_err());
}

#[test]
fn a_warm_restart_keeps_retain_variables_and_a_cold_one_does_not() {
    let s = source(
        "PROGRAM Main
VAR RETAIN
    r : INT;
END_VAR
VAR
    n : INT;
END_VAR
    r := r + 1;
    n := n + 1;
END_PROGRAM
",
    );
    step(&s, 3);
    s.control(Control::WarmRestart).unwrap();
    assert_eq!(
        (get(&s, "r"), get(&s, "n")),
        ("3".to_string(), "0".to_string())
    );
    step(&s, 1);
    assert_eq!(
        (get(&s, "r"), get(&s, "n")),
        ("4".to_string(), "1".to_string())
    );
    s.control(Control::ColdRestart).unwrap();
    assert_eq!(
        (get(&s, "r"), get(&s, "n")),
        ("0".to_string(), "0".to_string())
    );
}

#[test]
fn crane_moves_on_after_stop_and_start_in_the_middle_of_a_step() {
    let s = project("crane");
    step(&s, 1);
    s.force("Ctrl.Pornire", "1").unwrap();
    step(&s, 2);
    s.unforce("Ctrl.Pornire").unwrap();
    step(&s, 5);
    assert_eq!(get(&s, "Ctrl.GS2.X"), "TRUE");
    assert_eq!(get(&s, "Ctrl.M2S"), "TRUE");
    // STOP: the motor is off and the plant stands.
    s.control(Control::Stop).unwrap();
    assert_eq!(get(&s, "Ctrl.M2S"), "FALSE");
    // Going on in GS2, the motor runs again (the chart's N action set it
    // at the step's activation, long before) and the crane reaches the
    // top (l2), where GS2 hands over to GS3.
    step(&s, 1);
    assert_eq!(get(&s, "Ctrl.M2S"), "TRUE");
    let mut scans = 0;
    while get(&s, "Ctrl.GS2.X") == "TRUE" && scans < 10_000 {
        step(&s, 10);
        scans += 10;
    }
    assert_eq!(get(&s, "Ctrl.GS3.X"), "TRUE", "after {scans} scans");
    assert_eq!(get(&s, "Ctrl.l2"), "TRUE");
}
