//! Hand-written IR run by the interpreter: arithmetic at every width, wrap,
//! division faults, branches and loops, calls with instance bases, bit
//! access, builtins, the watchdog and the verifier.

use automat_engine::Engine;
use automat_ir::code::*;
use automat_ir::{FaultKind, Program, ProgramInstance, Site, SymbolTable};

fn program(funcs: Vec<Func>, image_size: u32) -> Program {
    Program {
        image_size,
        initial_image: vec![0; image_size as usize],
        areas: Default::default(),
        retain: Vec::new(),
        symbols: SymbolTable::default(),
        tasks: Vec::new(),
        funcs,
        sites: vec![Site {
            pou: "MAIN".into(),
            location: "main.st:3:5".into(),
            meaning: None,
        }],
    }
}

fn inst(func: u32, offset: u32) -> ProgramInstance {
    ProgramInstance {
        name: "MAIN".into(),
        func,
        instance_offset: offset,
    }
}

/// `out := wrap(a op b)` at `ty`, a and b loaded from offsets 0 and 8 (I64), result stored at 16.
fn binop(
    op: impl Fn(&mut Func, Reg, Reg, Reg),
    ty: MemTy,
    a: i64,
    b: i64,
) -> Result<i64, FaultKind> {
    let mut f = Func::new("MAIN");
    let (ra, rb, rc, rd) = (
        f.reg(RegClass::I64),
        f.reg(RegClass::I64),
        f.reg(RegClass::I64),
        f.reg(RegClass::I64),
    );
    f.push(Inst::IConst { dst: ra, value: a });
    f.push(Inst::IConst { dst: rb, value: b });
    op(&mut f, rc, ra, rb);
    f.push(Inst::Wrap {
        dst: rd,
        src: rc,
        ty,
    });
    f.push(Inst::Store {
        src: rd,
        ty,
        addr: Addr::abs(16),
    });
    f.push(Inst::Ret);
    let mut e = Engine::new(program(vec![f], 32));
    e.run_program(&inst(0, 0), 0).map_err(|f| f.kind)?;
    let bytes: [u8; 8] = e.image()[16..24].try_into().unwrap();
    let raw = i64::from_le_bytes(bytes);
    Ok(match ty {
        MemTy::I8 => raw as i8 as i64,
        MemTy::U8 => raw as u8 as i64,
        MemTy::I16 => raw as i16 as i64,
        MemTy::U16 => raw as u16 as i64,
        MemTy::I32 => raw as i32 as i64,
        MemTy::U32 => raw as u32 as i64,
        _ => raw,
    })
}

fn int(op: IntOp) -> impl Fn(&mut Func, Reg, Reg, Reg) {
    move |f, dst, a, b| {
        f.push(Inst::Int { op, dst, a, b });
    }
}

fn div(signed: bool, rem: bool) -> impl Fn(&mut Func, Reg, Reg, Reg) {
    move |f, dst, a, b| {
        f.push(if rem {
            Inst::Rem {
                signed,
                dst,
                a,
                b,
                site: 0,
            }
        } else {
            Inst::Div {
                signed,
                dst,
                a,
                b,
                site: 0,
            }
        });
    }
}

#[test]
fn arithmetic_wraps_at_every_width() {
    assert_eq!(binop(int(IntOp::Add), MemTy::I8, 127, 1), Ok(-128));
    assert_eq!(binop(int(IntOp::Add), MemTy::U8, 255, 1), Ok(0));
    assert_eq!(binop(int(IntOp::Add), MemTy::I16, 32767, 1), Ok(-32768));
    assert_eq!(binop(int(IntOp::Sub), MemTy::U16, 0, 1), Ok(65535));
    assert_eq!(
        binop(int(IntOp::Mul), MemTy::I32, 65536, 32768),
        Ok(i32::MIN as i64)
    );
    assert_eq!(
        binop(int(IntOp::Sub), MemTy::U32, 0, 1),
        Ok(u32::MAX as i64)
    );
    assert_eq!(
        binop(int(IntOp::Add), MemTy::I64, i64::MAX, 1),
        Ok(i64::MIN)
    );
    assert_eq!(binop(int(IntOp::And), MemTy::U8, 0xF0, 0x3C), Ok(0x30));
    assert_eq!(binop(int(IntOp::Xor), MemTy::U8, 0xFF, 0x0F), Ok(0xF0));
}

#[test]
fn division_truncates_and_mod_has_the_dividends_sign() {
    assert_eq!(binop(div(true, false), MemTy::I16, -7, 2), Ok(-3));
    assert_eq!(binop(div(true, true), MemTy::I16, -7, 3), Ok(-1));
    assert_eq!(binop(div(true, true), MemTy::I16, 7, -3), Ok(1));
    assert_eq!(binop(div(true, false), MemTy::I8, -128, -1), Ok(-128));
    assert_eq!(binop(div(false, false), MemTy::I64, -1, 2), Ok(i64::MAX));
    assert_eq!(
        binop(div(true, false), MemTy::I16, 1, 0),
        Err(FaultKind::DivisionByZero)
    );
    assert_eq!(
        binop(div(true, true), MemTy::I16, 1, 0),
        Err(FaultKind::DivisionByZero)
    );
}

