//! Name resolution: locals, globals through VAR_EXTERNAL, constants, enum
//! values, POUs and types used as values, duplicates.

mod common;
use common::{analyze_files, check, clean, codes_of, messages};

#[test]
fn locals_inputs_outputs_and_return_value_resolve() {
    clean(
        "FUNCTION F : INT
VAR_INPUT a : INT; END_VAR
VAR_IN_OUT io : INT; END_VAR
VAR_OUTPUT q : BOOL; END_VAR
VAR_TEMP t : INT; END_VAR
    t := a + io;
    io := t;
    q := t > 0;
    F := t;
END_FUNCTION",
    );
}

#[test]
fn unknown_names_are_reported_once_each() {
    check(
        "PROGRAM MainProg
VAR
    a : INT;
END_VAR
    a := xyz;
    missing := 1;
    a := a + nowhere * 2;
    a := first + second;
END_PROGRAM",
        &[
            ("E020", 5),
            ("E020", 6),
            ("E020", 7),
            ("E020", 8),
            ("E020", 8),
        ],
    );
    let m = messages("PROGRAM MainProg\nVAR a : INT; END_VAR\n a := xyz;\nEND_PROGRAM");
    assert_eq!(m, ["unknown variable `xyz` in `MainProg`"]);
}

#[test]
fn globals_need_var_external_but_global_constants_do_not() {
    let files = [
        (
            "globals.st",
            "VAR_GLOBAL
    g_speed : INT;
END_VAR
VAR_GLOBAL CONSTANT
    N : INT := 4;
END_VAR",
        ),
        (
            "main.st",
            "PROGRAM Main
VAR_EXTERNAL
    g_speed : INT;
END_VAR
VAR
    a : ARRAY[1..N] OF INT;
    x : INT;
END_VAR
    x := g_speed + N;
    a[N] := x;
END_PROGRAM
PROGRAM Other
VAR
    x : INT;
END_VAR
    x := g_speed;
END_PROGRAM",
        ),
    ];
    let (map, _, a) = analyze_files(&files);
    let got: Vec<(String, u32)> = codes_of(&map, &a);
    assert_eq!(got, [("E020".to_string(), 16)]);
}

#[test]
fn var_external_must_match_a_global_by_name_and_type() {
    check(
        "VAR_GLOBAL
    g : INT;
    h : BOOL;
END_VAR
PROGRAM P
VAR_EXTERNAL
    g : INT;
    h : INT;
    nobody : REAL;
END_VAR
    g := 1;
END_PROGRAM",
        &[("E025", 8), ("E025", 9)],
    );
    let m = messages(
        "VAR_GLOBAL h : BOOL; END_VAR
PROGRAM P
VAR_EXTERNAL h : INT; x : REAL; END_VAR
END_PROGRAM",
    );
    assert_eq!(
        m,
        [
            "VAR_EXTERNAL `h` of type INT does not match VAR_GLOBAL `h` of type BOOL",
            "VAR_EXTERNAL `x` has no matching VAR_GLOBAL"
        ]
    );
}

