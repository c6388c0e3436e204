//! Execution-conformance programs (`tests/conformance`-style `.st` files)
//! for `automat test`: the header format is the one documented in
//! `crates/cli/tests/conformance.rs` (`cycles:`, `cycle-time:`,
//! `program:`, `budget:`, `expect:`, `expect-at K:`, `expect-fault:`,
//! `skip-until:`, `known-bug:`); a file is such a program when it starts
//! with a `(* ... *)` header holding at least one `cycles:`, `expect…:`
//! line.

use automat_engine::Engine;
use automat_ir::FaultKind;
use automat_runtime::io::NoIo;
use automat_runtime::scan::Env;
use automat_runtime::{
    resolve, run, timearg, value, ClockMode, Limit, Place, RunConfig, RunEnd, ScanObserver,
    SystemClock,
};
use std::path::Path;
use std::sync::atomic::AtomicBool;

struct Expect {
    at: Option<u64>,
    path: String,
    value: String,
    line: usize,
}

struct Spec {
    cycles: u64,
    cycle_time_ns: i64,
    program: Option<String>,
    budget: Option<u64>,
    expects: Vec<Expect>,
    fault: Option<(FaultKind, u32, Option<u64>)>,
    pending: Option<String>,
    known_bug: Option<String>,
    libraries: Vec<String>,
}

/// What a conformance program comes to.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Verdict {
    Passed,
    Failed(Vec<String>),
    /// `skip-until:` (passing or not): never counts as failed.
    Pending(String),
    /// `known-bug:` (passing or not): never counts as failed.
    KnownBug(String),
}

fn header(source: &str) -> Option<(&str, usize)> {
    let start = source.trim_start();
    let skipped = source.len() - start.len();
    let body = start.strip_prefix("(*")?;
    let end = body.find("*)")?;
    let first_line = source.get(..skipped)?.matches('\n').count() + 1;
    Some((body.get(..end)?, first_line))
}

fn key_of(l: &str) -> Option<(&str, &str)> {
    let l = l.trim();
    let l = l.split_once(" -- ").map_or(l, |(a, _)| a).trim();
    let (k, v) = l.split_once(':')?;
    Some((k.trim(), v.trim()))
}

/// Whether `source` is a conformance program.
pub fn is_conformance(source: &str) -> bool {
    header(source).is_some_and(|(h, _)| {
        h.lines().filter_map(key_of).any(|(k, _)| {
            k == "cycles" || k == "expect" || k == "expect-fault" || k.starts_with("expect-at ")
        })
    })
}

fn fault_kind(name: &str) -> Option<FaultKind> {
    Some(match name {
        "division-by-zero" => FaultKind::DivisionByZero,
        "index-out-of-bounds" => FaultKind::IndexOutOfBounds,
        "subrange" => FaultKind::SubrangeViolation,
        "string-index" => FaultKind::StringIndex,
        "watchdog" => FaultKind::Watchdog,
        "function" => FaultKind::Function,
        _ => return None,
    })
}

fn parse(source: &str) -> Result<Spec, String> {
    let (text, first) = header(source).ok_or("no `(* ... *)` header")?;
    let mut s = Spec {
        cycles: 1,
        cycle_time_ns: 10_000_000,
        program: None,
        budget: None,
        expects: Vec::new(),
        fault: None,
        pending: None,
        known_bug: None,
        libraries: Vec::new(),
    };
    for (i, raw) in text.lines().enumerate() {
        let line = first + i;
        let Some((key, rest)) = key_of(raw) else {
            continue;
        };
        let bad = |what: &str| format!("line {line}: {key}: `{rest}` is not {what}");
        let expect = |at| {
            let (p, v) = rest
                .split_once(" = ")
                .ok_or_else(|| bad("`PATH = VALUE`"))?;
            Ok::<Expect, String>(Expect {
                at,
                path: p.trim().into(),
                value: v.trim().into(),
                line,
            })
        };
        match key {
            "cycles" => s.cycles = rest.parse().map_err(|_| bad("a count"))?,
            "cycle-time" => {
                s.cycle_time_ns =
                    timearg::parse_duration(rest).map_err(|e| format!("line {line}: {e}"))?
            }
            "program" => s.program = Some(rest.into()),
            "budget" => s.budget = Some(rest.parse().map_err(|_| bad("a count"))?),
            "expect" => s.expects.push(expect(None)?),
            "skip-until" => s.pending = Some(rest.into()),
            "known-bug" => s.known_bug = Some(rest.into()),
            "libraries" => s.libraries.extend(
                rest.split(',')
                    .map(|x| x.trim().to_string())
                    .filter(|x| !x.is_empty()),
            ),
            "expect-fault" => {
                let w: Vec<&str> = rest.split_whitespace().collect();
                let (k, l, c) = match w.as_slice() {
                    [k, "at", l] => (k, l, None),
                    [k, "at", l, "in", "cycle", c] => (k, l, Some(c)),
                    _ => return Err(bad("`KIND at LINE [in cycle K]`")),
                };
                let kind = fault_kind(k).ok_or_else(|| bad("a known fault kind"))?;
                let l = l.parse().map_err(|_| bad("`KIND at LINE`"))?;
                let c = match c {
                    Some(c) => Some(c.parse().map_err(|_| bad("`in cycle K`"))?),
                    None => None,
                };
                s.fault = Some((kind, l, c));
            }
            k if k.starts_with("expect-at ") => {
                let n = k.get("expect-at ".len()..).unwrap_or("").trim();
                let at = n.parse().map_err(|_| bad("a scan number"))?;
                s.expects.push(expect(Some(at))?);
            }
            _ => {}
        }
    }
    Ok(s)
}

