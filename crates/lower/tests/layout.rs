//! Layout, symbol table, initial image and tasks.

mod common;
use automat_iec::Elementary as E;
use automat_ir::SymbolType;
use common::*;

#[test]
fn offsets_sizes_alignment_and_initial_image() {
    let p = build(
        "TYPE Pair : STRUCT a : BOOL; b : DINT := 7; END_STRUCT; END_TYPE
         TYPE Color : (Red, Green := 5, Blue); END_TYPE
         VAR_GLOBAL g : INT := -3; END_VAR
         PROGRAM Main
         VAR x : BOOL := TRUE; y : LREAL := 1.5; s : STRING[4] := 'ab'; p : Pair; c : Color := Green;
             arr : ARRAY[1..3] OF INT := [2(9)]; w : WSTRING[2] := \"hi\"; t : TIME := T#1s; END_VAR
         END_PROGRAM",
    );
    let syms = &p.engine.program().symbols;
    let base = syms.get("MAIN.X").unwrap().offset;
    let rel = |n: &str| syms.get(n).unwrap().offset - base;
    assert_eq!(rel("Main.y"), 8);
    assert_eq!(rel("Main.s"), 16);
    // STRING[4]: 2 + 4 bytes; Pair aligned to 4: BOOL, pad, DINT.
    assert_eq!(rel("Main.p"), 24);
    assert_eq!(rel("Main.c"), 32);
    assert_eq!(rel("Main.arr"), 34);
    assert_eq!(rel("Main.w"), 40);
    assert_eq!(rel("Main.t"), 48);
    assert_eq!(
        syms.get("main.p").unwrap().ty,
        SymbolType::Struct {
            name: "PAIR".into(),
            fields: vec![
                automat_ir::Field {
                    name: "a".into(),
                    offset: 0,
                    bit: None,
                    ty: SymbolType::Elementary(E::Bool)
                },
                automat_ir::Field {
                    name: "b".into(),
                    offset: 4,
                    bit: None,
                    ty: SymbolType::Elementary(E::Dint)
                },
            ],
        }
    );
    assert_eq!(
        syms.get("Main.arr").unwrap().ty,
        SymbolType::Array {
            elem: Box::new(SymbolType::Elementary(E::Int)),
            dims: vec![(1, 3)],
            stride: 2
        }
    );
    // The cold image holds every initial value.
    assert_eq!(p.int("Main.x"), 1);
    assert_eq!(p.real("Main.y"), 1.5);
    assert_eq!(p.string("Main.s"), "ab");
    assert_eq!(p.int("Main.p.b"), 7);
    assert_eq!(p.int("Main.c"), 5);
    assert_eq!(p.int("Main.arr[2]"), 9);
    assert_eq!(p.int("Main.arr[3]"), 0);
    assert_eq!(p.string("Main.w"), "hi");
    assert_eq!(p.int("Main.t"), 1_000_000_000);
    assert_eq!(p.int("g"), -3);
    let tasks = &p.engine.program().tasks;
    assert_eq!(tasks.len(), 1);
    assert_eq!(
        (
            tasks[0].name.as_str(),
            tasks[0].interval_ns,
            tasks[0].priority
        ),
        ("Main", None, 0)
    );
}

#[test]
fn configuration_tasks_and_instances() {
    let mut p = build(
        "PROGRAM Count VAR n : INT; END_VAR n := n + 1; END_PROGRAM
         CONFIGURATION Cell
           RESOURCE Res ON PLC
             TASK Fast (INTERVAL := T#10ms, PRIORITY := 1);
             TASK Slow (INTERVAL := T#100ms, PRIORITY := 5);
             PROGRAM A WITH Fast : Count;
             PROGRAM B WITH Slow : Count;
           END_RESOURCE
         END_CONFIGURATION",
    );
    let tasks = p.engine.program().tasks.clone();
    assert_eq!(tasks.len(), 2);
    assert_eq!(
        (
            tasks[0].name.as_str(),
            tasks[0].interval_ns,
            tasks[0].priority
        ),
        ("Fast", Some(10_000_000), 1)
    );
    assert_eq!(tasks[1].programs[0].name, "B");
    // Two instances of one program keep separate state.
    let (a, b) = (tasks[0].programs[0].clone(), tasks[1].programs[0].clone());
    assert_eq!(a.func, b.func);
    assert_ne!(a.instance_offset, b.instance_offset);
    for _ in 0..3 {
        p.engine.run_program(&a, 0).unwrap();
    }
    p.engine.run_program(&b, 0).unwrap();
    assert_eq!(p.int("A.n"), 3);
    assert_eq!(p.int("B.n"), 1);
    p.engine.cold_start();
    assert_eq!(p.int("A.n"), 0);
}
