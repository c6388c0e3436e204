//! `automat run PROJECT_FOLDER`: the project's program against its plant
//! (a project without `[plant]`, and plain sources run with --scenario, run
//! against no plant: the scenario drives the program's own variables).
//!
//! With --scenario its timed actions and reactions drive the run and its
//! expectations are judged as `automat test` does (failures on stderr,
//! exit 1). With --cycles, --duration or --scenario the run is in virtual time;
//! otherwise in real time (`--speed N`: N× faster), with a status view and
//! typed commands (see [`crate::live`]). `--print` and `--trace` take
//! variable paths, signal names of the model and `plant.<quantity>`.

use crate::cmd_run::{safe_note_end, stop_on_signals, RunArgs};
use crate::live::{Live, ScaledClock};
use crate::retain_run::{self, RetainCfg};
use crate::Outcome;
use automat_base::{render, FileId, SourceMap, Span};
use automat_ir::Program;
use automat_plant::Plant;
use automat_project::{bind, build, Project, Sim};
use automat_runtime::trace::{csv_cell, Column};
use automat_runtime::{ClockMode, Executor, Limit, ScanObserver};
use automat_scenario::ast::Name;
use automat_scenario::check::{Ref, Scope};
use automat_scenario::{Judge, NoPlant, Prepared};
use automat_session::{End, Parts, Watching};
use std::cell::RefCell;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;
use std::rc::Rc;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

fn fail(map: &SourceMap, diags: &[automat_base::Diagnostic]) -> Outcome {
    eprint!("{}", render::render_report(map, diags));
    Outcome::ProgramErrors
}

/// Resolves `--print`/`--trace` names (split like `--trace`).
fn refs(scope: &Scope, names: &[String], option: &str) -> Result<Vec<Ref>, Outcome> {
    names
        .iter()
        .map(|n| {
            let name = Name {
                text: n.trim().to_string(),
                span: Span::new(FileId(0), 0, 0),
            };
            scope.reference(&name).map_err(|d| {
                eprintln!("error: {option} {n}: {}", d.message);
                Outcome::BadInput
            })
        })
        .collect()
}

/// One `--trace` column of a project run: a variable, signal or plant
/// quantity, or `steps(OWNER)`, the active steps of a chart.
enum TraceCol {
    Ref(Ref),
    Steps(Column),
}

/// Resolves `--trace` names: `steps(OWNER)` first, then as `refs` does.
fn trace_cols(
    scope: &Scope,
    program: &Program,
    names: &[String],
) -> Result<Vec<TraceCol>, Outcome> {
    let mut out = Vec::with_capacity(names.len());
    for n in names {
        match automat_project::steps::column(program, n) {
            Some(Ok(chart)) => out.push(TraceCol::Steps(chart.trace_column())),
            Some(Err(e)) => {
                eprintln!("error: --trace {n}: {e}");
                return Err(Outcome::BadInput);
            }
            None => out.extend(
                refs(scope, std::slice::from_ref(n), "--trace")?
                    .into_iter()
                    .map(TraceCol::Ref),
            ),
        }
    }
    Ok(out)
}

/// Writes one CSV row per scan, judges the scenario, and drives the live
/// view.
struct Observer {
    sim: Rc<RefCell<Sim>>,
    trace: Option<(Vec<TraceCol>, BufWriter<File>)>,
    live: Option<Live>,
    judge: Option<Judge>,
}

impl ScanObserver for Observer {
    fn after_scan(&mut self, now: i64, image: &[u8]) -> Result<(), String> {
        if let Some(j) = &mut self.judge {
            j.after_scan(now, image, &self.sim);
        }
        if let Some((cols, out)) = &mut self.trace {
            let sim = self.sim.borrow();
            let mut line = automat_iec::format::format_duration(now, false);
            for c in cols.iter() {
                line.push(',');
                let cell = match c {
                    TraceCol::Ref(r) => r.show(image, &sim),
                    TraceCol::Steps(s) => s.cell(image),
                };
                line.push_str(&csv_cell(&cell));
            }
            line.push('\n');
            out.write_all(line.as_bytes()).map_err(|e| e.to_string())?;
        }
        if let Some(live) = &mut self.live {
            live.after_scan(now, image, Some(&self.sim));
        }
        Ok(())
    }

    fn stats(&mut self, stats: &automat_runtime::stats::Stats) {
        if let Some(live) = &mut self.live {
            live.stats(stats);
        }
    }
}

