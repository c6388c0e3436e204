//! The server's address map: Modbus addresses → places of the PLC image.
//!
//! The default map is OpenPLC's (`docs/modbus.md`): coil 8n+b = `%QXn.b`,
//! discrete input 8n+b = `%IXn.b`, input register n = `%IWn`, holding
//! registers 0–1023 = `%QW0..`, 1024–2047 = `%MW0..`, 2048–4095 = `%MD0..`
//! (two registers each, low word first), 4096–8191 = `%ML0..` (four each,
//! low word first); each only as far as the program's area reaches (the
//! areas are sized by the highest address the program uses), so an
//! address past it is exception 02. Explicit entries map one variable of
//! any path to a coil, discrete input or register range with its IEC type
//! (BOOL one bit; 8- and 16-bit types one register, sign-extended for
//! SINT; 32-bit types such as DINT and REAL two, 64-bit four, in the
//! entry's word order; a one-dimensional array maps its elements one
//! after another); they win over the default map where both give an
//! address.
//!
//! Registers are read from the image as the PLC stores them (little
//! endian), so a REAL's registers carry its IEEE 754 bits unchanged.

use crate::pdu::{Exception, Table};
use automat_iec::Elementary;
use automat_ir::{Program, SymbolType};
use automat_runtime::{Place, PlaceType};
use automat_session::value::Stored;
use std::ops::Range;

/// Where the words of a multi-register value go.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WordOrder {
    /// The most significant word at the lowest address (Modbus's usual
    /// big-endian order, "ABCD").
    HighFirst,
    /// The least significant word first (OpenPLC's %MD/%ML, "CDAB").
    LowFirst,
}

#[derive(Clone, Debug, PartialEq, Eq)]
enum BitAt {
    /// Bit k of the segment is bit k%8 of byte `byte + k/8`.
    Packed { byte: usize },
    /// One BOOL: a bit of a byte, or a whole byte (0/1).
    Single { offset: usize, bit: Option<u8> },
}

#[derive(Clone, Debug, PartialEq, Eq)]
struct BitSeg {
    start: u32,
    count: u32,
    at: BitAt,
}

/// A run of registers over consecutive elements of one size.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct RegSeg {
    pub start: u32,
    pub count: u32,
    pub base: usize,
    /// Registers per element (1, 2, 4).
    pub width: u32,
    /// Bytes per element (1, 2, 4, 8).
    pub bytes: u32,
    /// A one-byte signed type (SINT): sign-extended when read.
    pub signed: bool,
    pub order: WordOrder,
}

impl RegSeg {
    fn end(&self) -> u32 {
        self.start + self.count
    }
    /// The image bytes of register `r` (one byte for 8-bit types).
    fn bytes_of(&self, r: u32) -> (usize, usize) {
        let k = r - self.start;
        let elem = self.base + (k / self.width) as usize * self.bytes as usize;
        if self.bytes == 1 {
            return (elem, 1);
        }
        let j = k % self.width;
        let w = match self.order {
            WordOrder::LowFirst => j,
            WordOrder::HighFirst => self.width - 1 - j,
        };
        (elem + 2 * w as usize, 2)
    }
    pub(crate) fn read(&self, image: &[u8], r: u32) -> Option<u16> {
        let (at, n) = self.bytes_of(r);
        if n == 1 {
            let b = *image.get(at)?;
            return Some(if self.signed {
                i16::from(b as i8) as u16
            } else {
                u16::from(b)
            });
        }
        Some(u16::from_le_bytes([*image.get(at)?, *image.get(at + 1)?]))
    }
    pub(crate) fn store(&self, r: u32, v: u16) -> Stored {
        let (offset, n) = self.bytes_of(r);
        let bytes = if n == 1 {
            vec![v as u8]
        } else {
            v.to_le_bytes().to_vec()
        };
        Stored::Bytes { offset, bytes }
    }
}

/// How one variable maps onto registers: `(registers, bytes, signed)`;
/// `None` for types that are not one elementary value of 8 to 64 bits.
pub(crate) fn register_shape(ty: &PlaceType) -> Option<(u32, u32, bool)> {
    let e = match ty {
        PlaceType::Elementary(e) | PlaceType::Enum { base: e, .. } => *e,
        _ => return None,
    };
    match e.bit_width()? {
        8 => Some((1, 1, e == Elementary::Sint)),
        16 => Some((1, 2, false)),
        32 => Some((2, 4, false)),
        64 => Some((4, 8, false)),
        _ => None,
    }
}

/// The address map of a server (see the module comment).
#[derive(Clone, Debug, Default)]
pub struct Map {
    coils: Vec<BitSeg>,
    discrete: Vec<BitSeg>,
    input: Vec<RegSeg>,
    holding: Vec<RegSeg>,
    /// Image bytes of CONSTANTs a default range covers: written never.
    readonly: Vec<Range<usize>>,
    /// Refuse every write (`read_only = true`).
    pub read_only: bool,
}

/// One line of the printed map.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MapLine {
    pub table: Table,
    pub first: u32,
    pub last: u32,
    pub what: String,
}

