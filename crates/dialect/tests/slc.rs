//! The Allen-Bradley SLC-500 cases of `tests/slc/*.slc`
//! (docs/allen-bradley.md). Each case is a ladder file whose `;` comment
//! lines at the top say what must hold:
//! - `; period: MS` the scan period (10 ms by default; scan N runs at PLC
//!   time (N - 1) x period from 0);
//! - `; set N: ADDRESS = VALUE` written before scan N (1/0 or TRUE/FALSE
//!   for a bit, an integer for a word), kept until set again;
//! - `; expect N: ADDRESS = VALUE` read after scan N, exact (bits print
//!   1/0, as `--print` shows them);
//! - `; fault N: TEXT` scan N stops with a runtime fault whose message
//!   contains TEXT (the expects of scan N are read in the image the fault
//!   left, e.g. the PID's sub-error code);
//! - `; error LINE: CODE` the file must give exactly these diagnostics.
//!
//! Every case runs on the interpreter and on the JIT.

use automat_base::{Interner, SourceMap};
use automat_engine::Engine;
use automat_iec::Elementary;
use automat_lower::{lower, LowerOptions};
use automat_runtime::{resolve, value, Executor, PlaceType};
use std::path::{Path, PathBuf};

#[derive(Default)]
struct Case {
    period_ms: i64,
    sets: Vec<(u64, String, String)>,
    expects: Vec<(u64, String, String)>,
    fault: Option<(u64, String)>,
    errors: Vec<String>,
}

fn header(text: &str) -> Case {
    let mut c = Case {
        period_ms: 10,
        ..Case::default()
    };
    for line in text.lines() {
        let Some(l) = line.trim().strip_prefix(';') else {
            continue;
        };
        let l = l.trim();
        let Some((head, rest)) = l.split_once(':') else {
            continue;
        };
        let rest = rest.trim();
        if head == "period" {
            c.period_ms = rest.parse().unwrap_or_else(|_| panic!("bad period `{l}`"));
            continue;
        }
        let Some((what, at)) = head.split_once(' ') else {
            continue;
        };
        let Ok(at) = at.trim().parse::<u64>() else {
            continue;
        };
        match what {
            "set" | "expect" => {
                let (p, v) = rest
                    .rsplit_once('=')
                    .unwrap_or_else(|| panic!("bad line `{l}`"));
                let e = (at, p.trim().to_string(), v.trim().to_string());
                if what == "set" {
                    c.sets.push(e);
                } else {
                    c.expects.push(e);
                }
            }
            "fault" => c.fault = Some((at, rest.to_string())),
            "error" => c.errors.push(format!("{at}: {rest}")),
            _ => {}
        }
    }
    c
}

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
        (PlaceType::Elementary(Elementary::Int), None) => {
            let v: i16 = val.parse().unwrap_or_else(|_| panic!("{path}: `{val}`"));
            image[at..at + 2].copy_from_slice(&v.to_le_bytes());
        }
        _ => panic!("{path}: only bits and words are set"),
    }
}

