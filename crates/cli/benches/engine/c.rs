//! The C side of the engine benchmark (issue 15 point 2): `kernels.c`
//! compiled with the system compiler (`cc -O2`, or `$CC`) in the same run,
//! then run in process (its own clock around the kernel) and as a whole
//! process, against the JIT in process and the whole `automat run` process.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

/// The compiled `kernels` executable.
pub struct Kernels {
    exe: PathBuf,
}

/// What one run of the executable printed.
pub struct Printed {
    /// The `native TEXT` line: what the Rust version returns.
    pub native: String,
    /// The `NAME = value` lines, as `automat run --print` prints them.
    pub values: Vec<String>,
    /// The best run's time measured inside the process.
    pub best: Duration,
}

impl Kernels {
    /// Compiles `kernels.c` into `dir`; the error says why (no compiler).
    pub fn build(dir: &Path) -> Result<Kernels, String> {
        let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/engine/kernels.c");
        let exe = dir.join(format!("automat-bench-kernels-{}", std::process::id()));
        let cc = std::env::var("CC").unwrap_or_else(|_| "cc".to_string());
        let out = Command::new(&cc)
            .arg("-O2")
            .arg("-o")
            .arg(&exe)
            .arg(&src)
            .output()
            .map_err(|e| format!("{cc}: {e}"))?;
        if !out.status.success() {
            return Err(format!(
                "{cc} -O2 {}: {}",
                src.display(),
                String::from_utf8_lossy(&out.stderr)
            ));
        }
        Ok(Kernels { exe })
    }

    /// Runs case `name` `runs` times in one process, scans `period_ns`
    /// apart.
    pub fn run(&self, name: &str, runs: usize, period_ns: i64) -> Result<Printed, String> {
        let out = Command::new(&self.exe)
            .arg(name)
            .arg(runs.to_string())
            .arg(period_ns.to_string())
            .output()
            .map_err(|e| format!("{}: {e}", self.exe.display()))?;
        if !out.status.success() {
            return Err(format!(
                "kernels {name}: {}",
                String::from_utf8_lossy(&out.stderr)
            ));
        }
        let text = String::from_utf8_lossy(&out.stdout);
        let mut printed = Printed {
            native: String::new(),
            values: Vec::new(),
            best: Duration::ZERO,
        };
        for line in text.lines() {
            if let Some(n) = line.strip_prefix("native ") {
                printed.native = n.to_string();
            } else if let Some(ns) = line.strip_prefix("best_ns ") {
                let ns = ns.parse().map_err(|_| format!("kernels {name}: {line}"))?;
                printed.best = Duration::from_nanos(ns);
            } else {
                printed.values.push(line.to_string());
            }
        }
        Ok(printed)
    }

    /// The best wall time of `runs` whole processes each running case
    /// `name` `repeat` times, and what the last one printed.
    pub fn whole(
        &self,
        name: &str,
        runs: usize,
        repeat: u32,
        period_ns: i64,
    ) -> Result<(Duration, Printed), String> {
        let mut best = Duration::MAX;
        let mut last = None;
        for _ in 0..runs.max(1) {
            let t = Instant::now();
            let p = self.run(name, repeat as usize, period_ns)?;
            best = best.min(t.elapsed());
            last = Some(p);
        }
        last.map(|p| (best, p)).ok_or_else(|| "no run".to_string())
    }
}

impl Drop for Kernels {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.exe);
    }
}

/// `NAME = value` lines compared exactly: the same text, or two LREALs
/// that read back to the same bits (C prints 17 digits, automat the
/// shortest text that reads back).
pub fn same_values(automat: &[String], c: &[String]) -> bool {
    automat.len() == c.len()
        && automat.iter().zip(c).all(|(a, b)| {
            a == b
                || match (a.split_once(" = "), b.split_once(" = ")) {
                    (Some((na, va)), Some((nb, vb))) => {
                        na == nb
                            && matches!((va.parse::<f64>(), vb.parse::<f64>()),
                                (Ok(x), Ok(y)) if x.to_bits() == y.to_bits())
                    }
                    _ => false,
                }
        })
}
