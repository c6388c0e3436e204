//! The PLC session: one running PLC that clients drive by name.
//!
//! A [`Session`] owns, on its own scan thread, the backend (interpreter or
//! JIT, built there by the caller's [`Build`]), the scan runtime and its
//! clock, the plant (if any), the force table and the statistics. Clients
//! (`automat run`, the live view, the network server) hold the `Session`
//! handle, which is `Send + Sync`:
//!
//! - reads, status, forces and subscriptions come from [`Snapshot`]s the
//!   scan thread publishes after every scan (an `Arc` swapped under a lock
//!   held only for the swap, never across a scan);
//! - writes, forces, releases and run control are commands sent through a
//!   channel; the scan thread drains it between scans, never blocks on it
//!   while running, and answers each command once it took effect (the
//!   client waits for that answer, the scan never waits for a client).
//!
//! Paths and values are checked on the client's thread, so a bad one is an
//! [`Error`] at once, with the message `automat run --print` gives.
//!
//! Run control: `stop` is a PLC STOP between two scans: every output goes
//! to its safe state (the plant sees it) and PLC time and the plant stand
//! still (time stopped is left out of the run's clock); `start` resumes,
//! the program driving the outputs again; `step N` runs N scans and pauses
//! again with the outputs as the scans left them (a debugging pause, not a
//! STOP); `cold_restart` and `warm_restart` re-initialise the image (warm
//! keeps the RETAIN variables of the last completed scan) while PLC time
//! goes on; they are also how a PLC in fault starts again.
//!
//! The session owns RETAIN and the safe state as `automat run` always did:
//! the RETAIN file is saved from end-of-scan snapshots (periodically and
//! when the session ends, also after a fault), and the scan loop runs with
//! the configured safe state, applied on a fault and when the session
//! ends.

mod core;
pub mod force;
pub mod plant;
pub mod symbols;
pub mod value;

pub use symbols::Node;

use automat_ir::Program;
use automat_project::Sim;
use automat_runtime::slc_place::looks_dynamic;
pub use automat_runtime::Limit;
use automat_runtime::{
    locate, resolve, resolve_access, value as show, ClockMode, Executor, Locator, Monotonic,
};
use automat_runtime::{Place, SafeState, ScanObserver};
use std::cell::RefCell;
use std::path::PathBuf;
use std::rc::Rc;
use std::sync::atomic::AtomicBool;
use std::sync::mpsc::{channel, Receiver, Sender};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::Duration;

/// What the PLC is doing.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum State {
    Running,
    Stopped,
    /// A runtime fault stopped it (outputs in the safe state); a restart
    /// starts it again.
    Fault {
        message: String,
        site: String,
    },
}

impl State {
    pub fn name(&self) -> &'static str {
        match self {
            State::Running => "running",
            State::Stopped => "stopped",
            State::Fault { .. } => "fault",
        }
    }
}

/// Cycle statistics of the run (since the last restart after a fault).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CycleStats {
    pub min_ns: Option<i64>,
    pub avg_ns: Option<i64>,
    pub max_ns: Option<i64>,
    pub overruns: u64,
}

/// The PLC as the scan thread last published it.
#[derive(Clone, Debug)]
pub struct Snapshot {
    /// PLC time of the last scan (0 before the first).
    pub plc_time_ns: i64,
    /// Scans that ran a task since the session started.
    pub scans: u64,
    pub state: State,
    pub stats: CycleStats,
    /// The memory image after the last scan, with writes and forces that
    /// came since applied.
    pub image: Vec<u8>,
    /// Forced paths with their values, in the order they were set.
    pub forces: Arc<Vec<(String, String)>>,
    /// The snapshot's number: each publication (after a scan or after
    /// commands between scans) counts one up from 0 at the start, so a
    /// client holding values of two replies keeps the newer ones.
    pub seq: u64,
}

/// Why a request was refused.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Error {
    /// An unknown or malformed path (the `--print` message).
    Path(String),
    /// A value that does not parse as the target's type.
    Value(String),
    /// A CONSTANT, a step flag or time, compiler-generated state.
    ReadOnly(String),
    /// A command that does not apply now (e.g. `start` in fault).
    Refused(String),
    /// The scan thread has ended or did not answer.
    Gone(String),
}

