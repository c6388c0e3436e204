//! automat projects: a folder with `automat.toml`, its Structured Text
//! sources and a virtual plant bound to the program.
//!
//! - [`file`]: the project file (`[project]`, `[plant]`, `[plant.params]`,
//!   `[bind]`, `[retain]`, `[safe_state]`, `[tasks.NAME]`) with `file:line:col` diagnostics (E300–E308).
//! - [`folder`]: walking source folders, each file once whatever the
//!   symbolic links.
//! - [`bind`]: signals → PLC variables, checked at load.
//! - [`image`]: plant values in and out of the memory image.
//! - [`st_plant`]: a plant written in ST (`[plant] program = "plant.st"`),
//!   compiled like the controller and run on the plant's clock (E310–E315).
//! - [`sim`]: the coupling of the model to the scan, with overrides
//!   (stuck sensors and actuators, noise) and timed [`sim::Action`]s.
//! - [`exec`]: a backend wrapped so the runtime's scan loop drives the plant.
//! - [`steps`]: the active steps of the program's charts (live view).
//! - [`safe`]: the safe state of a run (outputs, actuator bindings,
//!   `[safe_state]` values).
//! - [`tasks`]: `[tasks.NAME]` settings (the watchdog) applied to the
//!   program's tasks.
//!
//! The contract the plant models follow is in `crates/plant/README.md`.

pub mod bind;
pub mod build;
pub mod charts;
pub mod exec;
pub mod file;
pub mod folder;
pub mod image;
pub mod safe;
pub mod sim;
pub mod st_plant;
pub mod steps;
pub mod tasks;

pub use bind::{bind, Binding};
pub use exec::PlantExec;
pub use file::{
    find_above, load, project_file, PlantSpec, Project, RetainSpec, RuntimeSpec, SafeSpec,
    UserSpec, FILE_NAME,
};
pub use sim::{Action, Sim};
