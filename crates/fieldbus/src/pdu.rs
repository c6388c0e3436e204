//! The Modbus TCP frame: the MBAP header and the PDUs of function codes
//! 1, 2, 3, 4, 5, 6, 15, 16 and 23, for both sides (a server decodes
//! requests and encodes responses, a client the reverse).
//!
//! Written here rather than taken from a crate: the codec is ~300 lines,
//! has no I/O, allocates only the value vectors, and is the one place a
//! hostile frame is judged, so it is fuzzed whole (`fuzz/fuzz_targets/
//! modbus_frame.rs`). Every limit of the specification (Modbus Application
//! Protocol V1.1b3) is checked: quantities (2000 bits / 125 registers
//! read, 1968 bits / 123 registers written, 121 in FC 23), byte counts
//! that must match the quantity, the address range staying below 65,536,
//! coil values 0x0000/0xFF00. A request that breaks one gets its exception
//! (02 address, 03 value); an unknown function 01; a frame whose MBAP
//! header is impossible (protocol ≠ 0, length outside 2..=254) is a
//! [`FrameError`] and the connection is closed, since the stream cannot be
//! resynchronised.

/// The largest PDU (function code + data).
pub const MAX_PDU: usize = 253;
/// MBAP header bytes (transaction, protocol, length, unit).
pub const HEADER: usize = 7;

/// Limits of the specification.
pub const MAX_READ_BITS: u16 = 2000;
pub const MAX_READ_REGS: u16 = 125;
pub const MAX_WRITE_BITS: u16 = 1968;
pub const MAX_WRITE_REGS: u16 = 123;
pub const MAX_RW_WRITE_REGS: u16 = 121;

/// Exception codes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exception {
    IllegalFunction = 1,
    IllegalDataAddress = 2,
    IllegalDataValue = 3,
    DeviceFailure = 4,
}

impl Exception {
    pub fn code(self) -> u8 {
        self as u8
    }
    pub fn from_code(c: u8) -> Option<Exception> {
        Some(match c {
            1 => Exception::IllegalFunction,
            2 => Exception::IllegalDataAddress,
            3 => Exception::IllegalDataValue,
            4 => Exception::DeviceFailure,
            _ => return None,
        })
    }
}

/// The four tables of the Modbus data model.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Table {
    Coils,
    DiscreteInputs,
    InputRegisters,
    HoldingRegisters,
}

impl Table {
    pub fn is_bits(self) -> bool {
        matches!(self, Table::Coils | Table::DiscreteInputs)
    }
    /// Coils and holding registers: a client may write them.
    pub fn writable(self) -> bool {
        matches!(self, Table::Coils | Table::HoldingRegisters)
    }
    pub fn name(self) -> &'static str {
        match self {
            Table::Coils => "coils",
            Table::DiscreteInputs => "discrete_inputs",
            Table::InputRegisters => "input_registers",
            Table::HoldingRegisters => "holding_registers",
        }
    }
    pub fn parse(s: &str) -> Option<Table> {
        Some(match s {
            "coils" | "coil" => Table::Coils,
            "discrete_inputs" | "discrete_input" | "discrete" => Table::DiscreteInputs,
            "input_registers" | "input_register" | "input" => Table::InputRegisters,
            "holding_registers" | "holding_register" | "holding" => Table::HoldingRegisters,
            _ => return None,
        })
    }
}

/// A decoded request.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Request {
    /// FC 1, 2, 3, 4.
    Read { table: Table, addr: u16, count: u16 },
    /// FC 5.
    WriteCoil { addr: u16, value: bool },
    /// FC 6.
    WriteRegister { addr: u16, value: u16 },
    /// FC 15.
    WriteCoils { addr: u16, values: Vec<bool> },
    /// FC 16.
    WriteRegisters { addr: u16, values: Vec<u16> },
    /// FC 23: the write is done before the read.
    ReadWrite {
        read_addr: u16,
        read_count: u16,
        write_addr: u16,
        values: Vec<u16>,
    },
}

