//! The scan thread: the runtime's scan loop with the session as its
//! observer. Between scans ([`ScanObserver::between_scans`]) it applies
//! the commands that came (never waiting for one while running), stores
//! the forces, publishes the snapshot, feeds the subscriptions due and
//! answers the commands; while stopped it waits there, its waiting time
//! left out of the run's clock so PLC time and the plant stand still.
//!
//! The scan loop is `run_safe` with the session's safe state and the
//! outside stop flag, so a fault, a signal and the end of the session all
//! leave the outputs safe and a long scan is stopped as a fault a second
//! after a stop request. RETAIN is kept by a [`Keeper`] that sees every
//! completed scan (and the image after a restart, a consistent state too).

use crate::force::{Boxed, ForceTable, Forcing, Shifted};
use crate::{
    Command, Config, Control, CycleStats, End, Error, Final, Parts, Request, RetainSaves, Shared,
    Sink, Snapshot, State,
};
use automat_ir::Program;
use automat_project::{PlantExec, Sim};
use automat_runtime::io::NoIo;
use automat_runtime::retain::Keeper;
use automat_runtime::scan::Env;
use automat_runtime::stats::Stats;
use automat_runtime::{
    run_safe, ClockMode, Executor, Limit, Monotonic, RunConfig, RunEnd, SafeState, ScanObserver,
};
use std::cell::{Cell, RefCell};
use std::ops::Range;
use std::rc::Rc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender, TryRecvError};
use std::sync::Arc;
use std::time::Duration;

/// How often a stopped session looks at the outside stop flag.
const POLL: Duration = Duration::from_millis(50);

/// The run's clock with the time spent stopped left out.
struct PausedClock {
    inner: Box<dyn Monotonic + Send>,
    /// Time spent stopped so far.
    paused_ns: i64,
    since: Option<i64>,
}

#[derive(Clone)]
struct ClockHandle(Rc<RefCell<PausedClock>>);

impl ClockHandle {
    fn pause(&self) {
        let mut c = self.0.borrow_mut();
        if c.since.is_none() {
            let now = c.inner.now_ns();
            c.since = Some(now);
        }
    }
    fn resume(&self) {
        let mut c = self.0.borrow_mut();
        if let Some(since) = c.since.take() {
            let now = c.inner.now_ns();
            c.paused_ns = c.paused_ns.saturating_add(now.saturating_sub(since));
        }
    }
}

impl Monotonic for ClockHandle {
    fn now_ns(&mut self) -> i64 {
        let mut c = self.0.borrow_mut();
        let paused = c.paused_ns;
        c.inner.now_ns().saturating_sub(paused)
    }
    fn sleep_until(&mut self, deadline_ns: i64) {
        let mut c = self.0.borrow_mut();
        let paused = c.paused_ns;
        c.inner.sleep_until(deadline_ns.saturating_add(paused));
    }
}

/// Where a command's answer goes.
type Reply = Sender<Result<(), Error>>;

struct Subscription {
    period_ns: i64,
    next_ns: i64,
    sink: Sink,
}

