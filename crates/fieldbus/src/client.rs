//! The Modbus client (master) for remote I/O, over TCP or over a serial
//! line (RTU, `rtu_client.rs`).
//!
//! Each configured device has a poller thread of its own: it connects,
//! and every `period` reads each `read` block and writes each `write`
//! block (outputs are written every period, so a device that restarted
//! gets them again), each request with the device's `timeout` and
//! `retries`. The scan thread only copies ([`Clients`] is the session's
//! [`Exchange`]): between scans the latest values read go into the image,
//! after each scan the values to write are taken from it. A dead device
//! therefore never stalls the scan; it shows in its status variables
//! (`connected` FALSE, `errors` counting up, `last_error` its code), and
//! with `on_loss = "zero"` (the default) its inputs read 0/FALSE until it
//! answers again (`"hold"` keeps the last values).
//!
//! `last_error` codes: 0 none, 1–11 the device's exception code, −1 a
//! timeout, −2 no connection (refused, closed, reset), −3 a malformed or
//! mismatched response (over RTU also a CRC error or another unit
//! answering).
//!
//! RTU devices on one serial port share it ([`crate::rtu_client::Bus`]):
//! their pollers take turns, one request and its response at a time.

use crate::map::WordOrder;
use crate::pdu::{self, Request, Response, ResponseError, Table};
use crate::rtu_client::Bus;
use crate::serial::Line;
use automat_session::Exchange;
use std::collections::BTreeMap;
use std::io::{ErrorKind, Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// Where a block's values live in the image.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Target {
    /// Bits from bit `bit` of byte `byte` on, packed (`%IX1.1`).
    Bits { byte: usize, bit: u8 },
    /// One BOOL per value: a bit of a byte or a whole byte.
    Bools(Vec<(usize, Option<u8>)>),
    /// Little-endian words from `base` on (`%IW0`, `%QW4`).
    Words { base: usize },
    /// Register-shaped variables one after another: (offset, registers,
    /// bytes, signed).
    Values {
        items: Vec<(usize, u32, u32, bool)>,
        order: WordOrder,
    },
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Block {
    pub table: Table,
    pub addr: u16,
    pub count: u16,
    pub target: Target,
}

/// What to do with a dead device's inputs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OnLoss {
    Zero,
    Hold,
}

/// Status variables of a device: (offset, bit) of a BOOL, (offset, bytes)
/// of integers.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct StatusPlaces {
    pub connected: Option<(usize, Option<u8>)>,
    pub errors: Option<(usize, usize)>,
    pub last_error: Option<(usize, usize)>,
}

/// How a device is reached.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Link {
    Tcp(SocketAddr),
    Rtu(Line),
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DeviceSpec {
    pub name: String,
    pub link: Link,
    pub unit: u8,
    pub period: Duration,
    pub timeout: Duration,
    pub retries: u32,
    pub on_loss: OnLoss,
    pub reads: Vec<Block>,
    pub writes: Vec<Block>,
    pub status: StatusPlaces,
}

/// Values of one block as Modbus carries them.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Values {
    Bits(Vec<bool>),
    Regs(Vec<u16>),
}

/// What the poller and the scan thread share (held only to copy).
#[derive(Debug, Default)]
struct Shared {
    /// The last values read per read block (`None`: not valid).
    inputs: Vec<Option<Values>>,
    /// The values to write per write block (`None`: no scan yet).
    outputs: Vec<Option<Values>>,
    connected: bool,
    errors: u64,
    last_error: i32,
    last_error_text: String,
}

/// A device's status as the poller last left it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Status {
    pub connected: bool,
    pub errors: u64,
    pub last_error: i32,
    pub last_error_text: String,
}

struct Device {
    spec: DeviceSpec,
    shared: Arc<Mutex<Shared>>,
    thread: Option<JoinHandle<()>>,
}

/// Every client device of a run: the session's [`Exchange`]. Dropping it
/// writes the last outputs given (the safe state at the end of a
/// session) once more and stops the pollers.
pub struct Clients {
    devices: Vec<Device>,
    stop: Arc<AtomicBool>,
}

fn lock(m: &Mutex<Shared>) -> std::sync::MutexGuard<'_, Shared> {
    m.lock().unwrap_or_else(|p| p.into_inner())
}

