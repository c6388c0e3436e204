//! The execution conformance corpus (`tests/conformance/*.st` at the
//! repository root), on the interpreter and on the JIT. The case format,
//! the runner and the verdicts are `automat_scenario::conformance` (the
//! same code `automat test` runs); this harness walks the corpus and
//! prints the summary line.

use automat_scenario::conformance::{judge, Backend, Verdict};
use std::path::PathBuf;

fn corpus() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../tests/conformance")
}

#[test]
fn conformance_corpus() {
    corpus_on(Backend::Interp);
}

/// The same corpus on the JIT: every verdict must be the interpreter's.
#[test]
fn conformance_corpus_jit() {
    corpus_on(Backend::Jit);
}

fn corpus_on(backend: Backend) {
    let mut files: Vec<PathBuf> = std::fs::read_dir(corpus())
        .unwrap_or_else(|e| panic!("{}: {e}", corpus().display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "st" || x == "xml"))
        .collect();
    files.sort();
    assert!(!files.is_empty(), "no cases in {}", corpus().display());
    let (mut passed, mut failed, mut pending, mut known) = (0, Vec::new(), Vec::new(), Vec::new());
    for path in &files {
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{name}: {e}"));
        match judge(&name, &text, backend) {
            Verdict::Passed => passed += 1,
            Verdict::Failed(m) => failed.push(m),
            Verdict::Pending(m) => pending.push(m),
            Verdict::KnownBug(m) => known.push(m),
        }
    }
    for p in &pending {
        eprintln!("PENDING {p}");
    }
    for k in &known {
        eprintln!("KNOWN-BUG {k}");
    }
    for f in &failed {
        eprintln!("FAILED {f}");
    }
    eprintln!(
        "conformance ({backend:?}): {} cases: {passed} passed, {} failed, {} pending, {} known bugs",
        files.len(),
        failed.len(),
        pending.len(),
        known.len()
    );
    assert!(
        failed.is_empty(),
        "{} conformance cases failed (see above)",
        failed.len()
    );
}
