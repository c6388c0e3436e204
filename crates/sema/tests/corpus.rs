//! The conformance corpus of the Structured Text front end (`tests/corpus/` at the repository root).
//!
//! - `valid/`: every project must check without any diagnostic of severity Error (warnings are fine).
//! - `invalid/`: every project must produce exactly the errors its `//~` comments announce.
//!
//! A project is either one `.st` file directly in `valid/` or `invalid/`, or one sub-directory made
//! of all the `.st` files in it, sorted by name (for cases that need several files: globals in one,
//! programs in another). `tests/corpus/library/` belongs to another suite and is not read here, and
//! neither are the `isagraf_*` / `pl7_*` projects (vendor dialects: `crates/dialect/tests/corpus.rs`).
//!
//! Expectations are comments at the end of the offending line:
//! - `x := d; //~ E030` expects error E030 on this line;
//! - `//~ E030 E020` expects several errors on this line (write a code twice to expect it twice);
//! - `//~^ E005` expects it on the line above (one `^` per line up), for lines that cannot hold the
//!   comment themselves.
//!
//! The (file, line, code) of the error diagnostics must equal the expected ones exactly, counted as a
//! multiset: a diagnostic reported twice for one fault is a failure too. Every invalid project needs
//! at least one expectation; a valid one must have none. Every error code of
//! `automat_base::codes` must be expected by at least one invalid program.
//!
//! Every project runs (in its own thread, with a time limit, so a panic or an endless loop in the
//! front end is reported like any other failure); all failures are printed at the end, then the test
//! panics if there was any.
//!
//! Run only some projects: `CORPUS_FILTER=e030 cargo test -p automat-sema --test corpus`
//! (a project runs when the substring occurs in its path relative to `tests/corpus/`, such as
//! `invalid/e030_assign.st` or `valid/multi_file_globals/d_main.st`; the match ignores case).

use automat_base::render::render_human;
use automat_base::{Code, Interner, SourceMap};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

/// Generous: a debug build checks each small project in milliseconds; only a hang comes near it.
const PROJECT_TIME_LIMIT: Duration = Duration::from_secs(60);

#[test]
fn corpus_valid() {
    run_directory("valid", Mode::Valid);
}

#[test]
fn corpus_invalid() {
    run_directory("invalid", Mode::Invalid);
}

/// The invalid corpus must exercise every error code of the table, so a new code comes with
/// programs that trigger it.
#[test]
fn corpus_invalid_covers_every_error_code() {
    let mut seen = std::collections::BTreeSet::new();
    for project in load_projects(&corpus_root(), "invalid") {
        for (_, text) in &project.files {
            if let Ok(list) = parse_expectations(text) {
                seen.extend(list.into_iter().map(|(_, code)| code));
            }
        }
    }
    let missing: Vec<&str> = Code::ALL
        .iter()
        .filter(|c| {
            c.as_str().starts_with('E')
                && !is_project_code(**c)
                && !is_vendor_code(**c)
                && !is_generated_only_code(**c)
                && !is_plcopen_code(**c)
                && !seen.contains(*c)
        })
        .map(|c| c.as_str())
        .collect();
    assert!(
        missing.is_empty(),
        "no invalid corpus program expects these codes: {}",
        missing.join(", ")
    );
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    Valid,
    Invalid,
}

/// One project: its name (relative path) and its files as (relative path, text).
struct Project {
    name: String,
    files: Vec<(String, String)>,
}

/// An error diagnostic reduced to what is compared, plus its rendering for the report.
struct Found {
    /// Index into the project's files; `None` when the span names no file of the project.
    file: Option<usize>,
    line: u32,
    code: Code,
    rendered: String,
}

/// Where the errors of a project are expected: (file index, line, code).
type Key = (usize, u32, Code);

fn corpus_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/corpus")
}

fn run_directory(dir: &str, mode: Mode) {
    let root = corpus_root();
    let filter = std::env::var("CORPUS_FILTER")
        .ok()
        .filter(|f| !f.is_empty())
        .map(|f| f.to_lowercase());
    let projects: Vec<Project> = load_projects(&root, dir)
        .into_iter()
        .filter(|p| match &filter {
            None => true,
            Some(f) => {
                p.name.to_lowercase().contains(f.as_str())
                    || p.files
                        .iter()
                        .any(|(n, _)| n.to_lowercase().contains(f.as_str()))
            }
        })
        .collect();
    if filter.is_none() {
        assert!(
            !projects.is_empty(),
            "no projects found in {}",
            root.join(dir).display()
        );
    }
    let mut report = String::new();
    let mut failed = 0;
    for project in &projects {
        let problems = check_project(project, mode);
        if !problems.is_empty() {
            failed += 1;
            report.push_str(&format!("==== {} ====\n", project.name));
            for p in problems {
                report.push_str(&p);
                if !p.ends_with('\n') {
                    report.push('\n');
                }
            }
            report.push('\n');
        }
    }
    let summary = format!(
        "corpus {dir}: {} projects, {failed} failures",
        projects.len()
    );
    if failed > 0 {
        eprint!("{report}");
        eprintln!("{summary}");
        panic!("{summary}");
    }
    println!("{summary}");
}