impl Error {
    pub fn message(&self) -> &str {
        match self {
            Error::Path(m) | Error::Value(m) | Error::ReadOnly(m) | Error::Refused(m) => m,
            Error::Gone(m) => m,
        }
    }
}

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.message())
    }
}

/// Run control.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Control {
    Start,
    Stop,
    /// Run this many scans (that run a task), then stop.
    Step(u64),
    ColdRestart,
    WarmRestart,
}

/// What the scan thread runs, built there (backends and plants need not
/// be `Send`).
pub struct Parts {
    pub exec: Box<dyn Executor>,
    /// The plant, synchronised before the first program of each scan;
    /// forces sit between it and the program.
    pub sim: Option<Rc<RefCell<Sim>>>,
    /// Sees every scan too (a trace, the live view).
    pub observer: Option<Box<dyn ScanObserver>>,
    /// Fieldbus I/O (Modbus client devices) exchanged between scans.
    pub exchange: Option<Box<dyn Exchange>>,
}

/// Process I/O exchanged with the outside on the scan thread, between
/// scans, by copying only: the protocol runs on threads of its own, so a
/// slow or dead device never stalls the scan (`automat-fieldbus`).
///
/// `inputs` is called between scans, before the forces are stored again
/// and the snapshot is published: the values the next scan reads (a
/// forced input still beats them). `outputs` is called after each
/// completed scan with its end image (forced outputs included), after a
/// STOP or a fault with the safe state, on every wait while stopped, and
/// once more at the end of the session with the final (safe) image.
pub trait Exchange {
    fn inputs(&mut self, image: &mut [u8]);
    fn outputs(&mut self, image: &[u8]);
}

pub type Build = Box<dyn FnOnce() -> Result<Parts, String> + Send>;

pub struct Config {
    /// The cyclic task's period when there is no CONFIGURATION.
    pub cycle_time_ns: i64,
    pub clock: ClockMode,
    /// The clock that paces real time and measures scans.
    pub monotonic: Box<dyn Monotonic + Send>,
    /// Start running at once (otherwise stopped, waiting for commands).
    pub running: bool,
    /// Set from outside (Ctrl-C, SIGTERM, SIGHUP) to end the session at
    /// the end of the scan; it is the scan loop's stop flag too, so a scan
    /// still running a second after it is stopped as a fault.
    pub stop: Arc<AtomicBool>,
    /// The RETAIN file the session keeps (`None`: RETAIN variables are not
    /// kept). The image the build returns is already warm- or cold-started.
    pub retain: Option<RetainFile>,
    /// The safe state of every output, applied on a fault, on a `stop`
    /// command and when the session ends (`None`: the program's default,
    /// [`SafeState::of_program`]).
    pub safe: Option<SafeState>,
    /// Real-time mode for the scan thread (memory locked, SCHED_FIFO,
    /// CPUs): entered on the scan thread before the program is built; a
    /// refusal of the system ends the start with its message.
    pub realtime: Option<automat_runtime::realtime::Realtime>,
    /// After a runtime fault, wait in the fault state for a restart
    /// command (a server's clients can give one); `false`: the fault ends
    /// the session (nobody could restart it), as on a plain `automat run`.
    pub wait_after_fault: bool,
}

/// The RETAIN file of a session: saved from end-of-scan snapshots only
/// (`automat_runtime::retain::Keeper`), every `every_ns` of PLC time while
/// running (`None`: only when the session ends), and at the end.
#[derive(Clone, Debug)]
pub struct RetainFile {
    pub path: PathBuf,
    pub every_ns: Option<i64>,
}

/// The RETAIN saves of a session that kept a file.
#[derive(Debug)]
pub struct RetainSaves {
    /// The final save (of the last end-of-scan snapshot).
    pub last: Result<(), String>,
    /// Periodic saves that failed, and the message of the last one.
    pub failures: u64,
    pub last_error: Option<String>,
}

