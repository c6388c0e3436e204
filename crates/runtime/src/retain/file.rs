//! Writing the RETAIN file atomically and durably, without trusting what
//! else is in its directory.
//!
//! A save writes `<file>.tmp` beside the target, created exclusively
//! (`O_CREAT | O_EXCL | O_NOFOLLOW`, mode 0600: a symlink or file planted
//! under that name is never followed or reused, and other users cannot
//! read the values), fsyncs it, renames it over the target and fsyncs the
//! directory, so a crash at any moment leaves either the old or the new
//! file. A `<file>.tmp` left by a crash is unlinked first: unlinking
//! removes a planted symlink itself, never its target.

use std::ffi::OsString;
use std::fs;
use std::io::{ErrorKind, Write};
use std::path::{Path, PathBuf};

/// The temporary file a save writes before renaming it over `path`.
pub fn temp_path(path: &Path) -> Option<PathBuf> {
    let mut name: OsString = path.file_name()?.to_os_string();
    name.push(".tmp");
    Some(path.with_file_name(name))
}

/// The folder holding `path` (`.` for a bare file name).
pub fn dir_of(path: &Path) -> &Path {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    }
}

/// Removes a temporary file left by an interrupted save. Only a file or a
/// symlink is removed (`remove_file` unlinks a symlink without following
/// it); a directory of that name is an error.
fn remove_stale(tmp: &Path) -> std::io::Result<()> {
    match fs::symlink_metadata(tmp) {
        Ok(m) if m.is_dir() => Err(std::io::Error::new(
            ErrorKind::AlreadyExists,
            format!("{} is a directory", tmp.display()),
        )),
        Ok(_) => fs::remove_file(tmp),
        Err(e) if e.kind() == ErrorKind::NotFound => Ok(()),
        Err(e) => Err(e),
    }
}

/// Creates `tmp` exclusively, never through a symlink, readable by its
/// owner only.
fn create_exclusive(tmp: &Path) -> std::io::Result<fs::File> {
    let mut opts = fs::OpenOptions::new();
    opts.write(true).create_new(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        opts.mode(0o600).custom_flags(libc::O_NOFOLLOW);
    }
    opts.open(tmp)
}

/// Writes `data` to `tmp` (fsynced when `durable`); the temporary is
/// removed on an error.
fn write_temp(tmp: &Path, data: &[u8], durable: bool) -> std::io::Result<()> {
    remove_stale(tmp)?;
    let mut f = create_exclusive(tmp)?;
    let written = f
        .write_all(data)
        .and_then(|()| if durable { f.sync_all() } else { Ok(()) });
    drop(f);
    if written.is_err() {
        let _ = fs::remove_file(tmp);
    }
    written
}

/// Replaces `path` by `data` atomically and durably (see the module
/// comment).
pub fn replace(path: &Path, data: &[u8]) -> std::io::Result<()> {
    let tmp = temp_path(path)
        .ok_or_else(|| std::io::Error::new(ErrorKind::InvalidInput, "not a file name"))?;
    write_temp(&tmp, data, true)?;
    if let Err(e) = fs::rename(&tmp, path) {
        let _ = fs::remove_file(&tmp);
        return Err(e);
    }
    // The rename is only durable once the directory entry is on disk.
    fs::File::open(dir_of(path))?.sync_all()
}

/// A test save before the first scan: the directory exists and takes a
/// new file of `size` bytes (the temporary, removed again), and `path` is
/// not a directory. The RETAIN file itself is left as it is.
pub fn check_writable(path: &Path, size: usize) -> Result<(), String> {
    let shown = path.display();
    let dir = dir_of(path);
    match fs::metadata(dir) {
        Ok(m) if m.is_dir() => {}
        Ok(_) => return Err(format!("{shown}: {} is not a directory", dir.display())),
        Err(e) => return Err(format!("{shown}: the directory {}: {e}", dir.display())),
    }
    if fs::symlink_metadata(path).is_ok_and(|m| m.is_dir()) {
        return Err(format!("{shown}: is a directory"));
    }
    let tmp = temp_path(path).ok_or_else(|| format!("{shown}: not a file name"))?;
    let probe = vec![0u8; size];
    // Not fsynced: the probe only shows the folder takes the file.
    let result = write_temp(&tmp, &probe, false).and_then(|()| fs::remove_file(&tmp));
    result.map_err(|e| format!("{shown}: a test save failed: {e}"))
}

/// Moves an unusable RETAIN file aside to `<file>.bad` (replacing an older
/// one), so the next save does not destroy what it held. Returns the new
/// name.
pub fn move_aside(path: &Path) -> std::io::Result<PathBuf> {
    let mut name: OsString = path
        .file_name()
        .ok_or_else(|| std::io::Error::new(ErrorKind::InvalidInput, "not a file name"))?
        .to_os_string();
    name.push(".bad");
    let bad = path.with_file_name(name);
    fs::rename(path, &bad)?;
    Ok(bad)
}