/// The projects of `root/dir`, sorted by name: single files first-class, sub-directories as one each.
fn load_projects(root: &Path, dir: &str) -> Vec<Project> {
    let base = root.join(dir);
    let mut projects = Vec::new();
    for entry in sorted_entries(&base) {
        if is_vendor_project(&file_name(&entry)) {
            continue;
        }
        let name = format!("{dir}/{}", file_name(&entry));
        if entry.is_dir() {
            let files: Vec<(String, String)> = sorted_entries(&entry)
                .into_iter()
                .filter(|p| p.is_file() && is_st(p))
                .map(|p| (format!("{name}/{}", file_name(&p)), read(&p)))
                .collect();
            projects.push(Project { name, files });
        } else if is_st(&entry) {
            let text = read(&entry);
            projects.push(Project {
                files: vec![(name.clone(), text)],
                name,
            });
        }
    }
    projects
}

fn sorted_entries(dir: &Path) -> Vec<PathBuf> {
    let read = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("cannot read corpus directory {}: {e}", dir.display()));
    let mut paths: Vec<PathBuf> = read
        .map(|e| {
            e.unwrap_or_else(|e| panic!("cannot list {}: {e}", dir.display()))
                .path()
        })
        .collect();
    paths.sort();
    paths
}

fn file_name(p: &Path) -> String {
    p.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// E090–E099: diagnostics of lowering (`automat-lower`), not of the front end.
fn is_lowering_code(code: Code) -> bool {
    code.as_str().starts_with("E09")
}

/// E3xx: diagnostics of project files and scenarios, not of ST sources;
/// `crates/cli/tests/project_errors.rs` covers every one of them.
fn is_project_code(code: Code) -> bool {
    code.as_str().starts_with("E3")
}

/// E107 (a jump into nested statements): IL puts every label at the top
/// level of its body, so no source text produces it today; it guards the
/// trees other desugarings build. `crates/sema/tests/labels.rs` covers it.
fn is_generated_only_code(code: Code) -> bool {
    code == Code::E107
}

/// E150–E169: diagnostics of the vendor dialects, which need `--lib`;
/// `crates/dialect/tests/corpus.rs` covers them.
/// E15x/E16x: `crates/dialect/tests/corpus.rs`; E18x (Festo STL):
/// `crates/dialect/tests/fst.rs`; E23x (SLC-500 ladder, `.slc` files):
/// `crates/dialect/tests/slc.rs`.
fn is_vendor_code(code: Code) -> bool {
    ["E15", "E16", "E18", "E23"]
        .iter()
        .any(|p| code.as_str().starts_with(p))
}

/// E170–E179: diagnostics of the PLCopen XML importer, whose inputs are XML
/// files; `crates/plcopen/tests/diagnostics.rs` covers them.
fn is_plcopen_code(code: Code) -> bool {
    code.as_str().starts_with("E17")
}

/// `isagraf_*` / `pl7_*` projects are checked with their dialect on by
/// `crates/dialect/tests/corpus.rs`, not here.
fn is_vendor_project(name: &str) -> bool {
    name.starts_with("isagraf_") || name.starts_with("pl7_") || name.starts_with("codesys_")
}

fn is_st(p: &Path) -> bool {
    p.extension().is_some_and(|e| e.eq_ignore_ascii_case("st"))
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap_or_else(|e| panic!("cannot read {}: {e}", p.display()))
}

/// Every problem of one project, as printable paragraphs; empty when it passes.
fn check_project(project: &Project, mode: Mode) -> Vec<String> {
    let mut problems = Vec::new();
    if project.files.is_empty() {
        return vec![format!("{}: directory without .st files", project.name)];
    }
    let mut expected: BTreeMap<Key, usize> = BTreeMap::new();
    let mut expectation_count = 0;
    for (index, (name, text)) in project.files.iter().enumerate() {
        match parse_expectations(text) {
            Ok(list) => {
                expectation_count += list.len();
                if mode == Mode::Valid && !list.is_empty() {
                    problems.push(format!(
                        "{name}: a valid project must not contain `//~` expectations"
                    ));
                }
                for (line, code) in list {
                    if is_lowering_code(code) {
                        // Reported by code generation, after this front end;
                        // `crates/lower/tests/corpus.rs` checks these.
                        continue;
                    }
                    *expected.entry((index, line, code)).or_default() += 1;
                }
            }
            Err(errors) => problems.extend(errors.into_iter().map(|e| format!("{name}:{e}"))),
        }
    }
    if mode == Mode::Invalid && expectation_count == 0 && problems.is_empty() {
        problems.push(format!(
            "{}: an invalid project needs at least one `//~ Ennn` expectation",
            project.name
        ));
    }
    let found = match run_front_end(project) {
        Ok(found) => found,
        Err(message) => {
            problems.push(format!("{}: {message}", project.name));
            return problems;
        }
    };
    match mode {
        Mode::Valid => problems.extend(found.iter().map(|f| {
            format!(
                "unexpected error (a valid project has none):\n{}",
                f.rendered
            )
        })),
        Mode::Invalid => problems.extend(compare(project, &expected, &found)),
    }
    problems
}

/// Missing and unexpected errors of an invalid project.
fn compare(project: &Project, expected: &BTreeMap<Key, usize>, found: &[Found]) -> Vec<String> {
    let mut remaining = expected.clone();
    let mut problems = Vec::new();
    for f in found {
        let matched = f
            .file
            .and_then(|file| remaining.get_mut(&(file, f.line, f.code)));
        match matched {
            Some(count) if *count > 0 => *count -= 1,
            _ => problems.push(format!("unexpected error:\n{}", f.rendered)),
        }
    }
    for (&(file, line, code), &count) in &remaining {
        for _ in 0..count {
            let (name, text) = &project.files[file];
            let source = text.lines().nth(line as usize - 1).unwrap_or("").trim_end();
            problems.push(format!(
                "missing error: {name}:{line}: expected {} ({})\n  | {source}\n",
                code.as_str(),
                code.title()
            ));
        }
    }
    problems
}

/// Runs `check_sources` on the project in a thread of its own: returns its error diagnostics, or
/// why there are none (a panic, or no answer within the time limit).
fn run_front_end(project: &Project) -> Result<Vec<Found>, String> {
    let files = project.files.clone();
    let (tx, rx) = mpsc::channel();
    let spawned = std::thread::Builder::new()
        .name(project.name.clone())
        .spawn(move || {
            let result = std::panic::catch_unwind(move || check_files(&files));
            // The receiver may have given up after the time limit; nothing is left to tell then.
            let _ = tx.send(result.map_err(|payload| panic_message(&*payload)));
        });
    if let Err(e) = spawned {
        return Err(format!("cannot start a thread: {e}"));
    }
    match rx.recv_timeout(PROJECT_TIME_LIMIT) {
        Ok(Ok(found)) => Ok(found),
        Ok(Err(message)) => Err(format!("the front end panicked: {message}")),
        Err(mpsc::RecvTimeoutError::Timeout) => Err(format!(
            "the front end did not finish within {} s (endless loop?)",
            PROJECT_TIME_LIMIT.as_secs()
        )),
        Err(mpsc::RecvTimeoutError::Disconnected) => {
            Err("the front end thread ended without an answer".to_string())
        }
    }
}

fn check_files(files: &[(String, String)]) -> Vec<Found> {
    let mut map = SourceMap::new();
    for (name, text) in files {
        map.add(name.clone(), text.clone());
    }
    let mut interner = Interner::new();
    let (_units, analysis) = automat_sema::check_sources(&map, &mut interner);
    analysis
        .diagnostics
        .iter()
        .filter(|d| d.is_error())
        .map(|d| {
            let file = d.span.file.0 as usize;
            let known = file < map.len();
            Found {
                file: known.then_some(file),
                line: if known {
                    map.get(d.span.file).line_col(d.span.start).0
                } else {
                    0
                },
                code: d.code,
                rendered: render_human(&map, d),
            }
        })
        .collect()
}

fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "(no message)".to_string()
    }
}

