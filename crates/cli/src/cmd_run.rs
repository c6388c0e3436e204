//! `automat run`: compile a project and run it on the scan-cycle runtime.
//!
//! Exit codes (a contract): 0 ok, 1 the program does not compile, 2 bad
//! command line (unknown variable, bad duration, unreadable file, `--program`
//! naming no PROGRAM), 3 runtime fault.

use crate::retain_run::{self, RetainCfg};
use crate::{files, Outcome};
use automat_base::{render, Code, Diagnostic, Interner, SourceMap};
use automat_ir::Program;
use automat_lower::{lower, LowerOptions};
use automat_runtime::trace::{Column, Trace};
use automat_runtime::{
    locate, timearg, value, ClockMode, Limit, Locator, SafeState, ScanObserver, SystemClock,
};
use automat_session::{Config, End, Final, Parts, Watching};
use clap::Args;
use std::cell::RefCell;
use std::fs::File;
use std::io::BufWriter;
use std::path::PathBuf;
use std::rc::Rc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Compile Structured Text sources and run them as a PLC.
///
/// Without a CONFIGURATION the PROGRAM runs as a cyclic task every
/// --cycle-time; with one, every TASK runs at its INTERVAL (higher priority
/// first) or on the rising edge of its SINGLE variable.
///
/// With --cycles or --duration the run uses the virtual clock (scans back to
/// back, PLC time of scan k exactly (k-1) x period) and stops by itself;
/// otherwise it runs in real time until Ctrl-C, SIGTERM or SIGHUP, which
/// stop at the end of the scan (outputs to their safe values, RETAIN
/// variables saved); a scan still running a second later is stopped as a
/// fault. Every task run is watched in wall time (--watchdog,
/// `[tasks.NAME]`; see docs/watchdog.md).
///
/// Exit codes: 0 ok, 1 the program does not compile (or, with --scenario,
/// an expectation failed), 2 bad command line
/// (including an unknown variable in --print or --trace, or a --retain
/// path that cannot be written), 3 runtime fault (every output, the %Q
/// area and each program VAR_OUTPUT, set to its safe value; the message
/// names the fault, the POU and file:line:col).
#[derive(Args)]
pub struct RunArgs {
    /// Source files or project directories (searched recursively for *.st).
    #[arg(required = true, value_name = "PATH")]
    pub(crate) paths: Vec<PathBuf>,
    /// The PROGRAM to run when there is no CONFIGURATION and several PROGRAMs.
    #[arg(long, value_name = "NAME")]
    pub(crate) program: Option<String>,
    /// Stop after N cycles of the fastest task (implies --virtual-clock).
    #[arg(long, value_name = "N", conflicts_with = "duration")]
    pub(crate) cycles: Option<u64>,
    /// Stop when PLC time reaches TIME: a task of interval I runs at 0, I,
    /// 2I, ... < TIME (implies --virtual-clock). TIME as `1s` or `T#1s500ms`.
    #[arg(long, value_name = "TIME", value_parser = timearg::parse_duration)]
    pub(crate) duration: Option<i64>,
    /// Period of the cyclic task when there is no CONFIGURATION (`10ms` or `T#10ms`).
    /// (Default 10ms, or the project's `cycle_time`.)
    #[arg(long, value_name = "TIME", value_parser = timearg::parse_duration)]
    pub(crate) cycle_time: Option<i64>,
    /// Run scans back to back on virtual PLC time instead of real time.
    #[arg(long)]
    pub(crate) virtual_clock: bool,
    /// After the run, print `VAR = VALUE` (repeatable; in the order given).
    /// VAR: `x` (a variable of the program), `inst.fb.Q`, `arr[2, 1].x`,
    /// a global name, or a direct address such as `%QX0.1`. VALUE is an IEC
    /// literal: TRUE, 42, 3.5, T#1s500ms, 'abc'.
    #[arg(long = "print", value_name = "VAR")]
    pub(crate) print: Vec<String>,
    /// Variables to trace, separated by commas (repeatable): one CSV row per
    /// scan with the PLC time then each value. `steps(INST)` traces the
    /// active steps of the SFC chart of instance INST (`steps(Main)`: one
    /// cell such as `S2 S5`, drawn as a band by `automat plot`). Needs
    /// --trace-file.
    #[arg(long, value_name = "VAR,...", requires = "trace_file")]
    pub(crate) trace: Vec<String>,
    /// The CSV file --trace writes: a header row (`time` and the variable
    /// names), then one row per scan, every cell in the --print form
    /// (`T#20ms,5,TRUE`).
    #[arg(long, value_name = "FILE", requires = "trace")]
    pub(crate) trace_file: Option<PathBuf>,
    /// Keep RETAIN variables in FILE: loaded at start (warm start), saved
    /// when the run stops, always as they were at the end of the last
    /// completed scan (after a runtime fault: before the faulting scan). A
    /// missing file means a cold start; a damaged or outdated one (the
    /// program's RETAIN variables changed), or one holding a value its
    /// type cannot have, a cold start with a warning, the file moved to
    /// FILE.bad. The folder is checked before the first scan: exit 2 if
    /// it cannot be written (see --retain-optional). (Projects: `[retain]
    /// file` in automat.toml.)
    #[arg(long, value_name = "FILE")]
    pub(crate) retain: Option<PathBuf>,
    /// Also save the RETAIN variables every TIME of PLC time while running
    /// (when one changed), so a power cut loses at most that; `0s`: only
    /// when the run stops. Default 10s. (Projects: `[retain] save_every`.)
    #[arg(long, value_name = "TIME", value_parser = timearg::parse_duration)]
    pub(crate) retain_every: Option<i64>,
    /// Run even when the --retain path fails its start-up check (a
    /// warning instead of exit 2).
    #[arg(long)]
    pub(crate) retain_optional: bool,
    /// Cold start: ignore the --retain file (it is still written at stop).
    #[arg(long)]
    pub(crate) cold: bool,
    /// Print scan statistics (scan time min/avg/max, overruns, runs per
    /// task) to stderr after the run.
    #[arg(long)]
    pub(crate) stats: bool,
    /// Use a vendor dialect (repeatable): `isagraf` (ISaGRAF helper blocks,
    /// TIMER, sections, child charts), `pl7` (%Xi steps, %S/%SW system
    /// objects, P1/N1/P0), `fst` (Festo STL) or `codesys` (CODESYS V2.3/V3
    /// and TwinCAT code). See docs/vendor-dialects.md.
    #[arg(long = "lib", value_name = "NAME")]
    pub(crate) libs: Vec<String>,
    /// The backend: `jit` (native code; a program it cannot compile runs on
    /// the interpreter, with a note) or `interp` (the reference interpreter).
    #[arg(long, value_enum, default_value_t = crate::engines::EngineKind::Jit)]
    pub(crate) engine: crate::engines::EngineKind,
    /// Project folders only: in real time, run N times faster than real
    /// time (PLC and plant time both).
    #[arg(long, value_name = "N", default_value_t = 1.0)]
    pub(crate) speed: f64,
    /// Drive the run by this scenario file (its timed actions and `when`
    /// reactions, its `seed`) and judge its expectations as `automat test`
    /// does: the failed ones on stderr, exit 1. Its `duration` bounds the
    /// run when neither --cycles nor --duration is given. Works on plain
    /// source files and on projects without `[plant]` too: the scenario
    /// sets and presses the program's own variables (docs/scenarios.md).
    #[arg(long, value_name = "FILE.scn")]
    pub(crate) scenario: Option<PathBuf>,
    /// Serve the network API (HTTP/JSON and a WebSocket, see
    /// docs/online-api.md) while the PLC runs, on 127.0.0.1:PORT or
    /// ADDR:PORT; runs until Ctrl-C. With --virtual-clock the PLC starts
    /// stopped and runs by `step` commands.
    #[arg(long, value_name = "[ADDR:]PORT")]
    pub(crate) listen: Option<String>,
    /// Serve the PLC as a Modbus TCP server (slave) on 127.0.0.1:PORT or
    /// ADDR:PORT with the OpenPLC-compatible map (docs/modbus.md); wins
    /// over `[modbus.server] listen` of automat.toml. Runs until Ctrl-C.
    #[arg(long, value_name = "[ADDR:]PORT")]
    pub(crate) modbus_server: Option<String>,
    /// Serve the PLC as an OPC UA server on 127.0.0.1:PORT or ADDR:PORT
    /// (docs/opcua.md); wins over `[opcua] listen` of automat.toml. Runs
    /// until Ctrl-C.
    #[arg(long, value_name = "[ADDR:]PORT")]
    pub(crate) opcua: Option<String>,
    /// --listen: the token (engineer rights) is the content of FILE; a
    /// missing FILE is created with a random token, readable only by you.
    #[arg(long, value_name = "FILE", requires = "listen")]
    pub(crate) token_file: Option<PathBuf>,
    /// --listen: serve HTTPS/WSS with this certificate (PEM).
    #[arg(long, value_name = "FILE", requires_all = ["listen", "tls_key"])]
    pub(crate) tls_cert: Option<PathBuf>,
    /// --listen: the private key (PEM) of --tls-cert.
    #[arg(long, value_name = "FILE", requires_all = ["listen", "tls_cert"])]
    pub(crate) tls_key: Option<PathBuf>,
    /// --listen: allow plain HTTP on a non-loopback address.
    #[arg(long, requires = "listen")]
    pub(crate) insecure: bool,
    /// The watchdog of the implicit task (and of every task without
    /// `[tasks.NAME] watchdog` in automat.toml): a run of the task longer
    /// than TIME (`100ms`, `T#2s`) stops the PLC with a fault naming the
    /// task and the line it was executing; `off` for none. Default: 10s of
    /// wall time per run on the virtual clock, off in real time. See
    /// docs/watchdog.md.
    #[arg(long, value_name = "TIME|off", value_parser = automat_runtime::watchdog::parse_watchdog)]
    pub(crate) watchdog: Option<automat_ir::TaskWatchdog>,
    /// Fault a task run after N IR instructions (deterministic, for tests;
    /// off by default).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub(crate) max_instructions: Option<u64>,
    /// Real-time mode (Linux, real-time runs): lock the process's memory
    /// and run the scan thread at SCHED_FIFO (--rt-priority, default 80),
    /// optionally pinned to --cpus; a refusal of the system is an error
    /// that says why (exit 2). Projects: `[runtime] realtime = true`. See
    /// docs/realtime.md.
    #[arg(long)]
    pub(crate) realtime: bool,
    /// --realtime: the scan thread's SCHED_FIFO priority, 1 to 99.
    #[arg(long, value_name = "N")]
    pub(crate) rt_priority: Option<i32>,
    /// --realtime: the CPUs the scan thread runs on (`1`, `0,2-3`).
    #[arg(long, value_name = "LIST")]
    pub(crate) cpus: Option<String>,
}

