//! The online run: `automat run PATH...` in real time (until Ctrl-C, with
//! the live view) or with `--listen [ADDR:]PORT` (served by the network
//! API, `automat-online`): the PLC as a session (`automat-session`), which
//! the live view's console and the server both drive. Source files run
//! alone; a project folder runs with its plant and its `[users]`.
//!
//! The rules of every real-time run hold (the session applies them): the
//! RETAIN path checked before the start (exit 2 unless optional), a warm
//! start, saves from end-of-scan snapshots every `--retain-every` and at
//! the end (also after a fault), the watchdog of every task, the safe state
//! (the project's, with its plant's actuators and `[safe_state]`) on a
//! fault and on a stop, and Ctrl-C/SIGTERM/SIGHUP as the scan loop's stop
//! flag (a scan still running a second later is stopped as a fault).
//!
//! Options that do not apply are refused, never ignored: with `--listen`,
//! `--cycles`, `--duration`, `--scenario` and `--trace` (the run is driven
//! online). `--speed` is honoured for source files too.

use crate::cmd_run::{safe_note_of, stop_on_signals, RunArgs};
use crate::live::{Console, Live, ScaledClock};
use crate::retain_run::{self, RetainCfg};
use crate::Outcome;
use automat_base::{render, SourceMap};
use automat_ir::Program;
use automat_online::{Options, Role, User};
use automat_project::{bind, Sim};
use automat_runtime::ScanObserver;
use automat_runtime::{ClockMode, SafeState};
use automat_session::{Config, Parts, Session};
use std::cell::RefCell;
use std::io::IsTerminal;
use std::path::Path;
use std::rc::Rc;
use std::sync::atomic::AtomicBool;
use std::sync::{Arc, Mutex};