/// The session's side of the scan thread.
struct Core {
    program: Arc<Program>,
    /// Whether a handle can read the published snapshot (a `Session`); a
    /// `run_here` has none, so its scans copy no image for it (the final
    /// snapshot is still made, for `Final`).
    clients: bool,
    rx: Receiver<Request>,
    shared: Arc<Shared>,
    forces: Rc<RefCell<ForceTable>>,
    forces_shown: Arc<Vec<(String, String)>>,
    offset: Rc<Cell<i64>>,
    clock: ClockHandle,
    outside_stop: Arc<AtomicBool>,
    extra: Option<Box<dyn ScanObserver>>,
    /// Fieldbus I/O, exchanged between scans (see [`crate::Exchange`]).
    exchange: Option<Box<dyn crate::Exchange>>,
    state: State,
    /// Scans left of a `step`, and who waits for them.
    steps: Option<(u64, Reply)>,
    plc_time_ns: i64,
    scans: u64,
    /// Snapshots published so far ([`Snapshot::seq`]).
    published: u64,
    stats: CycleStats,
    subs: Vec<Subscription>,
    quit: bool,
    /// A restart asked for while in fault (done outside the scan loop).
    restart: Option<()>,
    /// Replies to send once the snapshot shows the commands' effect.
    answers: Vec<(Reply, Result<(), Error>)>,
    /// Saves the RETAIN file from end-of-scan snapshots (passes scans on
    /// to nothing: the caller's observer is `extra`).
    keeper: Keeper<'static>,
    /// The RETAIN ranges of the image, and their bytes at the end of the
    /// last completed scan (or restart): what a warm restart keeps, never
    /// the half-done values of a faulted scan.
    retain_ranges: Vec<Range<usize>>,
    retained: Vec<u8>,
    /// Applied on a `stop` command (a PLC STOP).
    safe: SafeState,
    /// While stopped by a `stop` command: what the program's outputs held
    /// before the safe state, and the writes made since, in order. A start
    /// (or step) puts them back so the program continues where it stopped;
    /// a restart or a fault drops them.
    held: Option<(SafeState, Vec<crate::value::Stored>)>,
    /// Scan statistics of every run so far (a stop ends a run).
    totals: Stats,
    sim: Option<Rc<RefCell<Sim>>>,
    /// The last fault, as the runtime reports it.
    fault: Option<String>,
}

impl Core {
    fn publish(&mut self, image: &[u8]) {
        self.published += 1;
        let snap = Arc::new(Snapshot {
            plc_time_ns: self.plc_time_ns,
            scans: self.scans,
            state: self.state.clone(),
            stats: self.stats.clone(),
            image: image.to_vec(),
            forces: Arc::clone(&self.forces_shown),
            seq: self.published,
        });
        match self.shared.snapshot.lock() {
            Ok(mut s) => *s = Arc::clone(&snap),
            Err(p) => *p.into_inner() = Arc::clone(&snap),
        }
    }

    fn answer(&mut self) {
        for (to, answer) in self.answers.drain(..) {
            let _ = to.send(answer);
        }
    }

    fn feed(&mut self) {
        if self.subs.is_empty() {
            // Nobody subscribed (`automat test`, a plain run): no snapshot
            // lock and reference count per scan.
            return;
        }
        let snap = match self.shared.snapshot.lock() {
            Ok(s) => Arc::clone(&s),
            Err(p) => Arc::clone(&p.into_inner()),
        };
        let now = self.plc_time_ns;
        self.subs.retain_mut(|s| {
            if now < s.next_ns {
                return true;
            }
            s.next_ns = if s.period_ns > 0 {
                // The next multiple of the period: decimation never drifts.
                now - now.rem_euclid(s.period_ns) + s.period_ns
            } else {
                now
            };
            (s.sink)(&snap)
        });
    }

