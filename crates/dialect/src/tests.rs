//! Unit tests of the dialect front end: what the rewrites report.

use crate::{add_libraries, check_sources, parse_names, Dialect};
use automat_base::{Code, Interner, SourceMap};

fn codes(text: &str, dialect: Dialect) -> Vec<Code> {
    let mut map = SourceMap::new();
    map.add("t.st", text);
    add_libraries(&mut map, &[dialect]);
    let mut interner = Interner::new();
    let (_, a) = check_sources(&map, &mut interner, &[dialect]);
    a.diagnostics.iter().map(|d| d.code).collect()
}

#[test]
fn names_parse_in_any_case_once_each() {
    assert_eq!(
        parse_names(&["ISaGRAF", "pl7", "isagraf"]),
        Ok(vec![Dialect::Isagraf, Dialect::Pl7])
    );
    assert_eq!(parse_names(&["CODESYS"]), Ok(vec![Dialect::Codesys]));
    let err = parse_names(&["twincat"]).unwrap_err();
    assert_eq!(
        err,
        "unknown library `twincat` (known: isagraf, pl7, fst, codesys)"
    );
}

#[test]
fn no_dialect_changes_nothing() {
    let mut map = SourceMap::new();
    map.add("t.st", "PROGRAM p VAR t : TIMER; END_VAR END_PROGRAM");
    let mut interner = Interner::new();
    let (_, a) = check_sources(&map, &mut interner, &[]);
    assert_eq!(map.len(), 1);
    assert!(a.has_errors(), "TIMER is unknown without the dialect");
}

#[test]
fn sections_with_a_configuration_are_ignored() {
    let text =
        "{section begin}\nPROGRAM a END_PROGRAM\nCONFIGURATION c PROGRAM i : a; END_CONFIGURATION";
    assert_eq!(codes(text, Dialect::Isagraf), [Code::W150]);
}

#[test]
fn library_blocks_need_the_dialect() {
    let text = "PROGRAM p VAR b : BLINK; END_VAR b(RUN := TRUE, CYCLE := T#1s); END_PROGRAM";
    assert_eq!(codes(text, Dialect::Isagraf), []);
    assert_ne!(codes(text, Dialect::Pl7), []);
}

#[test]
fn pl7_objects_without_a_chart_still_work() {
    let text = "PROGRAM p VAR a : BOOL; n : INT; END_VAR a := %S20 OR %S1; n := %SW20; END_PROGRAM";
    assert_eq!(codes(text, Dialect::Pl7), []);
}

#[test]
fn bare_and_negated_associations_keep_offsets() {
    let src = "PROGRAM p\n  STEP s:\n    /idle;\n    run;\n  END_STEP\n  x := a /b;\nEND_PROGRAM";
    let (text, neg) = crate::boolact::text(src);
    let text = text.expect("rewritten");
    assert_eq!(text.len(), src.len());
    // Both become N associations; the text outside the step is untouched.
    assert!(text.contains("idle(N);"), "{text}");
    assert!(text.contains("run(N);"), "{text}");
    assert!(text.ends_with("  x := a /b;\nEND_PROGRAM"), "{text}");
    let slash = src.find('/').unwrap_or(0) as u32;
    let at = text.find("idle").unwrap_or(0) as u32;
    assert_eq!(neg, [(at, slash, slash + 5)]);
}

#[test]
fn bare_associations_without_blanks_are_left_to_the_parser() {
    for src in [
        "STEP s: run; END_STEP",
        "STEP s: (* /a; *) END_STEP",
        "STEP s: a(N); END_STEP",
    ] {
        assert_eq!(crate::boolact::text(src), (None, Vec::new()), "{src}");
    }
}

#[test]
fn bare_associations_need_the_isagraf_dialect() {
    // The one step is never left: W121, no error.
    let text = "PROGRAM p VAR v : BOOL; END_VAR\n INITIAL_STEP s:\n    v;\n END_STEP\nEND_PROGRAM";
    assert_eq!(codes(text, Dialect::Isagraf), [Code::W121]);
    assert_ne!(codes(text, Dialect::Pl7), []);
}

