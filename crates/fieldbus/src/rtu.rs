//! The Modbus RTU frame (Modbus over Serial Line V1.02, 2.5): unit
//! address, the PDU of [`crate::pdu`], CRC-16/Modbus low byte first; no
//! I/O, so the decoder is fuzzed whole (`fuzz/fuzz_targets/modbus_rtu.rs`).
//!
//! RTU has no length field: a frame ends with a silent interval of 3.5
//! character times. Waiting for that silence alone makes a slave late by
//! it and breaks over USB serial adapters, which deliver bytes in bursts
//! with gaps of several milliseconds inside one frame. So the [`Decoder`]
//! takes a frame as soon as its function code and byte count say it is
//! complete, and uses the silence ([`Decoder::gap`]) only to end what it
//! cannot measure: an unknown function code (answered with exception 01
//! when its CRC holds) or a fragment. A CRC error, a frame over 256 bytes
//! or a fragment is dropped, and everything up to the next silence with
//! it, since the line cannot be resynchronised inside a frame; the master
//! sees a timeout and retries, as the specification intends.

use std::time::Duration;

/// The largest RTU frame: address, 253 PDU bytes, CRC.
pub const MAX_ADU: usize = 256;
/// The smallest: address, function code, CRC.
pub const MIN_ADU: usize = 4;

/// CRC-16/Modbus (reflected polynomial 0xA001, initial value 0xFFFF).
pub fn crc16(data: &[u8]) -> u16 {
    let mut crc: u16 = 0xFFFF;
    for &b in data {
        crc ^= u16::from(b);
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xA001
            } else {
                crc >> 1
            };
        }
    }
    crc
}

/// Appends the frame of `pdu` for `unit` to `out`.
pub fn frame(unit: u8, pdu: &[u8], out: &mut Vec<u8>) {
    let start = out.len();
    out.push(unit);
    out.extend_from_slice(pdu);
    let crc = crc16(&out[start..]);
    out.extend_from_slice(&crc.to_le_bytes());
}

/// Whether the last two bytes of `adu` are the CRC of the rest.
pub fn crc_ok(adu: &[u8]) -> bool {
    match adu.len().checked_sub(2) {
        Some(n) if n >= 2 => crc16(&adu[..n]).to_le_bytes() == [adu[n], adu[n + 1]],
        _ => false,
    }
}

/// The time of one character at `baud`: start bit, 8 data bits, parity
/// (if any) and stop bits.
pub fn char_time(baud: u32, parity: bool, stop_bits: u8) -> Duration {
    let bits = 1 + 8 + u64::from(parity) + u64::from(stop_bits);
    Duration::from_nanos(bits * 1_000_000_000 / u64::from(baud.max(1)))
}

/// The specification's silent interval between frames: 3.5 characters,
/// fixed at 1.75 ms above 19200 baud. A master waits this long after a
/// response before its next request.
pub fn silence(baud: u32, parity: bool, stop_bits: u8) -> Duration {
    if baud > 19_200 {
        Duration::from_micros(1750)
    } else {
        char_time(baud, parity, stop_bits) * 7 / 2
    }
}

/// The silence after which a receiver takes a frame as ended: [`silence`]
/// but never below [`MIN_GAP`] (bursts of USB serial adapters and
/// pseudo-terminals).
pub fn frame_gap(baud: u32, parity: bool, stop_bits: u8) -> Duration {
    silence(baud, parity, stop_bits).max(MIN_GAP)
}

/// See [`frame_gap`].
pub const MIN_GAP: Duration = Duration::from_millis(20);

/// What the decoder reads: requests (a slave) or responses (a master).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    Requests,
    Responses,
}

/// The length of a frame as far as its first bytes tell.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Len {
    /// More bytes are needed to know.
    More,
    Known(usize),
    /// A function code whose length cannot be known: the silence ends it.
    Unknown,
}

/// The length of the frame at the start of `buf`.
pub fn frame_len(side: Side, buf: &[u8]) -> Len {
    let Some(&fc) = buf.get(1) else {
        return Len::More;
    };
    // Bytes before a byte count at `at`, then that many bytes, then CRC.
    let counted = |at: usize| {
        buf.get(at)
            .map_or(Len::More, |&n| Len::Known(at + 1 + usize::from(n) + 2))
    };
    match side {
        Side::Requests => match fc {
            1..=6 => Len::Known(8),
            15 | 16 => counted(6),
            23 => counted(10),
            _ => Len::Unknown,
        },
        Side::Responses => match fc {
            1..=4 | 23 => counted(2),
            5 | 6 | 15 | 16 => Len::Known(8),
            0x81..=0x86 | 0x8F | 0x90 | 0x97 => Len::Known(5),
            _ => Len::Unknown,
        },
    }
}

