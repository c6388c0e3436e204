//! Scenarios: files a user writes to drive a project's plant and check
//! what the controller does, in virtual time.

pub mod ast;
pub mod check;
pub mod conformance;
pub mod eval;
mod lex;
pub mod parse;
pub mod run;

pub use check::NoPlant;
pub use parse::parse;
pub use run::{describe, prepare, run, run_on, Failure, Judge, Outcome, Prepared};
