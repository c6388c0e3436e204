//! Diagnostics and recovery: each independent mistake gives exactly one
//! error, at the offending token, and parsing goes on.

mod common;
use automat_syntax::MAX_DEPTH;
use common::{errors, messages, parse};

#[test]
fn several_independent_errors_in_one_file() {
    let src = "\
PROGRAM p
VAR
  a : INT
  b : INT;
  c : ;
END_VAR
a := 1
b := 2;
IF a > b
  c := 3;
END_IF;
x := 16#G0;
y := (a + ;
WHILE a DO b := 1; END_IF;
END_WHILE;
z := 'abc;
w := %IY0;
q := 99999999999999999999999;
END_PROGRAM
";
    assert_eq!(
        errors(src),
        vec![
            ("E005", 4),  // missing `;` after `a : INT`
            ("E005", 5),  // no type after `c :`
            ("E005", 7),  // missing `;` after `a := 1`, at the end of its line
            ("E005", 10), // missing THEN
            ("E004", 12), // 16#G0
            ("E005", 13), // no operand after `+`
            ("E005", 14), // stray END_IF inside WHILE
            ("E003", 16), // unterminated string (eats the `;`: no second error)
            ("E007", 17), // %IY0
            ("E006", 18), // integer literal overflow
        ]
    );
}

#[test]
fn errors_in_several_pous_and_types() {
    let src = "\
TYPE
  E : (A, B;
  S : STRUCT x : INT; END_STRUCT
  T : INT;
END_TYPE
FUNCTION f : INT
  f := ;
END_FUNCTION
FUNCTION_BLOCK fb
  VAR_INPUT i : BOOL R_EDGE END_VAR
  IF i THEN
    x := 1;
END_FUNCTION_BLOCK
junk;
PROGRAM p
  y := f(1, 2;
END_PROGRAM
";
    assert_eq!(
        errors(src),
        vec![
            ("E005", 2),  // `)` missing in the enumeration
            ("E005", 7),  // no expression
            ("E005", 10), // missing `;` before END_VAR
            ("E005", 13), // IF not closed
            ("E005", 14), // junk at top level
            ("E005", 16), // `)` missing in the call
        ]
    );
}

#[test]
fn messages_name_what_was_expected_and_found() {
    assert_eq!(
        messages("PROGRAM p\nIF a THEN x := 1 END_IF;\nEND_PROGRAM"),
        vec!["expected `;` after the assignment, found `END_IF`"]
    );
    assert_eq!(
        messages("PROGRAM p\nIF a x := 1; END_IF;\nEND_PROGRAM"),
        vec!["expected `THEN` after the IF condition, found identifier `x`"]
    );
    assert_eq!(
        messages("PROGRAM p\nIF a THEN x := 1; END_PROGRAM"),
        vec!["expected `END_IF` to close this `IF`, found `END_PROGRAM`"]
    );
    assert_eq!(
        messages("PROGRAM p\nx := 1 + ;\nEND_PROGRAM"),
        vec!["expected an expression, found `;`"]
    );
    assert_eq!(
        messages("PROGRAM p\nEND_IF;\nEND_PROGRAM"),
        vec!["unexpected `END_IF` here: it does not continue an open `IF`"]
    );
    assert_eq!(
        messages("PROGRAM p\nx := T#5q;\nEND_PROGRAM"),
        vec!["malformed duration literal `T#5q`: `q` is not a unit (d, h, m, s, ms, us or ns)"]
    );
    assert_eq!(
        messages("PROGRAM p VAR x AT %IY0 : BOOL; END_VAR END_PROGRAM"),
        vec!["invalid direct address `%IY0`: `Y` is not a size (X, B, W, D or L)"]
    );
}

#[test]
fn spans_point_at_the_offending_token() {
    let src = "PROGRAM p\nIF a THEN x := 1 END_IF;\nEND_PROGRAM";
    let out = parse(src);
    assert_eq!(out.text(out.diags[0].span), "END_IF");
    let src = "PROGRAM p\nx := 16#G0 + 1;\nEND_PROGRAM";
    let out = parse(src);
    assert_eq!(out.text(out.diags[0].span), "16#G0");
    let src = "PROGRAM p\nIF a THEN\nEND_PROGRAM";
    let out = parse(src);
    assert_eq!(out.text(out.diags[0].span), "END_PROGRAM");
    assert_eq!(out.text(out.diags[0].labels[0].span), "IF");
}

#[test]
fn one_missing_semicolon_is_one_error() {
    assert_eq!(
        errors("PROGRAM p\nx := 1\ny := 2\nz := 3;\nEND_PROGRAM"),
        vec![("E005", 2), ("E005", 3)]
    );
    // On one line the rest of the statement is skipped, not re-parsed.
    assert_eq!(
        errors("PROGRAM p\nx := 1 2 3 4;\ny := 2;\nEND_PROGRAM"),
        vec![("E005", 2)]
    );
    assert_eq!(
        errors("PROGRAM p\nIF a THEN x := 1; END_IF\nEND_PROGRAM"),
        vec![("E005", 2)]
    );
}

#[test]
fn unclosed_blocks_report_once() {
    assert_eq!(
        errors("PROGRAM p\nWHILE a DO\n  IF b THEN\n    c := 1;\nEND_WHILE;\nEND_PROGRAM"),
        vec![("E005", 5)]
    );
    assert_eq!(
        errors("PROGRAM p\nVAR\n  x : INT;\nx := 1;\nEND_PROGRAM"),
        vec![("E005", 4)]
    );
    assert_eq!(
        errors("PROGRAM p\nx := 1;\nEND_FUNCTION\nPROGRAM q\nEND_PROGRAM"),
        vec![("E005", 3)]
    );
    assert_eq!(
        errors("PROGRAM p\nCASE x OF 1: y := 2;\nEND_PROGRAM"),
        vec![("E005", 3)]
    );
    assert_eq!(
        errors("TYPE\n  S : STRUCT a : INT;\nEND_TYPE\nPROGRAM p END_PROGRAM"),
        vec![("E005", 3)]
    );
    assert_eq!(
        errors("PROGRAM p\nIF a THEN x := 1; ELSE y := 2; ELSE z := 3; END_IF;\nEND_PROGRAM"),
        vec![("E005", 2)]
    );
}

#[test]
fn lexical_errors_do_not_cascade_into_syntax_errors() {
    assert_eq!(
        errors("PROGRAM p\nx := 5 @ 3;\ny := 1;\nEND_PROGRAM"),
        vec![("E001", 2)]
    );
    assert_eq!(
        errors("PROGRAM p\nx := 'abc;\ny := 1;\nEND_PROGRAM"),
        vec![("E003", 2)]
    );
    assert_eq!(
        errors("PROGRAM p\nx := 1; (* never closed\ny := 1;\nEND_PROGRAM"),
        vec![("E002", 2)]
    );
}

#[test]
fn top_level_recovery_skips_to_the_next_pou() {
    let out =
        parse("garbage 1 2 3;\nPROGRAM a END_PROGRAM\n)))\nFUNCTION_BLOCK b END_FUNCTION_BLOCK");
    assert_eq!(out.diags.len(), 2);
    assert_eq!(out.unit.items.len(), 2);
}

#[test]
fn deep_nesting_is_an_error_not_a_crash() {
    let deep = format!(
        "PROGRAM p\nx := {}1{};\nEND_PROGRAM",
        "(".repeat(10_000),
        ")".repeat(10_000)
    );
    let msgs = messages(&deep);
    assert_eq!(msgs, vec!["nesting too deep: more than 256 levels"]);
    assert_eq!(MAX_DEPTH, 256);

    let ifs = format!(
        "PROGRAM p\n{}x := 1;\n{}y := 2;\nEND_PROGRAM",
        "IF a THEN\n".repeat(1000),
        "END_IF;\n".repeat(1000)
    );
    let out = parse(&ifs);
    assert_eq!(out.diags.len(), 1);
    assert_eq!(out.stmts(&out.body(0)[1..]), "[y := 2]");

    let unary = format!("PROGRAM p\nx := {}1;\nEND_PROGRAM", "-".repeat(5000));
    assert_eq!(parse(&unary).diags.len(), 1);
    let not = format!("PROGRAM p\nx := {}a;\nEND_PROGRAM", "NOT ".repeat(5000));
    assert_eq!(parse(&not).diags.len(), 1);
    let arrays = format!("TYPE T : {}INT; END_TYPE", "ARRAY [1..2] OF ".repeat(2000));
    assert_eq!(parse(&arrays).diags.len(), 1);
    let inits = format!(
        "PROGRAM p VAR x : T := {}; END_VAR END_PROGRAM",
        "[".repeat(3000)
    );
    assert!(!parse(&inits).diags.is_empty());
}

#[test]
fn nesting_up_to_the_limit_is_fine() {
    let n = 200;
    let src = format!(
        "PROGRAM p\nx := {}1{};\nEND_PROGRAM",
        "(".repeat(n),
        ")".repeat(n)
    );
    assert!(parse(&src).diags.is_empty());
}

/// Every kind of nesting, just under the limit, on a default-sized test
/// thread (2 MiB) in a debug build: the cap keeps the stack bounded.
#[test]
fn nesting_just_under_the_limit_fits_the_stack() {
    let n = 250;
    let wrap = |stmts: String| format!("PROGRAM p\n{stmts}\nEND_PROGRAM");
    let cases = [
        wrap(format!("x := {}1{};", "(".repeat(n), ")".repeat(n))),
        wrap(format!("x := {}1{};", "f(".repeat(n), ")".repeat(n))),
        wrap(format!("x := {}1{};", "a[".repeat(n), "]".repeat(n))),
        wrap(format!("x := {}1;", "NOT -".repeat(n / 2))),
        wrap(format!(
            "{}x := 1;{}",
            "IF a THEN ".repeat(n),
            " END_IF;".repeat(n)
        )),
        wrap(format!(
            "{}x := 1;{}",
            "CASE a OF 1: ".repeat(n),
            " END_CASE;".repeat(n)
        )),
        wrap(format!(
            "{}x := 1;{}",
            "WHILE a DO ".repeat(n),
            " END_WHILE;".repeat(n)
        )),
        wrap(format!(
            "{}x := 1;{}",
            "FOR i := 1 TO 2 DO ".repeat(n),
            " END_FOR;".repeat(n)
        )),
        wrap(format!(
            "{}x := 1;{}",
            "REPEAT ".repeat(n),
            " UNTIL a END_REPEAT;".repeat(n)
        )),
        format!("TYPE T : {}INT; END_TYPE", "ARRAY [1..2] OF ".repeat(n)),
        format!("TYPE T : {}INT; END_TYPE", "REF_TO ".repeat(n)),
        format!(
            "TYPE T : {} a : INT; {} END_TYPE",
            "STRUCT s : ".repeat(n - 1) + "STRUCT",
            "END_STRUCT; ".repeat(n)
        ),
        format!(
            "PROGRAM p VAR x : T := {}1{}; END_VAR END_PROGRAM",
            "[".repeat(n),
            "]".repeat(n)
        ),
        format!(
            "PROGRAM p VAR x : T := {}1{}; END_VAR END_PROGRAM",
            "(a := ".repeat(n),
            ")".repeat(n)
        ),
    ];
    for (i, src) in cases.iter().enumerate() {
        let out = parse(src);
        assert!(out.diags.is_empty(), "case {i}: {:?}", out.diags.first());
        // One more level of the same: an error, never a crash.
        assert!(out.unit.items.len() == 1, "case {i}");
    }
}

/// Left-associative chains build trees as deep as they are long, so each
/// link counts as a level: every tree the parser returns has a bounded
/// depth, and dropping or walking it cannot overflow the stack.
#[test]
fn long_chains_are_bounded_too() {
    let n = 100_000;
    let chains = [
        format!("x := a{};", " + a".repeat(n)),
        format!("x := a{};", " ** a".repeat(n)),
        format!("x := s{};", ".m".repeat(n)),
        format!("x := p{};", "^".repeat(n)),
        format!("x := f{};", "()".repeat(n)),
        format!("x := a{};", "[1]".repeat(n)),
        format!("x := w{};", ".%X1".repeat(n)),
    ];
    for c in &chains {
        let out = parse(&format!("PROGRAM p\n{c}\ny := 1;\nEND_PROGRAM"));
        assert_eq!(out.diags.len(), 1, "{}", &c[..20]);
        // `a[1][1]...` may hit the limit inside an index: either message.
        let m = &out.diags[0].message;
        assert!(
            m.starts_with("expression too long") || m.starts_with("nesting too deep"),
            "{m}"
        );
        // The statement after the long one is intact.
        assert_eq!(out.stmts(&out.body(0)[1..]), "[y := 1]");
    }
    // Long but within the limit: fine.
    let ok = format!("PROGRAM p\nx := a{};\nEND_PROGRAM", " + a".repeat(200));
    assert!(parse(&ok).diags.is_empty());
}