impl Request {
    pub fn function(&self) -> u8 {
        match self {
            Request::Read { table, .. } => match table {
                Table::Coils => 1,
                Table::DiscreteInputs => 2,
                Table::HoldingRegisters => 3,
                Table::InputRegisters => 4,
            },
            Request::WriteCoil { .. } => 5,
            Request::WriteRegister { .. } => 6,
            Request::WriteCoils { .. } => 15,
            Request::WriteRegisters { .. } => 16,
            Request::ReadWrite { .. } => 23,
        }
    }
}

/// What a server answers (the data part; the function code is the request's).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Response {
    Bits(Vec<bool>),
    Registers(Vec<u16>),
    /// FC 5 and 6: the request echoed.
    Echo {
        addr: u16,
        value: u16,
    },
    /// FC 15 and 16: address and quantity written.
    Written {
        addr: u16,
        count: u16,
    },
}

/// An MBAP header.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Header {
    pub transaction: u16,
    pub unit: u8,
    /// Bytes after the length field: the unit id and the PDU.
    pub length: u16,
}

/// A stream that is not Modbus TCP: the connection is closed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum FrameError {
    Protocol(u16),
    Length(u16),
}

impl std::fmt::Display for FrameError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FrameError::Protocol(p) => write!(f, "protocol identifier {p}, not 0 (Modbus)"),
            FrameError::Length(l) => write!(f, "MBAP length {l} outside 2..=254"),
        }
    }
}

fn be16(b: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_be_bytes([*b.get(at)?, *b.get(at + 1)?]))
}

/// The header at the start of `b` (7 bytes).
pub fn parse_header(b: &[u8; HEADER]) -> Result<Header, FrameError> {
    let transaction = u16::from_be_bytes([b[0], b[1]]);
    let protocol = u16::from_be_bytes([b[2], b[3]]);
    let length = u16::from_be_bytes([b[4], b[5]]);
    if protocol != 0 {
        return Err(FrameError::Protocol(protocol));
    }
    if !(2..=(MAX_PDU as u16 + 1)).contains(&length) {
        return Err(FrameError::Length(length));
    }
    Ok(Header {
        transaction,
        unit: b[6],
        length,
    })
}

/// A whole frame at the start of a buffer: its header, its PDU and the
/// bytes it takes.
pub type Split<'a> = (Header, &'a [u8], usize);

/// The first whole frame of `buf`; `Ok(None)` while the frame is incomplete.
pub fn split_frame(buf: &[u8]) -> Result<Option<Split<'_>>, FrameError> {
    let Some(head) = buf.get(..HEADER) else {
        return Ok(None);
    };
    let mut h = [0u8; HEADER];
    h.copy_from_slice(head);
    let header = parse_header(&h)?;
    let end = HEADER + usize::from(header.length) - 1;
    match buf.get(HEADER..end) {
        Some(pdu) => Ok(Some((header, pdu, end))),
        None => Ok(None),
    }
}

/// Appends an MBAP header and `pdu` to `out`.
pub fn frame(transaction: u16, unit: u8, pdu: &[u8], out: &mut Vec<u8>) {
    let len = u16::try_from(pdu.len() + 1).unwrap_or(u16::MAX);
    out.extend_from_slice(&transaction.to_be_bytes());
    out.extend_from_slice(&0u16.to_be_bytes());
    out.extend_from_slice(&len.to_be_bytes());
    out.push(unit);
    out.extend_from_slice(pdu);
}

/// The range `addr .. addr + count` must stay inside the 16-bit space.
fn in_space(addr: u16, count: u16) -> bool {
    u32::from(addr) + u32::from(count) <= 65_536
}

fn unpack_bits(bytes: &[u8], count: usize) -> Vec<bool> {
    (0..count)
        .map(|i| bytes.get(i / 8).is_some_and(|b| b & (1 << (i % 8)) != 0))
        .collect()
}

fn pack_bits(bits: &[bool], out: &mut Vec<u8>) {
    for chunk in bits.chunks(8) {
        let mut b = 0u8;
        for (i, v) in chunk.iter().enumerate() {
            if *v {
                b |= 1 << i;
            }
        }
        out.push(b);
    }
}

