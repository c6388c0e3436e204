//! Turning the PATH arguments of a command into source files.

use automat_base::SourceMap;
use std::path::{Path, PathBuf};

/// File extensions read as Structured Text when a directory is given.
const SOURCE_EXTENSIONS: &[&str] = &["st", "iecst"];

/// Expands files and directories (recursively, sorted by path so every run
/// sees the same order) into the list of source files.
pub fn collect(paths: &[PathBuf]) -> Result<Vec<PathBuf>, String> {
    let mut out = Vec::new();
    for p in paths {
        let meta = std::fs::metadata(p).map_err(|e| format!("{}: {}", p.display(), e))?;
        if meta.is_dir() {
            let before = out.len();
            walk(p, &mut out)?;
            if out.len() == before {
                return Err(format!(
                    "{}: no Structured Text files (*.st) in this directory",
                    p.display()
                ));
            }
        } else {
            out.push(p.clone());
        }
    }
    Ok(out)
}

fn walk(dir: &Path, out: &mut Vec<PathBuf>) -> Result<(), String> {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: {}", dir.display(), e))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            walk(&path, out)?;
        } else if path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| SOURCE_EXTENSIONS.iter().any(|x| x.eq_ignore_ascii_case(e)))
            || automat_vendor::is_fst_file(&path.to_string_lossy())
        {
            out.push(path);
        }
    }
    Ok(())
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
