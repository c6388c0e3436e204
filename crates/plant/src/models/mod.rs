//! The model of every process of the sources, one file each, and the
//! registry the project loader looks names up in.

use crate::Plant;

pub mod containers;
pub mod crane;
pub mod dosing;
pub mod oscillating;
pub mod pneumatic;

/// Names of every model, for messages and listings.
pub const NAMES: &[&str] = &["crane", "dosing", "containers", "oscillating"];

/// A new model in its initial state, by the name used in project files.
pub fn by_name(name: &str) -> Option<Box<dyn Plant>> {
    Some(match name {
        "crane" => Box::new(crane::Crane::new()),
        "dosing" => Box::new(dosing::Dosing::new()),
        "containers" => Box::new(containers::Containers::new()),
        "oscillating" => Box::new(oscillating::Oscillating::new()),
        _ => return None,
    })
}
