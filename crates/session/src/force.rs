//! The force table and the executor wrapper that holds forced values.
//!
//! Wrapped *inside* a plant (`PlantExec<Forcing<E>>`) the forces are
//! stored before and after every program instance runs: before, so a
//! forced input beats what the plant or the I/O has just written (both
//! write before the first program of a scan); after, so a forced output or
//! internal variable beats the program's own assignments, and the %Q area
//! written to the outputs, and the actuators the plant reads at the next
//! scan, carry the forced value. Between scans the session stores them
//! once more after applying one-shot writes, so a write never undoes a
//! force, and every snapshot shows the forced values.

use crate::value::Stored;
use automat_ir::{Fault, Program, ProgramInstance};
use automat_runtime::Executor;
use std::cell::RefCell;
use std::rc::Rc;

/// One forced location.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Force {
    /// The path as the client gave it (trimmed), for the list of forces.
    pub path: String,
    /// The value as the client typed it.
    pub text: String,
    pub stored: Stored,
}

/// The forces in the order they were set; one per location.
#[derive(Clone, Debug, Default)]
pub struct ForceTable {
    forces: Vec<Force>,
}

impl ForceTable {
    /// Sets a force, replacing any force of the same location.
    pub fn set(&mut self, force: Force) {
        let key = force.stored.key();
        self.forces.retain(|f| f.stored.key() != key);
        self.forces.push(force);
    }

    /// Releases the force of the location of `stored`; whether there was one.
    pub fn release(&mut self, stored: &Stored) -> bool {
        let before = self.forces.len();
        let key = stored.key();
        self.forces.retain(|f| f.stored.key() != key);
        self.forces.len() != before
    }

    pub fn clear(&mut self) {
        self.forces.clear();
    }

    pub fn apply(&self, image: &mut [u8]) {
        for f in &self.forces {
            f.stored.apply(image);
        }
    }

    pub fn list(&self) -> Vec<(String, String)> {
        self.forces
            .iter()
            .map(|f| (f.path.clone(), f.text.clone()))
            .collect()
    }
}

/// An executor whose forced locations hold their value around every
/// program run (see the module comment).
pub struct Forcing<E: Executor> {
    pub inner: E,
    pub table: Rc<RefCell<ForceTable>>,
}

impl<E: Executor> Executor for Forcing<E> {
    fn program(&self) -> &Program {
        self.inner.program()
    }
    fn image(&self) -> &[u8] {
        self.inner.image()
    }
    fn image_mut(&mut self) -> &mut [u8] {
        self.inner.image_mut()
    }
    fn cold_start(&mut self) {
        self.inner.cold_start()
    }
    fn run_program(&mut self, inst: &ProgramInstance, now_ns: i64) -> Result<(), Fault> {
        let table = self.table.borrow();
        table.apply(self.inner.image_mut());
        let result = self.inner.run_program(inst, now_ns);
        table.apply(self.inner.image_mut());
        result
    }
    fn interrupt(&self) -> automat_ir::Interrupt {
        self.inner.interrupt()
    }
}

/// A boxed backend as an [`Executor`] (the session takes any backend).
pub struct Boxed(pub Box<dyn Executor>);

impl Executor for Boxed {
    fn program(&self) -> &Program {
        self.0.program()
    }
    fn image(&self) -> &[u8] {
        self.0.image()
    }
    fn image_mut(&mut self) -> &mut [u8] {
        self.0.image_mut()
    }
    fn cold_start(&mut self) {
        self.0.cold_start()
    }
    fn run_program(&mut self, inst: &ProgramInstance, now_ns: i64) -> Result<(), Fault> {
        self.0.run_program(inst, now_ns)
    }
    fn interrupt(&self) -> automat_ir::Interrupt {
        self.0.interrupt()
    }
}

/// PLC time continued across a restart after a fault: the scan loop
/// starts again at 0, the program and the plant see `offset` more.
pub struct Shifted<E: Executor> {
    pub inner: E,
    pub offset: Rc<std::cell::Cell<i64>>,
}

impl<E: Executor> Executor for Shifted<E> {
    fn program(&self) -> &Program {
        self.inner.program()
    }
    fn image(&self) -> &[u8] {
        self.inner.image()
    }
    fn image_mut(&mut self) -> &mut [u8] {
        self.inner.image_mut()
    }
    fn cold_start(&mut self) {
        self.inner.cold_start()
    }
    fn run_program(&mut self, inst: &ProgramInstance, now_ns: i64) -> Result<(), Fault> {
        self.inner
            .run_program(inst, now_ns.saturating_add(self.offset.get()))
    }
    fn interrupt(&self) -> automat_ir::Interrupt {
        self.inner.interrupt()
    }
}
