//! Functions, function blocks, VAR_IN_OUT, arrays, structures, strings,
//! bit access and located variables.

mod common;
use common::*;

#[test]
fn functions_and_function_blocks() {
    let mut p = build(
        "FUNCTION Add3 : INT
         VAR_INPUT a : INT; b : INT; c : INT := 100; END_VAR
         VAR t : INT; END_VAR
         t := t + a;
         Add3 := t + b + c;
         END_FUNCTION
         FUNCTION_BLOCK Counter
         VAR_INPUT step : INT := 1; END_VAR
         VAR_OUTPUT n : INT; big : BOOL; END_VAR
         n := n + step;
         big := n > 5;
         END_FUNCTION_BLOCK
         PROGRAM Main
         VAR x : INT; y : INT; c1 : Counter; c2 : Counter; n1 : INT; b2 : BOOL; nb : BOOL; END_VAR
         x := Add3(1, 2, 3);
         y := Add3(a := 10, b := 20);
         c1();
         c2(step := 3, n => n1, NOT big => nb);
         b2 := c2.big;
         END_PROGRAM",
    );
    p.run(2);
    assert_eq!(p.int("Main.x"), 6);
    assert_eq!(p.int("Main.y"), 130);
    assert_eq!(p.int("Main.c1.n"), 2);
    assert_eq!(p.int("Main.c2.n"), 6);
    assert_eq!(p.int("Main.n1"), 6);
    assert_eq!(p.int("Main.b2"), 1);
    assert_eq!(p.int("Main.nb"), 0);
}

#[test]
fn in_out_by_reference_and_temp_reinitialised() {
    let mut p = build(
        "FUNCTION_BLOCK Acc
         VAR_IN_OUT v : DINT; END_VAR
         VAR_TEMP t : DINT := 5; END_VAR
         t := t + 1;
         v := v + t;
         END_FUNCTION_BLOCK
         FUNCTION Swap : BOOL
         VAR_IN_OUT a : INT; b : INT; END_VAR
         VAR t : INT; END_VAR
         t := a; a := b; b := t; Swap := TRUE;
         END_FUNCTION
         PROGRAM Main
         VAR total : DINT; acc : Acc; p : INT := 1; q : INT := 2; ok : BOOL; END_VAR
         acc(v := total);
         ok := Swap(p, q);
         END_PROGRAM",
    );
    p.run(3);
    assert_eq!(p.int("Main.total"), 18);
    assert_eq!(p.int("Main.p"), 2);
    assert_eq!(p.int("Main.q"), 1);
    assert_eq!(p.int("Main.ok"), 1);
}

#[test]
fn arrays_multi_dim_and_bounds() {
    let mut p = build(
        "PROGRAM Main
         VAR m : ARRAY[1..3, 0..1] OF INT; v : ARRAY[-2..2] OF DINT := [1, 2, 3, 4, 5];
             i : INT; j : INT; s : DINT; k : INT := 1; END_VAR
         FOR i := 1 TO 3 DO FOR j := 0 TO 1 DO m[i, j] := i * 10 + j; END_FOR; END_FOR;
         s := 0;
         FOR i := -2 TO 2 DO s := s + v[i]; END_FOR;
         v[k] := 40;
         END_PROGRAM",
    );
    p.run(1);
    assert_eq!(p.int("Main.m[1, 0]"), 10);
    assert_eq!(p.int("Main.m[2, 1]"), 21);
    assert_eq!(p.int("Main.m[3, 1]"), 31);
    assert_eq!(p.int("Main.s"), 15);
    assert_eq!(p.int("Main.v[1]"), 40);
    p.set_int("Main.k", 3);
    let f = p.scan().unwrap_err();
    assert_eq!(f.kind, automat_ir::FaultKind::IndexOutOfBounds);
    assert_eq!(f.message, "index 3 outside -2..2");
}

#[test]
fn structs_copy_by_value() {
    let mut p = build(
        "TYPE Point : STRUCT x : INT := 1; y : REAL := 2.5; END_STRUCT; END_TYPE
         PROGRAM Main
         VAR a : Point; b : Point; pts : ARRAY[0..1] OF Point; END_VAR
         a.x := a.x + 1;
         b := a;
         a.x := 100;
         pts[1] := b;
         pts[1].y := pts[1].y * 2.0;
         END_PROGRAM",
    );
    p.run(1);
    assert_eq!(p.int("Main.b.x"), 2);
    assert_eq!(p.int("Main.a.x"), 100);
    assert_eq!(p.real("Main.b.y"), 2.5);
    assert_eq!(p.int("Main.pts[1].x"), 2);
    assert_eq!(p.real("Main.pts[1].y"), 5.0);
    assert_eq!(p.int("Main.pts[0].x"), 1);
}

