//! The Modbus TCP server (slave): a thread accepting connections and one
//! thread per connection, never the scan thread.
//!
//! A [`Device`] answers the requests: [`SessionDevice`] reads the PLC's
//! last published snapshot (a read never waits for the scan) and sends
//! writes to the session as one between-scans command (the session's
//! rules hold: a forced location stays forced; CONSTANTs are refused by
//! the map), [`crate::plant::PlantDevice`] serves a virtual plant.
//!
//! Limits: at most `max_connections` at once (a further one is closed at
//! once), clients outside the `allow` list closed at once, a connection
//! idle for `idle_timeout` closed, a partial frame not completed within
//! [`PARTIAL_WITHIN`] closed, an impossible MBAP header closed; every
//! other bad request gets its exception response.

use crate::map::Map;
use crate::pdu::{self, Exception, Request, Response, Table};
use automat_session::Session;
use std::io::{ErrorKind, Read, Write};
use std::net::{IpAddr, SocketAddr, TcpListener, TcpStream};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// A partial frame must be completed within this time.
pub const PARTIAL_WITHIN: Duration = Duration::from_secs(5);
/// How often blocked threads look at the stop flag.
const POLL: Duration = Duration::from_millis(50);

/// What answers the requests of a server.
pub trait Device: Send + Sync + 'static {
    fn read_bits(&self, table: Table, addr: u16, count: u16) -> Result<Vec<bool>, Exception>;
    fn read_registers(&self, table: Table, addr: u16, count: u16) -> Result<Vec<u16>, Exception>;
    fn write_coils(&self, addr: u16, values: &[bool]) -> Result<(), Exception>;
    fn write_registers(&self, addr: u16, values: &[u16]) -> Result<(), Exception>;
}

/// Answers one request PDU into `out` (a response or an exception PDU).
pub fn handle(dev: &dyn Device, pdu: &[u8], out: &mut Vec<u8>) {
    let req = match pdu::decode_request(pdu) {
        Ok(r) => r,
        Err((fc, e)) => return pdu::encode_exception(fc, e, out),
    };
    let fc = req.function();
    let answer = match req {
        Request::Read { table, addr, count } => {
            if table.is_bits() {
                dev.read_bits(table, addr, count).map(Response::Bits)
            } else {
                dev.read_registers(table, addr, count)
                    .map(Response::Registers)
            }
        }
        Request::WriteCoil { addr, value } => {
            dev.write_coils(addr, &[value]).map(|()| Response::Echo {
                addr,
                value: if value { 0xFF00 } else { 0 },
            })
        }
        Request::WriteRegister { addr, value } => dev
            .write_registers(addr, &[value])
            .map(|()| Response::Echo { addr, value }),
        Request::WriteCoils { addr, values } => {
            let count = values.len() as u16;
            dev.write_coils(addr, &values)
                .map(|()| Response::Written { addr, count })
        }
        Request::WriteRegisters { addr, values } => {
            let count = values.len() as u16;
            dev.write_registers(addr, &values)
                .map(|()| Response::Written { addr, count })
        }
        Request::ReadWrite {
            read_addr,
            read_count,
            write_addr,
            values,
        } => dev.write_registers(write_addr, &values).and_then(|()| {
            dev.read_registers(Table::HoldingRegisters, read_addr, read_count)
                .map(Response::Registers)
        }),
    };
    match answer {
        Ok(r) => pdu::encode_response(fc, &r, out),
        Err(e) => pdu::encode_exception(fc, e, out),
    }
}

/// The PLC session as a Modbus device, through its address map.
pub struct SessionDevice {
    pub session: Arc<Session>,
    pub map: Map,
}

impl Device for SessionDevice {
    fn read_bits(&self, table: Table, addr: u16, count: u16) -> Result<Vec<bool>, Exception> {
        let snap = self.session.snapshot();
        self.map.read_bits(table, &snap.image, addr, count)
    }
    fn read_registers(&self, table: Table, addr: u16, count: u16) -> Result<Vec<u16>, Exception> {
        let snap = self.session.snapshot();
        self.map.read_registers(table, &snap.image, addr, count)
    }
    fn write_coils(&self, addr: u16, values: &[bool]) -> Result<(), Exception> {
        let stored = self.map.write_coils(addr, values)?;
        self.session
            .write_stored(stored)
            .map_err(|_| Exception::DeviceFailure)
    }
    fn write_registers(&self, addr: u16, values: &[u16]) -> Result<(), Exception> {
        let stored = self.map.write_registers(addr, values)?;
        self.session
            .write_stored(stored)
            .map_err(|_| Exception::DeviceFailure)
    }
}

