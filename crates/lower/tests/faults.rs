//! Runtime faults: the kind, a message naming the values, the POU and the
//! `file:line:col` of the construct.

mod common;
use automat_ir::{Fault, FaultKind};
use common::*;

fn fault_of(src: &str) -> Fault {
    let mut p = build(src);
    p.engine.set_budget(100_000);
    match p.scan() {
        Err(f) => f,
        Ok(()) => panic!("no fault"),
    }
}

#[test]
fn integer_division_by_zero() {
    let f = fault_of(
        "PROGRAM Main
         VAR a : DINT := 7; z : DINT; r : DINT; END_VAR
         r := a / z;
         END_PROGRAM",
    );
    assert_eq!(f.kind, FaultKind::DivisionByZero);
    assert_eq!(f.message, "division by zero (7 / 0)");
    assert_eq!(f.site.pou, "Main");
    assert_eq!(f.site.location, "test.st:3:15");
}

#[test]
fn index_out_of_bounds() {
    let f = fault_of(
        "FUNCTION_BLOCK Fb
         VAR a : ARRAY[1..4] OF INT; i : INT := 5; END_VAR
         a[i] := 1;
         END_FUNCTION_BLOCK
         PROGRAM Main VAR fb : Fb; END_VAR fb(); END_PROGRAM",
    );
    assert_eq!(f.kind, FaultKind::IndexOutOfBounds);
    assert_eq!(f.message, "index 5 outside 1..4");
    assert_eq!(f.site.pou, "Fb");
    assert_eq!(f.site.location, "test.st:3:12");
}

#[test]
fn index_out_of_bounds_of_array_of_unknown_size() {
    let f = fault_of(
        "FUNCTION Get : INT
         VAR_IN_OUT a : ARRAY[*] OF INT; END_VAR VAR_INPUT i : INT; END_VAR
         Get := a[i];
         END_FUNCTION
         PROGRAM Main VAR v : ARRAY[10..12] OF INT; x : INT; END_VAR x := Get(v, 13); END_PROGRAM",
    );
    assert_eq!(f.kind, FaultKind::IndexOutOfBounds);
    assert_eq!(f.message, "index 13 outside 10..12");
    assert_eq!(f.site.pou, "Get");
    assert_eq!(f.site.location, "test.st:3:19");
}

#[test]
fn subrange_violation_on_assignment() {
    let f = fault_of(
        "PROGRAM Main
         VAR s : INT(0..10); v : INT := 11; END_VAR
         s := v;
         END_PROGRAM",
    );
    assert_eq!(f.kind, FaultKind::SubrangeViolation);
    assert_eq!(f.message, "value 11 outside 0..10");
    assert_eq!(f.site.pou, "Main");
    assert_eq!(f.site.location, "test.st:3:10");
}

#[test]
fn string_index_error() {
    let f = fault_of(
        "PROGRAM Main
         VAR s : STRING := 'abc'; t : STRING; p : INT := 9; END_VAR
         t := MID(s, 1, p);
         END_PROGRAM",
    );
    assert_eq!(f.kind, FaultKind::StringIndex);
    assert_eq!(
        f.message,
        "MID: P = 9 is out of range 1..=4 (IN has 3 characters)"
    );
    assert_eq!(f.site.pou, "Main");
    assert_eq!(f.site.location, "test.st:3:15");
}

#[test]
fn watchdog() {
    let f = fault_of(
        "PROGRAM Main
         VAR n : DINT; END_VAR
         WHILE TRUE DO n := n + 1; END_WHILE;
         END_PROGRAM",
    );
    assert_eq!(f.kind, FaultKind::Watchdog);
    assert_eq!(
        f.message,
        "watchdog: more than 100000 instructions in one run"
    );
    assert_eq!(f.site.pou, "Main");
    assert_eq!(f.site.location, "test.st:3:10");
}

#[test]
fn null_reference() {
    let f = fault_of(
        "PROGRAM Main
         VAR r : REF_TO INT; x : INT; END_VAR
         x := r^;
         END_PROGRAM",
    );
    assert_eq!(f.kind, FaultKind::Function);
    assert_eq!(f.message, "dereference of a NULL reference");
    assert_eq!(f.site.pou, "Main");
    assert_eq!(f.site.location, "test.st:3:15");
}
