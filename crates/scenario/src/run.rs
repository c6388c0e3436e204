//! Running a scenario on the virtual clock and judging its expectations.
//!
//! After each scan at PLC time t the values the scenario names are read
//! (the values after the previous scan are kept for `prev`, `rise`, `fall`
//! and `change`; before the first scan they are the initial values), then:
//! - `at T C`: at the first scan with t >= T (T itself when a scan falls
//!   on it), C must hold; not reached before the end of the run fails
//!   (T at or before the run's duration is judged on the final state).
//! - `C within W after A`: passes at the first scan in (A, A+W] where C
//!   holds; fails at the first scan with t >= A+W where it did not (or at
//!   the end of the run). After an event E, every occurrence at a scan t_e
//!   opens the window [t_e, t_e+W] (the scan of the event counts: the
//!   program has already seen it); a window still open when the run ends
//!   fails only when it ended within the run, and an event that never
//!   happened fails the expectation.
//! - `always C [during A..B]`: fails at the first scan in [A, B] (the whole
//!   run without `during`) where C does not hold.
//! - `C during A..B`: judged once, at the first scan with t >= B (or on the
//!   final state when B is at or before the run's duration).
//! - `X stable for D after A`: the value of X at the first scan at or after
//!   A (or at each occurrence of an event) must not change at any scan up
//!   to A+D.
//! - `count(C)` is the number of scans of the expectation's window where C
//!   held: [0, T] for `at T`, [A, B] for `during A..B` (the whole run for
//!   `always` without `during`).
//! - `when E [after D] then ACTION`: at every scan where the event E occurs,
//!   the action is scheduled D later (the next scan applies it).
//!
//! An expectation fails at most once: at its first violation. A runtime
//! fault of the program fails the scenario.

use crate::ast::{self, Anchor, Scenario, When};
use crate::check::{Cond, Ctx, LocatedWrite, NoPlant, Ref, Scope, Src};
use crate::eval::{same, show_f64, show_value, Frame, Val};
use automat_base::Diagnostic;
use automat_engine::Engine;
use automat_iec::format::format_duration;
use automat_ir::Program;
use automat_project::{bind, Action, Project, Sim};
use automat_runtime::trace::csv_cell;
use automat_runtime::{value, ClockMode, Executor, Limit, ScanObserver, SystemClock};
use automat_session::{run_here, Config, End, Parts, Watching};
use std::cell::RefCell;
use std::collections::VecDeque;
use std::io::Write;
use std::rc::Rc;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

/// One failed expectation (or a fault, or a refused plant command).
#[derive(Clone, Debug, PartialEq)]
pub struct Failure {
    /// The expectation as written (`expect at 2s M2S`), or what went wrong.
    pub what: String,
    /// Line in the scenario file (0 when not about a line).
    pub line: u32,
    pub at_ns: i64,
    pub reason: String,
    /// `name = value` of every name in the condition, at `at_ns`.
    pub values: String,
}

/// What a run came to.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    pub failures: Vec<Failure>,
    /// PLC time of the last scan.
    pub end_ns: i64,
}

/// The failures as `automat test` and `automat run --scenario` print them:
/// `FILE:LINE: expect ...`, `  failed at T: reason`, `  values: ...`.
pub fn describe(shown: &str, failures: &[Failure]) -> String {
    let mut details = String::new();
    for f in failures {
        let at = format_duration(f.at_ns, false);
        if f.line > 0 {
            details.push_str(&format!("{shown}:{}: {}\n", f.line, f.what));
        } else {
            details.push_str(&format!("{shown}: {}\n", f.what));
        }
        details.push_str(&format!("  failed at {at}: {}\n", f.reason));
        if !f.values.is_empty() {
            details.push_str(&format!("  values: {}\n", f.values));
        }
    }
    details
}

/// A window's start, resolved.
enum Start {
    Time(i64),
    Event(Cond),
}

/// When an expectation is judged, resolved.
enum Win {
    At(i64),
    Within { after: Start, within: i64 },
    Always { from: i64, to: Option<i64> },
    During { from: i64, to: i64 },
    Stable { after: Start, for_ns: i64 },
}

