//! The image form of a STRING[n] / WSTRING[n] variable, in one place:
//! a little-endian `u16` length (characters stored), then room for n
//! characters (one byte each, or one UCS-2 `u16` each for WSTRING).
//!
//! Everything that reads or writes a string's length in an image (the
//! interpreter's builtins, which the JIT calls too, the cold-start image,
//! `--print`, traces, retain checks) goes through [`len`] and [`set_len`],
//! so the field's width is decided here. It is 16 bits, and the longest
//! string is [`MAX_LEN`] = 32,767 characters: `LEN` and `FIND` return an
//! INT and positions are INTs, so every length and position of every
//! declarable string is exact (the checker refuses a longer declaration,
//! E072). Both engines share this code, so they agree to the character.

/// Bytes of the length field before the characters.
pub const LEN_BYTES: u32 = 2;

/// The longest STRING/WSTRING (`i16::MAX`: its length is an INT).
pub const MAX_LEN: u32 = i16::MAX as u32;

/// The stored length of the string at `at`; `None` outside the image.
pub fn len(image: &[u8], at: u32) -> Option<u32> {
    let a = usize::try_from(at).ok()?;
    let b: [u8; 2] = image.get(a..a.checked_add(2)?)?.try_into().ok()?;
    Some(u32::from(u16::from_le_bytes(b)))
}

/// Stores the length `n` of the string at `at` (at most [`MAX_LEN`]: no
/// string has more room than that); `None` outside the image.
pub fn set_len(image: &mut [u8], at: u32, n: u32) -> Option<()> {
    let a = usize::try_from(at).ok()?;
    let dst = image.get_mut(a..a.checked_add(2)?)?;
    dst.copy_from_slice(&header(n));
    Some(())
}

/// The length field for `n` characters, as bytes (saturated at what 16
/// bits hold).
pub fn header(n: u32) -> [u8; 2] {
    u16::try_from(n).unwrap_or(u16::MAX).to_le_bytes()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_length_round_trips_up_to_the_largest_string() {
        let mut img = vec![0u8; 8];
        for n in [0, 1, 255, 256, MAX_LEN, u32::from(u16::MAX)] {
            set_len(&mut img, 3, n).unwrap();
            assert_eq!(len(&img, 3), Some(n));
        }
        assert_eq!(header(1 << 16), [0xff, 0xff]);
        assert_eq!(len(&img, 7), None);
        assert_eq!(set_len(&mut img, 7, 1), None);
        assert_eq!(len(&img, u32::MAX), None);
    }
}
