//! The lowering emits lean code: no reload of a value just stored, no wrap
//! that cannot change a value, array addresses without multiply-by-1 or
//! constant adds, no jump to the next instruction — and the programs still
//! compute the same values.

mod common;
use automat_ir::code::{Inst, IntOp};
use common::*;

fn main_code(p: &Plc) -> Vec<Inst> {
    let f = p.inst.func as usize;
    p.engine.program().funcs[f].code.clone()
}

fn count(code: &[Inst], pred: impl Fn(&Inst) -> bool) -> usize {
    code.iter().filter(|i| pred(i)).count()
}

#[test]
fn store_then_read_uses_the_stored_register() {
    let mut p = build(
        "PROGRAM Main
         VAR a : DINT := 3; b : DINT; END_VAR
         a := a * a;
         b := a + 1;
         END_PROGRAM",
    );
    let code = main_code(&p);
    // `a` is loaded once (`a * a` reads it twice, the next statement reads
    // the value just stored).
    assert_eq!(count(&code, |i| matches!(i, Inst::Load { .. })), 1);
    p.run(1);
    assert_eq!(p.int("Main.a"), 9);
    assert_eq!(p.int("Main.b"), 10);
}

#[test]
fn bitwise_and_widening_need_no_wrap() {
    let mut p = build(
        "PROGRAM Main
         VAR x : DWORD := 16#F0F0_0F0F; y : DWORD := 16#FFFF_0000; z : DWORD;
             i : INT := -5; l : DINT; END_VAR
         z := (x XOR y) AND (x OR y);
         l := i;
         END_PROGRAM",
    );
    let code = main_code(&p);
    assert_eq!(count(&code, |i| matches!(i, Inst::Wrap { .. })), 0);
    p.run(1);
    assert_eq!(p.int("Main.z"), 0x0F0F_0F0F);
    assert_eq!(p.int("Main.l"), -5);
}

#[test]
fn byte_array_element_address_is_check_addrof_add() {
    let mut p = build(
        "PROGRAM Main
         VAR a : ARRAY[3..9] OF BYTE; i : INT := 4; END_VAR
         a[i] := 7;
         a[i + 5] := 1;
         END_PROGRAM",
    );
    let code = main_code(&p);
    assert_eq!(
        count(&code, |i| matches!(i, Inst::Int { op: IntOp::Mul, .. })),
        0
    );
    // One add per element address (the constant part is in the operand).
    assert_eq!(
        count(&code, |i| matches!(i, Inst::Int { op: IntOp::Add, .. })),
        3
    );
    p.run(1);
    assert_eq!(p.int("Main.a[4]"), 7);
    assert_eq!(p.int("Main.a[9]"), 1);
    assert_eq!(p.int("Main.a[3]"), 0);
}

#[test]
fn no_jump_goes_to_the_next_instruction() {
    let mut p = build(
        "PROGRAM Main
         VAR n : INT; k : INT; END_VAR
         IF n < 3 THEN IF k = 0 THEN n := n + 1; END_IF; END_IF;
         END_PROGRAM",
    );
    let code = main_code(&p);
    for (at, i) in code.iter().enumerate() {
        if let Inst::Jump { target } = i {
            assert_ne!(*target as usize, at + 1, "jump to next at {at}");
            assert!(!matches!(
                code.get(*target as usize),
                Some(Inst::Jump { .. })
            ));
        }
    }
    p.run(5);
    assert_eq!(p.int("Main.n"), 3);
}

#[test]
fn for_with_constant_step_checks_one_side_only() {
    let mut p = build(
        "PROGRAM Main
         VAR i : SINT; n : DINT; d : SINT; m : DINT; END_VAR
         n := 0; m := 0;
         FOR i := 120 TO 127 DO n := n + 1; END_FOR;
         FOR d := -120 TO -128 BY -2 DO m := m + 1; END_FOR;
         END_PROGRAM",
    );
    let code = main_code(&p);
    // No AND of two range tests on the increment.
    assert_eq!(
        count(&code, |i| matches!(i, Inst::Int { op: IntOp::And, .. })),
        0
    );
    p.run(1);
    assert_eq!(p.int("Main.n"), 8);
    assert_eq!(p.int("Main.i"), 127);
    assert_eq!(p.int("Main.m"), 5);
    assert_eq!(p.int("Main.d"), -128);
}