struct Check {
    win: Win,
    cond: Cond,
    /// The arguments of its `count(...)`s, their counters and their text.
    counts: Vec<Cond>,
    counters: Vec<f64>,
    count_texts: Vec<String>,
    text: String,
    line: u32,
    /// Indexes into the refs this condition names, for the failure values.
    names: Vec<usize>,
    /// Every ref it evaluates (its condition, counts and event), and
    /// whether it needs them after the previous scan too (`prev`, `rise`,
    /// ...): then they are read at every scan until it is done, else only
    /// at the scans it is judged at (see [`Judge::after_scan`]).
    reads: Vec<usize>,
    uses_prev: bool,
    done: bool,
    /// Event windows still open (their start times), oldest first.
    open: VecDeque<i64>,
    /// The anchor happened (an event) or was reached (a time).
    seen: bool,
    /// `stable`: the value the open windows hold to.
    reference: Val,
    /// The first scan time at which [`judge`] can do anything but answer
    /// `Open` (count, anchor, pass or fail): before it the check is
    /// skipped, so a scan judges only the lines due.
    wake_ns: i64,
}

/// A resolved `when` line.
struct React {
    event: Cond,
    delay_ns: i64,
    actions: Vec<(i64, Action)>,
    /// Its sets of indexed or indirect addresses (times after the firing).
    located: Vec<LocatedWrite>,
}

fn t(ns: i64) -> String {
    format_duration(ns, false)
}

fn show_val(v: Val) -> String {
    match v {
        Val::B(true) => "TRUE".into(),
        Val::B(false) => "FALSE".into(),
        Val::N(x) => show_f64(x),
    }
}

mod prepare;
pub use prepare::{check_expect, prepare, Prepared};

/// Judges the expectations and fires the reactions of one scenario, scan
/// by scan (see the module comment).
pub struct Judge {
    refs: Vec<Ref>,
    /// The values after this scan and after the previous one, by ref; an
    /// entry nobody evaluates at a scan is not read then (it keeps an older
    /// value that nothing looks at).
    vals: Vec<Val>,
    prev: Vec<Val>,
    /// The refs of the reactions' events, read at every scan.
    always: Vec<usize>,
    /// The scan (counted from 1; 0: before the first) at which each ref
    /// was last read.
    read_at: Vec<u64>,
    scans: u64,
    started: bool,
    checks: Vec<Check>,
    reactions: Vec<React>,
    failures: Vec<Failure>,
    last_ns: i64,
    duration_ns: i64,
    /// Sets of indexed or indirect addresses not yet due.
    pending: Vec<LocatedWrite>,
    /// The run's cycle time: a set due before the next scan is placed
    /// after this one.
    cycle_ns: i64,
}

/// A set whose indexed or indirect address lies outside its data file.
fn set_failure(w: &LocatedWrite, reason: String) -> Failure {
    Failure {
        what: format!("set {}", w.name),
        line: w.line,
        at_ns: w.at_ns,
        reason,
        values: String::new(),
    }
}

/// What one check comes to at a scan: nothing yet, passed, or failed.
enum Verdict {
    Open,
    Pass,
    Fail(String),
}

impl Judge {
    /// A judge of nothing (what is left where one was taken out).
    fn empty() -> Judge {
        Judge {
            refs: Vec::new(),
            vals: Vec::new(),
            prev: Vec::new(),
            always: Vec::new(),
            read_at: Vec::new(),
            scans: 0,
            started: false,
            checks: Vec::new(),
            reactions: Vec::new(),
            failures: Vec::new(),
            last_ns: 0,
            duration_ns: 0,
            pending: Vec::new(),
            cycle_ns: 0,
        }
    }

    /// The run's cycle time (the PLC time between two scans): a set of an
    /// indexed or indirect address finds its place in the image of the
    /// last scan before it is due.
    pub fn set_cycle(&mut self, cycle_ns: i64) {
        self.cycle_ns = cycle_ns;
    }

    /// The names the scenario reads.
    pub fn refs(&self) -> &[Ref] {
        &self.refs
    }

