//! The automat native-code engine: compiles the IR ([`automat_ir`]) to
//! machine code with Cranelift and runs it over the same flat image as the
//! interpreter, with the same results and faults.
//!
//! # Design
//! - Every IR function becomes one native function
//!   `(ctx: *mut RunCtx, this: u64) -> status`; IR registers become SSA
//!   variables (registers of a function are private to it, so nothing of
//!   them survives a call); `Call` is a direct native call, which is sound
//!   because [`Jit::new`] refuses a program whose call graph has a cycle.
//! - Memory operands are pointers into the image: `Abs` ones unchecked
//!   (the verifier proved them inside), `This`/`Reg` ones bounds-checked
//!   (`emit.rs`). Checking instructions are compiled where the IR has them.
//! - Faults: generated code calls a Rust helper that builds the same
//!   [`Fault`] as the interpreter (through `automat_engine::shared`) and
//!   returns status 1 up the native call chain. The instruction budget
//!   counts exactly like the interpreter (`translate.rs`); the interrupt
//!   flag ([`Jit::interrupt`]) is polled at loop headers every
//!   [`automat_ir::interrupt::POLL_INSTRUCTIONS`] (a load and a compare
//!   per iteration, the call on a cold path) and after long copies.
//! - Standard functions run in the interpreter's own implementation
//!   (`automat_engine::shared::builtin`) through one helper.
//! - [`Jit::new`] verifies the program and returns an error naming anything
//!   it cannot compile; callers then use the interpreter.

mod compile;
mod emit;
mod inline;
mod instances;
mod locals;
mod loops;
mod promote;
mod rt;
mod select;
mod translate;

/// The lengths (IR instructions) above which a function is compiled for
/// compile time linear in its length: see `compile.rs` and `promote.rs`.
pub use compile::QUICK_CODE;
pub use promote::MAX_CODE as MAX_PROMOTED_CODE;

use automat_ir::code::Inst;
use automat_ir::{Fault, FaultKind, Interrupt, Program, ProgramInstance, Site};
use cranelift_jit::JITModule;

/// Why a program cannot be compiled; the interpreter runs it instead.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum JitError {
    /// The program fails the IR verifier.
    Invalid(String),
    /// An instruction or construct this backend does not implement.
    Unsupported(String),
    /// Cranelift refused the generated code (a bug of this crate).
    Backend(String),
}

impl std::fmt::Display for JitError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            JitError::Invalid(m) => write!(f, "the program failed verification: {m}"),
            JitError::Unsupported(m) => write!(f, "not supported by the JIT: {m}"),
            JitError::Backend(m) => write!(f, "JIT code generation failed: {m}"),
        }
    }
}

impl std::error::Error for JitError {}

/// A program compiled to native code, with its image.
pub struct Jit {
    program: Box<Program>,
    image: Vec<u8>,
    budget: u64,
    /// Whether the code counts the budget: compiled so by the first
    /// `set_budget` with a finite budget (the default code has no budget
    /// bookkeeping at all, so it compiles and runs faster).
    counted: bool,
    /// Why that recompilation failed (every run then faults with it).
    recompile_error: Option<JitError>,
    /// Native entry of every function the tasks can reach.
    entries: Vec<Option<compile::EntryFn>>,
    /// Per function: `Some(bound)` when compiled without its entry check
    /// (see `instances.rs`), valid only for `this + bound <= image size`.
    bounds: Vec<Option<u64>>,
    shared: Box<rt::Shared>,
    /// Owns the executable memory `entries` point into.
    module: Option<JITModule>,
}

