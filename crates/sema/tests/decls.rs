//! Declarations: constant folding of bounds and lengths, recursive types,
//! initial values, located variables.

mod common;
use common::{check, clean, messages};

#[test]
fn constant_expressions_size_types() {
    clean(
        "VAR_GLOBAL CONSTANT
    N : INT := 4;
    M : INT := N * 2 - 1;
    LEN_ : INT := 20;
END_VAR
TYPE
    Buf : ARRAY[0..N - 1] OF INT;
    Name : STRING[LEN_];
    Small : INT (0..M);
    E : (A := N, B, C := M + 1);
END_TYPE
PROGRAM P
VAR CONSTANT K : INT := N + 1; END_VAR
VAR
    local : ARRAY[1..K, 0..M] OF BOOL;
    b : Buf;
    s : STRING[LEN_ * 2];
END_VAR
    local[K, M] := TRUE;
    b[N - 1] := 1;
    CASE b[0] OF N: ; K + 1 .. K + 3: ; END_CASE;
END_PROGRAM",
    );
}

#[test]
fn constants_may_be_declared_after_use() {
    clean(
        "TYPE Buf : ARRAY[1..SIZE] OF INT; END_TYPE
VAR_GLOBAL CONSTANT SIZE : INT := LAST + 1; LAST : INT := 9; END_VAR
PROGRAM P
VAR a : ARRAY[0..K] OF BOOL; END_VAR
VAR CONSTANT K : INT := SIZE; END_VAR
    a[10] := TRUE;
END_PROGRAM",
    );
}

#[test]
fn non_constant_bounds_and_bad_folds() {
    check(
        "VAR_GLOBAL CONSTANT
    Z : INT := 0;
    BIG : SINT := 100;
END_VAR
PROGRAM P
VAR
    n : INT := 5;
    a : ARRAY[1..n] OF INT;
    b : ARRAY[1..10 / Z] OF INT;
    c : ARRAY[5..1] OF INT;
    d : STRING[0];
    e : ARRAY[1..1.5] OF INT;
    f : SINT := BIG + BIG;
    g : ARRAY[1..F()] OF INT;
END_VAR
END_PROGRAM",
        &[
            ("E070", 8),
            ("E071", 9),
            ("E072", 10),
            ("E072", 11),
            ("E030", 12),
            ("E073", 13),
            ("E070", 14),
        ],
    );
}

#[test]
fn constant_cycles_are_reported_not_looped() {
    check(
        "VAR_GLOBAL CONSTANT
    A : INT := B + 1;
    B : INT := A + 1;
END_VAR
PROGRAM P
VAR CONSTANT X : INT := X; END_VAR
VAR arr : ARRAY[1..A] OF INT; END_VAR
END_PROGRAM",
        &[("E070", 3), ("E070", 6)],
    );
}

#[test]
fn recursive_types_are_reported() {
    check(
        "TYPE
    A : STRUCT x : A; END_STRUCT;
    B : C;
    C : B;
    D : ARRAY[1..2] OF D;
    Node : STRUCT value : INT; next : REF_TO Node; END_STRUCT;
    E : STRUCT f : F; END_STRUCT;
    F : STRUCT e : E; END_STRUCT;
END_TYPE
FUNCTION_BLOCK Self
VAR inner : Self; END_VAR
END_FUNCTION_BLOCK
FUNCTION_BLOCK Ping
VAR p : Pong; END_VAR
END_FUNCTION_BLOCK
FUNCTION_BLOCK Pong
VAR p : ARRAY[1..2] OF Ping; END_VAR
END_FUNCTION_BLOCK",
        &[
            ("E027", 2),
            ("E027", 4),
            ("E027", 5),
            ("E027", 8),
            ("E027", 11),
            ("E027", 17),
        ],
    );
}

#[test]
fn unknown_types() {
    check(
        "FUNCTION F : INT
    F := 1;
END_FUNCTION
PROGRAM P
VAR
    a : Nothing;
    b : F;
    c : ARRAY[1..2] OF Nothing2;
    d : REF_TO Nothing3;
END_VAR
    a := 1;
END_PROGRAM",
        &[("E021", 6), ("E021", 7), ("E021", 8), ("E021", 9)],
    );
}

