//! The interrupt flag and the instruction budget's poll slices, on both
//! engines: budgets across slice boundaries stay exact and identical, a
//! raised flag stops an endless loop (raised before the run or from another
//! thread during it) at its statement, and a long block copy polls the
//! flag itself.

use automat_engine::Engine;
use automat_ir::code::{Addr, Func, Inst, IntOp, MemTy, RegClass};
use automat_ir::interrupt::{INTERRUPTED, POLL_INSTRUCTIONS};
use automat_ir::{Fault, FaultKind, Program, Site, SymbolTable};
use automat_jit::Jit;
use std::time::Duration;

fn program(funcs: Vec<Func>, image: Vec<u8>) -> Program {
    Program {
        image_size: image.len() as u32,
        initial_image: image,
        areas: Default::default(),
        retain: vec![],
        symbols: SymbolTable::default(),
        tasks: vec![],
        funcs,
        sites: vec![
            Site {
                pou: "F".into(),
                location: "t.st:1:1".into(),
                meaning: None,
            },
            Site {
                pou: "F".into(),
                location: "t.st:2:5".into(),
                meaning: None,
            },
        ],
    }
}

fn engines(p: Program) -> (Engine, Jit) {
    let jit = Jit::new(p.clone()).unwrap_or_else(|e| panic!("{e}"));
    (Engine::new(p), jit)
}

fn counter(img: &[u8]) -> i64 {
    i64::from_le_bytes(img[0..8].try_into().unwrap())
}

/// `loop: [0] += 1; (copy of `copy` bytes); goto loop`, statement site 1.
fn endless(copy: Option<u32>) -> Func {
    let mut f = Func::new("F");
    f.regs = vec![RegClass::I64; 2];
    let mut code = vec![
        Inst::IConst { dst: 1, value: 1 },
        Inst::Load {
            dst: 0,
            ty: MemTy::I64,
            addr: Addr::abs(0),
        },
        Inst::Int {
            op: IntOp::Add,
            dst: 0,
            a: 0,
            b: 1,
        },
        Inst::Store {
            src: 0,
            ty: MemTy::I64,
            addr: Addr::abs(0),
        },
    ];
    if let Some(len) = copy {
        code.push(Inst::Copy {
            dst: Addr::abs(8),
            src: Addr::abs(8 + len),
            len,
        });
    }
    code.push(Inst::Jump { target: 0 });
    f.code = code;
    f.stmt_sites = vec![(0, 1)];
    f
}

fn is_interrupt(r: &Result<(), Fault>) {
    let f = r.clone().unwrap_err();
    assert_eq!(f.kind, FaultKind::Watchdog);
    assert_eq!(f.message, INTERRUPTED);
    assert_eq!(f.site.location, "t.st:2:5");
}

#[test]
fn budgets_across_poll_slices_stay_exact_and_agree() {
    let p = POLL_INSTRUCTIONS;
    for budget in [p - 1, p, p + 1, p + 4, 3 * p + 2, 5 * p - 3] {
        let (mut e, mut j) = engines(program(vec![endless(None)], vec![0; 16]));
        e.set_budget(budget);
        j.set_budget(budget);
        let a = e.run_func(0, 0, 0);
        let b = j.run_func(0, 0, 0);
        assert_eq!(a, b, "budget {budget}");
        assert_eq!(
            a.unwrap_err().message,
            format!("watchdog: more than {budget} instructions in one run")
        );
        assert_eq!(e.image(), j.image(), "budget {budget}");
        // Five instructions per iteration, the budget counted exactly.
        assert_eq!(
            counter(e.image()),
            ((budget + 1) / 5) as i64,
            "budget {budget}"
        );
    }
}

#[test]
fn a_finite_loop_longer_than_many_slices_runs_to_its_end() {
    // [0] counts down from 1,000,000 to 0: about 4 million instructions.
    let mut f = Func::new("F");
    f.regs = vec![RegClass::I64; 3];
    f.code = vec![
        Inst::IConst { dst: 1, value: 1 },
        Inst::Load {
            dst: 0,
            ty: MemTy::I64,
            addr: Addr::abs(0),
        },
        Inst::Int {
            op: IntOp::Sub,
            dst: 0,
            a: 0,
            b: 1,
        },
        Inst::Store {
            src: 0,
            ty: MemTy::I64,
            addr: Addr::abs(0),
        },
        Inst::Branch {
            cond: 0,
            then: 1,
            els: 5,
        },
        Inst::Ret,
    ];
    let mut image = vec![0; 16];
    image[0..8].copy_from_slice(&1_000_000i64.to_le_bytes());
    let (mut e, mut j) = engines(program(vec![f], image));
    assert_eq!(e.run_func(0, 0, 0), Ok(()));
    assert_eq!(j.run_func(0, 0, 0), Ok(()));
    assert_eq!(counter(e.image()), 0);
    assert_eq!(e.image(), j.image());
}

