//! The standard function blocks (bodies in `crates/sema/src/stdlib/fbs.st`),
//! run scan by scan with the PLC time as an input.

mod common;
use common::*;

const MS: i64 = 1_000_000;

fn timers() -> Plc {
    build(
        "PROGRAM Main
         VAR i : BOOL; ton1 : TON; tof1 : TOF; tp1 : TP; q_on : BOOL; et_on : TIME; END_VAR
         ton1(IN := i, PT := T#100ms, Q => q_on, ET => et_on);
         tof1(IN := i, PT := T#100ms);
         tp1(IN := i, PT := T#100ms);
         END_PROGRAM",
    )
}

fn step(p: &mut Plc, at_ms: i64, i: bool) {
    p.now = at_ms * MS;
    p.set_int("Main.i", i as i64);
    p.run(1);
}

#[test]
fn ton_delays_the_rising_edge() {
    let mut p = timers();
    step(&mut p, 0, true);
    assert_eq!((p.int("Main.q_on"), p.int("Main.et_on")), (0, 0));
    step(&mut p, 60, true);
    assert_eq!(
        (p.int("Main.q_on"), p.int("Main.et_on")),
        (0, 60 * MS as i128)
    );
    step(&mut p, 100, true);
    assert_eq!(
        (p.int("Main.q_on"), p.int("Main.et_on")),
        (1, 100 * MS as i128)
    );
    step(&mut p, 250, true);
    assert_eq!(p.int("Main.ton1.ET"), 100 * MS as i128);
    step(&mut p, 260, false);
    assert_eq!((p.int("Main.q_on"), p.int("Main.et_on")), (0, 0));
}

#[test]
fn tof_delays_the_falling_edge() {
    let mut p = timers();
    step(&mut p, 0, true);
    assert_eq!(p.int("Main.tof1.Q"), 1);
    step(&mut p, 10, false);
    assert_eq!((p.int("Main.tof1.Q"), p.int("Main.tof1.ET")), (1, 0));
    step(&mut p, 60, false);
    assert_eq!(
        (p.int("Main.tof1.Q"), p.int("Main.tof1.ET")),
        (1, 50 * MS as i128)
    );
    step(&mut p, 110, false);
    assert_eq!(
        (p.int("Main.tof1.Q"), p.int("Main.tof1.ET")),
        (0, 100 * MS as i128)
    );
    step(&mut p, 120, true);
    assert_eq!((p.int("Main.tof1.Q"), p.int("Main.tof1.ET")), (1, 0));
}

#[test]
fn tp_gives_a_fixed_pulse_and_is_not_retriggerable() {
    let mut p = timers();
    step(&mut p, 0, true);
    assert_eq!(p.int("Main.tp1.Q"), 1);
    step(&mut p, 30, false);
    step(&mut p, 40, true);
    assert_eq!(
        (p.int("Main.tp1.Q"), p.int("Main.tp1.ET")),
        (1, 40 * MS as i128)
    );
    step(&mut p, 100, true);
    assert_eq!(
        (p.int("Main.tp1.Q"), p.int("Main.tp1.ET")),
        (0, 100 * MS as i128)
    );
    step(&mut p, 150, true);
    assert_eq!(p.int("Main.tp1.ET"), 100 * MS as i128);
    step(&mut p, 160, false);
    assert_eq!(p.int("Main.tp1.ET"), 0);
}

#[test]
fn counters_count_edges_and_triggers_and_bistables() {
    let mut p = build(
        "PROGRAM Main
         VAR pulse : BOOL; rst : BOOL; up : CTU; down : CTD; ud : CTUD; rt : R_TRIG; ft : F_TRIG;
             nr : INT; nf : INT; sr1 : SR; rs1 : RS; s : BOOL; r : BOOL; END_VAR
         up(CU := pulse, RESET := rst, PV := 3);
         down(CD := pulse, LD := rst, PV := 2);
         ud(CU := pulse, CD := FALSE, R := rst, PV := 2);
         rt(CLK := pulse); IF rt.Q THEN nr := nr + 1; END_IF;
         ft(CLK := pulse); IF ft.Q THEN nf := nf + 1; END_IF;
         sr1(S1 := s, R := r); rs1(S := s, R1 := r);
         END_PROGRAM",
    );
    p.set_int("Main.rst", 1);
    p.run(1);
    assert_eq!(p.int("Main.down.CV"), 2);
    p.set_int("Main.rst", 0);
    for k in 0..8 {
        p.set_int("Main.pulse", (k % 2 == 0) as i64);
        p.run(1);
    }
    // Four rising edges.
    assert_eq!((p.int("Main.up.CV"), p.int("Main.up.Q")), (4, 1));
    assert_eq!((p.int("Main.down.CV"), p.int("Main.down.Q")), (-2, 1));
    assert_eq!((p.int("Main.ud.CV"), p.int("Main.ud.QU")), (4, 1));
    assert_eq!((p.int("Main.nr"), p.int("Main.nf")), (4, 4));
    p.set_int("Main.s", 1);
    p.set_int("Main.r", 1);
    p.run(1);
    assert_eq!((p.int("Main.sr1.Q1"), p.int("Main.rs1.Q1")), (1, 0));
}

#[test]
fn standard_blocks_show_only_their_interface() {
    let p = timers();
    let e = p.engine.program().symbols.get("Main.ton1").unwrap();
    let automat_ir::SymbolType::Struct { name, fields } = &e.ty else {
        panic!("{:?}", e.ty)
    };
    assert_eq!(name, "TON");
    let names: Vec<&str> = fields.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, ["IN", "PT", "Q", "ET"]);
}
