//! IEC 61131-3 value semantics as pure functions on plain Rust values.
//!
//! This crate is the reference for everything the standard (or
//! `docs/semantics.md`) defines about values independently of how code runs:
//! the elementary types, conversions, integer and real arithmetic, strings,
//! time and date arithmetic, and the printed form of values. The engine and
//! the tools call it; it knows nothing of ASTs, memory images or I/O, has no
//! dependencies, and never panics on any input: failures are [`IecError`]
//! values.
//!
//! Modules, each with its rules in its own documentation:
//! - [`elementary`]: the [`Elementary`] types, names, widths, categories.
//! - [`value`]: [`Value`], the representation of one value of any of them.
//! - [`convert`](mod@convert): `*_TO_*`, `TRUNC`, BCD.
//! - [`arith`]: DIV/MOD, wrapping, EXPT, shifts and rotations, selection.
//! - [`strings`]: LEN, LEFT, RIGHT, MID, CONCAT, INSERT, DELETE, REPLACE,
//!   FIND, comparison, STRING(n) truncation.
//! - [`time`]: calendar, DAY_OF_WEEK, time and date arithmetic, CONCAT_* and
//!   SPLIT_*.
//! - [`format`](mod@format): the printed form (`automat run --print`) and
//!   [`parse_literal`], its inverse.
//!
//! ```
//! use automat_iec::{convert, format_value, parse_literal, Elementary as E, Value};
//!
//! // REAL_TO_INT rounds halves to even; INT_TO_USINT wraps.
//! assert_eq!(convert(&Value::real(2.5, E::Real), E::Int), Ok(Value::Int(2, E::Int)));
//! assert_eq!(convert(&Value::Int(300, E::Int), E::Usint), Ok(Value::Int(44, E::Usint)));
//! // TIME_TO_DINT counts milliseconds.
//! assert_eq!(convert(&Value::time(1_000_000_000), E::Dint), Ok(Value::Int(1000, E::Dint)));
//! // Printing and reading back.
//! assert_eq!(format_value(&Value::real(0.1, E::Real)), "0.1");
//! assert_eq!(format_value(&Value::time(1_500_000_000)), "T#1s500ms");
//! assert_eq!(parse_literal("T#1s500ms", E::Time), Ok(Value::time(1_500_000_000)));
//! ```

pub mod arith;
pub mod convert;
pub mod elementary;
pub mod error;
pub mod format;
pub mod num;
pub mod strings;
pub mod time;
pub mod value;

pub use convert::{convert, is_convertible, trunc};
pub use elementary::Elementary;
pub use error::{ErrorKind, IecError};
pub use format::{format_value, parse_literal};
pub use num::PlcInt;
pub use value::Value;