#[test]
fn strings_truncate_and_functions() {
    let mut p = build(
        "PROGRAM Main
         VAR s : STRING[5]; t : STRING := 'Hello'; u : STRING; n : INT; f : INT; m : STRING; eq : BOOL; END_VAR
         s := 'abcdefgh';
         u := CONCAT(t, ', world');
         n := LEN(u);
         f := FIND(u, 'world');
         m := MID(u, 3, 2);
         eq := t = 'Hello';
         END_PROGRAM",
    );
    p.run(1);
    assert_eq!(p.string("Main.s"), "abcde");
    assert_eq!(p.string("Main.u"), "Hello, world");
    assert_eq!(p.int("Main.n"), 12);
    assert_eq!(p.int("Main.f"), 8);
    assert_eq!(p.string("Main.m"), "ell");
    assert_eq!(p.int("Main.eq"), 1);
}

#[test]
fn bits_shifts_and_located_variables() {
    let mut p = build(
        "PROGRAM Main
         VAR w : WORD := 16#00F0; b : BOOL; r : BYTE; start AT %IX0.2 : BOOL; lamp AT %QX1.3 : BOOL;
             out AT %QW2 : WORD; END_VAR
         b := w.4;
         w.0 := TRUE;
         r := ROL(BYTE#16#81, 1);
         lamp := start;
         out := SHL(w, 4);
         END_PROGRAM",
    );
    let areas = p.engine.program().areas.clone();
    // 8 reserved bytes (offset 0 is NULL), then %I (1 byte), then %Q up to
    // %QW2 = bytes 4..=5 (the number counts words).
    assert_eq!(areas.input, 8..9);
    assert_eq!(areas.output, 9..15);
    p.engine.image_mut()[8] = 0b100;
    p.run(1);
    assert_eq!(p.int("Main.b"), 1);
    assert_eq!(p.int("Main.w"), 0xF1);
    assert_eq!(p.int("Main.r"), 0x03);
    assert_eq!(p.int("Main.lamp"), 1);
    assert_eq!(p.engine.image()[areas.output.start as usize + 1], 0b1000);
    assert_eq!(p.int("Main.out"), 0xF10);
    let e = p.engine.program().symbols.get("Main.lamp").unwrap();
    assert_eq!((e.offset, e.bit), (areas.output.start + 1, Some(3)));
}

#[test]
fn recursion_is_an_error() {
    let errs = build_err(
        "FUNCTION F : INT VAR_INPUT x : INT; END_VAR
         IF x > 0 THEN F := G(x - 1); END_IF;
         END_FUNCTION
         FUNCTION G : INT VAR_INPUT x : INT; END_VAR
         G := F(x);
         END_FUNCTION
         PROGRAM Main VAR a : INT; END_VAR a := F(3); END_PROGRAM",
    );
    assert_eq!(errs.len(), 1);
    assert_eq!(errs[0].0, "E092");
    assert_eq!(errs[0].1, "recursive call: F -> G -> F");
}

#[test]
fn several_programs_need_a_choice() {
    let src = "PROGRAM A VAR x : INT; END_VAR x := 1; END_PROGRAM
               PROGRAM B VAR x : INT; END_VAR x := 2; END_PROGRAM";
    let errs = build_err(src);
    assert_eq!(errs[0].0, "E090");
    assert_eq!(
        errs[0].1,
        "several PROGRAMs (A, B) and no CONFIGURATION: choose one with --program"
    );
    let opts = automat_lower::LowerOptions {
        program: Some("b".into()),
    };
    let mut p = try_build(src, &opts).ok().unwrap();
    p.run(1);
    assert_eq!(p.int("B.x"), 2);
    assert_eq!(p.inst.name, "B");
}

#[test]
fn watchdog_stops_an_endless_loop() {
    let mut p =
        build("PROGRAM Main VAR x : INT; END_VAR WHILE TRUE DO x := x + 1; END_WHILE; END_PROGRAM");
    p.engine.set_budget(10_000);
    assert_eq!(p.scan().unwrap_err().kind, automat_ir::FaultKind::Watchdog);
}

#[test]
fn oversized_memory_is_an_error_not_an_abort() {
    let errs = build_err(
        "PROGRAM Main VAR a : ARRAY[0..200000000] OF LREAL; END_VAR a[1] := 1.0; END_PROGRAM",
    );
    assert_eq!(errs[0].0, "E091");
    assert!(errs[0].1.starts_with("the program needs "), "{}", errs[0].1);
}