/// A checked frame: the unit address and the PDU.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Frame {
    pub unit: u8,
    pub pdu: Vec<u8>,
}

/// Why bytes were dropped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dropped {
    /// The CRC does not match.
    Crc,
    /// Silence before the frame was complete.
    Fragment,
    /// More than [`MAX_ADU`] bytes without a frame.
    TooLong,
}

/// What the decoder found.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Event {
    Frame(Frame),
    Dropped(Dropped),
}

/// Splits the received bytes into frames (see the module).
#[derive(Debug)]
pub struct Decoder {
    side: Side,
    buf: Vec<u8>,
    /// After an error, everything until the next silence is dropped.
    discarding: bool,
}

impl Decoder {
    pub fn new(side: Side) -> Decoder {
        Decoder {
            side,
            buf: Vec::with_capacity(MAX_ADU),
            discarding: false,
        }
    }

    /// Whether bytes of an incomplete frame are held.
    pub fn pending(&self) -> bool {
        !self.buf.is_empty()
    }

    /// Bytes received; the frames they complete are appended to `out`.
    pub fn push(&mut self, bytes: &[u8], out: &mut Vec<Event>) {
        if self.discarding {
            return;
        }
        self.buf.extend_from_slice(bytes);
        loop {
            match frame_len(self.side, &self.buf) {
                Len::Known(n) if n > MAX_ADU => return self.drop_all(Dropped::TooLong, out),
                Len::Known(n) if self.buf.len() >= n => {
                    if !crc_ok(&self.buf[..n]) {
                        return self.drop_all(Dropped::Crc, out);
                    }
                    out.push(Event::Frame(Frame {
                        unit: self.buf[0],
                        pdu: self.buf[1..n - 2].to_vec(),
                    }));
                    self.buf.drain(..n);
                }
                Len::Known(_) | Len::More | Len::Unknown => break,
            }
        }
        if self.buf.len() > MAX_ADU {
            self.drop_all(Dropped::TooLong, out);
        }
    }

    /// A silent interval of [`frame_gap`]: an unmeasurable frame ends here,
    /// a fragment is dropped, and reception starts afresh.
    pub fn gap(&mut self, out: &mut Vec<Event>) {
        let discarding = std::mem::replace(&mut self.discarding, false);
        if discarding || self.buf.is_empty() {
            self.buf.clear();
            return;
        }
        let unmeasurable = frame_len(self.side, &self.buf) == Len::Unknown;
        if unmeasurable && self.buf.len() >= MIN_ADU && crc_ok(&self.buf) {
            let n = self.buf.len();
            out.push(Event::Frame(Frame {
                unit: self.buf[0],
                pdu: self.buf[1..n - 2].to_vec(),
            }));
        } else if unmeasurable && self.buf.len() >= MIN_ADU {
            out.push(Event::Dropped(Dropped::Crc));
        } else {
            out.push(Event::Dropped(Dropped::Fragment));
        }
        self.buf.clear();
    }

