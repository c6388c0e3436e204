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

/// `Main` with n LREALs: an `ARRAY[0..n/1024-1] OF ARRAY[0..1023] OF LREAL`.
fn array_program(n: u64) -> String {
    format!(
        "PROGRAM Main VAR a : ARRAY[0..{}] OF ARRAY[0..1023] OF LREAL; END_VAR a[0][0] := 1.0; END_PROGRAM",
        n / 1024 - 1
    )
}

#[test]
fn the_image_limit_states_the_exact_size_needed_beyond_4_gib() {
    // The program instance and its pristine template are 8n bytes each;
    // everything else (the reserved bytes, the standard FBs' templates) is
    // the same for any n: measure it on a program that fits.
    let small = 1024u64;
    let image = u64::from(build(&array_program(small)).engine.program().image_size);
    let rest = image - 16 * small;
    for n in [1u64 << 31, 1 << 40, 1 << 41] {
        let errs = build_err(&array_program(n));
        assert_eq!(
            errs,
            vec![(
                "E091".to_string(),
                format!(
                    "the program needs {} bytes of memory, more than the 268435456 bytes supported",
                    rest + 16 * n
                )
            )],
            "n = {n}"
        );
    }
}

#[test]
fn a_tree_of_2_pow_40_instances_is_refused_before_it_is_enumerated() {
    // F40 holds two F39, ..., F1 two F0: 2^40 F0 instances. Sizing goes by
    // type, so this is E091 at once (enumerating the tree for the symbol
    // table or the initial image would never end).
    let mut src =
        String::from("FUNCTION_BLOCK F0 VAR x : INT; END_VAR x := x + 1; END_FUNCTION_BLOCK\n");
    for i in 1..=40 {
        src += &format!(
            "FUNCTION_BLOCK F{i} VAR a, b : F{}; END_VAR a(); b(); END_FUNCTION_BLOCK\n",
            i - 1
        );
    }
    src += "PROGRAM Main VAR t : F40; END_VAR t(); END_PROGRAM\n";
    let errs = build_err(&src);
    assert_eq!(errs.len(), 1);
    assert_eq!(errs[0].0, "E091");
    // F0 is 4 bytes (x and the hidden EN/ENO), Fi = 2 F(i-1) + 2: Fi is
    // 6 * 2^i - 2 bytes. Main holds one F40 (and so does its template);
    // each Fi has a template (8-aligned).
    let f = |i: u32| 6 * (1u64 << i) - 2;
    let templates: u64 = (0..=40).map(|i| f(i).div_ceil(8) * 8).sum();
    let needed: u64 = errs[0].1["the program needs ".len()..]
        .split(' ')
        .next()
        .and_then(|n| n.parse().ok())
        .expect("a number of bytes");
    let fixed = 2 * f(40).div_ceil(8) * 8 + templates;
    // The rest (reserved bytes, standard FB templates) is a few KiB.
    assert!(needed > fixed && needed < fixed + 65536, "{}", errs[0].1);
}

#[test]
fn types_nested_too_deep_are_refused_not_laid_out_as_nothing() {
    let mut src =
        String::from("FUNCTION_BLOCK F0 VAR x : INT; END_VAR x := x + 1; END_FUNCTION_BLOCK\n");
    for i in 1..=70 {
        src += &format!(
            "FUNCTION_BLOCK F{i} VAR a : F{}; END_VAR a(); END_FUNCTION_BLOCK\n",
            i - 1
        );
    }
    src += "PROGRAM Main VAR t : F70; END_VAR t(); END_PROGRAM\n";
    assert_eq!(
        build_err(&src),
        vec![(
            "E091".to_string(),
            "types nest more than 64 levels deep (arrays, structures and FB instances within each other)".to_string()
        )]
    );
    // 60 levels are fine.
    let mut src =
        String::from("FUNCTION_BLOCK F0 VAR x : INT; END_VAR x := x + 1; END_FUNCTION_BLOCK\n");
    for i in 1..=60 {
        src += &format!(
            "FUNCTION_BLOCK F{i} VAR a : F{}; END_VAR a(); END_FUNCTION_BLOCK\n",
            i - 1
        );
    }
    src += "PROGRAM Main VAR t : F60; END_VAR t(); END_PROGRAM\n";
    let mut p = build(&src);
    p.run(3);
    let path = format!("Main.t{}.x", ".a".repeat(60));
    assert_eq!(p.int(&path), 3);
}

#[test]
fn the_checker_and_the_image_agree_on_the_longest_string() {
    assert_eq!(
        automat_sema::types::MAX_STRING_LEN,
        automat_ir::strbuf::MAX_LEN
    );
    let errs = build_err("PROGRAM Main VAR s : STRING[32768]; END_VAR s := 'a'; END_PROGRAM");
    assert_eq!(
        errs,
        vec![(
            "E072".to_string(),
            "string length must be between 1 and 32767 (LEN and positions are INT), found 32768"
                .to_string()
        )]
    );
}
