//! Differential tests: every execution conformance case
//! (`tests/conformance/*.st`) and every runnable program of the valid
//! front-end corpus (`tests/corpus/valid`) runs on the interpreter and on
//! the JIT; the whole image after every scan, the way the run ended (fault
//! kind, message and site included) and the final image must be identical.
//! A case stopped by its watchdog in time (`watchdog:`) stops wherever the
//! timer finds it: there the fault's kind, message and source line and the
//! images of the scans before must be identical.

mod common;

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

/// The run parameters of a conformance case's header (the format is
/// `automat_scenario::conformance`'s; only these keys matter here).
struct Header {
    cycles: u64,
    cycle_time_ns: i64,
    program: Option<String>,
    budget: Option<u64>,
    watchdog: Option<automat_ir::TaskWatchdog>,
}

fn header(text: &str) -> Header {
    let mut h = Header {
        cycles: 1,
        cycle_time_ns: 10_000_000,
        program: None,
        budget: None,
        watchdog: None,
    };
    let body = text
        .trim_start()
        .strip_prefix("(*")
        .and_then(|b| b.split_once("*)"))
        .map_or("", |(b, _)| b);
    for line in body.lines() {
        let l = line.split_once(" -- ").map_or(line, |(a, _)| a).trim();
        let Some((key, v)) = l.split_once(':') else {
            continue;
        };
        let v = v.trim();
        match key.trim() {
            "cycles" => h.cycles = v.parse().unwrap_or(1),
            "cycle-time" => {
                h.cycle_time_ns = automat_runtime::timearg::parse_duration(v).unwrap_or(10_000_000)
            }
            "program" => h.program = Some(v.to_string()),
            "budget" => h.budget = v.parse().ok(),
            "watchdog" => h.watchdog = automat_runtime::watchdog::parse_watchdog(v).ok(),
            _ => {}
        }
    }
    h
}

#[test]
fn conformance_cases_agree() {
    let dir = root().join("tests/conformance");
    let (mut ran, mut timed, mut failed) = (0, 0, Vec::new());
    for (name, text) in st_files(&dir) {
        let spec = header(&text);
        let Ok(mut program) = common::compile(&[(name.clone(), text)], spec.program.as_deref())
        else {
            continue; // pending cases that do not compile yet
        };
        ran += 1;
        let result = match spec.watchdog {
            Some(w) => {
                timed += 1;
                for t in &mut program.tasks {
                    t.watchdog = w;
                }
                common::differential_timed(program, spec.cycles, spec.cycle_time_ns)
            }
            None => common::differential(program, spec.cycles, spec.cycle_time_ns, spec.budget),
        };
        if let Err(e) = result {
            failed.push(format!("{name}: {e}"));
        }
    }
    for f in &failed {
        eprintln!("DIFFERS {f}");
    }
    eprintln!(
        "differential: {ran} conformance cases ({timed} stopped by a watchdog in time), {} differ",
        failed.len()
    );
    assert!(ran >= 70, "only {ran} cases ran");
    assert!(timed >= 2, "only {timed} watchdog-in-time cases ran");
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
    eprintln!(
        "differential: {ran} corpus programs, {} differ",
        failed.len()
    );
    assert!(ran >= 20, "only {ran} programs ran");
    assert!(failed.is_empty(), "{} programs differ", failed.len());
}
