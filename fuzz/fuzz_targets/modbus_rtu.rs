//! Arbitrary bytes as a Modbus RTU line through the decoder of both sides
//! (`automat_fieldbus::rtu::Decoder`), cut into reads and silences as the
//! input's first byte says, and each request frame through the slave's
//! handler. Never a panic; every frame is at most 256 bytes with its CRC
//! right; how the bytes are cut into reads changes nothing (the same
//! frames and drops whether pushed at once or byte by byte); every answer
//! is one response or exception PDU of at most 253 bytes.
#![no_main]

use automat_fieldbus::pdu::{Exception, Table, MAX_PDU};
use automat_fieldbus::rtu::{self, Decoder, Event, Side};
use automat_fieldbus::server::{handle, Device};
use libfuzzer_sys::fuzz_target;

/// Values follow from the address; writes past 60,000 are exception 02.
struct Mem;

fn fits(addr: u16, n: usize) -> Result<(), Exception> {
    if u32::from(addr) + n as u32 > 60_000 {
        Err(Exception::IllegalDataAddress)
    } else {
        Ok(())
    }
}

impl Device for Mem {
    fn read_bits(&self, _t: Table, addr: u16, count: u16) -> Result<Vec<bool>, Exception> {
        fits(addr, usize::from(count))?;
        Ok((0..count).map(|i| addr.wrapping_add(i) % 3 == 0).collect())
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

/// The events of `bytes` pushed in reads of `sizes` (cycled), a silence
/// after each read whose size is a multiple of 7, and one at the end.
fn run(side: Side, bytes: &[u8], cut: u8) -> Vec<Event> {
    let mut d = Decoder::new(side);
    let mut ev = Vec::new();
    let mut rest = bytes;
    let mut k = u32::from(cut);
    while !rest.is_empty() {
        k = k.wrapping_mul(1_103_515_245).wrapping_add(12_345);
        let n = (1 + (k >> 16) as usize % 40).min(rest.len());
        d.push(&rest[..n], &mut ev);
        if cut & 1 == 1 && n % 7 == 0 {
            d.gap(&mut ev);
        }
        rest = &rest[n..];
    }
    d.gap(&mut ev);
    ev
}

fuzz_target!(|data: &[u8]| {
    let Some((&cut, bytes)) = data.split_first() else {
        return;
    };
    for side in [Side::Requests, Side::Responses] {
        let events = run(side, bytes, cut);
        for e in &events {
            let Event::Frame(f) = e else { continue };
            let mut adu = Vec::new();
            rtu::frame(f.unit, &f.pdu, &mut adu);
            assert!(adu.len() <= rtu::MAX_ADU, "a frame of {} bytes", adu.len());
            assert!(rtu::crc_ok(&adu));
            if side == Side::Requests {
                let mut out = Vec::new();
                handle(&Mem, &f.pdu, &mut out);
                assert!(!out.is_empty() && out.len() <= MAX_PDU, "answer of {} bytes", out.len());
            }
        }
        // Without silences inside, the cutting does not matter.
        if cut & 1 == 0 {
            let mut whole = Decoder::new(side);
            let mut ev = Vec::new();
            whole.push(bytes, &mut ev);
            whole.gap(&mut ev);
            assert_eq!(ev, events, "pushed at once and in pieces differ");
        }
    }
});
