//! The scan-cycle runtime of automat: everything between a linked
//! [`automat_ir::Program`] executed by a backend and the outside world.
//!
//! One scan (see [`scan`]): copy the inputs into the %I area, run the tasks
//! due at this instant (higher priority first, ties in declaration order;
//! event tasks on the rising edge of their BOOL), copy the %Q area to the
//! outputs. A fault or a stop request leaves the PLC in its safe state
//! ([`safe`]: the %Q area, program outputs and plant-bound places at their
//! safe values).
//!
//! The scan logic does no I/O: the clock ([`clock::Monotonic`]), inputs and
//! outputs ([`io`]), the observer of each scan (tracing) and the stop request
//! are passed in, so tests drive it with fakes and the CLI with the system
//! clock, files and Ctrl-C.
//!
//! Modules:
//! - [`executor`]: the [`Executor`] trait a backend implements.
//! - [`schedule`]: which tasks run when (intervals, GCD base tick, events).
//! - [`clock`]: virtual and real time, the monotonic clock.
//! - [`scan`]: the scan loop, stop conditions, faults, statistics.
//! - [`retain`]: the RETAIN file (atomic durable write, header, CRC32,
//!   value checks on load, the keeper saving end-of-scan snapshots).
//! - [`safe`]: the safe state of every output.
//! - [`path`]: `inst.fb.Q`, `arr[2, 1].x`, `%QX0.1` → a place in the image.
//! - [`value`]: reading a value at such a place.
//! - [`trace`]: one CSV row per scan.
//! - [`timearg`]: `10ms` / `T#10ms` command-line durations.
//! - [`watchdog`]: the watchdog in wall time (a timer thread raising the
//!   backend's interrupt flag); the one part of the loop that reads a
//!   clock of its own, because a virtual-clock run needs a wall-time limit.

pub mod clock;
mod crc;
mod engine;
pub mod executor;
pub mod io;
pub mod path;
pub mod realtime;
pub mod retain;
pub mod safe;
pub mod scan;
pub mod schedule;
pub mod slc_place;
pub mod stats;
pub mod timearg;
pub mod trace;
pub mod value;
pub mod watchdog;

#[cfg(test)]
mod testutil;

pub use clock::{ClockMode, Monotonic, SystemClock};
pub use executor::Executor;
pub use path::{resolve, resolve_access, Access, Place, PlaceType};
pub use safe::SafeState;
pub use scan::{run, run_safe, Limit, RunConfig, RunEnd, RunReport, ScanObserver};
pub use slc_place::{locate, Locator};
pub use stats::Stats;
