//! The interface between the runtime and a backend (the interpreter now,
//! native code later): the runtime only needs the program's layout, the
//! image and a way to run one program instance at a given PLC time.

use automat_ir::{Fault, Interrupt, Program, ProgramInstance};

/// A backend executing a linked [`Program`] over its memory image.
pub trait Executor {
    fn program(&self) -> &Program;
    fn image(&self) -> &[u8];
    fn image_mut(&mut self) -> &mut [u8];
    /// Resets the image to the program's initial image.
    fn cold_start(&mut self);
    /// Runs one program instance once at PLC time `now_ns`. On a fault the
    /// image is left as it was at the fault; the runtime applies the safe
    /// state.
    fn run_program(&mut self, inst: &ProgramInstance, now_ns: i64) -> Result<(), Fault>;
    /// The backend's interrupt flag: once raised, the run in progress
    /// faults at its next poll (inside loops too) with the message
    /// [`automat_ir::interrupt::INTERRUPTED`]. The runtime's watchdog
    /// raises it; a wrapper returns the flag of the backend it wraps.
    fn interrupt(&self) -> Interrupt;
}
