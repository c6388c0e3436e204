//! The real-time view of `automat run`: a status of the program's watched
//! variables and forces, and of a project's inputs, outputs and plant
//! quantities (redrawn on a terminal, one line a second otherwise), and
//! commands typed on standard input. Program commands go to the PLC
//! session at once (`watch PATH`, `unwatch PATH|all`, `write PATH VALUE`,
//! `force PATH VALUE`, `unforce PATH|all`, `help`); plant commands are
//! applied at the next scan: `press Pornire [for 200ms]`, `release
//! Pornire`, `set l2 1` (on a sensor or actuator: stuck at that value),
//! `stuck l2 = TRUE`, `unstick l2`, `noise Temp 20`, `plant CMD key=value`;
//! `quit` stops.
use automat_ir::Program;
use automat_plant::{Dir, Value};
use automat_project::steps::{charts, Chart};
use automat_project::Sim;
use automat_runtime::clock::{Monotonic, SystemClock};
use automat_runtime::stats::Stats;
use automat_scenario::ast::{self, ActionKind};
use automat_scenario::check::Scope;
use automat_scenario::eval::{show_f64, show_value};
use std::cell::RefCell;
use std::io::{BufRead, IsTerminal, Write};
use std::rc::Rc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{channel, Receiver, Sender};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// The system clock run `speed` times faster: PLC time and plant time
/// advance together, so the plant behaves as in real time, only sooner.
pub struct ScaledClock {
    inner: SystemClock,
    speed: f64,
}

impl ScaledClock {
    pub fn new(speed: f64) -> ScaledClock {
        ScaledClock {
            inner: SystemClock::new(),
            speed,
        }
    }
}

impl Monotonic for ScaledClock {
    fn now_ns(&mut self) -> i64 {
        (self.inner.now_ns() as f64 * self.speed) as i64
    }
    fn sleep_until(&mut self, deadline_ns: i64) {
        self.inner
            .sleep_until((deadline_ns as f64 / self.speed) as i64);
    }
}

/// What the console thread (typing) and the view (drawing, on the scan
/// thread) share: locked only to change or copy it, never across a scan.
#[derive(Default)]
pub struct Console {
    /// Watched paths with their places, in the order given.
    pub watch: Vec<(String, automat_runtime::Place)>,
    /// The session's forces after the last force command.
    pub forces: Vec<(String, String)>,
    /// Answers to commands not shown yet.
    pub messages: Vec<String>,
}

pub struct Live {
    program: Program,
    console: Arc<Mutex<Console>>,
    /// The program's SFC charts, whose active steps the view lists.
    charts: Vec<Chart>,
    commands: Receiver<String>,
    stop: Arc<AtomicBool>,
    terminal: bool,
    last_draw: Option<Instant>,
    scans: u64,
    speed: f64,
    message: String,
    /// Scan time min/avg/max (ns, on the run's clock) and overruns, as
    /// the runtime last reported them.
    cycle: Option<(i64, i64, i64, u64)>,
}

const HELP: &str = "commands: press NAME [for TIME] | release NAME | set NAME VALUE | stuck NAME VALUE | unstick NAME | plant CMD key=value | quit";
const PROGRAM_HELP: &str = "program: watch PATH | unwatch PATH|all | write PATH VALUE | force PATH VALUE | unforce PATH|all | help | quit";

/// Variables of the program shown before any `watch`: the elementary
/// variables of the program instances and the globals, at most this many.
const DEFAULT_WATCH: usize = 12;

/// The program's own elementary variables, for the view's default list.
pub fn default_watch(program: &Program) -> Vec<(String, automat_runtime::Place)> {
    let mut out = Vec::new();
    for root in automat_session::symbols::tree(program, "").unwrap_or_default() {
        let level = if root.children.is_empty() {
            vec![root]
        } else {
            root.children
        };
        for n in level {
            if out.len() >= DEFAULT_WATCH {
                return out;
            }
            if n.children.is_empty() && n.more == 0 {
                if let Ok(p) = automat_runtime::resolve(program, &n.path) {
                    out.push((n.path, p));
                }
            }
        }
    }
    out
}

