//! The model of every process of the sources, one file each, and the
//! registry the project loader looks names up in.

use crate::Plant;

/// Names of every model, for messages and listings.
pub const NAMES: &[&str] = &[];

/// A new model in its initial state, by the name used in project files.
pub fn by_name(name: &str) -> Option<Box<dyn Plant>> {
    let _ = name;
    None
}
