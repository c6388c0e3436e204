//! The real-time view of `automat run PROJECT`: a status of the inputs,
//! outputs and plant quantities (redrawn on a terminal, one line a second
//! otherwise), and commands typed on standard input, applied at the next
//! scan: `press Pornire [for 200ms]`, `release Pornire`, `set l2 1` (on a
//! sensor or actuator: stuck at that value), `stuck l2 = TRUE`,
//! `unstick l2`, `noise Temp 20`, `plant CMD key=value`, `quit`.

use automat_ir::Program;
use automat_plant::{Dir, Value};
use automat_project::steps::{charts, Chart};
use automat_project::Sim;
use automat_runtime::clock::{Monotonic, SystemClock};
use automat_runtime::stats::Stats;
use automat_scenario::ast::{self, ActionKind};
use automat_scenario::check::{show_f64, show_value, Scope};
use std::cell::RefCell;
use std::io::{BufRead, IsTerminal, Write};
use std::rc::Rc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{channel, Receiver};
use std::sync::Arc;
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

pub struct Live {
    program: Program,
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

impl Live {
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
        Live {
            program: program.clone(),
            charts: charts(program),
            commands: rx,
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
        .chain(steps_line(&self.charts, image))
        .collect()
    }

    /// Keeps the figures of the cycle statistics (no allocation per scan).
    pub fn stats(&mut self, st: &Stats) {
        if let (Some(min), Some(avg), Some(max)) = (st.min_ns, st.avg_ns(), st.max_ns) {
            self.cycle = Some((min, avg, max, st.overruns));
        }
    }

    pub fn after_scan(&mut self, now: i64, image: &[u8], sim: &Rc<RefCell<Sim>>) {
        self.scans += 1;
        while let Ok(line) = self.commands.try_recv() {
            self.command(&line, now, sim);
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
        let lines = self.status(now, image, &sim.borrow());
        let mut out = std::io::stdout().lock();
        if self.terminal {
            // Clear and redraw in place; the status stays at the top.
            let _ = write!(
                out,
                "\x1b[2J\x1b[H{}\n  {}\n  {HELP}\n> ",
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
