//! Reading the value at a [`Place`] of the image, and its printed form
//! (`automat run --print`, traces): the layout is the IR's (little-endian;
//! BOOL a byte 0/1 or one bit; times i64 ns, dates i64 days; STRING[n] a
//! length field ([`string_len`]) then n bytes; WSTRING[n] the length field
//! then n u16).

use crate::path::{Place, PlaceType};
use automat_iec::{format_value, Elementary as E, Value};
use automat_ir::strbuf;

fn bytes<const N: usize>(image: &[u8], offset: u32) -> Option<[u8; N]> {
    let start = usize::try_from(offset).ok()?;
    image.get(start..start.checked_add(N)?)?.try_into().ok()
}

fn int_at(image: &[u8], offset: u32, ty: E) -> Option<i128> {
    Some(match ty {
        E::Sint => i8::from_le_bytes(bytes(image, offset)?).into(),
        E::Int => i16::from_le_bytes(bytes(image, offset)?).into(),
        E::Dint => i32::from_le_bytes(bytes(image, offset)?).into(),
        E::Lint => i64::from_le_bytes(bytes(image, offset)?).into(),
        E::Usint | E::Byte | E::Char => u8::from_le_bytes(bytes(image, offset)?).into(),
        E::Uint | E::Word | E::Wchar => u16::from_le_bytes(bytes(image, offset)?).into(),
        E::Udint | E::Dword => u32::from_le_bytes(bytes(image, offset)?).into(),
        E::Ulint | E::Lword => u64::from_le_bytes(bytes(image, offset)?).into(),
        _ => i64::from_le_bytes(bytes(image, offset)?).into(),
    })
}

/// The value of an elementary type at `offset` (`bit` for a packed BOOL);
/// `None` when it is not inside the image.
pub fn read_elementary(image: &[u8], offset: u32, bit: Option<u8>, ty: E) -> Option<Value> {
    let i64_at = || bytes::<8>(image, offset).map(i64::from_le_bytes);
    Some(match ty {
        E::Bool => {
            let [b] = bytes::<1>(image, offset)?;
            Value::Bool(match bit {
                Some(k) => k < 8 && b >> k & 1 != 0,
                None => b != 0,
            })
        }
        E::Real => Value::Real(f32::from_le_bytes(bytes(image, offset)?).into(), E::Real),
        E::Lreal => Value::Real(f64::from_le_bytes(bytes(image, offset)?), E::Lreal),
        E::Time | E::Ltime => Value::Duration(i64_at()?, ty),
        E::Date | E::Ldate => Value::Date(i64_at()?, ty),
        E::Tod | E::Ltod => Value::Tod(i64_at()?, ty),
        E::Dt | E::Ldt => Value::Dt(i64_at()?, ty),
        E::Char => Value::Char(bytes::<1>(image, offset)?[0]),
        E::Wchar => Value::WChar(u16::from_le_bytes(bytes(image, offset)?)),
        E::String => return read_string(image, offset, 80),
        E::Wstring => return read_wstring(image, offset, 80),
        _ => Value::Int(int_at(image, offset, ty)?, ty),
    })
}

/// Bytes of the length field in front of a STRING's or WSTRING's
/// characters (the field itself is `automat_ir::strbuf`'s).
pub const STRING_LEN_BYTES: u32 = strbuf::LEN_BYTES;

/// The stored length (in characters) of the STRING or WSTRING at `offset`,
/// through `automat_ir::strbuf`, the one place that knows the field's
/// width. `None` when it is not inside the image.
pub fn string_len(image: &[u8], offset: u32) -> Option<u32> {
    strbuf::len(image, offset)
}

/// Writes the length field of the STRING or WSTRING at `offset`; `None`
/// when it is not inside the image or `len` is beyond the longest string.
pub fn put_string_len(image: &mut [u8], offset: u32, len: u32) -> Option<()> {
    if len > strbuf::MAX_LEN {
        return None;
    }
    strbuf::set_len(image, offset, len)
}

/// Where the characters of the string at `offset` start.
fn chars_start(offset: u32) -> Option<usize> {
    usize::try_from(offset.checked_add(STRING_LEN_BYTES)?).ok()
}

/// A STRING[cap]: the stored length is clamped to the capacity, so a
/// damaged length never reads beyond the variable.
fn read_string(image: &[u8], offset: u32, cap: u32) -> Option<Value> {
    let len = usize::try_from(string_len(image, offset)?.min(cap)).ok()?;
    let start = chars_start(offset)?;
    let data = image.get(start..start.checked_add(len)?)?;
    Some(Value::Str(data.to_vec()))
}

