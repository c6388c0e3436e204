//! The execution conformance corpus (`tests/conformance/*.st` at the
//! repository root): each file is a program plus its expected results, all
//! computed by hand from IEC 61131-3 and `docs/semantics.md`.
//!
//! # Case format
//!
//! A case is one `.st` file that starts with a `(* ... *)` comment, the
//! header (no nested comments inside it). Each header line is `key: value`;
//! lines without a known key are free text, and ` -- ` starts a note.
//!
//! - `cycles: N` — run N scans (default 1).
//! - `cycle-time: T#10ms` — period of the cyclic task (default T#10ms). The
//!   clock is virtual: scan k runs at PLC time (k − 1) × cycle time.
//! - `program: NAME` — the PROGRAM to run when the file has several.
//! - `budget: N` — the engine's watchdog budget (instructions per scan).
//! - `expect: PATH = VALUE` — after the last scan, the variable at PATH
//!   (`x`, `Main.fb.Q`, `arr[2, 1].x`, a global, `%QX0.1`: anything
//!   `automat run --print` takes) prints exactly as VALUE (the
//!   `format_value` literal: `TRUE`, `-3`, `2.5`, `T#1s500ms`, `'abc'`).
//! - `expect-at K: PATH = VALUE` — the same, after scan K.
//! - `expect-fault: KIND at LINE [in cycle K]` — the run stops with a
//!   runtime fault of KIND (`division-by-zero`, `index-out-of-bounds`,
//!   `subrange`, `string-index`, `watchdog`, `function`) whose site is on
//!   LINE of the file (in scan K). `expect:` lines are then checked on the
//!   image as the fault left it.
//! - `skip-until: REASON` — a construct the tool does not support yet. The
//!   case still runs; it is reported as pending (and as "now passes" when
//!   it does), never as passed, and never fails the run.
//! - `known-bug: REASON` — the tool is known to be wrong here: mismatches
//!   are reported but do not fail the run.
//! - `libraries: NAME[, NAME]` — vendor dialects and their libraries, as
//!   `automat run --lib NAME` (`isagraf`, `pl7`; see `docs/vendor-dialects.md`).
//!
//! Every other mismatch fails the test; all are reported at the end.

#[path = "conformance/exec.rs"]
mod exec;
#[path = "conformance/spec.rs"]
mod spec;

use std::path::PathBuf;

fn corpus() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../tests/conformance")
}

/// What one case comes to.
#[derive(Debug, PartialEq, Eq)]
enum Verdict {
    Passed,
    /// Fails the run.
    Failed(String),
    /// `skip-until:` cases, passing or not.
    Pending(String),
    /// `known-bug:` cases, passing or not.
    KnownBug(String),
}

/// Classifies the outcome of [`exec::check`] for a case.
fn verdict(name: &str, spec: &spec::Spec, result: &Result<Vec<String>, String>) -> Verdict {
    let problems = match result {
        Ok(f) => f.join("\n    "),
        Err(e) => format!("does not compile or run:\n{e}"),
    };
    let ok = matches!(result, Ok(f) if f.is_empty());
    // Pending cases often fail to compile with many diagnostics: the first
    // few lines say why.
    let brief = || {
        let mut lines: Vec<&str> = problems.lines().take(8).collect();
        if problems.lines().nth(8).is_some() {
            lines.push("...");
        }
        lines.join("\n")
    };
    // A mark that is no longer needed is said loudly, so it gets removed.
    let state = |mark: &str| {
        if ok {
            format!("NOW PASSES, remove {mark}")
        } else {
            brief()
        }
    };
    if let Some(why) = &spec.pending {
        Verdict::Pending(format!(
            "{name} (pending: {why}):\n    {}",
            state("skip-until")
        ))
    } else if let Some(why) = &spec.known_bug {
        Verdict::KnownBug(format!(
            "{name} (known-bug: {why}):\n    {}",
            state("known-bug")
        ))
    } else if ok {
        Verdict::Passed
    } else {
        Verdict::Failed(format!("{name}:\n    {problems}"))
    }
}

#[test]
fn verdicts() {
    let plain = spec::parse("(* *)").unwrap_or_else(|e| panic!("{e}"));
    let pending = spec::parse("(* skip-until: E091 *)").unwrap_or_else(|e| panic!("{e}"));
    let known = spec::parse("(* known-bug: off by one *)").unwrap_or_else(|e| panic!("{e}"));
    let pass = Ok(Vec::new());
    let fail = Ok(vec!["line 2: x: expected 1, got 2".to_string()]);
    let broken = Err("E091".to_string());
    assert_eq!(verdict("a.st", &plain, &pass), Verdict::Passed);
    assert_eq!(
        verdict("a.st", &plain, &fail),
        Verdict::Failed("a.st:\n    line 2: x: expected 1, got 2".into())
    );
    assert_eq!(
        verdict("a.st", &pending, &broken),
        Verdict::Pending("a.st (pending: E091):\n    does not compile or run:\nE091".into())
    );
    assert_eq!(
        verdict("a.st", &pending, &pass),
        Verdict::Pending("a.st (pending: E091):\n    NOW PASSES, remove skip-until".into())
    );
    assert_eq!(
        verdict("a.st", &known, &fail),
        Verdict::KnownBug("a.st (known-bug: off by one):\n    line 2: x: expected 1, got 2".into())
    );
}

#[test]
fn conformance_corpus() {
    corpus_on(exec::Backend::Interp);
}

/// The same corpus on the JIT: every verdict must be the interpreter's.
#[test]
fn conformance_corpus_jit() {
    corpus_on(exec::Backend::Jit);
}

fn corpus_on(backend: exec::Backend) {
    let mut files: Vec<PathBuf> = std::fs::read_dir(corpus())
        .unwrap_or_else(|e| panic!("{}: {e}", corpus().display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "st"))
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
        let spec = match spec::parse(&text) {
            Ok(s) => s,
            Err(e) => {
                failed.push(format!("{name}: bad header: {e}"));
                continue;
            }
        };
        match verdict(&name, &spec, &exec::check_on(&name, &text, &spec, backend)) {
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
