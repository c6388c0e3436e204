//! Calls: user functions, function block instances, standard functions and
//! function blocks; argument counts, names, types, directions.

mod common;
use common::{check, clean, messages};

const DECLS: &str = "FUNCTION Add3 : INT
VAR_INPUT a : INT; b : INT; c : INT; END_VAR
    Add3 := a + b + c;
END_FUNCTION
FUNCTION Swap : BOOL
VAR_IN_OUT x : INT; y : INT; END_VAR
VAR t : INT; END_VAR
    t := x; x := y; y := t; Swap := TRUE;
END_FUNCTION
FUNCTION_BLOCK Motor
VAR_INPUT start : BOOL; speed : INT; END_VAR
VAR_OUTPUT running : BOOL; END_VAR
VAR_IN_OUT cfg : INT; END_VAR
    running := start;
END_FUNCTION_BLOCK
";

/// `DECLS` (15 lines) followed by a program whose body starts on line 20.
fn with_decls(vars: &str, body: &str) -> String {
    format!("{DECLS}PROGRAM P\nVAR\n{vars}\nEND_VAR\n{body}\nEND_PROGRAM\n")
}

#[test]
fn user_function_calls() {
    check(
        &with_decls(
            "i : INT; d : DINT; b : BOOL;",
            "    i := Add3(1, 2, 3);
    i := Add3(a := 1, b := 2, c := i);
    i := Add3(1, 2);
    i := Add3(1, 2, 3, 4);
    i := Add3(a := 1, zz := 2);
    i := Add3(a := 1, a := 2);
    i := Add3(1, b := 2, c := 3);
    i := Add3(d, 1, 2);
    i := Add3(a := TRUE);
    b := Swap(x := i, y := i);
    b := Swap(x := i);
    b := Swap(x := 5, y := i);
    b := Swap(x := d, y := i);
    Add3(1, 2, 3);
    i := Nope(1);",
        ),
        &[
            ("E050", 22),
            ("E050", 23),
            ("E051", 24),
            ("E056", 25),
            ("E055", 26),
            ("E052", 27),
            ("E052", 28),
            ("E057", 30),
            ("E042", 31),
            ("E052", 32),
            ("E022", 34),
        ],
    );
}

#[test]
fn arity_messages_name_the_function() {
    let m = messages(
        "PROGRAM MainProg
VAR x : INT; END_VAR
    x := LIMIT(0, x);
    x := ADD(x);
END_PROGRAM",
    );
    assert_eq!(
        m,
        [
            "function `LIMIT` expects 3 arguments, found 2",
            "function `ADD` expects at least 2 arguments, found 1"
        ]
    );
}

#[test]
fn function_block_instance_calls() {
    check(
        &with_decls(
            "m : Motor; c : INT; r : BOOL; i : INT;",
            "    m(start := TRUE, speed := 5, cfg := c, running => r);
    m(start := TRUE, cfg := c);
    m(TRUE, 5, c);
    m(start := TRUE);
    m(cfg := c, running := r);
    m(cfg := c, start => r);
    m(cfg := c, running => 5);
    r := m(cfg := c);
    Motor(cfg := c);
    i(cfg := c);
    m(cfg := c, EN := TRUE, ENO => r);
    m(cfg := c, running => i);",
        ),
        &[
            ("E055", 22),
            ("E057", 23),
            ("E051", 24),
            ("E051", 25),
            ("E042", 26),
            ("E054", 27),
            ("E053", 28),
            ("E054", 29),
            ("E052", 31),
        ],
    );
}

