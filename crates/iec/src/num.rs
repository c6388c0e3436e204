//! [`PlcInt`]: the Rust integer types that hold IEC integers and bit strings
//! (`i8`..`i64` for SINT..LINT, `u8`..`u64` for USINT..ULINT and
//! BYTE..LWORD), so that the typed helpers in `convert` and `arith` are
//! written once for every width.

use std::fmt::Debug;

/// A fixed-width integer as the engine stores it.
pub trait PlcInt: Copy + Ord + Debug + 'static {
    /// Width in bits.
    const BITS: u32;
    /// Whether the type is two's-complement signed.
    const SIGNED: bool;
    const ZERO: Self;

    /// The exact value.
    fn to_i128(self) -> i128;
    /// The low `BITS` bits of `v` (two's-complement wrap).
    fn wrap_i128(v: i128) -> Self;
    /// `v` rounded toward zero; out of range saturates, NaN gives 0.
    fn saturate_f64(v: f64) -> Self;
    /// The bit pattern, zero-extended to 64 bits.
    fn to_bits(self) -> u64;
    /// The low `BITS` bits of `bits`.
    fn from_bits(bits: u64) -> Self;

    fn wrapping_add(self, rhs: Self) -> Self;
    fn wrapping_sub(self, rhs: Self) -> Self;
    fn wrapping_mul(self, rhs: Self) -> Self;
    /// Truncating division; `MIN / -1` wraps to `MIN`. `rhs` must not be 0.
    fn wrapping_div(self, rhs: Self) -> Self;
    /// Remainder with the dividend's sign; `MIN % -1` is 0. `rhs` must not be 0.
    fn wrapping_rem(self, rhs: Self) -> Self;
    fn wrapping_neg(self) -> Self;
    fn wrapping_abs(self) -> Self;
}

macro_rules! plc_int {
    ($($t:ty, $signed:tt);* $(;)?) => {$(
        impl PlcInt for $t {
            const BITS: u32 = <$t>::BITS;
            const SIGNED: bool = $signed;
            const ZERO: Self = 0;

            fn to_i128(self) -> i128 {
                self as i128
            }
            fn wrap_i128(v: i128) -> Self {
                // `as` between integers keeps the low bits: the wrap we want.
                v as $t
            }
            fn saturate_f64(v: f64) -> Self {
                // Float-to-int `as` truncates, saturates and maps NaN to 0.
                v as $t
            }
            fn to_bits(self) -> u64 {
                // Sign bits above the width are masked off.
                (self as u64) & (u64::MAX >> (64 - <$t>::BITS))
            }
            fn from_bits(bits: u64) -> Self {
                bits as $t
            }
            fn wrapping_add(self, rhs: Self) -> Self {
                <$t>::wrapping_add(self, rhs)
            }
            fn wrapping_sub(self, rhs: Self) -> Self {
                <$t>::wrapping_sub(self, rhs)
            }
            fn wrapping_mul(self, rhs: Self) -> Self {
                <$t>::wrapping_mul(self, rhs)
            }
            fn wrapping_div(self, rhs: Self) -> Self {
                <$t>::checked_div(self, rhs).unwrap_or_else(|| {
                    // Only MIN / -1 (rhs 0 is excluded by the caller): wraps to MIN.
                    <$t>::wrapping_neg(self)
                })
            }
            fn wrapping_rem(self, rhs: Self) -> Self {
                <$t>::checked_rem(self, rhs).unwrap_or(0)
            }
            fn wrapping_neg(self) -> Self {
                <$t>::wrapping_neg(self)
            }
            fn wrapping_abs(self) -> Self {
                plc_int!(@abs $signed, self)
            }
        }
    )*};
    (@abs true, $v:expr) => { $v.wrapping_abs() };
    (@abs false, $v:expr) => { $v };
}

plc_int! {
    i8, true; i16, true; i32, true; i64, true;
    u8, false; u16, false; u32, false; u64, false;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bit_patterns() {
        assert_eq!((-1i8).to_bits(), 0xFF);
        assert_eq!((-2i32).to_bits(), 0xFFFF_FFFE);
        assert_eq!(i16::from_bits(0xFFFF), -1);
        assert_eq!(u8::from_bits(0x1FF), 0xFF);
        assert_eq!(u64::MAX.to_bits(), u64::MAX);
        assert_eq!(i8::wrap_i128(200), -56);
        assert_eq!(u16::wrap_i128(-1), 65535);
    }

    #[test]
    fn wrapping_corner_cases() {
        assert_eq!(PlcInt::wrapping_div(i8::MIN, -1), i8::MIN);
        assert_eq!(PlcInt::wrapping_rem(i64::MIN, -1), 0);
        assert_eq!(PlcInt::wrapping_abs(i16::MIN), i16::MIN);
        assert_eq!(PlcInt::wrapping_abs(200u8), 200);
        assert_eq!(PlcInt::wrapping_neg(5u8), 251);
        assert_eq!(i32::saturate_f64(f64::NAN), 0);
        assert_eq!(u8::saturate_f64(-3.0), 0);
        assert_eq!(i8::saturate_f64(1e9), 127);
    }

    #[test]
    fn widths_and_signs() {
        assert_eq!((i8::BITS, i16::BITS, i32::BITS, i64::BITS), (8, 16, 32, 64));
        const { assert!(<i32 as PlcInt>::SIGNED && !<u32 as PlcInt>::SIGNED) };
        assert_eq!(i64::MIN.to_bits(), 1 << 63);
        assert_eq!((-1i16).to_i128(), -1);
        assert_eq!(u64::MAX.to_i128(), 18446744073709551615);
        assert_eq!(i32::from_bits(0xFFFF_FFFF), -1);
    }
}
