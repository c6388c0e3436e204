//! Configurations: tasks, program instances, connections, access paths.

mod common;
use common::{analyze, check, clean};

const PROGS: &str = "PROGRAM Main
VAR_INPUT start : BOOL; END_VAR
VAR_OUTPUT busy : BOOL; END_VAR
VAR count : INT; t : TON; END_VAR
    busy := start;
END_PROGRAM
FUNCTION_BLOCK Valve
END_FUNCTION_BLOCK
";

#[test]
fn a_complete_configuration_checks_clean() {
    clean(&format!(
        "{PROGS}CONFIGURATION Cell
VAR_GLOBAL go : BOOL; state : BOOL; trig : BOOL; END_VAR
RESOURCE R ON PLC
    TASK Fast (INTERVAL := T#10ms, PRIORITY := 1);
    TASK Slow (INTERVAL := T#100ms, PRIORITY := 5);
    TASK Event (SINGLE := trig, PRIORITY := 2);
    PROGRAM m1 WITH Fast : Main (start := go, busy => state);
    PROGRAM m2 WITH Slow : Main;
END_RESOURCE
VAR_ACCESS
    acc_count : R.m1.count : INT READ_ONLY;
    acc_go : go : BOOL READ_WRITE;
    acc_q : R.m1.t.Q : BOOL;
END_VAR
END_CONFIGURATION"
    ));
}

#[test]
fn task_properties() {
    check(
        &format!(
            "{PROGS}CONFIGURATION C
VAR_GLOBAL i : INT; b : BOOL; END_VAR
RESOURCE R ON PLC
    TASK a (INTERVAL := 10, PRIORITY := 1);
    TASK b1 (INTERVAL := T#1s, PRIORITY := 1.5);
    TASK c (SINGLE := i);
    TASK d (INTERVAL := T#1s, INTERVAL := T#2s);
    TASK e (SPEED := 3);
    TASK a (PRIORITY := 2);
    TASK f (SINGLE := b, PRIORITY := 0);
END_RESOURCE
END_CONFIGURATION"
        ),
        &[
            ("E081", 12),
            ("E081", 13),
            ("E081", 14),
            ("E081", 15),
            ("E081", 16),
            ("E023", 17),
        ],
    );
}

#[test]
fn program_instances() {
    check(
        &format!(
            "{PROGS}CONFIGURATION C
VAR_GLOBAL g : BOOL; n : INT; END_VAR
RESOURCE R ON PLC
    TASK t (INTERVAL := T#10ms, PRIORITY := 1);
    PROGRAM p1 WITH t : Main;
    PROGRAM p2 WITH nope : Main;
    PROGRAM p3 WITH t : Valve;
    PROGRAM p4 WITH t : Missing;
    PROGRAM p1 WITH t : Main;
    PROGRAM p5 WITH t : Main (start := n);
    PROGRAM p6 WITH t : Main (zz := g);
    PROGRAM p7 WITH t : Main (busy := g);
    PROGRAM p8 WITH t : Main (start => g);
    PROGRAM p9 WITH t : Main (busy => n);
    PROGRAM p10 WITH t : Main (start := undefined_global);
END_RESOURCE
END_CONFIGURATION"
        ),
        &[
            ("E080", 14),
            ("E082", 15),
            ("E022", 16),
            ("E023", 17),
            ("E052", 18),
            ("E051", 19),
            ("E051", 20),
            ("E051", 21),
            ("E052", 22),
            ("E020", 23),
        ],
    );
}

#[test]
fn access_paths() {
    check(
        &format!(
            "{PROGS}CONFIGURATION C
VAR_GLOBAL g : BOOL; END_VAR
RESOURCE R ON PLC
    TASK t (INTERVAL := T#10ms, PRIORITY := 1);
    PROGRAM m WITH t : Main;
END_RESOURCE
VAR_ACCESS
    a1 : R.m.count : INT;
    a2 : R.m.nothing : INT;
    a3 : R.zz.count : INT;
    a4 : Nowhere.x : INT;
    a5 : R.m.count : BOOL;
    a6 : g : BOOL;
    a7 : R.m.t.ET : TIME;
    a8 : R.m.t.Nope : TIME;
END_VAR
END_CONFIGURATION"
        ),
        &[
            ("E083", 17),
            ("E083", 18),
            ("E083", 19),
            ("E030", 20),
            ("E083", 23),
        ],
    );
}

#[test]
fn var_config_completes_partial_addresses() {
    check(
        "PROGRAM Main
VAR
    sensor AT %I* : BOOL;
    fixed AT %IX0.0 : BOOL;
    level : INT;
END_VAR
END_PROGRAM
CONFIGURATION C
RESOURCE R ON PLC
    TASK t (INTERVAL := T#10ms, PRIORITY := 1);
    PROGRAM m WITH t : Main;
END_RESOURCE
VAR_CONFIG
    R.m.sensor AT %IX1.0 : BOOL;
    R.m.fixed AT %IX1.1 : BOOL;
    R.m.level : INT := 5;
    R.m.sensor AT %IW2 : BOOL;
    R.m.ghost : INT;
END_VAR
END_CONFIGURATION",
        &[("E084", 15), ("E084", 17), ("E083", 18)],
    );
}

#[test]
fn configuration_without_resource() {
    let (_, _, a) = analyze(&format!(
        "{PROGS}CONFIGURATION C
TASK t (INTERVAL := T#20ms, PRIORITY := 3);
PROGRAM m WITH t : Main;
VAR_ACCESS a : m.count : INT; END_VAR
END_CONFIGURATION"
    ));
    assert!(a.diagnostics.is_empty(), "{:?}", a.diagnostics);
    let c = &a.model.configs[0];
    assert_eq!(c.resources.len(), 1);
    assert!(c.resources[0].implicit);
    assert_eq!(c.resources[0].tasks[0].interval, Some(20_000_000));
    assert_eq!(c.resources[0].tasks[0].priority, Some(3));
    assert_eq!(c.resources[0].programs[0].task, Some(0));
    assert_eq!(c.access.len(), 1);
    assert_eq!(c.access[0].path.len(), 2);
}