    fn drop_all(&mut self, why: Dropped, out: &mut Vec<Event>) {
        self.buf.clear();
        self.discarding = true;
        out.push(Event::Dropped(why));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn adu(unit: u8, pdu: &[u8]) -> Vec<u8> {
        let mut v = Vec::new();
        frame(unit, pdu, &mut v);
        v
    }

    #[test]
    fn crc_matches_the_specifications_examples() {
        // Modbus over Serial Line V1.02, 6.2.2: read 2 holding registers
        // from 0x006B of slave 0x11 (the classic example, CRC 0x8776).
        assert_eq!(crc16(&[0x11, 0x03, 0x00, 0x6B, 0x00, 0x03]), 0x8776);
        assert_eq!(
            adu(0x11, &[0x03, 0x00, 0x6B, 0x00, 0x03]),
            [0x11, 0x03, 0x00, 0x6B, 0x00, 0x03, 0x76, 0x87]
        );
        // Read 1 coil from 0 of slave 1: 01 01 00 00 00 01 FD CA.
        assert_eq!(adu(1, &[1, 0, 0, 0, 1]), [1, 1, 0, 0, 0, 1, 0xFD, 0xCA]);
        assert_eq!(crc16(b"123456789"), 0x4B37);
        assert!(crc_ok(&[1, 1, 0, 0, 0, 1, 0xFD, 0xCA]));
        assert!(!crc_ok(&[1, 1, 0, 0, 0, 1, 0xFD, 0xCB]));
        assert!(!crc_ok(&[1, 2]));
    }

    #[test]
    fn silent_interval_follows_the_baud_rate() {
        // 9600 8E1: 11 bits = 1.1458 ms a character, 3.5 of them 4.01 ms,
        // raised to the 20 ms floor.
        assert_eq!(char_time(9600, true, 1), Duration::from_nanos(1_145_833));
        assert_eq!(frame_gap(9600, true, 1), MIN_GAP);
        // 1200 8N1: 10 bits = 8.333 ms, 3.5 characters 29.17 ms.
        assert_eq!(frame_gap(1200, false, 1), Duration::from_nanos(29_166_665));
        assert_eq!(frame_gap(115_200, false, 1), MIN_GAP);
        assert_eq!(silence(9600, true, 1), Duration::from_nanos(4_010_415));
        assert_eq!(silence(115_200, false, 1), Duration::from_micros(1750));
    }

    #[test]
    fn lengths_come_from_function_code_and_byte_count() {
        use Side::*;
        assert_eq!(frame_len(Requests, &[1]), Len::More);
        assert_eq!(frame_len(Requests, &[1, 3]), Len::Known(8));
        assert_eq!(frame_len(Requests, &[1, 16, 0, 0, 0, 2]), Len::More);
        assert_eq!(frame_len(Requests, &[1, 16, 0, 0, 0, 2, 4]), Len::Known(13));
        assert_eq!(
            frame_len(Requests, &[1, 23, 0, 0, 0, 1, 0, 0, 0, 1, 2]),
            Len::Known(15)
        );
        assert_eq!(frame_len(Requests, &[1, 8]), Len::Unknown);
        assert_eq!(frame_len(Responses, &[1, 3, 4]), Len::Known(9));
        assert_eq!(frame_len(Responses, &[1, 0x83]), Len::Known(5));
        assert_eq!(frame_len(Responses, &[1, 16]), Len::Known(8));
    }

    #[test]
    fn the_decoder_splits_joins_and_drops() {
        let mut d = Decoder::new(Side::Requests);
        let mut ev = Vec::new();
        let a = adu(1, &[3, 0, 0, 0, 2]);
        let b = adu(7, &[16, 0, 4, 0, 1, 2, 0x12, 0x34]);
        // Two frames in one read, the second split across reads.
        let mut both = a.clone();
        both.extend_from_slice(&b[..5]);
        d.push(&both, &mut ev);
        assert_eq!(
            ev,
            [Event::Frame(Frame {
                unit: 1,
                pdu: vec![3, 0, 0, 0, 2]
            })]
        );
        assert!(d.pending());
        ev.clear();
        d.push(&b[5..], &mut ev);
        assert_eq!(
            ev,
            [Event::Frame(Frame {
                unit: 7,
                pdu: vec![16, 0, 4, 0, 1, 2, 0x12, 0x34]
            })]
        );
        assert!(!d.pending());
        // A CRC error drops the rest until the silence, then all is well.
        ev.clear();
        let mut bad = a.clone();
        bad[7] ^= 1;
        d.push(&bad, &mut ev);
        d.push(&a, &mut ev);
        assert_eq!(ev, [Event::Dropped(Dropped::Crc)]);
        ev.clear();
        d.gap(&mut ev);
        d.push(&a, &mut ev);
        assert_eq!(ev.len(), 1);
        // A fragment ends at the silence.
        ev.clear();
        d.push(&a[..5], &mut ev);
        d.gap(&mut ev);
        assert_eq!(ev, [Event::Dropped(Dropped::Fragment)]);
        // An unknown function code ends at the silence, CRC checked.
        ev.clear();
        d.push(&adu(1, &[8, 0, 0, 0xA5, 0x37]), &mut ev);
        assert!(ev.is_empty());
        d.gap(&mut ev);
        assert_eq!(
            ev,
            [Event::Frame(Frame {
                unit: 1,
                pdu: vec![8, 0, 0, 0xA5, 0x37]
            })]
        );
        // A flood without a silence is dropped at 257 bytes.
        ev.clear();
        d.push(&[1, 8], &mut ev);
        d.push(&[0u8; 300], &mut ev);
        assert_eq!(ev, [Event::Dropped(Dropped::TooLong)]);
        // A byte count that announces more than 256 bytes at once.
        let mut d = Decoder::new(Side::Responses);
        ev.clear();
        d.push(&[1, 3, 255], &mut ev);
        assert_eq!(ev, [Event::Dropped(Dropped::TooLong)]);
    }
}
