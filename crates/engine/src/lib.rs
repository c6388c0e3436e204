//! The automat interpreter: executes [`automat_ir`] code over the memory
//! image.
//!
//! # Design
//! - The image is the program's state; [`Engine::run_program`] runs one
//!   program instance once at a given PLC time.
//! - Every function has a static register window (IEC forbids recursion);
//!   the register file and the call stack are allocated once in
//!   [`Engine::new`], so running does not allocate (except in string and
//!   conversion builtins), hash or look up names.
//! - The program is verified in [`Engine::new`]; a program that fails
//!   verification faults on every run instead of executing.
//! - A run can be stopped from outside: the [`Interrupt`] flag
//!   ([`Engine::interrupt`]) is polled every
//!   [`automat_ir::interrupt::POLL_INSTRUCTIONS`] instructions, at no cost
//!   of its own (the compare the budget needs anyway), and after long block
//!   copies. The runtime's watchdog raises it.
//! - An optional instruction budget per run (`set_budget`, off by default)
//!   faults deterministically at an exact instruction, for tests.

mod builtins;
mod dates;
mod exec;
mod fast;
mod fuse;
mod interp;
pub mod mem;
mod strplace;

/// What another backend (the Cranelift JIT, `automat-jit`) shares with the
/// interpreter so that semantics and fault messages exist once: the
/// standard functions over a register slice, and the fault constructors.
pub mod shared {
    pub use crate::builtins::call as builtin;
    pub use crate::interp::{check_range, fault, interrupted, Ctx};
    pub use crate::strplace::{handles as str_in_place, run as run_str_in_place};
}

use automat_ir::{Fault, FaultKind, Interrupt, Program, ProgramInstance, Site};

/// Default instruction budget per `run_program`: none (the watchdog in
/// time, through the [`Interrupt`] flag, stops endless loops).
pub const DEFAULT_BUDGET: u64 = u64::MAX;

pub struct Engine {
    program: Program,
    image: Vec<u8>,
    /// All register windows, as raw 64-bit patterns.
    regs: Vec<u64>,
    /// Start of each function's window in `regs`.
    windows: Vec<u32>,
    /// Every function's code pre-decoded for the fast path (`fast.rs`).
    decoded: Vec<fast::Code>,
    /// Return frames; capacity fixed at creation.
    stack: Vec<interp::Frame>,
    budget: u64,
    /// Raised from outside to stop the run in progress.
    interrupt: Interrupt,
    /// Why the program cannot run (failed verification).
    invalid: Option<String>,
}

impl Engine {
    /// An engine whose image is the program's initial image (cold).
    pub fn new(program: Program) -> Engine {
        let invalid = program.verify().err().map(|e| e.to_string());
        let mut windows = Vec::with_capacity(program.funcs.len());
        let mut total = 0u32;
        for f in &program.funcs {
            windows.push(total);
            total = total.saturating_add(f.regs.len() as u32);
        }
        let decoded = program
            .funcs
            .iter()
            .zip(&windows)
            .map(|(f, &w)| fast::decode(f, w))
            .collect();
        let mut image = program.initial_image.clone();
        image.resize(program.image_size as usize, 0);
        Engine {
            stack: Vec::with_capacity(program.funcs.len() + 1),
            regs: vec![0; total as usize],
            windows,
            decoded,
            image,
            program,
            budget: DEFAULT_BUDGET,
            interrupt: Interrupt::new(),
            invalid,
        }
    }

    pub fn program(&self) -> &Program {
        &self.program
    }

    pub fn image(&self) -> &[u8] {
        &self.image
    }

    pub fn image_mut(&mut self) -> &mut [u8] {
        &mut self.image
    }

    /// image := initial image.
    pub fn cold_start(&mut self) {
        self.image.clear();
        self.image.extend_from_slice(&self.program.initial_image);
        self.image.resize(self.program.image_size as usize, 0);
    }

    /// The instruction budget per run: a run executing more faults
    /// (`FaultKind::Watchdog`) at exactly that instruction. `u64::MAX`
    /// ([`DEFAULT_BUDGET`]) is no budget.
    pub fn set_budget(&mut self, instructions: u64) {
        self.budget = instructions.max(1);
    }

    /// The flag that stops the run in progress at its next poll (a fault
    /// of kind `Watchdog` at the statement it was executing, message
    /// [`automat_ir::interrupt::INTERRUPTED`]). The engine never clears it.
    pub fn interrupt(&self) -> Interrupt {
        self.interrupt.clone()
    }

    /// Runs one program instance once at PLC time `now_ns`. A fault leaves
    /// the image as it was at the fault.
    pub fn run_program(&mut self, inst: &ProgramInstance, now_ns: i64) -> Result<(), Fault> {
        if let Some(why) = &self.invalid {
            return Err(Fault {
                kind: FaultKind::Function,
                message: format!("the program failed verification: {why}"),
                site: Site {
                    pou: inst.name.clone(),
                    location: String::new(),
                    meaning: None,
                },
            });
        }
        self.run_func(inst.func, inst.instance_offset, now_ns)
    }

    /// Runs any function with an instance base (for tests and tools).
    pub fn run_func(&mut self, func: u32, this: u32, now_ns: i64) -> Result<(), Fault> {
        interp::run(self, func, this, now_ns)
    }
}