/// How the session ended.
#[derive(Debug)]
pub struct Final {
    /// The image at the end (for saving RETAIN variables).
    pub image: Vec<u8>,
    pub snapshot: Arc<Snapshot>,
    /// Why the scan loop ended when not by a stop (a configuration error,
    /// the caller's observer).
    pub error: Option<String>,
    /// The fault the session ended in, as the runtime reports it
    /// (`file:line:col: fault in POU: message (task …, PLC time …)`).
    pub fault: Option<String>,
    /// The same fault as the runtime reported it (its kind and site), for
    /// harnesses that compare them.
    pub fault_report: Option<automat_runtime::scan::FaultReport>,
    /// The RETAIN saves (`None` without a RETAIN file).
    pub retain: Option<RetainSaves>,
    /// Scan statistics of the whole session (every run between stops).
    pub stats: automat_runtime::stats::Stats,
    /// What ended the scan loop.
    pub end: End,
}

/// What ended a session's scan loop.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum End {
    /// The run's limit ([`run_here`]: cycles or PLC time).
    Limit,
    /// A stop: the outside stop flag, a shutdown, every handle gone.
    Stopped,
    /// A runtime fault ([`Final::fault`]).
    Fault,
    /// The caller's observer refused a scan ([`Final::error`]: a trace
    /// that cannot be written).
    Observer,
    /// The run could not start or go on ([`Final::error`]).
    Error,
}

/// An observer the caller keeps a handle on, to ask after a
/// [`run_here`] (a trace to flush, a scenario's verdicts).
pub struct Watching<T>(pub Rc<RefCell<T>>);

impl<T: ScanObserver> ScanObserver for Watching<T> {
    fn after_scan(&mut self, plc_time_ns: i64, image: &[u8]) -> Result<(), String> {
        self.0.borrow_mut().after_scan(plc_time_ns, image)
    }
    fn stats(&mut self, stats: &automat_runtime::stats::Stats) {
        self.0.borrow_mut().stats(stats);
    }
    fn between_scans(&mut self, image: &mut [u8]) -> bool {
        self.0.borrow_mut().between_scans(image)
    }
}

/// Runs a session on the calling thread until `limit` (`--cycles`,
/// `--duration`, a scenario's duration), a fault or the stop flag: the
/// batch runs of `automat run` and `automat test` go through the same
/// scan loop, forces and RETAIN keeping as a served PLC. `parts` are
/// built by the caller (they need not be `Send`); `config.running` is
/// taken as true and nobody sends commands.
pub fn run_here(program: Arc<Program>, mut config: Config, parts: Parts, limit: Limit) -> Final {
    config.running = true;
    config.wait_after_fault = false;
    let shared = Arc::new(Shared {
        snapshot: Mutex::new(Arc::new(Snapshot {
            plc_time_ns: 0,
            scans: 0,
            state: State::Running,
            stats: CycleStats::default(),
            image: program.initial_image.clone(),
            forces: Arc::new(Vec::new()),
            seq: 0,
        })),
    });
    // The sender lives as long as the run, so the loop never takes the
    // closed channel for "every handle is gone".
    let (tx, rx) = channel::<Request>();
    let end = core::here(program, config, parts, limit, rx, shared);
    drop(tx);
    end
}

/// Values of watched paths after a scan, as `--print` shows them.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Update {
    pub plc_time_ns: i64,
    pub scans: u64,
    pub values: Vec<(String, String)>,
}

/// Called on the scan thread with each snapshot due; must not block (try
/// a bounded channel); `false` ends the subscription.
pub type Sink = Box<dyn FnMut(&Arc<Snapshot>) -> bool + Send>;

pub(crate) enum Command {
    Write(value::Stored),
    /// Several places in one step between two scans (a Modbus write of
    /// several registers is one consistent change).
    WriteMany(Vec<value::Stored>),
    Force(force::Force),
    Unforce(Option<value::Stored>),
    Control(Control),
    /// Runs on the scan thread with the plant (`None` without one).
    Plant(PlantCall),
    Subscribe {
        period_ns: i64,
        sink: Sink,
    },
    Quit,
}

pub(crate) type PlantCall = Box<dyn FnOnce(Option<&mut Sim>) -> Result<(), Error> + Send>;

pub(crate) struct Request {
    pub command: Command,
    pub reply: Sender<Result<(), Error>>,
}