/// Reads standard input: program commands go to the session at once,
/// the others to the view (plant commands, applied at the next scan).
pub fn console(
    session: Arc<automat_session::Session>,
    shared: Arc<Mutex<Console>>,
    to_view: Sender<String>,
    stop: Arc<AtomicBool>,
    plant: bool,
) {
    eprintln!("{PROGRAM_HELP}");
    if plant {
        eprintln!("{HELP}");
    }
    std::thread::spawn(move || {
        let stdin = std::io::stdin();
        for line in stdin.lock().lines() {
            let Ok(line) = line else { break };
            let t = line.trim();
            let (word, rest) = t.split_once(char::is_whitespace).unwrap_or((t, ""));
            let rest = rest.trim();
            let answer = match word.to_ascii_lowercase().as_str() {
                "" => continue,
                "quit" | "q" => {
                    stop.store(true, Ordering::Relaxed);
                    break;
                }
                "help" | "?" => {
                    if plant {
                        format!("{PROGRAM_HELP} || {HELP}")
                    } else {
                        PROGRAM_HELP.to_string()
                    }
                }
                "watch" => match session.place(rest) {
                    Ok(p) => {
                        let mut c = shared.lock().unwrap_or_else(|p| p.into_inner());
                        c.watch.retain(|(n, _)| !n.eq_ignore_ascii_case(rest));
                        c.watch.push((rest.to_string(), p));
                        format!("ok: watching {rest}")
                    }
                    Err(e) => format!("`{t}`: {e}"),
                },
                "unwatch" => {
                    let mut c = shared.lock().unwrap_or_else(|p| p.into_inner());
                    let before = c.watch.len();
                    if rest.eq_ignore_ascii_case("all") {
                        c.watch.clear();
                    } else {
                        c.watch.retain(|(n, _)| !n.eq_ignore_ascii_case(rest));
                    }
                    if c.watch.len() == before {
                        format!("`{t}`: {rest} is not watched")
                    } else {
                        format!("ok: {t}")
                    }
                }
                "write" | "force" => {
                    let (path, value) = rest.split_once(char::is_whitespace).unwrap_or((rest, ""));
                    let done = if word.eq_ignore_ascii_case("write") {
                        session.write(path, value.trim())
                    } else {
                        session.force(path, value.trim())
                    };
                    match done {
                        Ok(()) => format!("ok: {t}"),
                        Err(e) => format!("`{t}`: {e}"),
                    }
                }
                "unforce" => {
                    let done = if rest.eq_ignore_ascii_case("all") {
                        session.unforce_all()
                    } else {
                        session.unforce(rest)
                    };
                    match done {
                        Ok(()) => format!("ok: {t}"),
                        Err(e) => format!("`{t}`: {e}"),
                    }
                }
                _ if plant => {
                    if to_view.send(line).is_err() {
                        break;
                    }
                    continue;
                }
                _ => format!("`{t}`: unknown command; {PROGRAM_HELP}"),
            };
            let mut c = shared.lock().unwrap_or_else(|p| p.into_inner());
            c.forces = session.forces();
            if c.messages.len() < 64 {
                c.messages.push(answer);
            }
        }
    });
}

impl Live {
    /// The view of a run without a session: every typed line is a plant
    /// command.
    pub fn start(
        program: &Program,
        _sim: Rc<RefCell<Sim>>,
        stop: Arc<AtomicBool>,
        speed: f64,
    ) -> Live {
        let (tx, rx) = channel();
        std::thread::spawn(move || {
            let stdin = std::io::stdin();
            for line in stdin.lock().lines() {
                let Ok(line) = line else { break };
                if tx.send(line).is_err() {
                    break;
                }
            }
        });
        eprintln!("{HELP}");
        let console = Arc::new(Mutex::new(Console::default()));
        Live::new(program, rx, console, stop, speed)
    }

    /// The view of a session's run: `commands` are the plant commands the
    /// [`console`] passes on.
    pub fn new(
        program: &Program,
        commands: Receiver<String>,
        console: Arc<Mutex<Console>>,
        stop: Arc<AtomicBool>,
        speed: f64,
    ) -> Live {
        Live {
            console,
            program: program.clone(),
            charts: charts(program),
            commands,
            stop,
            terminal: std::io::stdout().is_terminal(),
            last_draw: None,
            scans: 0,
            speed,
            message: String::new(),
            cycle: None,
        }
    }

