//! Typing of statements and expressions: assignments, literals, operators,
//! conditions, CASE, FOR, bit access, arrays, structures, instances.

mod common;
use common::{check, clean, messages};

#[test]
fn assignment_follows_the_widening_lattice() {
    check(
        "PROGRAM P
VAR
    i : INT; d : DINT; s : SINT; u : UINT; r : REAL; lr : LREAL;
    b : BOOL; w : WORD; bt : BYTE; t : TIME; lt : LTIME; str : STRING; ws : WSTRING;
END_VAR
    d := i;
    i := d;
    i := s;
    d := u;
    i := u;
    r := i;
    r := d;
    lr := d;
    w := bt;
    bt := w;
    b := bt;
    lt := t;
    t := lt;
    str := ws;
    i := r;
END_PROGRAM",
        &[
            ("E030", 7),
            ("E030", 10),
            ("E030", 12),
            ("E030", 15),
            ("E030", 16),
            ("E030", 18),
            ("E030", 19),
            ("E030", 20),
        ],
    );
    let m = messages("PROGRAM p\nVAR i : INT; d : DINT; END_VAR\n i := d;\nEND_PROGRAM");
    assert_eq!(
        m,
        ["cannot assign a value of type DINT to `i` of type INT; convert it with `DINT_TO_INT(...)`"]
    );
}

#[test]
fn untyped_literals_fit_by_value() {
    check(
        "PROGRAM P
VAR s : SINT; b : BOOL; bt : BYTE; r : REAL; t : TIME; c : CHAR; wc : WCHAR; u : USINT; END_VAR
    s := 127;
    s := 300;
    s := 2 * 100;
    s := 300 - 200;
    s := 300 + 100;
    b := 1;
    b := 2;
    bt := 16#FF;
    bt := 256;
    r := 5;
    r := 1.5;
    t := 5;
    c := 'a';
    c := 'ab';
    wc := \"w\";
    u := -1;
END_PROGRAM",
        &[
            ("E030", 4),
            ("E030", 5),
            ("E030", 7),
            ("E030", 9),
            ("E030", 11),
            ("E030", 14),
            ("E030", 16),
            ("E030", 18),
        ],
    );
    let m = messages("PROGRAM p\nVAR s : SINT; END_VAR\n s := 300;\nEND_PROGRAM");
    assert_eq!(m, ["the value 300 does not fit `s` of type SINT"]);
}

#[test]
fn operators_widen_and_reject_mismatches() {
    check(
        "PROGRAM P
VAR i : INT; d : DINT; r : REAL; b : BOOL; w : WORD; s : STRING; t : TIME; dt1 : DT; END_VAR
    d := i + d;
    r := i * r;
    i := i + 100000;
    b := TRUE + 1;
    b := i AND w;
    w := w AND 16#F0F0;
    i := i AND 3;
    b := s = 'x';
    r := s * 2;
    t := t * 2;
    t := dt1 - dt1;
    dt1 := dt1 + t;
    t := t + 1;
    i := i MOD 2;
    r := r MOD 2.0;
    r := i ** 2;
    b := NOT b;
    r := NOT r;
    i := -i;
    w := -w;
END_PROGRAM",
        &[
            ("E030", 5),
            ("E031", 6),
            ("E031", 7),
            ("E031", 11),
            ("E031", 15),
            ("E031", 17),
            ("E031", 20),
            ("E031", 22),
        ],
    );
    let m = messages("PROGRAM p\nVAR b : BOOL; i : INT; END_VAR\n b := b + i;\nEND_PROGRAM");
    assert_eq!(m, ["operator `+` is not defined for BOOL and INT"]);
}

#[test]
fn poison_silences_follow_on_errors() {
    // One unknown name deep in an expression gives one error, not one per operator.
    check(
        "PROGRAM P
VAR i : INT; b : BOOL; END_VAR
    i := (nothing + 1) * 2 - i;
    b := nothing2 AND b OR TRUE;
    IF nothing3 > 0 THEN i := 1; END_IF;
    i := LIMIT(0, nothing4, 10);
    i := nothing5[1].x.y;
    nothing6.a := 1;
END_PROGRAM",
        &[
            ("E020", 3),
            ("E020", 4),
            ("E020", 5),
            ("E020", 6),
            ("E020", 7),
            ("E020", 8),
        ],
    );
}

#[test]
fn multiple_independent_errors_in_one_file() {
    check(
        "PROGRAM P
VAR i : INT; d : DINT; b : BOOL; c : INT := 1; END_VAR
VAR CONSTANT k : INT := 1; END_VAR
    i := d;
    undefined := 1;
    IF i THEN b := TRUE; END_IF;
    k := 2;
    EXIT;
    i := b + 1;
    TON(IN := TRUE);
    b := i;
END_PROGRAM",
        &[
            ("E030", 4),
            ("E020", 5),
            ("E032", 6),
            ("E040", 7),
            ("E060", 8),
            ("E031", 9),
            ("E053", 10),
            ("E030", 11),
        ],
    );
}