#[test]
fn division_fault_names_site_and_keeps_image() {
    let mut f = Func::new("MAIN");
    let (a, b, c) = (
        f.reg(RegClass::I64),
        f.reg(RegClass::I64),
        f.reg(RegClass::I64),
    );
    f.push(Inst::IConst { dst: a, value: 5 });
    f.push(Inst::Store {
        src: a,
        ty: MemTy::I16,
        addr: Addr::this(0),
    });
    f.push(Inst::IConst { dst: b, value: 0 });
    f.push(Inst::Div {
        signed: true,
        dst: c,
        a,
        b,
        site: 0,
    });
    f.push(Inst::Store {
        src: c,
        ty: MemTy::I16,
        addr: Addr::this(0),
    });
    f.push(Inst::Ret);
    let mut e = Engine::new(program(vec![f], 16));
    let fault = e.run_program(&inst(0, 4), 0).unwrap_err();
    assert_eq!(fault.kind, FaultKind::DivisionByZero);
    assert_eq!(
        fault.to_string(),
        "main.st:3:5: fault in MAIN: division by zero (5 / 0)"
    );
    assert_eq!(&e.image()[4..6], &[5, 0]);
}

/// sum := 0; FOR i := 1 TO n DO sum := sum + i; END_FOR at This+0 (n) and This+8 (sum).
fn loop_func() -> Func {
    let mut f = Func::new("MAIN");
    let (n, i, sum, one, c) = (
        f.reg(RegClass::I64),
        f.reg(RegClass::I64),
        f.reg(RegClass::I64),
        f.reg(RegClass::I64),
        f.reg(RegClass::I64),
    );
    f.push(Inst::Load {
        dst: n,
        ty: MemTy::I32,
        addr: Addr::this(0),
    });
    f.push(Inst::IConst { dst: sum, value: 0 });
    f.push(Inst::IConst { dst: i, value: 1 });
    f.push(Inst::IConst { dst: one, value: 1 });
    // 4: test
    f.push(Inst::ICmp {
        cmp: Cmp::Le,
        signed: true,
        dst: c,
        a: i,
        b: n,
    });
    f.push(Inst::Branch {
        cond: c,
        then: 6,
        els: 9,
    });
    f.push(Inst::Int {
        op: IntOp::Add,
        dst: sum,
        a: sum,
        b: i,
    });
    f.push(Inst::Int {
        op: IntOp::Add,
        dst: i,
        a: i,
        b: one,
    });
    f.push(Inst::Jump { target: 4 });
    // 9
    f.push(Inst::Store {
        src: sum,
        ty: MemTy::I64,
        addr: Addr::this(8),
    });
    f.push(Inst::Ret);
    f
}

#[test]
fn loops_branch_and_use_the_instance_base() {
    let mut e = Engine::new(program(vec![loop_func()], 64));
    e.image_mut()[32] = 100;
    e.run_program(&inst(0, 32), 0).unwrap();
    assert_eq!(
        i64::from_le_bytes(e.image()[40..48].try_into().unwrap()),
        5050
    );
    e.cold_start();
    assert!(e.image().iter().all(|b| *b == 0));
}

#[test]
fn watchdog_stops_endless_loops() {
    let mut f = Func::new("MAIN");
    f.push(Inst::Jump { target: 0 });
    let mut e = Engine::new(program(vec![f], 8));
    e.set_budget(1000);
    let fault = e.run_program(&inst(0, 0), 0).unwrap_err();
    assert_eq!(fault.kind, FaultKind::Watchdog);
    // A long but finite loop within budget passes.
    let mut e = Engine::new(program(vec![loop_func()], 64));
    e.image_mut()[0] = 200;
    e.set_budget(500);
    assert_eq!(
        e.run_program(&inst(0, 0), 0).unwrap_err().kind,
        FaultKind::Watchdog
    );
    e.set_budget(5000);
    assert!(e.run_program(&inst(0, 0), 0).is_ok());
}

#[test]
fn calls_pass_instance_bases() {
    // func 1: This+0 (INT) := This+0 + 1; two instances at 8 and 16, called from MAIN.
    let mut inc = Func::new("INC");
    let (x, one) = (inc.reg(RegClass::I64), inc.reg(RegClass::I64));
    inc.push(Inst::Load {
        dst: x,
        ty: MemTy::I16,
        addr: Addr::this(0),
    });
    inc.push(Inst::IConst { dst: one, value: 1 });
    inc.push(Inst::Int {
        op: IntOp::Add,
        dst: x,
        a: x,
        b: one,
    });
    inc.push(Inst::Wrap {
        dst: x,
        src: x,
        ty: MemTy::I16,
    });
    inc.push(Inst::Store {
        src: x,
        ty: MemTy::I16,
        addr: Addr::this(0),
    });
    inc.push(Inst::Ret);
    let mut main = Func::new("MAIN");
    main.push(Inst::Call {
        func: 1,
        this: Addr::this(8),
    });
    main.push(Inst::Call {
        func: 1,
        this: Addr::this(16),
    });
    main.push(Inst::Call {
        func: 1,
        this: Addr::this(16),
    });
    main.push(Inst::Ret);
    let mut e = Engine::new(program(vec![main, inc], 32));
    for _ in 0..3 {
        e.run_program(&inst(0, 0), 0).unwrap();
    }
    assert_eq!(e.image()[8], 3);
    assert_eq!(e.image()[16], 6);
}

