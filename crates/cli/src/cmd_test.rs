//! `automat test`: every scenario and conformance program under the paths,
//! on `--jobs` threads, reported in the order the files were found (the
//! same output for every number of jobs), optionally as JUnit XML.

use crate::{plot, Outcome};
use automat_base::{render, SourceMap};
use automat_ir::Program;
use automat_project::folder::{Entry, Walk};
use automat_project::{build, find_above, Project};
use automat_scenario::conformance::{self, Backend, Verdict};
use clap::Args;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::sync::{mpsc, Arc, Mutex, OnceLock};
use std::time::Instant;

/// Run every scenario (`*.scn`, with the project of the `automat.toml` at
/// or above it; a project without `[plant]` drives and checks its own
/// variables) and every execution-conformance program (`.st` with a
/// `cycles:`/`expect:` header) under the paths, in virtual time.
///
/// Prints one line per scenario or program (`ok NAME`, `FAILED NAME` with
/// the failed expectations as written, their file:line, the PLC time and
/// the values involved, or `ERROR NAME` with the diagnostics of a
/// scenario or project that cannot run), writes the failed run's trace
/// (`NAME.fail.csv`) and timing diagram (`NAME.fail.svg`) next to the
/// scenario or under --out, and `N passed, M failed` last (`, K errors`
/// when some could not run). The output is the same, in the same order,
/// for every --jobs.
///
/// Folders searched skip hidden folders (`.git`, ...), `target` folders and
/// every folder holding a file named `.automat-test-skip` (deliberately
/// failing fixtures mark themselves so; `skipped DIR` is printed). A path
/// given on the command line is always searched, marked or not.
///
/// Exit codes: 0 all passed, 1 some failed, 2 some could not run (a
/// scenario or program with errors, an unreadable file, a project that
/// does not build) or a bad command line (also an unwritable --junit file).
#[derive(Args)]
pub struct TestArgs {
    /// Files or folders to search (default: the current folder).
    #[arg(value_name = "PATH")]
    paths: Vec<PathBuf>,
    /// Write the traces and diagrams of failures into DIR.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Also write the results as JUnit XML to FILE (one testsuite per
    /// project or folder, one testcase per scenario or program; read by
    /// GitLab, Jenkins and GitHub test reporters).
    #[arg(long, value_name = "FILE")]
    junit: Option<PathBuf>,
    /// Run N scenarios and programs at once (default: the number of
    /// cores). Results and output order do not depend on N.
    #[arg(long, short = 'j', value_name = "N", value_parser = clap::value_parser!(u64).range(1..=1024))]
    jobs: Option<u64>,
    /// The backend that runs the scenarios and programs: native code (as
    /// `automat run`; a program the JIT refuses runs on the interpreter) or
    /// the reference interpreter. Verdicts are the same. Default: each on
    /// the faster end to end, scenarios on native code (compiled once per
    /// project), conformance programs (a few scans each, compiled once) on
    /// the interpreter.
    #[arg(long, value_enum)]
    engine: Option<crate::engines::EngineKind>,
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

/// A project loaded, compiled and bound to its plant once for all its
/// scenarios; `warnings` are printed (once) before its first result.
struct BuiltProject {
    project: Project,
    program: Program,
    warnings: String,
    /// Its compiled backends, lent to one scenario at a time.
    backends: crate::test_pool::Pool,
}

type Built = Result<BuiltProject, String>;

/// How one scenario or program came out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Status {
    Passed,
    Failed,
    /// It could not run: its diagnostics are the details.
    Error,
    /// `pending` or `known-bug` conformance cases (not counted).
    Pending,
}

/// The result of one item, printed by the main thread in item order.
struct Report {
    /// `examples/crane/scenarios/normal.scn (normal cycle)`.
    title: String,
    /// The file, as shown.
    file: String,
    /// The JUnit testsuite: the project folder, or the file's folder.
    suite: String,
    status: Status,
    /// Failed or error details, one line each (printed indented), or the
    /// pending line.
    details: String,
    /// The project whose warnings go to stderr before this report.
    project: Option<PathBuf>,
    warnings: String,
    secs: f64,
}

