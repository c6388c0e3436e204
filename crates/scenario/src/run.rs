//! Running a scenario on the virtual clock and judging its expectations.
//!
//! When an expectation is decided (after each scan at PLC time t):
//! - `at T C`: at the first scan with t >= T (T itself when a scan falls
//!   on it), C must hold; not reached before the end of the run fails.
//! - `C within W after A`: passes at the first scan in (A, A+W] where C
//!   holds; fails at the first scan with t >= A+W where it did not (or at
//!   the end of the run).
//! - `always C [during A..B]`: fails at the first scan in [A, B] (the whole
//!   run without `during`) where C does not hold.
//!
//! A runtime fault of the program fails the scenario.

use crate::ast::{Scenario, When};
use crate::check::{show_f64, show_value, Cond, Ref, Scope, Src, Val};
use automat_base::{Code, Diagnostic, Span};
use automat_engine::Engine;
use automat_iec::format::format_duration;
use automat_ir::Program;
use automat_project::{bind, PlantExec, Project, Sim};
use automat_runtime::io::NoIo;
use automat_runtime::scan::Env;
use automat_runtime::trace::csv_cell;
use automat_runtime::{
    run as run_scan, value, ClockMode, Executor, Limit, RunConfig, RunEnd, ScanObserver,
    SystemClock,
};
use std::cell::RefCell;
use std::io::Write;
use std::rc::Rc;
use std::sync::atomic::AtomicBool;

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

struct Check {
    when: When,
    cond: Cond,
    text: String,
    line: u32,
    /// Indexes into the refs this condition names, for the failure values.
    names: Vec<usize>,
    done: bool,
}