    /// The values before the first scan (for `prev`, `rise`, ...).
    pub fn start(&mut self, image: &[u8], sim: &Sim) {
        self.prev.clear();
        self.prev
            .extend(self.refs.iter().map(|r| r.read(image, sim)));
        self.vals.clone_from(&self.prev);
        self.read_at.iter_mut().for_each(|s| *s = self.scans);
        self.started = true;
    }

    fn values(&self, names: &[usize], image: &[u8], sim: &Sim) -> String {
        names
            .iter()
            .filter_map(|&i| self.refs.get(i))
            .map(|r| format!("{} = {}", r.name, r.show(image, sim)))
            .collect::<Vec<_>>()
            .join(", ")
    }

    fn fail(&mut self, k: usize, at: i64, reason: String, image: &[u8], sim: &Sim) {
        let Some(c) = self.checks.get(k) else { return };
        let mut values = self.values(&c.names, image, sim);
        for (text, n) in c.count_texts.iter().zip(&c.counters) {
            if !values.is_empty() {
                values.push_str(", ");
            }
            values.push_str(&format!("{text} = {n}"));
        }
        let f = Failure {
            what: format!("expect {}", c.text),
            line: c.line,
            at_ns: at,
            reason,
            values,
        };
        self.failures.push(f);
    }

    /// After the scan at `now`: reads the values, judges, fires reactions.
    pub fn after_scan(&mut self, now: i64, image: &[u8], sim: &RefCell<Sim>) {
        let step = self.cycle_ns.max(now.saturating_sub(self.last_ns));
        self.last_ns = now;
        self.scans += 1;
        {
            let s = sim.borrow();
            if !self.started {
                self.start(image, &s);
            } else {
                // Only what is evaluated at this scan (most expectations
                // wait for their time, or are done): the same verdicts as
                // reading every name every scan.
                let mut read = |i: usize| {
                    if let (Some(at), Some(r), Some(v)) = (
                        self.read_at.get_mut(i),
                        self.refs.get(i),
                        self.vals.get_mut(i),
                    ) {
                        if *at != self.scans {
                            *at = self.scans;
                            *v = r.read(image, &s);
                        }
                    }
                };
                self.always.iter().for_each(|&i| read(i));
                for c in &self.checks {
                    if !c.done && (now >= c.wake_ns || c.uses_prev) {
                        c.reads.iter().for_each(|&i| read(i));
                    }
                }
            }
        }
        for k in 0..self.checks.len() {
            let verdict = match self.checks.get_mut(k) {
                Some(c) if !c.done && now >= c.wake_ns => judge(c, now, &self.vals, &self.prev),
                _ => continue,
            };
            match verdict {
                Verdict::Open => {}
                Verdict::Pass => {
                    if let Some(c) = self.checks.get_mut(k) {
                        c.done = true;
                    }
                }
                Verdict::Fail(reason) => {
                    if let Some(c) = self.checks.get_mut(k) {
                        c.done = true;
                    }
                    self.fail(k, now, reason, image, &sim.borrow());
                }
            }
        }
        let frame = Frame {
            now: &self.vals,
            prev: &self.prev,
            counts: &[],
        };
        for r in &self.reactions {
            if r.event.truth(frame) {
                let mut s = sim.borrow_mut();
                let at = now.saturating_add(r.delay_ns);
                for (off, a) in &r.actions {
                    s.schedule(at.saturating_add(*off), a.clone());
                }
                self.pending.extend(r.located.iter().map(|w| LocatedWrite {
                    at_ns: at.saturating_add(w.at_ns),
                    ..w.clone()
                }));
            }
        }
        // The sets due before the next scan, at the places this image names.
        let horizon = now.saturating_add(step);
        let (due, later): (Vec<LocatedWrite>, Vec<LocatedWrite>) =
            std::mem::take(&mut self.pending)
                .into_iter()
                .partition(|w| w.at_ns <= horizon);
        self.pending = later;
        for w in due {
            match w.loc.place(image) {
                Ok(place) => sim.borrow_mut().schedule(
                    w.at_ns,
                    Action::Write {
                        place,
                        value: w.value,
                    },
                ),
                Err(e) => {
                    let f = set_failure(&w, e);
                    self.failures.push(f);
                }
            }
        }
        std::mem::swap(&mut self.vals, &mut self.prev);
    }