/// Decodes a request PDU; an error is the function code and the exception
/// to answer.
pub fn decode_request(pdu: &[u8]) -> Result<Request, (u8, Exception)> {
    let Some(&fc) = pdu.first() else {
        return Err((0, Exception::IllegalFunction));
    };
    let value = |_| (fc, Exception::IllegalDataValue);
    let addr_err = (fc, Exception::IllegalDataAddress);
    let word = |at: usize| be16(pdu, at).ok_or((fc, Exception::IllegalDataValue));
    match fc {
        1..=4 => {
            if pdu.len() != 5 {
                return Err((fc, Exception::IllegalDataValue));
            }
            let (addr, count) = (word(1)?, word(3)?);
            let (table, max) = match fc {
                1 => (Table::Coils, MAX_READ_BITS),
                2 => (Table::DiscreteInputs, MAX_READ_BITS),
                3 => (Table::HoldingRegisters, MAX_READ_REGS),
                _ => (Table::InputRegisters, MAX_READ_REGS),
            };
            if count == 0 || count > max {
                return Err(value(()));
            }
            if !in_space(addr, count) {
                return Err(addr_err);
            }
            Ok(Request::Read { table, addr, count })
        }
        5 => {
            if pdu.len() != 5 {
                return Err(value(()));
            }
            let (addr, v) = (word(1)?, word(3)?);
            let value = match v {
                0xFF00 => true,
                0x0000 => false,
                _ => return Err((fc, Exception::IllegalDataValue)),
            };
            Ok(Request::WriteCoil { addr, value })
        }
        6 => {
            if pdu.len() != 5 {
                return Err(value(()));
            }
            Ok(Request::WriteRegister {
                addr: word(1)?,
                value: word(3)?,
            })
        }
        15 => {
            let (addr, count) = (word(1)?, word(3)?);
            let n = usize::from(*pdu.get(5).ok_or((fc, Exception::IllegalDataValue))?);
            if count == 0 || count > MAX_WRITE_BITS || n != usize::from(count).div_ceil(8) {
                return Err(value(()));
            }
            if pdu.len() != 6 + n {
                return Err(value(()));
            }
            if !in_space(addr, count) {
                return Err(addr_err);
            }
            Ok(Request::WriteCoils {
                addr,
                values: unpack_bits(&pdu[6..], usize::from(count)),
            })
        }
        16 => {
            let (addr, count) = (word(1)?, word(3)?);
            let n = usize::from(*pdu.get(5).ok_or((fc, Exception::IllegalDataValue))?);
            if count == 0 || count > MAX_WRITE_REGS || n != 2 * usize::from(count) {
                return Err(value(()));
            }
            if pdu.len() != 6 + n {
                return Err(value(()));
            }
            if !in_space(addr, count) {
                return Err(addr_err);
            }
            let values = (0..usize::from(count))
                .map(|i| word(6 + 2 * i))
                .collect::<Result<Vec<u16>, _>>()?;
            Ok(Request::WriteRegisters { addr, values })
        }
        23 => {
            let (read_addr, read_count) = (word(1)?, word(3)?);
            let (write_addr, write_count) = (word(5)?, word(7)?);
            let n = usize::from(*pdu.get(9).ok_or((fc, Exception::IllegalDataValue))?);
            if read_count == 0
                || read_count > MAX_READ_REGS
                || write_count == 0
                || write_count > MAX_RW_WRITE_REGS
                || n != 2 * usize::from(write_count)
                || pdu.len() != 10 + n
            {
                return Err(value(()));
            }
            if !in_space(read_addr, read_count) || !in_space(write_addr, write_count) {
                return Err(addr_err);
            }
            let values = (0..usize::from(write_count))
                .map(|i| word(10 + 2 * i))
                .collect::<Result<Vec<u16>, _>>()?;
            Ok(Request::ReadWrite {
                read_addr,
                read_count,
                write_addr,
                values,
            })
        }
        _ => Err((fc, Exception::IllegalFunction)),
    }
}