fn area(r: &Range<u32>) -> (usize, usize) {
    (r.start as usize, r.len())
}

impl Map {
    /// The OpenPLC-compatible default map of `program`.
    pub fn default_of(program: &Program) -> Map {
        let (i0, il) = area(&program.areas.input);
        let (q0, ql) = area(&program.areas.output);
        let (m0, ml) = area(&program.areas.memory);
        let cap = |n: usize| u32::try_from(n.min(65_536)).unwrap_or(65_536);
        let mut map = Map::default();
        if ql > 0 {
            map.coils.push(BitSeg {
                start: 0,
                count: cap(ql * 8),
                at: BitAt::Packed { byte: q0 },
            });
        }
        if il > 0 {
            map.discrete.push(BitSeg {
                start: 0,
                count: cap(il * 8),
                at: BitAt::Packed { byte: i0 },
            });
        }
        let words = |start: u32, base: usize, len: usize, width: u32, max_elems: usize| {
            let bytes = width * 2;
            let elems = (len / bytes as usize).min(max_elems);
            (elems > 0).then(|| RegSeg {
                start,
                count: elems as u32 * width,
                base,
                width,
                bytes,
                signed: false,
                order: WordOrder::LowFirst,
            })
        };
        map.input.extend(words(0, i0, il, 1, 65_536));
        map.holding.extend(words(0, q0, ql, 1, 1024));
        map.holding.extend(words(1024, m0, ml, 1, 1024));
        map.holding.extend(words(2048, m0, ml, 2, 1024));
        map.holding.extend(words(4096, m0, ml, 4, 1024));
        for e in program.symbols.entries() {
            if !e.constant {
                continue;
            }
            let size = symbol_size(&e.ty);
            let start = e.offset as usize;
            if size > 0 {
                map.readonly.push(start..start + size);
            }
        }
        map
    }

    /// Adds an explicit entry for a BOOL place in a bit table.
    pub(crate) fn add_bit(&mut self, table: Table, address: u16, place: &Place) {
        let seg = BitSeg {
            start: u32::from(address),
            count: 1,
            at: BitAt::Single {
                offset: place.offset as usize,
                bit: place.bit,
            },
        };
        let list = self.bits_mut(table);
        list.insert(0, seg);
    }

    /// Adds an explicit entry for a register-shaped place.
    pub(crate) fn add_registers(
        &mut self,
        table: Table,
        address: u16,
        place: &Place,
        order: WordOrder,
    ) -> bool {
        let Some((width, bytes, signed)) = register_shape(&place.ty) else {
            return false;
        };
        let seg = RegSeg {
            start: u32::from(address),
            count: width,
            base: place.offset as usize,
            width,
            bytes,
            signed,
            order,
        };
        match table {
            Table::InputRegisters => self.input.insert(0, seg),
            _ => self.holding.insert(0, seg),
        }
        true
    }

    fn bits_mut(&mut self, table: Table) -> &mut Vec<BitSeg> {
        match table {
            Table::Coils => &mut self.coils,
            _ => &mut self.discrete,
        }
    }

    fn bits(&self, table: Table) -> &[BitSeg] {
        match table {
            Table::Coils => &self.coils,
            _ => &self.discrete,
        }
    }

    fn regs(&self, table: Table) -> &[RegSeg] {
        match table {
            Table::InputRegisters => &self.input,
            _ => &self.holding,
        }
    }

    /// Explicit entries come first, so they win where both map an address.
    fn bit_seg(&self, table: Table, a: u32) -> Option<&BitSeg> {
        self.bits(table)
            .iter()
            .find(|s| a >= s.start && a < s.start + s.count)
    }

    fn reg_seg(&self, table: Table, a: u32) -> Option<&RegSeg> {
        self.regs(table)
            .iter()
            .find(|s| a >= s.start && a < s.end())
    }

    pub fn read_bits(
        &self,
        table: Table,
        image: &[u8],
        addr: u16,
        count: u16,
    ) -> Result<Vec<bool>, Exception> {
        let mut out = Vec::with_capacity(usize::from(count));
        for a in u32::from(addr)..u32::from(addr) + u32::from(count) {
            let seg = self
                .bit_seg(table, a)
                .ok_or(Exception::IllegalDataAddress)?;
            let v = match &seg.at {
                BitAt::Packed { byte } => {
                    let k = (a - seg.start) as usize;
                    image
                        .get(byte + k / 8)
                        .ok_or(Exception::IllegalDataAddress)?
                        & (1 << (k % 8))
                        != 0
                }
                BitAt::Single { offset, bit } => {
                    let b = *image.get(*offset).ok_or(Exception::IllegalDataAddress)?;
                    match bit {
                        Some(bit) => b & (1 << (bit & 7)) != 0,
                        None => b != 0,
                    }
                }
            };
            out.push(v);
        }
        Ok(out)
    }