    /// How many expectations are still open (not yet passed or failed).
    pub fn open(&self) -> usize {
        self.checks.iter().filter(|c| !c.done).count()
    }

    /// The failures so far (a run that stopped early: what was still open
    /// is not judged), in time order.
    pub fn failures(self) -> Vec<Failure> {
        let mut f = self.failures;
        f.sort_by_key(|f| f.at_ns);
        f
    }

    /// Judges what is still open when the run ends (its last scan was at
    /// `last_ns`) and returns every failure, in time order.
    pub fn finish(mut self, image: &[u8], sim: &Sim) -> Vec<Failure> {
        let end = self.last_ns;
        let duration = self.duration_ns;
        // The values after the last scan (`after_scan` moved them); what
        // was not read then is read now (nothing changed them since).
        let mut vals = std::mem::take(&mut self.prev);
        for (i, r) in self.refs.iter().enumerate() {
            if let (Some(&at), Some(v)) = (self.read_at.get(i), vals.get_mut(i)) {
                if at != self.scans {
                    *v = r.read(image, sim);
                }
            }
        }
        for k in 0..self.checks.len() {
            let Some(c) = self.checks.get_mut(k) else {
                continue;
            };
            if c.done {
                continue;
            }
            c.done = true;
            let frame = Frame {
                now: &vals,
                prev: &vals,
                counts: &c.counters,
            };
            let reason = match &c.win {
                // The state at the end of the run is the state at its
                // duration: `expect at 60s` of a 60 s run is judged on it.
                Win::At(at) if *at <= duration => {
                    if c.cond.truth(frame) {
                        continue;
                    }
                    "it is FALSE at the end of the run".to_string()
                }
                Win::At(at) => format!("the run ends at {} before {}", t(duration), t(*at)),
                Win::During { to, .. } if *to <= duration => {
                    if c.cond.truth(frame) {
                        continue;
                    }
                    "it is FALSE at the end of the run".to_string()
                }
                Win::During { to, .. } => format!(
                    "the run ends at {} before the window ends at {}",
                    t(duration),
                    t(*to)
                ),
                Win::Within {
                    after: Start::Time(_),
                    ..
                } => format!("it did not become TRUE before the run ended at {}", t(end)),
                Win::Within { within, .. } => {
                    if !c.seen {
                        "its event never happened".to_string()
                    } else {
                        match c.open.front() {
                            Some(&s) if s.saturating_add(*within) <= duration => format!(
                                "after the event at {} it did not become TRUE before the run ended at {}",
                                t(s),
                                t(end)
                            ),
                            _ => continue,
                        }
                    }
                }
                Win::Always { .. } => continue,
                Win::Stable {
                    after: Start::Time(a),
                    for_ns,
                } => {
                    if *a > duration {
                        format!("the run ends at {} before {}", t(duration), t(*a))
                    } else if a.saturating_add(*for_ns) > duration {
                        format!(
                            "the run ends at {} before the window ends at {}",
                            t(duration),
                            t(a.saturating_add(*for_ns))
                        )
                    } else {
                        continue;
                    }
                }
                Win::Stable { .. } => {
                    if c.seen {
                        continue;
                    }
                    "its event never happened".to_string()
                }
            };
            self.fail(k, end, reason, image, sim);
        }
        let mut failures = self.failures;
        failures.sort_by_key(|f| f.at_ns);
        failures
    }
}

