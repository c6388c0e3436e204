//! `automat export`: a project as PLCopen TC6 2.01 XML.

use crate::{files, Outcome};
use automat_base::{render, Interner, SourceMap};
use clap::Args;
use std::path::PathBuf;

/// Write a project as one PLCopen TC6 2.01 XML file.
///
/// The sources (ST, IL, SFC and PLCopen XML files; a folder holding
/// `automat.toml` is its project's sources) are checked first; a project with
/// errors is not exported. POUs, data types and configurations read from
/// PLCopen XML are written as the file had them (LD, FBD, SFC graphics
/// included); those from ST as TC6 declarations with their bodies as text.
/// See docs/plcopen.md. Exits with 0 when written, 1 when the project has
/// errors or cannot be expressed in TC6 (E178), 2 when a path cannot be read
/// or written.
#[derive(Args)]
pub struct ExportArgs {
    /// Source files or directories (searched recursively for *.st, *.xml).
    #[arg(required = true, value_name = "PATH")]
    paths: Vec<PathBuf>,
    /// The XML file to write.
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    output: PathBuf,
}

pub fn run(args: &ExportArgs) -> Outcome {
    let mut sources = Vec::new();
    let mut plain = Vec::new();
    for p in &args.paths {
        let Some(toml) = automat_project::project_file(p) else {
            plain.push(p.clone());
            continue;
        };
        let mut map = SourceMap::new();
        match automat_project::load(&toml, &mut map) {
            Ok(project) if project.libraries.is_empty() => sources.extend(project.sources),
            Ok(_) => {
                eprintln!(
                    "error[E178]: {}: a project using a vendor dialect is not exported (its rewrites work on the ST text)",
                    toml.display()
                );
                return Outcome::ProgramErrors;
            }
            Err(d) => {
                eprint!("{}", render::render_report(&map, &d));
                return Outcome::ProgramErrors;
            }
        }
    }
    if !plain.is_empty() {
        match files::collect(&plain) {
            Ok(f) => sources.extend(f),
            Err(e) => {
                eprintln!("error: {e}");
                return Outcome::BadInput;
            }
        }
    }
    let map = match files::load(&sources) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("error: {e}");
            return Outcome::BadInput;
        }
    };
    let mut interner = Interner::new();
    let (units, analysis) = automat_dialect::check_sources(&map, &mut interner, &[]);
    if analysis.has_errors() {
        eprint!("{}", render::render_report(&map, &analysis.diagnostics));
        return Outcome::ProgramErrors;
    }
    let name = args
        .output
        .file_stem()
        .map_or("project".to_string(), |s| s.to_string_lossy().into_owned());
    match automat_plcopen::export(&units, &map, &name) {
        Ok(xml) => match std::fs::write(&args.output, xml) {
            Ok(()) => Outcome::Ok,
            Err(e) => {
                eprintln!("error: {}: {e}", args.output.display());
                Outcome::BadInput
            }
        },
        Err(d) => {
            eprint!("{}", render::render_report(&map, &d));
            Outcome::ProgramErrors
        }
    }
}
