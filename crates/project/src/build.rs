//! Compiling a project's sources to a [`Program`] (parse, check, lower).

use automat_base::{render, Code, Interner, SourceMap};
use automat_ir::Program;
use automat_lower::{lower, LowerOptions};
use std::path::PathBuf;

/// Why a build failed: the rendered diagnostics, and whether the fault is
/// the caller's input (an unreadable file, `--program` naming nothing)
/// rather than the program's.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BuildError {
    pub text: String,
    pub bad_input: bool,
}

/// Reads the files into a source map. Text that is not UTF-8 is read as
/// Latin-1 (what older PLC tools write), so no byte is lost or rejected.
pub fn read_sources(files: &[PathBuf]) -> Result<SourceMap, String> {
    let mut map = SourceMap::new();
    for f in files {
        let bytes = std::fs::read(f).map_err(|e| format!("{}: {}", f.display(), e))?;
        let text = match String::from_utf8(bytes) {
            Ok(s) => s,
            Err(e) => e.into_bytes().iter().map(|&b| char::from(b)).collect(),
        };
        map.add(f.display().to_string(), text);
    }
    Ok(map)
}

/// Compiles the files; warnings are returned rendered in `Ok`'s second
/// element so the caller decides where they go.
/// `libraries` names vendor dialects (`isagraf`) whose library and
/// rewrites the project uses.
pub fn compile(
    files: &[PathBuf],
    program: Option<String>,
    libraries: &[String],
) -> Result<(Program, String), BuildError> {
    let bad = |text: String| BuildError {
        text,
        bad_input: true,
    };
    let map = read_sources(files).map_err(|e| bad(format!("error: {e}\n")))?;
    compile_map(map, program, libraries)
}

/// [`compile`] on sources already in a map (tests, fuzz targets).
pub fn compile_map(
    mut map: SourceMap,
    program: Option<String>,
    libraries: &[String],
) -> Result<(Program, String), BuildError> {
    let bad = |text: String| BuildError {
        text,
        bad_input: true,
    };
    let libraries =
        automat_dialect::parse_libraries(libraries).map_err(|e| bad(format!("error: {e}\n")))?;
    automat_dialect::add_libraries_to(&mut map, &libraries);
    let dialects = libraries.dialects;
    let mut interner = Interner::new();
    let (units, analysis) = automat_dialect::check_sources(&map, &mut interner, &dialects);
    let warnings = render::render_report(&map, &analysis.diagnostics);
    if analysis.has_errors() {
        return Err(BuildError {
            text: warnings,
            bad_input: false,
        });
    }
    let named = program.is_some();
    let opts = LowerOptions { program };
    let p = lower(&units, &analysis, &interner, &map, &opts).map_err(|diags| BuildError {
        text: render::render_report(&map, &diags),
        // `--program` naming no PROGRAM is a command-line mistake.
        bad_input: named && diags.iter().all(|d| d.code == Code::E090),
    })?;
    let warnings = if analysis.diagnostics.is_empty() {
        String::new()
    } else {
        warnings
    };
    Ok((p, warnings))
}
