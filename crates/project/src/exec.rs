//! A backend wrapped with a plant: the runtime's scan loop drives it like
//! any [`Executor`], and before the first program of each scan instant the
//! plant is synchronised ([`Sim::sync`]). The plant state is shared
//! (`Rc<RefCell<_>>`) with the observers of the run (scenario checks,
//! traces, the live view), which read it between scans.

use crate::sim::Sim;
use automat_ir::{Fault, Program, ProgramInstance};
use automat_runtime::Executor;
use std::cell::RefCell;
use std::rc::Rc;

pub struct PlantExec<E: Executor> {
    pub inner: E,
    pub sim: Rc<RefCell<Sim>>,
    synced: Option<i64>,
}

impl<E: Executor> PlantExec<E> {
    pub fn new(inner: E, sim: Rc<RefCell<Sim>>) -> PlantExec<E> {
        PlantExec {
            inner,
            sim,
            synced: None,
        }
    }
}

impl<E: Executor> Executor for PlantExec<E> {
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
        if self.synced != Some(now_ns) {
            self.synced = Some(now_ns);
            self.sim.borrow_mut().sync(now_ns, self.inner.image_mut());
        }
        self.inner.run_program(inst, now_ns)
    }
    fn interrupt(&self) -> automat_ir::Interrupt {
        self.inner.interrupt()
    }
}
