//! The conformance corpus (`tests/corpus/`) through code generation.
//!
//! - `invalid/`: projects that expect lowering errors (E090–E099, `//~ E09x`
//!   comments as in the front end's corpus) must check without front-end
//!   errors and produce exactly those errors from `lower`.
//! - `valid/`: every project lowers without panicking; its code passes the
//!   verifier; the only errors allowed are E090 (several programs) and E091
//!   (not supported yet).

use automat_base::{Interner, SourceMap};
use automat_lower::{lower, LowerOptions};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/corpus")
}

/// Projects: one .st file, or a directory of them (sorted).
fn projects(dir: &str) -> Vec<(String, Vec<(String, String)>)> {
    let mut out = Vec::new();
    let Ok(rd) = std::fs::read_dir(root().join(dir)) else {
        return out;
    };
    let mut entries: Vec<PathBuf> = rd.flatten().map(|e| e.path()).collect();
    entries.sort();
    let is_st = |p: &Path| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("st"));
    let read = |p: &Path| {
        (
            p.file_name().unwrap().to_string_lossy().to_string(),
            std::fs::read_to_string(p).unwrap(),
        )
    };
    for p in entries {
        // Vendor-dialect projects need `--lib`: crates/dialect/tests/corpus.rs
        // checks and lowers them.
        let name = p.file_name().map(|n| n.to_string_lossy().to_string());
        if name.is_some_and(|n| n.starts_with("isagraf_") || n.starts_with("pl7_")) {
            continue;
        }
        if p.is_dir() {
            let mut files: Vec<PathBuf> = std::fs::read_dir(&p)
                .unwrap()
                .flatten()
                .map(|e| e.path())
                .filter(|p| is_st(p))
                .collect();
            files.sort();
            out.push((
                p.display().to_string(),
                files.iter().map(|f| read(f)).collect(),
            ));
        } else if is_st(&p) {
            out.push((p.display().to_string(), vec![read(&p)]));
        }
    }
    out
}

/// (file index, line, code) of the `//~` expectations.
fn expectations(files: &[(String, String)]) -> Vec<(usize, u32, String)> {
    let mut out = Vec::new();
    for (fi, (_, text)) in files.iter().enumerate() {
        for (li, line) in text.lines().enumerate() {
            let Some(i) = line.find("//~") else { continue };
            let rest = &line[i + 3..];
            let up = rest.chars().take_while(|c| *c == '^').count();
            for code in rest[up..].split_whitespace() {
                out.push((fi, (li + 1 - up) as u32, code.to_string()));
            }
        }
    }
    out.sort();
    out
}

/// Front-end errors, or the lowering errors as (file index, line, code, message).
fn run(files: &[(String, String)]) -> Result<Vec<(usize, u32, String, String)>, String> {
    let mut sources = SourceMap::new();
    for (n, t) in files {
        sources.add(n.clone(), t.clone());
    }
    let mut interner = Interner::new();
    let (units, analysis) = automat_sema::check_sources(&sources, &mut interner);
    if analysis.has_errors() {
        return Err(format!(
            "front-end errors: {:?}",
            analysis
                .diagnostics
                .iter()
                .map(|d| d.message.clone())
                .collect::<Vec<_>>()
        ));
    }
    match lower(
        &units,
        &analysis,
        &interner,
        &sources,
        &LowerOptions::default(),
    ) {
        Ok(p) => {
            p.verify().map_err(|e| format!("verifier: {e}"))?;
            Ok(Vec::new())
        }
        Err(d) => Ok(d
            .iter()
            .filter(|d| d.is_error())
            .map(|d| {
                let (fi, line) = match files.get(d.span.file.0 as usize) {
                    Some(_) => (
                        d.span.file.0 as usize,
                        sources.get(d.span.file).line_col(d.span.start).0,
                    ),
                    None => (usize::MAX, 0),
                };
                (fi, line, d.code.as_str().to_string(), d.message.clone())
            })
            .collect()),
    }
}

#[test]
fn corpus_invalid_lowering_errors() {
    let mut problems = Vec::new();
    let mut checked = 0;
    for (name, files) in projects("invalid") {
        let want: Vec<(usize, u32, String)> = expectations(&files)
            .into_iter()
            .filter(|e| e.2.starts_with("E09"))
            .collect();
        if want.is_empty() {
            continue;
        }
        checked += 1;
        match run(&files) {
            Err(e) => problems.push(format!("{name}: {e}")),
            Ok(found) => {
                let mut got: Vec<(usize, u32, String)> = found
                    .iter()
                    .map(|(f, l, c, _)| (*f, *l, c.clone()))
                    .collect();
                got.sort();
                if got != want {
                    problems.push(format!("{name}: expected {want:?}, found {found:?}"));
                }
            }
        }
    }
    assert!(checked >= 3, "the corpus has no lowering cases");
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn corpus_valid_lowers() {
    let mut problems = Vec::new();
    for (name, files) in projects("valid") {
        match run(&files) {
            Err(e) => problems.push(format!("{name}: {e}")),
            Ok(errs) => {
                for (_, line, code, msg) in errs {
                    if !(code == "E090" || code == "E091") || msg.contains("internal error") {
                        problems.push(format!("{name}:{line}: {code} {msg}"));
                    }
                }
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}