#[test]
fn conditions_are_bool() {
    check(
        "PROGRAM P
VAR i : INT; b : BOOL; w : WORD; END_VAR
    IF i THEN b := TRUE; END_IF;
    IF b THEN i := 1; ELSIF w THEN i := 2; END_IF;
    WHILE 1 DO EXIT; END_WHILE;
    REPEAT i := i + 1; UNTIL i END_REPEAT;
    WHILE b AND i > 0 DO EXIT; END_WHILE;
END_PROGRAM",
        &[("E032", 3), ("E032", 4), ("E032", 5), ("E032", 6)],
    );
}

#[test]
fn case_selector_and_labels() {
    check(
        "TYPE Color : (Red, Green, Blue); Size : (Small, Big); END_TYPE
PROGRAM P
VAR i : INT; s : SINT; c : Color; r : REAL; n : INT; END_VAR
VAR CONSTANT K : INT := 10; END_VAR
    CASE i OF
        1, 2: n := 1;
        K - 1: n := 2;
        3..5: n := 3;
        9..7: n := 4;
        n: n := 5;
        1.5: n := 6;
    END_CASE;
    CASE s OF 300: n := 1; END_CASE;
    CASE c OF
        Red: n := 1;
        Green, Blue: n := 2;
        Small: n := 3;
        1: n := 4;
    END_CASE;
    CASE r OF 1: n := 1; END_CASE;
END_PROGRAM",
        &[
            ("E033", 9),
            ("E070", 10),
            ("E033", 11),
            ("E033", 13),
            ("E033", 17),
            ("E033", 18),
            ("E030", 20),
        ],
    );
}

#[test]
fn for_loops() {
    check(
        "VAR_GLOBAL g : INT; END_VAR
PROGRAM P
VAR i : INT; r : REAL; d : DINT; END_VAR
VAR CONSTANT k : INT := 1; END_VAR
VAR_EXTERNAL g : INT; END_VAR
    FOR i := 1 TO 10 BY 2 DO EXIT; END_FOR;
    FOR r := 1 TO 10 DO ; END_FOR;
    FOR i := 1 TO d DO ; END_FOR;
    FOR i := 1 TO 10 BY 0 DO ; END_FOR;
    FOR k := 1 TO 10 DO ; END_FOR;
    FOR g := 1 TO 10 DO ; END_FOR;
    FOR nope := 1 TO 10 DO ; END_FOR;
    FOR i := 1 TO 10 DO CONTINUE; END_FOR;
END_PROGRAM",
        &[
            ("E062", 7),
            ("E062", 8),
            ("E062", 9),
            ("E040", 10),
            ("E062", 11),
            ("E020", 12),
        ],
    );
}

#[test]
fn exit_and_continue_outside_loops() {
    check(
        "PROGRAM P
VAR b : BOOL; END_VAR
    EXIT;
    IF b THEN CONTINUE; END_IF;
    WHILE b DO
        IF b THEN EXIT; END_IF;
        REPEAT CONTINUE; UNTIL b END_REPEAT;
    END_WHILE;
    CONTINUE;
END_PROGRAM",
        &[("E060", 3), ("E061", 4), ("E061", 9)],
    );
}

#[test]
fn constant_and_input_assignment() {
    check(
        "FUNCTION_BLOCK FB
VAR_INPUT in1 : INT; END_VAR
VAR_OUTPUT out1 : INT; END_VAR
VAR_IN_OUT io : INT; END_VAR
VAR CONSTANT c : INT := 1; END_VAR
    in1 := 1;
    out1 := in1;
    io := 2;
    c := 3;
END_FUNCTION_BLOCK
PROGRAM P
VAR f : FB; x : INT; END_VAR
    f.in1 := 5;
    f.out1 := 5;
    x := f.out1;
    f(io := x, out1 => x);
END_PROGRAM",
        &[("E041", 6), ("E040", 9), ("E042", 14)],
    );
}

#[test]
fn not_assignable_and_no_effect() {
    check(
        "TYPE Color : (Red, Green); END_TYPE
FUNCTION F : INT
    F := 1;
END_FUNCTION
PROGRAM P
VAR i : INT; END_VAR
    i + 1 := 2;
    F() := 3;
    Red := Green;
    i + 1;
    i;
    F();
END_PROGRAM",
        &[
            ("E042", 7),
            ("E042", 8),
            ("E042", 9),
            ("E063", 10),
            ("E063", 11),
        ],
    );
}