/// Whether `automat run` goes online: with `--listen`, or a real-time run
/// (no `--cycles`, `--duration`, `--scenario`, `--virtual-clock`) without
/// `--trace`.
pub fn wanted(args: &RunArgs) -> bool {
    args.listen.is_some()
        || args.modbus_server.is_some()
        || args.opcua.is_some()
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

/// The program, its cyclic period, its safe state and the project folder.
struct LoadedRun {
    program: Program,
    cycle_ns: i64,
    safe: SafeState,
    project: Option<automat_project::Project>,
    /// `[modbus]` of the project, checked against the program.
    modbus: automat_fieldbus::config::Config,
    /// `[opcua]` of the project.
    opcua: Option<OpcuaCfg>,
}

/// `[opcua]` with its certificate folder made absolute.
#[derive(Clone, Debug)]
#[cfg_attr(not(feature = "opcua"), allow(dead_code))]
struct OpcuaCfg {
    addr: std::net::SocketAddr,
    pki_dir: std::path::PathBuf,
    trust_client_certs: bool,
}

fn load(args: &RunArgs) -> Result<LoadedRun, Outcome> {
    if let [p] = args.paths.as_slice() {
        if let Some(toml) = automat_project::project_file(p) {
            return load_project(args, &toml);
        }
    }
    let mut program = crate::cmd_run::compile(args)?;
    crate::engines::default_watchdog(&mut program, args.watchdog);
    Ok(LoadedRun {
        safe: SafeState::of_program(&program),
        program,
        cycle_ns: args.cycle_time.unwrap_or(10_000_000),
        project: None,
        modbus: Default::default(),
        opcua: None,
    })
}

fn load_project(args: &RunArgs, toml: &Path) -> Result<LoadedRun, Outcome> {
    let crate::project_run::Compiled {
        map,
        project,
        program,
        modbus,
    } = crate::project_run::compile_project(args, toml)?;
    let fail = |d: &[automat_base::Diagnostic]| {
        eprint!("{}", render::render_report(&map, d));
        Outcome::ProgramErrors
    };
    // The bindings are checked here, where their diagnostics can be shown;
    // the safe state includes every variable an actuator is bound to.
    let plant = project.new_plant().map_err(|d| fail(&d))?;
    let safe = match (&project.plant, plant) {
        (Some(spec), Some(plant)) => {
            let (bindings, diags) = bind(spec, plant.as_ref(), &program);
            if !diags.is_empty() {
                eprint!("{}", render::render_report(&map, &diags));
            }
            let bindings = bindings.ok_or(Outcome::ProgramErrors)?;
            automat_project::safe::build(
                &project,
                &program,
                Some((plant.as_ref(), bindings.as_slice())),
            )
        }
        _ => automat_project::safe::build(&project, &program, None),
    }
    .map_err(|d| fail(&d))?;
    let opcua = opcua_config(&project, &map).map_err(|d| fail(&d))?;
    Ok(LoadedRun {
        safe,
        cycle_ns: args.cycle_time.unwrap_or(project.cycle_time_ns),
        program,
        project: Some(project),
        modbus,
        opcua,
    })
}

/// `[opcua]` of the project; the certificates default to
/// `.automat/opcua-pki` in the project folder.
fn opcua_config(
    project: &automat_project::Project,
    map: &SourceMap,
) -> Result<Option<OpcuaCfg>, Vec<automat_base::Diagnostic>> {
    #[cfg(feature = "opcua")]
    {
        let dir = project.dir.clone();
        Ok(
            automat_opcua::config::load(&map.get(project.file).text, project.file)?.map(|c| {
                OpcuaCfg {
                    addr: c.addr,
                    pki_dir: dir.join(
                        c.pki_dir
                            .unwrap_or_else(|| std::path::PathBuf::from(".automat/opcua-pki")),
                    ),
                    trust_client_certs: c.trust_client_certs,
                }
            }),
        )
    }
    #[cfg(not(feature = "opcua"))]
    {
        let _ = (project, map);
        Ok(None)
    }
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
        if given && args.opcua.is_some() {
            return Err(bad(format!(
                "{name} does not apply with --opcua: the run goes on in real time until Ctrl-C"
            )));
        }
        if given && args.modbus_server.is_some() {
            return Err(bad(format!(
                "{name} does not apply with --modbus-server: the run goes on in real time until Ctrl-C"
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
    let modbus_addr = match &args.modbus_server {
        Some(a) => Some(
            automat_fieldbus::server::parse_addr(a)
                .map_err(|e| bad(format!("--modbus-server: {e}")))?,
        ),
        None => None,
    };
    let opcua_addr = match &args.opcua {
        #[cfg(feature = "opcua")]
        Some(a) => {
            Some(automat_opcua::config::parse_addr(a).map_err(|e| bad(format!("--opcua: {e}")))?)
        }
        #[cfg(not(feature = "opcua"))]
        Some(_) => {
            return Err(bad(
                "--opcua: this automat was built without OPC UA (cargo feature `opcua`)",
            ))
        }
        None => None,
    };
    let mut loaded = load(args)?;
    let opcua = match (opcua_addr, loaded.opcua.take()) {
        (Some(addr), Some(mut c)) => {
            c.addr = addr;
            Some(c)
        }
        (Some(addr), None) => Some(OpcuaCfg {
            addr,
            pki_dir: loaded
                .project
                .as_ref()
                .map_or_else(|| std::path::PathBuf::from("."), |p| p.dir.clone())
                .join(".automat/opcua-pki"),
            trust_client_certs: false,
        }),
        (None, c) => c,
    };
    if args.virtual_clock && opcua.is_some() {
        return Err(bad(
            "an OPC UA server needs the real-time clock: --virtual-clock does not apply",
        ));
    }
    if args.virtual_clock
        && (modbus_addr.is_some()
            || loaded.modbus.server.is_some()
            || loaded.modbus.rtu_server.is_some())
    {
        return Err(bad(
            "a Modbus server needs the real-time clock: --virtual-clock does not apply",
        ));
    }
    let modbus_server = match (modbus_addr, loaded.modbus.server.take()) {
        (Some(addr), Some(mut s)) => {
            s.options.addr = addr;
            Some(s)
        }
        (Some(addr), None) => Some(automat_fieldbus::config::ServerConfig {
            options: automat_fieldbus::server::Options::new(addr),
            map: automat_fieldbus::map::Map::default_of(&loaded.program),
        }),
        (None, s) => s,
    };
    // `--modbus-server` may move a checked server to another address.
    if let Some(why) = modbus_server
        .as_ref()
        .and_then(|s| s.options.open_to_writes(s.map.read_only))
    {
        return Err(bad(format!(
            "--modbus-server: {why}: list the clients in `[modbus.server] allow = [...]` or set `read_only = true` in automat.toml"
        )));
    }
    let modbus_clients = std::mem::take(&mut loaded.modbus.clients);
    let modbus_rtu = loaded.modbus.rtu_server.take();
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
        opts.project = loaded.project.as_ref().map(|p| p.name.clone());
        opts.cycle_time_ns = loaded.cycle_ns;
        // The charts as the compiler reads them, for the HMI.
        opts.charts = match loaded.project.as_ref() {
            Some(p) => {
                let mut libs = p.libraries.clone();
                libs.extend(args.libs.iter().cloned());
                automat_project::charts::of_files(&p.sources, &libs)
            }
            None => crate::files::collect(&args.paths)
                .and_then(|f| crate::files::load(&f))
                .map(|map| automat_project::charts::of_sources(map, &args.libs))
                .unwrap_or_default(),
        };
        // The LD and FBD drawings, for the HMI.
        let sources = match loaded.project.as_ref() {
            Some(p) => Ok(p.sources.clone()),
            None => crate::files::collect(&args.paths),
        };
        opts.drawings = sources
            .and_then(|f| crate::files::load(&f))
            .map(|map| crate::draw::live::drawings(&map))
            .unwrap_or_default();
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

    // The RETAIN path is checked before anything starts (the live view,
    // the server).
    let retain = RetainCfg::of(args, loaded.project.as_ref().map(|p| &p.retain));
    retain_run::check(&loaded.program, retain.as_ref())?;
    let realtime =
        crate::realtime_run::settings(args, loaded.project.as_ref(), !args.virtual_clock)?;
    let stop = Arc::new(AtomicBool::new(false));
    stop_on_signals(&stop);
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
        retain: retain.as_ref().map(RetainCfg::file),
        safe: Some(loaded.safe.clone()),
        realtime: realtime.clone(),
        // Only a client of the server can restart a faulted PLC.
        wait_after_fault: args.listen.is_some(),
    };
    let safe = loaded.safe;
    let program = Arc::new(loaded.program);
    let for_build = (*program).clone();
    let engine_kind = args.engine;
    let warm_from = retain.as_ref().map(|r| RetainCfg {
        path: r.path.clone(),
        every_ns: r.every_ns,
        optional: r.optional,
    });
    let cold = args.cold;
    let budget = args.max_instructions;
    let opcua_users = users(loaded.project.as_ref());
    let opcua_sample_ns = loaded.cycle_ns;
    let project = loaded.project;
    let view_console = Arc::clone(&console);
    let view_stop = Arc::clone(&stop);
    let speed = args.speed;
    let build = Box::new(move || -> Result<Parts, String> {
        let mut engine = crate::engines::build(for_build.clone(), engine_kind);
        engine.set_budget(budget);
        retain_run::warm(&mut engine, warm_from.as_ref(), cold);
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
        let exchange: Option<Box<dyn automat_session::Exchange>> = if modbus_clients.is_empty() {
            None
        } else {
            Some(Box::new(automat_fieldbus::client::Clients::start(
                modbus_clients.clone(),
            )?))
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
            exchange,
        })
    });
    let session = Arc::new(Session::start(Arc::clone(&program), config, build).map_err(bad)?);
    if let Some(rt) = &realtime {
        crate::realtime_run::announce(rt);
    }
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
            "automat: PLC API on {}://{}/api/v1/ (WebSocket {ws}://{}/api/v1/watch), web HMI on {}://{}/; Ctrl-C stops",
            server.scheme, server.addr, server.addr, server.scheme, server.addr
        );
    }
    let modbus = match modbus_server {
        None => None,
        Some(cfg) => {
            let dev = automat_fieldbus::server::SessionDevice {
                session: Arc::clone(&session),
                map: cfg.map,
            };
            match automat_fieldbus::server::start(Arc::new(dev), cfg.options) {
                Ok(s) => {
                    eprintln!(
                        "automat: Modbus TCP server on {} (docs/modbus.md); Ctrl-C stops",
                        s.addr
                    );
                    Some(s)
                }
                Err(e) => {
                    drop(server);
                    let _ = session.shutdown();
                    return Err(bad(e));
                }
            }
        }
    };
    #[cfg(feature = "opcua")]
    let opcua_server = match opcua {
        None => None,
        Some(c) => {
            let opts = automat_opcua::Options {
                addr: c.addr,
                pki_dir: c.pki_dir,
                users: opcua_users,
                trust_client_certs: c.trust_client_certs,
                sample_ns: opcua_sample_ns,
            };
            match automat_opcua::start(Arc::clone(&session), opts) {
                Ok(s) => {
                    eprintln!(
                        "automat: OPC UA server on opc.tcp://{} ({} variables; {}; docs/opcua.md); Ctrl-C stops",
                        s.addr,
                        s.variables,
                        if s.anonymous {
                            "anonymous read-only without security, users with Basic256Sha256"
                        } else {
                            "users with Basic256Sha256 only"
                        }
                    );
                    Some(s)
                }
                Err(e) => {
                    drop(server);
                    drop(modbus);
                    let _ = session.shutdown();
                    return Err(bad(e));
                }
            }
        }
    };
    #[cfg(not(feature = "opcua"))]
    let _ = (opcua, opcua_users, opcua_sample_ns);
    let modbus_rtu = match modbus_rtu {
        None => None,
        Some(cfg) => {
            let dev = automat_fieldbus::server::SessionDevice {
                session: Arc::clone(&session),
                map: cfg.map,
            };
            match automat_fieldbus::rtu_server::start(Arc::new(dev), cfg.line, cfg.unit) {
                Ok(s) => {
                    eprintln!(
                        "automat: Modbus RTU slave {} on {} (docs/modbus.md); Ctrl-C stops",
                        s.unit,
                        s.line.describe()
                    );
                    Some(s)
                }
                Err(e) => {
                    drop(server);
                    drop(modbus);
                    let _ = session.shutdown();
                    return Err(bad(e));
                }
            }
        }
    };
    if view {
        crate::live::console(
            Arc::clone(&session),
            console,
            to_view,
            Arc::clone(&stop),
            has_plant,
        );
    }
    let mut end = session.join().map_err(bad)?;
    drop(server);
    drop(modbus);
    drop(modbus_rtu);
    #[cfg(feature = "opcua")]
    drop(opcua_server);
    let mut outcome = Outcome::Ok;
    if let Some(saves) = end.retain.take() {
        let saved = retain_run::report(
            saves.last,
            saves.failures,
            saves.last_error.as_deref(),
            retain.as_ref(),
        );
        if !saved {
            outcome = Outcome::BadInput;
        }
    }
    crate::cmd_run::print_values(&end.image, &prints);
    if args.stats {
        eprintln!("{}", end.stats);
    }
    if let Some(e) = &end.error {
        return Err(bad(e));
    }
    if let Some(f) = &end.fault {
        eprintln!("error: runtime fault: {f}");
        safe_note_of(true, &safe);
        return Ok(Outcome::Fault);
    }
    safe_note_of(false, &safe);
    Ok(outcome)
}