/// Appends the response PDU to `out`.
pub fn encode_response(function: u8, r: &Response, out: &mut Vec<u8>) {
    out.push(function);
    match r {
        Response::Bits(bits) => {
            out.push(u8::try_from(bits.len().div_ceil(8)).unwrap_or(u8::MAX));
            pack_bits(bits, out);
        }
        Response::Registers(regs) => {
            out.push(u8::try_from(regs.len() * 2).unwrap_or(u8::MAX));
            for r in regs {
                out.extend_from_slice(&r.to_be_bytes());
            }
        }
        Response::Echo { addr, value } => {
            out.extend_from_slice(&addr.to_be_bytes());
            out.extend_from_slice(&value.to_be_bytes());
        }
        Response::Written { addr, count } => {
            out.extend_from_slice(&addr.to_be_bytes());
            out.extend_from_slice(&count.to_be_bytes());
        }
    }
}

/// Appends an exception response PDU to `out`.
pub fn encode_exception(function: u8, e: Exception, out: &mut Vec<u8>) {
    out.push(function | 0x80);
    out.push(e.code());
}

/// Appends the request PDU to `out` (the client's side).
pub fn encode_request(r: &Request, out: &mut Vec<u8>) {
    out.push(r.function());
    match r {
        Request::Read { addr, count, .. } => {
            out.extend_from_slice(&addr.to_be_bytes());
            out.extend_from_slice(&count.to_be_bytes());
        }
        Request::WriteCoil { addr, value } => {
            out.extend_from_slice(&addr.to_be_bytes());
            out.extend_from_slice(&(if *value { 0xFF00u16 } else { 0 }).to_be_bytes());
        }
        Request::WriteRegister { addr, value } => {
            out.extend_from_slice(&addr.to_be_bytes());
            out.extend_from_slice(&value.to_be_bytes());
        }
        Request::WriteCoils { addr, values } => {
            out.extend_from_slice(&addr.to_be_bytes());
            out.extend_from_slice(&(values.len() as u16).to_be_bytes());
            out.push(u8::try_from(values.len().div_ceil(8)).unwrap_or(u8::MAX));
            pack_bits(values, out);
        }
        Request::WriteRegisters { addr, values } => {
            out.extend_from_slice(&addr.to_be_bytes());
            out.extend_from_slice(&(values.len() as u16).to_be_bytes());
            out.push(u8::try_from(values.len() * 2).unwrap_or(u8::MAX));
            for v in values {
                out.extend_from_slice(&v.to_be_bytes());
            }
        }
        Request::ReadWrite {
            read_addr,
            read_count,
            write_addr,
            values,
        } => {
            out.extend_from_slice(&read_addr.to_be_bytes());
            out.extend_from_slice(&read_count.to_be_bytes());
            out.extend_from_slice(&write_addr.to_be_bytes());
            out.extend_from_slice(&(values.len() as u16).to_be_bytes());
            out.push(u8::try_from(values.len() * 2).unwrap_or(u8::MAX));
            for v in values {
                out.extend_from_slice(&v.to_be_bytes());
            }
        }
    }
}

/// Why a response was not the answer to the request.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ResponseError {
    /// The device answered with an exception (its code).
    Exception(u8),
    /// Not a well-formed answer to this request.
    Malformed(String),
}

impl std::fmt::Display for ResponseError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ResponseError::Exception(c) => {
                let what = match Exception::from_code(*c) {
                    Some(Exception::IllegalFunction) => "illegal function",
                    Some(Exception::IllegalDataAddress) => "illegal data address",
                    Some(Exception::IllegalDataValue) => "illegal data value",
                    Some(Exception::DeviceFailure) => "server device failure",
                    None => "exception",
                };
                write!(f, "exception {c:02} ({what})")
            }
            ResponseError::Malformed(m) => write!(f, "malformed response: {m}"),
        }
    }
}

