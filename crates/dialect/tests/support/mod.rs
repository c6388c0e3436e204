//! What the dialect case runners (`fst.rs`, `slc.rs`) share: the scans of
//! a case with its inputs set and its values compared exactly on both
//! engines, the case files of a folder, and the mutations that show bad
//! input never panics. Each runner keeps only its own file format.

use automat_base::{Code, Diagnostic, Interner, SourceMap};
use automat_dialect::Dialect;
use automat_engine::Engine;
use automat_iec::Elementary;
use automat_lower::{lower, LowerOptions};
use automat_runtime::{resolve, value, Executor, PlaceType};
use std::path::{Path, PathBuf};

/// What a case runs: `(scan, path, value)` sets written before their scan
/// and kept, expects read after theirs; scan N runs at PLC time
/// (N - 1) x `period_ms` from 0; `fault` is the scan that must stop with
/// a runtime fault whose message contains the text (its expects are read
/// in the image the fault left).
pub struct Run {
    pub period_ms: i64,
    pub sets: Vec<(u64, String, String)>,
    pub expects: Vec<(u64, String, String)>,
    pub fault: Option<(u64, String)>,
}

impl Default for Run {
    fn default() -> Run {
        Run {
            period_ms: 10,
            sets: Vec::new(),
            expects: Vec::new(),
            fault: None,
        }
    }
}

/// The case files `tests/<folder>/*.<ext>`, sorted.
pub fn case_files(folder: &str, ext: &str) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests")
        .join(folder);
    let mut cases: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == ext))
        .collect();
    cases.sort();
    cases
}