impl Jit {
    /// Verifies and compiles `program`; the image starts cold.
    pub fn new(program: Program) -> Result<Jit, JitError> {
        program
            .verify()
            .map_err(|e| JitError::Invalid(e.to_string()))?;
        check_calls(&program)?;
        let program = Box::new(program);
        let interrupt = Interrupt::new();
        let compiled = compile::compile(&program, false, interrupt.as_ptr() as i64)?;
        let mut image = program.initial_image.clone();
        image.resize(program.image_size as usize, 0);
        let shared = Box::new(rt::Shared {
            program: &*program,
            builtins: compiled.builtins,
            budget: automat_engine::DEFAULT_BUDGET,
            interrupt,
        });
        Ok(Jit {
            program,
            image,
            budget: automat_engine::DEFAULT_BUDGET,
            counted: false,
            recompile_error: None,
            entries: compiled.entries,
            bounds: compiled.bounds,
            shared,
            module: Some(compiled.module),
        })
    }

    pub fn program(&self) -> &Program {
        &self.program
    }

    /// Whether function `func` was compiled once, without the entry check
    /// of its instance, because every instance it runs on is proved inside
    /// the image (`instances.rs`); `false` for functions reached through
    /// an instance address in a register, which keep the checked twin.
    pub fn is_static(&self, func: u32) -> bool {
        self.bounds.get(func as usize).is_some_and(|b| b.is_some())
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

    /// The instruction budget per run (as the interpreter's; `u64::MAX`,
    /// the default, is none). The first finite budget recompiles the
    /// program with the budget's bookkeeping (the image is kept).
    pub fn set_budget(&mut self, instructions: u64) {
        self.budget = instructions.max(1);
        self.shared.budget = self.budget;
        if self.budget != u64::MAX && !self.counted {
            self.counted = true;
            let flag = self.shared.interrupt.as_ptr() as i64;
            match compile::compile(&self.program, true, flag) {
                Ok(c) => {
                    self.free_code();
                    self.entries = c.entries;
                    self.bounds = c.bounds;
                    self.shared.builtins = c.builtins;
                    self.module = Some(c.module);
                }
                Err(e) => self.recompile_error = Some(e),
            }
        }
    }

    /// Frees the generated code (nothing may run it afterwards).
    fn free_code(&mut self) {
        if let Some(m) = self.module.take() {
            self.entries.clear();
            // SAFETY: the only pointers into the module's code are `entries`,
            // cleared above; nothing runs generated code after this point.
            unsafe { m.free_memory() };
        }
    }

    /// The flag that stops the run in progress at its next poll (as the
    /// interpreter's `Engine::interrupt`).
    pub fn interrupt(&self) -> Interrupt {
        self.shared.interrupt.clone()
    }

    /// Runs one program instance once at PLC time `now_ns`. A fault leaves
    /// the image as it was at the fault.
    pub fn run_program(&mut self, inst: &ProgramInstance, now_ns: i64) -> Result<(), Fault> {
        self.run_func(inst.func, inst.instance_offset, now_ns)
    }

    /// Runs any function with an instance base (for tests and tools).
    pub fn run_func(&mut self, func: u32, this: u32, now_ns: i64) -> Result<(), Fault> {
        if let Some(e) = &self.recompile_error {
            return Err(Fault {
                kind: FaultKind::Function,
                message: format!("cannot compile the program with an instruction budget: {e}"),
                site: Site {
                    pou: String::new(),
                    location: String::new(),
                    meaning: None,
                },
            });
        }
        let Some(&Some(entry)) = self.entries.get(func as usize) else {
            return Err(Fault {
                kind: FaultKind::Function,
                message: format!("function {func} is not compiled (no task runs it)"),
                site: Site {
                    pou: String::new(),
                    location: String::new(),
                    meaning: None,
                },
            });
        };
        if let Some(&Some(bound)) = self.bounds.get(func as usize) {
            // Compiled for the instances the tasks run it on: any other
            // must lie inside the image too (its accesses are unchecked).
            if (this as u64).saturating_add(bound) > self.image.len() as u64 {
                return Err(Fault {
                    kind: FaultKind::Function,
                    message: format!(
                        "instance at {this} (+{bound} bytes) lies outside the image of {} bytes",
                        self.image.len()
                    ),
                    site: Site {
                        pou: self
                            .program
                            .funcs
                            .get(func as usize)
                            .map(|f| f.name.clone())
                            .unwrap_or_default(),
                        location: String::new(),
                        meaning: None,
                    },
                });
            }
        }
        let left = self.budget.min(i64::MAX as u64) as i64;
        let mut ctx = rt::RunCtx {
            image: self.image.as_mut_ptr(),
            image_len: self.image.len() as u64,
            left,
            now: now_ns,
            shared: &*self.shared,
            mark: rt::first_mark(left),
            fault: None,
            polled: 0,
        };
        // SAFETY: `entry` was compiled from this program with the `EntryFn`
        // signature; `ctx` points to the image we own mutably for the whole
        // call (no other reference to it exists meanwhile) with its exact
        // length, and to `shared`, alive as long as `self`. Generated code
        // only accesses the image through verified absolute offsets or
        // bounds-checked ones, and never recurses (checked in `new`).
        let status = unsafe { entry(&mut ctx, this as u64) };
        match (status, ctx.fault.take()) {
            (0, _) => Ok(()),
            (_, Some(f)) => Err(f),
            (s, None) => Err(Fault {
                kind: FaultKind::Function,
                message: format!("native code returned status {s} without a fault"),
                site: Site {
                    pou: self
                        .program
                        .funcs
                        .get(func as usize)
                        .map(|f| f.name.clone())
                        .unwrap_or_default(),
                    location: String::new(),
                    meaning: None,
                },
            }),
        }
    }
}

impl Drop for Jit {
    fn drop(&mut self) {
        self.free_code();
    }
}

/// Native calls need an acyclic call graph (IEC forbids recursion and
/// lowering rejects it, E092; a cycle here would overflow the native stack).
fn check_calls(program: &Program) -> Result<(), JitError> {
    // 0 = unvisited, 1 = on the current path, 2 = done.
    let n = program.funcs.len();
    let mut state = vec![0u8; n];
    let callees = |f: usize| -> Vec<usize> {
        program
            .funcs
            .get(f)
            .map(|x| {
                x.code
                    .iter()
                    .filter_map(|i| match i {
                        Inst::Call { func, .. } => Some(*func as usize),
                        _ => None,
                    })
                    .collect()
            })
            .unwrap_or_default()
    };
    for root in 0..n {
        if state.get(root) != Some(&0) {
            continue;
        }
        let mut stack = vec![(root, callees(root), 0usize)];
        if let Some(s) = state.get_mut(root) {
            *s = 1;
        }
        while let Some((f, cs, i)) = stack.last_mut() {
            let Some(&c) = cs.get(*i) else {
                if let Some(s) = state.get_mut(*f) {
                    *s = 2;
                }
                stack.pop();
                continue;
            };
            *i += 1;
            match state.get(c) {
                Some(0) => {
                    if let Some(s) = state.get_mut(c) {
                        *s = 1;
                    }
                    stack.push((c, callees(c), 0));
                }
                Some(1) => {
                    let name = program.funcs.get(c).map(|x| x.name.as_str()).unwrap_or("?");
                    return Err(JitError::Unsupported(format!(
                        "recursive call of {name} (Call instruction in a call cycle)"
                    )));
                }
                _ => {}
            }
        }
    }
    Ok(())
}

impl automat_runtime::Executor for Jit {
    fn program(&self) -> &Program {
        Jit::program(self)
    }
    fn image(&self) -> &[u8] {
        Jit::image(self)
    }
    fn image_mut(&mut self) -> &mut [u8] {
        Jit::image_mut(self)
    }
    fn cold_start(&mut self) {
        Jit::cold_start(self)
    }
    fn run_program(&mut self, inst: &ProgramInstance, now_ns: i64) -> Result<(), Fault> {
        Jit::run_program(self, inst, now_ns)
    }
    fn interrupt(&self) -> Interrupt {
        Jit::interrupt(self)
    }
}