impl Clients {
    /// Starts one poller thread per device.
    pub fn start(specs: Vec<DeviceSpec>) -> Result<Clients, String> {
        let stop = Arc::new(AtomicBool::new(false));
        let mut devices = Vec::new();
        let mut buses: BTreeMap<String, Arc<Bus>> = BTreeMap::new();
        for spec in specs {
            let bus = match &spec.link {
                Link::Tcp(_) => None,
                Link::Rtu(line) => Some(Arc::clone(
                    buses
                        .entry(line.device.clone())
                        .or_insert_with(|| Arc::new(Bus::new(line.clone()))),
                )),
            };
            let shared = Arc::new(Mutex::new(Shared {
                inputs: vec![None; spec.reads.len()],
                outputs: vec![None; spec.writes.len()],
                ..Shared::default()
            }));
            let (s2, stop2, spec2) = (Arc::clone(&shared), Arc::clone(&stop), spec.clone());
            let thread = std::thread::Builder::new()
                .name(format!("automat-modbus-{}", spec.name))
                .spawn(move || poll(&spec2, &s2, &stop2, bus))
                .map_err(|e| format!("cannot start the Modbus client thread: {e}"))?;
            devices.push(Device {
                spec,
                shared,
                thread: Some(thread),
            });
        }
        Ok(Clients { devices, stop })
    }

    /// The status of each device, by name.
    pub fn status(&self) -> Vec<(String, Status)> {
        self.devices
            .iter()
            .map(|d| {
                let s = lock(&d.shared);
                (
                    d.spec.name.clone(),
                    Status {
                        connected: s.connected,
                        errors: s.errors,
                        last_error: s.last_error,
                        last_error_text: s.last_error_text.clone(),
                    },
                )
            })
            .collect()
    }
}

impl Drop for Clients {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        for d in &mut self.devices {
            if let Some(t) = d.thread.take() {
                let _ = t.join();
            }
        }
    }
}

fn set_int(image: &mut [u8], (offset, bytes): (usize, usize), v: i64) {
    let le = v.to_le_bytes();
    if let (Some(dst), Some(src)) = (image.get_mut(offset..offset + bytes), le.get(..bytes)) {
        dst.copy_from_slice(src);
    }
}

fn set_bool(image: &mut [u8], (offset, bit): (usize, Option<u8>), v: bool) {
    if let Some(b) = image.get_mut(offset) {
        match bit {
            Some(bit) if v => *b |= 1 << (bit & 7),
            Some(bit) => *b &= !(1 << (bit & 7)),
            None => *b = u8::from(v),
        }
    }
}

fn get_bool(image: &[u8], (offset, bit): (usize, Option<u8>)) -> bool {
    image.get(offset).is_some_and(|b| match bit {
        Some(bit) => b & (1 << (bit & 7)) != 0,
        None => *b != 0,
    })
}

/// The image bytes of word `j` (of `width`) of a value at `offset`.
fn word_at(offset: usize, width: u32, j: u32, order: WordOrder) -> usize {
    let w = match order {
        WordOrder::LowFirst => j,
        WordOrder::HighFirst => width - 1 - j,
    };
    offset + 2 * w as usize
}

/// Stores a block's values into the image.
fn put(target: &Target, values: &Values, image: &mut [u8]) {
    match (target, values) {
        (Target::Bits { byte, bit }, Values::Bits(bits)) => {
            for (k, v) in bits.iter().enumerate() {
                let i = usize::from(*bit) + k;
                set_bool(image, (byte + i / 8, Some((i % 8) as u8)), *v);
            }
        }
        (Target::Bools(places), Values::Bits(bits)) => {
            for (p, v) in places.iter().zip(bits) {
                set_bool(image, *p, *v);
            }
        }
        (Target::Words { base }, Values::Regs(regs)) => {
            for (k, r) in regs.iter().enumerate() {
                if let Some(dst) = image.get_mut(base + 2 * k..base + 2 * k + 2) {
                    dst.copy_from_slice(&r.to_le_bytes());
                }
            }
        }
        (Target::Values { items, order }, Values::Regs(regs)) => {
            let mut at = 0usize;
            for &(offset, width, bytes, _) in items {
                if bytes == 1 {
                    if let (Some(b), Some(r)) = (image.get_mut(offset), regs.get(at)) {
                        *b = *r as u8;
                    }
                } else {
                    for j in 0..width {
                        let o = word_at(offset, width, j, *order);
                        if let (Some(dst), Some(r)) =
                            (image.get_mut(o..o + 2), regs.get(at + j as usize))
                        {
                            dst.copy_from_slice(&r.to_le_bytes());
                        }
                    }
                }
                at += width as usize;
            }
        }
        _ => {}
    }
}