pub(crate) struct Shared {
    pub snapshot: Mutex<Arc<Snapshot>>,
}

/// The handle clients hold (see the crate comment).
pub struct Session {
    program: Arc<Program>,
    shared: Arc<Shared>,
    tx: Mutex<Sender<Request>>,
    thread: Mutex<Option<JoinHandle<Final>>>,
}

/// How long a client waits for the scan thread to take a command.
const ANSWER_WITHIN: Duration = Duration::from_secs(60);

impl Session {
    /// Starts the scan thread; errors when `build` fails.
    pub fn start(program: Arc<Program>, config: Config, build: Build) -> Result<Session, String> {
        let empty = Snapshot {
            plc_time_ns: 0,
            scans: 0,
            state: if config.running {
                State::Running
            } else {
                State::Stopped
            },
            stats: CycleStats::default(),
            image: program.initial_image.clone(),
            forces: Arc::new(Vec::new()),
            seq: 0,
        };
        let shared = Arc::new(Shared {
            snapshot: Mutex::new(Arc::new(empty)),
        });
        let (tx, rx): (Sender<Request>, Receiver<Request>) = channel();
        let (ready_tx, ready_rx) = channel();
        let thread_shared = Arc::clone(&shared);
        let thread_program = Arc::clone(&program);
        let thread = std::thread::Builder::new()
            .name("automat-scan".into())
            .spawn(move || core::main(thread_program, config, build, rx, thread_shared, ready_tx))
            .map_err(|e| format!("cannot start the scan thread: {e}"))?;
        match ready_rx.recv() {
            Ok(Ok(())) => {}
            Ok(Err(e)) => {
                let _ = thread.join();
                return Err(e);
            }
            Err(_) => return Err("the scan thread ended before starting".into()),
        }
        Ok(Session {
            program,
            shared,
            tx: Mutex::new(tx),
            thread: Mutex::new(Some(thread)),
        })
    }

    pub fn program(&self) -> &Program {
        &self.program
    }

    /// The last published snapshot.
    pub fn snapshot(&self) -> Arc<Snapshot> {
        match self.shared.snapshot.lock() {
            Ok(s) => Arc::clone(&s),
            Err(p) => Arc::clone(&p.into_inner()),
        }
    }

    /// Resolves a path for reading.
    pub fn place(&self, path: &str) -> Result<Place, Error> {
        resolve(&self.program, path).map_err(Error::Path)
    }

    /// Resolves a path for reading at run time: an SLC indexed or
    /// indirect address (`#N7:5`, `N7:[N7:0]`) is found in each image.
    pub fn locate(&self, path: &str) -> Result<Locator, Error> {
        locate(&self.program, path).map_err(Error::Path)
    }

    /// The values of `paths` in the last snapshot, as `--print` shows them
    /// (an indexed or indirect address outside its data file in that
    /// snapshot is an error of this read).
    pub fn read(&self, paths: &[String]) -> Result<Vec<(String, String)>, Error> {
        self.read_seq(paths).map(|(_, values)| values)
    }

    /// [`Session::read`] with the number of the snapshot the values come
    /// from ([`Snapshot::seq`]).
    pub fn read_seq(&self, paths: &[String]) -> Result<(u64, Vec<(String, String)>), Error> {
        let locators = paths
            .iter()
            .map(|p| self.locate(p))
            .collect::<Result<Vec<Locator>, Error>>()?;
        let snap = self.snapshot();
        let values = paths
            .iter()
            .zip(&locators)
            .map(|(p, l)| {
                let place = l.place(&snap.image).map_err(Error::Path)?;
                Ok((p.clone(), show::format(&snap.image, &place)))
            })
            .collect::<Result<Vec<_>, Error>>()?;
        Ok((snap.seq, values))
    }

    /// An SLC indexed or indirect `path` as the last snapshot has it: its
    /// direct address (`N7:3`) and place; `None` for any other path. A
    /// write or force goes to the place so found (CODESYS forces the
    /// concrete place at the time of the force likewise).
    fn concrete(&self, path: &str) -> Result<Option<(String, Place)>, Error> {
        if !looks_dynamic(path) {
            return Ok(None);
        }
        let l = self.locate(path)?;
        let snap = self.snapshot();
        let place = l.place(&snap.image).map_err(Error::Path)?;
        let name = match l.direct(&snap.image) {
            Some(Ok(n)) => n,
            _ => path.trim().to_string(),
        };
        Ok(Some((name, place)))
    }