    fn command(&mut self, line: &str, now: i64, sim: &Rc<RefCell<Sim>>) {
        let line = line.trim();
        if line.is_empty() {
            return;
        }
        if line.eq_ignore_ascii_case("quit") || line.eq_ignore_ascii_case("q") {
            self.stop.store(true, Ordering::Relaxed);
            return;
        }
        let kind = match automat_scenario::parse::parse_action(line, automat_base::FileId(0)) {
            Ok(k) => k,
            Err(d) => {
                self.message = format!("`{line}`: {}", d.message);
                return;
            }
        };
        let actions = {
            let s = sim.borrow();
            let plant = s.plant();
            // `set` on a sensor or actuator forces it: a toggled switch.
            let kind = match kind {
                ActionKind::Set(n, v, sp)
                    if plant.signals().iter().any(|x| {
                        x.name.eq_ignore_ascii_case(&n.text) && x.dir != Dir::Operator
                    }) =>
                {
                    ActionKind::Stuck(n, v, sp)
                }
                k => k,
            };
            let scope = Scope {
                program: &self.program,
                plant,
                bindings: s.bindings(),
            };
            scope.action(&ast::Action {
                at_ns: now,
                kind,
                line: 0,
            })
        };
        match actions {
            Ok(list) => {
                let mut s = sim.borrow_mut();
                for (at, a) in list {
                    s.schedule(at, a);
                }
                self.message = format!("ok: {line}");
            }
            Err(d) => self.message = format!("`{line}`: {}", d.message),
        }
    }

    /// The watched variables and the forces.
    fn program_lines(&self, image: &[u8]) -> Vec<String> {
        let c = self.console.lock().unwrap_or_else(|p| p.into_inner());
        let mut out = Vec::new();
        if !c.watch.is_empty() {
            let each: Vec<String> = c
                .watch
                .iter()
                .map(|(n, p)| format!("{n}={}", automat_runtime::value::format(image, p)))
                .collect();
            out.push(format!("  vars:  {}", each.join(" ")));
        }
        if !c.forces.is_empty() {
            let each: Vec<String> = c.forces.iter().map(|(n, v)| format!("{n}={v}")).collect();
            out.push(format!("  FORCED: {}", each.join(" ")));
        }
        out
    }

    fn plc_status(&self, now: i64, image: &[u8]) -> Vec<String> {
        let head = format!(
            "PLC {} | scans {}{}{}",
            automat_iec::format::format_duration(now, false),
            self.scans,
            cycle_text(self.cycle),
            if self.speed == 1.0 {
                String::new()
            } else {
                format!(" | speed {}x", self.speed)
            }
        );
        std::iter::once(head)
            .chain(self.program_lines(image))
            .chain(steps_line(&self.charts, image))
            .collect()
    }

    fn status(&self, now: i64, image: &[u8], sim: &Sim) -> Vec<String> {
        let plant = sim.plant();
        let sig = |dirs: &[Dir]| {
            plant
                .signals()
                .iter()
                .enumerate()
                .filter(|(_, s)| dirs.contains(&s.dir))
                .map(|(i, s)| {
                    let v = plant.get(i);
                    let v = match v {
                        Value::Bool(b) => u8::from(b).to_string(),
                        v => show_value(v),
                    };
                    let stuck = if sim.stuck(i).is_some() { "!" } else { "" };
                    format!("{}={v}{stuck}", s.name)
                })
                .collect::<Vec<_>>()
                .join(" ")
        };
        let q = plant
            .quantities()
            .iter()
            .enumerate()
            .map(|(i, q)| format!("{}={}{}", q.name, show_f64(plant.quantity(i)), q.unit))
            .collect::<Vec<_>>()
            .join(" ");
        vec![
            format!(
                "{} {} | scans {}{} | speed {}x",
                plant.name(),
                automat_iec::format::format_duration(now, false),
                self.scans,
                cycle_text(self.cycle),
                self.speed
            ),
            format!("  in:    {}", sig(&[Dir::Sensor, Dir::Operator])),
            format!("  out:   {}", sig(&[Dir::Actuator])),
            format!("  plant: {q}"),
        ]
        .into_iter()
        .chain(self.program_lines(image))
        .chain(steps_line(&self.charts, image))
        .collect()
    }

    /// Keeps the figures of the cycle statistics (no allocation per scan).
    pub fn stats(&mut self, st: &Stats) {
        if let (Some(min), Some(avg), Some(max)) = (st.min_ns, st.avg_ns(), st.max_ns) {
            self.cycle = Some((min, avg, max, st.overruns));
        }
    }