/// Splits `--trace` values on the commas that are not inside `[...]`, so
/// `a,arr[1, 2].x` is two variables.
pub(crate) fn split_trace(values: &[String]) -> Vec<String> {
    let mut out = Vec::new();
    for v in values {
        let mut depth = 0i32;
        let mut cur = String::new();
        for c in v.chars() {
            match c {
                '[' => depth += 1,
                ']' => depth -= 1,
                ',' if depth <= 0 => {
                    out.push(std::mem::take(&mut cur).trim().to_string());
                    continue;
                }
                _ => {}
            }
            cur.push(c);
        }
        out.push(cur.trim().to_string());
    }
    out
}

/// Parses, checks and lowers the project; diagnostics are printed to stderr.
pub(crate) fn compile(args: &RunArgs) -> Result<Program, Outcome> {
    let libraries = automat_dialect::parse_libraries(&args.libs).map_err(|e| {
        eprintln!("error: --lib: {e}");
        Outcome::BadInput
    })?;
    let mut map: SourceMap = files::collect(&args.paths)
        .and_then(|f| files::load(&f))
        .map_err(|e| {
            eprintln!("error: {e}");
            Outcome::BadInput
        })?;
    automat_dialect::add_libraries_to(&mut map, &libraries);
    let dialects = libraries.dialects;
    let mut interner = Interner::new();
    let (units, analysis) = automat_dialect::check_sources(&map, &mut interner, &dialects);
    if !analysis.diagnostics.is_empty() {
        eprint!("{}", render::render_report(&map, &analysis.diagnostics));
    }
    if analysis.has_errors() {
        return Err(Outcome::ProgramErrors);
    }
    let opts = LowerOptions {
        program: args.program.clone(),
    };
    lower(&units, &analysis, &interner, &map, &opts).map_err(|diags: Vec<Diagnostic>| {
        eprint!("{}", render::render_report(&map, &diags));
        // `--program` naming no PROGRAM is a command-line mistake.
        if args.program.is_some() && diags.iter().all(|d| d.code == Code::E090) {
            Outcome::BadInput
        } else {
            Outcome::ProgramErrors
        }
    })
}