fn read_wstring(image: &[u8], offset: u32, cap: u32) -> Option<Value> {
    let len = usize::try_from(string_len(image, offset)?.min(cap)).ok()?;
    let start = chars_start(offset)?;
    let data = image.get(start..start.checked_add(len.checked_mul(2)?)?)?;
    Some(Value::WStr(
        data.chunks_exact(2)
            .map(|c| u16::from_le_bytes([c[0], c[1]]))
            .collect(),
    ))
}

/// The value at `place`; an enumeration reads as its base integer.
pub fn read(image: &[u8], place: &Place) -> Option<Value> {
    match &place.ty {
        PlaceType::Elementary(e) => read_elementary(image, place.offset, place.bit, *e),
        PlaceType::Enum { base, .. } => read_elementary(image, place.offset, None, *base),
        PlaceType::String { cap } => read_string(image, place.offset, *cap),
        PlaceType::WString { cap } => read_wstring(image, place.offset, *cap),
    }
}

/// The printed form of the value at `place`: [`format_value`]'s IEC
/// literal; an enumeration value as `Type#Name` (its number when no name
/// has it); `?` when the place is not inside the image.
pub fn format(image: &[u8], place: &Place) -> String {
    let Some(v) = read(image, place) else {
        return "?".to_string();
    };
    if let (true, Value::Bool(b)) = (place.slc_bit, &v) {
        return if *b { "1" } else { "0" }.to_string();
    }
    if let (PlaceType::Enum { name, values, .. }, Value::Int(n, _)) = (&place.ty, &v) {
        if let Some((vn, _)) = values.iter().find(|(_, x)| i128::from(*x) == *n) {
            return format!("{name}#{vn}");
        }
    }
    format_value(&v)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn place(offset: u32, bit: Option<u8>, ty: PlaceType) -> Place {
        Place {
            offset,
            bit,
            ty,
            slc_bit: false,
        }
    }

    #[test]
    fn elementary_values_little_endian() {
        let mut img = vec![0u8; 64];
        img[0] = 0b0000_0100;
        img[1..3].copy_from_slice(&(-2i16).to_le_bytes());
        img[4..8].copy_from_slice(&3.5f32.to_le_bytes());
        img[8..16].copy_from_slice(&1_500_000_000i64.to_le_bytes());
        img[16..24].copy_from_slice(&0.1f64.to_le_bytes());
        img[24] = 0xFF;
        let el = |o, b, e| format(&img, &place(o, b, PlaceType::Elementary(e)));
        assert_eq!(el(0, Some(2), E::Bool), "TRUE");
        assert_eq!(el(0, Some(1), E::Bool), "FALSE");
        assert_eq!(el(0, None, E::Bool), "TRUE");
        assert_eq!(el(1, None, E::Int), "-2");
        assert_eq!(el(1, None, E::Word), "65534");
        assert_eq!(el(4, None, E::Real), "3.5");
        assert_eq!(el(8, None, E::Time), "T#1s500ms");
        assert_eq!(el(16, None, E::Lreal), "0.1");
        assert_eq!(el(24, None, E::Sint), "-1");
        assert_eq!(el(24, None, E::Byte), "255");
        assert_eq!(el(60, None, E::Lint), "?");
    }

    #[test]
    fn strings_clamp_their_length_to_the_capacity() {
        let mut img = vec![0u8; 16];
        img[0..2].copy_from_slice(&3u16.to_le_bytes());
        img[2..5].copy_from_slice(b"a'b");
        assert_eq!(
            format(&img, &place(0, None, PlaceType::String { cap: 5 })),
            "'a$'b'"
        );
        assert_eq!(
            format(&img, &place(0, None, PlaceType::String { cap: 2 })),
            "'a$''"
        );
        img[0..2].copy_from_slice(&1000u16.to_le_bytes());
        assert_eq!(
            format(&img, &place(0, None, PlaceType::String { cap: 4 })),
            "'a$'b$00'"
        );
        let mut w = vec![0u8; 8];
        w[0..2].copy_from_slice(&2u16.to_le_bytes());
        w[2..4].copy_from_slice(&u16::from(b'h').to_le_bytes());
        w[4..6].copy_from_slice(&u16::from(b'i').to_le_bytes());
        assert_eq!(
            format(&w, &place(0, None, PlaceType::WString { cap: 3 })),
            "\"hi\""
        );
    }

    #[test]
    fn enums_print_their_value_name() {
        let ty = PlaceType::Enum {
            name: "COLOR".into(),
            base: E::Int,
            values: vec![("RED".into(), 0), ("GREEN".into(), 1)],
        };
        let img = [1u8, 0, 7, 0];
        assert_eq!(format(&img, &place(0, None, ty.clone())), "COLOR#GREEN");
        assert_eq!(format(&img, &place(2, None, ty)), "7");
    }
}
