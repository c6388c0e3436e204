//! Writing to stdout and stderr when the reader may be gone.
//!
//! `automat check x.st | head -1` closes the pipe after one line. The
//! standard `println!` panics on the write error that follows (exit 101
//! and a panic message); restoring the default SIGPIPE action instead,
//! as C tools do, would kill `automat run` in the middle of a scan, with
//! no safe state and no RETAIN saved. So the binary keeps Rust's ignored
//! SIGPIPE and writes through these functions: output to a closed pipe is
//! dropped without a word, the command carries on and exits with the code
//! it would have returned anyway (0 ok, 1 program errors, ...), which is
//! what a script reading `${PIPESTATUS[0]}` needs. Any other write error
//! (a full disk behind a redirect) is said once on stderr.
//!
//! `main.rs` defines `print!`, `println!`, `eprint!` and `eprintln!`
//! before every module, shadowing the standard macros in the whole
//! binary, so no code path of the CLI can panic on a closed stream.

use std::fmt;
use std::io::{ErrorKind, Write};
use std::sync::atomic::{AtomicBool, Ordering};

/// A write error other than a closed pipe was already reported.
static REPORTED: AtomicBool = AtomicBool::new(false);

/// Writes to stdout; a closed pipe is ignored.
pub fn stdout(args: fmt::Arguments) {
    let mut out = std::io::stdout().lock();
    if let Err(e) = out.write_fmt(args).and_then(|()| out.flush()) {
        drop(out);
        report("stdout", &e);
    }
}

/// Writes to stderr; a closed pipe is ignored.
pub fn stderr(args: fmt::Arguments) {
    if let Err(e) = std::io::stderr().lock().write_fmt(args) {
        report("stderr", &e);
    }
}

fn report(stream: &str, e: &std::io::Error) {
    if e.kind() == ErrorKind::BrokenPipe || REPORTED.swap(true, Ordering::Relaxed) {
        return;
    }
    let _ = writeln!(std::io::stderr(), "error: cannot write to {stream}: {e}");
}