    /// Where `path` is and what storing `text` there means; refused for
    /// what only the compiler or a chart may change.
    pub fn target(&self, path: &str, text: &str) -> Result<value::Stored, Error> {
        let path = path.trim();
        if let Some((_, place)) = self.concrete(path)? {
            return value::encode(&place, text, None)
                .map_err(|e| Error::Value(format!("`{path}`: {e}")));
        }
        let a = resolve_access(&self.program, path).map_err(Error::Path)?;
        if a.constant {
            return Err(Error::ReadOnly(format!(
                "`{path}` is a CONSTANT and cannot be written or forced"
            )));
        }
        if let Some(hidden) = &a.generated {
            let upper = path.to_ascii_uppercase();
            let what = if hidden.starts_with("__SFC_STEP") || hidden.starts_with("__SFC_INITIAL") {
                if upper.ends_with(".T") {
                    "a step time"
                } else if upper.ends_with(".X") {
                    "a step flag"
                } else {
                    "step state"
                }
            } else if hidden.starts_with("__SFC_ACTION") {
                "an action's control state"
            } else {
                "compiler-generated state"
            };
            return Err(Error::ReadOnly(format!(
                "`{path}` is {what}; only the program's chart changes it, it cannot be written or forced"
            )));
        }
        value::encode(&a.place, text, a.bounds).map_err(|e| Error::Value(format!("`{path}`: {e}")))
    }

    fn send(&self, command: Command) -> Result<(), Error> {
        let (reply, answer) = channel();
        let sent = match self.tx.lock() {
            Ok(tx) => tx.send(Request { command, reply }),
            Err(p) => p.into_inner().send(Request { command, reply }),
        };
        sent.map_err(|_| Error::Gone("the PLC session has ended".into()))?;
        match answer.recv_timeout(ANSWER_WITHIN) {
            Ok(r) => r,
            Err(_) => Err(Error::Gone(
                "the PLC did not take the command (the session has ended or is busy)".into(),
            )),
        }
    }

    /// Writes `text` once, between two scans (the program may overwrite
    /// it at its next scan; a force holds).
    pub fn write(&self, path: &str, text: &str) -> Result<(), Error> {
        let stored = self.target(path, text)?;
        self.send(Command::Write(stored))
    }

    /// Stores already encoded values (places the caller resolved and
    /// checked for writability) together, between two scans, as
    /// [`Session::write`] does: forces hold, the answer comes with the
    /// snapshot that shows the change.
    pub fn write_stored(&self, stored: Vec<value::Stored>) -> Result<(), Error> {
        if stored.is_empty() {
            return Ok(());
        }
        self.send(Command::WriteMany(stored))
    }

    /// Forces `path` to `text` until released. An SLC indexed or indirect
    /// address forces the place it names now, listed under its direct
    /// address (`N7:[N7:0]` while N7:0 = 3 forces and lists `N7:3`).
    pub fn force(&self, path: &str, text: &str) -> Result<(), Error> {
        let stored = self.target(path, text)?;
        let shown = match self.concrete(path)? {
            Some((name, _)) => name,
            None => path.trim().to_string(),
        };
        self.send(Command::Force(force::Force {
            path: shown,
            text: text.trim().to_string(),
            stored,
        }))
    }

    /// Releases the force of `path` (an error when it is not forced).
    pub fn unforce(&self, path: &str) -> Result<(), Error> {
        let place = match self.concrete(path)? {
            Some((_, place)) => place,
            None => {
                resolve_access(&self.program, path.trim())
                    .map_err(Error::Path)?
                    .place
            }
        };
        // Any value of the right shape names the location.
        let stored = match place.bit {
            Some(bit) => value::Stored::Bit {
                offset: place.offset as usize,
                bit,
                value: false,
            },
            None => value::Stored::Bytes {
                offset: place.offset as usize,
                bytes: Vec::new(),
            },
        };
        self.send(Command::Unforce(Some(stored)))
    }

