//! MAX, MIN, LIMIT, SEL, MUX.

use crate::error::{ErrorKind, IecError};

/// MAX of two: `a` unless `b` is strictly greater.
pub fn max<T: PartialOrd + Copy>(a: T, b: T) -> T {
    if b > a {
        b
    } else {
        a
    }
}

/// MIN of two: `a` unless `b` is strictly smaller.
pub fn min<T: PartialOrd + Copy>(a: T, b: T) -> T {
    if b < a {
        b
    } else {
        a
    }
}

/// MAX of any number of inputs; `None` when there are none.
pub fn max_of<T: PartialOrd + Copy>(inputs: &[T]) -> Option<T> {
    let (first, rest) = inputs.split_first()?;
    Some(rest.iter().fold(*first, |m, &x| max(m, x)))
}

/// MIN of any number of inputs; `None` when there are none.
pub fn min_of<T: PartialOrd + Copy>(inputs: &[T]) -> Option<T> {
    let (first, rest) = inputs.split_first()?;
    Some(rest.iter().fold(*first, |m, &x| min(m, x)))
}

/// LIMIT(MN, IN, MX) = MIN(MAX(IN, MN), MX).
pub fn limit<T: PartialOrd + Copy>(mn: T, input: T, mx: T) -> T {
    min(max(input, mn), mx)
}

/// SEL(G, IN0, IN1).
pub fn sel<T>(g: bool, in0: T, in1: T) -> T {
    if g {
        in1
    } else {
        in0
    }
}

/// MUX(K, IN0, IN1, ...): input number `k` (0-based).
pub fn mux<T: Clone>(k: i64, inputs: &[T]) -> Result<T, IecError> {
    usize::try_from(k)
        .ok()
        .and_then(|i| inputs.get(i))
        .cloned()
        .ok_or_else(|| {
            IecError::new(
                ErrorKind::SelectorRange,
                format!(
                    "MUX: K = {k} selects no input (there are {} inputs, K must be in 0..={})",
                    inputs.len(),
                    inputs.len() as i128 - 1
                ),
            )
        })
}