    /// Applies one command to the image; the answer goes out with the next
    /// snapshot (or, for a `step`, when its scans have run).
    fn handle(&mut self, req: Request, image: &mut [u8], in_scan_loop: bool) {
        let Request { command, reply } = req;
        let answer = match command {
            Command::Write(stored) => {
                stored.apply(image);
                if let Some((_, written)) = &mut self.held {
                    written.push(stored);
                }
                Ok(())
            }
            Command::WriteMany(all) => {
                for stored in &all {
                    stored.apply(image);
                }
                Ok(())
            }
            Command::Force(f) => {
                f.stored.apply(image);
                self.forces.borrow_mut().set(f);
                self.forces_shown = Arc::new(self.forces.borrow().list());
                Ok(())
            }
            Command::Unforce(None) => {
                self.forces.borrow_mut().clear();
                self.forces_shown = Arc::new(Vec::new());
                Ok(())
            }
            Command::Unforce(Some(at)) => {
                if self.forces.borrow_mut().release(&at) {
                    self.forces_shown = Arc::new(self.forces.borrow().list());
                    Ok(())
                } else {
                    Err(Error::Refused("this location is not forced".into()))
                }
            }
            Command::Subscribe { period_ns, sink } => {
                // Decimated: on the multiples of the period from the next
                // scan on, so every client sees the same instants.
                let next_ns = if period_ns > 0 {
                    let last = if self.scans == 0 {
                        self.plc_time_ns.saturating_sub(1)
                    } else {
                        self.plc_time_ns
                    };
                    last - last.rem_euclid(period_ns) + period_ns
                } else {
                    i64::MIN
                };
                self.subs.push(Subscription {
                    period_ns,
                    next_ns,
                    sink,
                });
                Ok(())
            }
            Command::Plant(call) => match &self.sim {
                Some(sim) => call(Some(&mut sim.borrow_mut())),
                None => call(None),
            },
            Command::Quit => {
                self.quit = true;
                Ok(())
            }
            Command::Control(c) => return self.control(c, reply, image, in_scan_loop),
        };
        self.answers.push((reply, answer));
    }

    fn control(&mut self, c: Control, reply: Reply, image: &mut [u8], in_scan_loop: bool) {
        let fault = matches!(self.state, State::Fault { .. });
        let answer = match c {
            Control::Start | Control::Step(_) if fault => Err(Error::Refused(
                "the PLC is in fault: cold_restart or warm_restart starts it again".into(),
            )),
            Control::Start => {
                self.steps = None;
                self.state = State::Running;
                self.unhold(image);
                self.resume_plant();
                Ok(())
            }
            Control::Stop => {
                self.steps = None;
                if !fault {
                    // A PLC in STOP holds its outputs in the safe state, and
                    // the plant's actuators follow (in fault they already do).
                    if self.held.is_none() {
                        self.held = Some((self.safe.held(image), Vec::new()));
                    }
                    self.safe.apply(image);
                    if let Some(s) = &self.sim {
                        s.borrow_mut().safe_state(image);
                    }
                }
                self.state = State::Stopped;
                Ok(())
            }
            Control::Step(0) => Ok(()),
            Control::Step(n) => {
                self.state = State::Running;
                self.unhold(image);
                self.resume_plant();
                // Answered when the scans have run.
                if let Some((_, earlier)) = self.steps.replace((n, reply)) {
                    let _ = earlier.send(Err(Error::Refused(
                        "a newer step command replaced this one".into(),
                    )));
                }
                return;
            }
            Control::ColdRestart | Control::WarmRestart => {
                let kept = (c == Control::WarmRestart)
                    .then_some((self.retain_ranges.as_slice(), self.retained.as_slice()));
                self.held = None;
                restart_image(&self.program, image, kept);
                self.forces.borrow().apply(image);
                // The restarted image is consistent: RETAIN keeps it until
                // the next scan ends (a cold restart's zeros included).
                self.retained_from(image);
                let _ = self.keeper.after_scan(self.plc_time_ns, image);
                if !in_scan_loop {
                    // Out of the scan loop (in fault): it starts again.
                    self.restart = Some(());
                }
                if fault {
                    self.state = State::Stopped;
                }
                Ok(())
            }
        };
        self.answers.push((reply, answer));
    }

    /// Leaving a STOP: the outputs get back the values the program gave
    /// them, then the writes made while stopped, then the forces.
    fn unhold(&mut self, image: &mut [u8]) {
        if let Some((held, written)) = self.held.take() {
            held.apply(image);
            for w in &written {
                w.apply(image);
            }
            self.forces.borrow().apply(image);
        }
    }

    /// The plant's actuators follow the image again (after a STOP).
    fn resume_plant(&self) {
        if let Some(s) = &self.sim {
            if s.borrow().halted() {
                s.borrow_mut().resume();
            }
        }
    }

