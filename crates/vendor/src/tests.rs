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
    let err = parse_names(&["codesys"]).unwrap_err();
    assert_eq!(err, "unknown library `codesys` (known: isagraf, pl7)");
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
