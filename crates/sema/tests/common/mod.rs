//! Helpers of the checker's snippet tests: check ST text (one or more files
//! of one project) and compare the diagnostics as exact (code, line) pairs.

#![allow(dead_code)]

use automat_base::{render, Interner, SourceMap};
use automat_sema::Analysis;

/// Checks one file; returns the map, the interner and the analysis.
pub fn analyze(src: &str) -> (SourceMap, Interner, Analysis) {
    analyze_files(&[("test.st", src)])
}

pub fn analyze_files(files: &[(&str, &str)]) -> (SourceMap, Interner, Analysis) {
    let mut map = SourceMap::new();
    for (name, text) in files {
        map.add(*name, *text);
    }
    let mut interner = Interner::new();
    let (_, analysis) = automat_sema::check_sources(&map, &mut interner);
    (map, interner, analysis)
}

/// (code, line) of every diagnostic, in order. W001 (unused variable) is
/// left out: snippets declare variables only to provoke other diagnostics,
/// and `tests/warnings.rs` pins W001 itself.
pub fn codes_of(map: &SourceMap, a: &Analysis) -> Vec<(String, u32)> {
    a.diagnostics
        .iter()
        .filter(|d| d.code != automat_base::Code::W001)
        .map(|d| {
            let line = map.get(d.span.file).line_col(d.span.start).0;
            (d.code.as_str().to_string(), line)
        })
        .collect()
}

/// Asserts the exact diagnostics of a snippet.
#[track_caller]
pub fn check(src: &str, expected: &[(&str, u32)]) {
    let (map, _, a) = analyze(src);
    let got = codes_of(&map, &a);
    let want: Vec<(String, u32)> = expected.iter().map(|(c, l)| (c.to_string(), *l)).collect();
    assert_eq!(
        got,
        want,
        "\n{}",
        render::render_report(&map, &a.diagnostics)
    );
}

/// Asserts a snippet checks clean.
#[track_caller]
pub fn clean(src: &str) {
    check(src, &[]);
}

/// The messages of all diagnostics.
pub fn messages(src: &str) -> Vec<String> {
    let (_, _, a) = analyze(src);
    a.diagnostics.iter().map(|d| d.message.clone()).collect()
}

/// Wraps statements in a program with the given declarations.
pub fn prog(decls: &str, body: &str) -> String {
    format!("PROGRAM Main\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n")
}