/// An allowed client address: one address or a network (`10.0.0.0/8`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Allow {
    pub net: IpAddr,
    pub prefix: u8,
}

impl Allow {
    pub fn parse(s: &str) -> Result<Allow, String> {
        let (ip, prefix) = match s.split_once('/') {
            Some((ip, p)) => (ip, Some(p)),
            None => (s, None),
        };
        let net: IpAddr = ip
            .trim()
            .parse()
            .map_err(|_| format!("`{s}` is not an IP address or network (`10.0.0.0/8`)"))?;
        let max = if net.is_ipv4() { 32 } else { 128 };
        let prefix = match prefix {
            None => max,
            Some(p) => p
                .trim()
                .parse::<u8>()
                .ok()
                .filter(|p| *p <= max)
                .ok_or_else(|| format!("`{s}`: the prefix length must be 0..={max}"))?,
        };
        Ok(Allow { net, prefix })
    }

    pub fn contains(&self, ip: IpAddr) -> bool {
        let ip = match ip {
            IpAddr::V6(v6) => v6.to_ipv4_mapped().map_or(ip, IpAddr::V4),
            v4 => v4,
        };
        match (self.net, ip) {
            (IpAddr::V4(n), IpAddr::V4(a)) => {
                let m = if self.prefix == 0 {
                    0
                } else {
                    u32::MAX << (32 - u32::from(self.prefix))
                };
                u32::from(n) & m == u32::from(a) & m
            }
            (IpAddr::V6(n), IpAddr::V6(a)) => {
                let m = if self.prefix == 0 {
                    0
                } else {
                    u128::MAX << (128 - u32::from(self.prefix))
                };
                u128::from(n) & m == u128::from(a) & m
            }
            _ => false,
        }
    }
}

/// `[ADDR:]PORT`: a port alone binds 127.0.0.1.
pub fn parse_addr(s: &str) -> Result<SocketAddr, String> {
    let s = s.trim();
    if let Ok(port) = s.parse::<u16>() {
        return Ok(SocketAddr::from(([127, 0, 0, 1], port)));
    }
    s.parse::<SocketAddr>().map_err(|_| {
        format!("`{s}` is not PORT or ADDR:PORT (e.g. 5020, 127.0.0.1:5020, [::1]:5020)")
    })
}

#[derive(Clone, Debug)]
pub struct Options {
    pub addr: SocketAddr,
    pub max_connections: usize,
    /// Empty: every client may connect.
    pub allow: Vec<Allow>,
    pub idle_timeout: Duration,
}

impl Options {
    /// Why a server with these options must not start: Modbus has no
    /// passwords, so a server reachable from other hosts that accepts
    /// writes must at least name the clients it takes them from
    /// (`allow`). Loopback, an allow list, or a read-only map is fine; the
    /// caller adds the remedy that fits where the address came from.
    pub fn open_to_writes(&self, read_only: bool) -> Option<String> {
        if self.addr.ip().is_loopback() || !self.allow.is_empty() || read_only {
            return None;
        }
        Some(format!(
            "a Modbus server on {} would take writes from any host (Modbus has no passwords)",
            self.addr
        ))
    }

    pub fn new(addr: SocketAddr) -> Options {
        Options {
            addr,
            max_connections: 16,
            allow: Vec::new(),
            idle_timeout: Duration::from_secs(60),
        }
    }
}

