//! `automat check`: parse and check a project, print diagnostics.

use crate::{files, Outcome};
use automat_base::{render, Interner, Severity, SourceMap};
use clap::{Args, ValueEnum};
use std::path::PathBuf;

/// Check Structured Text sources and report every error and warning.
///
/// A program without errors is also compiled (not run), so everything
/// `automat run` refuses at compile time is reported: a memory image too
/// large (E091, with the bytes needed), recursion (E092), ...
/// All files given (and all *.st files under the directories given) form one
/// project: POUs, types and globals of one file are visible in the others.
/// A directory holding `automat.toml` is checked as that project: its
/// sources with its `libraries` (as `automat run` and `automat test` do).
/// Exits with 0 when there are no errors, 1 when there are, 2 when a path
/// cannot be read.
#[derive(Args)]
pub struct CheckArgs {
    /// Source files or project directories (searched recursively for *.st).
    #[arg(required = true, value_name = "PATH")]
    paths: Vec<PathBuf>,
    /// Output format of the diagnostics.
    #[arg(long, value_enum, default_value_t = Format::Human)]
    format: Format,
    /// Treat warnings as errors (exit 1 when there is any warning).
    #[arg(long)]
    deny_warnings: bool,
    /// Do not print warnings.
    #[arg(long, conflicts_with = "deny_warnings")]
    no_warnings: bool,
    /// Use a vendor dialect (repeatable): `isagraf` (ISaGRAF helper blocks,
    /// TIMER, sections, child charts), `pl7` (%Xi steps, %S/%SW system
    /// objects, P1/N1/P0), `fst` (Festo STL) or `codesys` (CODESYS V2.3/V3
    /// and TwinCAT code). See docs/vendor-dialects.md.
    #[arg(long = "lib", value_name = "NAME")]
    libs: Vec<String>,
}

#[derive(Clone, Copy, ValueEnum)]
enum Format {
    /// rustc-like text: `file:line:col: error[E030]: message`, an excerpt and a caret.
    Human,
    /// A JSON array of diagnostics (code, severity, file, line, column, end, message, labels, notes).
    /// Both formats show the first 200 diagnostics, then one line (in JSON a `note`) counting the rest.
    Json,
}

/// What the PATH arguments stand for: a folder (or file) holding
/// `automat.toml` is the project it describes, checked as `automat run`
/// compiles it (its `sources` and `libraries`); anything else is sources.
struct Inputs {
    files: Vec<PathBuf>,
    libraries: Vec<String>,
}

fn inputs(args: &CheckArgs) -> Result<Inputs, Outcome> {
    let mut plain = Vec::new();
    let mut files = Vec::new();
    let mut libraries = Vec::new();
    for p in &args.paths {
        let Some(toml) = automat_project::project_file(p) else {
            plain.push(p.clone());
            continue;
        };
        let mut map = SourceMap::new();
        match automat_project::load(&toml, &mut map) {
            Ok(project) => {
                for w in &project.warnings {
                    eprintln!("{w}");
                }
                files.extend(project.sources);
                libraries.extend(project.libraries);
            }
            Err(d) => {
                eprint!("{}", render::render_report(&map, &d));
                return Err(Outcome::ProgramErrors);
            }
        }
    }
    if !plain.is_empty() {
        files.extend(files::collect(&plain).map_err(|e| {
            eprintln!("error: {e}");
            Outcome::BadInput
        })?);
    }
    libraries.extend(args.libs.iter().cloned());
    Ok(Inputs { files, libraries })
}

pub fn run(args: &CheckArgs) -> Outcome {
    let inputs = match inputs(args) {
        Ok(i) => i,
        Err(o) => return o,
    };
    let libraries = match automat_dialect::parse_libraries(&inputs.libraries) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("error: --lib: {e}");
            return Outcome::BadInput;
        }
    };
    let mut map = match files::load(&inputs.files) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("error: {e}");
            return Outcome::BadInput;
        }
    };
    automat_dialect::add_libraries_to(&mut map, &libraries);
    let dialects = libraries.dialects;
    let mut interner = Interner::new();
    let (units, analysis) = automat_dialect::check_sources(&map, &mut interner, &dialects);
    // A clean program is lowered too, so check refuses what run would
    // refuse at compile time (E091 image too large, E092 recursion, ...).
    let lowered = if analysis.has_errors() {
        Vec::new()
    } else {
        automat_lower::check(&units, &analysis, &interner, &map)
    };
    let mut diags = analysis.diagnostics;
    diags.extend(lowered);
    if args.no_warnings {
        diags.retain(|d| d.severity == Severity::Error);
    }
    let failed = diags
        .iter()
        .any(|d| d.is_error() || (args.deny_warnings && d.severity == Severity::Warning));
    match args.format {
        Format::Human => print!("{}", render::render_report(&map, &diags)),
        Format::Json => println!("{}", render::render_json(&map, &diags)),
    }
    if failed {
        Outcome::ProgramErrors
    } else {
        Outcome::Ok
    }
}
