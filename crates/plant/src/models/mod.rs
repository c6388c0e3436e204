//! The model of every process of the sources, one file each, and the
//! registry the project loader looks names up in.

use crate::{Dir, Kind, Plant, Quantity, Signal};

pub mod bottling;
pub mod capping;
pub mod carwash;
pub mod containers;
pub mod crane;
pub mod dosing;
pub mod festo;
pub mod oscillating;
pub mod pid_temperature;
pub mod pneumatic;
pub mod sorter;
pub mod tank_temperature;
pub mod trains;

/// Names of every model, for messages and listings.
pub const NAMES: &[&str] = &[
    "crane",
    "dosing",
    "containers",
    "trains",
    "festo",
    "pid-temperature",
    "bottling",
    "oscillating",
    "capping",
    "tank-temperature",
    "carwash",
    "sorter",
];

/// A new model in its initial state, by the name used in project files.
pub fn by_name(name: &str) -> Option<Box<dyn Plant>> {
    Some(match name {
        "crane" => Box::new(crane::Crane::new()),
        "dosing" => Box::new(dosing::Dosing::new()),
        "containers" => Box::new(containers::Containers::new()),
        "trains" => Box::new(trains::Trains::new()),
        "festo" => Box::new(festo::Festo::new()),
        "pid-temperature" => Box::new(pid_temperature::PidTemperature::new()),
        "bottling" => Box::new(bottling::Bottling::new()),
        "oscillating" => Box::new(oscillating::Oscillating::new()),
        "capping" => Box::new(capping::Capping::new()),
        "tank-temperature" => Box::new(tank_temperature::TankTemperature::new()),
        "carwash" => Box::new(carwash::Carwash::new()),
        "sorter" => Box::new(sorter::Sorter::new()),
        _ => return None,
    })
}

/// A BOOL signal of a model's table (most of the sources' I/O).
pub(crate) const fn sig(name: &'static str, dir: Dir, doc: &'static str) -> Signal {
    Signal {
        name,
        dir,
        kind: Kind::Bool,
        doc,
    }
}

/// A quantity of a model's table.
pub(crate) const fn q(name: &'static str, unit: &'static str, doc: &'static str) -> Quantity {
    Quantity { name, unit, doc }
}
