//! The scan is never disturbed by Modbus and OPC UA clients: the crane
//! example at its 10 ms period in real time (JIT), with the Modbus TCP
//! server and the OPC UA server on loopback, first without clients, then in
//! the same run with 10 Modbus clients each reading 100 holding registers
//! at 100 Hz (FC 3, 1,000 requests/s in all), every tenth poll also writing
//! 10 registers (FC 16, 100 writes/s through the session), plus an OPC UA
//! client (Python `asyncua`, `support/opcua_load.py`) subscribed to 500
//! nodes at 10 ms — the 500 words `ua_0..ua_499` that the Modbus writes
//! change. Reported: overruns and the scan-start jitter (how late each scan
//! starts after its deadline, less the least lateness seen) with and
//! without clients; the bar is zero overruns with clients.
//!
//! `cargo bench -p automat --bench modbus` (MODBUS_BENCH_SECONDS, default
//! 15, per phase).

use automat_base::SourceMap;
use automat_fieldbus::client::Conn;
use automat_fieldbus::map::Map;
use automat_fieldbus::pdu::{Request, Response, Table};
use automat_fieldbus::server::{self, Options, SessionDevice};
use automat_project::{bind, build, Sim};
use automat_runtime::{ClockMode, SystemClock};
use automat_session::{Config, Parts, Session};
use std::cell::RefCell;
use std::path::Path;
use std::rc::Rc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

#[path = "support/probe.rs"]
mod probe;
use probe::{percentile, Probe};

/// Nodes the OPC UA client subscribes to.
const UA_NODES: usize = 500;

