//! Binary-coded decimal: `BCD_TO_*` / `*_BCD_TO_*` and `*_TO_BCD` /
//! `*_TO_BCD_*`. A bit string of width w holds w/4 decimal digits, one a
//! nibble, most significant first: WORD 16#1234 is 1234.

use crate::elementary::Elementary;
use crate::error::{ErrorKind, IecError};

/// The number that bit pattern `bits` encodes in BCD, looking at the low
/// `width` bits (8, 16, 32 or 64). A nibble above 9 is an error naming it.
pub fn bcd_decode(bits: u64, width: u32) -> Result<u64, IecError> {
    let width = width.clamp(4, 64);
    let mut value: u64 = 0;
    for i in (0..width / 4).rev() {
        let nibble = (bits >> (i * 4)) & 0xF;
        if nibble > 9 {
            return Err(IecError::new(
                ErrorKind::Bcd,
                format!(
                    "16#{bits:X} is not a BCD number: digit {} holds {nibble:X}, above 9",
                    width / 4 - i
                ),
            ));
        }
        // At most 16 digits: below 10^16, no overflow.
        value = value * 10 + nibble;
    }
    Ok(value)
}

/// `v` encoded in BCD in `width` bits (8, 16, 32 or 64). Negative values
/// and values with more than width/4 digits are errors.
pub fn bcd_encode(v: i128, width: u32) -> Result<u64, IecError> {
    let width = width.clamp(4, 64);
    let digits = width / 4;
    let limit = 10i128.pow(digits);
    if v < 0 || v >= limit {
        return Err(IecError::new(
            ErrorKind::Bcd,
            format!(
                "{v} cannot be written in {digits} BCD digits (0..={})",
                limit - 1
            ),
        ));
    }
    let mut rest = v as u64;
    let mut bits: u64 = 0;
    for i in 0..digits {
        bits |= (rest % 10) << (i * 4);
        rest /= 10;
    }
    Ok(bits)
}

/// `BCD_TO_<to>` of a bit-string value of type `from` (BYTE..LWORD) into
/// integer type `to` (the decoded number wraps like any integer conversion).
pub fn bcd_to_int(bits: u64, from: Elementary, to: Elementary) -> Result<i128, IecError> {
    let width = from.bit_width().unwrap_or(64);
    bcd_decode(bits, width)
        .map(|v| super::wrap_int(i128::from(v), to))
        .map_err(|e| named(e, &format!("{from}_BCD_TO_{to}")))
}

/// `<from>_TO_BCD_<to>`: integer `v` as BCD in bit string type `to`.
pub fn int_to_bcd(v: i128, from: Elementary, to: Elementary) -> Result<u64, IecError> {
    let width = to.bit_width().unwrap_or(64);
    bcd_encode(v, width).map_err(|e| named(e, &format!("{from}_TO_BCD_{to}")))
}

fn named(e: IecError, function: &str) -> IecError {
    IecError::new(e.kind, format!("{function}: {}", e.message))
}
