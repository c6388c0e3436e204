//! Robustness of the scenario reader and the conformance header reader:
//! every real input of the repository (`examples/*/scenarios/*.scn`, the
//! scenarios of the CLI test fixtures, `tests/conformance/*.st` headers) is
//! mutated in many deterministic ways (see `support/mutate.rs`).
//!
//! Scenarios: `parse` must return a scenario or E320/E323 diagnostics
//! whose spans lie inside the text, in order; a scenario that parses is
//! resolved by the checker (`check::Scope`) against its real project, and
//! every 8th one is also run for at most 100 ms of PLC time. The live
//! console's `parse_action` reads every mutated line. Conformance headers:
//! `spec::parse` returns a spec or an error that names its line (or says
//! the header is missing or unclosed). Nothing may panic, hang or overflow
//! the stack.

#[path = "support/mutate.rs"]
mod mutate;

use automat_base::{Code, FileId, SourceMap};
use automat_ir::Program;
use automat_project::{bind, find_above, Binding, Project};
use automat_scenario::check::Scope;
use automat_scenario::conformance::{self, spec};
use mutate::{brief, guarded, mutate, Rng};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Mutants of each scenario file (about 55 files).
const SCN_MUTANTS: usize = 80;
/// Mutants of each conformance header (about 120 files).
const HEADER_MUTANTS: usize = 40;
/// A single case slower than this is reported as a hang.
const CASE_LIMIT: Duration = Duration::from_secs(3);

const SCN_WORDS: &[&str] = &[
    "name",
    "duration",
    "seed",
    "at",
    "expect",
    "press",
    "release",
    "set",
    "stuck",
    "unstick",
    "noise",
    "plant",
    "for",
    "within",
    "after",
    "always",
    "never",
    "during",
    "AND",
    "OR",
    "XOR",
    "NOT",
    "&",
    "0s..1s",
    "1s..0s",
    "..",
    "plant.x",
    "plant.nothing",
    "Ctrl.",
    "Ctrl.x[1]",
    "%QX3.1",
    "%IX0.0",
    "%MW99999999",
    "A#B",
    "#Rest1",
    "x=1",
    "=1",
    "k=",
    "arr[1,",
    "a[]",
    "when",
    "then",
    "stable",
    "rise(",
    "fall(x)",
    "change(",
    "prev(",
    "count(",
    "abs(",
    "min(1,",
    "max(",
    "+",
    "-",
    "*",
    "/",
    "MOD",
    ",",
    "-1e-3",
    "T#-1s",
];

const SCN_NESTS: &[(&str, &str)] = &[
    ("(", ")"),
    ("NOT ", ""),
    ("[", "]"),
    ("NOT (", ")"),
    ("x AND ", ""),
    ("(x OR ", ")"),
    ("rise(", ")"),
    ("count(", ")"),
    ("abs(", ")"),
    ("min(1, ", ")"),
    ("- ", ""),
    ("x + ", ""),
];

const HEADER_WORDS: &[&str] = &[
    "cycles:",
    "cycle-time:",
    "program:",
    "budget:",
    "expect:",
    "expect-at",
    "expect-at 0:",
    "expect-at 99999999999999999999:",
    "expect-fault:",
    "skip-until:",
    "known-bug:",
    "libraries:",
    "division-by-zero",
    "watchdog",
    "at",
    "in cycle",
    " -- ",
    "--",
    "(*",
    "*)",
];

const HEADER_NESTS: &[(&str, &str)] = &[("(*", "*)"), ("expect: ", " = "), (":", "")];

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn files_with(dir: &Path, ext: &str, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut paths: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    paths.sort();
    for p in paths {
        if p.is_dir() {
            files_with(&p, ext, out);
        } else if p.extension().is_some_and(|e| e == ext) {
            out.push(p);
        }
    }
}

/// What a scenario is checked against: its project, built once.
struct Target {
    project: Project,
    program: Program,
    plant: Box<dyn automat_plant::Plant>,
    bindings: Vec<Binding>,
}