/// A block's values taken from the image.
fn take(block: &Block, image: &[u8]) -> Values {
    let n = usize::from(block.count);
    match &block.target {
        Target::Bits { byte, bit } => Values::Bits(
            (0..n)
                .map(|k| {
                    let i = usize::from(*bit) + k;
                    get_bool(image, (byte + i / 8, Some((i % 8) as u8)))
                })
                .collect(),
        ),
        Target::Bools(places) => Values::Bits(places.iter().map(|p| get_bool(image, *p)).collect()),
        Target::Words { base } => Values::Regs(
            (0..n)
                .map(|k| {
                    let o = base + 2 * k;
                    image
                        .get(o..o + 2)
                        .map_or(0, |b| u16::from_le_bytes([b[0], b[1]]))
                })
                .collect(),
        ),
        Target::Values { items, order } => {
            let mut regs = Vec::with_capacity(n);
            for &(offset, width, bytes, signed) in items {
                if bytes == 1 {
                    let b = image.get(offset).copied().unwrap_or(0);
                    regs.push(if signed {
                        i16::from(b as i8) as u16
                    } else {
                        u16::from(b)
                    });
                } else {
                    for j in 0..width {
                        let o = word_at(offset, width, j, *order);
                        regs.push(
                            image
                                .get(o..o + 2)
                                .map_or(0, |b| u16::from_le_bytes([b[0], b[1]])),
                        );
                    }
                }
            }
            Values::Regs(regs)
        }
    }
}

fn zeros(block: &Block) -> Values {
    if block.table.is_bits() {
        Values::Bits(vec![false; usize::from(block.count)])
    } else {
        Values::Regs(vec![0; usize::from(block.count)])
    }
}

impl Exchange for Clients {
    fn inputs(&mut self, image: &mut [u8]) {
        for d in &self.devices {
            let s = lock(&d.shared);
            for (block, v) in d.spec.reads.iter().zip(&s.inputs) {
                match (v, d.spec.on_loss) {
                    (Some(v), _) => put(&block.target, v, image),
                    (None, OnLoss::Zero) => put(&block.target, &zeros(block), image),
                    (None, OnLoss::Hold) => {}
                }
            }
            if let Some(p) = d.spec.status.connected {
                set_bool(image, p, s.connected);
            }
            if let Some(p) = d.spec.status.errors {
                set_int(image, p, i64::try_from(s.errors).unwrap_or(i64::MAX));
            }
            if let Some(p) = d.spec.status.last_error {
                set_int(image, p, i64::from(s.last_error));
            }
        }
    }

    fn outputs(&mut self, image: &[u8]) {
        for d in &self.devices {
            let values: Vec<Values> = d.spec.writes.iter().map(|b| take(b, image)).collect();
            let mut s = lock(&d.shared);
            for (slot, v) in s.outputs.iter_mut().zip(values) {
                *slot = Some(v);
            }
        }
    }
}

/// Why one exchange with the device failed.
#[derive(Debug)]
pub(crate) enum Failure {
    Timeout,
    Connection(String),
    Response(ResponseError),
}

impl Failure {
    fn code(&self) -> i32 {
        match self {
            Failure::Timeout => -1,
            Failure::Connection(_) => -2,
            Failure::Response(ResponseError::Exception(c)) => i32::from(*c),
            Failure::Response(ResponseError::Malformed(_)) => -3,
        }
    }
    pub(crate) fn text(&self) -> String {
        match self {
            Failure::Timeout => "timeout".into(),
            Failure::Connection(e) => format!("connection: {e}"),
            Failure::Response(e) => e.to_string(),
        }
    }
    /// After these the connection is not trusted any more.
    fn closes(&self) -> bool {
        !matches!(self, Failure::Response(ResponseError::Exception(_)))
    }
}