impl Report {
    fn new(file: &str, suite: String) -> Report {
        Report {
            title: file.to_string(),
            file: file.to_string(),
            suite,
            status: Status::Passed,
            details: String::new(),
            project: None,
            warnings: String::new(),
            secs: 0.0,
        }
    }
    fn case(&self) -> crate::junit::Case<'_> {
        use crate::junit::Kind;
        crate::junit::Case {
            suite: &self.suite,
            name: self
                .title
                .strip_prefix(&self.suite)
                .and_then(|t| t.strip_prefix('/'))
                .unwrap_or(&self.title),
            file: &self.file,
            kind: match self.status {
                Status::Passed => Kind::Passed,
                Status::Failed => Kind::Failed,
                Status::Error => Kind::Error,
                Status::Pending => Kind::Skipped,
            },
            details: &self.details,
            secs: self.secs,
        }
    }
    fn fail(mut self, status: Status, details: String) -> Report {
        self.status = status;
        self.details = details;
        self
    }
}

/// What the worker threads share.
struct Shared {
    /// Projects by `automat.toml`: built by the first scenario that needs
    /// one, while the others wait for it (other projects build meanwhile).
    projects: Mutex<BTreeMap<PathBuf, Arc<OnceLock<Built>>>>,
    out: Option<PathBuf>,
    /// `--engine`, or `None`: each kind of item on its faster backend.
    engine: Option<crate::engines::EngineKind>,
}

impl Shared {
    fn project(&self, toml: &Path) -> Arc<OnceLock<Built>> {
        let cell = {
            let mut map = match self.projects.lock() {
                Ok(m) => m,
                Err(poisoned) => poisoned.into_inner(),
            };
            Arc::clone(map.entry(toml.to_path_buf()).or_default())
        };
        cell.get_or_init(|| build_project(toml));
        cell
    }

