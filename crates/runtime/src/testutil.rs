//! A fake backend for the runtime's tests: programs are Rust closures over
//! the image, and every run is logged with its PLC time.

use crate::executor::Executor;
use automat_ir::{Areas, Fault, FaultKind, Program, ProgramInstance, Site, SymbolTable, TaskDef};

/// What the fake "code" of a program does, by `ProgramInstance::func`.
pub const COUNT: u32 = 0;
/// Sets %Q byte 0 to 0xFF and counts like [`COUNT`].
pub const SET_OUTPUT: u32 = 1;
/// Faults when its counter reaches 3 (on its third run).
pub const FAULT_ON_THIRD: u32 = 2;

pub struct Fake {
    pub program: Program,
    pub image: Vec<u8>,
    pub log: Vec<(String, i64)>,
}

impl Fake {
    pub fn new(program: Program) -> Fake {
        Fake {
            image: program.initial_image.clone(),
            program,
            log: Vec::new(),
        }
    }

    pub fn counter(&self, offset: usize) -> u32 {
        u32::from_le_bytes(self.image[offset..offset + 4].try_into().unwrap())
    }
}

impl Executor for Fake {
    fn program(&self) -> &Program {
        &self.program
    }
    fn image(&self) -> &[u8] {
        &self.image
    }
    fn image_mut(&mut self) -> &mut [u8] {
        &mut self.image
    }
    fn cold_start(&mut self) {
        self.image = self.program.initial_image.clone();
    }
    fn run_program(&mut self, inst: &ProgramInstance, now_ns: i64) -> Result<(), Fault> {
        self.log.push((inst.name.clone(), now_ns));
        let at = inst.instance_offset as usize;
        let n = self.counter(at) + 1;
        self.image[at..at + 4].copy_from_slice(&n.to_le_bytes());
        match inst.func {
            SET_OUTPUT => {
                let q = self.program.areas.output.start as usize;
                self.image[q] = 0xFF;
            }
            FAULT_ON_THIRD if n == 3 => {
                return Err(Fault {
                    kind: FaultKind::DivisionByZero,
                    message: "division by zero".into(),
                    site: Site {
                        pou: "MAIN".into(),
                        location: "main.st:4:10".into(),
                    },
                })
            }
            _ => {}
        }
        Ok(())
    }
}

pub fn inst(name: &str, func: u32, offset: u32) -> ProgramInstance {
    ProgramInstance {
        name: name.into(),
        func,
        instance_offset: offset,
    }
}

pub fn task(
    name: &str,
    interval_ms: Option<i64>,
    priority: u32,
    programs: Vec<ProgramInstance>,
) -> TaskDef {
    TaskDef {
        name: name.into(),
        interval_ns: interval_ms.map(|ms| ms * 1_000_000),
        priority,
        single: None,
        programs,
    }
}

/// A 64-byte image: counters anywhere in 0..40, %I at 40..44, %Q at 44..48.
pub fn program(tasks: Vec<TaskDef>) -> Program {
    Program {
        image_size: 64,
        initial_image: vec![0; 64],
        areas: Areas {
            input: 40..44,
            output: 44..48,
            memory: 48..52,
        },
        retain: Vec::new(),
        symbols: SymbolTable::default(),
        tasks,
        funcs: Vec::new(),
        sites: Vec::new(),
    }
}
