//! The online run: `automat run PATH...` in real time (until Ctrl-C, with
//! the live view) or with `--listen [ADDR:]PORT` (served by the network
//! API, `automat-online`): the PLC as a session (`automat-session`), which
//! the live view's console and the server both drive. Source files run
//! alone; a project folder runs with its plant and its `[users]`.
//!
//! Options that do not apply are refused, never ignored: with `--listen`,
//! `--cycles`, `--duration`, `--scenario` and `--trace` (the run is driven
//! online). `--speed` is honoured for source files too.

use crate::cmd_run::RunArgs;
use crate::live::{Console, Live, ScaledClock};
use crate::Outcome;
use automat_base::{render, SourceMap};
use automat_ir::Program;
use automat_online::{Options, Role, User};
use automat_project::{bind, build, Sim};
use automat_runtime::retain::{self, Loaded};
use automat_runtime::ClockMode;
use automat_runtime::ScanObserver;
use automat_session::{Config, Parts, Session, State};
use std::cell::RefCell;
use std::io::IsTerminal;
use std::path::Path;
use std::rc::Rc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

/// Whether `automat run` goes online: with `--listen`, or a real-time run
/// (no `--cycles`, `--duration`, `--scenario`, `--virtual-clock`) without
/// `--trace`.
pub fn wanted(args: &RunArgs) -> bool {
    args.listen.is_some()
        || (args.cycles.is_none()
            && args.duration.is_none()
            && args.scenario.is_none()
            && !args.virtual_clock
            && args.trace.is_empty())
}

/// The live view as the session's observer (on the scan thread).
struct View {
    live: Live,
    sim: Option<Rc<RefCell<Sim>>>,
}

impl ScanObserver for View {
    fn after_scan(&mut self, now: i64, image: &[u8]) -> Result<(), String> {
        self.live.after_scan(now, image, self.sim.as_ref());
        Ok(())
    }
    fn stats(&mut self, stats: &automat_runtime::stats::Stats) {
        self.live.stats(stats);
    }
}

fn bad(msg: impl std::fmt::Display) -> Outcome {
    eprintln!("error: {msg}");
    Outcome::BadInput
}

/// The program, its cyclic period and the users of a project folder.
struct LoadedRun {
    program: Program,
    cycle_ns: i64,
    project: Option<automat_project::Project>,
}

fn load(args: &RunArgs) -> Result<LoadedRun, Outcome> {
    if let [p] = args.paths.as_slice() {
        if let Some(toml) = automat_project::project_file(p) {
            return load_project(args, &toml);
        }
    }
    Ok(LoadedRun {
        program: crate::cmd_run::compile(args)?,
        cycle_ns: args.cycle_time.unwrap_or(10_000_000),
        project: None,
    })
}

