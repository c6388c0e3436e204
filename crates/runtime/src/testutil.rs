//! A fake backend for the runtime's tests: programs are Rust closures over
//! the image, and every run is logged with its PLC time.

use crate::executor::Executor;
use automat_ir::{
    Areas, Fault, FaultKind, Interrupt, Program, ProgramInstance, Site, SymbolTable, TaskDef,
};

/// What the fake "code" of a program does, by `ProgramInstance::func`.
pub const COUNT: u32 = 0;
/// Sets %Q byte 0 to 0xFF and counts like [`COUNT`].
pub const SET_OUTPUT: u32 = 1;
/// Faults when its counter reaches 3 (on its third run).
pub const FAULT_ON_THIRD: u32 = 2;
/// An endless loop: runs until the interrupt flag is raised, then faults
/// as a backend does (gives up after 30 s so a broken test ends).
pub const SPIN: u32 = 3;
/// `SLEEP + ms`: counts like [`COUNT`] after `ms` of wall time.
pub const SLEEP: u32 = 1000;

pub struct Fake {
    pub program: Program,
    pub image: Vec<u8>,
    pub log: Vec<(String, i64)>,
    pub interrupt: Interrupt,
}

impl Fake {
    pub fn new(program: Program) -> Fake {
        Fake {
            image: program.initial_image.clone(),
            program,
            log: Vec::new(),
            interrupt: Interrupt::new(),
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
            SPIN => {
                let t = std::time::Instant::now();
                while !self.interrupt.is_raised() {
                    if t.elapsed().as_secs() >= 30 {
                        return Ok(());
                    }
                    std::thread::sleep(std::time::Duration::from_millis(1));
                }
                return Err(Fault {
                    kind: FaultKind::Watchdog,
                    message: automat_ir::interrupt::INTERRUPTED.into(),
                    site: Site {
                        pou: "MAIN".into(),
                        location: "main.st:7:5".into(),
                        meaning: None,
                    },
                });
            }
            f if f >= SLEEP => {
                std::thread::sleep(std::time::Duration::from_millis(u64::from(f - SLEEP)));
            }
            FAULT_ON_THIRD if n == 3 => {
                return Err(Fault {
                    kind: FaultKind::DivisionByZero,
                    message: "division by zero".into(),
                    site: Site {
                        pou: "MAIN".into(),
                        location: "main.st:4:10".into(),
                        meaning: None,
                    },
                })
            }
            _ => {}
        }
        Ok(())
    }
    fn interrupt(&self) -> Interrupt {
        self.interrupt.clone()
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
        watchdog: Default::default(),
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