    pub fn read_registers(
        &self,
        table: Table,
        image: &[u8],
        addr: u16,
        count: u16,
    ) -> Result<Vec<u16>, Exception> {
        let mut out = Vec::with_capacity(usize::from(count));
        for a in u32::from(addr)..u32::from(addr) + u32::from(count) {
            let seg = self
                .reg_seg(table, a)
                .ok_or(Exception::IllegalDataAddress)?;
            out.push(seg.read(image, a).ok_or(Exception::IllegalDataAddress)?);
        }
        Ok(out)
    }

    fn check_writable(&self, s: &Stored) -> Result<(), Exception> {
        let (at, n) = match s {
            Stored::Bit { offset, .. } => (*offset, 1),
            Stored::Bytes { offset, bytes } => (*offset, bytes.len()),
        };
        if self.readonly.iter().any(|r| at < r.end && r.start < at + n) {
            return Err(Exception::IllegalDataAddress);
        }
        Ok(())
    }

    /// What writing `values` to the coils from `addr` stores.
    pub fn write_coils(&self, addr: u16, values: &[bool]) -> Result<Vec<Stored>, Exception> {
        if self.read_only {
            return Err(Exception::IllegalFunction);
        }
        let mut out = Vec::with_capacity(values.len());
        for (k, v) in values.iter().enumerate() {
            let a = u32::from(addr) + k as u32;
            let seg = self
                .bit_seg(Table::Coils, a)
                .ok_or(Exception::IllegalDataAddress)?;
            let s = match &seg.at {
                BitAt::Packed { byte } => {
                    let i = (a - seg.start) as usize;
                    Stored::Bit {
                        offset: byte + i / 8,
                        bit: (i % 8) as u8,
                        value: *v,
                    }
                }
                BitAt::Single {
                    offset,
                    bit: Some(bit),
                } => Stored::Bit {
                    offset: *offset,
                    bit: *bit,
                    value: *v,
                },
                BitAt::Single { offset, bit: None } => Stored::Bytes {
                    offset: *offset,
                    bytes: vec![u8::from(*v)],
                },
            };
            self.check_writable(&s)?;
            out.push(s);
        }
        Ok(out)
    }

    /// What writing `values` to the holding registers from `addr` stores.
    pub fn write_registers(&self, addr: u16, values: &[u16]) -> Result<Vec<Stored>, Exception> {
        if self.read_only {
            return Err(Exception::IllegalFunction);
        }
        let mut out = Vec::with_capacity(values.len());
        for (k, v) in values.iter().enumerate() {
            let a = u32::from(addr) + k as u32;
            let seg = self
                .reg_seg(Table::HoldingRegisters, a)
                .ok_or(Exception::IllegalDataAddress)?;
            let s = seg.store(a, *v);
            self.check_writable(&s)?;
            out.push(s);
        }
        Ok(out)
    }

    /// The map for people: one line per range, explicit entries first.
    pub fn lines(&self) -> Vec<MapLine> {
        let mut out = Vec::new();
        for (table, segs) in [
            (Table::Coils, &self.coils),
            (Table::DiscreteInputs, &self.discrete),
        ] {
            for s in segs {
                out.push(MapLine {
                    table,
                    first: s.start,
                    last: s.start + s.count - 1,
                    what: match &s.at {
                        BitAt::Packed { .. } => {
                            let a = if table == Table::Coils { "Q" } else { "I" };
                            format!(
                                "%{a}X0.0 .. %{a}X{}.{}",
                                (s.count - 1) / 8,
                                (s.count - 1) % 8
                            )
                        }
                        BitAt::Single { .. } => "explicit BOOL".into(),
                    },
                });
            }
        }
        for (table, segs) in [
            (Table::InputRegisters, &self.input),
            (Table::HoldingRegisters, &self.holding),
        ] {
            for s in segs {
                out.push(MapLine {
                    table,
                    first: s.start,
                    last: s.end() - 1,
                    what: format!(
                        "{} byte(s) per value, {} register(s) each{}",
                        s.bytes,
                        s.width,
                        if s.width > 1 {
                            match s.order {
                                WordOrder::LowFirst => ", low word first",
                                WordOrder::HighFirst => ", high word first",
                            }
                        } else {
                            ""
                        }
                    ),
                });
            }
        }
        out
    }
}

/// Bytes a symbol occupies (0 when unknown).
fn symbol_size(ty: &SymbolType) -> usize {
    match ty {
        SymbolType::Elementary(e)
        | SymbolType::Enum { base: e, .. }
        | SymbolType::Subrange { base: e, .. } => {
            e.bit_width().map_or(0, |w| w.div_ceil(8)) as usize
        }
        SymbolType::String { cap } => *cap as usize + 2,
        SymbolType::WString { cap } => *cap as usize * 2 + 2,
        SymbolType::Array { dims, stride, .. } => {
            let n: i64 = dims
                .iter()
                .map(|(lo, hi)| (hi - lo + 1).max(0))
                .fold(1i64, |a, b| a.saturating_mul(b));
            usize::try_from(n.saturating_mul(i64::from(*stride))).unwrap_or(0)
        }
        SymbolType::Struct { fields, .. } => fields
            .iter()
            .map(|f| f.offset as usize + symbol_size(&f.ty))
            .max()
            .unwrap_or(0),
        SymbolType::Ref(_) => 4,
    }
}