fn load_project(args: &RunArgs, toml: &Path) -> Result<LoadedRun, Outcome> {
    let mut map = SourceMap::new();
    let project = automat_project::load(toml, &mut map).map_err(|d| {
        eprint!("{}", render::render_report(&map, &d));
        Outcome::ProgramErrors
    })?;
    let mut libraries = project.libraries.clone();
    libraries.extend(args.libs.iter().cloned());
    let name = args.program.clone().or(project.program.clone());
    let program = match build::compile(&project.sources, name, &libraries) {
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
    // The bindings are checked here, where their diagnostics can be shown.
    if let (Some(spec), Ok(Some(plant))) = (&project.plant, project.new_plant()) {
        let (bindings, diags) = bind(spec, plant.as_ref(), &program);
        if !diags.is_empty() {
            eprint!("{}", render::render_report(&map, &diags));
        }
        if bindings.is_none() {
            return Err(Outcome::ProgramErrors);
        }
    }
    Ok(LoadedRun {
        cycle_ns: args.cycle_time.unwrap_or(project.cycle_time_ns),
        program,
        project: Some(project),
    })
}

fn users(project: Option<&automat_project::Project>) -> Vec<User> {
    project
        .map(|p| {
            p.users
                .iter()
                .filter_map(|u| {
                    Some(User {
                        name: u.name.clone(),
                        role: Role::parse(&u.role)?,
                        hash: u.password_hash.clone(),
                    })
                })
                .collect()
        })
        .unwrap_or_default()
}

pub fn run(args: &RunArgs) -> Result<Outcome, Outcome> {
    for (given, name) in [
        (args.cycles.is_some(), "--cycles"),
        (args.duration.is_some(), "--duration"),
        (args.scenario.is_some(), "--scenario"),
        (!args.trace.is_empty(), "--trace"),
    ] {
        if given && args.listen.is_some() {
            return Err(bad(format!(
                "{name} does not apply with --listen: the run goes on until Ctrl-C (with --virtual-clock, scans run on `step` commands)"
            )));
        }
    }
    if !(args.speed.is_finite() && args.speed > 0.0) {
        return Err(bad("--speed must be a number greater than 0"));
    }
    let addr = match &args.listen {
        Some(l) => {
            Some(automat_online::listen::parse_addr(l).map_err(|e| bad(format!("--listen: {e}")))?)
        }
        None => None,
    };
    let loaded = load(args)?;
    if loaded.cycle_ns <= 0 {
        return Err(bad("--cycle-time must be longer than 0"));
    }
    let prints = crate::cmd_run::places(&loaded.program, &args.print, "--print")?;
    let token = match &args.token_file {
        Some(path) => Some(automat_online::token_file(path).map_err(bad)?),
        None => None,
    };
    let opts = addr.map(|addr| {
        let mut opts = Options::new(addr);
        opts.token = token;
        opts.users = users(loaded.project.as_ref());
        opts.insecure = args.insecure;
        opts.tls = args.tls_cert.clone().zip(args.tls_key.clone());
        opts
    });
    // The live view, unless a server runs without a terminal (a service);
    // for source files only on a terminal, so scripts reading `--print`
    // get their values alone (a project's view prints a line a second, as
    // it always did).
    let view = (args.listen.is_none() || std::io::stdin().is_terminal())
        && (loaded.project.is_some() || std::io::stdout().is_terminal());
    let console = Arc::new(Mutex::new(Console {
        watch: crate::live::default_watch(&loaded.program),
        ..Console::default()
    }));
    let (to_view, view_commands) = std::sync::mpsc::channel::<String>();
    let has_plant = loaded.project.as_ref().is_some_and(|p| p.plant.is_some());

    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    if let Err(e) = ctrlc::set_handler(move || flag.store(true, Ordering::Relaxed)) {
        eprintln!("warning: cannot handle Ctrl-C ({e}); stop the PLC with a signal");
    }
    let virtual_clock = args.virtual_clock;
    let config = Config {
        cycle_time_ns: loaded.cycle_ns,
        clock: if virtual_clock {
            ClockMode::Virtual
        } else {
            ClockMode::RealTime
        },
        monotonic: Box::new(ScaledClock::new(args.speed)),
        running: !virtual_clock,
        stop: Arc::clone(&stop),
    };
    let program = Arc::new(loaded.program);
    let for_build = (*program).clone();
    let engine_kind = args.engine;
    let retain_file = (!args.cold).then(|| args.retain.clone()).flatten();
    let project = loaded.project;
    let view_console = Arc::clone(&console);
    let view_stop = Arc::clone(&stop);
    let speed = args.speed;
    let build = Box::new(move || -> Result<Parts, String> {
        let mut engine = crate::engines::build(for_build.clone(), engine_kind);
        if let Some(path) = &retain_file {
            let p = automat_runtime::Executor::program(&engine).clone();
            match retain::load(&p, path, automat_runtime::Executor::image_mut(&mut engine)) {
                Loaded::Warm | Loaded::NoFile => {}
                Loaded::Cold(why) => eprintln!("warning: {}: {why}; cold start", path.display()),
            }
        }
        let sim = match project
            .as_ref()
            .and_then(|p| p.plant.clone().map(|s| (p, s)))
        {
            Some((p, spec)) => {
                let plant = p
                    .new_plant()
                    .map_err(|_| "the plant cannot be made".to_string())?
                    .ok_or("the project has no plant")?;
                let (bindings, _) = bind(&spec, plant.as_ref(), &for_build);
                let bindings = bindings.ok_or("the plant's bindings do not check")?;
                Some(Rc::new(RefCell::new(Sim::new(plant, bindings, spec.seed))))
            }
            None => None,
        };
        let observer: Option<Box<dyn ScanObserver>> = view.then(|| {
            let live = Live::new(&for_build, view_commands, view_console, view_stop, speed);
            Box::new(View {
                live,
                sim: sim.clone(),
            }) as Box<dyn ScanObserver>
        });
        Ok(Parts {
            exec: Box::new(engine),
            sim,
            observer,
        })
    });
    let session = Arc::new(Session::start(Arc::clone(&program), config, build).map_err(bad)?);
    let server = match opts.map(|o| automat_online::start(Arc::clone(&session), o)) {
        None => None,
        Some(Ok(s)) => Some(s),
        Some(Err(e)) => {
            let _ = session.shutdown();
            return Err(bad(e));
        }
    };
    if let Some(server) = &server {
        let ws = if server.scheme == "https" {
            "wss"
        } else {
            "ws"
        };
        eprintln!(
            "automat: PLC API on {}://{}/api/v1/ (WebSocket {ws}://{}/api/v1/watch); Ctrl-C stops",
            server.scheme, server.addr, server.addr
        );
    }
    if view {
        crate::live::console(
            Arc::clone(&session),
            console,
            to_view,
            Arc::clone(&stop),
            has_plant,
        );
    }
    let end = session.join().map_err(bad)?;
    drop(server);
    let mut outcome = Outcome::Ok;
    if let Some(path) = &args.retain {
        if let Err(e) = retain::save(&program, path, &end.image) {
            eprintln!("error: {e}");
            outcome = Outcome::BadInput;
        }
    }
    for (name, place) in &prints {
        println!(
            "{name} = {}",
            automat_runtime::value::format(&end.image, place)
        );
    }
    if let Some(e) = &end.error {
        return Err(bad(e));
    }
    if let State::Fault { message, site } = &end.snapshot.state {
        eprintln!("error: runtime fault: {site}: {message}");
        eprintln!("note: the PLC stopped; every output was set to 0/FALSE");
        return Ok(Outcome::Fault);
    }
    Ok(outcome)
}