fn target(toml: &Path) -> Option<Target> {
    let mut map = SourceMap::new();
    let project = automat_project::load(toml, &mut map).ok()?;
    let (program, _) = automat_project::build::compile(
        &project.sources,
        project.program.clone(),
        &project.libraries,
    )
    .ok()?;
    // A project without [plant] is checked against no plant.
    let (plant, bindings) = match (project.new_plant().ok()?, project.plant.as_ref()) {
        (Some(plant), Some(spec)) => {
            let (bindings, _) = bind(spec, plant.as_ref(), &program);
            (plant, bindings?)
        }
        _ => (
            Box::new(automat_scenario::NoPlant) as Box<dyn automat_plant::Plant>,
            Vec::new(),
        ),
    };
    Some(Target {
        bindings,
        project,
        program,
        plant,
    })
}

/// Checks one mutant; `run` also runs it (shortened) when it is valid.
fn scenario_case(text: &str, target: Option<&Target>, run: bool) -> bool {
    let file = FileId(0);
    let parsed = automat_scenario::parse(text, file, "mutant");
    for line in text.lines() {
        // The live console reads one action per line.
        let action = line.trim_start();
        if let Err(d) = automat_scenario::parse::parse_action(action, file) {
            assert!(d.span.start <= d.span.end, "bad action span {:?}", d.span);
            assert!(d.span.start as usize <= action.len() + 1);
        }
    }
    let scn = match parsed {
        Err(diags) => {
            assert!(!diags.is_empty(), "an error without a diagnostic");
            let mut last = 0;
            for d in &diags {
                assert!(
                    matches!(d.code, Code::E320 | Code::E323),
                    "unexpected code {:?}",
                    d.code
                );
                assert!(
                    d.span.start <= d.span.end && d.span.end as usize <= text.len() + 1,
                    "span {:?} outside the text ({} bytes)",
                    d.span,
                    text.len()
                );
                assert!(d.span.start >= last, "diagnostics out of order");
                last = d.span.start;
                assert!(!d.message.is_empty());
            }
            return false;
        }
        Ok(s) => s,
    };
    assert!(scn.duration_ns >= 0);
    let Some(t) = target else { return true };
    let scope = Scope {
        program: &t.program,
        plant: t.plant.as_ref(),
        bindings: &t.bindings,
    };
    let mut refs = Vec::new();
    for e in &scn.expects {
        if let Err(d) = automat_scenario::run::check_expect(&scope, e, &mut refs) {
            assert!(
                matches!(d.code, Code::E321 | Code::E322 | Code::E325 | Code::E326)
                    && d.span.end as usize <= text.len(),
                "checker diagnostic {d:?}"
            );
        }
        if let Ok(c) = scope.condition(&e.cond, &mut refs) {
            let _ = c.truth(automat_scenario::eval::Frame::of(&[]));
        }
    }
    for r in &scn.reactions {
        if let Err(d) = scope.event(&r.event, &mut refs) {
            assert!(
                matches!(d.code, Code::E321 | Code::E322 | Code::E325 | Code::E326),
                "checker diagnostic {d:?}"
            );
        }
    }
    for a in &scn.actions {
        if let Err(d) = scope.action(a) {
            assert!(
                matches!(d.code, Code::E302 | Code::E321 | Code::E322 | Code::E325)
                    && d.span.end as usize <= text.len(),
                "checker diagnostic {d:?}"
            );
        }
    }
    if run {
        // A short run: the scenario's own duration may be hours.
        let mut short = scn.clone();
        short.duration_ns = short.duration_ns.min(100_000_000);
        let _ = automat_scenario::run::<std::io::Sink>(&t.program, &t.project, &short, None);
    }
    true
}

