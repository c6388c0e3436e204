//! Diagnostics that teach (issue 16 point 5): the nearest visible name for
//! an unknown one, fix-its for `=` and `==`, the conversion to use on a
//! type mismatch, and W004 for an integer division assigned to a REAL.
//! Exact messages: they are the user interface.

mod common;
use common::{messages, prog};

fn one(decls: &str, body: &str) -> String {
    let m = messages(&prog(decls, body));
    assert_eq!(m.len(), 1, "{m:?}");
    m.into_iter().next().unwrap_or_default()
}

#[test]
fn unknown_names_suggest_the_nearest_visible_one() {
    assert_eq!(
        one(
            "MotorRunning : BOOL; Start : BOOL;",
            "MotorRuning := Start;"
        ),
        "unknown variable `MotorRuning` in `Main`; did you mean `MotorRunning`?"
    );
    // Read, not written; letters swapped.
    assert_eq!(
        one(
            "MotorRunning : BOOL; Start : BOOL;",
            "MotorRunning := Strat;"
        ),
        "unknown variable `Strat` in `Main`; did you mean `Start`?"
    );
    // Nothing near: no guess.
    assert_eq!(
        one("MotorRunning : BOOL;", "MotorRunning := Pump;"),
        "unknown variable `Pump` in `Main`"
    );
    assert_eq!(
        one("t : TON;", "t := TONN(1);"),
        "unknown function or function block `TONN`; did you mean `TON`?"
    );
    assert_eq!(
        one("t : TONN;", ""),
        "unknown type `TONN`; did you mean `TON`?"
    );
    assert_eq!(
        one("x : DIMT;", ""),
        "unknown type `DIMT`; did you mean `DINT`?"
    );
}

#[test]
fn a_namespace_item_named_without_its_namespace_is_suggested_qualified() {
    // The namespace is opened in two files; its items are one set.
    let (_, _, a) = common::analyze_files(&[
        (
            "a.st",
            "NAMESPACE Motion\nTYPE Axis : STRUCT pos : INT; END_STRUCT; END_TYPE\nEND_NAMESPACE\n",
        ),
        (
            "b.st",
            "NAMESPACE Motion\nFUNCTION Clamp : INT\nVAR_INPUT a : Axis; END_VAR\n    Clamp := a.pos;\nEND_FUNCTION\nEND_NAMESPACE\n\
             PROGRAM Main\nVAR x : INT; a : Axis; b : Motion.Axis; END_VAR\n    x := Clamp(b) + Motion.Clamp(b);\nEND_PROGRAM\n",
        ),
    ]);
    let m: Vec<&str> = a.diagnostics.iter().map(|d| d.message.as_str()).collect();
    assert_eq!(
        m,
        [
            "unknown type `Axis`; did you mean `Motion.Axis`?",
            "unknown function or function block `Clamp`; did you mean `Motion.Clamp`?"
        ]
    );
}

#[test]
fn a_global_without_var_external_says_how_to_use_it() {
    let src = "VAR_GLOBAL Level : INT; END_VAR
PROGRAM Main
VAR x : INT; END_VAR
    x := Level;
END_PROGRAM
";
    assert_eq!(
        messages(src),
        ["unknown variable `Level` in `Main`; `Level` is a global variable: declare it in a VAR_EXTERNAL section to use it here"]
    );
}

#[test]
fn c_style_equals_get_fix_its() {
    assert_eq!(
        one("i : INT;", "i = 3;"),
        "the expression `i = 3` has no effect; only calls can be statements; to assign, write `i := 3`"
    );
    assert_eq!(
        one("i : INT; d : INT;", "IF i == 3 THEN d := 1; END_IF;"),
        "`==` is not an ST operator: equality is a single `=` (`IF a = b THEN`), assignment is `:=`"
    );
}

#[test]
fn type_mismatches_name_the_conversion() {
    assert_eq!(
        one("i : INT; d : DINT;", "i := d;"),
        "cannot assign a value of type DINT to `i` of type INT; convert it with `DINT_TO_INT(...)`"
    );
    assert_eq!(
        one("s : STRING; r : REAL;", "s := r;"),
        "cannot assign a value of type REAL to `s` of type STRING; convert it with `REAL_TO_STRING(...)`"
    );
    assert_eq!(
        one("t : TON;", "t(IN := TRUE, PT := 5);"),
        "parameter `PT` of `TON` expects TIME, found an integer literal; write a duration such as `T#5s` or `T#500ms`, or convert a number of milliseconds with `DINT_TO_TIME`"
    );
    // No conversion function between them: no hint.
    assert_eq!(
        one("r : REAL; d : DATE;", "r := d;"),
        "cannot assign a value of type DATE to `r` of type REAL"
    );
}

#[test]
fn an_integer_division_assigned_to_a_real_is_a_warning() {
    assert_eq!(
        one("i : INT := 7; r : REAL;", "r := i / 2;"),
        "the integer division `i / 2` truncates before it is converted to REAL for `r`; convert an operand to a real first"
    );
    assert_eq!(
        one("r : LREAL;", "r := (7 / 2);"),
        "the integer division `7 / 2` truncates before it is converted to LREAL for `r` (it gives 3); convert an operand to a real first"
    );
    // A real division, or an integer target: nothing to say.
    assert!(messages(&prog(
        "i : INT := 7; r : REAL;",
        "r := INT_TO_REAL(i) / 2.0;"
    ))
    .is_empty());
    assert!(messages(&prog("i : INT := 7; k : INT;", "k := i / 2;")).is_empty());
}