fn cond_refs(c: &Cond, out: &mut Vec<usize>) {
    match c {
        Cond::Ref(i) if !out.contains(i) => out.push(*i),
        Cond::Not(x) => cond_refs(x, out),
        Cond::Logic(_, a, b) | Cond::Cmp(_, a, b) => {
            cond_refs(a, out);
            cond_refs(b, out);
        }
        _ => {}
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

struct Observer<W: Write> {
    sim: Rc<RefCell<Sim>>,
    refs: Vec<Ref>,
    vals: Vec<Val>,
    checks: Vec<Check>,
    failures: Vec<Failure>,
    last_ns: i64,
    trace: Option<(Vec<Column>, W)>,
    header_written: bool,
    duration_ns: i64,
}

fn t(ns: i64) -> String {
    format_duration(ns, false)
}

impl<W: Write> Observer<W> {
    fn values(&self, names: &[usize], image: &[u8]) -> String {
        let sim = self.sim.borrow();
        names
            .iter()
            .filter_map(|&i| self.refs.get(i))
            .map(|r| format!("{} = {}", r.name, r.show(image, &sim)))
            .collect::<Vec<_>>()
            .join(", ")
    }

    fn fail(&mut self, k: usize, at: i64, reason: String, image: &[u8]) {
        let Some(c) = self.checks.get(k) else { return };
        let f = Failure {
            what: format!("expect {}", c.text),
            line: c.line,
            at_ns: at,
            reason,
            values: self.values(&c.names, image),
        };
        self.failures.push(f);
    }

    fn judge(&mut self, now: i64, image: &[u8]) {
        for k in 0..self.checks.len() {
            let Some(c) = self.checks.get(k) else {
                continue;
            };
            if c.done {
                continue;
            }
            let holds = c.cond.truth(&self.vals);
            let verdict = match c.when {
                When::At(at) if now >= at => Some((!holds).then(|| "it is FALSE".to_string())),
                When::At(_) => None,
                When::Within { after, within } => {
                    let end = after.saturating_add(within);
                    if holds && now > after && now <= end {
                        Some(None)
                    } else if now >= end {
                        Some(Some(format!(
                            "it did not become TRUE in ({}, {}]",
                            t(after),
                            t(end)
                        )))
                    } else {
                        None
                    }
                }
                When::Always { from, to } => {
                    let inside = now >= from && to.is_none_or(|b| now <= b);
                    if inside && !holds {
                        Some(Some("it is FALSE".to_string()))
                    } else if to.is_some_and(|b| now >= b) {
                        Some(None)
                    } else {
                        None
                    }
                }
            };
            if let Some(v) = verdict {
                if let Some(c) = self.checks.get_mut(k) {
                    c.done = true;
                }
                if let Some(reason) = v {
                    self.fail(k, now, reason, image);
                }
            }
        }
    }

    /// Expectations still open when the run ends.
    fn finish(&mut self, image: &[u8]) {
        let end = self.last_ns;
        for k in 0..self.checks.len() {
            let Some(c) = self.checks.get(k) else {
                continue;
            };
            if c.done {
                continue;
            }
            let reason = match c.when {
                // The state at the end of the run is the state at its
                // duration: `expect at 60s` of a 60 s run is judged on it.
                When::At(at) if at <= self.duration_ns => {
                    if let Some(c) = self.checks.get_mut(k) {
                        c.done = true;
                    }
                    if self.checks.get(k).is_some_and(|c| c.cond.truth(&self.vals)) {
                        continue;
                    }
                    "it is FALSE at the end of the run".to_string()
                }
                When::At(at) => format!("the run ends at {} before {}", t(self.duration_ns), t(at)),
                When::Within { .. } => {
                    format!("it did not become TRUE before the run ended at {}", t(end))
                }
                When::Always { .. } => continue,
            };
            self.fail(k, end, reason, image);
        }
    }

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

impl<W: Write> ScanObserver for Observer<W> {
    fn after_scan(&mut self, now: i64, image: &[u8]) -> Result<(), String> {
        self.last_ns = now;
        {
            let sim = self.sim.borrow();
            self.vals.clear();
            self.vals
                .extend(self.refs.iter().map(|r| r.read(image, &sim)));
        }
        self.judge(now, image);
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
pub fn run_on<E: Executor, W: Write>(
    program: &Program,
    exec: E,
    project: &Project,
    scn: &Scenario,
    trace: Option<W>,
) -> Result<Outcome, Vec<Diagnostic>> {
    let plant = project.new_plant()?.ok_or_else(|| {
        vec![Diagnostic::error(
            Code::E301,
            Span::new(project.file, 0, 0),
            "the project has no [plant]: a scenario needs a plant model",
        )]
    })?;
    let (bindings, diags) = bind(
        project.plant.as_ref().ok_or_else(Vec::new)?,
        plant.as_ref(),
        program,
    );
    let Some(bindings) = bindings else {
        return Err(diags);
    };
    let scope = Scope {
        program,
        plant: plant.as_ref(),
        bindings: &bindings,
    };
    let mut errors = Vec::new();
    let mut refs = Vec::new();
    let mut checks = Vec::new();
    for e in &scn.expects {
        match scope.condition(&e.cond, &mut refs) {
            Ok(cond) => {
                let mut names = Vec::new();
                cond_refs(&cond, &mut names);
                checks.push(Check {
                    when: e.when.clone(),
                    cond,
                    text: e.text.clone(),
                    line: e.line,
                    names,
                    done: false,
                });
            }
            Err(d) => errors.push(d),
        }
    }
    let mut actions = Vec::new();
    for a in &scn.actions {
        match scope.action(a) {
            Ok(list) => actions.extend(list),
            Err(d) => errors.push(d),
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    let seed = scn
        .seed
        .or(project.plant.as_ref().map(|p| p.seed))
        .unwrap_or(1);
    let mut sim = Sim::new(plant, bindings, seed);
    for (at, a) in actions {
        sim.schedule(at, a);
    }
    let cols = columns(&sim, program, &refs);
    let sim = Rc::new(RefCell::new(sim));
    let mut obs = Observer {
        sim: Rc::clone(&sim),
        vals: Vec::with_capacity(refs.len()),
        refs,
        checks,
        failures: Vec::new(),
        last_ns: 0,
        trace: trace.map(|w| (cols, w)),
        header_written: false,
        duration_ns: scn.duration_ns,
    };
    let mut exec = PlantExec::new(exec, Rc::clone(&sim));
    let cfg = RunConfig {
        cycle_time_ns: project.cycle_time_ns,
        clock: ClockMode::Virtual,
        limit: Limit::Duration(scn.duration_ns),
    };
    let stop = AtomicBool::new(false);
    let mut clock = SystemClock::new();
    let (mut inputs, mut outputs) = (NoIo, NoIo);
    let report = {
        let mut env = Env {
            clock: &mut clock,
            inputs: &mut inputs,
            outputs: &mut outputs,
            observer: &mut obs,
            stop: &stop,
        };
        run_scan(&mut exec, &cfg, &mut env)
    };
    let image = automat_runtime::Executor::image(&exec).to_vec();
    match report {
        Err(e) => obs.failures.push(Failure {
            what: "the run".into(),
            line: 0,
            at_ns: 0,
            reason: e,
            values: String::new(),
        }),
        Ok(r) => match r.end {
            RunEnd::Fault(f) => obs.failures.push(Failure {
                what: "the program".into(),
                line: 0,
                at_ns: f.plc_time_ns,
                reason: format!("runtime fault: {f}"),
                values: String::new(),
            }),
            RunEnd::Observer(e) => obs.failures.push(Failure {
                what: "the trace".into(),
                line: 0,
                at_ns: obs.last_ns,
                reason: e,
                values: String::new(),
            }),
            _ => obs.finish(&image),
        },
    }
    for (at, e) in &sim.borrow().errors {
        obs.failures.push(Failure {
            what: "a plant command".into(),
            line: 0,
            at_ns: *at,
            reason: e.clone(),
            values: String::new(),
        });
    }
    if let Some((_, mut w)) = obs.trace.take() {
        let _ = w.flush();
    }
    obs.failures.sort_by_key(|f| f.at_ns);
    Ok(Outcome {
        failures: obs.failures,
        end_ns: obs.last_ns,
    })
}
