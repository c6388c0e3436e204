//! The RETAIN file: the bytes of the program's retain ranges, kept across a
//! warm start.
//!
//! Format (little-endian):
//! ```text
//! 0   8  magic "AUTOMATR"
//! 8   4  version (1)
//! 12  8  layout hash (FNV-1a 64 of the retain ranges and the retained
//!        symbols' paths, offsets and types)
//! 20  4  payload length
//! 24  n  payload: the retain ranges' bytes, in order
//! 24+n 4 CRC-32 of every byte before it
//! ```
//! Saving is atomic and durable ([`file`]): a power cut or kill leaves
//! either the old or the new file. What is saved is always a consistent
//! image, the state at the end of a completed scan ([`keeper`]). Loading
//! never fails hard: a missing file is a cold start; a damaged, truncated
//! or foreign file, one written by a different program layout, or one
//! holding a value its variable's type cannot have ([`validate`]) is a
//! cold start with a warning saying why, and is moved aside to
//! `<file>.bad` rather than overwritten by the next save.

pub mod file;
pub mod keeper;
pub mod validate;

use crate::crc::crc32;
use automat_ir::{Program, SymbolType};
use std::fs;
use std::ops::Range;
use std::path::Path;

pub use keeper::Keeper;

const MAGIC: &[u8; 8] = b"AUTOMATR";
const VERSION: u32 = 1;
const HEADER: usize = 24;

/// The outcome of loading a retain file into an image.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Loaded {
    /// The retain ranges were restored: a warm start.
    Warm,
    /// No file: a cold start.
    NoFile,
    /// Unusable file: a cold start; the message says why.
    Cold(String),
}

struct Fnv(u64);

impl Fnv {
    fn bytes(&mut self, data: &[u8]) {
        for &b in data {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01B3);
        }
    }
    fn num(&mut self, n: i128) {
        self.bytes(&n.to_le_bytes());
    }
    fn str(&mut self, s: &str) {
        self.num(s.len() as i128);
        self.bytes(s.as_bytes());
    }
    fn ty(&mut self, ty: &SymbolType) {
        match ty {
            SymbolType::Elementary(e) => {
                self.num(1);
                self.str(e.name());
            }
            SymbolType::String { cap } => {
                self.num(2);
                self.num((*cap).into());
            }
            SymbolType::WString { cap } => {
                self.num(3);
                self.num((*cap).into());
            }
            SymbolType::Array { elem, dims, stride } => {
                self.num(4);
                for (lo, hi) in dims {
                    self.num((*lo).into());
                    self.num((*hi).into());
                }
                self.num((*stride).into());
                self.ty(elem);
            }
            SymbolType::Struct { name, fields } => {
                self.num(5);
                self.str(name);
                for f in fields {
                    self.str(&f.name);
                    self.num(f.offset.into());
                    self.num(f.bit.map_or(-1, i128::from));
                    self.ty(&f.ty);
                }
            }
            SymbolType::Enum { name, base, values } => {
                self.num(6);
                self.str(name);
                self.str(base.name());
                for (n, v) in values {
                    self.str(n);
                    self.num((*v).into());
                }
            }
            SymbolType::Subrange { base, lo, hi } => {
                self.num(7);
                self.str(base.name());
                self.num((*lo).into());
                self.num((*hi).into());
            }
            SymbolType::Ref(t) => {
                self.num(8);
                self.ty(t);
            }
        }
    }
}

/// A hash of everything that gives the retain bytes their meaning: a file
/// written by a program with another hash is not loaded.
pub fn layout_hash(program: &Program) -> u64 {
    let mut h = Fnv(0xCBF2_9CE4_8422_2325);
    for r in &program.retain {
        h.num(r.start.into());
        h.num(r.end.into());
    }
    for e in program.symbols.entries().iter().filter(|e| e.retain) {
        h.str(&e.path);
        h.num(e.offset.into());
        h.num(e.bit.map_or(-1, i128::from));
        h.ty(&e.ty);
    }
    h.0
}

fn usize_range(r: &Range<u32>) -> Option<Range<usize>> {
    Some(usize::try_from(r.start).ok()?..usize::try_from(r.end).ok()?)
}

/// The bytes of the retain ranges of `image`, in order; `None` when a
/// range is not inside the image.
pub fn payload(program: &Program, image: &[u8]) -> Option<Vec<u8>> {
    let mut payload = Vec::new();
    for r in &program.retain {
        payload.extend_from_slice(image.get(usize_range(r)?)?);
    }
    Some(payload)
}

/// The file's bytes for the retain ranges of `image`; `None` when a range
/// is not inside the image.
pub fn encode(program: &Program, image: &[u8]) -> Option<Vec<u8>> {
    encode_payload(layout_hash(program), &payload(program, image)?)
}

/// The file's bytes for a payload ([`payload`]) of a program whose layout
/// hash is `hash`.
pub fn encode_payload(hash: u64, payload: &[u8]) -> Option<Vec<u8>> {
    let mut out = Vec::with_capacity(HEADER + payload.len() + 4);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&VERSION.to_le_bytes());
    out.extend_from_slice(&hash.to_le_bytes());
    out.extend_from_slice(&u32::try_from(payload.len()).ok()?.to_le_bytes());
    out.extend_from_slice(payload);
    let crc = crc32(&out);
    out.extend_from_slice(&crc.to_le_bytes());
    Some(out)
}