#[test]
fn bit_access_and_time() {
    let mut f = Func::new("MAIN");
    let (a, t) = (f.reg(RegClass::I64), f.reg(RegClass::I64));
    f.push(Inst::LoadBit {
        dst: a,
        addr: Addr::abs(0),
        bit: 2,
    });
    f.push(Inst::StoreBit {
        src: a,
        addr: Addr::abs(1),
        bit: 7,
    });
    f.push(Inst::Now { dst: t });
    f.push(Inst::Store {
        src: t,
        ty: MemTy::I64,
        addr: Addr::abs(8),
    });
    f.push(Inst::Ret);
    let mut e = Engine::new(program(vec![f], 16));
    e.image_mut()[0] = 0b100;
    e.image_mut()[1] = 0b1;
    e.run_program(&inst(0, 0), 1_500_000_000).unwrap();
    assert_eq!(e.image()[1], 0b1000_0001);
    assert_eq!(
        i64::from_le_bytes(e.image()[8..16].try_into().unwrap()),
        1_500_000_000
    );
}

#[test]
fn reals_round_to_f32_and_builtins_run() {
    let mut f = Func::new("MAIN");
    let (a, b, c, d) = (
        f.reg(RegClass::F32),
        f.reg(RegClass::F32),
        f.reg(RegClass::F32),
        f.reg(RegClass::I64),
    );
    f.push(Inst::F32Const { dst: a, value: 0.1 });
    f.push(Inst::F32Const { dst: b, value: 0.2 });
    f.push(Inst::Float {
        op: FloatOp::Add,
        wide: false,
        dst: c,
        a,
        b,
    });
    f.push(Inst::Store {
        src: c,
        ty: MemTy::F32,
        addr: Addr::abs(0),
    });
    f.args.push(c);
    f.push(Inst::Builtin {
        op: Builtin::Convert(automat_iec::Elementary::Real, automat_iec::Elementary::Int),
        dst: Some(d),
        first: 0,
        count: 1,
        site: 0,
    });
    f.push(Inst::Store {
        src: d,
        ty: MemTy::I16,
        addr: Addr::abs(4),
    });
    f.push(Inst::Ret);
    let mut e = Engine::new(program(vec![f], 8));
    e.run_program(&inst(0, 0), 0).unwrap();
    assert_eq!(
        f32::from_le_bytes(e.image()[0..4].try_into().unwrap()),
        0.1f32 + 0.2f32
    );
    assert_eq!(e.image()[4], 0);
}

#[test]
fn index_checks_fault() {
    let mut f = Func::new("MAIN");
    let a = f.reg(RegClass::I64);
    f.push(Inst::IConst { dst: a, value: 11 });
    f.push(Inst::Check {
        kind: CheckKind::Index,
        val: a,
        lo: 1,
        hi: 10,
        site: 0,
    });
    f.push(Inst::Ret);
    let mut e = Engine::new(program(vec![f], 8));
    let fault = e.run_program(&inst(0, 0), 0).unwrap_err();
    assert_eq!(fault.kind, FaultKind::IndexOutOfBounds);
    assert_eq!(fault.message, "index 11 outside 1..10");
}

#[test]
fn verifier_rejects_bad_code_and_the_engine_refuses_it() {
    let mut f = Func::new("MAIN");
    let a = f.reg(RegClass::F32);
    f.push(Inst::IConst { dst: a, value: 1 });
    f.push(Inst::Ret);
    let p = program(vec![f], 8);
    let err = p.verify().unwrap_err();
    assert_eq!(err.to_string(), "MAIN @0: r0 is F32, expected I64");
    let mut e = Engine::new(p);
    assert_eq!(
        e.run_program(&inst(0, 0), 0).unwrap_err().kind,
        FaultKind::Function
    );

    let mut g = Func::new("MAIN");
    g.push(Inst::Jump { target: 7 });
    assert!(program(vec![g], 8).verify().is_err());
    let mut h = Func::new("MAIN");
    let r = h.reg(RegClass::I64);
    h.push(Inst::Load {
        dst: r,
        ty: MemTy::I64,
        addr: Addr::abs(4),
    });
    h.push(Inst::Ret);
    assert_eq!(
        program(vec![h], 8).verify().unwrap_err().message,
        "address 4+8 outside the image of 8 bytes"
    );
}
