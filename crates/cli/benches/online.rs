//! The scan is never disturbed by online clients: the crane example at its
//! 10 ms period in real time (JIT), first alone, then in the same run with
//! 10 WebSocket clients each watching 100 values at 10 Hz plus 100
//! read/write requests per second (`tests/online/load.py`, Python
//! `requests` + `websockets`). Reported: overruns and the scan-start
//! jitter (how late each scan starts after its deadline, less the least
//! lateness seen) with and without clients; the bar is zero overruns and
//! a p99 at most 20 µs above the run without clients.
//!
//! `cargo bench -p automat --bench online` (ONLINE_BENCH_SECONDS, default
//! 20, per phase).

use automat_base::SourceMap;
use automat_online::Options;
use automat_project::{bind, build, Sim};
use automat_runtime::{ClockMode, SystemClock};
use automat_session::{Config, Parts, Session};
use std::cell::RefCell;
use std::path::Path;
use std::process::Command;
use std::rc::Rc;
use std::sync::atomic::AtomicBool;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

#[path = "support/probe.rs"]
mod probe;
use probe::{percentile, Probe};

fn main() {
    let seconds: u64 = std::env::var("ONLINE_BENCH_SECONDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20);
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let toml = root.join("examples/crane/automat.toml");
    let mut map = SourceMap::new();
    let project = automat_project::load(&toml, &mut map).expect("crane project");
    let (program, _) = build::compile(
        &project.sources,
        project.program.clone(),
        &project.libraries,
    )
    .unwrap_or_else(|e| panic!("{}", e.text));
    let program = Arc::new(program);
    let p = (*program).clone();
    let lateness = Arc::new(Mutex::new(Vec::with_capacity(8192)));
    let probe_lateness = Arc::clone(&lateness);
    let cycle = project.cycle_time_ns;
    let config = Config {
        cycle_time_ns: cycle,
        clock: ClockMode::RealTime,
        monotonic: Box::new(SystemClock::new()),
        running: true,
        stop: Arc::new(AtomicBool::new(false)),
        retain: None,
        safe: None,
        realtime: None,
        wait_after_fault: true,
    };
    let session = Arc::new(
        Session::start(
            Arc::clone(&program),
            config,
            Box::new(move || {
                let plant = project.new_plant().ok().flatten().ok_or("plant")?;
                let spec = project.plant.clone().ok_or("plant")?;
                let (bindings, _) = bind(&spec, plant.as_ref(), &p);
                let sim = Sim::new(plant, bindings.ok_or("bindings")?, spec.seed);
                let jit = automat_jit::Jit::new(p).map_err(|e| e.to_string())?;
                Ok(Parts {
                    exec: Box::new(Probe {
                        inner: jit,
                        epoch: Instant::now(),
                        last: None,
                        lateness: probe_lateness,
                    }),
                    sim: Some(Rc::new(RefCell::new(sim))),
                    observer: None,
                    exchange: None,
                })
            }),
        )
        .expect("session"),
    );
    let token = automat_online::auth::random_token().expect("token");
    let mut opts = Options::new("127.0.0.1:0".parse().expect("address"));
    opts.token = Some(token.clone());
    let server = automat_online::start(Arc::clone(&session), opts).expect("server");
    let url = format!("http://{}", server.addr);

    // 100 distinct watched paths: the crane's variables in several spellings.
    let base: Vec<String> = automat_session::symbols::tree(&program, "Ctrl")
        .unwrap_or_default()
        .iter()
        .flat_map(|n| n.children.iter())
        .flat_map(|n| {
            if n.children.is_empty() {
                vec![n.path.clone()]
            } else {
                n.children.iter().map(|c| c.path.clone()).collect()
            }
        })
        .collect();
    let mut paths = Vec::new();
    'fill: for variant in 0.. {
        for b in &base {
            let p = match variant {
                0 => b.clone(),
                1 => b.to_ascii_uppercase(),
                2 => b.to_ascii_lowercase(),
                _ => format!(
                    "{}{}",
                    &b[..1].to_ascii_lowercase(),
                    &b[1..].to_ascii_uppercase()
                ),
            };
            if !paths.contains(&p) {
                paths.push(p);
            }
            if paths.len() == 100 {
                break 'fill;
            }
        }
        if variant > 5 {
            break;
        }
    }

    eprintln!("online bench: {seconds} s without clients, then {seconds} s with them");
    std::thread::sleep(Duration::from_secs(1));
    let t_a = session.snapshot().plc_time_ns;
    let over_a0 = session.snapshot().stats.overruns;
    std::thread::sleep(Duration::from_secs(seconds));
    let t_b = session.snapshot().plc_time_ns;
    let over_b0 = session.snapshot().stats.overruns;
    let load = Command::new("python3")
        .arg(root.join("crates/cli/tests/online/load.py"))
        .args([&url, &token, &seconds.to_string()])
        .args(&paths)
        .output()
        .expect("python3 load.py (needs requests, websockets)");
    let t_c = session.snapshot().plc_time_ns;
    let over_c = session.snapshot().stats.overruns;
    let counts = String::from_utf8_lossy(&load.stdout).trim().to_string();
    if !load.status.success() {
        eprintln!("{}", String::from_utf8_lossy(&load.stderr));
        panic!("the load failed");
    }
    drop(server);
    let _ = session.shutdown();

    let all = lateness.lock().map(|l| l.clone()).unwrap_or_default();
    let least = all.iter().map(|(_, l)| *l).min().unwrap_or(0);
    let phase = |from: i64, to: i64| {
        let mut v: Vec<i64> = all
            .iter()
            .filter(|(t, _)| *t >= from && *t < to)
            .map(|(_, l)| l - least)
            .collect();
        v.sort_unstable();
        v
    };
    let a = phase(t_a, t_b);
    let b = phase(t_b, t_c);
    let us = |ns: i64| format!("{:.1} µs", ns as f64 / 1000.0);
    println!("online: crane, 10 ms period, real time, JIT; {seconds} s per phase; load: {counts}");
    println!();
    println!("| run | scans | overruns | jitter p50 | jitter p99 | jitter max |");
    println!("|---|---|---|---|---|---|");
    println!(
        "| without clients | {} | {} | {} | {} | {} |",
        a.len(),
        over_b0 - over_a0,
        us(percentile(&a, 0.5)),
        us(percentile(&a, 0.99)),
        us(a.last().copied().unwrap_or(0))
    );
    println!(
        "| 10 WS clients x 100 values at 10 Hz + 100 req/s | {} | {} | {} | {} | {} |",
        b.len(),
        over_c - over_b0,
        us(percentile(&b, 0.5)),
        us(percentile(&b, 0.99)),
        us(b.last().copied().unwrap_or(0))
    );
    let growth = percentile(&b, 0.99) - percentile(&a, 0.99);
    let verdict = if over_c == over_b0 && growth <= 20_000 {
        "meets the bar"
    } else {
        "misses the bar"
    };
    println!();
    println!(
        "p99 growth with clients: {} (bar ≤ 20 µs, zero overruns): {verdict}",
        us(growth)
    );
}
