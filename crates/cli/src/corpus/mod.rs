//! The real-code corpus harness behind `automat corpus`: how much of a body
//! of code written elsewhere (a library exported from CODESYS, another
//! compiler's test programs, the standard's examples) automat checks, and
//! whether its documented examples run to their documented values.
//!
//! A *source* is a folder given on the command line. Inside it each file is
//! a project of its own (test programs are written to stand alone) and each
//! sub-folder one project of all the files under it (a library whose files
//! use each other); with `whole` the source itself is one project. A file
//! is clean when no error diagnostic falls in it, a POU (function, function
//! block, program, class, interface) when none falls in its span. Files
//! opening with a conformance header (`expect:` …, the format of
//! `tests/conformance`) are the examples: each runs with the project's
//! other, non-example files and the dialects given.

pub mod report;

use automat_base::{Code, FileId, Interner, Severity, SourceMap, Span};
use automat_scenario::conformance::{self, Backend, Context, Verdict};
use automat_syntax::ast::Item;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// How a corpus is measured.
pub struct Options {
    pub libraries: Vec<String>,
    pub whole: bool,
    pub backend: Backend,
}

/// One POU as written, with the error codes inside it.
pub struct Pou {
    pub name: String,
    pub line: u32,
    pub errors: Vec<Code>,
}

/// One source file of a project.
pub struct File {
    pub path: String,
    pub errors: usize,
    pub pous: Vec<Pou>,
}

/// One example and what came of it.
pub struct Example {
    pub path: String,
    pub verdict: Verdict,
}

/// The figures of one source folder.
pub struct Source {
    pub path: String,
    pub files: Vec<File>,
    /// Diagnostics (errors and warnings) by code, over all its projects.
    pub codes: BTreeMap<Code, usize>,
    pub examples: Vec<Example>,
}

/// Measures every source; an error is an unreadable path.
pub fn measure(sources: &[PathBuf], opts: &Options) -> Result<Vec<Source>, String> {
    let mut out = Vec::with_capacity(sources.len());
    for s in sources {
        let mut source = Source {
            path: s.display().to_string(),
            files: Vec::new(),
            codes: BTreeMap::new(),
            examples: Vec::new(),
        };
        for project in projects(s, opts.whole)? {
            measure_project(&project, opts, &mut source)?;
        }
        out.push(source);
    }
    Ok(out)
}

/// The projects of a source folder (see the module comment), in path order.
fn projects(source: &Path, whole: bool) -> Result<Vec<Vec<PathBuf>>, String> {
    let meta = std::fs::metadata(source).map_err(|e| format!("{}: {e}", source.display()))?;
    if whole || !meta.is_dir() {
        return Ok(vec![crate::files::collect(&[source.to_path_buf()])?]);
    }
    let mut entries: Vec<PathBuf> = std::fs::read_dir(source)
        .map_err(|e| format!("{}: {e}", source.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    entries.sort();
    let mut out = Vec::new();
    for p in entries {
        let hidden = p
            .file_name()
            .and_then(|n| n.to_str())
            .is_some_and(|n| n.starts_with('.'));
        if hidden {
            continue;
        }
        if p.is_dir() {
            // A folder without sources (documentation, pictures) is no project.
            if let Ok(files) = crate::files::collect(std::slice::from_ref(&p)) {
                out.push(files);
            }
        } else if crate::files::is_source(&p) {
            out.push(vec![p]);
        }
    }
    Ok(out)
}

fn measure_project(paths: &[PathBuf], opts: &Options, into: &mut Source) -> Result<(), String> {
    let libraries = automat_dialect::parse_libraries(&opts.libraries)?;
    let mut map = crate::files::load(paths)?;
    let own = map.len();
    automat_dialect::add_libraries_to(&mut map, &libraries);
    let dialects = libraries.dialects;
    let mut interner = Interner::new();
    let (units, analysis) = automat_dialect::check_sources(&map, &mut interner, &dialects);
    let lowered = if analysis.has_errors() {
        Vec::new()
    } else {
        automat_lower::check(&units, &analysis, &interner, &map)
    };
    let mut diags = analysis.diagnostics;
    diags.extend(lowered);
    for d in &diags {
        *into.codes.entry(d.code).or_default() += 1;
    }
    let errors: Vec<Span> = diags
        .iter()
        .filter(|d| d.severity == Severity::Error)
        .map(|d| d.span)
        .collect();
    let codes_in = |span: Span| -> Vec<Code> {
        diags
            .iter()
            .filter(|d| d.severity == Severity::Error && inside(d.span, span))
            .map(|d| d.code)
            .collect()
    };
    let mut files: Vec<File> = (0..own)
        .map(|i| {
            let f = map.get(FileId(i as u32));
            File {
                path: f.name.clone(),
                errors: errors.iter().filter(|s| s.file.0 as usize == i).count(),
                pous: Vec::new(),
            }
        })
        .collect();
    for unit in &units {
        let Some(file) = files.get_mut(unit.file.0 as usize) else {
            continue; // a dialect's library
        };
        for item in &unit.items {
            let Some((name, span)) = written_pou(item, &interner) else {
                continue;
            };
            let line = map.get(span.file).line_col(span.start).0;
            file.pous.push(Pou {
                name,
                line,
                errors: codes_in(span),
            });
        }
    }
    run_examples(&map, own, opts, into);
    into.files.append(&mut files);
    Ok(())
}

/// A POU the user wrote (the OOP and dialect rewrites append hidden `__`
/// items, which are not counted) and its span.
fn written_pou(item: &Item, interner: &Interner) -> Option<(String, Span)> {
    let (name, span) = match item {
        Item::Pou(p) => (p.name, p.span),
        Item::Class(c) => (c.name, c.span),
        Item::Interface(i) => (i.name, i.span),
        Item::Types(_) | Item::Globals(_) | Item::Config(_) | Item::Namespace(_) => return None,
    };
    let text = interner.name(name.sym);
    (!text.starts_with("__")).then(|| (text.to_string(), span))
}

fn inside(d: Span, pou: Span) -> bool {
    d.file == pou.file && d.start >= pou.start && d.start < pou.end.max(pou.start + 1)
}

/// Runs every example of the project (its first `own` files) with the
/// project's other files.
fn run_examples(map: &SourceMap, own: usize, opts: &Options, into: &mut Source) {
    let files: Vec<(String, String)> = (0..own)
        .map(|i| {
            let f = map.get(FileId(i as u32));
            (f.name.clone(), f.text.clone())
        })
        .collect();
    let (examples, library): (Vec<_>, Vec<_>) = files
        .into_iter()
        .partition(|(_, text)| conformance::is_conformance(text));
    let ctx = Context {
        files: &library,
        libraries: &opts.libraries,
    };
    for (name, text) in &examples {
        let verdict = conformance::judge_in(name, text, opts.backend, ctx);
        into.examples.push(Example {
            path: name.clone(),
            verdict,
        });
    }
}
