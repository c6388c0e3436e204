mod common;
use common::{body, ok};

#[test]
fn assignments_calls_and_simple_statements() {
    assert_eq!(body("x := 1;"), "[x := 1]");
    assert_eq!(body("a.b[1] := f(2);"), "[(index (. a b) 1) := (call f 2)]");
    assert_eq!(body("p^ := 0;"), "[(^ p) := 0]");
    assert_eq!(
        body("fb(IN := x, Q => y);"),
        "[(call fb (IN := x) (Q => y))]"
    );
    assert_eq!(body("f(a, b);"), "[(call f a b)]");
    assert_eq!(
        body("RETURN; EXIT; CONTINUE; ;"),
        "[RETURN; EXIT; CONTINUE; EMPTY]"
    );
    assert_eq!(body(""), "[]");
    // A non-call expression statement is syntax; sema rejects it (E063).
    assert_eq!(body("x = 1;"), "[(= x 1)]");
    assert_eq!(body("w.3 := TRUE;"), "[(.% w None 3) := TRUE]");
}

#[test]
fn if_elsif_else() {
    assert_eq!(body("IF a THEN x := 1; END_IF;"), "[IF a [x := 1]]");
    assert_eq!(
        body("IF a THEN x := 1; ELSIF b THEN x := 2; ELSIF c THEN ; ELSE x := 3; y := 4; END_IF;"),
        "[IF a [x := 1] b [x := 2] c [EMPTY] ELSE [x := 3; y := 4]]"
    );
    assert_eq!(
        body("IF a THEN IF b THEN x := 1; END_IF; END_IF;"),
        "[IF a [IF b [x := 1]]]"
    );
    assert_eq!(body("if a then else end_if;"), "[IF a [] ELSE []]");
}

#[test]
fn case_labels_values_lists_ranges_enums() {
    assert_eq!(
        body("CASE x OF 1: y := 1; 2, 3, 5..7: y := 2; z := 3; -1: ; ELSE y := 0; END_CASE;"),
        "[CASE x | 1: [y := 1] | 2,3,5..7: [y := 2; z := 3] | (neg 1): [EMPTY] | ELSE [y := 0]]"
    );
    assert_eq!(
        body("CASE c OF Red: y := 1; Color#Green, Blue: y := 2; END_CASE;"),
        "[CASE c | Red: [y := 1] | Color#Green,Blue: [y := 2]]"
    );
    assert_eq!(
        body("CASE c OF 1: IF a THEN b := 1; END_IF; 2: c(); END_CASE;"),
        "[CASE c | 1: [IF a [b := 1]] | 2: [(call c)]]"
    );
    assert_eq!(body("CASE c OF END_CASE;"), "[CASE c]");
    assert_eq!(
        body("CASE c OF 1..2: ; E.A: ; END_CASE;"),
        "[CASE c | 1..2: [EMPTY] | (. E A): [EMPTY]]"
    );
}

#[test]
fn loops() {
    assert_eq!(
        body("FOR i := 1 TO 10 DO x := x + i; END_FOR;"),
        "[FOR i 1 10 - [x := (+ x i)]]"
    );
    assert_eq!(
        body("FOR i := 10 TO 0 BY -2 DO EXIT; END_FOR;"),
        "[FOR i 10 0 (neg 2) [EXIT]]"
    );
    assert_eq!(
        body("WHILE a < 10 DO a := a + 1; CONTINUE; END_WHILE;"),
        "[WHILE (< a 10) [a := (+ a 1); CONTINUE]]"
    );
    assert_eq!(
        body("REPEAT a := a - 1; UNTIL a = 0 END_REPEAT;"),
        "[REPEAT [a := (- a 1)] UNTIL (= a 0)]"
    );
}

#[test]
fn statement_spans_end_at_end_keyword() {
    let out = ok("PROGRAM p\nIF a THEN\n  x := 1;\nEND_IF;\nEND_PROGRAM\n");
    let s = &out.body(0)[0];
    assert_eq!(out.text(s.span), "IF a THEN\n  x := 1;\nEND_IF");
    let automat_syntax::ast::StmtKind::If { branches, .. } = &s.kind else {
        panic!()
    };
    assert_eq!(out.text(branches[0].body[0].span), "x := 1");
}

#[test]
fn comments_and_pragmas_anywhere() {
    assert_eq!(
        body("x := (* c (* nested *) *) 1; // end\n{attribute 'hide'} /* c */ y := 2;"),
        "[x := 1; y := 2]"
    );
}
