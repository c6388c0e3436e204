//! `automat test`: every scenario and conformance program under the paths.

use crate::{plot, Outcome};
use automat_base::{render, SourceMap};
use automat_iec::format::format_duration;
use automat_ir::Program;
use automat_project::folder::{Entry, Walk};
use automat_project::{build, find_above, Project};
use automat_scenario::conformance::{self, Backend, Verdict};
use clap::Args;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Run every scenario (`*.scn`, with the project of the `automat.toml` at
/// or above it) and every execution-conformance program (`.st` with a
/// `cycles:`/`expect:` header) under the paths, in virtual time.
///
/// Prints one line per scenario or program (`ok NAME` or `FAILED NAME`,
/// with the failed expectations as written, their file:line, the PLC time
/// and the values involved), writes the failed run's trace
/// (`NAME.fail.csv`) and timing diagram (`NAME.fail.svg`) next to the
/// scenario or under --out, and `N passed, M failed` last.
///
/// Folders searched skip hidden folders (`.git`, ...), `target` folders and
/// every folder holding a file named `.automat-test-skip` (deliberately
/// failing fixtures mark themselves so; `skipped DIR` is printed). A path
/// given on the command line is always searched, marked or not.
///
/// Exit codes: 0 all passed, 1 some failed, 2 bad command line.
#[derive(Args)]
pub struct TestArgs {
    /// Files or folders to search (default: the current folder).
    #[arg(value_name = "PATH")]
    paths: Vec<PathBuf>,
    /// Write the traces and diagrams of failures into DIR.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
}

enum Item {
    Scenario(PathBuf),
    Conformance(PathBuf),
}

/// The file that keeps `automat test` out of a folder it searches.
pub const SKIP_MARKER: &str = ".automat-test-skip";

/// Collects the items under the command-line paths (searched even when
/// marked), each file once whatever the symbolic links
/// (`automat_project::folder`; what was left out is one warning).
fn collect(paths: &[PathBuf]) -> Result<Vec<Item>, String> {
    let mut walk = Walk::new();
    let mut keep = |e: Entry| match e {
        Entry::Dir(d) => {
            // Hidden folders and build output are not searched.
            let name = d.file_name().and_then(|n| n.to_str()).unwrap_or("");
            if name.starts_with('.') || name == "target" {
                false
            } else if d.join(SKIP_MARKER).is_file() {
                println!("skipped {} ({SKIP_MARKER})", d.display());
                false
            } else {
                true
            }
        }
        Entry::File(f) => matches!(extension(f).as_deref(), Some("scn" | "st" | "xml")),
    };
    let mut files = Vec::new();
    for p in paths {
        let meta = std::fs::metadata(p).map_err(|e| format!("{}: {e}", p.display()))?;
        if meta.is_dir() {
            walk.dir(p, &mut keep, &mut files)?;
        } else if walk.first_visit(p)? {
            files.push(p.clone());
        }
    }
    if let Some(w) = walk.warning() {
        eprintln!("{w}");
    }
    let mut out = Vec::new();
    for p in files {
        match extension(&p).as_deref() {
            Some("scn") => out.push(Item::Scenario(p)),
            Some("st" | "xml") => {
                let text = std::fs::read(&p).map_err(|e| format!("{}: {e}", p.display()))?;
                if conformance::is_conformance(&String::from_utf8_lossy(&text)) {
                    out.push(Item::Conformance(p));
                }
            }
            _ => {}
        }
    }
    Ok(out)
}

fn extension(p: &Path) -> Option<String> {
    p.extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
}

/// A project loaded and compiled once for all its scenarios.
type Built = Result<(Project, Program), String>;

struct Runner {
    map: SourceMap,
    projects: BTreeMap<PathBuf, Built>,
    out: Option<PathBuf>,
    passed: usize,
    failed: usize,
    pending: usize,
}

impl Runner {
    fn project(&mut self, toml: &Path) -> &Built {
        let map = &mut self.map;
        self.projects.entry(toml.to_path_buf()).or_insert_with(|| {
            let p = automat_project::load(toml, map).map_err(|d| render::render_report(map, &d))?;
            for w in &p.warnings {
                eprintln!("{w}");
            }
            match build::compile(&p.sources, p.program.clone(), &p.libraries) {
                Ok((mut prog, _warnings)) => {
                    match automat_project::tasks::apply(&p.tasks, &mut prog) {
                        Ok(()) => Ok((p, prog)),
                        Err(d) => Err(render::render_report(map, &d)),
                    }
                }
                Err(e) => Err(e.text),
            }
        })
    }

    fn fail(&mut self, name: &str, details: &str) {
        self.failed += 1;
        println!("FAILED {name}");
        for l in details.lines() {
            println!("    {l}");
        }
    }

    fn scenario(&mut self, path: &Path) {
        let shown = path.display().to_string();
        let Some(toml) = find_above(path) else {
            self.fail(
                &shown,
                &format!("{shown}:1:1: error[E324]: the scenario is in no project folder (no automat.toml at or above it)"),
            );
            return;
        };
        let text = match std::fs::read_to_string(path) {
            Ok(t) => t,
            Err(e) => return self.fail(&shown, &format!("{shown}: {e}")),
        };
        let file = self.map.add(shown.clone(), text.clone());
        let stem = path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("scenario")
            .to_string();
        let scn = match automat_scenario::parse(&text, file, &stem) {
            Ok(s) => s,
            Err(d) => {
                let r = render::render_report(&self.map, &d);
                return self.fail(&shown, &r);
            }
        };
        let built = match self.project(&toml) {
            Ok((p, prog)) => (p.clone(), prog.clone()),
            Err(e) => {
                let e = e.clone();
                return self.fail(&shown, &e);
            }
        };
        let (project, program) = built;
        let title = format!("{shown} ({})", scn.name);
        match automat_scenario::run::<std::io::Sink>(&program, &project, &scn, None) {
            Err(d) => {
                let r = render::render_report(&self.map, &d);
                self.fail(&title, &r);
            }
            Ok(o) if o.failures.is_empty() => {
                self.passed += 1;
                println!("ok {title}");
            }
            Ok(o) => {
                let mut details = String::new();
                for f in &o.failures {
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
                details.push_str(&self.write_failure(path, &stem, &program, &project, &scn));
                self.fail(&title, &details);
            }
        }
    }

    /// Runs the failed scenario again with a trace (runs are deterministic)
    /// and writes the CSV and the diagram; returns the line saying where.
    fn write_failure(
        &self,
        path: &Path,
        stem: &str,
        program: &Program,
        project: &Project,
        scn: &automat_scenario::ast::Scenario,
    ) -> String {
        let dir = self
            .out
            .clone()
            .or_else(|| path.parent().map(Path::to_path_buf))
            .unwrap_or_else(|| PathBuf::from("."));
        let csv = dir.join(format!("{stem}.fail.csv"));
        let svg = dir.join(format!("{stem}.fail.svg"));
        let mut buf = Vec::new();
        if let Err(e) = automat_scenario::run(program, project, scn, Some(&mut buf)) {
            return format!("trace not written: {} diagnostics\n", e.len());
        }
        if let Err(e) = std::fs::create_dir_all(&dir).and_then(|()| std::fs::write(&csv, &buf)) {
            return format!("trace not written: {}: {e}\n", csv.display());
        }
        let text = String::from_utf8_lossy(&buf);
        match plot::write_diagram(&text, &[], &svg) {
            Ok(()) => format!("trace: {}\ndiagram: {}\n", csv.display(), svg.display()),
            Err(e) => format!("trace: {}\ndiagram not written: {e}\n", csv.display()),
        }
    }

    fn conformance(&mut self, path: &Path) {
        let shown = path.display().to_string();
        let text = match std::fs::read(path) {
            Ok(b) => String::from_utf8_lossy(&b).into_owned(),
            Err(e) => return self.fail(&shown, &format!("{shown}: {e}")),
        };
        // The interpreter runs it, as `automat run` would by default.
        match conformance::judge(&shown, &text, Backend::Interp) {
            Verdict::Passed => {
                self.passed += 1;
                println!("ok {shown}");
            }
            Verdict::Failed(f) => {
                // The verdict starts with `NAME:`; the header line names it.
                let details = f.strip_prefix(&format!("{shown}:\n")).unwrap_or(&f);
                let details: Vec<&str> = details
                    .lines()
                    .map(|l| l.strip_prefix("    ").unwrap_or(l))
                    .collect();
                self.fail(&shown, &details.join("\n"))
            }
            Verdict::Pending(why) => {
                self.pending += 1;
                println!("pending {why}");
            }
            Verdict::KnownBug(why) => {
                self.pending += 1;
                println!("known-bug {why}");
            }
        }
    }
}

pub fn run(args: &TestArgs) -> Outcome {
    let paths = if args.paths.is_empty() {
        vec![PathBuf::from(".")]
    } else {
        args.paths.clone()
    };
    let items = match collect(&paths) {
        Ok(items) => items,
        Err(e) => {
            eprintln!("error: {e}");
            return Outcome::BadInput;
        }
    };
    let mut r = Runner {
        map: SourceMap::new(),
        projects: BTreeMap::new(),
        out: args.out.clone(),
        passed: 0,
        failed: 0,
        pending: 0,
    };
    for item in &items {
        match item {
            Item::Scenario(p) => r.scenario(p),
            Item::Conformance(p) => r.conformance(p),
        }
    }
    if r.pending > 0 {
        println!("{} pending or known bugs (not counted)", r.pending);
    }
    println!("{} passed, {} failed", r.passed, r.failed);
    if r.failed > 0 {
        Outcome::ProgramErrors
    } else {
        Outcome::Ok
    }
}
