//! Number-to-number conversions: integer wrap, real rounding, typed helpers.

use crate::elementary::Elementary;
use crate::num::PlcInt;

/// `v` wrapped into integer, bit-string or character type `ty` by two's
/// complement: the low bits of the type's width are kept (300 → USINT 44,
/// 128 → SINT −128, −1 → WORD 65535). Other types return `v` unchanged.
pub fn wrap_int(v: i128, ty: Elementary) -> i128 {
    if !(ty.is_integral() || ty.is_char()) {
        return v;
    }
    let Some(bits) = ty.bit_width() else {
        return v;
    };
    let shift = 128 - bits;
    if ty.is_signed_int() {
        // Move the type's sign bit to bit 127, then shift back arithmetically.
        (v << shift) >> shift
    } else {
        v & ((1i128 << bits) - 1)
    }
}

/// A real converted to integer type `ty`: rounded to nearest with halves to
/// even (or truncated toward zero when `truncate`), saturated at the type's
/// range; NaN gives 0. A `ty` without an integer range gives 0.
pub fn real_to_int(x: f64, ty: Elementary, truncate: bool) -> i128 {
    let Some((lo, hi)) = ty.int_range() else {
        return 0;
    };
    if x.is_nan() {
        return 0;
    }
    let whole = if truncate {
        x.trunc()
    } else {
        x.round_ties_even()
    };
    // `as i128` saturates (±inf included); the clamp narrows to the type.
    (whole as i128).clamp(lo, hi)
}

/// An integer as REAL (`ty` = REAL, one rounding straight to `f32`) or
/// LREAL (any other `ty`), rounded to nearest, halves to even.
pub fn int_to_real(v: i128, ty: Elementary) -> f64 {
    if ty == Elementary::Real {
        f64::from(v as f32)
    } else {
        v as f64
    }
}

/// REAL/LREAL → integer type `T`, halves to even: `round_to::<i16>(2.5)` = 2.
pub fn round_to<T: PlcInt>(x: f64) -> T {
    T::saturate_f64(x.round_ties_even())
}

/// TRUNC: REAL/LREAL → integer type `T` toward zero, saturating, NaN → 0.
pub fn trunc_to<T: PlcInt>(x: f64) -> T {
    T::saturate_f64(x)
}

/// Integer or bit string → another: two's-complement wrap.
pub fn int_to<S: PlcInt, T: PlcInt>(v: S) -> T {
    T::wrap_i128(v.to_i128())
}

/// Integer → REAL, rounded to nearest `f32`.
pub fn int_to_f32<T: PlcInt>(v: T) -> f32 {
    v.to_i128() as f32
}

/// Integer → LREAL, rounded to nearest `f64` (exact below 2^53).
pub fn int_to_f64<T: PlcInt>(v: T) -> f64 {
    v.to_i128() as f64
}

/// LREAL → REAL: IEEE round to nearest even; beyond REAL's range gives ±inf.
pub fn lreal_to_real(x: f64) -> f32 {
    x as f32
}

/// BOOL → number: 0 or 1.
pub fn bool_to<T: PlcInt>(b: bool) -> T {
    T::wrap_i128(i128::from(b))
}

/// Number → BOOL: TRUE when not zero (NaN is not zero: TRUE).
pub fn real_to_bool(x: f64) -> bool {
    x != 0.0
}