    fn retained_from(&mut self, image: &[u8]) {
        let mut at = 0;
        for r in &self.retain_ranges {
            if let (Some(src), Some(dst)) = (
                image.get(r.clone()),
                self.retained.get_mut(at..at + r.len()),
            ) {
                dst.copy_from_slice(src);
            }
            at += r.len();
        }
    }

    /// Between scans (or while in fault): commands, snapshot, waiting.
    /// `false` ends the scan loop.
    fn between(&mut self, image: &mut [u8], in_scan_loop: bool, scanned: bool) -> bool {
        if scanned {
            if let Some((left, _)) = &mut self.steps {
                *left = left.saturating_sub(1);
                if *left == 0 {
                    if let Some((_, to)) = self.steps.take() {
                        self.answers.push((to, Ok(())));
                    }
                    self.state = State::Stopped;
                }
            }
        }
        let mut first = true;
        loop {
            loop {
                match self.rx.try_recv() {
                    Ok(req) => self.handle(req, image, in_scan_loop),
                    Err(TryRecvError::Empty) => break,
                    // Every handle is gone: nobody can stop the PLC any more.
                    Err(TryRecvError::Disconnected) => {
                        self.quit = true;
                        break;
                    }
                }
            }
            if let Some(x) = &mut self.exchange {
                if self.state != State::Running {
                    // Stopped or in fault: the devices get the safe state
                    // (and what a client wrote to the outputs since).
                    x.outputs(image);
                }
                x.inputs(image);
            }
            self.forces.borrow().apply(image);
            if !matches!(self.state, State::Fault { .. }) {
                // Writes and forces between scans are consistent states
                // too; a faulted scan's half-done values never are.
                self.retained_from(image);
            }
            if self.clients {
                self.publish(image);
            }
            if first && scanned {
                self.feed();
            }
            self.answer();
            first = false;
            if self.quit || self.outside_stop.load(Ordering::Relaxed) {
                self.clock.resume();
                return false;
            }
            if self.restart.is_some() {
                return false;
            }
            if self.state == State::Running {
                self.clock.resume();
                return true;
            }
            self.clock.pause();
            match self.rx.recv_timeout(POLL) {
                Ok(req) => self.handle(req, image, in_scan_loop),
                Err(RecvTimeoutError::Timeout) => {}
                Err(RecvTimeoutError::Disconnected) => {
                    self.quit = true;
                }
            }
        }
    }
}

/// The cold-start image; with `kept` (a warm restart) the RETAIN ranges
/// get the bytes kept for them (one after another, as
/// [`Core::retained`] holds them).
fn restart_image(program: &Program, image: &mut [u8], kept: Option<(&[Range<usize>], &[u8])>) {
    image.fill(0);
    let n = program.initial_image.len().min(image.len());
    if let (Some(dst), Some(src)) = (image.get_mut(..n), program.initial_image.get(..n)) {
        dst.copy_from_slice(src);
    }
    let Some((ranges, bytes)) = kept else {
        return;
    };
    let mut at = 0;
    for r in ranges {
        if let (Some(dst), Some(src)) = (image.get_mut(r.clone()), bytes.get(at..at + r.len())) {
            dst.copy_from_slice(src);
        }
        at += r.len();
    }
}

/// The RETAIN ranges of `program` as image ranges.
fn retain_ranges(program: &Program) -> Vec<Range<usize>> {
    program
        .retain
        .iter()
        .filter_map(|r| Some(usize::try_from(r.start).ok()?..usize::try_from(r.end).ok()?))
        .collect()
}

/// The observer the scan loop calls: the session's core and the caller's
/// own observer.
struct Observer<'a> {
    core: &'a mut Core,
}