/// Resolves every variable named on the command line (an SLC indexed or
/// indirect address is found in the image when it is printed).
pub(crate) fn places(
    program: &Program,
    names: &[String],
    option: &str,
) -> Result<Vec<(String, Locator)>, Outcome> {
    names
        .iter()
        .map(|n| match locate(program, n) {
            Ok(p) => Ok((n.clone(), p)),
            Err(e) => {
                eprintln!("error: {option} {n}: {e}");
                Err(Outcome::BadInput)
            }
        })
        .collect()
}

/// The `--print` lines of the last image; an SLC indexed or indirect
/// address outside its data file in that image prints `?` and says why.
pub(crate) fn print_values(image: &[u8], prints: &[(String, Locator)]) {
    for (name, loc) in prints {
        match loc.place(image) {
            Ok(p) => println!("{name} = {}", value::format(image, &p)),
            Err(e) => {
                println!("{name} = ?");
                eprintln!("error: --print {name}: {e}");
            }
        }
    }
}

/// The `--trace` columns: variables, and `steps(OWNER)` for the active
/// steps of a chart (a band in `automat plot`).
fn trace_columns(program: &Program, names: &[String]) -> Result<Vec<(String, Column)>, Outcome> {
    names
        .iter()
        .map(|n| match automat_project::steps::column(program, n) {
            Some(Ok(chart)) => Ok((n.clone(), chart.trace_column())),
            Some(Err(e)) => {
                eprintln!("error: --trace {n}: {e}");
                Err(Outcome::BadInput)
            }
            None => match locate(program, n) {
                Ok(Locator::Fixed(p)) => Ok((n.clone(), Column::Value(p))),
                Ok(l) => Ok((n.clone(), Column::Located(l))),
                Err(e) => {
                    eprintln!("error: --trace {n}: {e}");
                    Err(Outcome::BadInput)
                }
            },
        })
        .collect()
}