fn run_case(path: &Path, jit: bool) -> Result<(), String> {
    let text = std::fs::read_to_string(path).map_err(|e| e.to_string())?;
    let case = header(&text);
    let mut map = SourceMap::new();
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_default();
    map.add(name, text);
    automat_dialect::add_libraries(&mut map, &[]);
    let mut interner = Interner::new();
    let (units, analysis) = automat_dialect::check_sources(&map, &mut interner, &[]);
    let report = automat_base::render::render_report(&map, &analysis.diagnostics);
    let mut got: Vec<String> = analysis
        .diagnostics
        .iter()
        .map(|d| {
            let f = map.get(d.span.file);
            format!("{}: {}", f.line_col(d.span.start).0, d.code.as_str())
        })
        .collect();
    got.sort();
    let mut want = case.errors.clone();
    want.sort();
    if got != want {
        return Err(format!("diagnostics {got:?}, wanted {want:?}\n{report}"));
    }
    if !want.is_empty() {
        return Ok(());
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

fn run_scans<E: Executor>(engine: &mut E, case: &Case) -> Result<(), String> {
    let last = case
        .expects
        .iter()
        .map(|e| e.0)
        .chain(case.fault.as_ref().map(|f| f.0))
        .max()
        .unwrap_or(0);
    let mut failures = Vec::new();
    for scan in 1..=last {
        for (_, p, v) in case.sets.iter().filter(|s| s.0 == scan) {
            write(engine, p, v);
        }
        let now = (scan as i64 - 1) * case.period_ms * 1_000_000;
        let insts: Vec<_> = engine
            .program()
            .tasks
            .iter()
            .flat_map(|t| t.programs.clone())
            .collect();
        for inst in &insts {
            match (engine.run_program(inst, now), &case.fault) {
                (Err(f), Some((at, text))) if *at == scan && f.message.contains(text.as_str()) => {
                    check_expects(engine, case, scan, &mut failures)?;
                    return if failures.is_empty() {
                        Ok(())
                    } else {
                        Err(failures.join("\n"))
                    };
                }
                (Err(f), _) => return Err(format!("scan {scan}: fault {}", f.message)),
                (Ok(_), Some((at, _))) if *at == scan => {
                    return Err(format!("scan {scan}: no fault"));
                }
                _ => {}
            }
        }
        check_expects(engine, case, scan, &mut failures)?;
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
    case: &Case,
    scan: u64,
    failures: &mut Vec<String>,
) -> Result<(), String> {
    for (_, p, v) in case.expects.iter().filter(|e| e.0 == scan) {
        let place = resolve(engine.program(), p).map_err(|e| format!("{p}: {e}"))?;
        let got = value::format(engine.image(), &place);
        if &got != v {
            failures.push(format!("after scan {scan}: {p} = {got}, expected {v}"));
        }
    }
    Ok(())
}

fn cases() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/slc");
    let mut cases: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "slc"))
        .collect();
    cases.sort();
    cases
}

#[test]
fn slc_cases() {
    let cases = cases();
    assert!(cases.len() >= 10, "{}", cases.len());
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
    // Every SLC code is announced by a case.
    let all: String = cases
        .iter()
        .map(|c| std::fs::read_to_string(c).unwrap_or_default())
        .collect();
    for code in automat_base::Code::ALL
        .iter()
        .filter(|c| c.as_str().starts_with("E23"))
    {
        assert!(
            all.contains(&format!(": {}", code.as_str())),
            "no case expects {}",
            code.as_str()
        );
    }
}

/// Bad input never panics: every case with one word deleted, or cut
/// short, at many places, gives diagnostics or a program that lowers, and
/// the generated ST never fails to check.
#[test]
fn mutated_cases_never_panic() {
    let mut tried = 0;
    for c in cases() {
        let t = std::fs::read_to_string(&c).unwrap_or_default();
        let cuts: Vec<usize> = (0..t.len())
            .step_by(7)
            .filter(|&i| t.is_char_boundary(i))
            .collect();
        for &at in &cuts {
            let end = t[at..]
                .find(char::is_whitespace)
                .map_or(t.len(), |e| at + e);
            for mutated in [format!("{}{}", &t[..at], &t[end..]), t[..at].to_string()] {
                let mut map = SourceMap::new();
                map.add("m.slc", mutated.clone());
                automat_dialect::add_libraries(&mut map, &[]);
                let mut interner = Interner::new();
                let (units, analysis) = automat_dialect::check_sources(&map, &mut interner, &[]);
                let generated: Vec<_> = analysis
                    .diagnostics
                    .iter()
                    .filter(|d| map.get(d.span.file).name.starts_with("<slc>"))
                    .collect();
                assert!(
                    generated.is_empty(),
                    "{}: {mutated:?}\n{}",
                    c.display(),
                    automat_base::render::render_report(&map, &analysis.diagnostics)
                );
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
    assert!(tried > 500, "{tried}");
}