/// Counts, then judges, one open check after the scan at `now`.
fn judge(c: &mut Check, now: i64, vals: &[Val], prev: &[Val]) -> Verdict {
    let counting = match &c.win {
        Win::At(at) => now <= *at,
        Win::Always { from, to } => now >= *from && to.is_none_or(|b| now <= b),
        Win::During { from, to } => now >= *from && now <= *to,
        _ => false,
    };
    if counting && !c.counts.is_empty() {
        let f = Frame {
            now: vals,
            prev,
            counts: &[],
        };
        for (n, arg) in c.counters.iter_mut().zip(&c.counts) {
            if arg.truth(f) {
                *n += 1.0;
            }
        }
    }
    let f = Frame {
        now: vals,
        prev,
        counts: &c.counters,
    };
    match &c.win {
        Win::At(at) if now >= *at => {
            if c.cond.truth(f) {
                Verdict::Pass
            } else {
                Verdict::Fail("it is FALSE".into())
            }
        }
        Win::At(_) => Verdict::Open,
        Win::Within {
            after: Start::Time(after),
            within,
        } => {
            let end = after.saturating_add(*within);
            if c.cond.truth(f) && now > *after && now <= end {
                Verdict::Pass
            } else if now >= end {
                Verdict::Fail(format!(
                    "it did not become TRUE in ({}, {}]",
                    t(*after),
                    t(end)
                ))
            } else {
                Verdict::Open
            }
        }
        Win::Within {
            after: Start::Event(ev),
            within,
        } => {
            let happened = ev.truth(f);
            c.seen |= happened;
            let missed = |s: i64| {
                Verdict::Fail(format!(
                    "after the event at {} it did not become TRUE in [{}, {}]",
                    t(s),
                    t(s),
                    t(s.saturating_add(*within))
                ))
            };
            // A window that ended between the last scan and this one.
            if let Some(&s) = c.open.front() {
                if s.saturating_add(*within) < now {
                    return missed(s);
                }
            }
            if c.cond.truth(f) {
                // Every open window (and one opening now) is satisfied.
                c.open.clear();
                return Verdict::Open;
            }
            if happened {
                c.open.push_back(now);
            }
            match c.open.front() {
                Some(&s) if now >= s.saturating_add(*within) => missed(s),
                _ => Verdict::Open,
            }
        }
        Win::Always { from, to } => {
            let inside = now >= *from && to.is_none_or(|b| now <= b);
            if inside && !c.cond.truth(f) {
                Verdict::Fail("it is FALSE".into())
            } else if to.is_some_and(|b| now >= b) {
                Verdict::Pass
            } else {
                Verdict::Open
            }
        }
        Win::During { to, .. } => {
            if now < *to {
                Verdict::Open
            } else if c.cond.truth(f) {
                Verdict::Pass
            } else {
                Verdict::Fail("it is FALSE at the end of the window".into())
            }
        }
        Win::Stable {
            after: Start::Time(a),
            for_ns,
        } => {
            let cur = c.cond.eval(f);
            let end = a.saturating_add(*for_ns);
            if now < *a {
                Verdict::Open
            } else if !c.seen {
                c.seen = true;
                c.reference = cur;
                if now >= end {
                    Verdict::Pass
                } else {
                    Verdict::Open
                }
            } else if now > end {
                // The window ended between the last scan and this one.
                Verdict::Pass
            } else if !same(cur, c.reference) {
                Verdict::Fail(format!(
                    "it changed from {} to {} (stable since {})",
                    show_val(c.reference),
                    show_val(cur),
                    t(*a)
                ))
            } else if now >= end {
                Verdict::Pass
            } else {
                Verdict::Open
            }
        }
        Win::Stable {
            after: Start::Event(ev),
            for_ns,
        } => {
            let cur = c.cond.eval(f);
            while c
                .open
                .front()
                .is_some_and(|&s| s.saturating_add(*for_ns) < now)
            {
                c.open.pop_front();
            }
            if let Some(&s) = c.open.front() {
                if !same(cur, c.reference) {
                    return Verdict::Fail(format!(
                        "it changed from {} to {}, {} after the event at {}",
                        show_val(c.reference),
                        show_val(cur),
                        t(now.saturating_sub(s)),
                        t(s)
                    ));
                }
            }
            if ev.truth(f) {
                c.seen = true;
                c.open.push_back(now);
                c.reference = cur;
            }
            Verdict::Open
        }
    }
}

/// A trace column.
struct Column {
    name: String,
    src: ColSrc,
}

/// Where a trace column's cells come from.
enum ColSrc {
    Src(Src),
    /// The active steps of a chart (`steps(OWNER)`: a band in the plot).
    Steps(automat_runtime::trace::Column),
}

/// Judges every scan and writes the trace rows into a buffer (the run's
/// session owns its observer, so it cannot borrow the caller's writer;
/// the buffer goes to the writer after the run).
struct Observer {
    sim: Rc<RefCell<Sim>>,
    judge: Judge,
    trace: Option<(Vec<Column>, Vec<u8>)>,
    header_written: bool,
}

