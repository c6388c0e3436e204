//! Warnings: exact (code, line) pairs, and no warning where none is due.

use automat_base::{Code, Interner, Severity, SourceMap};

fn warnings(src: &str) -> Vec<(Code, u32)> {
    let mut map = SourceMap::new();
    let file = map.add("w.st", src);
    let mut interner = Interner::new();
    let (_, analysis) = automat_sema::check_sources(&map, &mut interner);
    assert!(!analysis.has_errors(), "{:?}", analysis.diagnostics);
    analysis
        .diagnostics
        .iter()
        .filter(|d| d.severity == Severity::Warning)
        .map(|d| (d.code, map.get(file).line_col(d.span.start).0))
        .collect()
}

#[test]
fn unused_private_variables_and_unreachable_code() {
    let src = "FUNCTION_BLOCK Fb
VAR_INPUT a : INT; unusedInput : INT; END_VAR
VAR_OUTPUT unusedOutput : INT; END_VAR
VAR
    unused1 : INT;
    used1 : INT;
    t : TON;
    k : INT := 3;
END_VAR
VAR CONSTANT unusedConstant : INT := 1; END_VAR
VAR_TEMP tmp : REAL; END_VAR
    used1 := a + k;
    RETURN;
    used1 := 2;
END_FUNCTION_BLOCK
PROGRAM P
VAR x : INT; f : Fb; io AT %IX0.0 : BOOL; END_VAR
VAR_TEMP y : INT; END_VAR
    f(a := 1);
END_PROGRAM
";
    assert_eq!(
        warnings(src),
        vec![
            (Code::W001, 5),
            (Code::W001, 7),
            (Code::W001, 11),
            (Code::W002, 14),
            (Code::W001, 18),
        ]
    );
}

#[test]
fn written_only_and_read_only_variables_count_as_used() {
    let src = "FUNCTION F : INT
VAR_INPUT a : INT; END_VAR
VAR w : INT; r : INT; END_VAR
    w := a;
    F := r;
END_FUNCTION
";
    assert_eq!(warnings(src), vec![]);
}