#[test]
fn mutated_scenarios_never_crash() {
    let root = repo();
    let mut files = Vec::new();
    let Ok(examples) = std::fs::read_dir(root.join("examples")) else {
        panic!("no examples folder");
    };
    let mut dirs: Vec<PathBuf> = examples.filter_map(|e| e.ok().map(|e| e.path())).collect();
    dirs.sort();
    for d in dirs {
        files_with(&d.join("scenarios"), "scn", &mut files);
    }
    files_with(&root.join("crates/cli/tests"), "scn", &mut files);
    assert!(files.len() >= 40, "only {} scenario files", files.len());
    let start = Instant::now();
    let (mut cases, mut valid, mut runs) = (0, 0, 0);
    let mut failures = Vec::new();
    // Projects built so far, by project file (most hold several scenarios).
    let mut built: Vec<(Option<PathBuf>, Option<Target>)> = Vec::new();
    let mut building = Duration::ZERO;
    let mut slowest = (Duration::ZERO, String::new());
    for (k, f) in files.iter().enumerate() {
        let Ok(src) = std::fs::read(f) else { continue };
        let toml = find_above(f);
        let i = match built.iter().position(|(t, _)| *t == toml) {
            Some(i) => i,
            None => {
                let t0 = Instant::now();
                built.push((toml.clone(), toml.as_deref().and_then(target)));
                building += t0.elapsed();
                built.len() - 1
            }
        };
        let target = built.get(i).and_then(|(_, t)| t.as_ref());
        let name = f.strip_prefix(&root).unwrap_or(f).display().to_string();
        for m in 0..SCN_MUTANTS {
            let seed = (k * 1_000 + m) as u64;
            let mut rng = Rng::new(seed);
            let bytes = mutate(&mut rng, &src, SCN_WORDS, SCN_NESTS);
            // `automat test` reads scenarios as UTF-8 text.
            let text = String::from_utf8_lossy(&bytes).into_owned();
            let run = m % 8 == 0;
            if std::env::var_os("ROBUST_TRACE").is_some() {
                eprintln!("{name} seed {seed}");
            }
            let mut ok = false;
            let r = guarded(&format!("{name} seed {seed}"), CASE_LIMIT, || {
                ok = scenario_case(&text, target, run);
            });
            cases += 1;
            if ok {
                valid += 1;
                runs += usize::from(run && target.is_some());
            }
            match r {
                Err(e) => failures.push(format!("{e}\n  input: {:?}", brief(&text, 300))),
                Ok(d) if d > slowest.0 => slowest = (d, format!("{name} seed {seed}")),
                Ok(_) => {}
            }
        }
    }
    eprintln!(
        "scenarios: {} files, {cases} mutants ({valid} valid, {runs} run) in {:?} \
         ({building:?} building {} projects; slowest case {:?}: {})",
        files.len(),
        start.elapsed(),
        built.iter().filter(|(_, t)| t.is_some()).count(),
        slowest.0,
        slowest.1
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The error of `spec::parse` names a line of the file, or says the header
/// is missing or not closed.
fn header_case(text: &str) {
    let _ = conformance::is_conformance(text);
    let lines = text.lines().count().max(1);
    match spec::parse(text) {
        Ok(s) => {
            for e in &s.expects {
                assert!(e.line >= 1 && e.line <= lines, "expect line {}", e.line);
            }
        }
        Err(e) => {
            if let Some(rest) = e.strip_prefix("line ") {
                let n: usize = rest
                    .split(':')
                    .next()
                    .and_then(|n| n.parse().ok())
                    .unwrap_or_else(|| panic!("no line number in {e:?}"));
                assert!(n >= 1 && n <= lines, "line {n} of {lines}: {e}");
            } else {
                assert!(
                    e.contains("expectation header"),
                    "an error without its line: {e:?}"
                );
            }
        }
    }
}

#[test]
fn mutated_conformance_headers_never_crash() {
    let root = repo();
    let mut files = Vec::new();
    files_with(&root.join("tests/conformance"), "st", &mut files);
    assert!(files.len() >= 50, "only {} conformance files", files.len());
    let start = Instant::now();
    let mut cases = 0;
    let mut failures = Vec::new();
    for (k, f) in files.iter().enumerate() {
        let Ok(src) = std::fs::read(f) else { continue };
        // The header and the line after it: the rest of the file is the
        // ST parser's business (crates/syntax/tests/mangled.rs).
        let end = src
            .windows(2)
            .position(|w| w == b"*)")
            .map_or(src.len(), |i| i + 2);
        let end = src[end..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(src.len(), |i| end + i + 1);
        let (head, body) = src.split_at(end);
        let name = f.strip_prefix(&root).unwrap_or(f).display().to_string();
        for m in 0..HEADER_MUTANTS {
            let seed = (k * 1_000 + m) as u64;
            let mut rng = Rng::new(seed);
            let mut bytes = mutate(&mut rng, head, HEADER_WORDS, HEADER_NESTS);
            bytes.extend_from_slice(body);
            // `automat test` reads the file as lossy UTF-8.
            let text = String::from_utf8_lossy(&bytes).into_owned();
            cases += 1;
            if let Err(e) = guarded(&format!("{name} seed {seed}"), CASE_LIMIT, || {
                header_case(&text)
            }) {
                failures.push(format!("{e}\n  input: {:?}", brief(&text, 300)));
            }
        }
    }
    eprintln!(
        "conformance headers: {} files, {cases} mutants in {:?}",
        files.len(),
        start.elapsed()
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