#[test]
fn bit_access() {
    check(
        "PROGRAM P
VAR w : WORD; d : DINT; b : BOOL; r : REAL; bt : BYTE; x : BOOL; END_VAR
    x := w.15;
    x := w.16;
    x := d.%X31;
    x := r.1;
    x := b.0;
    bt := w.%B1;
    bt := w.%B2;
    w.3 := TRUE;
    d := d.%W1;
END_PROGRAM",
        &[
            ("E037", 4),
            ("E037", 6),
            ("E037", 7),
            ("E037", 9),
            ("E030", 11),
        ],
    );
}

#[test]
fn arrays_index_count_type_and_constant_range() {
    check(
        "PROGRAM P
VAR
    a : ARRAY[1..10] OF INT;
    m : ARRAY[0..2, 0..3] OF BOOL;
    i : INT; r : REAL; x : INT;
END_VAR
VAR CONSTANT last : INT := 10; END_VAR
    x := a[1] + a[last] + a[i];
    x := a[0];
    x := a[11];
    x := a[last + 1];
    x := a[1, 2];
    m[2, 3] := TRUE;
    m[3, 0] := TRUE;
    m[1] := TRUE;
    x := a[r];
    x := i[1];
END_PROGRAM",
        &[
            ("E035", 9),
            ("E035", 10),
            ("E035", 11),
            ("E034", 12),
            ("E035", 14),
            ("E034", 15),
            ("E030", 16),
            ("E036", 17),
        ],
    );
    let m = messages("PROGRAM p\nVAR a : ARRAY[1..10] OF INT; END_VAR\n a[11] := 0;\nEND_PROGRAM");
    assert_eq!(m, ["index 11 is out of range 1..10 of `a`"]);
}

#[test]
fn structures_and_instance_members() {
    check(
        "TYPE Point : STRUCT x : INT; y : INT; END_STRUCT; END_TYPE
FUNCTION_BLOCK FB
VAR_INPUT i1 : INT; END_VAR
VAR_OUTPUT o1 : INT; END_VAR
VAR secret : INT; END_VAR
END_FUNCTION_BLOCK
PROGRAM P
VAR p : Point; f : FB; n : INT; t : TON; END_VAR
    p.x := 1;
    n := p.z;
    n := f.o1 + f.i1;
    n := f.secret;
    n := f.nothing;
    n := n.x;
    t(IN := TRUE, PT := T#1s);
    IF t.Q THEN n := 1; END_IF;
    n := TIME_TO_INT(t.ET);
END_PROGRAM",
        &[("E024", 10), ("E024", 12), ("E024", 13), ("E036", 14)],
    );
}

#[test]
fn subranges_check_constants() {
    check(
        "TYPE Percent : INT (0..100); END_TYPE
PROGRAM P
VAR p : Percent; i : INT; d : DINT; END_VAR
    p := 50;
    p := 101;
    p := i;
    i := p;
    d := p;
    p := -1;
END_PROGRAM",
        &[("E038", 5), ("E038", 9)],
    );
}

#[test]
fn references_and_dereference() {
    clean(
        "PROGRAM P
VAR
    x : INT;
    p : REF_TO INT;
    q : POINTER TO INT;
END_VAR
    p := REF(x);
    q := ADR(x);
    p^ := 5;
    x := p^ + q^;
END_PROGRAM",
    );
    check(
        "PROGRAM P
VAR x : INT; r : REAL; p : REF_TO INT; END_VAR
    p := REF(r);
    x := x^;
    p := REF(5);
END_PROGRAM",
        &[("E030", 3), ("E031", 4), ("E042", 5)],
    );
}

#[test]
fn time_and_date_arithmetic() {
    clean(
        "PROGRAM P
VAR t : TIME; lt : LTIME; d : DATE; tod1 : TOD; dt1 : DT; i : INT; r : REAL; END_VAR
    t := T#1s + T#500ms;
    t := t * 2;
    t := t / r;
    t := 3 * t;
    lt := lt - t;
    dt1 := dt1 + t;
    dt1 := dt1 - t;
    t := dt1 - dt1;
    tod1 := tod1 + t;
    t := tod1 - tod1;
    t := d - d;
    t := -t;
    IF t > T#1s AND d <> D#2024-01-01 THEN i := 1; END_IF;
END_PROGRAM",
    );
}

#[test]
fn direct_addresses_in_code() {
    check(
        "PROGRAM P
VAR b : BOOL; w : WORD; i : INT; END_VAR
    b := %IX0.1;
    w := %IW2;
    %QX0.0 := b;
    i := %IW2;
    b := %I*;
END_PROGRAM",
        &[("E030", 6), ("E084", 7)],
    );
}

#[test]
fn unreachable_statements_are_warned_once_per_block() {
    check(
        "FUNCTION F : INT
VAR_INPUT x : INT; END_VAR
    F := 0;
    WHILE x > 0 DO
        EXIT;
        F := 1;
        F := 2;
    END_WHILE;
    IF x > 1 THEN RETURN; ; END_IF;
    RETURN;
    F := 3;
END_FUNCTION",
        &[("W002", 6), ("W002", 11)],
    );
}