/// The `//~` expectations of one file as (line, code), or one message per malformed comment
/// (each starting with its line number).
fn parse_expectations(text: &str) -> Result<Vec<(u32, Code)>, Vec<String>> {
    let mut found = Vec::new();
    let mut errors = Vec::new();
    for (index, line) in text.lines().enumerate() {
        let line_no = index as u32 + 1;
        let Some(pos) = line.find("//~") else {
            continue;
        };
        let rest = &line[pos + 3..];
        let ups = rest.chars().take_while(|&c| c == '^').count() as u32;
        let rest = &rest[ups as usize..];
        if ups >= line_no {
            errors.push(format!(
                "{line_no}: `//~{}` points above the first line",
                "^".repeat(ups as usize)
            ));
            continue;
        }
        let target = line_no - ups;
        let codes: Vec<&str> = rest.split_whitespace().collect();
        if codes.is_empty() {
            errors.push(format!("{line_no}: `//~` without a diagnostic code"));
        }
        for word in codes {
            match Code::parse(word) {
                Some(code) => found.push((target, code)),
                None => errors.push(format!(
                    "{line_no}: `{word}` in a `//~` comment is not a diagnostic code"
                )),
            }
        }
    }
    if errors.is_empty() {
        Ok(found)
    } else {
        Err(errors)
    }
}

#[test]
fn expectation_comments_are_read() {
    let text = "a\nb := 1; //~ E030 e020\n//~^ E005\n  //~^^E001\n";
    assert_eq!(
        parse_expectations(text),
        Ok(vec![
            (2, Code::E030),
            (2, Code::E020),
            (2, Code::E005),
            (2, Code::E001)
        ])
    );
    assert_eq!(
        parse_expectations("x //~ E999\n//~\n//~^^^ E005\n"),
        Err(vec![
            "1: `E999` in a `//~` comment is not a diagnostic code".to_string(),
            "2: `//~` without a diagnostic code".to_string(),
            "3: `//~^^^` points above the first line".to_string(),
        ])
    );
}
