//! Arithmetic, bit-shift and selection functions on plain Rust values.
//!
//! Rules:
//! - **Integer `+`, `-`, `*`, unary `-`, ABS** wrap on overflow (two's
//!   complement, as CODESYS and TwinCAT): INT 32767 + 1 = −32768,
//!   −(−128) = −128 for SINT, ABS(−32768) = −32768 for INT.
//! - **Integer `/`** truncates toward zero (7 / −2 = −3); **MOD** has the
//!   sign of the dividend (−7 MOD 2 = −1, 7 MOD −2 = 1). Division or MOD by
//!   zero is an [`ErrorKind::DivisionByZero`] error naming the function, never
//!   a panic; MIN / −1 wraps to MIN and MIN MOD −1 is 0.
//! - **Real `/`** follows IEEE 754: x / 0.0 is ±inf, 0.0 / 0.0 is NaN.
//! - **EXPT (`**`)** on REAL/LREAL follows IEEE `pow` (0.0 ** −1 = inf,
//!   (−8.0) ** (1/3) = NaN, x ** 0 = 1 even for NaN). REAL is computed in
//!   `f32`. On integers (a common extension): repeated wrapping
//!   multiplication; a negative exponent gives 1 for base 1, ±1 for base −1,
//!   0 for |base| > 1 and an error for base 0.
//! - **SHL/SHR** move bits within the width (8/16/32/64); a count ≥ the
//!   width gives 0. **ROL/ROR** rotate by the count modulo the width. A
//!   negative count is read as an unsigned number (two's complement), so it
//!   shifts everything out and rotates by `width − |n| mod width`. SHR is
//!   logical (zero fill) on the bit pattern, whatever the type's sign.
//! - **MAX/MIN** keep the first argument unless another is strictly
//!   greater/smaller (a NaN first argument stays, a later NaN is skipped).
//!   **LIMIT(MN, IN, MX)** is MIN(MAX(IN, MN), MX), so MX wins when MN > MX.
//!   **SEL(G, IN0, IN1)** is IN1 when G. **MUX(K, ...)** with K outside
//!   0..count is an [`ErrorKind::SelectorRange`] error.

mod bits;
mod real;
mod select;
#[cfg(test)]
mod tests;

pub use bits::{not, rol, ror, shl, shr};
pub use real::{expt_int, expt_lreal, expt_lreal_int, expt_real, expt_real_int};
pub use select::{limit, max, max_of, min, min_of, mux, sel};

#[cfg(doc)]
use crate::error::ErrorKind;
use crate::error::IecError;
use crate::num::PlcInt;

/// Integer `+`, wrapping.
pub fn add<T: PlcInt>(a: T, b: T) -> T {
    a.wrapping_add(b)
}

/// Integer `-`, wrapping.
pub fn sub<T: PlcInt>(a: T, b: T) -> T {
    a.wrapping_sub(b)
}

/// Integer `*`, wrapping.
pub fn mul<T: PlcInt>(a: T, b: T) -> T {
    a.wrapping_mul(b)
}

/// Integer `/` (DIV): truncates toward zero; by zero is an error.
///
/// ```
/// use automat_iec::arith::{div, modulo};
/// assert_eq!(div(-7i16, 2), Ok(-3));
/// assert_eq!(modulo(-7i16, 2), Ok(-1));
/// assert!(div(1u8, 0).is_err());
/// ```
pub fn div<T: PlcInt>(a: T, b: T) -> Result<T, IecError> {
    if b == T::ZERO {
        return Err(IecError::div_zero("DIV"));
    }
    Ok(a.wrapping_div(b))
}

/// MOD: remainder with the dividend's sign; by zero is an error.
pub fn modulo<T: PlcInt>(a: T, b: T) -> Result<T, IecError> {
    if b == T::ZERO {
        return Err(IecError::div_zero("MOD"));
    }
    Ok(a.wrapping_rem(b))
}

/// Unary `-` (NEG), wrapping: −MIN = MIN.
pub fn neg<T: PlcInt>(a: T) -> T {
    a.wrapping_neg()
}

/// ABS, wrapping: ABS(MIN) = MIN.
pub fn abs<T: PlcInt>(a: T) -> T {
    a.wrapping_abs()
}
