//! Constructs that used to be E091: EN/ENO, ARRAY[*] and array bounds,
//! references, SIZEOF, BCD, dates, ATAN2, STRING <-> WSTRING, time
//! arithmetic functions; and the reuse of string scratch buffers.

mod common;
use common::*;

#[test]
fn en_eno_on_function_fb_and_standard_calls() {
    let mut p = build(
        "FUNCTION Twice : INT VAR_INPUT x : INT; END_VAR Twice := 2 * x; END_FUNCTION
         FUNCTION_BLOCK Cnt VAR_OUTPUT n : INT; END_VAR n := n + 1; END_FUNCTION_BLOCK
         PROGRAM Main
         VAR go : BOOL; a : INT := 7; b : INT := 7; e1 : BOOL := TRUE; e2 : BOOL; e3 : BOOL := TRUE;
             e4 : BOOL; c : Cnt; d : Cnt; fe : BOOL; ge : BOOL; s : INT := 9; e5 : BOOL := TRUE; END_VAR
         a := Twice(EN := go, x := 5, ENO => e1);
         b := Twice(EN := TRUE, x := 5, ENO => e2);
         c(EN := go, ENO => e3);
         d(ENO => e4);
         fe := c.ENO;
         ge := d.ENO;
         s := ADD(EN := go, IN1 := 1, IN2 := 2, ENO => e5);
         END_PROGRAM",
    );
    p.run(1);
    // EN FALSE: skipped, result zero, ENO FALSE.
    assert_eq!(p.int("Main.a"), 0);
    assert_eq!(p.int("Main.e1"), 0);
    assert_eq!(p.int("Main.b"), 10);
    assert_eq!(p.int("Main.e2"), 1);
    assert_eq!(p.int("Main.c.n"), 0);
    assert_eq!(p.int("Main.e3"), 0);
    assert_eq!(p.int("Main.d.n"), 1);
    assert_eq!(p.int("Main.e4"), 1);
    assert_eq!(p.int("Main.fe"), 0);
    assert_eq!(p.int("Main.ge"), 1);
    assert_eq!(p.int("Main.s"), 0);
    assert_eq!(p.int("Main.e5"), 0);
    p.set_int("Main.go", 1);
    p.run(1);
    assert_eq!(p.int("Main.a"), 10);
    assert_eq!(p.int("Main.e1"), 1);
    assert_eq!(p.int("Main.c.n"), 1);
    assert_eq!(p.int("Main.e3"), 1);
    assert_eq!(p.int("Main.fe"), 1);
    assert_eq!(p.int("Main.s"), 3);
    assert_eq!(p.int("Main.e5"), 1);
}

#[test]
fn arrays_of_unknown_size_and_bounds() {
    let mut p = build(
        "FUNCTION Sum : DINT
         VAR_IN_OUT a : ARRAY[*] OF INT; END_VAR
         VAR i : DINT; END_VAR
         FOR i := LOWER_BOUND(a, 1) TO UPPER_BOUND(a, 1) DO Sum := Sum + a[i]; END_FOR;
         END_FUNCTION
         FUNCTION Corner : INT
         VAR_IN_OUT m : ARRAY[*, *] OF INT; END_VAR
         Corner := m[UPPER_BOUND(m, 1), UPPER_BOUND(m, 2)];
         m[LOWER_BOUND(m, 1), LOWER_BOUND(m, 2)] := 99;
         END_FUNCTION
         FUNCTION Outer : DINT
         VAR_IN_OUT a : ARRAY[*] OF INT; END_VAR
         Outer := Sum(a) + UPPER_BOUND(a, 1);
         END_FUNCTION
         PROGRAM Main
         VAR v : ARRAY[-2..2] OF INT := [1, 2, 3, 4, 5]; w : ARRAY[1..3] OF INT := [10, 20, 30];
             g : ARRAY[0..1, 5..7] OF INT := [1, 2, 3, 4, 5, 6];
             s1 : DINT; s2 : DINT; c : INT; o : DINT; lo : DINT; hi : DINT; k : INT := 2; END_VAR
         s1 := Sum(v);
         s2 := Sum(a := w);
         c := Corner(g);
         o := Outer(w);
         lo := LOWER_BOUND(g, k);
         hi := UPPER_BOUND(v, 1);
         END_PROGRAM",
    );
    p.run(1);
    assert_eq!(p.int("Main.s1"), 15);
    assert_eq!(p.int("Main.s2"), 60);
    assert_eq!(p.int("Main.c"), 6);
    assert_eq!(p.int("Main.g[0, 5]"), 99);
    assert_eq!(p.int("Main.o"), 63);
    assert_eq!(p.int("Main.lo"), 5);
    assert_eq!(p.int("Main.hi"), 2);
}