fn main() {
    let seconds: u64 = std::env::var("MODBUS_BENCH_SECONDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(15);
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let toml = root.join("examples/crane/automat.toml");
    let mut map = SourceMap::new();
    let project = automat_project::load(&toml, &mut map).expect("crane project");
    // 200 memory words beside the crane (%MW0..%MW199 = holding 1024..1223),
    // then 500 words the OPC UA client watches (%MW200.. = holding 1224..).
    let extra =
        std::env::temp_dir().join(format!("automat-modbus-bench-{}.st", std::process::id()));
    let mut text = String::from("VAR_GLOBAL\n    modbus_words AT %MW199 : INT;\n");
    for i in 0..UA_NODES {
        text.push_str(&format!("    ua_{i} AT %MW{} : INT;\n", 200 + i));
    }
    text.push_str("END_VAR\n");
    std::fs::write(&extra, text).expect("extra source");
    let mut sources = project.sources.clone();
    sources.push(extra.clone());
    let (program, _) = build::compile(&sources, project.program.clone(), &project.libraries)
        .unwrap_or_else(|e| panic!("{}", e.text));
    let _ = std::fs::remove_file(&extra);
    let program = Arc::new(program);
    let p = (*program).clone();
    let lateness = Arc::new(Mutex::new(Vec::with_capacity(8192)));
    let probe_lateness = Arc::clone(&lateness);
    let config = Config {
        cycle_time_ns: project.cycle_time_ns,
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
    let dev = SessionDevice {
        session: Arc::clone(&session),
        map: Map::default_of(&program),
    };
    let srv = server::start(
        Arc::new(dev),
        Options::new("127.0.0.1:0".parse().expect("address")),
    )
    .expect("server");
    #[cfg(feature = "opcua")]
    let pki = std::env::temp_dir().join(format!("automat-modbus-bench-pki-{}", std::process::id()));
    #[cfg(feature = "opcua")]
    let ua = automat_opcua::start(
        Arc::clone(&session),
        automat_opcua::Options {
            addr: "127.0.0.1:0".parse().expect("address"),
            pki_dir: pki.clone(),
            users: Vec::new(),
            trust_client_certs: false,
            sample_ns: 10_000_000,
        },
    )
    .expect("OPC UA server");

    eprintln!("modbus bench: {seconds} s without clients, then {seconds} s with them");
    std::thread::sleep(Duration::from_secs(1));
    let t_a = session.snapshot().plc_time_ns;
    let over_a0 = session.snapshot().stats.overruns;
    std::thread::sleep(Duration::from_secs(seconds));
    let t_b = session.snapshot().plc_time_ns;
    let over_b0 = session.snapshot().stats.overruns;
    let (reads, writes, errors) = (
        Arc::new(AtomicU64::new(0)),
        Arc::new(AtomicU64::new(0)),
        Arc::new(AtomicU64::new(0)),
    );
    let until = Instant::now() + Duration::from_secs(seconds);
    #[cfg(feature = "opcua")]
    let ua_client = std::process::Command::new("python3")
        .arg(root.join("crates/cli/benches/support/opcua_load.py"))
        .arg(format!("opc.tcp://{}", ua.addr))
        .arg(UA_NODES.to_string())
        .arg(seconds.to_string())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .expect("python3 with asyncua (python3 -m pip install asyncua)");
    let clients: Vec<_> = (0..10u16)
        .map(|k| {
            let (reads, writes, errors) =
                (Arc::clone(&reads), Arc::clone(&writes), Arc::clone(&errors));
            let addr = srv.addr;
            std::thread::spawn(move || {
                let mut c = Conn::connect(addr, 1, Duration::from_secs(2)).expect("connect");
                let mut next = Instant::now();
                let mut n = 0u64;
                while Instant::now() < until {
                    let r = c.call(&Request::Read {
                        table: Table::HoldingRegisters,
                        addr: 1024,
                        count: 100,
                    });
                    match r {
                        Ok(Response::Registers(v)) if v.len() == 100 => {
                            reads.fetch_add(1, Ordering::Relaxed);
                        }
                        _ => {
                            errors.fetch_add(1, Ordering::Relaxed);
                        }
                    }
                    if n.is_multiple_of(10) {
                        let values: Vec<u16> =
                            (0..10).map(|i| (n as u16).wrapping_add(i)).collect();
                        // Into the words the OPC UA client watches.
                        match c.call(&Request::WriteRegisters {
                            addr: 1224 + 50 * k,
                            values,
                        }) {
                            Ok(_) => writes.fetch_add(1, Ordering::Relaxed),
                            Err(_) => errors.fetch_add(1, Ordering::Relaxed),
                        };
                    }
                    n += 1;
                    next += Duration::from_millis(10);
                    let now = Instant::now();
                    if next > now {
                        std::thread::sleep(next - now);
                    }
                }
            })
        })
        .collect();
    for c in clients {
        let _ = c.join();
    }
    #[cfg(feature = "opcua")]
    let ua_line = {
        let out = ua_client.wait_with_output().expect("the OPC UA client");
        let text = String::from_utf8_lossy(&out.stdout).trim().to_string();
        (out.status.success(), text)
    };
    #[cfg(not(feature = "opcua"))]
    let ua_line = (true, "opcua: not built (feature `opcua` off)".to_string());
    let t_c = session.snapshot().plc_time_ns;
    let over_c = session.snapshot().stats.overruns;
    drop(srv);
    #[cfg(feature = "opcua")]
    {
        drop(ua);
        let _ = std::fs::remove_dir_all(&pki);
    }
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
    let (r, w, e) = (
        reads.load(Ordering::Relaxed),
        writes.load(Ordering::Relaxed),
        errors.load(Ordering::Relaxed),
    );
    println!(
        "modbus: crane, 10 ms period, real time, JIT; {seconds} s per phase; load: {r} reads of 100 registers ({}/s), {w} writes of 10 ({}/s), {e} errors",
        r / seconds.max(1),
        w / seconds.max(1)
    );
    println!("{}", ua_line.1);
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
        "| 10 Modbus clients x 100 registers at 100 Hz + 100 writes/s + OPC UA x {UA_NODES} nodes | {} | {} | {} | {} | {} |",
        b.len(),
        over_c - over_b0,
        us(percentile(&b, 0.5)),
        us(percentile(&b, 0.99)),
        us(b.last().copied().unwrap_or(0))
    );
    let verdict = if over_c == over_b0 && e == 0 && ua_line.0 {
        "meets the bar"
    } else {
        "misses the bar"
    };
    println!();
    println!(
        "p99 growth with clients: {}; zero overruns with clients: {verdict}",
        us(percentile(&b, 0.99) - percentile(&a, 0.99))
    );
}
