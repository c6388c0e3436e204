//! The automat IR: the contract between the compiler (lowering from the
//! semantic model) and every backend (the interpreter now, Cranelift later),
//! and between the backends and everything outside them (runtime, printing,
//! monitoring, forcing, protocols).
//!
//! # Invariants
//! - **One memory image.** All state of a linked program lives in one byte
//!   image of [`Program::image_size`] bytes, little-endian, at offsets fixed
//!   here: globals, program instances, function-block instances (nested in
//!   their owner), the static frames of functions, the %I/%Q/%M areas.
//!   IEC 61131-3 forbids recursion and the runtime never preempts a scan in
//!   the middle of a POU, so every frame can be static.
//! - **The symbol table is the only way in from outside.** Printing,
//!   monitoring, forcing, tracing, retain and protocols address variables by
//!   qualified name through [`symbols::SymbolTable`]; nothing outside a
//!   backend knows how code is executed.
//! - **Time is an input.** Code reads the scan's timestamp only through the
//!   IR's explicit time read; no backend reads a clock.
//! - **Typed and explicit.** (code module, owned by the engine work) no
//!   implicit conversions, every memory access names its width and
//!   signedness, every check that can fault (division, index, subrange,
//!   string position) is an explicit instruction carrying a [`Site`].
//!
//! This file holds the parts that the runtime and tools share; the
//! instruction set lives in its own modules.

pub mod code;
pub mod interrupt;
pub mod strbuf;
pub mod symbols;
pub mod verify;

pub use interrupt::Interrupt;
pub use symbols::{Field, SymbolEntry, SymbolTable, SymbolType};

use std::ops::Range;

/// Where in the sources a fault can happen: the POU and `file:line:col`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Site {
    pub pou: String,
    /// `file:line:col`
    pub location: String,
    /// What a fault here means, when the code is generated from another
    /// language (`SourceMap::add_fault_meaning`): it replaces the
    /// check's own message.
    pub meaning: Option<String>,
}

/// Why the PLC stopped in its fault state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FaultKind {
    DivisionByZero,
    IndexOutOfBounds,
    SubrangeViolation,
    StringIndex,
    Watchdog,
    /// Any other runtime error of a standard function (invalid BCD, ...).
    Function,
}

/// A runtime fault: the kind, a message naming the values involved, where.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Fault {
    pub kind: FaultKind,
    pub message: String,
    pub site: Site,
}

impl std::fmt::Display for Fault {
    /// `file:line:col: fault in POU: message`
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}: fault in {}: {}",
            self.site.location, self.site.pou, self.message
        )
    }
}

/// Byte ranges of the located areas inside the image.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Areas {
    /// `%I`: written by the runtime from the inputs before each scan.
    pub input: Range<u32>,
    /// `%Q`: read by the runtime after each scan; zeroed in the safe state.
    pub output: Range<u32>,
    /// `%M`
    pub memory: Range<u32>,
}

/// One program instance run by a task.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ProgramInstance {
    /// Qualified name of the instance (`Inst`, or the program name when
    /// there is no configuration).
    pub name: String,
    /// Index of the program's code in the backend's function list.
    pub func: u32,
    /// Offset of the instance's memory in the image.
    pub instance_offset: u32,
}

/// A task of the configuration (or the implicit cyclic task).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TaskDef {
    pub name: String,
    /// `INTERVAL` in ns; `None` for a cyclic task (runs every cycle of the
    /// runtime's base period) or an event task.
    pub interval_ns: Option<i64>,
    /// Lower number = higher priority.
    pub priority: u32,
    /// `SINGLE`: the BOOL whose rising edge triggers the task (offset, bit).
    pub single: Option<(u32, Option<u8>)>,
    /// Run in this order within the task.
    pub programs: Vec<ProgramInstance>,
    /// How long a run of the task may take (set by the project file or
    /// the command line after lowering; the runtime enforces it).
    pub watchdog: TaskWatchdog,
}

/// A task's watchdog in wall-clock time (`[tasks.NAME] watchdog = "100ms"`
/// and `sensitivity = n` in `automat.toml`, `--watchdog` for the implicit
/// task). The runtime enforces it; `docs/watchdog.md` is the reference.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TaskWatchdog {
    /// Nothing configured: the runtime's default for its clock (10 s per
    /// run on the virtual clock, none in real time).
    #[default]
    Default,
    /// No watchdog (`--watchdog off`).
    Off,
    /// A run longer than `time_ns` is an overrun; `sensitivity`
    /// consecutive overruns fault, and so does a run still going after
    /// `time_ns × sensitivity` (stopped where it is).
    Limit { time_ns: i64, sensitivity: u32 },
}

/// A linked, executable program: code, memory layout, symbols, tasks.
/// Produced by lowering (`automat-lower`), executed by a backend.
#[derive(Clone, Debug, PartialEq)]
pub struct Program {
    pub image_size: u32,
    /// The image after a cold start: every variable at its initial value.
    pub initial_image: Vec<u8>,
    pub areas: Areas,
    /// Byte ranges of RETAIN variables (saved from end-of-scan snapshots, restored on a warm start).
    pub retain: Vec<Range<u32>>,
    pub symbols: SymbolTable,
    /// The configuration's tasks in declaration order, or one implicit
    /// cyclic task running the selected program when there is none.
    pub tasks: Vec<TaskDef>,
    /// The code of every POU that can run; indexed by `ProgramInstance::func`.
    pub funcs: Vec<code::Func>,
    /// Indexed by the site numbers that checking instructions carry.
    pub sites: Vec<Site>,
}

impl Program {
    /// The verifier's limits for this program.
    pub fn limits(&self) -> verify::Limits {
        verify::Limits {
            image_size: self.image_size,
            funcs: self.funcs.len() as u32,
            sites: self.sites.len() as u32,
        }
    }

    /// Verifies every function.
    pub fn verify(&self) -> Result<(), verify::VerifyError> {
        let lim = self.limits();
        self.funcs.iter().try_for_each(|f| verify::verify(f, lim))
    }
}
