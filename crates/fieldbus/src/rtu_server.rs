//! The Modbus RTU slave: one thread owning the serial port, never the scan
//! thread, answering the requests addressed to its unit through the same
//! [`Device`] as the TCP server (so the same map and the same write rules).
//!
//! Requests for other units are someone else's on the bus and ignored;
//! unit 0 is a broadcast: its writes are done and, as the specification
//! requires, not answered (a broadcast read is ignored). A damaged frame
//! is not answered either (the master times out and retries). If the port
//! fails (a USB adapter unplugged) it is reopened every second.

use crate::rtu::{self, Decoder, Event, Side};
use crate::serial::Line;
use crate::server::{handle, Device};
use std::io::{ErrorKind, Read, Write};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::Duration;

/// Counters of a running slave (tests and the log).
#[derive(Debug, Default)]
pub struct Counters {
    pub answered: AtomicU64,
    pub dropped: AtomicU64,
}

/// A running slave; dropping it stops it (within one frame gap) and
/// closes the port.
pub struct RtuServer {
    pub line: Line,
    pub unit: u8,
    pub counters: Arc<Counters>,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

impl Drop for RtuServer {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// Opens `line` and serves `dev` as slave `unit` (1..=247).
pub fn start(dev: Arc<dyn Device>, line: Line, unit: u8) -> Result<RtuServer, String> {
    let gap = line.gap();
    let port = line.open(gap)?;
    let stop = Arc::new(AtomicBool::new(false));
    let counters = Arc::new(Counters::default());
    let (stop2, counters2, line2) = (Arc::clone(&stop), Arc::clone(&counters), line.clone());
    let thread = std::thread::Builder::new()
        .name("automat-modbus-rtu".into())
        .spawn(move || run(port, &line2, dev.as_ref(), unit, &stop2, &counters2))
        .map_err(|e| format!("cannot start the Modbus RTU thread: {e}"))?;
    Ok(RtuServer {
        line,
        unit,
        counters,
        stop,
        thread: Some(thread),
    })
}

/// Function codes that write (the ones a broadcast may carry).
fn writes(pdu: &[u8]) -> bool {
    matches!(pdu.first(), Some(5 | 6 | 15 | 16))
}

fn run(
    mut port: Box<dyn serialport::SerialPort>,
    line: &Line,
    dev: &dyn Device,
    unit: u8,
    stop: &AtomicBool,
    counters: &Counters,
) {
    let gap = line.gap();
    let mut decoder = Decoder::new(Side::Requests);
    let mut chunk = [0u8; rtu::MAX_ADU];
    let mut events = Vec::new();
    let mut resp = Vec::with_capacity(rtu::MAX_ADU);
    let mut out = Vec::with_capacity(rtu::MAX_ADU);
    while !stop.load(Ordering::Relaxed) {
        events.clear();
        match port.read(&mut chunk) {
            Ok(0) => decoder.gap(&mut events),
            Ok(n) => decoder.push(&chunk[..n], &mut events),
            Err(e) if e.kind() == ErrorKind::TimedOut => decoder.gap(&mut events),
            Err(e) if e.kind() == ErrorKind::Interrupted => {}
            Err(_) => {
                // The port failed: reopen it until it comes back or the
                // server stops.
                decoder = Decoder::new(Side::Requests);
                port = loop {
                    if stop.load(Ordering::Relaxed) {
                        return;
                    }
                    std::thread::sleep(Duration::from_secs(1));
                    if let Ok(p) = line.open(gap) {
                        break p;
                    }
                };
                continue;
            }
        }
        for ev in &events {
            let f = match ev {
                Event::Frame(f) => f,
                Event::Dropped(_) => {
                    counters.dropped.fetch_add(1, Ordering::Relaxed);
                    continue;
                }
            };
            if f.unit != unit && !(f.unit == 0 && writes(&f.pdu)) {
                continue;
            }
            resp.clear();
            handle(dev, &f.pdu, &mut resp);
            if f.unit == 0 {
                continue;
            }
            out.clear();
            rtu::frame(unit, &resp, &mut out);
            if port.write_all(&out).and_then(|()| port.flush()).is_ok() {
                counters.answered.fetch_add(1, Ordering::Relaxed);
            }
        }
    }
}
