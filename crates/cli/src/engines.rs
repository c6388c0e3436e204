//! `--engine`: which backend executes the program. The JIT (native code,
//! `automat-jit`) is the default; a program it cannot compile runs on the
//! interpreter, with a note on stderr, never a failure.

use automat_engine::Engine;
use automat_ir::{Fault, Interrupt, Program, ProgramInstance, TaskWatchdog};
use automat_jit::Jit;
use automat_runtime::Executor;

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum EngineKind {
    /// The reference interpreter.
    Interp,
    /// Native code compiled with Cranelift (same results and faults).
    #[default]
    Jit,
}

/// The backend a run uses.
pub enum Backend {
    Interp(Box<Engine>),
    Jit(Box<Jit>),
}

/// `--watchdog`: the watchdog of every task the project file left at its
/// default (the implicit task of a program without a CONFIGURATION).
pub fn default_watchdog(program: &mut Program, watchdog: Option<TaskWatchdog>) {
    if let Some(w) = watchdog {
        for t in &mut program.tasks {
            if t.watchdog == TaskWatchdog::Default {
                t.watchdog = w;
            }
        }
    }
}

/// The backend of `kind` for `program`; falls back to the interpreter when
/// the JIT refuses the program.
pub fn build(program: Program, kind: EngineKind) -> Backend {
    build_noting(program, kind, |e| {
        eprintln!("note: {e}; running on the interpreter");
    })
}

/// [`build`] without the note: `automat test` falls back silently (its
/// verdicts are the same on both backends).
pub fn build_quiet(program: Program, kind: EngineKind) -> Backend {
    build_noting(program, kind, |_| {})
}

fn build_noting(program: Program, kind: EngineKind, note: impl FnOnce(String)) -> Backend {
    match kind {
        EngineKind::Interp => Backend::Interp(Box::new(Engine::new(program))),
        EngineKind::Jit => match Jit::new(program.clone()) {
            Ok(j) => Backend::Jit(Box::new(j)),
            Err(e) => {
                note(e.to_string());
                Backend::Interp(Box::new(Engine::new(program)))
            }
        },
    }
}

impl Backend {
    /// `--max-instructions`: the deterministic instruction budget per run
    /// (`None`: none).
    pub fn set_budget(&mut self, instructions: Option<u64>) {
        let n = instructions.unwrap_or(automat_engine::DEFAULT_BUDGET);
        match self {
            Backend::Interp(e) => e.set_budget(n),
            Backend::Jit(j) => j.set_budget(n),
        }
    }
}

impl Executor for Backend {
    fn program(&self) -> &Program {
        match self {
            Backend::Interp(e) => e.program(),
            Backend::Jit(j) => j.program(),
        }
    }
    fn image(&self) -> &[u8] {
        match self {
            Backend::Interp(e) => e.image(),
            Backend::Jit(j) => j.image(),
        }
    }
    fn image_mut(&mut self) -> &mut [u8] {
        match self {
            Backend::Interp(e) => e.image_mut(),
            Backend::Jit(j) => j.image_mut(),
        }
    }
    fn cold_start(&mut self) {
        match self {
            Backend::Interp(e) => e.cold_start(),
            Backend::Jit(j) => j.cold_start(),
        }
    }
    fn run_program(&mut self, inst: &ProgramInstance, now_ns: i64) -> Result<(), Fault> {
        match self {
            Backend::Interp(e) => e.run_program(inst, now_ns),
            Backend::Jit(j) => j.run_program(inst, now_ns),
        }
    }
    fn interrupt(&self) -> Interrupt {
        match self {
            Backend::Interp(e) => e.interrupt(),
            Backend::Jit(j) => j.interrupt(),
        }
    }
}
