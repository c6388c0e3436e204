//! The instruction set (placeholder: defined by the engine work).

/// The code of one POU.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Func {
    pub name: String,
}
