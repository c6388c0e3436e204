//! Compiles one conformance case, runs it on the scan-cycle runtime with the
//! virtual clock and compares what it sees with the case's expectations.

use super::spec::{Expect, Spec};
use automat_base::{render, Interner, SourceMap};
use automat_engine::Engine;
use automat_ir::Program;
use automat_lower::{lower, LowerOptions};
use automat_runtime::Executor;
use automat_runtime::{
    resolve, value, ClockMode, Limit, Place, SafeState, ScanObserver, SystemClock,
};
use automat_session::{run_here, Config, End, Parts, Watching};
use std::cell::RefCell;
use std::rc::Rc;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

/// What a case is checked with besides its own text: the other files of
/// its project (a library the case exercises, `automat corpus`) and
/// dialects beside its header's `libraries:`. Empty for a plain case.
#[derive(Clone, Copy, Debug, Default)]
pub struct Context<'a> {
    /// (file name, text) of each other source file.
    pub files: &'a [(String, String)],
    pub libraries: &'a [String],
}

/// Parses, checks and lowers one file (with its context); the error is the
/// rendered diagnostics.
fn compile(name: &str, text: &str, spec: &Spec, ctx: Context) -> Result<Program, String> {
    let mut map = SourceMap::new();
    map.add(name, text);
    for (n, t) in ctx.files {
        map.add(n.as_str(), t.as_str());
    }
    let mut names = spec.libraries.clone();
    names.extend(ctx.libraries.iter().cloned());
    let libraries = automat_dialect::parse_libraries(&names)?;
    automat_dialect::add_libraries_to(&mut map, &libraries);
    let dialects = libraries.dialects;
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
struct Snapshots {
    scans: u64,
    wanted: Vec<(Expect, Place)>,
    /// (expectation, printed value) in scan order.
    seen: Vec<(Expect, String)>,
}

impl ScanObserver for Snapshots {
    fn after_scan(&mut self, _plc_time_ns: i64, image: &[u8]) -> Result<(), String> {
        self.scans += 1;
        for (e, p) in &self.wanted {
            if e.at == Some(self.scans) {
                self.seen.push((e.clone(), value::format(image, p)));
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
    check_in(name, text, spec, backend, Context::default())
}

/// Runs a case on `backend` together with its [`Context`].
pub fn check_in(
    name: &str,
    text: &str,
    spec: &Spec,
    backend: Backend,
    ctx: Context,
) -> Result<Vec<String>, String> {
    let program = compile(name, text, spec, ctx)?;
    match backend {
        Backend::Interp => {
            let mut engine = Engine::new(program);
            if let Some(b) = spec.budget {
                engine.set_budget(b);
            }
            observe(engine, spec)
        }
        #[cfg(feature = "jit")]
        Backend::Jit => {
            let mut jit =
                automat_jit::Jit::new(program).map_err(|e| format!("the JIT refused it: {e}"))?;
            if let Some(b) = spec.budget {
                jit.set_budget(b);
            }
            observe(jit, spec)
        }
        #[cfg(not(feature = "jit"))]
        Backend::Jit => Err("automat-scenario was built without its `jit` feature".to_string()),
    }
}

/// Runs the case through the PLC session (the scan loop every run of
/// automat uses) on the virtual clock. A fault leaves the image as the
/// fault left it (no outputs are forced to a safe state): the case's
/// final expectations see what the program did.
fn observe<E: Executor + 'static>(engine: E, spec: &Spec) -> Result<Vec<String>, String> {
    let program = engine.program().clone();
    let mut places = Vec::new();
    for e in &spec.expects {
        let p = resolve(&program, &e.path)
            .map_err(|err| format!("line {}: cannot resolve `{}`: {err}", e.line, e.path))?;
        places.push((e, p));
    }
    let wanted: Vec<(Expect, Place)> = places
        .iter()
        .filter(|(e, _)| e.at.is_some())
        .map(|(e, p)| ((*e).clone(), p.clone()))
        .collect();
    let snaps = Rc::new(RefCell::new(Snapshots {
        scans: 0,
        wanted,
        seen: Vec::new(),
    }));
    let config = Config {
        cycle_time_ns: spec.cycle_time_ns,
        clock: ClockMode::Virtual,
        monotonic: Box::new(SystemClock::new()),
        running: true,
        stop: Arc::new(AtomicBool::new(false)),
        retain: None,
        safe: Some(SafeState::default()),
        realtime: None,
        wait_after_fault: false,
    };
    let parts = Parts {
        exec: Box::new(engine),
        sim: None,
        observer: Some(Box::new(Watching(Rc::clone(&snaps)))),
        exchange: None,
    };
    let end = run_here(Arc::new(program), config, parts, Limit::Cycles(spec.cycles));
    if end.end == End::Error {
        return Err(end.error.unwrap_or_default());
    }
    let snaps = snaps.borrow();
    let mut fails = Vec::new();
    match (end.end, &end.fault_report, &spec.fault) {
        (End::Fault, Some(f), Some(want)) => {
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
        (End::Fault, f, None) => fails.push(format!(
            "unexpected fault: {}",
            f.as_ref().map_or(String::new(), ToString::to_string)
        )),
        (end, _, Some(want)) => fails.push(format!(
            "expected fault {:?} at line {}, run ended with {end:?}",
            want.kind, want.line
        )),
        (End::Limit, _, None) => {}
        (end, _, None) => fails.push(format!("run ended with {end:?}")),
    }
    for (e, got) in &snaps.seen {
        if *got != e.value {
            fails.push(mismatch(e, got));
        }
    }
    for (e, p) in &places {
        match e.at {
            None => {
                let got = value::format(&end.image, p);
                if got != e.value {
                    fails.push(mismatch(e, &got));
                }
            }
            Some(k) if !snaps.seen.iter().any(|(s, _)| s.line == e.line) => fails.push(format!(
                "line {}: {}: scan {k} never ran ({} scans)",
                e.line, e.path, snaps.scans
            )),
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
