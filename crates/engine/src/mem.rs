//! Checked access to the image: every read and write names its width; an
//! address outside the image is `None` (the interpreter turns it into a
//! fault), never a panic.

use automat_ir::code::MemTy;
use automat_ir::strbuf;

/// Reads a value of `ty` at `at`, extended to the register's 64 bits
/// (floats as their bit patterns).
#[inline]
pub fn load(image: &[u8], at: u32, ty: MemTy) -> Option<u64> {
    let a = at as usize;
    Some(match ty {
        MemTy::I8 => *image.get(a)? as i8 as i64 as u64,
        MemTy::U8 => *image.get(a)? as u64,
        MemTy::I16 => i16::from_le_bytes(bytes(image, a)?) as i64 as u64,
        MemTy::U16 => u16::from_le_bytes(bytes(image, a)?) as u64,
        MemTy::I32 => i32::from_le_bytes(bytes(image, a)?) as i64 as u64,
        MemTy::U32 | MemTy::F32 => u32::from_le_bytes(bytes(image, a)?) as u64,
        MemTy::I64 | MemTy::F64 => u64::from_le_bytes(bytes(image, a)?),
    })
}

/// Writes the low `ty.size()` bytes of `v` at `at`.
#[inline]
pub fn store(image: &mut [u8], at: u32, ty: MemTy, v: u64) -> Option<()> {
    let a = at as usize;
    // One fixed-size write per width: a length known at compile time is a
    // single move, where a slice copy of `ty.size()` bytes calls memcpy.
    match ty.size() {
        1 => *image.get_mut(a)? = v as u8,
        2 => put(image, a, (v as u16).to_le_bytes())?,
        4 => put(image, a, (v as u32).to_le_bytes())?,
        _ => put(image, a, v.to_le_bytes())?,
    }
    Some(())
}

#[inline]
fn put<const N: usize>(image: &mut [u8], a: usize, b: [u8; N]) -> Option<()> {
    let dst: &mut [u8; N] = image.get_mut(a..a.checked_add(N)?)?.try_into().ok()?;
    *dst = b;
    Some(())
}

#[inline]
fn bytes<const N: usize>(image: &[u8], a: usize) -> Option<[u8; N]> {
    image.get(a..a.checked_add(N)?)?.try_into().ok()
}

/// The characters of the string buffer at `at` (`automat_ir::strbuf`:
/// length, then units). The length is clamped to what the image holds.
pub fn read_str(image: &[u8], at: u32) -> Vec<u8> {
    let len = strbuf::len(image, at).unwrap_or(0) as usize;
    let start = at as usize + strbuf::LEN_BYTES as usize;
    let end = (start + len).min(image.len());
    image
        .get(start..end)
        .map(<[u8]>::to_vec)
        .unwrap_or_default()
}

pub fn read_wstr(image: &[u8], at: u32) -> Vec<u16> {
    let len = strbuf::len(image, at).unwrap_or(0);
    (0..len)
        .map_while(|i| {
            let a = at.checked_add(strbuf::LEN_BYTES + 2 * i)?;
            load(image, a, MemTy::U16).map(|u| u as u16)
        })
        .collect()
}

/// Stores `s` truncated to `cap` characters.
pub fn write_str(image: &mut [u8], at: u32, cap: u32, s: &[u8]) -> Option<()> {
    let n = s.len().min(cap.min(strbuf::MAX_LEN) as usize);
    strbuf::set_len(image, at, n as u32)?;
    let start = at as usize + strbuf::LEN_BYTES as usize;
    image
        .get_mut(start..start + n)?
        .copy_from_slice(s.get(..n)?);
    Some(())
}

pub fn write_wstr(image: &mut [u8], at: u32, cap: u32, s: &[u16]) -> Option<()> {
    let n = s.len().min(cap.min(strbuf::MAX_LEN) as usize);
    strbuf::set_len(image, at, n as u32)?;
    for (i, u) in s.iter().take(n).enumerate() {
        store(
            image,
            at + strbuf::LEN_BYTES + 2 * i as u32,
            MemTy::U16,
            *u as u64,
        )?;
    }
    Some(())
}