    pub fn after_scan(&mut self, now: i64, image: &[u8], sim: Option<&Rc<RefCell<Sim>>>) {
        self.scans += 1;
        while let Ok(line) = self.commands.try_recv() {
            match sim {
                Some(sim) => self.command(&line, now, sim),
                None => self.message = format!("`{line}`: this run has no plant"),
            }
        }
        let every = if self.terminal {
            Duration::from_millis(200)
        } else {
            Duration::from_secs(1)
        };
        if self.last_draw.is_some_and(|t| t.elapsed() < every) {
            return;
        }
        self.last_draw = Some(Instant::now());
        let lines = match sim {
            Some(sim) => self.status(now, image, &sim.borrow()),
            None => self.plc_status(now, image),
        };
        {
            // The console's answer, shown once.
            let mut c = self.console.lock().unwrap_or_else(|p| p.into_inner());
            if !c.messages.is_empty() {
                let mut all = std::mem::take(&mut c.messages);
                if !self.message.is_empty() {
                    all.insert(0, std::mem::take(&mut self.message));
                }
                self.message = all.join(if self.terminal { " | " } else { "\n  " });
            }
        }
        let help = if sim.is_some() { HELP } else { PROGRAM_HELP };
        let mut out = std::io::stdout().lock();
        if self.terminal {
            // Clear and redraw in place; the status stays at the top.
            let _ = write!(
                out,
                "\x1b[2J\x1b[H{}\n  {}\n  {help}\n> ",
                lines.join("\n"),
                self.message
            );
        } else {
            let _ = writeln!(out, "{}", lines.join(" |"));
            if !self.message.is_empty() {
                let _ = writeln!(out, "  {}", std::mem::take(&mut self.message));
            }
        }
        let _ = out.flush();
    }
}

/// ` | scan 12us avg (8us..40us) | overruns 0`, empty before any scan.
fn cycle_text(cycle: Option<(i64, i64, i64, u64)>) -> String {
    let Some((min, avg, max, overruns)) = cycle else {
        return String::new();
    };
    let t = |ns: i64| {
        if ns >= 1_000_000 {
            format!("{:.1}ms", ns as f64 / 1e6)
        } else if ns >= 1_000 {
            format!("{}us", ns / 1_000)
        } else {
            format!("{ns}ns")
        }
    };
    format!(
        " | scan {} avg ({}..{}) | overruns {overruns}",
        t(avg),
        t(min),
        t(max)
    )
}

/// `  steps: MAIN: FILL | MAIN.DOSE: IDLE`: the active steps of every chart
/// (`-` for a chart with none active); `None` without charts.
fn steps_line(charts: &[Chart], image: &[u8]) -> Option<String> {
    if charts.is_empty() {
        return None;
    }
    let each: Vec<String> = charts
        .iter()
        .map(|c| format!("{}: {}", c.owner, c.active_text(image)))
        .collect();
    Some(format!("  steps: {}", each.join(" | ")))
}

#[cfg(test)]
mod tests {
    use super::*;
    use automat_iec::Elementary;
    use automat_project::steps::Step;
    use automat_runtime::{Place, PlaceType};

    fn step(name: &str, offset: u32) -> Step {
        Step {
            name: name.into(),
            x: Place {
                offset,
                bit: None,
                ty: PlaceType::Elementary(Elementary::Bool),
                slc_bit: false,
            },
        }
    }

    #[test]
    fn the_steps_line_lists_active_steps_per_chart() {
        let charts = vec![
            Chart {
                owner: "MAIN".into(),
                steps: vec![step("START", 0), step("A1", 1), step("B1", 2)],
            },
            Chart {
                owner: "MAIN.FILL".into(),
                steps: vec![step("IDLE", 3)],
            },
        ];
        assert_eq!(
            steps_line(&charts, &[0, 1, 1, 0]).as_deref(),
            Some("  steps: MAIN: A1 B1 | MAIN.FILL: -")
        );
        assert_eq!(steps_line(&[], &[]), None);
    }

    #[test]
    fn the_status_line_shows_the_cycle_statistics() {
        assert_eq!(cycle_text(None), "");
        assert_eq!(
            cycle_text(Some((800, 12_345, 2_500_000, 3))),
            " | scan 12us avg (800ns..2.5ms) | overruns 3"
        );
    }
}