/// A running server; dropping it stops it (open connections end within
/// [`POLL`]).
pub struct Server {
    /// The address bound (the port chosen when 0 was asked).
    pub addr: SocketAddr,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

impl Drop for Server {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// Binds and starts serving `dev`.
pub fn start(dev: Arc<dyn Device>, opts: Options) -> Result<Server, String> {
    let listener =
        TcpListener::bind(opts.addr).map_err(|e| format!("cannot listen on {}: {e}", opts.addr))?;
    let addr = listener
        .local_addr()
        .map_err(|e| format!("cannot listen on {}: {e}", opts.addr))?;
    listener
        .set_nonblocking(true)
        .map_err(|e| format!("cannot listen on {addr}: {e}"))?;
    let stop = Arc::new(AtomicBool::new(false));
    let thread_stop = Arc::clone(&stop);
    let thread = std::thread::Builder::new()
        .name("automat-modbus".into())
        .spawn(move || accept_loop(listener, dev, opts, thread_stop))
        .map_err(|e| format!("cannot start the Modbus server thread: {e}"))?;
    Ok(Server {
        addr,
        stop,
        thread: Some(thread),
    })
}

fn accept_loop(listener: TcpListener, dev: Arc<dyn Device>, opts: Options, stop: Arc<AtomicBool>) {
    let open = Arc::new(AtomicUsize::new(0));
    let mut threads: Vec<JoinHandle<()>> = Vec::new();
    while !stop.load(Ordering::Relaxed) {
        match listener.accept() {
            Ok((stream, peer)) => {
                threads.retain(|t| !t.is_finished());
                if !opts.allow.is_empty() && !opts.allow.iter().any(|a| a.contains(peer.ip())) {
                    drop(stream);
                    continue;
                }
                if open.load(Ordering::Relaxed) >= opts.max_connections {
                    drop(stream);
                    continue;
                }
                open.fetch_add(1, Ordering::Relaxed);
                let (dev, stop, open2) = (Arc::clone(&dev), Arc::clone(&stop), Arc::clone(&open));
                let idle = opts.idle_timeout;
                let spawned = std::thread::Builder::new()
                    .name("automat-modbus-conn".into())
                    .spawn(move || {
                        serve(stream, dev.as_ref(), &stop, idle);
                        open2.fetch_sub(1, Ordering::Relaxed);
                    });
                match spawned {
                    Ok(t) => threads.push(t),
                    Err(_) => {
                        open.fetch_sub(1, Ordering::Relaxed);
                    }
                }
            }
            Err(e) if e.kind() == ErrorKind::WouldBlock => std::thread::sleep(POLL / 5),
            Err(_) => std::thread::sleep(POLL / 5),
        }
    }
    for t in threads {
        let _ = t.join();
    }
}

/// Serves one connection until it closes, misbehaves or the server stops.
fn serve(mut stream: TcpStream, dev: &dyn Device, stop: &AtomicBool, idle: Duration) {
    if stream.set_nonblocking(false).is_err()
        || stream.set_read_timeout(Some(POLL)).is_err()
        || stream
            .set_write_timeout(Some(Duration::from_secs(5)))
            .is_err()
    {
        return;
    }
    let _ = stream.set_nodelay(true);
    let mut buf: Vec<u8> = Vec::with_capacity(2 * (pdu::HEADER + pdu::MAX_PDU));
    let mut chunk = [0u8; 512];
    let mut last_frame = Instant::now();
    let mut partial_since: Option<Instant> = None;
    let mut out = Vec::with_capacity(pdu::HEADER + pdu::MAX_PDU);
    let mut resp = Vec::with_capacity(pdu::MAX_PDU);
    while !stop.load(Ordering::Relaxed) {
        match stream.read(&mut chunk) {
            Ok(0) => return,
            Ok(n) => buf.extend_from_slice(&chunk[..n]),
            Err(e) if matches!(e.kind(), ErrorKind::WouldBlock | ErrorKind::TimedOut) => {}
            Err(e) if e.kind() == ErrorKind::Interrupted => {}
            Err(_) => return,
        }
        out.clear();
        loop {
            match pdu::split_frame(&buf) {
                Err(_) => return,
                Ok(None) => break,
                Ok(Some((h, body, used))) => {
                    resp.clear();
                    handle(dev, body, &mut resp);
                    pdu::frame(h.transaction, h.unit, &resp, &mut out);
                    buf.drain(..used);
                    last_frame = Instant::now();
                }
            }
        }
        if !out.is_empty() && stream.write_all(&out).is_err() {
            return;
        }
        if buf.is_empty() {
            partial_since = None;
            if last_frame.elapsed() > idle {
                return;
            }
        } else {
            let since = *partial_since.get_or_insert_with(Instant::now);
            if since.elapsed() > PARTIAL_WITHIN {
                return;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    /// 16 coils and 16 holding registers in memory.
    #[derive(Default)]
    struct Mem {
        coils: Mutex<[bool; 16]>,
        regs: Mutex<[u16; 16]>,
    }

    impl Device for Mem {
        fn read_bits(&self, table: Table, addr: u16, count: u16) -> Result<Vec<bool>, Exception> {
            let c = self.coils.lock().map_err(|_| Exception::DeviceFailure)?;
            if table != Table::Coils {
                return Err(Exception::IllegalDataAddress);
            }
            c.get(usize::from(addr)..usize::from(addr) + usize::from(count))
                .map(<[bool]>::to_vec)
                .ok_or(Exception::IllegalDataAddress)
        }
        fn read_registers(&self, _t: Table, addr: u16, count: u16) -> Result<Vec<u16>, Exception> {
            let r = self.regs.lock().map_err(|_| Exception::DeviceFailure)?;
            r.get(usize::from(addr)..usize::from(addr) + usize::from(count))
                .map(<[u16]>::to_vec)
                .ok_or(Exception::IllegalDataAddress)
        }
        fn write_coils(&self, addr: u16, values: &[bool]) -> Result<(), Exception> {
            let mut c = self.coils.lock().map_err(|_| Exception::DeviceFailure)?;
            c.get_mut(usize::from(addr)..usize::from(addr) + values.len())
                .ok_or(Exception::IllegalDataAddress)?
                .copy_from_slice(values);
            Ok(())
        }
        fn write_registers(&self, addr: u16, values: &[u16]) -> Result<(), Exception> {
            let mut r = self.regs.lock().map_err(|_| Exception::DeviceFailure)?;
            r.get_mut(usize::from(addr)..usize::from(addr) + values.len())
                .ok_or(Exception::IllegalDataAddress)?
                .copy_from_slice(values);
            Ok(())
        }
    }

    fn ask(dev: &Mem, pdu: &[u8]) -> Vec<u8> {
        let mut out = Vec::new();
        handle(dev, pdu, &mut out);
        out
    }

    #[test]
    fn handle_answers_every_function_and_exception() {
        let m = Mem::default();
        assert_eq!(ask(&m, &[6, 0, 2, 0x12, 0x34]), [6, 0, 2, 0x12, 0x34]);
        assert_eq!(ask(&m, &[3, 0, 1, 0, 2]), [3, 4, 0, 0, 0x12, 0x34]);
        assert_eq!(ask(&m, &[16, 0, 0, 0, 2, 4, 0, 7, 0, 8]), [16, 0, 0, 0, 2]);
        assert_eq!(ask(&m, &[4, 0, 0, 0, 3]), [4, 6, 0, 7, 0, 8, 0x12, 0x34]);
        assert_eq!(ask(&m, &[5, 0, 3, 0xFF, 0]), [5, 0, 3, 0xFF, 0]);
        assert_eq!(ask(&m, &[15, 0, 8, 0, 3, 1, 0b101]), [15, 0, 8, 0, 3]);
        assert_eq!(ask(&m, &[1, 0, 0, 0, 11]), [1, 2, 0b0000_1000, 0b101]);
        assert_eq!(
            ask(&m, &[23, 0, 0, 0, 1, 0, 0, 0, 1, 2, 0xAB, 0xCD]),
            [23, 2, 0xAB, 0xCD]
        );
        assert_eq!(ask(&m, &[3, 0, 15, 0, 2]), [0x83, 2]);
        assert_eq!(ask(&m, &[2, 0, 0, 0, 1]), [0x82, 2]);
        assert_eq!(ask(&m, &[3, 0, 0, 0, 200]), [0x83, 3]);
        assert_eq!(ask(&m, &[8, 0, 0, 0, 0]), [0x88, 1]);
    }

    #[test]
    fn allow_lists_match_addresses_and_networks() {
        let a = Allow::parse("10.1.0.0/16").unwrap();
        assert!(a.contains("10.1.200.3".parse().unwrap()));
        assert!(!a.contains("10.2.0.1".parse().unwrap()));
        assert!(a.contains("::ffff:10.1.0.9".parse().unwrap()));
        let one = Allow::parse("127.0.0.1").unwrap();
        assert!(one.contains("127.0.0.1".parse().unwrap()));
        assert!(!one.contains("127.0.0.2".parse().unwrap()));
        assert!(Allow::parse("0.0.0.0/0")
            .unwrap()
            .contains("192.0.2.1".parse().unwrap()));
        assert!(Allow::parse("10.0.0.0/33").is_err());
        assert!(Allow::parse("host").is_err());
        assert_eq!(
            parse_addr("5020"),
            Ok(SocketAddr::from(([127, 0, 0, 1], 5020)))
        );
        assert!(parse_addr("x:1").is_err());
    }

    #[test]
    fn the_server_answers_closes_bad_streams_and_limits_connections() {
        let dev: Arc<dyn Device> = Arc::new(Mem::default());
        let mut opts = Options::new(SocketAddr::from(([127, 0, 0, 1], 0)));
        opts.max_connections = 2;
        let server = start(dev, opts).unwrap();
        let connect = || {
            let s = TcpStream::connect(server.addr).unwrap();
            s.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
            s
        };
        let mut a = connect();
        // Two requests in one write, the second split across two writes.
        a.write_all(&[0, 1, 0, 0, 0, 6, 1, 6, 0, 0, 0, 42, 0, 2, 0, 0])
            .unwrap();
        std::thread::sleep(Duration::from_millis(20));
        a.write_all(&[0, 6, 1, 3, 0, 0, 0, 1]).unwrap();
        let mut got = [0u8; 12 + 11];
        a.read_exact(&mut got).unwrap();
        assert_eq!(&got[..12], [0, 1, 0, 0, 0, 6, 1, 6, 0, 0, 0, 42]);
        assert_eq!(&got[12..], [0, 2, 0, 0, 0, 5, 1, 3, 2, 0, 42]);
        // A second connection works; a third is over the limit and closed.
        let mut b = connect();
        std::thread::sleep(Duration::from_millis(100));
        let mut c = connect();
        let mut one = [0u8; 1];
        assert!(matches!(c.read(&mut one), Ok(0) | Err(_)));
        // A wrong protocol id closes the connection.
        b.write_all(&[0, 1, 0, 9, 0, 6, 1, 3, 0, 0, 0, 1]).unwrap();
        assert!(matches!(b.read(&mut one), Ok(0) | Err(_)));
        // The first still answers.
        a.write_all(&[0, 3, 0, 0, 0, 6, 1, 3, 0, 0, 0, 1]).unwrap();
        let mut got = [0u8; 11];
        a.read_exact(&mut got).unwrap();
        assert_eq!(got, [0, 3, 0, 0, 0, 5, 1, 3, 2, 0, 42]);
        drop(server);
    }

    #[test]
    fn clients_outside_the_allow_list_are_closed_at_once() {
        let dev: Arc<dyn Device> = Arc::new(Mem::default());
        let mut opts = Options::new(SocketAddr::from(([127, 0, 0, 1], 0)));
        opts.allow = vec![Allow::parse("10.0.0.0/8").unwrap()];
        let server = start(Arc::clone(&dev), opts).unwrap();
        let mut s = TcpStream::connect(server.addr).unwrap();
        s.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
        let _ = s.write_all(&[0, 1, 0, 0, 0, 6, 1, 3, 0, 0, 0, 1]);
        let mut one = [0u8; 1];
        assert!(matches!(s.read(&mut one), Ok(0) | Err(_)));
        drop(server);
        let mut opts = Options::new(SocketAddr::from(([127, 0, 0, 1], 0)));
        opts.allow = vec![Allow::parse("127.0.0.0/8").unwrap()];
        let server = start(dev, opts).unwrap();
        let mut s = TcpStream::connect(server.addr).unwrap();
        s.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
        s.write_all(&[0, 1, 0, 0, 0, 6, 1, 3, 0, 0, 0, 1]).unwrap();
        let mut got = [0u8; 11];
        s.read_exact(&mut got).unwrap();
        assert_eq!(got, [0, 1, 0, 0, 0, 5, 1, 3, 2, 0, 0]);
    }
}
