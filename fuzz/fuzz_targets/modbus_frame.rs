//! Arbitrary bytes as a Modbus TCP stream through the server's side
//! (`automat_fieldbus::pdu::split_frame`, then `server::handle` over an
//! in-memory device, frame after frame) and as a response PDU to each kind
//! of request on the client's side (`pdu::decode_response`). Never a panic;
//! every answer is one response or exception PDU of at most `MAX_PDU`
//! bytes, answering the request's function; a request that decodes
//! re-encodes to a PDU that decodes to the same request.
#![no_main]

use automat_fieldbus::pdu::{
    decode_request, decode_response, encode_request, split_frame, Exception, Request, Table,
    MAX_PDU,
};
use automat_fieldbus::server::{handle, Device};
use libfuzzer_sys::fuzz_target;

/// 60,000 registers and bits whose values follow from their address;
/// writes past them are exception 02.
struct Mem;

const SIZE: u32 = 60_000;

fn fits(addr: u16, n: usize) -> Result<(), Exception> {
    if u32::from(addr) + n as u32 > SIZE {
        Err(Exception::IllegalDataAddress)
    } else {
        Ok(())
    }
}

impl Device for Mem {
    fn read_bits(&self, _t: Table, addr: u16, count: u16) -> Result<Vec<bool>, Exception> {
        fits(addr, usize::from(count))?;
        Ok((0..count).map(|i| (addr.wrapping_add(i)) % 3 == 0).collect())
    }
    fn read_registers(&self, _t: Table, addr: u16, count: u16) -> Result<Vec<u16>, Exception> {
        fits(addr, usize::from(count))?;
        Ok((0..count).map(|i| addr.wrapping_mul(7).wrapping_add(i)).collect())
    }
    fn write_coils(&self, addr: u16, values: &[bool]) -> Result<(), Exception> {
        fits(addr, values.len())
    }
    fn write_registers(&self, addr: u16, values: &[u16]) -> Result<(), Exception> {
        fits(addr, values.len())
    }
}

fuzz_target!(|data: &[u8]| {
    let mut rest = data;
    let mut out = Vec::new();
    while let Ok(Some((_, pdu, used))) = split_frame(rest) {
        out.clear();
        handle(&Mem, pdu, &mut out);
        assert!(!out.is_empty() && out.len() <= MAX_PDU, "answer of {} bytes", out.len());
        let fc = pdu.first().copied().unwrap_or(0);
        assert!(out[0] == fc || out[0] == fc | 0x80, "answered function {}", out[0]);
        if let Ok(req) = decode_request(pdu) {
            let mut again = Vec::new();
            encode_request(&req, &mut again);
            assert_eq!(decode_request(&again), Ok(req));
        }
        rest = &rest[used..];
    }
    let requests = [
        Request::Read { table: Table::Coils, addr: 0, count: 13 },
        Request::Read { table: Table::HoldingRegisters, addr: 9, count: 3 },
        Request::WriteCoil { addr: 1, value: true },
        Request::WriteRegister { addr: 2, value: 0x1234 },
        Request::WriteCoils { addr: 3, values: vec![true, false, true] },
        Request::WriteRegisters { addr: 4, values: vec![1, 2] },
        Request::ReadWrite { read_addr: 0, read_count: 2, write_addr: 5, values: vec![9] },
    ];
    for req in &requests {
        let _ = decode_response(req, data);
    }
});