impl ScanObserver for Observer<'_> {
    fn after_scan(&mut self, plc_time_ns: i64, image: &[u8]) -> Result<(), String> {
        let c = &mut *self.core;
        c.plc_time_ns = plc_time_ns.saturating_add(c.offset.get());
        c.scans += 1;
        // The end of a completed scan: the consistent state RETAIN keeps.
        c.keeper.after_scan(c.plc_time_ns, image)?;
        c.retained_from(image);
        if let Some(x) = &mut c.exchange {
            x.outputs(image);
        }
        match &mut c.extra {
            Some(o) => o.after_scan(c.plc_time_ns, image),
            None => Ok(()),
        }
    }

    fn stats(&mut self, stats: &Stats) {
        let c = &mut *self.core;
        c.stats = CycleStats {
            min_ns: stats.min_ns,
            avg_ns: stats.avg_ns(),
            max_ns: stats.max_ns,
            overruns: stats.overruns,
        };
        if let Some(o) = &mut c.extra {
            o.stats(stats);
        }
    }

    fn between_scans(&mut self, image: &mut [u8]) -> bool {
        let go_on = self.core.between(image, true, true);
        match &mut self.core.extra {
            Some(o) => o.between_scans(image) && go_on,
            None => go_on,
        }
    }
}

/// A session that ended before its first scan (`error`).
fn failed(shared: &Shared, ready: &Sender<Result<(), String>>, e: String) -> Final {
    let _ = ready.send(Err(e.clone()));
    Final {
        image: Vec::new(),
        snapshot: Arc::clone(&*shared.snapshot.lock().unwrap_or_else(|p| p.into_inner())),
        error: Some(e),
        fault: None,
        fault_report: None,
        retain: None,
        stats: Stats::default(),
        end: End::Error,
    }
}

/// The scan thread of a [`crate::Session`]: enters real time, builds the
/// parts there, runs until the session is shut down.
pub(crate) fn main(
    program: Arc<Program>,
    config: Config,
    build: crate::Build,
    rx: Receiver<Request>,
    shared: Arc<Shared>,
    ready: Sender<Result<(), String>>,
) -> Final {
    if let Some(rt) = &config.realtime {
        if let Err(e) = automat_runtime::realtime::enter(rt) {
            return failed(&shared, &ready, e);
        }
    }
    match build() {
        Ok(parts) => run(program, config, parts, Mode::Served, rx, shared, ready),
        Err(e) => failed(&shared, &ready, e),
    }
}

/// A batch run on the calling thread ([`crate::run_here`]).
pub(crate) fn here(
    program: Arc<Program>,
    config: Config,
    parts: Parts,
    limit: Limit,
    rx: Receiver<Request>,
    shared: Arc<Shared>,
) -> Final {
    let (ready, _) = std::sync::mpsc::channel();
    if let Some(rt) = &config.realtime {
        if let Err(e) = automat_runtime::realtime::enter(rt) {
            return failed(&shared, &ready, e);
        }
    }
    run(program, config, parts, Mode::Here(limit), rx, shared, ready)
}

/// How a session runs: served (handles read its snapshots and send it
/// commands; no limit), or here to a limit with nobody reading.
#[derive(Clone, Copy)]
enum Mode {
    Served,
    Here(Limit),
}

