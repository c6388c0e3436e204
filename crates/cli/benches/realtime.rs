//! Scan-start jitter of a 1 ms task, normal against real-time mode, as the
//! whole `automat run` process reports it (`--stats`): the same program,
//! the same machine, the same run of this benchmark, each phase alone and
//! then with every core kept busy by a CPU-bound load (one spinning
//! process per core, at normal priority), which is where SCHED_FIFO
//! matters. A phase the machine does not grant (no CAP_SYS_NICE) is
//! reported as refused, with the reason.
//!
//! `cargo bench -p automat --bench realtime` (REALTIME_BENCH_SECONDS,
//! default 5, per phase).

use std::io::Read;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

const PROGRAM: &str = "PROGRAM Main
VAR t : TON; lamp : BOOL; n : DINT; END_VAR
    t(IN := NOT t.Q, PT := T#100ms);
    IF t.Q THEN lamp := NOT lamp; END_IF;
    n := n + 1;
END_PROGRAM
";

fn load(cores: usize) -> Vec<Child> {
    (0..cores)
        .filter_map(|_| {
            Command::new("sh")
                .args(["-c", "while :; do :; done"])
                .stdout(Stdio::null())
                .spawn()
                .ok()
        })
        .collect()
}

/// The `--stats` lines of one run of `seconds`, or why it did not run.
fn phase(dir: &std::path::Path, realtime: bool, seconds: u64) -> Result<(String, String), String> {
    let mut args = vec!["run", "main.st", "--cycle-time", "1ms", "--stats"];
    if realtime {
        args.extend(["--realtime", "--cpus", "0"]);
    }
    let mut child = Command::new(env!("CARGO_BIN_EXE_automat"))
        .args(&args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| e.to_string())?;
    std::thread::sleep(Duration::from_secs(seconds));
    let _ = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status();
    let _ = child.wait();
    let mut err = String::new();
    if let Some(mut e) = child.stderr.take() {
        let _ = e.read_to_string(&mut err);
    }
    let find = |prefix: &str| {
        err.lines()
            .find(|l| l.starts_with(prefix))
            .map(|l| l.trim_start_matches(prefix).to_string())
    };
    match (find("scans: "), find("scan start jitter: ")) {
        (Some(scans), Some(jitter)) => Ok((scans, jitter)),
        _ => Err(err
            .lines()
            .find(|l| l.starts_with("error:"))
            .unwrap_or("no statistics")
            .to_string()),
    }
}

fn main() {
    let seconds: u64 = std::env::var("REALTIME_BENCH_SECONDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(5);
    let dir = std::env::temp_dir().join(format!("automat-rt-bench-{}", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    if std::fs::write(dir.join("main.st"), PROGRAM).is_err() {
        eprintln!("cannot write the benchmark program");
        return;
    }
    let cores = std::thread::available_parallelism().map_or(2, |n| n.get());
    println!("1 ms task, {seconds} s per phase, {cores} cores; jitter = how late each scan starts");
    println!();
    println!("| mode | load | scans, overruns | scan start jitter |");
    println!("|---|---|---|---|");
    for loaded in [false, true] {
        let hogs = if loaded { load(cores) } else { Vec::new() };
        for realtime in [false, true] {
            let mode = if realtime {
                "--realtime (SCHED_FIFO 80, CPU 0)"
            } else {
                "normal"
            };
            let what = if loaded {
                format!("{cores} CPU hogs")
            } else {
                "idle".into()
            };
            match phase(&dir, realtime, seconds) {
                Ok((scans, jitter)) => {
                    let short: String = scans.split(", scan time").next().unwrap_or("").to_string();
                    let overruns = scans
                        .split(", ")
                        .find(|p| p.starts_with("overruns"))
                        .unwrap_or("");
                    println!("| {mode} | {what} | {short}, {overruns} | {jitter} |");
                }
                Err(e) => println!("| {mode} | {what} | refused | {e} |"),
            }
        }
        for mut h in hogs {
            let _ = h.kill();
            let _ = h.wait();
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
