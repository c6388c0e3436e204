//! Shared by the real-time benchmarks (`online`, `modbus`): an executor
//! that records how late each scan's first program starts against its
//! PLC time, and the percentile of a sorted sample.

use automat_ir::{Fault, Program, ProgramInstance};
use automat_runtime::Executor;
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// Records when each scan's first program starts, against PLC time.
pub struct Probe {
    pub inner: automat_jit::Jit,
    pub epoch: Instant,
    pub last: Option<i64>,
    pub lateness: Arc<Mutex<Vec<(i64, i64)>>>,
}

impl Executor for Probe {
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
        if self.last != Some(now_ns) {
            self.last = Some(now_ns);
            let wall = self.epoch.elapsed().as_nanos() as i64;
            if let Ok(mut l) = self.lateness.lock() {
                l.push((now_ns, wall - now_ns));
            }
        }
        self.inner.run_program(inst, now_ns)
    }
    fn interrupt(&self) -> automat_ir::Interrupt {
        self.inner.interrupt()
    }
}

pub fn percentile(sorted: &[i64], p: f64) -> i64 {
    if sorted.is_empty() {
        return 0;
    }
    let i = ((sorted.len() - 1) as f64 * p).round() as usize;
    sorted[i.min(sorted.len() - 1)]
}