#[test]
fn references_and_sizeof() {
    let mut p = build(
        "TYPE Pt : STRUCT x : INT; y : LREAL; END_STRUCT; END_TYPE
         PROGRAM Main
         VAR a : INT := 5; b : INT := 6; r : REF_TO INT; q : REF_TO Pt; pt : Pt;
             v1 : INT; v2 : INT; n1 : UDINT; n2 : UDINT; n3 : UDINT; END_VAR
         r := REF(a);
         v1 := r^;
         r^ := 50;
         r := REF(b);
         r^ := r^ + 1;
         v2 := a;
         q := REF(pt);
         q^.y := 2.5;
         q^.x := 3;
         n1 := SIZEOF(pt);
         n2 := SIZEOF(a);
         n3 := SIZEOF(r);
         END_PROGRAM",
    );
    p.run(1);
    assert_eq!(p.int("Main.v1"), 5);
    assert_eq!(p.int("Main.v2"), 50);
    assert_eq!(p.int("Main.b"), 7);
    assert_eq!(p.int("Main.pt.x"), 3);
    assert_eq!(p.real("Main.pt.y"), 2.5);
    assert_eq!(p.int("Main.n1"), 16);
    assert_eq!(p.int("Main.n2"), 2);
    assert_eq!(p.int("Main.n3"), 4);
}

