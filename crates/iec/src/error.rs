//! The one error type of this crate.
//!
//! Every fallible function returns `Result<_, IecError>`. An error carries a
//! [`ErrorKind`] (what the engine maps to a runtime fault code) and a message
//! that names the function and the offending argument, ready to show to a
//! user: `MID: P = 0 is out of range 1..=4 for a string of length 3`.
//! Nothing in this crate panics on any input; errors are values.

use std::fmt;

/// What went wrong, without the details (those are in the message).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ErrorKind {
    /// Integer or time division (or MOD) by zero.
    DivisionByZero,
    /// A time or date result that does not fit its representation.
    Overflow,
    /// A string function position or length out of range.
    StringIndex,
    /// A selector (MUX `K`) that picks no input.
    SelectorRange,
    /// A bit string with a nibble above 9 given to a BCD conversion, or a
    /// number too large or negative for a BCD result.
    Bcd,
    /// Text that is not a valid literal of the wanted type.
    Parse,
    /// A value outside the range of the wanted type (text conversions only:
    /// numeric conversions wrap or saturate instead).
    OutOfRange,
    /// A calendar date or time of day that does not exist (month 13,
    /// 2023-02-29, 24:00:00).
    InvalidDate,
    /// A conversion the standard does not define (TIME to DATE, ...).
    NotConvertible,
}

/// An error of an IEC function: a kind and a message for people.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct IecError {
    pub kind: ErrorKind,
    pub message: String,
}

impl IecError {
    pub fn new(kind: ErrorKind, message: impl Into<String>) -> IecError {
        IecError {
            kind,
            message: message.into(),
        }
    }

    pub(crate) fn div_zero(function: &str) -> IecError {
        IecError::new(
            ErrorKind::DivisionByZero,
            format!("{function}: division by zero"),
        )
    }

    pub(crate) fn overflow(function: &str) -> IecError {
        IecError::new(
            ErrorKind::Overflow,
            format!("{function}: the result does not fit in 64-bit nanoseconds"),
        )
    }
}

impl fmt::Display for IecError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for IecError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_is_the_message() {
        let e = IecError::new(ErrorKind::Parse, "`x` is not a valid INT literal");
        assert_eq!(e.to_string(), "`x` is not a valid INT literal");
        assert_eq!(
            IecError::div_zero("DIV").to_string(),
            "DIV: division by zero"
        );
        assert_eq!(
            IecError::overflow("ADD_TIME").to_string(),
            "ADD_TIME: the result does not fit in 64-bit nanoseconds"
        );
    }
}
