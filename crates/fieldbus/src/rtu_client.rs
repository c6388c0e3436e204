//! The Modbus RTU master's side of a serial line: a [`Bus`] is one port
//! shared by every configured device on it (each device's poller takes
//! the bus for one request and its response, so requests never overlap on
//! the line, as RS-485 requires).

use crate::client::{io_failure, Failure};
use crate::pdu::{self, Request, Response, ResponseError};
use crate::rtu::{self, Decoder, Dropped, Event, Side};
use crate::serial::Line;
use std::io::ErrorKind;
use std::sync::Mutex;
use std::time::{Duration, Instant};

pub struct Bus {
    pub line: Line,
    /// Opened at the first request and after a failure.
    port: Mutex<Option<Box<dyn serialport::SerialPort>>>,
}

fn malformed(why: impl Into<String>) -> Failure {
    Failure::Response(ResponseError::Malformed(why.into()))
}

impl Bus {
    pub fn new(line: Line) -> Bus {
        Bus {
            line,
            port: Mutex::new(None),
        }
    }

    /// One request to `unit` and its response within `timeout` (a test
    /// or a tool's view; the pollers use `exchange`).
    pub fn call(&self, unit: u8, req: &Request, timeout: Duration) -> Result<Response, String> {
        self.exchange(unit, req, timeout).map_err(|f| f.text())
    }

    pub(crate) fn exchange(
        &self,
        unit: u8,
        req: &Request,
        timeout: Duration,
    ) -> Result<Response, Failure> {
        let mut guard = self.port.lock().unwrap_or_else(|p| p.into_inner());
        if guard.is_none() {
            *guard = Some(
                self.line
                    .open(self.line.gap())
                    .map_err(Failure::Connection)?,
            );
        }
        let Some(port) = guard.as_mut() else {
            return Err(Failure::Connection("no port".into()));
        };
        let result = self.on(port.as_mut(), unit, req, timeout);
        if matches!(result, Err(Failure::Connection(_))) {
            *guard = None;
        }
        // The line stays silent before the next request.
        std::thread::sleep(self.line.silence());
        result
    }

    fn on(
        &self,
        port: &mut dyn serialport::SerialPort,
        unit: u8,
        req: &Request,
        timeout: Duration,
    ) -> Result<Response, Failure> {
        // A late answer to an earlier request must not be taken for this one.
        let _ = port.clear(serialport::ClearBuffer::Input);
        let mut body = Vec::with_capacity(pdu::MAX_PDU);
        pdu::encode_request(req, &mut body);
        let mut adu = Vec::with_capacity(rtu::MAX_ADU);
        rtu::frame(unit, &body, &mut adu);
        port.write_all(&adu)
            .and_then(|()| port.flush())
            .map_err(io_failure)
            .map_err(|f| match f {
                Failure::Timeout => Failure::Connection("write timed out".into()),
                f => f,
            })?;
        let deadline = Instant::now() + timeout;
        let mut decoder = Decoder::new(Side::Responses);
        let mut chunk = [0u8; rtu::MAX_ADU];
        let mut events = Vec::new();
        loop {
            if Instant::now() >= deadline {
                return Err(Failure::Timeout);
            }
            match port.read(&mut chunk) {
                Ok(0) => decoder.gap(&mut events),
                Ok(n) => decoder.push(&chunk[..n], &mut events),
                Err(e) if e.kind() == ErrorKind::TimedOut => decoder.gap(&mut events),
                Err(e) if e.kind() == ErrorKind::Interrupted => {}
                Err(e) => return Err(Failure::Connection(e.to_string())),
            }
            if let Some(ev) = events.drain(..).next() {
                return match ev {
                    Event::Frame(f) if f.unit == unit => {
                        pdu::decode_response(req, &f.pdu).map_err(Failure::Response)
                    }
                    Event::Frame(f) => {
                        Err(malformed(format!("unit {} answered, {unit} asked", f.unit)))
                    }
                    Event::Dropped(Dropped::Crc) => Err(malformed("CRC error")),
                    Event::Dropped(Dropped::Fragment) => Err(malformed("incomplete frame")),
                    Event::Dropped(Dropped::TooLong) => Err(malformed("frame over 256 bytes")),
                };
            }
        }
    }
}