struct Snapshots<'a> {
    scans: u64,
    wanted: Vec<(&'a Expect, Place)>,
    seen: Vec<(usize, String)>,
}

impl ScanObserver for Snapshots<'_> {
    fn after_scan(&mut self, _t: i64, image: &[u8]) -> Result<(), String> {
        self.scans += 1;
        for (k, (e, p)) in self.wanted.iter().enumerate() {
            if e.at == Some(self.scans) {
                self.seen.push((k, value::format(image, p)));
            }
        }
        Ok(())
    }
}

fn mismatch(e: &Expect, got: &str) -> String {
    let when = e.at.map(|k| format!(" after scan {k}")).unwrap_or_default();
    format!(
        "line {}: {}{when}: expected {}, got {got}",
        e.line, e.path, e.value
    )
}

/// The mismatches of one program (empty: it passed); `Err` when it does
/// not compile.
fn check(path: &Path, spec: &Spec) -> Result<Vec<String>, String> {
    let (program, _) = automat_project::build::compile(
        &[path.to_path_buf()],
        spec.program.clone(),
        &spec.libraries,
    )
    .map_err(|e| e.text)?;
    let mut places = Vec::new();
    for e in &spec.expects {
        let p = resolve(&program, &e.path).map_err(|err| format!("line {}: {err}", e.line))?;
        places.push((e, p));
    }
    let mut engine = Engine::new(program);
    if let Some(b) = spec.budget {
        engine.set_budget(b);
    }
    let mut snaps = Snapshots {
        scans: 0,
        wanted: places
            .iter()
            .filter(|(e, _)| e.at.is_some())
            .cloned()
            .collect(),
        seen: Vec::new(),
    };
    let cfg = RunConfig {
        cycle_time_ns: spec.cycle_time_ns,
        clock: ClockMode::Virtual,
        limit: Limit::Cycles(spec.cycles),
    };
    let stop = AtomicBool::new(false);
    let mut clock = SystemClock::new();
    let (mut i, mut o) = (NoIo, NoIo);
    let mut env = Env {
        clock: &mut clock,
        inputs: &mut i,
        outputs: &mut o,
        observer: &mut snaps,
        stop: &stop,
    };
    let report = run(&mut engine, &cfg, &mut env)?;
    let mut fails = Vec::new();
    match (&report.end, &spec.fault) {
        (RunEnd::Fault(f), Some((kind, line, cycle))) => {
            let at = f
                .fault
                .site
                .location
                .split(':')
                .rev()
                .nth(1)
                .and_then(|l| l.parse().ok());
            let scan = snaps.scans + 1;
            if f.fault.kind != *kind || at != Some(*line) || cycle.is_some_and(|c| c != scan) {
                fails.push(format!(
                    "fault: expected {kind:?} at line {line}, got {f} in cycle {scan}"
                ));
            }
        }
        (RunEnd::Fault(f), None) => fails.push(format!("unexpected fault: {f}")),
        (end, Some((kind, line, _))) => fails.push(format!(
            "expected fault {kind:?} at line {line}, run ended with {end:?}"
        )),
        (RunEnd::Limit, None) => {}
        (end, None) => fails.push(format!("run ended with {end:?}")),
    }
    for (k, got) in &snaps.seen {
        if let Some((e, _)) = snaps.wanted.get(*k) {
            if *got != e.value {
                fails.push(mismatch(e, got));
            }
        }
    }
    for (e, p) in places.iter().filter(|(e, _)| e.at.is_none()) {
        let got = value::format(engine.image(), p);
        if got != e.value {
            fails.push(mismatch(e, &got));
        }
    }
    for (k, (e, _)) in snaps.wanted.iter().enumerate() {
        if !snaps.seen.iter().any(|(s, _)| *s == k) {
            let n = e.at.unwrap_or(0);
            fails.push(format!(
                "line {}: {}: scan {n} never ran ({} scans)",
                e.line, e.path, snaps.scans
            ));
        }
    }
    Ok(fails)
}

/// Runs the conformance program at `path` whose text is `source`.
pub fn verdict(path: &Path, source: &str) -> Verdict {
    let spec = match parse(source) {
        Ok(s) => s,
        Err(e) => return Verdict::Failed(vec![format!("bad header: {e}")]),
    };
    let result = check(path, &spec);
    let ok = matches!(&result, Ok(f) if f.is_empty());
    if let Some(why) = &spec.pending {
        return Verdict::Pending(if ok {
            format!("{why}; NOW PASSES, remove skip-until")
        } else {
            why.clone()
        });
    }
    if let Some(why) = &spec.known_bug {
        return Verdict::KnownBug(if ok {
            format!("{why}; NOW PASSES, remove known-bug")
        } else {
            why.clone()
        });
    }
    match result {
        Ok(f) if f.is_empty() => Verdict::Passed,
        Ok(f) => Verdict::Failed(f),
        Err(e) => Verdict::Failed(vec![format!("does not compile or run:\n{e}")]),
    }
}