    fn scenario(&self, path: &Path) -> Report {
        let shown = path.display().to_string();
        let Some(toml) = find_above(path) else {
            let suite = parent_of(path);
            return Report::new(&shown, suite).fail(
                Status::Error,
                format!("{shown}:1:1: error[E324]: the scenario is in no project folder (no automat.toml at or above it)"),
            );
        };
        let mut report = Report::new(&shown, parent_of(&toml));
        let text = match std::fs::read_to_string(path) {
            Ok(t) => t,
            Err(e) => return report.fail(Status::Error, format!("{shown}: {e}")),
        };
        let mut map = SourceMap::new();
        let file = map.add(shown.clone(), text.clone());
        let stem = path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("scenario")
            .to_string();
        let scn = match automat_scenario::parse(&text, file, &stem) {
            Ok(s) => s,
            Err(d) => return report.fail(Status::Error, render::render_report(&map, &d)),
        };
        let cell = self.project(&toml);
        let built = match cell.get() {
            Some(Ok(b)) => b,
            Some(Err(e)) => return report.fail(Status::Error, e.clone()),
            None => return report.fail(Status::Error, "the project was not built".into()),
        };
        report.project = Some(toml.clone());
        report.warnings = built.warnings.clone();
        report.title = format!("{shown} ({})", scn.name);
        let (project, program) = (&built.project, &built.program);
        let kind = self.engine.unwrap_or(crate::engines::EngineKind::Jit);
        let exec = built.backends.lend(program, kind);
        match automat_scenario::run_on::<_, std::io::Sink>(program, exec, project, &scn, None) {
            Err(d) => report.fail(Status::Error, render::render_report(&map, &d)),
            Ok(o) if o.failures.is_empty() => report,
            Ok(o) => {
                let mut details = automat_scenario::describe(&shown, &o.failures);
                details.push_str(&self.write_failure(path, &stem, program, project, &scn));
                report.fail(Status::Failed, details)
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

    fn conformance(&self, path: &Path) -> Report {
        let shown = path.display().to_string();
        let report = Report::new(&shown, parent_of(path));
        let text = match std::fs::read(path) {
            Ok(b) => String::from_utf8_lossy(&b).into_owned(),
            Err(e) => return report.fail(Status::Error, format!("{shown}: {e}")),
        };
        // A conformance program runs a few scans once: compiling it to
        // native code costs more than interpreting it (the 174 files of
        // tests/conformance: 0.36 s of CPU on the JIT, 0.20 s interpreted).
        let backend = match self.engine {
            None | Some(crate::engines::EngineKind::Interp) => Backend::Interp,
            Some(crate::engines::EngineKind::Jit) => Backend::Jit,
        };
        match conformance::judge(&shown, &text, backend) {
            Verdict::Passed => report,
            Verdict::Failed(f) => {
                // The verdict starts with `NAME:`; the header line names it.
                let details = f.strip_prefix(&format!("{shown}:\n")).unwrap_or(&f);
                let details: Vec<&str> = details
                    .lines()
                    .map(|l| l.strip_prefix("    ").unwrap_or(l))
                    .collect();
                report.fail(Status::Failed, details.join("\n"))
            }
            Verdict::Pending(why) => report.fail(Status::Pending, format!("pending {why}")),
            Verdict::KnownBug(why) => report.fail(Status::Pending, format!("known-bug {why}")),
        }
    }

    fn item(&self, item: &Item) -> Report {
        let t0 = Instant::now();
        let mut r = match item {
            Item::Scenario(p) => self.scenario(p),
            Item::Conformance(p) => self.conformance(p),
        };
        r.secs = t0.elapsed().as_secs_f64();
        r
    }
}

/// Loads, compiles and binds a project (bindings checked here, so running
/// its scenarios reports only the scenario's own diagnostics).
fn build_project(toml: &Path) -> Built {
    let mut map = SourceMap::new();
    let p = automat_project::load(toml, &mut map).map_err(|d| render::render_report(&map, &d))?;
    let mut warnings = String::new();
    for w in &p.warnings {
        warnings.push_str(w);
        warnings.push('\n');
    }
    let mut prog = match build::compile(&p.sources, p.program.clone(), &p.libraries) {
        Ok((prog, _warnings)) => prog,
        Err(e) => return Err(e.text),
    };
    automat_project::tasks::apply(&p.tasks, &mut prog)
        .map_err(|d| render::render_report(&map, &d))?;
    if let (Some(spec), Some(plant)) = (
        &p.plant,
        p.new_plant().map_err(|d| render::render_report(&map, &d))?,
    ) {
        let (bindings, diags) = automat_project::bind(spec, plant.as_ref(), &prog);
        if bindings.is_none() {
            return Err(render::render_report(&map, &diags));
        }
    }
    Ok(BuiltProject {
        project: p,
        program: prog,
        warnings,
        backends: crate::test_pool::Pool::default(),
    })
}

/// The folder of a file, as shown (the JUnit testsuite).
fn parent_of(p: &Path) -> String {
    p.parent()
        .map(|d| d.display().to_string())
        .filter(|d| !d.is_empty())
        .unwrap_or_else(|| ".".into())
}

/// The default --jobs: the cores this process may use.
fn default_jobs() -> usize {
    std::thread::available_parallelism().map_or(1, usize::from)
}

/// Prints one report (and its project's warnings, the first time).
fn print(r: &Report, warned: &mut BTreeSet<PathBuf>) {
    if let Some(p) = &r.project {
        if warned.insert(p.clone()) && !r.warnings.is_empty() {
            eprint!("{}", r.warnings);
        }
    }
    match r.status {
        Status::Passed => println!("ok {}", r.title),
        Status::Pending => println!("{}", r.details),
        Status::Failed | Status::Error => {
            println!(
                "{} {}",
                if r.status == Status::Failed {
                    "FAILED"
                } else {
                    "ERROR"
                },
                r.title
            );
            for l in r.details.lines() {
                println!("    {l}");
            }
        }
    }
}

/// Runs the items on `jobs` threads; `each` sees the reports in item order
/// as soon as they and every one before them are done.
fn run_all(shared: &Shared, items: &[Item], jobs: usize, mut each: impl FnMut(Report)) {
    let queue = crate::test_queue::Queue::new(
        items
            .iter()
            .map(|item| match item {
                Item::Scenario(p) => find_above(p),
                Item::Conformance(_) => None,
            })
            .collect(),
    );
    let (tx, rx) = mpsc::channel::<(usize, Report)>();
    std::thread::scope(|scope| {
        for _ in 0..jobs.clamp(1, items.len().max(1)) {
            let tx = tx.clone();
            let queue = &queue;
            // Interpreting a program may recurse deeply: the main thread's
            // stack size, not a spawned thread's 2 MiB.
            let spawned = std::thread::Builder::new()
                .stack_size(8 << 20)
                .spawn_scoped(scope, move || {
                    while let Some(take) = queue.take() {
                        if let Some((project, toml)) = &take.build {
                            shared.project(toml);
                            queue.built(*project);
                        }
                        let Some(item) = items.get(take.item) else {
                            break;
                        };
                        let report = shared.item(item);
                        queue.done(take.item);
                        if tx.send((take.item, report)).is_err() {
                            break;
                        }
                    }
                });
            if let Err(e) = spawned {
                eprintln!("warning: cannot start a test thread: {e}");
            }
        }
        drop(tx);
        let mut pending = BTreeMap::new();
        let mut want = 0;
        for (i, r) in rx.iter() {
            pending.insert(i, r);
            while let Some(r) = pending.remove(&want) {
                each(r);
                want += 1;
            }
        }
    });
    // No thread could start: run them here.
    if queue.taken() == 0 {
        for item in items {
            each(shared.item(item));
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
    let jobs = args
        .jobs
        .and_then(|j| usize::try_from(j).ok())
        .unwrap_or_else(default_jobs);
    let shared = Shared {
        projects: Mutex::new(BTreeMap::new()),
        out: args.out.clone(),
        engine: args.engine,
    };
    let (mut passed, mut failed, mut errors, mut pending) = (0, 0, 0, 0);
    let mut warned = BTreeSet::new();
    let mut reports = Vec::new();
    let started = Instant::now();
    run_all(&shared, &items, jobs, |r| {
        print(&r, &mut warned);
        match r.status {
            Status::Passed => passed += 1,
            Status::Failed => failed += 1,
            Status::Error => errors += 1,
            Status::Pending => pending += 1,
        }
        if args.junit.is_some() {
            reports.push(r);
        }
    });
    // The process ends after the summary: freeing every project's compiled
    // code and image one by one would only cost time (0.5 % of a run).
    std::mem::forget(shared);
    if pending > 0 {
        println!("{pending} pending or known bugs (not counted)");
    }
    if errors > 0 {
        println!("{passed} passed, {failed} failed, {errors} errors");
    } else {
        println!("{passed} passed, {failed} failed");
    }
    if let Some(path) = &args.junit {
        let cases: Vec<crate::junit::Case> = reports.iter().map(Report::case).collect();
        let xml = crate::junit::write(&cases, started.elapsed().as_secs_f64());
        if let Err(e) = std::fs::write(path, xml) {
            eprintln!("error: --junit {}: {e}", path.display());
            return Outcome::BadInput;
        }
    }
    if errors > 0 {
        Outcome::BadInput
    } else if failed > 0 {
        Outcome::ProgramErrors
    } else {
        Outcome::Ok
    }
}