pub(crate) fn io_failure(e: std::io::Error) -> Failure {
    if matches!(e.kind(), ErrorKind::WouldBlock | ErrorKind::TimedOut) {
        Failure::Timeout
    } else {
        Failure::Connection(e.to_string())
    }
}

/// One request and its response, however the device is reached.
trait Transport {
    fn exchange(&mut self, req: &Request) -> Result<Response, Failure>;
}

impl Transport for Conn {
    fn exchange(&mut self, req: &Request) -> Result<Response, Failure> {
        Conn::exchange(self, req)
    }
}

/// A device on a serial line: its unit on the shared bus.
struct RtuConn {
    bus: Arc<Bus>,
    unit: u8,
    timeout: Duration,
}

impl Transport for RtuConn {
    fn exchange(&mut self, req: &Request) -> Result<Response, Failure> {
        self.bus.exchange(self.unit, req, self.timeout)
    }
}

/// One connection to a device.
pub struct Conn {
    stream: TcpStream,
    unit: u8,
    transaction: u16,
    timeout: Duration,
}

impl Conn {
    pub fn connect(addr: SocketAddr, unit: u8, timeout: Duration) -> std::io::Result<Conn> {
        let stream = TcpStream::connect_timeout(&addr, timeout)?;
        stream.set_nodelay(true)?;
        stream.set_write_timeout(Some(timeout))?;
        Ok(Conn {
            stream,
            unit,
            transaction: 0,
            timeout,
        })
    }

    /// One request and its response, within the timeout.
    pub fn call(&mut self, req: &Request) -> Result<Response, String> {
        self.exchange(req).map_err(|f| f.text())
    }

    fn exchange(&mut self, req: &Request) -> Result<Response, Failure> {
        self.transaction = self.transaction.wrapping_add(1);
        let mut body = Vec::with_capacity(pdu::MAX_PDU);
        pdu::encode_request(req, &mut body);
        let mut f = Vec::with_capacity(pdu::HEADER + body.len());
        pdu::frame(self.transaction, self.unit, &body, &mut f);
        self.stream.write_all(&f).map_err(io_failure)?;
        let deadline = Instant::now() + self.timeout;
        let mut head = [0u8; pdu::HEADER];
        self.read_exact(&mut head, deadline)?;
        let h = pdu::parse_header(&head)
            .map_err(|e| Failure::Response(ResponseError::Malformed(e.to_string())))?;
        let mut rest = vec![0u8; usize::from(h.length) - 1];
        self.read_exact(&mut rest, deadline)?;
        if h.transaction != self.transaction {
            return Err(Failure::Response(ResponseError::Malformed(format!(
                "transaction {} answered, {} asked",
                h.transaction, self.transaction
            ))));
        }
        pdu::decode_response(req, &rest).map_err(Failure::Response)
    }

    fn read_exact(&mut self, buf: &mut [u8], deadline: Instant) -> Result<(), Failure> {
        let mut at = 0;
        while at < buf.len() {
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() {
                return Err(Failure::Timeout);
            }
            self.stream
                .set_read_timeout(Some(left))
                .map_err(io_failure)?;
            match self.stream.read(&mut buf[at..]) {
                Ok(0) => return Err(Failure::Connection("closed by the device".into())),
                Ok(n) => at += n,
                Err(e) if e.kind() == ErrorKind::Interrupted => {}
                Err(e) => return Err(io_failure(e)),
            }
        }
        Ok(())
    }
}

fn read_request(b: &Block) -> Request {
    Request::Read {
        table: b.table,
        addr: b.addr,
        count: b.count,
    }
}

fn write_request(b: &Block, v: &Values) -> Option<Request> {
    Some(match (b.table, v) {
        (Table::Coils, Values::Bits(bits)) => Request::WriteCoils {
            addr: b.addr,
            values: bits.clone(),
        },
        (Table::HoldingRegisters, Values::Regs(regs)) => Request::WriteRegisters {
            addr: b.addr,
            values: regs.clone(),
        },
        _ => return None,
    })
}

