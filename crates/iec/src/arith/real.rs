//! EXPT (`**`).

use crate::error::{ErrorKind, IecError};
use crate::num::PlcInt;

/// LREAL ** LREAL (IEEE `pow`).
pub fn expt_lreal(base: f64, exp: f64) -> f64 {
    base.powf(exp)
}

/// REAL ** REAL, computed in `f32`.
pub fn expt_real(base: f32, exp: f32) -> f32 {
    base.powf(exp)
}

/// LREAL ** integer.
pub fn expt_lreal_int(base: f64, exp: i64) -> f64 {
    // powi takes an i32; beyond it every finite base ≠ ±1 over- or
    // underflows anyway, and powf agrees exactly at integer exponents.
    match i32::try_from(exp) {
        Ok(e) => base.powi(e),
        Err(_) => base.powf(exp as f64),
    }
}

/// REAL ** integer, computed in `f32`.
pub fn expt_real_int(base: f32, exp: i64) -> f32 {
    match i32::try_from(exp) {
        Ok(e) => base.powi(e),
        Err(_) => base.powf(exp as f32),
    }
}

/// Integer ** integer with wrapping multiplication (see the module rules
/// for negative exponents).
pub fn expt_int<T: PlcInt>(base: T, exp: i64) -> Result<T, IecError> {
    let one = T::wrap_i128(1);
    if exp < 0 {
        return match base.to_i128() {
            0 => Err(IecError::new(
                ErrorKind::DivisionByZero,
                "EXPT: 0 raised to a negative power",
            )),
            1 => Ok(one),
            -1 => Ok(if exp % 2 == 0 { one } else { base }),
            _ => Ok(T::ZERO),
        };
    }
    // Square-and-multiply: at most 63 rounds.
    let mut result = one;
    let mut square = base;
    let mut e = exp as u64;
    while e > 0 {
        if e & 1 == 1 {
            result = result.wrapping_mul(square);
        }
        square = square.wrapping_mul(square);
        e >>= 1;
    }
    Ok(result)
}
