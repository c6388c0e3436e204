//! The vendor dialects' part of the front-end corpus: the projects of
//! `tests/corpus/valid` and `tests/corpus/invalid` whose name starts with
//! `isagraf_` (or `pl7_`), checked with that dialect on (as `automat check
//! --lib isagraf`). The generic corpus harness (`crates/sema/tests/corpus.rs`)
//! leaves them to this one.
//!
//! A project is one `.st` file or a folder of them. Valid projects must have
//! no error; in invalid ones every error must be announced by a `//~ CODE`
//! comment at the end of its line (several codes: `//~ E150 E151`), and
//! every announced error must occur: the (line, code) lists are compared as
//! multisets. Every E15x/E16x code must be announced by some invalid project.
//! A valid project may announce warnings the same way (`//~ W121`): for each
//! warning code it announces, its warnings of that code are compared, so a
//! missing warning is pinned as well as a present one.

use automat_base::{render, Code, Interner, SourceMap};
use automat_dialect::Dialect;
use std::path::{Path, PathBuf};

fn corpus(dir: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/corpus")
        .join(dir)
}

/// (project name, dialect, files) of the vendor projects of a folder.
fn projects(dir: &str) -> Vec<(String, Dialect, Vec<PathBuf>)> {
    let mut out = Vec::new();
    let mut entries: Vec<PathBuf> = std::fs::read_dir(corpus(dir))
        .map(|rd| rd.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    entries.sort();
    for path in entries {
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let Some(dialect) = name.split('_').next().and_then(Dialect::from_name) else {
            continue;
        };
        let files = if path.is_dir() {
            let mut f: Vec<PathBuf> = std::fs::read_dir(&path)
                .map(|rd| rd.filter_map(|e| e.ok().map(|e| e.path())).collect())
                .unwrap_or_default();
            f.retain(|p| p.extension().is_some_and(|e| e == "st"));
            f.sort();
            f
        } else if path.extension().is_some_and(|e| e == "st") {
            vec![path.clone()]
        } else {
            continue;
        };
        out.push((format!("{dir}/{name}"), dialect, files));
    }
    out
}

/// (file index, line, code) of a diagnostic.
type Site = (usize, u32, Code);

/// What a check found: errors, warnings, the rendered report, the texts.
struct Checked {
    errors: Vec<Site>,
    warnings: Vec<Site>,
    report: String,
    texts: Vec<String>,
}

/// Checks a project; a project without errors is also lowered (the only
/// lowering error allowed: E090, several programs) and its code verified.
fn check(dialect: Dialect, files: &[PathBuf]) -> Checked {
    let mut map = SourceMap::new();
    let mut texts = Vec::new();
    for f in files {
        let text = std::fs::read_to_string(f).unwrap_or_default();
        map.add(f.display().to_string(), text.clone());
        texts.push(text);
    }
    automat_dialect::add_libraries(&mut map, &[dialect]);
    let mut interner = Interner::new();
    let (units, analysis) = automat_dialect::check_sources(&map, &mut interner, &[dialect]);
    let site = |d: &automat_base::Diagnostic| {
        let file = d.span.file.0 as usize;
        let line = if file < files.len() {
            map.get(d.span.file).line_col(d.span.start).0
        } else {
            0
        };
        (file, line, d.code)
    };
    let errors: Vec<_> = analysis
        .diagnostics
        .iter()
        .filter(|d| d.is_error())
        .map(site)
        .collect();
    let warnings: Vec<_> = analysis
        .diagnostics
        .iter()
        .filter(|d| !d.is_error())
        .map(site)
        .collect();
    let mut report = render::render_report(&map, &analysis.diagnostics);
    if errors.is_empty() {
        let opts = automat_lower::LowerOptions { program: None };
        if let Err(d) = automat_lower::lower(&units, &analysis, &interner, &map, &opts) {
            if d.iter().any(|d| d.code != Code::E090) {
                report.push_str(&render::render_report(&map, &d));
                return Checked {
                    errors: vec![(0, 0, Code::E091)],
                    warnings,
                    report,
                    texts,
                };
            }
        }
    }
    Checked {
        errors,
        warnings,
        report,
        texts,
    }
}

/// The `//~ CODE ...` announcements of a file: (line, code).
fn announced(text: &str) -> Vec<(u32, Code)> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if let Some((_, rest)) = line.split_once("//~") {
            for word in rest.split_whitespace() {
                match Code::parse(word) {
                    Some(c) => out.push((i as u32 + 1, c)),
                    None => panic!("line {}: `{word}` is not a diagnostic code", i + 1),
                }
            }
        }
    }
    out
}

#[test]
fn vendor_corpus_valid() {
    let mut failures = Vec::new();
    let all = projects("valid");
    assert!(!all.is_empty(), "no vendor projects in tests/corpus/valid");
    for (name, dialect, files) in all {
        let c = check(dialect, &files);
        if !c.errors.is_empty() {
            failures.push(format!("{name}:\n{}", c.report));
            continue;
        }
        let mut want: Vec<Site> = c
            .texts
            .iter()
            .enumerate()
            .flat_map(|(i, t)| announced(t).into_iter().map(move |(l, code)| (i, l, code)))
            .collect();
        let mut got: Vec<Site> = c
            .warnings
            .iter()
            .filter(|w| want.iter().any(|a| a.2 == w.2))
            .copied()
            .collect();
        want.sort();
        got.sort();
        if want != got {
            failures.push(format!(
                "{name}: expected warnings {want:?}\n  got {got:?}\n{}",
                c.report
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn vendor_corpus_invalid() {
    let mut failures = Vec::new();
    let mut seen = Vec::new();
    let all = projects("invalid");
    assert!(
        !all.is_empty(),
        "no vendor projects in tests/corpus/invalid"
    );
    for (name, dialect, files) in all {
        let Checked {
            errors,
            report,
            texts,
            ..
        } = check(dialect, &files);
        let mut want: Vec<Site> = texts
            .iter()
            .enumerate()
            .flat_map(|(i, t)| announced(t).into_iter().map(move |(l, c)| (i, l, c)))
            .collect();
        let mut got = errors;
        want.sort();
        got.sort();
        seen.extend(want.iter().map(|w| w.2));
        if want.is_empty() {
            failures.push(format!("{name}: announces no error"));
        } else if want != got {
            failures.push(format!(
                "{name}: expected {want:?}\n  got {got:?}\n{report}"
            ));
        }
    }
    let missing: Vec<&str> = Code::ALL
        .iter()
        .filter(|c| {
            let s = c.as_str();
            (s.starts_with("E15") || s.starts_with("E16")) && !seen.contains(c)
        })
        .map(|c| c.as_str())
        .collect();
    assert!(
        missing.is_empty(),
        "no vendor invalid project announces {}",
        missing.join(", ")
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
