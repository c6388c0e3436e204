//! Shared by the JIT's tests: compile ST text to a Program, and run it on
//! both engines through the scan-cycle runtime, recording the image after
//! every scan.

#![allow(dead_code)]

use automat_base::{render, Interner, SourceMap};
use automat_engine::Engine;
use automat_ir::Program;
use automat_jit::Jit;
use automat_lower::{lower, LowerOptions};
use automat_runtime::io::NoIo;
use automat_runtime::scan::Env;
use automat_runtime::SystemClock;
use automat_runtime::{run, ClockMode, Executor, Limit, RunConfig, RunEnd, ScanObserver};
use std::sync::atomic::AtomicBool;

/// Parses, checks and lowers `files` (name, text); the error is the
/// rendered diagnostics.
pub fn compile(files: &[(String, String)], program: Option<&str>) -> Result<Program, String> {
    let mut map = SourceMap::new();
    for (name, text) in files {
        map.add(name, text);
    }
    let mut interner = Interner::new();
    let (units, analysis) = automat_sema::check_sources(&map, &mut interner);
    if analysis.has_errors() {
        return Err(render::render_report(&map, &analysis.diagnostics));
    }
    let opts = LowerOptions {
        program: program.map(str::to_string),
    };
    lower(&units, &analysis, &interner, &map, &opts).map_err(|d| render::render_report(&map, &d))
}

pub fn compile_one(text: &str) -> Program {
    compile(&[("t.st".to_string(), text.to_string())], None).unwrap_or_else(|e| panic!("{e}"))
}

struct Images(Vec<Vec<u8>>);

impl ScanObserver for Images {
    fn after_scan(&mut self, _t: i64, image: &[u8]) -> Result<(), String> {
        self.0.push(image.to_vec());
        Ok(())
    }
}

/// What a run shows from outside: the image after every scan, how it
/// ended, and the image at the end.
#[derive(Debug, PartialEq)]
pub struct Outcome {
    pub images: Vec<Vec<u8>>,
    pub end: RunEnd,
    pub last: Vec<u8>,
}

pub fn run_on<E: Executor>(exec: &mut E, cycles: u64, cycle_time_ns: i64) -> Outcome {
    let cfg = RunConfig {
        cycle_time_ns,
        clock: ClockMode::Virtual,
        limit: Limit::Cycles(cycles),
    };
    let stop = AtomicBool::new(false);
    let mut sys = SystemClock::new();
    let (mut i, mut o) = (NoIo, NoIo);
    let mut obs = Images(Vec::new());
    let mut env = Env {
        clock: &mut sys,
        inputs: &mut i,
        outputs: &mut o,
        observer: &mut obs,
        stop: &stop,
    };
    let report = run(exec, &cfg, &mut env).unwrap_or_else(|e| panic!("{e}"));
    Outcome {
        images: obs.0,
        end: report.end,
        last: exec.image().to_vec(),
    }
}

/// Runs `program`, whose tasks have a watchdog in time that stops it, on
/// both engines: both must fault alike (kind, message, source line; the
/// column and the image at the fault depend on where the timer found the
/// run) after identical scans.
pub fn differential_timed(program: Program, cycles: u64, cycle_time_ns: i64) -> Result<(), String> {
    let mut jit = Jit::new(program.clone()).map_err(|e| format!("JIT refused: {e}"))?;
    let mut interp = Engine::new(program);
    let a = run_on(&mut interp, cycles, cycle_time_ns);
    let b = run_on(&mut jit, cycles, cycle_time_ns);
    let (RunEnd::Fault(x), RunEnd::Fault(y)) = (&a.end, &b.end) else {
        return Err(format!(
            "not stopped by the watchdog: interpreter {:?}, JIT {:?}",
            a.end, b.end
        ));
    };
    let line = |l: &str| {
        l.rsplit_once(':')
            .map_or(l.to_string(), |(a, _)| a.to_string())
    };
    let same = x.fault.kind == y.fault.kind
        && x.fault.message == y.fault.message
        && x.fault.site.pou == y.fault.site.pou
        && line(&x.fault.site.location) == line(&y.fault.site.location)
        && (&x.task, &x.instance, x.plc_time_ns) == (&y.task, &y.instance, y.plc_time_ns);
    if !same {
        return Err(format!("fault: interpreter {x}, JIT {y}"));
    }
    if a.images != b.images {
        return Err("the images of the completed scans differ".into());
    }
    Ok(())
}

/// Runs `program` on the interpreter and the JIT; `Err` describes the
/// first difference.
pub fn differential(
    program: Program,
    cycles: u64,
    cycle_time_ns: i64,
    budget: Option<u64>,
) -> Result<(), String> {
    let mut jit = Jit::new(program.clone()).map_err(|e| format!("JIT refused: {e}"))?;
    let mut interp = Engine::new(program);
    if let Some(b) = budget {
        interp.set_budget(b);
        jit.set_budget(b);
    }
    let a = run_on(&mut interp, cycles, cycle_time_ns);
    let b = run_on(&mut jit, cycles, cycle_time_ns);
    if a.end != b.end {
        return Err(format!("run end: interpreter {:?}, JIT {:?}", a.end, b.end));
    }
    if a.images.len() != b.images.len() {
        return Err(format!(
            "scans: interpreter {}, JIT {}",
            a.images.len(),
            b.images.len()
        ));
    }
    for (k, (x, y)) in a
        .images
        .iter()
        .zip(&b.images)
        .chain([(&a.last, &b.last)])
        .enumerate()
    {
        if let Some(at) = x.iter().zip(y).position(|(p, q)| p != q) {
            return Err(format!(
                "image differs after scan {} at byte {at}: interpreter {}, JIT {}",
                k + 1,
                x[at],
                y[at]
            ));
        }
    }
    Ok(())
}