/// Runs every case on the interpreter and on the JIT and asserts that all
/// passed, then that every code starting with `prefix` is expected by one
/// (`: CODE` somewhere in a case file).
pub fn run_all(
    cases: &[PathBuf],
    prefix: &str,
    run_case: impl Fn(&Path, bool) -> Result<(), String>,
) {
    let mut bad = Vec::new();
    for c in cases {
        for jit in [false, true] {
            if let Err(e) = run_case(c, jit) {
                let on = if jit { "JIT" } else { "interpreter" };
                bad.push(format!("{} ({on}):\n{e}", c.display()));
            }
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n\n"));
    let all: String = cases
        .iter()
        .map(|c| std::fs::read_to_string(c).unwrap_or_default())
        .collect();
    for code in Code::ALL.iter().filter(|c| c.as_str().starts_with(prefix)) {
        assert!(
            all.contains(&format!(": {}", code.as_str())),
            "no case expects {}",
            code.as_str()
        );
    }
}

/// The diagnostics as sorted `[FILE:]LINE: CODE` lines.
pub fn diagnostic_lines(map: &SourceMap, diags: &[Diagnostic], with_file: bool) -> Vec<String> {
    let mut got: Vec<String> = diags
        .iter()
        .map(|d| {
            let f = map.get(d.span.file);
            let line = f.line_col(d.span.start).0;
            if with_file {
                format!("{}:{line}: {}", f.name, d.code.as_str())
            } else {
                format!("{line}: {}", d.code.as_str())
            }
        })
        .collect();
    got.sort();
    got
}

/// A project checked: its sources (the dialects' libraries added), what
/// the checker made of them and its diagnostics.
pub struct Checked {
    pub map: SourceMap,
    interner: Interner,
    units: Vec<automat_syntax::ast::SourceUnit>,
    pub analysis: automat_sema::Analysis,
}

/// Checks the sources of `map` with `dialects`.
pub fn check(mut map: SourceMap, dialects: &[Dialect]) -> Checked {
    automat_dialect::add_libraries(&mut map, dialects);
    let mut interner = Interner::new();
    let (units, analysis) = automat_dialect::check_sources(&map, &mut interner, dialects);
    Checked {
        map,
        interner,
        units,
        analysis,
    }
}

impl Checked {
    /// The diagnostics rendered as `automat check` prints them.
    pub fn report(&self) -> String {
        automat_base::render::render_report(&self.map, &self.analysis.diagnostics)
    }

    /// Lowers the project and runs `run` on one engine.
    pub fn run(&self, run: &Run, jit: bool) -> Result<(), String> {
        let opts = LowerOptions { program: None };
        let program = lower(
            &self.units,
            &self.analysis,
            &self.interner,
            &self.map,
            &opts,
        )
        .map_err(|d| automat_base::render::render_report(&self.map, &d))?;
        if jit {
            let mut j =
                automat_jit::Jit::new(program).map_err(|e| format!("the JIT refused it: {e}"))?;
            run_scans(&mut j, run)
        } else {
            run_scans(&mut Engine::new(program), run)
        }
    }
}

/// Writes a bit (1/0 or TRUE/FALSE), a WORD or an INT by its path.
fn write<E: Executor>(engine: &mut E, path: &str, val: &str) {
    let place = resolve(engine.program(), path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let image = engine.image_mut();
    let at = place.offset as usize;
    match (&place.ty, place.bit) {
        (PlaceType::Elementary(Elementary::Bool), Some(bit)) => {
            if matches!(val, "TRUE" | "1") {
                image[at] |= 1 << bit;
            } else {
                image[at] &= !(1 << bit);
            }
        }
        (PlaceType::Elementary(Elementary::Word), None) => {
            let v: u16 = val.parse().unwrap_or_else(|_| panic!("{path}: `{val}`"));
            image[at..at + 2].copy_from_slice(&v.to_le_bytes());
        }
        (PlaceType::Elementary(Elementary::Int), None) => {
            let v: i16 = val.parse().unwrap_or_else(|_| panic!("{path}: `{val}`"));
            image[at..at + 2].copy_from_slice(&v.to_le_bytes());
        }
        _ => panic!("{path}: only bits and words are set"),
    }
}

/// Runs the scans of a case, setting its inputs and comparing its values.
fn run_scans<E: Executor>(engine: &mut E, run: &Run) -> Result<(), String> {
    let last = run
        .expects
        .iter()
        .map(|e| e.0)
        .chain(run.fault.as_ref().map(|f| f.0))
        .max()
        .unwrap_or(0);
    let mut failures = Vec::new();
    'scans: for scan in 1..=last {
        for (_, p, v) in run.sets.iter().filter(|s| s.0 == scan) {
            write(engine, p, v);
        }
        let now = (scan as i64 - 1) * run.period_ms * 1_000_000;
        let insts: Vec<_> = engine
            .program()
            .tasks
            .iter()
            .flat_map(|t| t.programs.clone())
            .collect();
        for inst in &insts {
            match (engine.run_program(inst, now), &run.fault) {
                (Err(f), Some((at, text))) if *at == scan && f.message.contains(text.as_str()) => {
                    check_expects(engine, run, scan, &mut failures)?;
                    break 'scans;
                }
                (Err(f), _) => return Err(format!("scan {scan}: fault {}", f.message)),
                (Ok(_), Some((at, _))) if *at == scan => {
                    return Err(format!("scan {scan}: no fault"));
                }
                _ => {}
            }
        }
        check_expects(engine, run, scan, &mut failures)?;
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(failures.join("\n"))
    }
}

/// The expects of `scan`, each mismatch pushed to `failures`.
fn check_expects<E: Executor>(
    engine: &E,
    run: &Run,
    scan: u64,
    failures: &mut Vec<String>,
) -> Result<(), String> {
    for (_, p, v) in run.expects.iter().filter(|e| e.0 == scan) {
        let place = resolve(engine.program(), p).map_err(|e| format!("{p}: {e}"))?;
        let got = value::format(engine.image(), &place);
        if &got != v {
            failures.push(format!("after scan {scan}: {p} = {got}, expected {v}"));
        }
    }
    Ok(())
}

/// `text` with one word deleted, and cut short, at every `step`-th byte.
pub fn mutations(text: &str, step: usize) -> Vec<String> {
    let mut out = Vec::new();
    for at in (0..text.len())
        .step_by(step)
        .filter(|&i| text.is_char_boundary(i))
    {
        let end = text[at..]
            .find(char::is_whitespace)
            .map_or(text.len(), |e| at + e);
        out.push(format!("{}{}", &text[..at], &text[end..]));
        out.push(text[..at].to_string());
    }
    out
}

/// A mutated project never panics: the code the dialect generates (files
/// named `<generated>…`) never fails to check, and what checks clean lowers.
pub fn check_mutated(map: SourceMap, dialects: &[Dialect], generated: &str, label: &str) {
    let c = check(map, dialects);
    let in_generated = c
        .analysis
        .diagnostics
        .iter()
        .any(|d| c.map.get(d.span.file).name.starts_with(generated));
    assert!(!in_generated, "{label}\n{}", c.report());
    if !c.analysis.has_errors() {
        let opts = LowerOptions { program: None };
        if let Err(d) = lower(&c.units, &c.analysis, &c.interner, &c.map, &opts) {
            panic!(
                "{label}: {}",
                automat_base::render::render_report(&c.map, &d)
            );
        }
    }
}