/// Asks `stop` to be set on Ctrl-C, SIGTERM (how service managers stop a
/// process) and SIGHUP: the scan in progress completes, the outputs go to
/// their safe values and the RETAIN variables are saved.
pub(crate) fn stop_on_signals(stop: &Arc<AtomicBool>) {
    let flag = Arc::clone(stop);
    if let Err(e) = ctrlc::set_handler(move || flag.store(true, Ordering::Relaxed)) {
        eprintln!("warning: cannot handle Ctrl-C/SIGTERM/SIGHUP ({e}); stop the PLC with a signal");
    }
}

/// The note of a run that ended in the safe state, on a fault or not.
pub(crate) fn safe_note_of(fault: bool, safe: &SafeState) {
    if fault {
        eprintln!(
            "note: the PLC stopped in its safe state: {}",
            safe.describe()
        );
    } else {
        eprintln!(
            "note: stopped at the end of a scan, in the safe state: {}",
            safe.describe()
        );
    }
}

pub fn run_cmd(args: &RunArgs) -> Outcome {
    match run_inner(args) {
        Ok(o) | Err(o) => o,
    }
}

fn run_inner(args: &RunArgs) -> Result<Outcome, Outcome> {
    if crate::cmd_online::wanted(args) {
        return crate::cmd_online::run(args);
    }
    if args.speed != 1.0 {
        eprintln!(
            "error: --speed applies to real-time runs; this one is on the virtual clock (--cycles, --duration, --scenario or --virtual-clock)"
        );
        return Err(Outcome::BadInput);
    }
    if let [p] = args.paths.as_slice() {
        if let Some(toml) = automat_project::project_file(p) {
            return crate::project_run::run(args, &toml);
        }
    }
    if args.scenario.is_some() {
        return crate::project_run::run_sources(args);
    }
    let cycle_time = args.cycle_time.unwrap_or(10_000_000);
    if cycle_time <= 0 {
        eprintln!("error: --cycle-time must be longer than 0");
        return Err(Outcome::BadInput);
    }
    let mut program = compile(args)?;
    crate::engines::default_watchdog(&mut program, args.watchdog);
    let prints = places(&program, &args.print, "--print")?;
    let traced = trace_columns(&program, &split_trace(&args.trace))?;
    let safe = SafeState::of_program(&program);
    let retain = RetainCfg::of(args, None);
    retain_run::check(&program, retain.as_ref())?;
    let mut engine = crate::engines::build(program.clone(), args.engine);
    engine.set_budget(args.max_instructions);
    retain_run::warm(&mut engine, retain.as_ref(), args.cold);

    let trace = match &args.trace_file {
        Some(path) => {
            let file = File::create(path).map_err(|e| {
                eprintln!("error: {}: {e}", path.display());
                Outcome::BadInput
            })?;
            let t = Trace::new(traced, BufWriter::new(file)).map_err(|e| {
                eprintln!("error: {}: {e}", path.display());
                Outcome::BadInput
            })?;
            Some(Rc::new(RefCell::new(t)))
        }
        None => None,
    };

    let limit = match (args.cycles, args.duration) {
        (Some(n), _) => Limit::Cycles(n),
        (None, Some(d)) => Limit::Duration(d),
        (None, None) => Limit::Unbounded,
    };
    let clock = if args.virtual_clock || limit != Limit::Unbounded {
        ClockMode::Virtual
    } else {
        ClockMode::RealTime
    };
    if let Some(rt) = crate::realtime_run::settings(args, None, clock == ClockMode::RealTime)? {
        // This thread runs the scans.
        crate::realtime_run::enter_here(&rt)?;
    }
    let stop = Arc::new(AtomicBool::new(false));
    if limit == Limit::Unbounded {
        stop_on_signals(&stop);
    }
    let config = batch_config(
        cycle_time,
        clock,
        Box::new(SystemClock::new()),
        stop,
        retain.as_ref(),
        &safe,
    );
    let parts = Parts {
        exec: Box::new(engine),
        sim: None,
        observer: trace
            .as_ref()
            .map(|t| Box::new(Watching(Rc::clone(t))) as Box<dyn ScanObserver>),
        exchange: None,
    };
    let end = automat_session::run_here(Arc::new(program), config, parts, limit);
    let trace = trace.and_then(|t| Rc::try_unwrap(t).ok().map(RefCell::into_inner));
    finish(args, end, trace, &prints, retain.as_ref(), &safe)
}

