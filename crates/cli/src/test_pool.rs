//! Backends compiled once per project and lent to its scenarios one at a
//! time (`automat test`): the JIT's compile is paid once per worker thread
//! that runs a scenario of the project, not once per scenario.
//!
//! A lent backend is cold-started before each run, so a scenario sees
//! exactly what a freshly built one shows it: the image is the initial
//! image and the watchdog clears the interrupt flag when it arms each task
//! run. No instruction budget is ever set on a pooled backend (a budget
//! recompiles the code and would stay with it).

use crate::engines::{self, Backend, EngineKind};
use automat_ir::{Fault, Interrupt, Program, ProgramInstance};
use automat_runtime::Executor;
use std::sync::{Arc, Mutex};

/// The idle backends of one project.
#[derive(Default)]
pub struct Pool {
    idle: Arc<Mutex<Vec<Backend>>>,
}

impl Pool {
    /// An idle backend of `program` on `kind`, cold, or a new one when all
    /// are lent (two threads never share one: each run owns its image and
    /// its interrupt flag).
    pub fn lend(&self, program: &Program, kind: EngineKind) -> Lent {
        let idle = lock(&self.idle).pop();
        let mut backend = idle.unwrap_or_else(|| engines::build_quiet(program.clone(), kind));
        backend.cold_start();
        Lent {
            backend: Some(backend),
            home: Arc::clone(&self.idle),
        }
    }
}

fn lock(m: &Mutex<Vec<Backend>>) -> std::sync::MutexGuard<'_, Vec<Backend>> {
    // A list of idle backends stays valid whatever panicked while it was held.
    m.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// A backend on loan; it goes back to its pool when the run drops it.
pub struct Lent {
    /// Always `Some` until `drop`.
    backend: Option<Backend>,
    home: Arc<Mutex<Vec<Backend>>>,
}

impl Lent {
    fn get(&self) -> &Backend {
        match &self.backend {
            Some(b) => b,
            None => unreachable!("a lent backend is only taken in drop"),
        }
    }
    fn get_mut(&mut self) -> &mut Backend {
        match &mut self.backend {
            Some(b) => b,
            None => unreachable!("a lent backend is only taken in drop"),
        }
    }
}

impl Drop for Lent {
    fn drop(&mut self) {
        if let Some(b) = self.backend.take() {
            lock(&self.home).push(b);
        }
    }
}

impl Executor for Lent {
    fn program(&self) -> &Program {
        self.get().program()
    }
    fn image(&self) -> &[u8] {
        self.get().image()
    }
    fn image_mut(&mut self) -> &mut [u8] {
        self.get_mut().image_mut()
    }
    fn cold_start(&mut self) {
        self.get_mut().cold_start()
    }
    fn run_program(&mut self, inst: &ProgramInstance, now_ns: i64) -> Result<(), Fault> {
        self.get_mut().run_program(inst, now_ns)
    }
    fn interrupt(&self) -> Interrupt {
        self.get().interrupt()
    }
}
