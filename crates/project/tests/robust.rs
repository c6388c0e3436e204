//! Robustness of the project file reader: every `automat.toml` of the
//! repository (`examples/*`, the CLI test fixtures and error projects) is
//! mutated in many deterministic ways (`crates/scenario/tests/support/
//! mutate.rs`) and read with `file::parse` at its real path (so `sources`
//! resolve). It must return a project or E300/E308 diagnostics whose spans
//! lie inside the text; a project that reads is given its plant
//! (`new_plant`, parameters applied) and, when its sources compile, its
//! bindings (`bind`) and its safe state (`safe::build`, `[safe_state]`
//! resolved and encoded). Nothing may panic, hang or overflow the stack.

#[path = "../../scenario/tests/support/mutate.rs"]
mod mutate;

use automat_base::{Code, FileId, SourceMap};
use automat_ir::Program;
use automat_project::{bind, file};
use mutate::{brief, guarded, mutate, Rng};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Mutants of each project file (about 30 files).
const MUTANTS: usize = 120;
const CASE_LIMIT: Duration = Duration::from_secs(3);

const WORDS: &[&str] = &[
    "[project]",
    "[plant]",
    "[bind]",
    "[plant.params]",
    "[retain]",
    "[safe_state]",
    "save_every =",
    "optional =",
    "file =",
    "M2S =",
    "\"%QX0.0\" =",
    "\"Ctrl.n\" =",
    "\"T#5s\"",
    "\"'text'\"",
    "[[project]]",
    "name =",
    "description =",
    "sources =",
    "program =",
    "cycle_time =",
    "libraries =",
    "model =",
    "seed =",
    "params =",
    "\"0ms\"",
    "\"T#-1s\"",
    "\"10000000000000000000d\"",
    "\"isagraf\"",
    "\"pl7\"",
    "\"nonesuch\"",
    "\"..\"",
    "\"/\"",
    "\"crane\"",
    "= \"%QX99999999999.9\"",
    "= 1e308",
    "= -1e308",
    "= nan",
    "= inf",
    "= 18446744073709551615",
    "= 18446744073709551616",
    "= -1",
    "= true",
    "= []",
    "= {}",
    "'''",
    "\"\"\"",
    "1979-05-27T07:32:00Z",
];

const NESTS: &[(&str, &str)] = &[
    ("[", "]"),
    ("{a=", "}"),
    ("[{a=", "}]"),
    ("a.", ""),
    ("[[", ""),
];

fn files() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut out = Vec::new();
    for dir in [
        "examples",
        "crates/cli/tests/fixtures",
        "crates/cli/tests/projects",
    ] {
        let Ok(entries) = std::fs::read_dir(root.join(dir)) else {
            continue;
        };
        let mut dirs: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
        dirs.sort();
        out.extend(
            dirs.into_iter()
                .map(|d| d.join(file::FILE_NAME))
                .filter(|f| f.is_file()),
        );
    }
    out
}

/// Compiled programs by (sources, program, libraries): most mutants keep
/// them, and compiling is the slow part.
type Builds = Vec<((Vec<PathBuf>, Option<String>, Vec<String>), Option<Program>)>;

fn program<'a>(builds: &'a mut Builds, p: &automat_project::Project) -> Option<&'a Program> {
    let key = (p.sources.clone(), p.program.clone(), p.libraries.clone());
    let i = match builds.iter().position(|(k, _)| *k == key) {
        Some(i) => i,
        None => {
            let built =
                automat_project::build::compile(&p.sources, p.program.clone(), &p.libraries)
                    .ok()
                    .map(|(prog, _)| prog);
            builds.push((key, built));
            builds.len() - 1
        }
    };
    builds.get(i).and_then(|(_, p)| p.as_ref())
}

