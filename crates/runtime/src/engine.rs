//! The interpreter is an [`Executor`].

use crate::executor::Executor;
use automat_engine::Engine;
use automat_ir::{Fault, Interrupt, Program, ProgramInstance};

impl Executor for Engine {
    fn program(&self) -> &Program {
        Engine::program(self)
    }
    fn image(&self) -> &[u8] {
        Engine::image(self)
    }
    fn image_mut(&mut self) -> &mut [u8] {
        Engine::image_mut(self)
    }
    fn cold_start(&mut self) {
        Engine::cold_start(self)
    }
    fn run_program(&mut self, inst: &ProgramInstance, now_ns: i64) -> Result<(), Fault> {
        Engine::run_program(self, inst, now_ns)
    }
    fn interrupt(&self) -> Interrupt {
        Engine::interrupt(self)
    }
}