/// Each CODESYS extension: clean with `--lib codesys`, an error in strict
/// IEC mode whose note names `--lib codesys`.
#[test]
fn codesys_extensions_are_errors_without_the_dialect() {
    let cases = [
        (
            "FUNCTION_BLOCK f VAR_INPUT n : INT; END_VAR n := n + 1; END_FUNCTION_BLOCK",
            Code::E041,
        ),
        (
            "PROGRAM p VAR w : WORD; END_VAR w := w + 1; END_PROGRAM",
            Code::E031,
        ),
        (
            "VAR_GLOBAL g : INT; END_VAR\nPROGRAM p g := 1; END_PROGRAM",
            Code::E020,
        ),
        (
            "PROGRAM p VAR x : INT; END_VAR IF x = 0 THEN x := 1; END_IF\nx := 2; END_PROGRAM",
            Code::E005,
        ),
        (
            "PROGRAM p VAR d : DINT; i : INT; END_VAR i := d; END_PROGRAM",
            Code::E030,
        ),
        (
            "FUNCTION f : INT VAR_INPUT n : INT; END_VAR f := n; END_FUNCTION\n\
             PROGRAM p VAR d : DINT; i : INT; END_VAR i := f(n := d); END_PROGRAM",
            Code::E052,
        ),
        (
            "FUNCTION_BLOCK g VAR_OUTPUT q : DINT; END_VAR q := 1; END_FUNCTION_BLOCK\n\
             PROGRAM p VAR b : g; i : INT; END_VAR b(q => i); END_PROGRAM",
            Code::E052,
        ),
    ];
    for (text, code) in cases {
        let mut map = SourceMap::new();
        map.add("t.st", text);
        let mut interner = Interner::new();
        let (_, strict) = check_sources(&map, &mut interner, &[]);
        let d = strict
            .diagnostics
            .iter()
            .find(|d| d.code == code)
            .unwrap_or_else(|| panic!("{text}: no {code:?} in {:?}", strict.diagnostics));
        assert!(
            d.notes.iter().any(|n| n.contains("--lib codesys")),
            "{text}: {:?}",
            d.notes
        );
        let got = codes(text, Dialect::Codesys);
        let want: &[Code] = if code == Code::E030 || code == Code::E052 {
            &[Code::W161]
        } else {
            &[]
        };
        assert_eq!(got, want, "{text}");
    }
}

#[test]
fn codesys_comments_and_pragmas() {
    // Non-nesting: the first `*)` closes, so `x := 1;` is code.
    let text = "PROGRAM p VAR x : INT; END_VAR (* a (* b *) x := 1; END_PROGRAM";
    assert_eq!(codes(text, Dialect::Codesys), []);
    assert!(codes(text, Dialect::Isagraf).contains(&Code::E002));
    // A V2.3 export that says its comments nest.
    let nested = "(* @NESTEDCOMMENTS := 'Yes' *)\nPROGRAM p VAR x : INT; END_VAR (* a (* b *) c *) x := 1; END_PROGRAM";
    assert_eq!(codes(nested, Dialect::Codesys), []);
    let pragmas = "{attribute 'a'}\nPROGRAM p {flag off} VAR x : INT; END_VAR x := 1; END_PROGRAM";
    assert_eq!(codes(pragmas, Dialect::Codesys), [Code::W160]);
}

/// A program other POUs reach moves to hidden globals only what they name
/// and what the actions they call use: its other inputs, outputs and
/// variables stay the instance's own, so a configuration connects them.
#[test]
fn program_access_moves_only_what_is_reached() {
    use automat_syntax::ast::{Item, PouKind};
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/conformance/codesys_program_access_config.st"
    ))
    .unwrap_or_default();
    let mut map = SourceMap::new();
    map.add("t.st", text);
    add_libraries(&mut map, &[Dialect::Codesys]);
    let mut interner = Interner::new();
    let (units, a) = check_sources(&map, &mut interner, &[Dialect::Codesys]);
    let codes: Vec<Code> = a.diagnostics.iter().map(|d| d.code).collect();
    assert_eq!(codes, []);
    let mut own = Vec::new();
    let mut globals = Vec::new();
    for item in units.iter().flat_map(|u| u.items.iter()) {
        match item {
            Item::Pou(p) if p.kind == PouKind::Program && interner.name(p.name.sym) == "Main" => {
                for b in &p.var_blocks {
                    for d in &b.decls {
                        for n in &d.names {
                            own.push((format!("{:?}", b.kind), interner.name(n.sym).to_string()));
                        }
                    }
                }
            }
            Item::Globals(b) => {
                for d in &b.decls {
                    for n in &d.names {
                        globals.push(interner.name(n.sym).to_string());
                    }
                }
            }
            _ => {}
        }
    }
    let own: Vec<(&str, &str)> = own.iter().map(|(k, n)| (k.as_str(), n.as_str())).collect();
    assert_eq!(
        own,
        [
            ("Input", "step"),
            ("Output", "total"),
            ("External", "Main.count"),
            ("External", "Main.calls"),
        ]
    );
    assert_eq!(globals, ["Main.count", "Main.calls"]);
}

/// `__ISVALIDREF` beside real references: the reference desugaring turns
/// the right use into `r <> NULL` and leaves the misuses to the checker.
#[test]
fn isvalidref_misuse_beside_a_reference() {
    let text = "PROGRAM Main\nVAR x : INT; r : REFERENCE TO INT; ok : BOOL; END_VAR\n    r REF= x;\n    ok := __ISVALIDREF(r);\n    ok := __ISVALIDREF(x);\n    ok := __ISVALIDREF(r, r);\nEND_PROGRAM\n";
    assert_eq!(codes(text, Dialect::Codesys), [Code::E163, Code::E163]);
}
