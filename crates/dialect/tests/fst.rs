//! The Festo FST STL cases of `tests/fst/*.fst` (docs/festo-stl.md), each
//! a small project in one file: `-- P0.stl`, `-- B1.stl`,
//! `-- allocation.txt` sections hold the project's files, then either
//! - `-- run`: `set N: OPERAND = VALUE` (written before scan N, kept until
//!   set again) and `expect N: PATH = VALUE` (printed after scan N, exact);
//!   scans are 10 ms of the virtual clock from PLC time 0; or
//! - `-- errors`: `FILE:LINE: CODE` lines, the diagnostics the project
//!   must give (compared as sorted lists).

use automat_base::{Interner, SourceMap};
use automat_dialect::Dialect;
use automat_engine::Engine;
use automat_iec::Elementary;
use automat_lower::{lower, LowerOptions};
use automat_runtime::{resolve, value, Executor, PlaceType};
use std::path::{Path, PathBuf};

struct Case {
    files: Vec<(String, String)>,
    sets: Vec<(u64, String, String)>,
    expects: Vec<(u64, String, String)>,
    errors: Option<Vec<String>>,
}

fn parse_case(text: &str) -> Case {
    let mut case = Case {
        files: Vec::new(),
        sets: Vec::new(),
        expects: Vec::new(),
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
                    "set" => case.sets.push(entry),
                    "expect" => case.expects.push(entry),
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

fn write<E: Executor>(engine: &mut E, path: &str, val: &str) {
    let place = resolve(engine.program(), path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let image = engine.image_mut();
    let at = place.offset as usize;
    match (&place.ty, place.bit) {
        (PlaceType::Elementary(Elementary::Bool), Some(bit)) => {
            let on = matches!(val, "TRUE" | "1");
            if on {
                image[at] |= 1 << bit;
            } else {
                image[at] &= !(1 << bit);
            }
        }
        (PlaceType::Elementary(Elementary::Word), None) => {
            let v: u16 = val.parse().unwrap_or_else(|_| panic!("{path}: `{val}`"));
            image[at..at + 2].copy_from_slice(&v.to_le_bytes());
        }
        _ => panic!("{path}: only bits and words are set"),
    }
}

fn run_case(path: &Path, jit: bool) -> Result<(), String> {
    let text = std::fs::read_to_string(path).map_err(|e| e.to_string())?;
    let case = parse_case(&text);
    let mut map = SourceMap::new();
    for (name, t) in &case.files {
        map.add(name.clone(), t.clone());
    }
    let dialects = [Dialect::Fst];
    automat_dialect::add_libraries(&mut map, &dialects);
    let mut interner = Interner::new();
    let (units, analysis) = automat_dialect::check_sources(&map, &mut interner, &dialects);
    let report = automat_base::render::render_report(&map, &analysis.diagnostics);
    if let Some(want) = &case.errors {
        let mut got: Vec<String> = analysis
            .diagnostics
            .iter()
            .map(|d| {
                let f = map.get(d.span.file);
                format!(
                    "{}:{}: {}",
                    f.name,
                    f.line_col(d.span.start).0,
                    d.code.as_str()
                )
            })
            .collect();
        got.sort();
        let mut want = want.clone();
        want.sort();
        return if got == want {
            Ok(())
        } else {
            Err(format!("diagnostics {got:?}, wanted {want:?}\n{report}"))
        };
    }
    if !analysis.diagnostics.is_empty() {
        return Err(format!("should check clean:\n{report}"));
    }
    let program = lower(
        &units,
        &analysis,
        &interner,
        &map,
        &LowerOptions { program: None },
    )
    .map_err(|d| automat_base::render::render_report(&map, &d))?;
    if jit {
        let mut j =
            automat_jit::Jit::new(program).map_err(|e| format!("the JIT refused it: {e}"))?;
        run_scans(&mut j, &case)
    } else {
        run_scans(&mut Engine::new(program), &case)
    }
}

/// Runs the scans of a case, setting its inputs and comparing its values.
fn run_scans<E: Executor>(engine: &mut E, case: &Case) -> Result<(), String> {
    let last = case.expects.iter().map(|e| e.0).max().unwrap_or(0);
    let mut failures = Vec::new();
    for scan in 1..=last {
        for (_, p, v) in case.sets.iter().filter(|s| s.0 == scan) {
            write(engine, p, v);
        }
        let now = (scan as i64 - 1) * 10_000_000;
        let insts: Vec<_> = engine
            .program()
            .tasks
            .iter()
            .flat_map(|t| t.programs.clone())
            .collect();
        for inst in &insts {
            engine
                .run_program(inst, now)
                .map_err(|f| format!("scan {scan}: {}", f.message))?;
        }
        for (_, p, v) in case.expects.iter().filter(|e| e.0 == scan) {
            let place = resolve(engine.program(), p).map_err(|e| format!("{p}: {e}"))?;
            let got = value::format(engine.image(), &place);
            if &got != v {
                failures.push(format!("after scan {scan}: {p} = {got}, expected {v}"));
            }
        }
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(failures.join("\n"))
    }
}

#[test]
fn fst_cases() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/fst");
    let mut cases: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "fst"))
        .collect();
    cases.sort();
    assert!(cases.len() >= 18, "the D3 examples are cases");
    let mut bad = Vec::new();
    for c in &cases {
        for jit in [false, true] {
            if let Err(e) = run_case(c, jit) {
                let on = if jit { "JIT" } else { "interpreter" };
                bad.push(format!("{} ({on}):\n{e}", c.display()));
            }
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n\n"));
    // Every FST code is announced by a case.
    let all: String = cases
        .iter()
        .map(|c| std::fs::read_to_string(c).unwrap_or_default())
        .collect();
    for code in automat_base::Code::ALL
        .iter()
        .filter(|c| c.as_str().starts_with("E18"))
    {
        assert!(
            all.contains(&format!(": {}", code.as_str())),
            "no case expects {}",
            code.as_str()
        );
    }
}

/// Bad input never panics: every case's STL files with one word deleted,
/// or cut short, at many places, still give diagnostics or a program.
#[test]
fn mutated_cases_never_panic() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/fst");
    let mut cases: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "fst"))
        .collect();
    cases.sort();
    let mut tried = 0;
    for c in &cases {
        let text = std::fs::read_to_string(c).unwrap_or_default();
        let case = parse_case(&text);
        for (k, (_, t)) in case.files.iter().enumerate() {
            let cuts: Vec<usize> = (0..t.len())
                .step_by(5)
                .filter(|&i| t.is_char_boundary(i))
                .collect();
            for &at in &cuts {
                let end = t[at..]
                    .find(char::is_whitespace)
                    .map_or(t.len(), |e| at + e);
                for mutated in [format!("{}{}", &t[..at], &t[end..]), t[..at].to_string()] {
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
                    automat_dialect::add_libraries(&mut map, &[Dialect::Fst]);
                    let mut interner = Interner::new();
                    let (units, analysis) =
                        automat_dialect::check_sources(&map, &mut interner, &[Dialect::Fst]);
                    // The generated ST never fails to check: STL errors
                    // are caught in the STL files.
                    let generated: Vec<_> = analysis
                        .diagnostics
                        .iter()
                        .filter(|d| map.get(d.span.file).name.starts_with("<fst>"))
                        .collect();
                    assert!(
                        generated.is_empty(),
                        "{}: {mutated:?}\n{}",
                        c.display(),
                        automat_base::render::render_report(&map, &analysis.diagnostics)
                    );
                    // An STL project that checks clean also lowers.
                    if !analysis.has_errors() {
                        let opts = LowerOptions { program: None };
                        if let Err(d) = lower(&units, &analysis, &interner, &map, &opts) {
                            panic!(
                                "{}: {}",
                                c.display(),
                                automat_base::render::render_report(&map, &d)
                            );
                        }
                    }
                    tried += 1;
                }
            }
        }
    }
    assert!(tried > 1000, "{tried}");
}
