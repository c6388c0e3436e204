//! Walking source folders: every folder and file once, whatever the
//! symbolic links.
//!
//! A folder is known by its device and inode (its canonical path where
//! there are no inodes), so a link back to an ancestor (`up -> ..`), two
//! links into each other, or a second name for a folder already searched
//! is not entered again: the walk always ends and never yields one file
//! twice. What was left out is reported once, by [`Walk::warning`]: a
//! silent skip would hide a mislinked project, one line per link would
//! bury the real diagnostics. Entries are visited sorted by path so every
//! run sees the same order.

use std::collections::HashMap;
use std::io;
use std::path::{Path, PathBuf};

/// A file or folder's identity on the machine.
#[cfg(unix)]
type Key = (u64, u64);
#[cfg(not(unix))]
type Key = PathBuf;

#[cfg(unix)]
fn key(path: &Path) -> Result<Key, String> {
    use std::os::unix::fs::MetadataExt;
    let m = std::fs::metadata(path).map_err(|e| failed(path, e))?;
    Ok((m.dev(), m.ino()))
}

#[cfg(not(unix))]
fn key(path: &Path) -> Result<Key, String> {
    std::fs::canonicalize(path).map_err(|e| failed(path, e))
}

/// An I/O error as `path: what`, the way every command reports it.
fn failed(path: &Path, e: io::Error) -> String {
    format!("{}: {e}", path.display())
}

/// What the filter of [`Walk::dir`] is asked about.
#[derive(Clone, Copy, Debug)]
pub enum Entry<'a> {
    /// A folder below the root: enter it?
    Dir(&'a Path),
    /// A file (or anything that is not a folder): take it?
    File(&'a Path),
}

/// An entry left out because it was already reached under another name.
#[derive(Clone, Debug, PartialEq)]
pub struct Skipped {
    /// The name it was reached by this time (usually a symbolic link).
    pub path: PathBuf,
    /// The name it was first reached by.
    pub first: PathBuf,
    /// It is a folder the walk was inside of: following it would loop.
    pub is_loop: bool,
}

/// One walk over any number of roots, remembering what it has seen.
#[derive(Default)]
pub struct Walk {
    seen: HashMap<Key, PathBuf>,
    /// The folders the walk is inside of, innermost last.
    inside: Vec<Key>,
    skipped: Vec<Skipped>,
}

impl Walk {
    pub fn new() -> Walk {
        Walk::default()
    }

    /// What was left out so far.
    pub fn skipped(&self) -> &[Skipped] {
        &self.skipped
    }

    /// One warning for everything left out (None when nothing was), naming
    /// the first link and counting the others.
    pub fn warning(&self) -> Option<String> {
        let first = self.skipped.first()?;
        let why = if first.is_loop {
            format!(
                "a symbolic link back to {} (a loop): not followed",
                first.first.display()
            )
        } else {
            format!("already read as {}: not read again", first.first.display())
        };
        let more = match self.skipped.len() - 1 {
            0 => String::new(),
            n => format!(" (and {n} more)"),
        };
        Some(format!("warning: {}: {why}{more}", first.path.display()))
    }

    /// Whether `path` (a file or folder) is reached for the first time;
    /// a second time is recorded as skipped. Errors read `path: why`.
    pub fn first_visit(&mut self, path: &Path) -> Result<bool, String> {
        let k = key(path)?;
        if let Some(first) = self.seen.get(&k) {
            self.skipped.push(Skipped {
                path: path.to_path_buf(),
                first: first.clone(),
                is_loop: self.inside.contains(&k),
            });
            return Ok(false);
        }
        self.seen.insert(k, path.to_path_buf());
        Ok(true)
    }

    /// Walks the folder `root` recursively: folders below it are entered
    /// when `keep(Entry::Dir)` says so, files for which `keep(Entry::File)`
    /// holds are appended to `out`, each file and folder at most once.
    pub fn dir(
        &mut self,
        root: &Path,
        keep: &mut dyn FnMut(Entry) -> bool,
        out: &mut Vec<PathBuf>,
    ) -> Result<(), String> {
        if !self.first_visit(root)? {
            return Ok(());
        }
        self.inside(root, keep, out)
    }

    fn inside(
        &mut self,
        dir: &Path,
        keep: &mut dyn FnMut(Entry) -> bool,
        out: &mut Vec<PathBuf>,
    ) -> Result<(), String> {
        self.inside.push(key(dir)?);
        let r = self.entries(dir, keep, out);
        self.inside.pop();
        r
    }

    fn entries(
        &mut self,
        dir: &Path,
        keep: &mut dyn FnMut(Entry) -> bool,
        out: &mut Vec<PathBuf>,
    ) -> Result<(), String> {
        let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
            .map_err(|e| failed(dir, e))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .collect();
        entries.sort();
        for path in entries {
            if path.is_dir() {
                if keep(Entry::Dir(&path)) && self.first_visit(&path)? {
                    self.inside(&path, keep, out)?;
                }
            } else if keep(Entry::File(&path)) {
                // A dangling link has no identity: it is taken, and reading it
                // gives the error that names it.
                if !path.exists() || self.first_visit(&path)? {
                    out.push(path);
                }
            }
        }
        Ok(())
    }
}

#[cfg(all(test, unix))]
#[path = "folder_tests.rs"]
mod tests;