impl Observer {
    fn write_row(&mut self, now: i64, image: &[u8]) -> Result<(), String> {
        let Some((cols, out)) = &mut self.trace else {
            return Ok(());
        };
        let sim = self.sim.borrow();
        let mut line = String::new();
        if !self.header_written {
            self.header_written = true;
            line.push_str("time");
            for c in cols.iter() {
                line.push(',');
                line.push_str(&csv_cell(&c.name));
            }
            line.push('\n');
        }
        line.push_str(&t(now));
        for c in cols.iter() {
            line.push(',');
            let cell = match &c.src {
                ColSrc::Src(Src::Place(p)) => value::format(image, p),
                ColSrc::Src(Src::Located(l)) => l.format(image),
                ColSrc::Src(Src::Signal(i)) => show_value(sim.plant().get(*i)),
                ColSrc::Src(Src::Quantity(i)) => show_f64(sim.plant().quantity(*i)),
                ColSrc::Steps(c) => c.cell(image),
            };
            line.push_str(&csv_cell(&cell));
        }
        line.push('\n');
        out.write_all(line.as_bytes()).map_err(|e| e.to_string())
    }
}

impl ScanObserver for Observer {
    fn after_scan(&mut self, now: i64, image: &[u8]) -> Result<(), String> {
        self.judge.after_scan(now, image, &self.sim);
        self.write_row(now, image)
    }
}

/// The columns of a scenario trace: every signal (bound: its variable),
/// every quantity, the active steps of every chart, then the other names
/// the expectations use.
fn columns(sim: &Sim, program: &Program, refs: &[Ref]) -> Vec<Column> {
    let plant = sim.plant();
    let mut cols: Vec<Column> = plant
        .signals()
        .iter()
        .enumerate()
        .map(|(i, s)| Column {
            name: s.name.to_string(),
            src: ColSrc::Src(
                sim.binding_of(i)
                    .map_or(Src::Signal(i), |b| Src::Place(b.place.clone())),
            ),
        })
        .collect();
    cols.extend(plant.quantities().iter().enumerate().map(|(i, q)| Column {
        name: format!("plant.{}", q.name),
        src: ColSrc::Src(Src::Quantity(i)),
    }));
    cols.extend(
        automat_project::steps::charts(program)
            .iter()
            .map(|chart| Column {
                name: chart.column(),
                src: ColSrc::Steps(chart.trace_column()),
            }),
    );
    for r in refs {
        if !cols.iter().any(|c| c.name.eq_ignore_ascii_case(&r.name)) {
            cols.push(Column {
                name: r.name.clone(),
                src: ColSrc::Src(r.src.clone()),
            });
        }
    }
    cols
}

/// Runs `scn` against the project's plant and `program`. Errors are diagnostics of the project file
/// (bindings) or of the scenario (names, types). With `trace`, one CSV row
/// per scan is written to it.
pub fn run<W: Write>(
    program: &Program,
    project: &Project,
    scn: &Scenario,
    trace: Option<W>,
) -> Result<Outcome, Vec<Diagnostic>> {
    run_on(program, Engine::new(program.clone()), project, scn, trace)
}