struct Loaded {
    map: SourceMap,
    project: Project,
    program: Program,
    plant: Box<dyn Plant>,
}

/// The project file read and its program compiled with the command line's
/// `--program`, `--lib` and `--watchdog`, `[tasks]` applied and `[modbus]`
/// checked (its errors are the project's in every run, though only a
/// real-time run opens a socket): what every run of a project starts from.
pub(crate) fn compile_project(args: &RunArgs, toml: &Path) -> Result<Compiled, Outcome> {
    let mut map = SourceMap::new();
    let project = automat_project::load(toml, &mut map).map_err(|d| fail(&map, &d))?;
    for w in &project.warnings {
        eprintln!("{w}");
    }
    let program_name = args.program.clone().or(project.program.clone());
    let mut libraries = project.libraries.clone();
    libraries.extend(args.libs.iter().cloned());
    let mut program = match build::compile(&project.sources, program_name, &libraries) {
        Ok((p, warnings)) => {
            eprint!("{warnings}");
            p
        }
        Err(e) => {
            eprint!("{}", e.text);
            return Err(if e.bad_input {
                Outcome::BadInput
            } else {
                Outcome::ProgramErrors
            });
        }
    };
    automat_project::tasks::apply(&project.tasks, &mut program).map_err(|d| fail(&map, &d))?;
    // `[modbus]` and `[opcua]` are checked in every run (their errors are
    // the project's), though a simulation opens no socket.
    let modbus =
        automat_fieldbus::config::load(&map.get(project.file).text, project.file, &program)
            .map_err(|d| fail(&map, &d))?;
    #[cfg(feature = "opcua")]
    automat_opcua::config::load(&map.get(project.file).text, project.file)
        .map_err(|d| fail(&map, &d))?;
    crate::engines::default_watchdog(&mut program, args.watchdog);
    Ok(Compiled {
        map,
        project,
        program,
        modbus,
    })
}

/// A project ready to run ([`compile_project`]).
pub(crate) struct Compiled {
    pub map: SourceMap,
    pub project: Project,
    pub program: Program,
    /// `[modbus]`, checked against the program.
    pub modbus: automat_fieldbus::config::Config,
}

fn load(args: &RunArgs, toml: &Path) -> Result<Loaded, Outcome> {
    let Compiled {
        map,
        project,
        program,
        ..
    } = compile_project(args, toml)?;
    // Without [plant] the program runs against no plant.
    let plant = project.new_plant().map_err(|d| fail(&map, &d))?;
    Ok(Loaded {
        map,
        project,
        program,
        plant: plant.unwrap_or_else(|| Box::new(NoPlant)),
    })
}

pub fn run(args: &RunArgs, toml: &Path) -> Result<Outcome, Outcome> {
    let loaded = load(args, toml)?;
    run_loaded(args, loaded, true)
}

/// `automat run FILE.st ... --scenario S.scn`: plain sources (no
/// automat.toml) against no plant, the scenario driving and checking the
/// program's variables.
pub fn run_sources(args: &RunArgs) -> Result<Outcome, Outcome> {
    if args.cycle_time.is_some_and(|c| c <= 0) {
        eprintln!("error: --cycle-time must be longer than 0");
        return Err(Outcome::BadInput);
    }
    let mut program = crate::cmd_run::compile(args)?;
    crate::engines::default_watchdog(&mut program, args.watchdog);
    let dir = args
        .paths
        .first()
        .and_then(|p| p.parent())
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let project = Project {
        dir,
        file: FileId(0),
        name: String::new(),
        description: String::new(),
        sources: args.paths.clone(),
        program: args.program.clone(),
        cycle_time_ns: 10_000_000,
        libraries: args.libs.clone(),
        plant: None,
        retain: automat_project::RetainSpec::default(),
        safe_state: Vec::new(),
        users: Vec::new(),
        tasks: Vec::new(),
        runtime: automat_project::RuntimeSpec::default(),
        warnings: Vec::new(),
    };
    let loaded = Loaded {
        map: SourceMap::new(),
        project,
        program,
        plant: Box::new(NoPlant),
    };
    run_loaded(args, loaded, false)
}