/// Decodes the response PDU to `req` (the client's side).
pub fn decode_response(req: &Request, pdu: &[u8]) -> Result<Response, ResponseError> {
    let bad = |m: &str| Err(ResponseError::Malformed(m.to_string()));
    let fc = req.function();
    let Some(&got) = pdu.first() else {
        return bad("empty PDU");
    };
    if got == fc | 0x80 {
        return match pdu.get(1) {
            Some(&c) if pdu.len() == 2 => Err(ResponseError::Exception(c)),
            _ => bad("exception response of the wrong length"),
        };
    }
    if got != fc {
        return bad(&format!("function {got}, expected {fc}"));
    }
    match req {
        Request::Read { table, count, .. } => {
            let n = usize::from(*pdu.get(1).unwrap_or(&0));
            if pdu.len() != 2 + n {
                return bad("byte count does not match the data");
            }
            if table.is_bits() {
                if n != usize::from(*count).div_ceil(8) {
                    return bad("byte count does not match the quantity");
                }
                Ok(Response::Bits(unpack_bits(&pdu[2..], usize::from(*count))))
            } else {
                if n != 2 * usize::from(*count) {
                    return bad("byte count does not match the quantity");
                }
                Ok(Response::Registers(
                    (0..usize::from(*count))
                        .filter_map(|i| be16(pdu, 2 + 2 * i))
                        .collect(),
                ))
            }
        }
        Request::ReadWrite { read_count, .. } => {
            let n = usize::from(*pdu.get(1).unwrap_or(&0));
            if pdu.len() != 2 + n || n != 2 * usize::from(*read_count) {
                return bad("byte count does not match the quantity");
            }
            Ok(Response::Registers(
                (0..usize::from(*read_count))
                    .filter_map(|i| be16(pdu, 2 + 2 * i))
                    .collect(),
            ))
        }
        Request::WriteCoil { .. } | Request::WriteRegister { .. } => {
            let mut want = Vec::new();
            encode_request(req, &mut want);
            if pdu != want.as_slice() {
                return bad("the echo differs from the request");
            }
            Ok(Response::Echo {
                addr: be16(pdu, 1).unwrap_or(0),
                value: be16(pdu, 3).unwrap_or(0),
            })
        }
        Request::WriteCoils { addr, values } => written(pdu, *addr, values.len()),
        Request::WriteRegisters { addr, values } => written(pdu, *addr, values.len()),
    }
}