/// [`run`] on a given backend `exec` built from `program` (the
/// interpreter, the JIT: both give the same trace; benchmarks compare
/// them). `exec` starts cold.
pub fn run_on<E: Executor + 'static, W: Write>(
    program: &Program,
    exec: E,
    project: &Project,
    scn: &Scenario,
    trace: Option<W>,
) -> Result<Outcome, Vec<Diagnostic>> {
    let (plant, bindings) = match (project.new_plant()?, &project.plant) {
        (Some(plant), Some(spec)) => {
            let (bindings, diags) = bind(spec, plant.as_ref(), program);
            let Some(bindings) = bindings else {
                return Err(diags);
            };
            (plant, bindings)
        }
        _ => (
            Box::new(NoPlant) as Box<dyn automat_plant::Plant>,
            Vec::new(),
        ),
    };
    let scope = Scope {
        program,
        plant: plant.as_ref(),
        bindings: &bindings,
    };
    let Prepared { actions, mut judge } = prepare(&scope, scn)?;
    judge.set_cycle(project.cycle_time_ns);
    let seed = scn
        .seed
        .or(project.plant.as_ref().map(|p| p.seed))
        .unwrap_or(1);
    let mut sim = Sim::new(plant, bindings, seed);
    for (at, a) in actions {
        sim.schedule(at, a);
    }
    let cols = columns(&sim, program, judge.refs());
    let sim = Rc::new(RefCell::new(sim));
    let obs = Rc::new(RefCell::new(Observer {
        sim: Rc::clone(&sim),
        judge,
        trace: trace.is_some().then(|| (cols, Vec::new())),
        header_written: false,
    }));
    obs.borrow_mut().judge.start(exec.image(), &sim.borrow());
    // The PLC session's scan loop, on this thread, to the scenario's end.
    let config = Config {
        cycle_time_ns: project.cycle_time_ns,
        clock: ClockMode::Virtual,
        monotonic: Box::new(SystemClock::new()),
        running: true,
        stop: Arc::new(AtomicBool::new(false)),
        retain: None,
        safe: None,
        realtime: None,
        wait_after_fault: false,
    };
    let parts = Parts {
        exec: Box::new(exec),
        sim: Some(Rc::clone(&sim)),
        observer: Some(Box::new(Watching(Rc::clone(&obs)))),
        exchange: None,
    };
    let end = run_here(
        Arc::new(program.clone()),
        config,
        parts,
        Limit::Duration(scn.duration_ns),
    );
    // The session dropped its handle on the observer when it ended.
    let mut obs = match Rc::try_unwrap(obs) {
        Ok(cell) => cell.into_inner(),
        Err(shared) => Observer {
            sim: Rc::clone(&sim),
            judge: std::mem::replace(&mut shared.borrow_mut().judge, Judge::empty()),
            trace: shared.borrow_mut().trace.take(),
            header_written: true,
        },
    };
    let image = end.image;
    let mut failures = Vec::new();
    let mut ended = true;
    match end.end {
        End::Error => failures.push(Failure {
            what: "the run".into(),
            line: 0,
            at_ns: 0,
            reason: end.error.unwrap_or_default(),
            values: String::new(),
        }),
        End::Fault => failures.push(Failure {
            what: "the program".into(),
            line: 0,
            at_ns: end.snapshot.plc_time_ns,
            reason: format!("runtime fault: {}", end.fault.unwrap_or_default()),
            values: String::new(),
        }),
        End::Observer => failures.push(Failure {
            what: "the trace".into(),
            line: 0,
            at_ns: obs.judge.last_ns,
            reason: end.error.unwrap_or_default(),
            values: String::new(),
        }),
        End::Limit | End::Stopped => ended = false,
    }
    let end_ns = obs.judge.last_ns;
    if let (Some((_, rows)), Some(mut w)) = (obs.trace.take(), trace) {
        if let Err(e) = w.write_all(&rows).and_then(|()| w.flush()) {
            failures.push(Failure {
                what: "the trace".into(),
                line: 0,
                at_ns: end_ns,
                reason: e.to_string(),
                values: String::new(),
            });
        }
    }
    let Observer { judge, .. } = obs;
    if ended {
        // The expectations met before the run stopped keep their verdicts;
        // what was still open is not judged.
        failures.extend(judge.failures);
    } else {
        failures.extend(judge.finish(&image, &sim.borrow()));
    }
    // A plant written in ST whose program faulted froze there: what the
    // scenario saw after it is no test of the controller.
    if let Some(why) = sim.borrow().plant().fault() {
        failures.push(Failure {
            what: "the plant".into(),
            line: 0,
            at_ns: sim.borrow().plant_fault_ns.unwrap_or(end_ns),
            reason: why,
            values: String::new(),
        });
    }
    for (at, e) in &sim.borrow().errors {
        failures.push(Failure {
            what: "a plant command".into(),
            line: 0,
            at_ns: *at,
            reason: e.clone(),
            values: String::new(),
        });
    }
    failures.sort_by_key(|f| f.at_ns);
    Ok(Outcome { failures, end_ns })
}
