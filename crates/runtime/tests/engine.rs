//! The runtime driving the real interpreter over hand-written IR: a
//! counter program, PLC time read by the program, and a division fault.

use automat_engine::Engine;
use automat_ir::code::*;
use automat_ir::{Areas, Program, ProgramInstance, Site, SymbolTable, TaskDef};
use automat_runtime::io::NoIo;
use automat_runtime::scan::Env;
use automat_runtime::{run, ClockMode, Limit, RunConfig, RunEnd, SystemClock};
use std::sync::atomic::AtomicBool;

/// `this.count := this.count + 1; this.out := this.count / this.div;` and
/// %QB0 := 1.
fn counter() -> Func {
    let mut f = Func::new("MAIN");
    let (a, one, sum, d, q) = (
        f.reg(RegClass::I64),
        f.reg(RegClass::I64),
        f.reg(RegClass::I64),
        f.reg(RegClass::I64),
        f.reg(RegClass::I64),
    );
    f.push(Inst::Load {
        dst: a,
        ty: MemTy::I32,
        addr: Addr::this(0),
    });
    f.push(Inst::IConst { dst: one, value: 1 });
    f.push(Inst::Int {
        op: IntOp::Add,
        dst: sum,
        a,
        b: one,
    });
    f.push(Inst::Store {
        src: sum,
        ty: MemTy::I32,
        addr: Addr::this(0),
    });
    f.push(Inst::Store {
        src: one,
        ty: MemTy::U8,
        addr: Addr::abs(16),
    });
    f.push(Inst::Load {
        dst: d,
        ty: MemTy::I32,
        addr: Addr::this(4),
    });
    f.push(Inst::Div {
        signed: true,
        dst: q,
        a: sum,
        b: d,
        site: 0,
    });
    f.push(Inst::Store {
        src: q,
        ty: MemTy::I32,
        addr: Addr::this(8),
    });
    f.push(Inst::Ret);
    f
}

fn program(divisor: i32) -> Program {
    let mut initial = vec![0u8; 24];
    initial[4..8].copy_from_slice(&divisor.to_le_bytes());
    Program {
        image_size: 24,
        initial_image: initial,
        areas: Areas {
            input: 16..16,
            output: 16..17,
            memory: 17..17,
        },
        retain: Vec::new(),
        symbols: SymbolTable::default(),
        tasks: vec![TaskDef {
            name: "MAIN".into(),
            interval_ns: None,
            priority: 0,
            single: None,
            programs: vec![ProgramInstance {
                name: "MAIN".into(),
                func: 0,
                instance_offset: 0,
            }],
            watchdog: Default::default(),
        }],
        funcs: vec![counter()],
        sites: vec![Site {
            pou: "MAIN".into(),
            location: "main.st:5:12".into(),
            meaning: None,
        }],
    }
}

fn go(engine: &mut Engine, cycles: u64) -> automat_runtime::RunReport {
    let stop = AtomicBool::new(false);
    let mut clock = SystemClock::new();
    let mut env = Env {
        clock: &mut clock,
        inputs: &mut NoIo,
        outputs: &mut NoIo,
        observer: &mut (),
        stop: &stop,
    };
    let cfg = RunConfig {
        cycle_time_ns: 10_000_000,
        clock: ClockMode::Virtual,
        limit: Limit::Cycles(cycles),
    };
    run(engine, &cfg, &mut env).unwrap()
}

fn i32_at(e: &Engine, at: usize) -> i32 {
    i32::from_le_bytes(e.image()[at..at + 4].try_into().unwrap())
}

#[test]
fn the_engine_runs_under_the_scan_loop() {
    let mut e = Engine::new(program(2));
    let r = go(&mut e, 7);
    assert_eq!(r.end, RunEnd::Limit);
    assert_eq!(i32_at(&e, 0), 7);
    assert_eq!(i32_at(&e, 8), 3);
    assert_eq!(e.image()[16], 1);
    assert_eq!(r.stats.task_runs, [("MAIN".to_string(), 7)]);
}

#[test]
fn an_engine_fault_zeroes_the_outputs() {
    let mut e = Engine::new(program(0));
    let r = go(&mut e, 7);
    let RunEnd::Fault(report) = r.end else {
        panic!("no fault: {:?}", r.end)
    };
    assert_eq!(report.fault.kind, automat_ir::FaultKind::DivisionByZero);
    assert_eq!(report.fault.site.location, "main.st:5:12");
    assert_eq!(report.plc_time_ns, 0);
    assert_eq!(e.image()[16], 0);
    assert_eq!(i32_at(&e, 0), 1);
}