#[test]
fn initial_values_fit_their_types() {
    check(
        "TYPE
    Point : STRUCT x : INT; y : INT; END_STRUCT;
    Percent : INT (0..100);
    Color : (Red, Green);
    Size : (Small, Big);
END_TYPE
PROGRAM P
VAR
    a : ARRAY[1..3] OF INT := [1, 2, 3];
    b : ARRAY[1..3] OF INT := [1, 2, 3, 4];
    c : ARRAY[1..10] OF INT := [5(0), 5(1)];
    d : ARRAY[1..10] OF INT := [11(0)];
    p : Point := (x := 1, y := 2);
    q : Point := (x := 1, z := 2);
    r : INT := (x := 1);
    s : SINT := 300;
    pc : Percent := 101;
    col : Color := Green;
    col2 : Color := Big;
    m : ARRAY[1..2, 1..2] OF INT := [[1, 2], [3, 4]];
    t : TON := (PT := T#1s);
    str : STRING[5] := 'abc';
    i : INT := TRUE;
    arr : ARRAY[1..2] OF Point := [(x := 1), (y := 2)];
END_VAR
END_PROGRAM",
        &[
            ("E039", 10),
            ("E039", 12),
            ("E039", 14),
            ("E039", 15),
            ("E039", 16),
            ("E038", 17),
            ("E039", 19),
            ("E039", 23),
        ],
    );
}

#[test]
fn narrowing_a_typed_constant_is_a_warning() {
    check(
        "VAR_GLOBAL CONSTANT D : DINT := 5; END_VAR
PROGRAM P
VAR i : INT := D; END_VAR
    i := D;
END_PROGRAM",
        &[("W003", 3), ("W003", 4)],
    );
}

#[test]
fn located_variables() {
    check(
        "PROGRAM P
VAR
    a AT %IX0.1 : BOOL;
    b AT %IX0.2 : INT;
    c AT %IB1 : BYTE;
    d AT %IB2 : INT;
    e AT %QW4 : INT;
    f AT %QW6 : WORD;
    g AT %MD8 : REAL;
    h AT %MD12 : LREAL;
    i AT %ML16 : LINT;
    j AT %I* : BOOL;
    k AT %IW10 : ARRAY[0..3] OF INT;
END_VAR
END_PROGRAM
FUNCTION F : INT
VAR x AT %I* : BOOL; END_VAR
    F := 1;
END_FUNCTION
VAR_GLOBAL
    y AT %Q* : BOOL;
    z AT %QX1.0 : BOOL;
END_VAR",
        &[
            ("E084", 4),
            ("E084", 6),
            ("E084", 10),
            ("E084", 17),
            ("E084", 21),
        ],
    );
    let m = messages("PROGRAM P\nVAR b AT %IX0.2 : INT; END_VAR\nEND_PROGRAM");
    assert_eq!(
        m,
        ["`b` of type INT cannot be located at %IX0.2: a bit address needs BOOL"]
    );
}

#[test]
fn edge_qualifiers_need_bool_inputs() {
    check(
        "FUNCTION_BLOCK FB
VAR_INPUT
    ok : BOOL R_EDGE;
    bad : INT F_EDGE;
END_VAR
END_FUNCTION_BLOCK",
        &[("E030", 4)],
    );
}

/// The folded value of each global constant of a snippet, by name.
fn folded(src: &str) -> Vec<(String, Option<automat_sema::value::Value>)> {
    let (_, interner, a) = common::analyze(src);
    assert!(
        a.diagnostics.iter().all(|d| !d.is_error()),
        "{:?}",
        a.diagnostics
    );
    a.model
        .globals
        .vars
        .iter()
        .map(|v| {
            let value = v.init.as_ref().and_then(|i| i.as_value()).cloned();
            (interner.name(v.name).to_string(), value)
        })
        .collect()
}

#[test]
fn folding_computes_exact_values() {
    use automat_sema::value::Value::*;
    let got = folded(
        "TYPE E : (A := 10, B, C := A * 2); END_TYPE
VAR_GLOBAL CONSTANT
    i1 : INT := 7 / 2;
    i2 : INT := -7 MOD 3;
    i3 : DINT := 2 * (3 + 4) - 1;
    r1 : REAL := 1.5 * 2;
    r2 : LREAL := 1 / 4.0;
    r3 : LREAL := 2 ** 10;
    b1 : BOOL := 3 > 2 AND NOT FALSE;
    w1 : WORD := 16#FF00 OR 16#00F0;
    w2 : BYTE := NOT 16#0F;
    t1 : TIME := T#1s + T#250ms * 2;
    e1 : E := C;
    s1 : STRING := 'abc';
    x1 : DINT := i1 + i3;
    u1 : UINT := 65535;
    c1 : CHAR := 'z';
END_VAR",
    );
    let want = [
        ("i1", Some(Int(3))),
        ("i2", Some(Int(-1))),
        ("i3", Some(Int(13))),
        ("r1", Some(Real(3.0))),
        ("r2", Some(Real(0.25))),
        ("r3", Some(Real(1024.0))),
        ("b1", Some(Bool(true))),
        ("w1", Some(Int(0xFFF0))),
        ("w2", Some(Int(0xF0))),
        ("t1", Some(Duration(1_500_000_000))),
        ("e1", Some(Enum(20))),
        ("s1", Some(Str("abc".into()))),
        ("x1", Some(Int(16))),
        ("u1", Some(Int(65535))),
        ("c1", Some(Str("z".into()))),
    ];
    let want: Vec<(String, Option<automat_sema::value::Value>)> =
        want.into_iter().map(|(n, v)| (n.to_string(), v)).collect();
    assert_eq!(got, want);
}

#[test]
fn folding_errors_in_bodies_and_declarations() {
    check(
        "VAR_GLOBAL CONSTANT
    S : SINT := 100;
    T : SINT := S * 2;
    Z : INT := 0;
    Q : INT := 1 / Z;
END_VAR
PROGRAM P
VAR i : INT; small : SINT; END_VAR
    i := 10 / 0;
    i := i / 0;
    small := S + S;
    CASE i OF 1 / 0: ; END_CASE;
END_PROGRAM",
        &[
            ("E073", 3),
            ("E071", 5),
            ("E071", 9),
            ("E073", 11),
            ("E071", 12),
        ],
    );
}