fn field<const N: usize>(data: &[u8], at: usize) -> Option<[u8; N]> {
    data.get(at..at.checked_add(N)?)?.try_into().ok()
}

/// Restores the retain ranges of `image` from file bytes; the image is
/// untouched unless the whole file is valid, every value included
/// ([`validate`]).
pub fn decode(program: &Program, data: &[u8], image: &mut [u8]) -> Result<(), String> {
    if data.len() < 8 || data.get(..8) != Some(MAGIC.as_slice()) {
        return Err("not an automat retain file".to_string());
    }
    let truncated = || "the file is truncated".to_string();
    let version = u32::from_le_bytes(field(data, 8).ok_or_else(truncated)?);
    if version != VERSION {
        return Err(format!(
            "format version {version} is not supported (this automat reads version {VERSION})"
        ));
    }
    let hash = u64::from_le_bytes(field(data, 12).ok_or_else(truncated)?);
    let len = u32::from_le_bytes(field(data, 20).ok_or_else(truncated)?);
    let len = usize::try_from(len).map_err(|_| truncated())?;
    let body_end = HEADER.checked_add(len).ok_or_else(truncated)?;
    let stored = u32::from_le_bytes(field(data, body_end).ok_or_else(truncated)?);
    if body_end + 4 != data.len() {
        return Err(format!(
            "the file has {} bytes; its header announces {}",
            data.len(),
            body_end + 4
        ));
    }
    let body = data.get(..body_end).ok_or_else(truncated)?;
    if crc32(body) != stored {
        return Err("the checksum does not match: the file is corrupt".to_string());
    }
    if hash != layout_hash(program) {
        return Err(
            "the program's RETAIN variables changed since the file was written".to_string(),
        );
    }
    let payload = data.get(HEADER..body_end).ok_or_else(truncated)?;
    let total: usize = program.retain.iter().map(|r| r.len()).sum();
    if total != payload.len() {
        return Err(format!(
            "the file holds {} bytes of RETAIN data; the program has {total}",
            payload.len()
        ));
    }
    // The values are checked on a copy, so a bad file leaves no trace.
    let mut scratch = image.to_vec();
    let mut at = 0usize;
    for r in &program.retain {
        let dst = usize_range(r)
            .and_then(|r| scratch.get_mut(r))
            .ok_or_else(|| "a RETAIN range lies outside the memory image".to_string())?;
        let end = at.checked_add(dst.len()).ok_or_else(truncated)?;
        let src = payload.get(at..end).ok_or_else(truncated)?;
        dst.copy_from_slice(src);
        at = end;
    }
    if let Some(why) = validate::first_invalid(program, &scratch) {
        return Err(format!("the RETAIN variable {why}"));
    }
    for r in &program.retain {
        let range = usize_range(r).ok_or_else(truncated)?;
        if let (Some(dst), Some(src)) = (image.get_mut(range.clone()), scratch.get(range)) {
            dst.copy_from_slice(src);
        }
    }
    Ok(())
}

/// Loads `path` into the retain ranges of `image` (see [`Loaded`]). A file
/// that cannot be used is moved aside to `<file>.bad` (the message says
/// so), so the next save keeps what it held for inspection.
pub fn load(program: &Program, path: &Path, image: &mut [u8]) -> Loaded {
    match fs::read(path) {
        Ok(data) => match decode(program, &data, image) {
            Ok(()) => Loaded::Warm,
            Err(why) => Loaded::Cold(match file::move_aside(path) {
                Ok(bad) => format!("{why}; the file was moved to {}", bad.display()),
                Err(e) => format!("{why}; it could not be moved aside: {e}"),
            }),
        },
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Loaded::NoFile,
        Err(e) => Loaded::Cold(format!("cannot read it: {e}")),
    }
}

/// Saves the retain ranges of `image` to `path` atomically and durably.
pub fn save(program: &Program, path: &Path, image: &[u8]) -> Result<(), String> {
    let data = encode(program, image)
        .ok_or_else(|| "a RETAIN range lies outside the memory image".to_string())?;
    save_bytes(path, &data)
}

/// Replaces `path` by the file bytes `data` ([`encode`]) atomically.
pub fn save_bytes(path: &Path, data: &[u8]) -> Result<(), String> {
    file::replace(path, data)
        .map_err(|e| format!("{}: cannot save the RETAIN variables: {e}", path.display()))
}

/// The start-up check of a RETAIN path, before the first scan: its folder
/// exists and takes a file of this program's size (a test save of the
/// temporary, removed again).
pub fn check_path(program: &Program, path: &Path) -> Result<(), String> {
    let payload: usize = program.retain.iter().map(|r| r.len()).sum();
    file::check_writable(path, HEADER + payload + 4)
}

#[cfg(test)]
#[path = "tests.rs"]
mod tests;
