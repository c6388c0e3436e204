//! Execution-conformance programs: the one implementation behind the
//! corpus harness (`crates/cli/tests/conformance.rs`, on
//! `tests/conformance/*.st`, interpreter and JIT) and `automat test`. Each
//! file is a program plus its expected results, all computed by hand from
//! IEC 61131-3 and `docs/semantics.md`.
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
//! - `budget: N` — the engine's instruction budget per task run: a run
//!   executing more faults as `watchdog` at exactly that instruction (a
//!   deterministic site; none by default).
//! - `watchdog: TIME|off` — the watchdog in time of every task (as
//!   `[tasks.NAME] watchdog`; default 10 s of wall time per run, the
//!   virtual clock's). Its fault site is the line the run was executing:
//!   write the endless loop on one line.
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

pub mod exec;
pub mod spec;

pub use exec::{check, check_in, check_on, Backend, Context};

/// What one case comes to.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Verdict {
    Passed,
    /// Fails the run: `NAME:` and the mismatches, indented.
    Failed(String),
    /// `skip-until:` cases, passing or not.
    Pending(String),
    /// `known-bug:` cases, passing or not.
    KnownBug(String),
}

/// Whether `source` is a conformance program: it opens with a `(* ... *)`
/// header holding a `cycles:`, `expect:`, `expect-at K:` or
/// `expect-fault:` line (other `.st` files are not run by `automat test`).
pub fn is_conformance(source: &str) -> bool {
    let Ok((h, _)) = spec::header(source) else {
        return false;
    };
    h.lines().any(|l| {
        let l = l.trim();
        let key = l.split_once(':').map_or("", |(k, _)| k.trim());
        key == "cycles" || key == "expect" || key == "expect-fault" || key.starts_with("expect-at ")
    })
}

/// Classifies the outcome of [`check_on`] for the case `name`.
pub fn verdict(name: &str, spec: &spec::Spec, result: &Result<Vec<String>, String>) -> Verdict {
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

/// Parses, runs on `backend` and classifies the case `name` (the file name
/// used in fault sites and messages) whose text is `source`.
pub fn judge(name: &str, source: &str, backend: Backend) -> Verdict {
    judge_in(name, source, backend, Context::default())
}

/// [`judge`] with the other files and dialects of the case's project.
pub fn judge_in(name: &str, source: &str, backend: Backend, ctx: Context) -> Verdict {
    match spec::parse(source) {
        Ok(s) => verdict(name, &s, &check_in(name, source, &s, backend, ctx)),
        Err(e) => Verdict::Failed(format!("{name}: bad header: {e}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
            Verdict::KnownBug(
                "a.st (known-bug: off by one):\n    line 2: x: expected 1, got 2".into()
            )
        );
    }

    #[test]
    fn conformance_programs_are_told_by_their_header() {
        assert!(is_conformance("(* cycles: 2 *) PROGRAM p END_PROGRAM"));
        assert!(is_conformance("\n(* t\n expect-at 1: x = 1 *)"));
        assert!(is_conformance("(* expect-fault: watchdog at 3 *)"));
        assert!(!is_conformance(
            "(* a comment: nothing *) PROGRAM p END_PROGRAM"
        ));
        assert!(!is_conformance("PROGRAM p (* cycles: 2 *) END_PROGRAM"));
    }

    #[test]
    fn judge_runs_a_case_and_reports_mismatches() {
        let src = "(* cycles: 3\n   expect: Main.n = 3\n   expect-at 1: Main.n = 2 *)\nPROGRAM Main VAR n : INT; END_VAR n := n + 1; END_PROGRAM\n";
        assert_eq!(
            judge("c.st", src, Backend::Interp),
            Verdict::Failed("c.st:\n    line 3: Main.n after scan 1: expected 2, got 1".into())
        );
        assert_eq!(
            judge("c.st", "(* cycles: x *)", Backend::Interp),
            Verdict::Failed("c.st: bad header: line 1: cycles: `x` is not a count".into())
        );
    }
}