/// The scan loop of a session, on the thread that calls it, until its
/// limit, a stop or the end of the session.
#[allow(clippy::too_many_arguments)]
fn run(
    program: Arc<Program>,
    config: Config,
    parts: Parts,
    mode: Mode,
    rx: Receiver<Request>,
    shared: Arc<Shared>,
    ready: Sender<Result<(), String>>,
) -> Final {
    let Parts {
        exec,
        sim,
        observer: extra,
        exchange,
    } = parts;
    let forces = Rc::new(RefCell::new(ForceTable::default()));
    let offset = Rc::new(Cell::new(0i64));
    let forcing = Forcing {
        inner: Boxed(exec),
        table: Rc::clone(&forces),
    };
    let inner: Box<dyn Executor> = match &sim {
        Some(s) => Box::new(PlantExec::new(forcing, Rc::clone(s))),
        None => Box::new(forcing),
    };
    let mut exec = Shifted {
        inner: Boxed(inner),
        offset: Rc::clone(&offset),
    };
    let safe = config
        .safe
        .unwrap_or_else(|| SafeState::of_program(&program));
    let start_image = exec.image().to_vec();
    // The keeper passes scans on to nothing (a zero-sized value leaked
    // costs nothing); the caller's observer is called by the session.
    let nothing: &'static mut () = Box::leak(Box::new(()));
    let mut keeper = Keeper::new(
        &program,
        &start_image,
        config.retain.as_ref().map(|r| r.path.clone()),
        config.retain.as_ref().and_then(|r| r.every_ns),
        nothing,
    );
    if config.clock == ClockMode::RealTime {
        // A scan never waits for the disk.
        keeper = keeper.in_background();
    }
    let ranges = retain_ranges(&program);
    let mut retained = vec![0; ranges.iter().map(|r| r.len()).sum()];
    {
        let mut at = 0;
        for r in &ranges {
            if let (Some(src), Some(dst)) = (
                start_image.get(r.clone()),
                retained.get_mut(at..at + r.len()),
            ) {
                dst.copy_from_slice(src);
            }
            at += r.len();
        }
    }
    let clock = ClockHandle(Rc::new(RefCell::new(PausedClock {
        inner: config.monotonic,
        paused_ns: 0,
        since: None,
    })));
    let (limit, clients) = match mode {
        Mode::Served => (Limit::Unbounded, true),
        Mode::Here(limit) => (limit, false),
    };
    let mut core = Core {
        program: Arc::clone(&program),
        clients,
        rx,
        shared,
        forces,
        forces_shown: Arc::new(Vec::new()),
        offset,
        clock: clock.clone(),
        outside_stop: Arc::clone(&config.stop),
        extra,
        exchange,
        state: if config.running {
            State::Running
        } else {
            State::Stopped
        },
        steps: None,
        plc_time_ns: 0,
        scans: 0,
        published: 0,
        stats: CycleStats::default(),
        subs: Vec::new(),
        quit: false,
        restart: None,
        answers: Vec::new(),
        keeper,
        retain_ranges: ranges,
        retained,
        safe: safe.clone(),
        held: None,
        totals: Stats::default(),
        sim: sim.clone(),
        fault: None,
    };
    let has_retain = config.retain.is_some();
    let _ = ready.send(Ok(()));
    let cfg = RunConfig {
        cycle_time_ns: config.cycle_time_ns,
        clock: config.clock,
        limit,
    };
    let stop = Arc::clone(&config.stop);
    let mut error = None;
    // Stopped unless a limit, a fault or an error says otherwise.
    let mut end = End::Stopped;
    let mut last_fault: Option<automat_runtime::scan::FaultReport> = None;
    loop {
        if core.restart.take().is_some() {
            if let Some(s) = &sim {
                s.borrow_mut().resume();
            }
        }
        // A stopped session waits for a command before the next scan.
        if core.state != State::Running && !core.between(exec.image_mut(), true, false) {
            if core.restart.is_some() {
                continue;
            }
            break;
        }
        let report = {
            let mut clock = clock.clone();
            let (mut inputs, mut outputs) = (NoIo, NoIo);
            let mut observer = Observer { core: &mut core };
            let mut env = Env {
                clock: &mut clock,
                inputs: &mut inputs,
                outputs: &mut outputs,
                observer: &mut observer,
                stop: &stop,
            };
            run_safe(&mut exec, &cfg, &mut env, &safe)
        };
        if let Ok(r) = &report {
            core.totals.merge(&r.stats);
        }
        match report {
            Err(e) => {
                error = Some(e);
                end = End::Error;
                break;
            }
            Ok(r) => match r.end {
                RunEnd::Fault(f) => {
                    end = End::Fault;
                    last_fault = Some(automat_runtime::scan::FaultReport {
                        plc_time_ns: f.plc_time_ns.saturating_add(core.offset.get()),
                        ..(*f).clone()
                    });
                    if let Some(s) = &sim {
                        s.borrow_mut().safe_state(exec.image());
                    }
                    if let Some((_, to)) = core.steps.take() {
                        // Answered with the snapshot that shows the fault.
                        core.answers
                            .push((to, Err(Error::Refused(format!("runtime fault: {f}")))));
                    }
                    core.fault = Some(format!(
                        "{} (task {}, program instance {}, PLC time {})",
                        f.fault,
                        f.task,
                        f.instance,
                        automat_iec::format::format_duration(
                            f.plc_time_ns.saturating_add(core.offset.get()),
                            false
                        )
                    ));
                    core.state = State::Fault {
                        message: f.fault.message.clone(),
                        site: format!(
                            "{} in {} (task {}, program instance {}, PLC time {})",
                            f.fault.site.location,
                            f.fault.site.pou,
                            f.task,
                            f.instance,
                            automat_iec::format::format_duration(
                                f.plc_time_ns.saturating_add(core.offset.get()),
                                false
                            )
                        ),
                    };
                    core.plc_time_ns = f.plc_time_ns.saturating_add(core.offset.get());
                    if !config.wait_after_fault {
                        break;
                    }
                    if !core.between(exec.image_mut(), false, false) && core.restart.is_none() {
                        break;
                    }
                    // The next run continues PLC time one base period after
                    // the faulted scan.
                    let base = automat_runtime::schedule::Schedule::new(
                        &program.tasks,
                        config.cycle_time_ns,
                    )
                    .map_or(config.cycle_time_ns, |s| s.base_ns());
                    core.offset
                        .set(core.plc_time_ns.saturating_add(base.max(1)));
                }
                RunEnd::Observer(e) => {
                    error = Some(e);
                    end = End::Observer;
                    break;
                }
                RunEnd::Stopped => {
                    end = End::Stopped;
                    // The outputs are in the safe state: the plant is told.
                    if let Some(s) = &sim {
                        s.borrow_mut().safe_state(exec.image());
                    }
                    break;
                }
                RunEnd::Limit | RunEnd::TimeExhausted => {
                    end = End::Limit;
                    break;
                }
            },
        }
    }
    finish(core, &exec, error, has_retain, (end, last_fault))
}