#[test]
fn standard_function_blocks() {
    check(
        "PROGRAM P
VAR
    t : TON; tp1 : TP; lt : LTON; c : CTU; cd : CTUD_DINT; s : SR; rs1 : RS; r : R_TRIG; f : F_TRIG;
    b : BOOL; i : INT; d : DINT; tt : TIME;
END_VAR
    t(IN := b, PT := T#5s);
    tt := t.ET;
    b := t.Q;
    lt(IN := b, PT := LT#5s);
    c(CU := b, RESET := b, PV := 10);
    c(CU := b, R := b, PV := 10, Q => b, CV => i);
    cd(CU := b, CD := b, R := b, LD := b, PV := d, QU => b, QD => b, CV => d);
    s(S1 := b, R := b);
    rs1(S := b, R1 := b);
    r(CLK := b);
    f(CLK := b);
    b := r.Q AND f.Q AND s.Q1 AND rs1.Q1;
    t(IN := b, PT := 5);
    c(CU := b, PV := d);
    tp1(IN := b, PT := T#1s, Q => i);
    b := r.M;
END_PROGRAM",
        &[("E052", 18), ("E052", 19), ("E052", 20), ("E024", 21)],
    );
}

#[test]
fn standard_functions_generic_typing() {
    clean(
        "PROGRAM P
VAR i : INT; d : DINT; r : REAL; lr : LREAL; b : BOOL; w : WORD; s : STRING; t : TIME; bt : BYTE; END_VAR
    i := LIMIT(0, i, 100);
    d := MAX(i, d, 5);
    r := SQRT(r);
    r := SQRT(i);
    lr := EXPT(lr, 2);
    i := ABS(-5);
    w := SHL(w, 3);
    bt := ROL(bt, 1);
    i := MUX(1, i, 2, 3);
    r := SEL(b, r, 1.5);
    b := GT(i, 2, 1);
    i := LEN(s);
    s := CONCAT(s, 'x', s);
    s := MID(s, 2, 1);
    i := FIND(s, 'a');
    s := REPLACE(s, 'b', 1, 2);
    t := ADD_TIME(t, T#1s);
    t := MUL_TIME(t, 2);
    r := INT_TO_REAL(i);
    i := REAL_TO_INT(r);
    d := TIME_TO_DINT(t);
    s := INT_TO_STRING(i);
    i := TO_INT(r);
    d := TRUNC(r);
    i := TRUNC_INT(lr);
    i := BCD_TO_INT(w);
    w := INT_TO_BCD(i);
    b := EQ(s, 'x');
    i := MOVE(i);
    i := MIN(IN1 := i, IN2 := 3);
    i := LIMIT(MN := 0, IN := i, MX := 10);
END_PROGRAM",
    );
}

#[test]
fn standard_function_errors() {
    check(
        "PROGRAM P
VAR i : INT; d : DINT; r : REAL; b : BOOL; s : STRING; w : WORD; t : TIME; END_VAR
    i := LIMIT(0, i);
    i := MAX(i, b);
    r := SQRT(b);
    i := INT_TO_REAL(i);
    r := INT_TO_REAL(d);
    i := LEN(i);
    i := MUX(r, i, i);
    i := LIMIT(MN := 0, IN := i, MX := 1, ZZ := 2);
    i := ADD(i, IN1 := 2);
    t := MUL_TIME(t, s);
    i := SEL(i, i, i);
    i := ABS(i, i);
    i := REAL_TO_DATE(r);
END_PROGRAM",
        &[
            ("E050", 3),
            ("E052", 4),
            ("E052", 5),
            ("E030", 6),
            ("E052", 7),
            ("E052", 8),
            ("E052", 9),
            ("E051", 10),
            ("E055", 11),
            ("E052", 12),
            ("E052", 13),
            ("E050", 14),
            ("E022", 15),
        ],
    );
}

#[test]
fn functions_with_outputs_and_split_functions() {
    check(
        "FUNCTION Div : INT
VAR_INPUT a : INT; b : INT; END_VAR
VAR_OUTPUT rest : INT; END_VAR
    Div := a / b;
    rest := a MOD b;
END_FUNCTION
PROGRAM P
VAR q : INT; r : INT; y : INT; m : INT; dd : INT; day : DATE; END_VAR
    q := Div(a := 7, b := 2, rest => r);
    q := Div(7, 2, r);
    q := Div(7, 2);
    SPLIT_DATE(IN := day, YEAR => y, MONTH => m, DAY => dd);
    q := SPLIT_DATE(IN := day, YEAR => y, MONTH => m, DAY => dd);
    q := Div(a := 7, b := 2, rest => 5);
END_PROGRAM",
        &[("E030", 13), ("E042", 14)],
    );
}

#[test]
fn en_eno_on_every_call() {
    check(
        "FUNCTION F : INT
VAR_INPUT x : INT; END_VAR
    F := x;
END_FUNCTION
PROGRAM P
VAR i : INT; ok : BOOL; t : TON; END_VAR
    i := F(EN := ok, x := 1, ENO => ok);
    i := LIMIT(EN := TRUE, MN := 0, IN := i, MX := 9, ENO => ok);
    t(EN := ok, IN := ok, ENO => ok);
    ok := t.ENO;
    i := F(EN := 5, x := 1);
    i := F(x := 1, ENO => i);
END_PROGRAM",
        &[("E052", 11), ("E052", 12)],
    );
}

#[test]
fn calling_non_callables() {
    check(
        "FUNCTION F : INT
    F := 1;
END_FUNCTION
TYPE Point : STRUCT x : INT; END_STRUCT; END_TYPE
PROGRAM Q
END_PROGRAM
PROGRAM P
VAR i : INT; t : TON; p : Point; END_VAR
    i := i(1);
    i := t.F(1);
    i := Point(1);
    Q();
    i := p.x(1);
END_PROGRAM",
        &[
            ("E054", 9),
            ("E054", 10),
            ("E054", 11),
            ("E054", 12),
            ("E054", 13),
        ],
    );
}

#[test]
fn argument_errors_inside_bad_calls_are_still_reported() {
    check(
        "PROGRAM P
VAR i : INT; END_VAR
    i := Unknown(nothing);
    TON(IN := nothing2);
END_PROGRAM",
        &[("E022", 3), ("E020", 3), ("E053", 4), ("E020", 4)],
    );
}

#[test]
fn var_in_out_arrays_of_any_length() {
    check(
        "FUNCTION Sum : DINT
VAR_IN_OUT a : ARRAY[*] OF INT; END_VAR
VAR i : DINT; END_VAR
    FOR i := LOWER_BOUND(a, 1) TO UPPER_BOUND(a, 1) DO
        Sum := Sum + a[i];
    END_FOR;
END_FUNCTION
PROGRAM P
VAR x : ARRAY[1..5] OF INT; y : ARRAY[0..2] OF REAL; d : DINT; END_VAR
    d := Sum(a := x);
    d := Sum(a := y);
END_PROGRAM",
        &[("E052", 11)],
    );
}

#[test]
fn recursive_function_calls_itself_by_name() {
    clean(
        "FUNCTION Fact : DINT
VAR_INPUT n : DINT; END_VAR
    IF n <= 1 THEN
        Fact := 1;
    ELSE
        Fact := n * Fact(n - 1);
    END_IF;
END_FUNCTION",
    );
}
