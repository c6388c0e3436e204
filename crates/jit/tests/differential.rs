//! Differential tests: every execution conformance case
//! (`tests/conformance/*.st`) and every runnable program of the valid
//! front-end corpus (`tests/corpus/valid`) runs on the interpreter and on
//! the JIT; the whole image after every scan, the way the run ended (fault
//! kind, message and site included) and the final image must be identical.

mod common;
#[path = "../../cli/tests/conformance/spec.rs"]
#[allow(dead_code)]
mod spec;

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn st_files(dir: &Path) -> Vec<(String, String)> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    paths.sort();
    let mut out = Vec::new();
    for p in paths {
        if p.is_dir() {
            out.extend(st_files(&p));
        } else if p.extension().is_some_and(|x| x == "st") {
            let bytes = std::fs::read(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            let text = String::from_utf8(bytes.clone())
                .unwrap_or_else(|_| bytes.iter().map(|&b| b as char).collect());
            out.push((p.display().to_string(), text));
        }
    }
    out
}

#[test]
fn conformance_cases_agree() {
    let dir = root().join("tests/conformance");
    let (mut ran, mut failed) = (0, Vec::new());
    for (name, text) in st_files(&dir) {
        let spec = spec::parse(&text).unwrap_or_else(|e| panic!("{name}: {e}"));
        let Ok(program) = common::compile(&[(name.clone(), text)], spec.program.as_deref())
        else {
            continue; // pending cases that do not compile yet
        };
        ran += 1;
        if let Err(e) = common::differential(program, spec.cycles, spec.cycle_time_ns, spec.budget)
        {
            failed.push(format!("{name}: {e}"));
        }
    }
    for f in &failed {
        eprintln!("DIFFERS {f}");
    }
    eprintln!("differential: {ran} conformance cases, {} differ", failed.len());
    assert!(ran >= 70, "only {ran} cases ran");
    assert!(failed.is_empty(), "{} cases differ", failed.len());
}

#[test]
fn valid_corpus_programs_agree() {
    let dir = root().join("tests/corpus/valid");
    let mut entries: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{e}"))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    entries.sort();
    let (mut ran, mut failed) = (0, Vec::new());
    for p in entries {
        let files = if p.is_dir() {
            st_files(&p)
        } else if p.extension().is_some_and(|x| x == "st") {
            let text = std::fs::read_to_string(&p).unwrap_or_default();
            vec![(p.display().to_string(), text)]
        } else {
            continue;
        };
        // Projects without a PROGRAM (or with several and no configuration)
        // do not lower to a runnable Program: nothing to compare.
        let Ok(program) = common::compile(&files, None) else {
            continue;
        };
        ran += 1;
        if let Err(e) = common::differential(program, 5, 10_000_000, Some(1_000_000)) {
            failed.push(format!("{}: {e}", p.display()));
        }
    }
    for f in &failed {
        eprintln!("DIFFERS {f}");
    }
    eprintln!("differential: {ran} corpus programs, {} differ", failed.len());
    assert!(ran >= 20, "only {ran} programs ran");
    assert!(failed.is_empty(), "{} programs differ", failed.len());
}