#[test]
fn bcd_dates_atan2_strings_and_time_functions() {
    let mut p = build(
        "PROGRAM Main
         VAR i : INT; w : WORD; b : BYTE; d : DATE; t : TOD; dt1 : DT; dow : INT;
             y : INT; mo : INT; dd : INT; h : INT; mi : INT; sec : INT; ms : INT;
             y2 : DINT; h2 : DINT; mo2 : SINT; dd2 : UINT; mi2 : LINT; sec2 : USINT; ms2 : UDINT; a : LREAL; ar : REAL;
             s : STRING := 'Grüße'; ws : WSTRING; s2 : STRING; tm : TIME; diff : TIME; END_VAR
         i := WORD_BCD_TO_INT(16#1234);
         w := INT_TO_BCD_WORD(4321);
         b := USINT_TO_BCD(99);
         d := CONCAT_DATE(2024, 2, 29);
         t := CONCAT_TOD(13, 14, 15, 16);
         dt1 := CONCAT_DT(2024, 3, 1, 1, 2, 3, 4);
         dow := DAY_OF_WEEK(d);
         SPLIT_DT(IN := dt1, YEAR => y, MONTH => mo, DAY => dd, HOUR => h, MINUTE => mi,
                  SECOND => sec, MILLISECOND => ms);
         SPLIT_DATE(IN := d, YEAR => y2, MONTH => mo2, DAY => dd2);
         SPLIT_TOD(IN := t, HOUR => h2, MINUTE => mi2, SECOND => sec2, MILLISECOND => ms2);
         a := ATAN2(1.0, -1.0);
         ar := ATAN2(REAL#0.0, REAL#2.0);
         ws := STRING_TO_WSTRING(s);
         s2 := WSTRING_TO_STRING(ws);
         tm := ADD_TIME(T#1s, T#250ms);
         diff := SUB_DATE_DATE(D#2024-03-01, D#2024-02-28);
         END_PROGRAM",
    );
    p.run(1);
    assert_eq!(p.int("Main.i"), 1234);
    assert_eq!(p.int("Main.w"), 0x4321);
    assert_eq!(p.int("Main.b"), 0x99);
    assert_eq!(p.int("Main.d"), 19_782);
    assert_eq!(p.int("Main.t"), 47_655_016_000_000);
    assert_eq!(p.int("Main.dow"), 4);
    assert_eq!(
        [
            p.int("Main.y"),
            p.int("Main.mo"),
            p.int("Main.dd"),
            p.int("Main.h"),
            p.int("Main.mi"),
            p.int("Main.sec"),
            p.int("Main.ms")
        ],
        [2024, 3, 1, 1, 2, 3, 4]
    );
    assert_eq!(
        [p.int("Main.y2"), p.int("Main.mo2"), p.int("Main.dd2")],
        [2024, 2, 29]
    );
    assert_eq!(
        [
            p.int("Main.h2"),
            p.int("Main.mi2"),
            p.int("Main.sec2"),
            p.int("Main.ms2")
        ],
        [13, 14, 15, 16]
    );
    assert_eq!(p.real("Main.a"), 3.0 * std::f64::consts::FRAC_PI_4);
    assert_eq!(p.real("Main.ar"), 0.0);
    assert_eq!(p.string("Main.ws"), "Grüße");
    assert_eq!(p.string("Main.s2"), "Grüße");
    assert_eq!(p.int("Main.tm"), 1_250_000_000);
    assert_eq!(p.int("Main.diff"), 2 * 86_400_000_000_000);
}

#[test]
fn invalid_bcd_is_a_function_fault() {
    let mut p = build(
        "PROGRAM Main
         VAR w : WORD := 16#12A4; i : INT; END_VAR
         i := WORD_BCD_TO_INT(w);
         END_PROGRAM",
    );
    let f = p.scan().unwrap_err();
    assert_eq!(f.kind, automat_ir::FaultKind::Function);
    assert!(f.message.contains("16#12A4"), "{}", f.message);
    assert_eq!(f.site.pou, "Main");
    assert_eq!(f.site.location, "test.st:3:15");
}

#[test]
fn string_scratch_is_reused_per_statement() {
    let one = "s := CONCAT(s, 'x');\n".to_string();
    let many = "s := CONCAT(s, 'x');\n".repeat(40);
    let src = |body: &str| {
        format!(
            "PROGRAM Main VAR s : STRING; END_VAR
             {body}
             END_PROGRAM"
        )
    };
    let a = build(&src(&one)).engine.program().image_size;
    let mut pb = build(&src(&many));
    let b = pb.engine.program().image_size;
    // 39 more call sites add only their literals ('x' = 3 bytes, 2-aligned: 4 each).
    assert!(b - a <= 39 * 8, "{a} -> {b}");
    pb.run(1);
    assert_eq!(pb.string("Main.s"), "x".repeat(40));
}

#[test]
fn en_false_gives_an_empty_string_and_zero_real() {
    let mut p = build(
        "FUNCTION Greet : STRING VAR_INPUT n : STRING; END_VAR Greet := CONCAT('hi ', n); END_FUNCTION
         PROGRAM Main
         VAR go : BOOL; s : STRING := 'old'; t : STRING := 'old'; r : REAL := 1.5; END_VAR
         s := Greet(EN := go, n := 'bob');
         t := CONCAT(EN := NOT go, IN1 := 'a', IN2 := 'b');
         r := SQRT(EN := go, IN := REAL#16.0);
         END_PROGRAM",
    );
    p.run(1);
    assert_eq!(p.string("Main.s"), "");
    assert_eq!(p.string("Main.t"), "ab");
    assert_eq!(p.real("Main.r"), 0.0);
    p.set_int("Main.go", 1);
    p.run(1);
    assert_eq!(p.string("Main.s"), "hi bob");
    assert_eq!(p.string("Main.t"), "");
    assert_eq!(p.real("Main.r"), 4.0);
}
