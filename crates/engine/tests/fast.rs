//! The pre-decoded fast path and its superinstructions must behave exactly
//! like the instructions they replace: entering a fused run in its middle,
//! faults inside a fused run, and every intermediate register written.

use automat_engine::Engine;
use automat_ir::code::*;
use automat_ir::{FaultKind, Program, ProgramInstance, Site, SymbolTable};

fn program(f: Func) -> Program {
    Program {
        image_size: 64,
        initial_image: vec![0; 64],
        areas: Default::default(),
        retain: Vec::new(),
        symbols: SymbolTable::default(),
        tasks: Vec::new(),
        funcs: vec![f],
        sites: vec![Site {
            pou: "MAIN".into(),
            location: "main.st:7:9".into(),
            meaning: None,
        }],
    }
}

fn run(f: Func) -> Result<Vec<u8>, (FaultKind, String)> {
    let mut e = Engine::new(program(f));
    let inst = ProgramInstance {
        name: "MAIN".into(),
        func: 0,
        instance_offset: 0,
    };
    e.run_program(&inst, 0)
        .map_err(|f| (f.kind, f.site.location))?;
    Ok(e.image().to_vec())
}

fn i64_at(image: &[u8], at: usize) -> i64 {
    let mut b = [0u8; 8];
    b.copy_from_slice(&image[at..at + 8]);
    i64::from_le_bytes(b)
}

/// `r2 := r0 + r1` where `r1` is set by an `IConst` fused with the add;
/// `skip_const` jumps straight to the add, past the constant.
fn const_add(skip_const: bool) -> Func {
    let mut f = Func::new("MAIN");
    let (r0, r1, r2) = (
        f.reg(RegClass::I64),
        f.reg(RegClass::I64),
        f.reg(RegClass::I64),
    );
    f.push(Inst::IConst { dst: r0, value: 5 });
    f.push(Inst::IConst {
        dst: r1,
        value: 100,
    });
    f.push(Inst::Jump {
        target: if skip_const { 4 } else { 3 },
    });
    f.push(Inst::IConst { dst: r1, value: 7 });
    f.push(Inst::Int {
        op: IntOp::Add,
        dst: r2,
        a: r0,
        b: r1,
    });
    f.push(Inst::Store {
        src: r2,
        ty: MemTy::I64,
        addr: Addr::abs(0),
    });
    // The constant register must hold the fused constant afterwards.
    f.push(Inst::Store {
        src: r1,
        ty: MemTy::I64,
        addr: Addr::abs(8),
    });
    f.push(Inst::Ret);
    f
}

#[test]
fn fused_constant_and_add_from_the_start_and_from_the_middle() {
    let img = run(const_add(false)).unwrap();
    assert_eq!((i64_at(&img, 0), i64_at(&img, 8)), (12, 7));
    let img = run(const_add(true)).unwrap();
    assert_eq!((i64_at(&img, 0), i64_at(&img, 8)), (105, 100));
}

/// `arr[i]` address computation as the lowering emits it, for an
/// `ARRAY[1..4] OF LINT` at offset 16; stores 42 into the element.
fn element_store(index: i64) -> Func {
    let mut f = Func::new("MAIN");
    let r: Vec<Reg> = (0..8).map(|_| f.reg(RegClass::I64)).collect();
    f.push(Inst::IConst {
        dst: r[0],
        value: index,
    });
    f.push(Inst::Check {
        kind: CheckKind::Index,
        val: r[0],
        lo: 1,
        hi: 4,
        site: 0,
    });
    f.push(Inst::IConst {
        dst: r[1],
        value: 8,
    });
    f.push(Inst::Int {
        op: IntOp::Mul,
        dst: r[2],
        a: r[0],
        b: r[1],
    });
    f.push(Inst::AddrOf {
        dst: r[3],
        addr: Addr::this(16),
    });
    f.push(Inst::IConst {
        dst: r[4],
        value: -8,
    });
    f.push(Inst::Int {
        op: IntOp::Add,
        dst: r[5],
        a: r[2],
        b: r[4],
    });
    f.push(Inst::Int {
        op: IntOp::Add,
        dst: r[6],
        a: r[3],
        b: r[5],
    });
    f.push(Inst::IConst {
        dst: r[7],
        value: 42,
    });
    f.push(Inst::Store {
        src: r[7],
        ty: MemTy::I64,
        addr: Addr::reg(r[6], 0),
    });
    // An intermediate register of the fused run, kept for the check below.
    f.push(Inst::Store {
        src: r[5],
        ty: MemTy::I64,
        addr: Addr::abs(56),
    });
    f.push(Inst::Ret);
    f
}

#[test]
fn fused_element_address_stores_and_keeps_intermediates() {
    let img = run(element_store(3)).unwrap();
    assert_eq!(i64_at(&img, 16 + 2 * 8), 42);
    assert_eq!(i64_at(&img, 56), 16);
    assert_eq!(i64_at(&img, 16), 0);
}

#[test]
fn fused_element_address_out_of_range_faults_at_its_site() {
    assert_eq!(
        run(element_store(5)),
        Err((FaultKind::IndexOutOfBounds, "main.st:7:9".to_string()))
    );
    assert_eq!(
        run(element_store(0)).map_err(|e| e.0),
        Err(FaultKind::IndexOutOfBounds)
    );
}

#[test]
fn fused_compare_and_branch_writes_the_condition() {
    // r2 := (r0 < r1); if r2 then store 1 else store 2; store r2 too.
    for (a, b, want) in [(1, 2, 1), (2, 1, 2), (-1, 0, 1)] {
        let mut f = Func::new("MAIN");
        let (r0, r1, r2, r3) = (
            f.reg(RegClass::I64),
            f.reg(RegClass::I64),
            f.reg(RegClass::I64),
            f.reg(RegClass::I64),
        );
        f.push(Inst::IConst { dst: r0, value: a });
        f.push(Inst::IConst { dst: r1, value: b });
        f.push(Inst::ICmp {
            cmp: Cmp::Lt,
            signed: true,
            dst: r2,
            a: r0,
            b: r1,
        });
        f.push(Inst::Branch {
            cond: r2,
            then: 4,
            els: 6,
        });
        f.push(Inst::IConst { dst: r3, value: 1 });
        f.push(Inst::Jump { target: 7 });
        f.push(Inst::IConst { dst: r3, value: 2 });
        f.push(Inst::Store {
            src: r3,
            ty: MemTy::I64,
            addr: Addr::abs(0),
        });
        f.push(Inst::Store {
            src: r2,
            ty: MemTy::I64,
            addr: Addr::abs(8),
        });
        f.push(Inst::Ret);
        let img = run(f).unwrap();
        assert_eq!(i64_at(&img, 0), want, "{a} < {b}");
        assert_eq!(i64_at(&img, 8), (want == 1) as i64, "{a} < {b}");
    }
}
