//! Small ST programs run for N scans; values read through the symbol table.

mod common;
use common::*;

#[test]
fn counter_wraps_at_int_width() {
    let mut p = build(
        "PROGRAM Main
         VAR c : INT := 32766; s : SINT; u : USINT := 250; END_VAR
         c := c + 1; s := s - 1; u := u + 3;
         END_PROGRAM",
    );
    p.run(1);
    assert_eq!(p.int("Main.c"), 32767);
    assert_eq!(p.int("Main.s"), -1);
    assert_eq!(p.int("Main.u"), 253);
    p.run(1);
    assert_eq!(p.int("Main.c"), -32768);
    assert_eq!(p.int("Main.u"), 0);
}

#[test]
fn division_and_mod_and_faults() {
    let mut p = build(
        "PROGRAM Main
         VAR a : DINT := -7; b : DINT := 2; q : DINT; r : DINT; z : DINT; END_VAR
         q := a / b; r := a MOD 3;
         IF b = 0 THEN z := a / b; END_IF;
         END_PROGRAM",
    );
    p.run(1);
    assert_eq!(p.int("Main.q"), -3);
    assert_eq!(p.int("Main.r"), -1);
    p.set_int("Main.b", 0);
    let f = p.scan().unwrap_err();
    assert_eq!(f.kind, automat_ir::FaultKind::DivisionByZero);
    assert_eq!(f.site.pou, "Main");
    assert_eq!(f.site.location, "test.st:3:15");
}

#[test]
fn control_flow() {
    let mut p = build(
        "PROGRAM Main
         VAR i : INT; sum : DINT; w : INT; r : INT; k : INT; c : INT; e : INT; odd : DINT; END_VAR
         sum := 0;
         FOR i := 1 TO 10 DO sum := sum + i; END_FOR;
         w := 0;
         WHILE w < 100 DO w := w + 7; END_WHILE;
         r := 0;
         REPEAT r := r + 1; UNTIL r >= 5 END_REPEAT;
         k := 0;
         FOR i := 10 TO 1 BY -2 DO k := k + 1; END_FOR;
         CASE w OF
           1..10: c := 1;
           105: c := 2;
         ELSE c := 3;
         END_CASE;
         e := 0;
         WHILE TRUE DO e := e + 1; IF e = 3 THEN EXIT; END_IF; END_WHILE;
         odd := 0;
         FOR i := 1 TO 10 DO
           IF i MOD 2 = 0 THEN CONTINUE; END_IF;
           odd := odd + i;
         END_FOR;
         END_PROGRAM",
    );
    p.run(1);
    assert_eq!(p.int("Main.sum"), 55);
    assert_eq!(p.int("Main.w"), 105);
    assert_eq!(p.int("Main.r"), 5);
    assert_eq!(p.int("Main.k"), 5);
    assert_eq!(p.int("Main.c"), 2);
    assert_eq!(p.int("Main.e"), 3);
    assert_eq!(p.int("Main.odd"), 25);
    assert_eq!(p.int("Main.i"), 11);
}

#[test]
fn for_loop_to_the_types_maximum_ends() {
    let mut p = build(
        "PROGRAM Main
         VAR i : SINT; n : INT; END_VAR
         n := 0;
         FOR i := 120 TO 127 DO n := n + 1; END_FOR;
         END_PROGRAM",
    );
    p.run(1);
    assert_eq!(p.int("Main.n"), 8);
    assert_eq!(p.int("Main.i"), 127);
}

#[test]
fn reals_and_conversions() {
    let mut p = build(
        "PROGRAM Main
         VAR r : REAL := 0.1; l : LREAL; i : INT; d : DINT := 7; x : REAL; END_VAR
         r := r + 0.2;
         l := 1.5 * 2.0;
         i := REAL_TO_INT(2.5);
         x := DINT_TO_REAL(d) / 2.0;
         END_PROGRAM",
    );
    p.run(1);
    assert_eq!(p.real("Main.r"), (0.1f32 + 0.2f32) as f64);
    assert_eq!(p.real("Main.l"), 3.0);
    assert_eq!(p.int("Main.i"), 2);
    assert_eq!(p.real("Main.x"), 3.5);
}
