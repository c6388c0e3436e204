//! SHL, SHR, ROL, ROR and NOT on 8/16/32/64-bit bit strings.

use crate::num::PlcInt;

/// The count as an unsigned shift distance (negative counts are huge).
fn distance(n: i64) -> u64 {
    n as u64
}

/// SHL: shift left by `n`, zero fill; `n` ≥ width gives 0.
pub fn shl<T: PlcInt>(v: T, n: i64) -> T {
    let n = distance(n);
    if n >= u64::from(T::BITS) {
        return T::from_bits(0);
    }
    T::from_bits(v.to_bits() << n)
}

/// SHR: logical shift right by `n`, zero fill; `n` ≥ width gives 0.
pub fn shr<T: PlcInt>(v: T, n: i64) -> T {
    let n = distance(n);
    if n >= u64::from(T::BITS) {
        return T::from_bits(0);
    }
    T::from_bits(v.to_bits() >> n)
}

/// ROL: rotate left by `n` modulo the width.
pub fn rol<T: PlcInt>(v: T, n: i64) -> T {
    let w = T::BITS;
    let r = (distance(n) % u64::from(w)) as u32;
    if r == 0 {
        return v;
    }
    let bits = v.to_bits();
    // to_bits is zero above the width, so the right part needs no mask.
    T::from_bits((bits << r) | (bits >> (w - r)))
}

/// ROR: rotate right by `n` modulo the width.
pub fn ror<T: PlcInt>(v: T, n: i64) -> T {
    let w = T::BITS;
    let r = (distance(n) % u64::from(w)) as u32;
    rol(v, i64::from(w - r))
}

/// NOT: every bit of the width inverted.
pub fn not<T: PlcInt>(v: T) -> T {
    T::from_bits(!v.to_bits())
}