#[test]
fn a_raised_flag_stops_an_endless_loop_at_the_next_poll() {
    let (mut e, mut j) = engines(program(vec![endless(None)], vec![0; 16]));
    // The JIT compiled with a budget's bookkeeping polls as the interpreter.
    let mut counted = Jit::new(program(vec![endless(None)], vec![0; 16])).unwrap();
    counted.set_budget(u64::MAX - 1);
    for flag in [e.interrupt(), j.interrupt(), counted.interrupt()] {
        flag.raise();
    }
    let (a, b, c) = (
        e.run_func(0, 0, 0),
        j.run_func(0, 0, 0),
        counted.run_func(0, 0, 0),
    );
    is_interrupt(&a);
    is_interrupt(&b);
    is_interrupt(&c);
    // Polled after POLL_INSTRUCTIONS (at the next loop header when counted).
    for img in [e.image(), counted.image()] {
        let n = counter(img) as u64;
        assert!(n > 0 && n <= POLL_INSTRUCTIONS / 5 + 2, "{n}");
    }
    // Without a budget the JIT tests the flag at every loop header: the
    // loop stops before its first iteration.
    assert_eq!(counter(j.image()), 0);
    // The engines never clear the flag themselves.
    assert!(e.interrupt().is_raised() && j.interrupt().is_raised());
    e.interrupt().clear();
    j.interrupt().clear();
    e.set_budget(100);
    j.set_budget(100);
    assert_eq!(e.run_func(0, 0, 0), j.run_func(0, 0, 0));
}

#[test]
fn a_flag_raised_by_another_thread_stops_the_run_in_progress() {
    let (mut e, mut j) = engines(program(vec![endless(None)], vec![0; 16]));
    for flag in [e.interrupt(), j.interrupt()] {
        std::thread::spawn(move || {
            std::thread::sleep(Duration::from_millis(50));
            flag.raise();
        });
    }
    is_interrupt(&e.run_func(0, 0, 0));
    is_interrupt(&j.run_func(0, 0, 0));
}

/// `[0] += 1; copy `len` bytes; [0] += 1; return`: no loop at all.
fn straight_copy(len: u32) -> Func {
    let mut f = endless(Some(len));
    let bump = f.code[0..4].to_vec();
    f.code.truncate(5);
    f.code.extend(bump);
    f.code.push(Inst::Ret);
    f
}

#[test]
fn a_long_copy_polls_the_flag_when_done() {
    // One copy of 1 MiB is one long instruction: with the flag raised the
    // run stops right after it, before the second increment.
    let len = 1 << 20;
    let p = program(vec![straight_copy(len)], vec![0; 8 + 2 * len as usize]);
    let (mut e, mut j) = engines(p.clone());
    let mut counted = Jit::new(p).unwrap();
    counted.set_budget(u64::MAX - 1);
    for flag in [e.interrupt(), j.interrupt(), counted.interrupt()] {
        flag.raise();
    }
    is_interrupt(&e.run_func(0, 0, 0));
    is_interrupt(&j.run_func(0, 0, 0));
    is_interrupt(&counted.run_func(0, 0, 0));
    for img in [e.image(), j.image(), counted.image()] {
        assert_eq!(counter(img), 1);
    }
    // A short copy does not poll: the run ends normally.
    let (mut e, mut j) = engines(program(vec![straight_copy(64)], vec![0; 8 + 128]));
    e.interrupt().raise();
    j.interrupt().raise();
    assert_eq!(e.run_func(0, 0, 0), Ok(()));
    assert_eq!(j.run_func(0, 0, 0), Ok(()));
    assert_eq!(counter(e.image()), 2);
    assert_eq!(counter(j.image()), 2);
}