fn run_loaded(args: &RunArgs, loaded: Loaded, from_project: bool) -> Result<Outcome, Outcome> {
    let Loaded {
        mut map,
        project,
        program,
        plant,
    } = loaded;
    let (bindings, seed) = match &project.plant {
        Some(spec) => {
            let (bindings, diags) = bind(spec, plant.as_ref(), &program);
            if !diags.is_empty() {
                eprint!("{}", render::render_report(&map, &diags));
            }
            (bindings.ok_or(Outcome::ProgramErrors)?, spec.seed)
        }
        None => (Vec::new(), 1),
    };
    let scope = Scope {
        program: &program,
        plant: plant.as_ref(),
        bindings: &bindings,
    };
    let safe = automat_project::safe::build(
        &project,
        &program,
        project
            .plant
            .is_some()
            .then_some((plant.as_ref(), bindings.as_slice())),
    )
    .map_err(|d| fail(&map, &d))?;
    let prints = refs(&scope, &args.print, "--print")?;
    let traced = trace_cols(&scope, &program, &crate::cmd_run::split_trace(&args.trace))?;
    let mut actions = Vec::new();
    let mut scenario_ns = None;
    let mut judge = None;
    let mut seed = seed;
    let mut scenario_shown = String::new();
    if let Some(path) = &args.scenario {
        let text = std::fs::read_to_string(path).map_err(|e| {
            eprintln!("error: {}: {e}", path.display());
            Outcome::BadInput
        })?;
        scenario_shown = path.display().to_string();
        let file = map.add(scenario_shown.clone(), text.clone());
        let scn = automat_scenario::parse(&text, file, "scenario").map_err(|d| fail(&map, &d))?;
        let Prepared {
            actions: a,
            judge: j,
        } = automat_scenario::prepare(&scope, &scn).map_err(|d| fail(&map, &d))?;
        let mut j = j;
        j.set_cycle(project.cycle_time_ns);
        actions = a;
        judge = Some(j);
        // The scenario's seed, as `automat test` uses it.
        seed = scn.seed.unwrap_or(seed);
        scenario_ns = Some(scn.duration_ns);
    }
    let mut sim = Sim::new(plant, bindings, seed);
    for (at, a) in actions {
        sim.schedule(at, a);
    }
    let sim = Rc::new(RefCell::new(sim));

    let limit = match (args.cycles, args.duration, scenario_ns) {
        (Some(n), _, _) => Limit::Cycles(n),
        (None, Some(d), _) | (None, None, Some(d)) => Limit::Duration(d),
        (None, None, None) => Limit::Unbounded,
    };
    let clock = if args.virtual_clock || limit != Limit::Unbounded {
        ClockMode::Virtual
    } else {
        ClockMode::RealTime
    };
    if !(args.speed.is_finite() && args.speed > 0.0) {
        eprintln!("error: --speed must be a number greater than 0");
        return Err(Outcome::BadInput);
    }
    if let Some(rt) =
        crate::realtime_run::settings(args, Some(&project), clock == ClockMode::RealTime)?
    {
        crate::realtime_run::enter_here(&rt)?;
    }
    let stop = Arc::new(AtomicBool::new(false));
    if limit == Limit::Unbounded {
        stop_on_signals(&stop);
    }
    let trace = match &args.trace_file {
        Some(path) => {
            let mut w = BufWriter::new(File::create(path).map_err(|e| {
                eprintln!("error: {}: {e}", path.display());
                Outcome::BadInput
            })?);
            let mut header = String::from("time");
            for n in crate::cmd_run::split_trace(&args.trace) {
                header.push(',');
                header.push_str(&csv_cell(&n));
            }
            writeln!(w, "{header}").map_err(|e| {
                eprintln!("error: {}: {e}", path.display());
                Outcome::BadInput
            })?;
            Some((traced, w))
        }
        None => None,
    };
    // The RETAIN path is checked before anything starts (the live view included).
    let retain = RetainCfg::of(args, from_project.then_some(&project.retain));
    let mut engine = crate::engines::build(program.clone(), args.engine);
    engine.set_budget(args.max_instructions);
    retain_run::start(&mut engine, retain.as_ref(), args.cold)?;
    let live = (clock == ClockMode::RealTime)
        .then(|| Live::start(&program, Rc::clone(&sim), Arc::clone(&stop), args.speed));
    let mut observer = Observer {
        sim: Rc::clone(&sim),
        trace,
        live,
        judge,
    };
    if let Some(j) = &mut observer.judge {
        j.start(engine.image(), &sim.borrow());
    }
    let observer = Rc::new(RefCell::new(observer));
    let cycle_time_ns = args.cycle_time.unwrap_or(project.cycle_time_ns);
    let config = crate::cmd_run::batch_config(
        cycle_time_ns,
        clock,
        Box::new(ScaledClock::new(args.speed)),
        Arc::clone(&stop),
        retain.as_ref(),
        &safe,
    );
    let parts = Parts {
        exec: Box::new(engine),
        sim: Some(Rc::clone(&sim)),
        observer: Some(Box::new(Watching(Rc::clone(&observer)))),
        exchange: None,
    };
    let mut end = automat_session::run_here(Arc::new(program.clone()), config, parts, limit);
    let Some(mut observer) = Rc::try_unwrap(observer).ok().map(RefCell::into_inner) else {
        eprintln!("error: the run's observer is still in use");
        return Err(Outcome::BadInput);
    };
    let saved = end.retain.take().is_none_or(|saves| {
        retain_run::report(
            saves.last,
            saves.failures,
            saves.last_error.as_deref(),
            retain.as_ref(),
        )
    });
    if matches!(end.end, End::Fault | End::Stopped) {
        // The PLC is in its safe state and the session told the plant so.
        // The plant is a physical machine: in virtual time it runs on to the
        // run's end (--duration, the scenario's duration) in the safe state,
        // so `--print plant.<quantity>` shows where it came to rest. The
        // PLC's image stays as the safe state left it.
        if let (Limit::Duration(end_ns), ClockMode::Virtual) = (&limit, clock) {
            let mut image = end.image.clone();
            sim.borrow_mut().sync(*end_ns, &mut image);
        }
    }
    let mut outcome = if saved {
        Outcome::Ok
    } else {
        Outcome::BadInput
    };
    if let Some(j) = observer.judge.take() {
        // A run stopped by a fault or a signal keeps the verdicts reached;
        // what was still open is not judged.
        // A run cut short of the scenario's duration (--cycles, a shorter
        // --duration) judges only what was decided before its end.
        let scn_ns = scenario_ns.unwrap_or(0);
        let covered = match limit {
            Limit::Duration(d) => d >= scn_ns,
            Limit::Cycles(n) => {
                i64::try_from(n).map_or(true, |n| n.saturating_mul(cycle_time_ns) >= scn_ns)
            }
            Limit::Unbounded => true,
        };
        let complete = covered && end.end == End::Limit;
        let open = j.open();
        let failures = if complete {
            j.finish(&end.image, &sim.borrow())
        } else {
            j.failures()
        };
        if !covered && open > 0 {
            eprintln!(
                "scenario {scenario_shown}: the run ends before the scenario's duration ({}): {open} expectation{} not judged",
                automat_iec::format::format_duration(scn_ns, false),
                if open == 1 { "" } else { "s" }
            );
        }
        if failures.is_empty() {
            if complete {
                eprintln!("scenario {scenario_shown}: every expectation held");
            }
        } else {
            eprintln!(
                "scenario {scenario_shown}: {} expectation{} failed",
                failures.len(),
                if failures.len() == 1 { "" } else { "s" }
            );
            eprint!("{}", automat_scenario::describe(&scenario_shown, &failures));
            if matches!(outcome, Outcome::Ok) {
                outcome = Outcome::ProgramErrors;
            }
        }
    }
    if let Some((_, mut w)) = observer.trace.take() {
        if let Err(e) = w.flush() {
            eprintln!("error: trace: {e}");
            outcome = Outcome::BadInput;
        }
    }
    {
        let s = sim.borrow();
        for (name, r) in args.print.iter().zip(&prints) {
            println!("{} = {}", name.trim(), r.show(&end.image, &s));
        }
        for (at, e) in &s.errors {
            eprintln!(
                "warning: plant command at {}: {e}",
                automat_iec::format::format_duration(*at, false)
            );
        }
    }
    if args.stats {
        eprintln!("{}", end.stats);
    }
    if let Some(f) = &end.fault {
        eprintln!("error: runtime fault: {f}");
    }
    safe_note_end(end.end, &safe);
    match end.end {
        End::Fault => Ok(Outcome::Fault),
        End::Observer | End::Error => {
            eprintln!("error: {}", end.error.unwrap_or_default());
            Ok(Outcome::BadInput)
        }
        End::Limit | End::Stopped => Ok(outcome),
    }
}