/// With retries: the first success, or the last failure.
fn with_retries(
    conn: &mut dyn Transport,
    req: &Request,
    retries: u32,
) -> Result<Response, Failure> {
    let mut last = Failure::Timeout;
    for _ in 0..=retries {
        match conn.exchange(req) {
            Ok(r) => return Ok(r),
            Err(f) if f.closes() => return Err(f),
            Err(f) => last = f,
        }
    }
    Err(last)
}

/// One poll of every block; the first failure ends it.
fn poll_once(
    spec: &DeviceSpec,
    conn: &mut dyn Transport,
    shared: &Mutex<Shared>,
) -> Result<(), Failure> {
    for (i, b) in spec.reads.iter().enumerate() {
        let r = with_retries(conn, &read_request(b), spec.retries)?;
        let v = match r {
            Response::Bits(bits) => Values::Bits(bits),
            Response::Registers(regs) => Values::Regs(regs),
            _ => continue,
        };
        if let Some(slot) = lock(shared).inputs.get_mut(i) {
            *slot = Some(v);
        }
    }
    let outputs = lock(shared).outputs.clone();
    for (b, v) in spec.writes.iter().zip(outputs) {
        let Some(req) = v.as_ref().and_then(|v| write_request(b, v)) else {
            continue;
        };
        with_retries(conn, &req, spec.retries)?;
    }
    Ok(())
}

fn failed(spec: &DeviceSpec, shared: &Mutex<Shared>, f: &Failure) {
    let mut s = lock(shared);
    s.errors = s.errors.saturating_add(1);
    s.last_error = f.code();
    s.last_error_text = f.text();
    if f.closes() {
        s.connected = false;
        if spec.on_loss == OnLoss::Zero {
            for v in &mut s.inputs {
                *v = None;
            }
        }
    }
}

/// Sleeps until `until` or the stop flag.
fn nap(until: Instant, stop: &AtomicBool) {
    while !stop.load(Ordering::Relaxed) {
        let now = Instant::now();
        if now >= until {
            return;
        }
        std::thread::sleep((until - now).min(Duration::from_millis(20)));
    }
}

fn poll(spec: &DeviceSpec, shared: &Mutex<Shared>, stop: &AtomicBool, bus: Option<Arc<Bus>>) {
    let mut conn: Option<Box<dyn Transport>> = None;
    let mut next = Instant::now();
    loop {
        let stopping = stop.load(Ordering::Relaxed);
        if conn.is_none() {
            if stopping {
                return;
            }
            match (&spec.link, &bus) {
                (Link::Tcp(addr), _) => match Conn::connect(*addr, spec.unit, spec.timeout) {
                    Ok(c) => {
                        conn = Some(Box::new(c));
                        lock(shared).connected = true;
                    }
                    Err(e) => failed(spec, shared, &io_failure(e)),
                },
                // A serial line has no connection: the device counts as
                // connected once it answers.
                (Link::Rtu(_), Some(bus)) => {
                    conn = Some(Box::new(RtuConn {
                        bus: Arc::clone(bus),
                        unit: spec.unit,
                        timeout: spec.timeout,
                    }))
                }
                (Link::Rtu(_), None) => return,
            }
        }
        if let Some(c) = &mut conn {
            let result = if stopping {
                // The last outputs (the safe state) once more, then stop.
                final_write(spec, c.as_mut(), shared)
            } else {
                poll_once(spec, c.as_mut(), shared)
            };
            match result {
                Ok(()) => {
                    let mut s = lock(shared);
                    s.connected = true;
                }
                Err(f) => {
                    failed(spec, shared, &f);
                    if f.closes() {
                        conn = None;
                    }
                }
            }
        }
        if stopping {
            return;
        }
        next += spec.period;
        let now = Instant::now();
        if next < now {
            // Late (a timeout): the next poll one period from now.
            next = now + spec.period;
        }
        nap(next, stop);
    }
}

fn final_write(
    spec: &DeviceSpec,
    conn: &mut dyn Transport,
    shared: &Mutex<Shared>,
) -> Result<(), Failure> {
    let outputs = lock(shared).outputs.clone();
    for (b, v) in spec.writes.iter().zip(outputs) {
        if let Some(req) = v.as_ref().and_then(|v| write_request(b, v)) {
            with_retries(conn, &req, 0)?;
        }
    }
    Ok(())
}