fn written(pdu: &[u8], addr: u16, n: usize) -> Result<Response, ResponseError> {
    match (pdu.len(), be16(pdu, 1), be16(pdu, 3)) {
        (5, Some(a), Some(c)) if a == addr && usize::from(c) == n => {
            Ok(Response::Written { addr: a, count: c })
        }
        _ => Err(ResponseError::Malformed(
            "the address or quantity written differs from the request".into(),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn requests_round_trip_through_both_sides() {
        let cases = vec![
            Request::Read {
                table: Table::Coils,
                addr: 3,
                count: 2000,
            },
            Request::Read {
                table: Table::InputRegisters,
                addr: 65_535,
                count: 1,
            },
            Request::WriteCoil {
                addr: 9,
                value: true,
            },
            Request::WriteRegister {
                addr: 1024,
                value: 0xBEEF,
            },
            Request::WriteCoils {
                addr: 1,
                values: vec![true, false, true, true, false, false, false, false, true],
            },
            Request::WriteRegisters {
                addr: 2048,
                values: vec![1, 2, 0xFFFF],
            },
            Request::ReadWrite {
                read_addr: 0,
                read_count: 4,
                write_addr: 10,
                values: vec![7, 8],
            },
        ];
        for r in cases {
            let mut pdu = Vec::new();
            encode_request(&r, &mut pdu);
            assert_eq!(decode_request(&pdu), Ok(r.clone()));
        }
    }

    #[test]
    fn exact_bytes_of_a_read_holding_registers_exchange() {
        let mut pdu = Vec::new();
        encode_request(
            &Request::Read {
                table: Table::HoldingRegisters,
                addr: 0x006B,
                count: 3,
            },
            &mut pdu,
        );
        assert_eq!(pdu, [0x03, 0x00, 0x6B, 0x00, 0x03]);
        let mut f = Vec::new();
        frame(0x1234, 0x11, &pdu, &mut f);
        assert_eq!(
            f,
            [0x12, 0x34, 0, 0, 0, 6, 0x11, 0x03, 0x00, 0x6B, 0x00, 0x03]
        );
        let mut resp = Vec::new();
        encode_response(3, &Response::Registers(vec![0x022B, 0, 0x0064]), &mut resp);
        assert_eq!(resp, [0x03, 0x06, 0x02, 0x2B, 0x00, 0x00, 0x00, 0x64]);
        let mut coils = Vec::new();
        let bits = [
            true, false, true, true, false, false, true, true, true, true,
        ];
        encode_response(1, &Response::Bits(bits.to_vec()), &mut coils);
        assert_eq!(coils, [0x01, 0x02, 0xCD, 0x03]);
    }

    #[test]
    fn bad_requests_get_their_exception() {
        let cases: [(&[u8], u8, Exception); 12] = [
            (&[], 0, Exception::IllegalFunction),
            (&[0x2B, 0x0E], 0x2B, Exception::IllegalFunction),
            (&[0x03, 0, 0, 0, 0], 3, Exception::IllegalDataValue),
            (&[0x03, 0, 0, 0, 126], 3, Exception::IllegalDataValue),
            (&[0x01, 0, 0, 0x07, 0xD1], 1, Exception::IllegalDataValue),
            (&[0x03, 0xFF, 0xFF, 0, 2], 3, Exception::IllegalDataAddress),
            (&[0x03, 0, 0], 3, Exception::IllegalDataValue),
            (&[0x05, 0, 1, 0x12, 0x34], 5, Exception::IllegalDataValue),
            (
                &[0x10, 0, 0, 0, 2, 3, 0, 1, 0],
                16,
                Exception::IllegalDataValue,
            ),
            (&[0x10, 0, 0, 0, 124, 248], 16, Exception::IllegalDataValue),
            (
                &[0x0F, 0, 0, 0, 9, 1, 0xFF],
                15,
                Exception::IllegalDataValue,
            ),
            (
                &[0x17, 0, 0, 0, 1, 0, 0, 0, 1, 2, 0],
                23,
                Exception::IllegalDataValue,
            ),
        ];
        for (pdu, fc, e) in cases {
            assert_eq!(decode_request(pdu), Err((fc, e)), "{pdu:?}");
        }
        let mut out = Vec::new();
        encode_exception(3, Exception::IllegalDataAddress, &mut out);
        assert_eq!(out, [0x83, 0x02]);
    }

    #[test]
    fn frames_split_only_when_whole_and_impossible_headers_are_errors() {
        let f = [0, 1, 0, 0, 0, 6, 1, 3, 0, 0, 0, 1, 9];
        assert_eq!(split_frame(&f[..5]), Ok(None));
        assert_eq!(split_frame(&f[..11]), Ok(None));
        let (h, pdu, used) = split_frame(&f).unwrap().unwrap();
        assert_eq!((h.transaction, h.unit, pdu, used), (1, 1, &f[7..12], 12));
        assert_eq!(
            split_frame(&[0, 1, 0, 1, 0, 6, 1]),
            Err(FrameError::Protocol(1))
        );
        assert_eq!(
            split_frame(&[0, 1, 0, 0, 0xFF, 0xFF, 1]),
            Err(FrameError::Length(0xFFFF))
        );
        assert_eq!(
            split_frame(&[0, 1, 0, 0, 0, 1, 1]),
            Err(FrameError::Length(1))
        );
    }

    #[test]
    fn responses_are_checked_against_their_request() {
        let r = Request::Read {
            table: Table::Coils,
            addr: 0,
            count: 10,
        };
        assert_eq!(
            decode_response(&r, &[0x01, 0x02, 0xCD, 0x03]),
            Ok(Response::Bits(vec![
                true, false, true, true, false, false, true, true, true, true
            ]))
        );
        assert!(decode_response(&r, &[0x01, 0x01, 0xCD]).is_err());
        assert_eq!(
            decode_response(&r, &[0x81, 0x02]),
            Err(ResponseError::Exception(2))
        );
        let w = Request::WriteRegisters {
            addr: 5,
            values: vec![1, 2],
        };
        assert!(decode_response(&w, &[0x10, 0, 5, 0, 2]).is_ok());
        assert!(decode_response(&w, &[0x10, 0, 5, 0, 3]).is_err());
    }
}