fn finish(
    mut core: Core,
    exec: &impl Executor,
    error: Option<String>,
    has_retain: bool,
    (end, last_fault): (End, Option<automat_runtime::scan::FaultReport>),
) -> Final {
    // The last end-of-scan snapshot, after the writer thread is done.
    let last = core.keeper.finish();
    let retain = has_retain.then(|| RetainSaves {
        last,
        failures: core.keeper.failures,
        last_error: core.keeper.last_error.take(),
    });
    core.state = match core.state {
        State::Running => State::Stopped,
        s => s,
    };
    core.publish(exec.image());
    core.answer();
    if let Some(mut x) = core.exchange.take() {
        // The final image (in the safe state unless a limit ended the run).
        x.outputs(exec.image());
    }
    // Anyone still waiting learns that the session ended.
    while let Ok(req) = core.rx.try_recv() {
        let _ = req
            .reply
            .send(Err(Error::Gone("the PLC session has ended".into())));
    }
    if let Some((_, to)) = core.steps.take() {
        let _ = to.send(Err(Error::Gone("the PLC session has ended".into())));
    }
    Final {
        image: exec.image().to_vec(),
        snapshot: core
            .shared
            .snapshot
            .lock()
            .map_or_else(|p| Arc::clone(&p.into_inner()), |s| Arc::clone(&s)),
        error,
        fault: matches!(core.state, State::Fault { .. })
            .then(|| core.fault.take())
            .flatten(),
        fault_report: matches!(core.state, State::Fault { .. })
            .then_some(last_fault)
            .flatten(),
        retain,
        stats: std::mem::take(&mut core.totals),
        end,
    }
}
