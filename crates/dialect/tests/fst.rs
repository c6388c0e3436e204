//! The Festo FST STL cases of `tests/fst/*.fst` (docs/festo-stl.md), each
//! a small project in one file: `-- P0.stl`, `-- B1.stl`,
//! `-- allocation.txt` sections hold the project's files, then either
//! - `-- run`: `set N: OPERAND = VALUE` (written before scan N, kept until
//!   set again) and `expect N: PATH = VALUE` (printed after scan N, exact);
//!   scans are 10 ms of the virtual clock from PLC time 0; or
//! - `-- errors`: `FILE:LINE: CODE` lines, the diagnostics the project
//!   must give (compared as sorted lists).

mod support;

use automat_base::SourceMap;
use automat_dialect::Dialect;
use std::path::Path;
use support::Run;

/// A case: its files, then what it runs or the diagnostics it must give.
struct Case {
    files: Vec<(String, String)>,
    run: Run,
    errors: Option<Vec<String>>,
}

fn parse_case(text: &str) -> Case {
    let mut case = Case {
        files: Vec::new(),
        run: Run::default(),
        errors: None,
    };
    let mut section = String::new();
    for line in text.lines() {
        if let Some(name) = line.strip_prefix("-- ") {
            section = name.trim().to_string();
            match section.as_str() {
                "run" => {}
                "errors" => case.errors = Some(Vec::new()),
                _ => case.files.push((section.clone(), String::new())),
            }
            continue;
        }
        match section.as_str() {
            "run" => {
                let l = line.trim();
                if l.is_empty() || l.starts_with('#') {
                    continue;
                }
                let (head, rest) = l
                    .split_once(':')
                    .unwrap_or_else(|| panic!("bad line `{l}`"));
                let (what, at) = head
                    .split_once(' ')
                    .unwrap_or_else(|| panic!("bad line `{l}`"));
                let at: u64 = at
                    .trim()
                    .parse()
                    .unwrap_or_else(|_| panic!("bad scan in `{l}`"));
                let (path, val) = rest
                    .split_once('=')
                    .unwrap_or_else(|| panic!("bad line `{l}`"));
                let entry = (at, path.trim().to_string(), val.trim().to_string());
                match what {
                    "set" => case.run.sets.push(entry),
                    "expect" => case.run.expects.push(entry),
                    _ => panic!("bad line `{l}`"),
                }
            }
            "errors" => {
                let l = line.trim();
                if !l.is_empty() {
                    if let Some(e) = case.errors.as_mut() {
                        e.push(l.to_string());
                    }
                }
            }
            _ => {
                if let Some((_, t)) = case.files.last_mut() {
                    t.push_str(line);
                    t.push('\n');
                }
            }
        }
    }
    case
}

fn run_case(path: &Path, jit: bool) -> Result<(), String> {
    let text = std::fs::read_to_string(path).map_err(|e| e.to_string())?;
    let case = parse_case(&text);
    let mut map = SourceMap::new();
    for (name, t) in &case.files {
        map.add(name.clone(), t.clone());
    }
    let checked = support::check(map, &[Dialect::Fst]);
    if let Some(want) = &case.errors {
        let got = support::diagnostic_lines(&checked.map, &checked.analysis.diagnostics, true);
        let mut want = want.clone();
        want.sort();
        return if got == want {
            Ok(())
        } else {
            Err(format!(
                "diagnostics {got:?}, wanted {want:?}\n{}",
                checked.report()
            ))
        };
    }
    if !checked.analysis.diagnostics.is_empty() {
        return Err(format!("should check clean:\n{}", checked.report()));
    }
    checked.run(&case.run, jit)
}

#[test]
fn fst_cases() {
    let cases = support::case_files("fst", "fst");
    assert!(cases.len() >= 18, "the D3 examples are cases");
    support::run_all(&cases, "E18", run_case);
}

/// Bad input never panics: every case's STL files with one word deleted,
/// or cut short, at many places, still give diagnostics or a program.
#[test]
fn mutated_cases_never_panic() {
    let mut tried = 0;
    for c in support::case_files("fst", "fst") {
        let text = std::fs::read_to_string(&c).unwrap_or_default();
        let case = parse_case(&text);
        for (k, (_, t)) in case.files.iter().enumerate() {
            for mutated in support::mutations(t, 5) {
                let mut map = SourceMap::new();
                for (j, (name, orig)) in case.files.iter().enumerate() {
                    map.add(
                        name.clone(),
                        if j == k {
                            mutated.clone()
                        } else {
                            orig.clone()
                        },
                    );
                }
                // The generated ST never fails to check: STL errors are
                // caught in the STL files.
                let label = format!("{}: {mutated:?}", c.display());
                support::check_mutated(map, &[Dialect::Fst], "<fst>", &label);
                tried += 1;
            }
        }
    }
    assert!(tried > 1000, "{tried}");
}