/// The session of a run to a limit (`--cycles`, `--duration`, a
/// scenario): the same as a served PLC (forces, RETAIN keeping, the safe
/// state), run on the calling thread, which entered any real-time mode
/// itself.
pub(crate) fn batch_config(
    cycle_time_ns: i64,
    clock: ClockMode,
    monotonic: Box<dyn automat_runtime::Monotonic + Send>,
    stop: Arc<AtomicBool>,
    retain: Option<&RetainCfg>,
    safe: &SafeState,
) -> Config {
    Config {
        cycle_time_ns,
        clock,
        monotonic,
        running: true,
        stop,
        retain: retain.map(RetainCfg::file),
        safe: Some(safe.clone()),
        realtime: None,
        wait_after_fault: false,
    }
}

/// After a batch run: RETAIN saves reported, trace flushed, values
/// printed, fault reported.
fn finish(
    args: &RunArgs,
    mut end: Final,
    trace: Option<Trace<BufWriter<File>>>,
    prints: &[(String, Locator)],
    retain: Option<&RetainCfg>,
    safe: &SafeState,
) -> Result<Outcome, Outcome> {
    let saved = end.retain.take().is_none_or(|saves| {
        retain_run::report(
            saves.last,
            saves.failures,
            saves.last_error.as_deref(),
            retain,
        )
    });
    let mut outcome = if saved {
        Outcome::Ok
    } else {
        Outcome::BadInput
    };
    if let (Some(t), Some(path)) = (trace, &args.trace_file) {
        if let Err(e) = t.finish() {
            eprintln!("error: {}: {e}", path.display());
            outcome = Outcome::BadInput;
        }
    }
    print_values(&end.image, prints);
    if args.stats {
        eprintln!("{}", end.stats);
    }
    if let Some(f) = &end.fault {
        eprintln!("error: runtime fault: {f}");
    }
    safe_note_end(end.end, safe);
    match end.end {
        End::Fault => Ok(Outcome::Fault),
        End::Observer => {
            let shown = args
                .trace_file
                .as_ref()
                .map_or(String::new(), |p| format!("{}: ", p.display()));
            eprintln!("error: {shown}{}", end.error.unwrap_or_default());
            Ok(Outcome::BadInput)
        }
        End::Error => {
            eprintln!("error: {}", end.error.unwrap_or_default());
            Err(Outcome::BadInput)
        }
        End::Limit | End::Stopped => Ok(outcome),
    }
}

/// The note after a session that ended in the safe state.
pub(crate) fn safe_note_end(end: End, safe: &SafeState) {
    match end {
        End::Fault => safe_note_of(true, safe),
        End::Stopped => safe_note_of(false, safe),
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::split_trace;

    #[test]
    fn trace_lists_split_outside_brackets() {
        assert_eq!(
            split_trace(&["a, arr[1, 2].x,b".into(), "c".into()]),
            ["a", "arr[1, 2].x", "b", "c"]
        );
    }
}
