//! Compiles one conformance case, runs it on the scan-cycle runtime with the
//! virtual clock and compares what it sees with the case's expectations.

use super::spec::{Expect, Spec};
use automat_base::{render, Interner, SourceMap};
use automat_engine::Engine;
use automat_ir::Program;
use automat_lower::{lower, LowerOptions};
use automat_runtime::io::NoIo;
use automat_runtime::scan::Env;
use automat_runtime::Executor;
use automat_runtime::{
    resolve, run, value, ClockMode, Limit, Place, RunConfig, RunEnd, ScanObserver, SystemClock,
};
use std::sync::atomic::AtomicBool;

/// Parses, checks and lowers one file; the error is the rendered diagnostics.
fn compile(name: &str, text: &str, spec: &Spec) -> Result<Program, String> {
    let mut map = SourceMap::new();
    map.add(name, text);
    let dialects = automat_dialect::parse_names(&spec.libraries)?;
    automat_dialect::add_libraries(&mut map, &dialects);
    let mut interner = Interner::new();
    let (units, analysis) = automat_dialect::check_sources(&map, &mut interner, &dialects);
    if analysis.has_errors() {
        return Err(render::render_report(&map, &analysis.diagnostics));
    }
    let opts = LowerOptions {
        program: spec.program.clone(),
    };
    let mut program = lower(&units, &analysis, &interner, &map, &opts)
        .map_err(|d| render::render_report(&map, &d))?;
    if let Some(w) = spec.watchdog {
        for t in &mut program.tasks {
            t.watchdog = w;
        }
    }
    Ok(program)
}

/// Prints the `expect-at` places after the scans they name.
struct Snapshots<'a> {
    scans: u64,
    wanted: Vec<(&'a Expect, Place)>,
    /// (expectation, printed value) in scan order.
    seen: Vec<(&'a Expect, String)>,
}

impl ScanObserver for Snapshots<'_> {
    fn after_scan(&mut self, _plc_time_ns: i64, image: &[u8]) -> Result<(), String> {
        self.scans += 1;
        for (e, p) in &self.wanted {
            if e.at == Some(self.scans) {
                self.seen.push((e, value::format(image, p)));
            }
        }
        Ok(())
    }
}

/// The backend a case runs on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    Interp,
    /// The Cranelift JIT (`automat-jit`); a program it refuses is a failure.
    Jit,
}

/// Runs a case on the interpreter; returns the list of mismatches (empty:
/// it passed).
pub fn check(name: &str, text: &str, spec: &Spec) -> Result<Vec<String>, String> {
    check_on(name, text, spec, Backend::Interp)
}

/// Runs a case on `backend`.
pub fn check_on(
    name: &str,
    text: &str,
    spec: &Spec,
    backend: Backend,
) -> Result<Vec<String>, String> {
    let program = compile(name, text, spec)?;
    match backend {
        Backend::Interp => {
            let mut engine = Engine::new(program);
            if let Some(b) = spec.budget {
                engine.set_budget(b);
            }
            observe(&mut engine, spec)
        }
        #[cfg(feature = "jit")]
        Backend::Jit => {
            let mut jit =
                automat_jit::Jit::new(program).map_err(|e| format!("the JIT refused it: {e}"))?;
            if let Some(b) = spec.budget {
                jit.set_budget(b);
            }
            observe(&mut jit, spec)
        }
        #[cfg(not(feature = "jit"))]
        Backend::Jit => Err("automat-scenario was built without its `jit` feature".to_string()),
    }
}

fn observe<E: Executor>(engine: &mut E, spec: &Spec) -> Result<Vec<String>, String> {
    let program = engine.program().clone();
    let mut places = Vec::new();
    for e in &spec.expects {
        let p = resolve(&program, &e.path)
            .map_err(|err| format!("line {}: cannot resolve `{}`: {err}", e.line, e.path))?;
        places.push((e, p));
    }
    let mut snaps = Snapshots {
        scans: 0,
        wanted: places
            .iter()
            .filter(|(e, _)| e.at.is_some())
            .cloned()
            .collect(),
        seen: Vec::new(),
    };
    let cfg = RunConfig {
        cycle_time_ns: spec.cycle_time_ns,
        clock: ClockMode::Virtual,
        limit: Limit::Cycles(spec.cycles),
    };
    let stop = AtomicBool::new(false);
    let mut sys = SystemClock::new();
    let (mut inputs, mut outputs) = (NoIo, NoIo);
    let mut env = Env {
        clock: &mut sys,
        inputs: &mut inputs,
        outputs: &mut outputs,
        observer: &mut snaps,
        stop: &stop,
    };
    let report = run(engine, &cfg, &mut env)?;
    let mut fails = Vec::new();
    match (&report.end, &spec.fault) {
        (RunEnd::Fault(f), Some(want)) => {
            let line = f
                .fault
                .site
                .location
                .split(':')
                .rev()
                .nth(1)
                .and_then(|l| l.parse().ok());
            // The fault ends the scan it happens in; that scan is not observed.
            let cycle = snaps.scans + 1;
            if f.fault.kind != want.kind
                || line != Some(want.line)
                || want.cycle.is_some_and(|c| c != cycle)
            {
                fails.push(format!(
                    "fault: expected {:?} at line {}{}, got {:?} in cycle {cycle}: {f}",
                    want.kind,
                    want.line,
                    want.cycle
                        .map(|c| format!(" in cycle {c}"))
                        .unwrap_or_default(),
                    f.fault.kind
                ));
            }
        }
        (RunEnd::Fault(f), None) => fails.push(format!("unexpected fault: {f}")),
        (end, Some(want)) => fails.push(format!(
            "expected fault {:?} at line {}, run ended with {end:?}",
            want.kind, want.line
        )),
        (RunEnd::Limit, None) => {}
        (end, None) => fails.push(format!("run ended with {end:?}")),
    }
    for (e, got) in &snaps.seen {
        if *got != e.value {
            fails.push(mismatch(e, got));
        }
    }
    for (e, p) in &places {
        match e.at {
            None => {
                let got = value::format(engine.image(), p);
                if got != e.value {
                    fails.push(mismatch(e, &got));
                }
            }
            Some(k) if !snaps.seen.iter().any(|(s, _)| std::ptr::eq(*s, *e)) => {
                fails.push(format!(
                    "line {}: {}: scan {k} never ran ({} scans)",
                    e.line, e.path, snaps.scans
                ))
            }
            Some(_) => {}
        }
    }
    Ok(fails)
}

fn mismatch(e: &Expect, got: &str) -> String {
    let when = e.at.map(|k| format!(" after scan {k}")).unwrap_or_default();
    format!(
        "line {}: {}{when}: expected {}, got {got}",
        e.line, e.path, e.value
    )
}
