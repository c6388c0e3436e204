//! Turning the PATH arguments of a command into source files.

use automat_base::SourceMap;
use automat_project::folder::{Entry, Walk};
use std::path::{Path, PathBuf};

/// File extensions read when a directory is given: Structured Text (and IL,
/// SFC in it), and PLCopen TC6 XML.
const SOURCE_EXTENSIONS: &[&str] = &["st", "iecst", "xml"];

/// Expands files and directories (recursively, sorted by path so every run
/// sees the same order) into the list of source files, each file once: a
/// folder or file reached again through a symbolic link is left out, with
/// one warning on stderr (see `automat_project::folder`).
pub fn collect(paths: &[PathBuf]) -> Result<Vec<PathBuf>, String> {
    let mut out = Vec::new();
    let mut walk = Walk::new();
    let mut keep = |e: Entry| match e {
        Entry::Dir(_) => true,
        Entry::File(p) => is_source(p),
    };
    for p in paths {
        let meta = std::fs::metadata(p).map_err(|e| format!("{}: {}", p.display(), e))?;
        if meta.is_dir() {
            let before = out.len();
            let skipped = walk.skipped().len();
            walk.dir(p, &mut keep, &mut out)?;
            if out.len() == before && walk.skipped().len() == skipped {
                return Err(format!(
                    "{}: no source files (*.st, *.xml) in this directory",
                    p.display()
                ));
            }
        } else if walk.first_visit(p)? {
            out.push(p.clone());
        }
    }
    if let Some(w) = walk.warning() {
        eprintln!("{w}");
    }
    Ok(out)
}

pub fn is_source(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| SOURCE_EXTENSIONS.iter().any(|x| x.eq_ignore_ascii_case(e)))
        || automat_dialect::is_fst_file(&path.to_string_lossy())
        || automat_dialect::is_slc_file(&path.to_string_lossy())
        || automat_dialect::is_export_file(&path.to_string_lossy())
}

/// Reads the files into a source map. Text that is not UTF-8 is read as
/// Latin-1 (what older PLC tools write), so no byte is lost or rejected.
pub fn load(files: &[PathBuf]) -> Result<SourceMap, String> {
    let mut map = SourceMap::new();
    for f in files {
        let bytes = std::fs::read(f).map_err(|e| format!("{}: {}", f.display(), e))?;
        let text = match String::from_utf8(bytes) {
            Ok(s) => s,
            Err(e) => e.into_bytes().iter().map(|&b| b as char).collect(),
        };
        map.add(f.display().to_string(), text);
    }
    Ok(map)
}
