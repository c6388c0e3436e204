//! The graphical network model of LD and FBD bodies, and its lowering.
//!
//! One model for both languages (and for the Allen-Bradley ladder front end
//! to come): a [`model::Network`] is a list of elements (rails, contacts,
//! coils, blocks, variables, labels, jumps, returns, connectors) whose input
//! pins name the output pins they are wired to. `read.rs` builds it from
//! TC6 XML; `lower.rs` writes it as Structured Text in execution order.

pub mod lower;
pub mod model;
pub mod read;