#[test]
fn var_external_matches_configuration_and_resource_globals() {
    clean(
        "PROGRAM P
VAR_EXTERNAL
    cfg_g : INT;
    res_g : BOOL;
END_VAR
    cfg_g := 1;
    res_g := TRUE;
END_PROGRAM
CONFIGURATION C
VAR_GLOBAL cfg_g : INT; END_VAR
RESOURCE R ON PLC
VAR_GLOBAL res_g : BOOL; END_VAR
TASK t (INTERVAL := T#10ms, PRIORITY := 1);
PROGRAM p1 WITH t : P;
END_RESOURCE
END_CONFIGURATION",
    );
}

#[test]
fn external_constant_takes_the_global_value() {
    check(
        "VAR_GLOBAL CONSTANT
    SIZE : INT := 3;
END_VAR
PROGRAM P
VAR_EXTERNAL CONSTANT
    SIZE : INT;
END_VAR
VAR
    a : ARRAY[1..SIZE] OF INT;
END_VAR
    a[4] := 1;
    SIZE := 2;
END_PROGRAM",
        &[("E035", 11), ("E040", 12)],
    );
}

#[test]
fn enumeration_values_resolve_bare_qualified_and_typed() {
    check(
        "TYPE
    Color : (Red, Green, Blue);
    Light : (Off, Red, Flashing);
END_TYPE
PROGRAM P
VAR
    c : Color;
    l : Light;
END_VAR
    c := Blue;
    c := Red;
    l := Red;
    c := Color#Green;
    c := Color.Green;
    l := Flashing;
    c := Flashing;
    c := Color#Purple;
    c := Color.Purple;
END_PROGRAM",
        &[("E030", 16), ("E020", 17), ("E020", 18)],
    );
}

#[test]
fn types_and_pous_are_not_values() {
    check(
        "TYPE Point : STRUCT x : INT; END_STRUCT; END_TYPE
FUNCTION F : INT
    F := 1;
END_FUNCTION
PROGRAM P
VAR
    i : INT;
END_VAR
    i := Point;
    i := F;
    i := TON;
    i := INT;
    i := LIMIT;
END_PROGRAM",
        &[
            ("E026", 9),
            ("E026", 10),
            ("E026", 11),
            ("E026", 12),
            ("E026", 13),
        ],
    );
}

#[test]
fn duplicate_declarations() {
    check(
        "TYPE
    T : INT;
    T : BOOL;
    E : (A, B, A);
    S : STRUCT x : INT; x : BOOL; END_STRUCT;
    INT : DINT;
END_TYPE
FUNCTION T : INT
    T := 1;
END_FUNCTION
FUNCTION G : INT
VAR
    G : INT;
END_VAR
    G := 1;
END_FUNCTION
PROGRAM P
VAR
    a : INT;
    a : BOOL;
END_VAR
VAR_TEMP
    a : REAL;
END_VAR
END_PROGRAM",
        &[
            ("E023", 3),
            ("E023", 4),
            ("E023", 5),
            ("E023", 6),
            ("E023", 8),
            ("E023", 13),
            ("E023", 20),
            ("E023", 23),
        ],
    );
}

#[test]
fn duplicates_across_files() {
    let (map, _, a) = analyze_files(&[
        ("a.st", "FUNCTION_BLOCK Motor\nEND_FUNCTION_BLOCK\n"),
        ("b.st", "\nFUNCTION_BLOCK Motor\nEND_FUNCTION_BLOCK\n"),
    ]);
    let got = codes_of(&map, &a);
    assert_eq!(got, [("E023".to_string(), 2)]);
    assert_eq!(a.diagnostics[0].labels.len(), 1);
    assert_eq!(
        a.diagnostics[0].labels[0].span.file,
        automat_base::FileId(0)
    );
}

#[test]
fn names_are_case_insensitive() {
    clean(
        "TYPE mode : (Auto, Manual) := AUTO; END_TYPE
FUNCTION_BLOCK Motor
VAR_INPUT Speed : INT; END_VAR
END_FUNCTION_BLOCK
PROGRAM p
VAR
    M1 : MOTOR;
    md : MODE;
    Counter : int;
END_VAR
    m1(speed := COUNTER);
    MD := manual;
    counter := m1.SPEED;
END_PROGRAM",
    );
}

#[test]
fn user_pous_replace_standard_ones() {
    clean(
        "FUNCTION_BLOCK TON
VAR_INPUT go : BOOL; END_VAR
VAR_OUTPUT done : BOOL; END_VAR
    done := go;
END_FUNCTION_BLOCK
FUNCTION LIMIT : INT
VAR_INPUT x : INT; END_VAR
    LIMIT := x;
END_FUNCTION
PROGRAM P
VAR t : TON; b : BOOL; i : INT; END_VAR
    t(go := TRUE);
    b := t.done;
    i := LIMIT(5);
END_PROGRAM",
    );
}

#[test]
fn program_globals_serve_external_declarations() {
    clean(
        "FUNCTION_BLOCK Counter
VAR_EXTERNAL total : DINT; END_VAR
    total := total + 1;
END_FUNCTION_BLOCK
PROGRAM Main
VAR_GLOBAL total : DINT; END_VAR
VAR c : Counter; END_VAR
    c();
    total := 0;
END_PROGRAM",
    );
}

#[test]
fn a_hidden_or_missing_member_names_a_class_as_a_class() {
    let m = messages(
        "CLASS Calc\nVAR total : INT; END_VAR\nMETHOD Add : INT\nAdd := total;\nEND_METHOD\nEND_CLASS\n\
         FUNCTION_BLOCK Fb\nVAR hidden : INT; END_VAR\nhidden := 1;\nEND_FUNCTION_BLOCK\n\
         PROGRAM Main\nVAR c : Calc; f : Fb; i : INT; END_VAR\n\
         i := c.total;\ni := c.nothing;\ni := f.hidden;\ni := f.nothing;\nEND_PROGRAM",
    );
    assert_eq!(
        m,
        [
            "`total` is not an input or output of class `Calc`",
            "class `Calc` has no member `nothing`",
            "`hidden` is not an input or output of function block `Fb`",
            "function block `Fb` has no member `nothing`",
        ]
    );
}
