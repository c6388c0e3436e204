//! What the end-to-end tests of the servers share (`tests/modbus.rs`,
//! `tests/modbus_rtu.rs`, `tests/opcua.rs`, `tests/online_api.rs`,
//! `tests/hmi.rs`): the binary, temporary folders, pymodbus, users made
//! with `automat passwd`, and child processes whose output is watched.
#![allow(dead_code)]

use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

pub fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_automat")
}

pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A `[users.NAME]` table for automat.toml, made by `automat passwd`.
pub fn hash(user: &str, role: &str, password: &str) -> String {
    let mut child = Command::new(bin())
        .args(["passwd", user, "--role", role])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .expect("automat passwd");
    if let Some(mut stdin) = child.stdin.take() {
        writeln!(stdin, "{password}").expect("password");
    }
    let out = child.wait_with_output().expect("automat passwd");
    assert!(out.status.success());
    String::from_utf8(out.stdout).expect("utf-8")
}

pub fn scripts() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/modbus")
}

pub fn pymodbus_ready() {
    let ok = Command::new("python3")
        .args([
            "-c",
            "import pymodbus; assert pymodbus.__version__ == '3.6.9'",
        ])
        .status()
        .is_ok_and(|s| s.success());
    assert!(
        ok,
        "python3 with pymodbus 3.6.9 is needed: python3 -m pip install pymodbus==3.6.9 (as .ci/run does)"
    );
}

pub fn temp(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("automat-modbus-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// A child process that is stopped (SIGTERM, then killed) when dropped.
pub struct Proc {
    child: Child,
    lines: mpsc::Receiver<String>,
}

impl Proc {
    pub fn start(cmd: &mut Command, name: &'static str) -> Proc {
        let mut child = cmd
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("spawn");
        let (tx, rx) = mpsc::channel();
        for out in [
            child
                .stdout
                .take()
                .map(|o| Box::new(o) as Box<dyn std::io::Read + Send>),
            child
                .stderr
                .take()
                .map(|e| Box::new(e) as Box<dyn std::io::Read + Send>),
        ]
        .into_iter()
        .flatten()
        {
            let tx = tx.clone();
            std::thread::spawn(move || {
                for line in BufReader::new(out).lines().map_while(Result::ok) {
                    eprintln!("{name}: {line}");
                    let _ = tx.send(line);
                }
            });
        }
        Proc { child, lines: rx }
    }

    /// Waits for a line containing `what`; returns it.
    pub fn wait_for(&self, what: &str, within: Duration) -> String {
        let end = Instant::now() + within;
        loop {
            let left = end.saturating_duration_since(Instant::now());
            match self.lines.recv_timeout(left) {
                Ok(l) if l.contains(what) => return l,
                Ok(_) => {}
                Err(_) => panic!("no line with `{what}` within {within:?}"),
            }
        }
    }

    /// SIGTERM (the PLC stops at the end of a scan), then the exit status.
    pub fn stop(&mut self) -> Option<i32> {
        let _ = Command::new("kill")
            .args(["-TERM", &self.child.id().to_string()])
            .status();
        let end = Instant::now() + Duration::from_secs(20);
        while Instant::now() < end {
            if let Ok(Some(s)) = self.child.try_wait() {
                return s.code();
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        let _ = self.child.kill();
        self.child.wait().ok().and_then(|s| s.code())
    }

    /// Every line printed so far.
    pub fn drain(&self) -> Vec<String> {
        self.lines.try_iter().collect()
    }
}

impl Drop for Proc {
    fn drop(&mut self) {
        if let Ok(None) = self.child.try_wait() {
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
    }
}