    pub fn unforce_all(&self) -> Result<(), Error> {
        self.send(Command::Unforce(None))
    }

    /// The forced paths and values.
    pub fn forces(&self) -> Vec<(String, String)> {
        self.snapshot().forces.as_ref().clone()
    }

    /// Whether the location of `place` is forced (whatever name the force
    /// was given), for views that mark forced values.
    pub fn is_forced(&self, place: &Place) -> bool {
        self.is_forced_in(&self.snapshot(), place)
    }

    /// Whether `place` is forced in `snap` (an update formats the values
    /// and the forces of the same snapshot).
    pub fn is_forced_in(&self, snap: &Snapshot, place: &Place) -> bool {
        snap.forces.iter().any(|(path, _)| {
            resolve(&self.program, path)
                .is_ok_and(|f| f.offset == place.offset && f.bit == place.bit)
        })
    }

    /// The plant as the last scan left it (`None`: the run has no plant).
    pub fn plant(&self) -> Result<Option<plant::View>, Error> {
        let (tx, rx) = channel();
        self.send(Command::Plant(Box::new(move |sim| {
            let _ = tx.send(sim.map(plant::view));
            Ok(())
        })))?;
        rx.recv()
            .map_err(|_| Error::Gone("the PLC session has ended".into()))
    }

    /// Applies an operator's action to the plant at the next scan; refused
    /// when the run has no plant.
    pub fn plant_op(&self, op: plant::Op) -> Result<(), Error> {
        self.send(Command::Plant(Box::new(move |sim| match sim {
            Some(sim) => plant::apply(sim, &op),
            None => Err(Error::Refused(
                "this run has no plant (run a project folder with a [plant])".into(),
            )),
        })))
    }

    /// Run control; returns once it took effect (`step` once the scans ran).
    pub fn control(&self, c: Control) -> Result<(), Error> {
        self.send(Command::Control(c))
    }

    /// The symbol tree under `prefix` (everything when empty).
    pub fn symbols(&self, prefix: &str) -> Result<Vec<Node>, Error> {
        symbols::tree(&self.program, prefix).ok_or_else(|| {
            Error::Path(format!(
                "unknown variable `{}`: nothing is declared under this name",
                prefix.trim()
            ))
        })
    }

    /// Calls `sink` with the values of `paths` after every scan
    /// (`period_ns` ≤ 0) or at most once per `period_ns` of PLC time.
    /// The values are formatted on the scan thread only for subscriptions
    /// due; `sink` must not block.
    pub fn subscribe(
        &self,
        paths: &[String],
        period_ns: i64,
        mut sink: Box<dyn FnMut(Update) -> bool + Send>,
    ) -> Result<(), Error> {
        let locators = paths
            .iter()
            .map(|p| self.locate(p))
            .collect::<Result<Vec<Locator>, Error>>()?;
        let names = paths.to_vec();
        let raw: Sink = Box::new(move |snap: &Arc<Snapshot>| {
            sink(Update {
                plc_time_ns: snap.plc_time_ns,
                scans: snap.scans,
                values: names
                    .iter()
                    .zip(&locators)
                    .map(|(n, l)| (n.clone(), l.format(&snap.image)))
                    .collect(),
            })
        });
        self.subscribe_raw(period_ns, raw)
    }

    /// As [`Session::subscribe`], the sink getting the whole snapshot (a
    /// server decodes on its own threads).
    pub fn subscribe_raw(&self, period_ns: i64, sink: Sink) -> Result<(), Error> {
        self.send(Command::Subscribe { period_ns, sink })
    }

    /// Ends the session at the end of the scan and returns its last state.
    pub fn shutdown(&self) -> Result<Final, String> {
        let _ = self.send(Command::Quit);
        self.join()
    }

    /// Waits for the scan thread to end by itself (the stop flag).
    pub fn join(&self) -> Result<Final, String> {
        let handle = match self.thread.lock() {
            Ok(mut t) => t.take(),
            Err(p) => p.into_inner().take(),
        };
        match handle {
            Some(h) => h.join().map_err(|_| "the scan thread panicked".to_string()),
            None => Err("the session has already ended".into()),
        }
    }
}