fn case(path: &Path, text: &str, builds: &mut Builds) -> bool {
    let project = match file::parse(path, FileId(0), text) {
        Err(diags) => {
            assert!(!diags.is_empty(), "an error without a diagnostic");
            for d in &diags {
                assert!(
                    matches!(d.code, Code::E300 | Code::E308),
                    "unexpected code {:?}: {}",
                    d.code,
                    d.message
                );
                assert!(
                    d.span.start <= d.span.end && d.span.end as usize <= text.len(),
                    "span {:?} outside the text ({} bytes): {}",
                    d.span,
                    text.len(),
                    d.message
                );
                assert!(!d.message.is_empty());
            }
            return false;
        }
        Ok(p) => p,
    };
    let mut project = project;
    // What `load` adds to `parse`: a plant written in ST is compiled.
    if let Some(st) = project.plant.as_mut().and_then(|p| p.program.as_mut()) {
        match automat_project::st_plant::compile(st, &mut automat_base::SourceMap::new()) {
            Ok(c) => st.compiled = Some(std::sync::Arc::new(c)),
            Err(diags) => {
                assert!(!diags.is_empty());
                return false;
            }
        }
    }
    assert!(project.cycle_time_ns > 0);
    assert!(!project.sources.is_empty());
    let plant = match project.new_plant() {
        Ok(Some(p)) => p,
        Ok(None) => return true,
        Err(diags) => {
            for d in &diags {
                assert!(matches!(d.code, Code::E301 | Code::E307), "{d:?}");
                assert!(d.span.end as usize <= text.len(), "{d:?}");
            }
            return true;
        }
    };
    if let (Some(spec), Some(prog)) = (&project.plant, program(builds, &project)) {
        let (bindings, diags) = bind(spec, plant.as_ref(), prog);
        for d in &diags {
            assert!(d.span.end as usize <= text.len(), "{d:?}");
        }
        let bound = bindings.as_deref().map(|b| (plant.as_ref(), b));
        match automat_project::safe::build(&project, prog, bound) {
            Ok(safe) => {
                let mut image = prog.initial_image.clone();
                safe.apply(&mut image);
                assert_eq!(image.len(), prog.initial_image.len());
                assert!(!safe.describe().is_empty());
            }
            Err(diags) => {
                for d in &diags {
                    assert_eq!(d.code, Code::E300, "{d:?}");
                    assert!(d.span.end as usize <= text.len(), "{d:?}");
                }
            }
        }
    }
    true
}

#[test]
fn mutated_project_files_never_crash() {
    let files = files();
    assert!(files.len() >= 20, "only {} project files", files.len());
    let start = Instant::now();
    let (mut cases, mut valid) = (0, 0);
    let mut builds = Builds::new();
    let mut failures = Vec::new();
    for (k, f) in files.iter().enumerate() {
        let Ok(src) = std::fs::read(f) else { continue };
        for m in 0..MUTANTS {
            let seed = (k * 1_000 + m) as u64;
            let mut rng = Rng::new(seed);
            let bytes = mutate(&mut rng, &src, WORDS, NESTS);
            // `load` reads the file as UTF-8 (see the test below for bytes
            // that are not).
            let text = String::from_utf8_lossy(&bytes).into_owned();
            let mut ok = false;
            let r = guarded(&format!("{} seed {seed}", f.display()), CASE_LIMIT, || {
                ok = case(f, &text, &mut builds);
            });
            cases += 1;
            valid += usize::from(ok);
            if let Err(e) = r {
                failures.push(format!("{e}\n  input: {:?}", brief(&text, 400)));
            }
        }
    }
    eprintln!(
        "project files: {} files, {cases} mutants ({valid} valid, {} builds) in {:?}",
        files.len(),
        builds.len(),
        start.elapsed()
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A project file that is not UTF-8 is E300 at the file, not a panic.
#[test]
fn a_project_file_that_is_not_utf8_is_an_error() {
    let dir = std::env::temp_dir().join(format!("automat-robust-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let path = dir.join(file::FILE_NAME);
    std::fs::write(&path, b"[project]\nname = \"\xff\xfe\"\n").unwrap_or_else(|e| panic!("{e}"));
    let mut map = SourceMap::new();
    let r = automat_project::load(&path, &mut map);
    let _ = std::fs::remove_dir_all(&dir);
    let diags = r.expect_err("not UTF-8");
    assert_eq!(diags.len(), 1);
    assert_eq!(diags[0].code, Code::E300);
    assert!(
        diags[0].message.contains("cannot read"),
        "{}",
        diags[0].message
    );
}

/// A project file over the size limit is one E300, quickly, whether it is
/// a little over (read, then refused) or far over (refused unread).
#[test]
fn a_huge_project_file_is_refused_at_once() {
    let dir = std::env::temp_dir().join(format!("automat-robust-big-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let path = dir.join(file::FILE_NAME);
    for size in [file::MAX_FILE_BYTES + 1, file::MAX_FILE_BYTES * 8] {
        let mut text = String::from("[project]\nname = \"x\"\n#");
        text.push_str(&"a".repeat(size - text.len()));
        std::fs::write(&path, &text).unwrap_or_else(|e| panic!("{e}"));
        let start = Instant::now();
        let mut map = SourceMap::new();
        let diags = automat_project::load(&path, &mut map).expect_err("too big");
        assert!(start.elapsed().as_secs_f64() < 1.0);
        assert_eq!(diags.len(), 1);
        assert_eq!(diags[0].code, Code::E300);
        assert!(diags[0].message.contains("1048576"), "{}", diags[0].message);
    }
    let _ = std::fs::remove_dir_all(&dir);
}
