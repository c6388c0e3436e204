//! Unit tests per instruction group on hand-written IR: each program runs
//! on the interpreter and the JIT, which must agree on the whole image and
//! the result; the tests then assert the exact values.

use automat_engine::Engine;
use automat_ir::code::{
    Addr, Builtin, CheckKind, Cmp, FloatOp, Func, Inst, IntOp, MathFn, MemTy, RegClass, ShiftOp,
    StrFn,
};
use automat_ir::{Fault, FaultKind, Program, Site, SymbolTable};
use automat_jit::{Jit, JitError};

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

/// Runs function 0 on both engines (this = 0, now = 7 ms); asserts they
/// agree and returns the result and the image.
fn both(p: Program, budget: Option<u64>) -> (Result<(), Fault>, Vec<u8>) {
    let mut jit = Jit::new(p.clone()).unwrap_or_else(|e| panic!("{e}"));
    let mut e = Engine::new(p);
    if let Some(b) = budget {
        e.set_budget(b);
        jit.set_budget(b);
    }
    let a = e.run_func(0, 0, 7_000_000);
    let b = jit.run_func(0, 0, 7_000_000);
    assert_eq!(a, b, "result");
    assert_eq!(e.image(), jit.image(), "image");
    // A second run from the state the first left.
    let a2 = e.run_func(0, 0, 7_000_000);
    let b2 = jit.run_func(0, 0, 7_000_000);
    assert_eq!(a2, b2, "second result");
    assert_eq!(e.image(), jit.image(), "second image");
    (a, jit.image().to_vec())
}

fn func(regs: &[RegClass], code: Vec<Inst>) -> Func {
    let mut f = Func::new("F");
    f.regs = regs.to_vec();
    f.code = code;
    f
}

fn i64_at(img: &[u8], at: usize) -> i64 {
    i64::from_le_bytes(img[at..at + 8].try_into().unwrap())
}

use RegClass::{F32, F64, I64};

fn st(r: u32, at: u32) -> Inst {
    Inst::Store {
        src: r,
        ty: MemTy::I64,
        addr: Addr::abs(at),
    }
}

fn c(dst: u32, value: i64) -> Inst {
    Inst::IConst { dst, value }
}

#[test]
fn integer_arithmetic_and_wraps() {
    let mut code = vec![c(0, 7), c(1, -3)];
    let ops = [
        IntOp::Add,
        IntOp::Sub,
        IntOp::Mul,
        IntOp::And,
        IntOp::Or,
        IntOp::Xor,
    ];
    for (i, op) in ops.iter().enumerate() {
        code.push(Inst::Int {
            op: *op,
            dst: 2,
            a: 0,
            b: 1,
        });
        code.push(st(2, 8 * i as u32));
    }
    code.push(c(3, 300));
    code.push(Inst::Wrap {
        dst: 2,
        src: 3,
        ty: MemTy::U8,
    });
    code.push(st(2, 48));
    code.push(c(3, 32768));
    code.push(Inst::Wrap {
        dst: 2,
        src: 3,
        ty: MemTy::I16,
    });
    code.push(st(2, 56));
    code.push(Inst::Neg { dst: 2, src: 1 });
    code.push(st(2, 64));
    code.push(Inst::Not { dst: 2, src: 0 });
    code.push(st(2, 72));
    code.push(Inst::Ret);
    let (r, img) = both(program(vec![func(&[I64; 4], code)], vec![0; 80]), None);
    assert!(r.is_ok());
    let got: Vec<i64> = (0..10).map(|i| i64_at(&img, 8 * i)).collect();
    assert_eq!(got, vec![4, 10, -21, 5, -1, -6, 44, -32768, 3, -8]);
}

#[test]
fn division_and_remainder() {
    let cases = [
        (true, 7, -2),
        (true, -7, 2),
        (true, i64::MIN, -1),
        (false, -1, 3),
    ];
    let mut code = Vec::new();
    for (i, (signed, a, b)) in cases.iter().enumerate() {
        code.extend([c(0, *a), c(1, *b)]);
        code.push(Inst::Div {
            signed: *signed,
            dst: 2,
            a: 0,
            b: 1,
            site: 0,
        });
        code.push(st(2, 16 * i as u32));
        code.push(Inst::Rem {
            signed: *signed,
            dst: 2,
            a: 0,
            b: 1,
            site: 0,
        });
        code.push(st(2, 16 * i as u32 + 8));
    }
    code.push(Inst::Ret);
    let (r, img) = both(program(vec![func(&[I64; 3], code)], vec![0; 64]), None);
    assert!(r.is_ok());
    let got: Vec<i64> = (0..8).map(|i| i64_at(&img, 8 * i)).collect();
    assert_eq!(
        got,
        vec![-3, 1, -3, -1, i64::MIN, 0, (u64::MAX / 3) as i64, 0]
    );
}

#[test]
fn division_by_zero_faults_after_earlier_stores() {
    let code = vec![
        c(0, 5),
        st(0, 0),
        c(1, 0),
        Inst::Rem {
            signed: true,
            dst: 2,
            a: 0,
            b: 1,
            site: 1,
        },
        st(2, 8),
        Inst::Ret,
    ];
    let (r, img) = both(program(vec![func(&[I64; 3], code)], vec![0; 16]), None);
    let f = r.unwrap_err();
    assert_eq!(f.kind, FaultKind::DivisionByZero);
    assert_eq!(f.message, "MOD by zero (5 / 0)");
    assert_eq!(f.site.location, "t.st:2:5");
    assert_eq!(i64_at(&img, 0), 5);
}

#[test]
fn shifts_and_rotations() {
    let cases = [
        (ShiftOp::Shl, 8, 0x81, 1, 0x02),
        (ShiftOp::Rol, 8, 0x81, 1, 0x03),
        (ShiftOp::Ror, 16, 1, 1, 0x8000),
        (ShiftOp::Shr, 32, -1, 4, 0x0FFF_FFFF),
        (ShiftOp::Shl, 8, 1, 9, 0),
        (ShiftOp::Rol, 64, i64::MIN, 1, 1),
        (ShiftOp::Shl, 16, 1, -2, 1),
        (ShiftOp::Ror, 32, 1, 33, 0x8000_0000),
        (ShiftOp::Rol, 1, 1, 5, 1),
    ];
    let mut code = Vec::new();
    for (i, (op, w, a, n, _)) in cases.iter().enumerate() {
        code.extend([c(0, *a), c(1, *n)]);
        code.push(Inst::Shift {
            op: *op,
            width: *w,
            dst: 2,
            a: 0,
            n: 1,
        });
        code.push(st(2, 8 * i as u32));
    }
    code.push(Inst::Ret);
    let (r, img) = both(program(vec![func(&[I64; 3], code)], vec![0; 72]), None);
    assert!(r.is_ok());
    for (i, case) in cases.iter().enumerate() {
        assert_eq!(i64_at(&img, 8 * i), case.4, "case {i}");
    }
}

#[test]
fn compares_and_branches() {
    // r2 := 0; loop: r2 += 1; if r2 < 10 (signed) goto loop; also unsigned -1 > 1.
    let code = vec![
        c(2, 0),
        c(3, 1),
        c(4, 10),
        Inst::Int {
            op: IntOp::Add,
            dst: 2,
            a: 2,
            b: 3,
        },
        Inst::ICmp {
            cmp: Cmp::Lt,
            signed: true,
            dst: 5,
            a: 2,
            b: 4,
        },
        Inst::Branch {
            cond: 5,
            then: 3,
            els: 6,
        },
        st(2, 0),
        c(0, -1),
        Inst::ICmp {
            cmp: Cmp::Gt,
            signed: false,
            dst: 5,
            a: 0,
            b: 3,
        },
        st(5, 8),
        Inst::Jump { target: 11 },
        Inst::Ret,
    ];
    let (r, img) = both(program(vec![func(&[I64; 6], code)], vec![0; 16]), None);
    assert!(r.is_ok());
    assert_eq!((i64_at(&img, 0), i64_at(&img, 8)), (10, 1));
}

#[test]
fn floats() {
    let code = vec![
        Inst::F64Const { dst: 0, value: 1.5 },
        Inst::F64Const {
            dst: 1,
            value: 0.25,
        },
        Inst::Float {
            op: FloatOp::Div,
            wide: true,
            dst: 2,
            a: 0,
            b: 1,
        },
        Inst::Store {
            src: 2,
            ty: MemTy::F64,
            addr: Addr::abs(0),
        },
        Inst::F32Const { dst: 3, value: 0.1 },
        Inst::Float {
            op: FloatOp::Mul,
            wide: false,
            dst: 4,
            a: 3,
            b: 3,
        },
        Inst::Store {
            src: 4,
            ty: MemTy::F32,
            addr: Addr::abs(8),
        },
        Inst::FResize {
            to_wide: true,
            dst: 2,
            src: 4,
        },
        Inst::Store {
            src: 2,
            ty: MemTy::F64,
            addr: Addr::abs(12),
        },
        Inst::FCmp {
            cmp: Cmp::Lt,
            wide: true,
            dst: 5,
            a: 1,
            b: 0,
        },
        st(5, 20),
        Inst::F64Const {
            dst: 0,
            value: f64::NAN,
        },
        Inst::FCmp {
            cmp: Cmp::Ne,
            wide: true,
            dst: 5,
            a: 0,
            b: 0,
        },
        st(5, 28),
        Inst::Load {
            dst: 4,
            ty: MemTy::F32,
            addr: Addr::abs(8),
        },
        Inst::Builtin {
            op: Builtin::Math(MathFn::Sqrt, false),
            dst: Some(3),
            first: 0,
            count: 1,
            site: 0,
        },
        Inst::Store {
            src: 3,
            ty: MemTy::F32,
            addr: Addr::abs(36),
        },
        Inst::Ret,
    ];
    let mut f = func(&[F64, F64, F64, F32, F32, I64], code);
    f.args = vec![4];
    let (r, img) = both(program(vec![f], vec![0; 40]), None);
    assert!(r.is_ok());
    assert_eq!(f64::from_le_bytes(img[0..8].try_into().unwrap()), 6.0);
    let sq = 0.1f32 * 0.1f32;
    assert_eq!(f32::from_le_bytes(img[8..12].try_into().unwrap()), sq);
    assert_eq!(
        f64::from_le_bytes(img[12..20].try_into().unwrap()),
        sq as f64
    );
    assert_eq!((i64_at(&img, 20), i64_at(&img, 28)), (1, 1));
    assert_eq!(
        f32::from_le_bytes(img[36..40].try_into().unwrap()),
        sq.sqrt()
    );
}

#[test]
fn memory_widths_bits_copy_and_this() {
    let mut init = vec![0u8; 48];
    init[0] = 0xFE; // I8 -2
    init[2..4].copy_from_slice(&0xFFFFu16.to_le_bytes());
    init[40] = 0b0000_0100;
    let code = vec![
        Inst::Load {
            dst: 0,
            ty: MemTy::I8,
            addr: Addr::abs(0),
        },
        st(0, 8),
        Inst::Load {
            dst: 0,
            ty: MemTy::U16,
            addr: Addr::abs(2),
        },
        Inst::Store {
            src: 0,
            ty: MemTy::U32,
            addr: Addr::abs(16),
        },
        Inst::LoadBit {
            dst: 1,
            addr: Addr::abs(40),
            bit: 2,
        },
        Inst::StoreBit {
            src: 1,
            addr: Addr::abs(40),
            bit: 7,
        },
        c(2, 0),
        Inst::StoreBit {
            src: 2,
            addr: Addr::abs(40),
            bit: 2,
        },
        Inst::Copy {
            dst: Addr::abs(24),
            src: Addr::abs(8),
            len: 12,
        },
        Inst::AddrOf {
            dst: 3,
            addr: Addr::this(5),
        },
        Inst::Store {
            src: 3,
            ty: MemTy::I16,
            addr: Addr::reg(3, 36),
        },
        Inst::Ret,
    ];
    let (r, img) = both(program(vec![func(&[I64; 4], code)], init), None);
    assert!(r.is_ok());
    assert_eq!(i64_at(&img, 8), -2);
    assert_eq!(&img[16..20], &[0xFF, 0xFF, 0, 0]);
    // The second run copies the cleared bit 2 into bit 7.
    assert_eq!(img[40], 0);
    assert_eq!(&img[24..36], &img[8..20].to_vec()[..]);
    assert_eq!(&img[41..43], &[5, 0]);
}

#[test]
fn access_outside_the_image_faults_like_the_interpreter() {
    let code = vec![
        c(0, 1000),
        Inst::Load {
            dst: 1,
            ty: MemTy::I32,
            addr: Addr::reg(0, 0),
        },
        Inst::Ret,
    ];
    let (r, _) = both(program(vec![func(&[I64; 2], code)], vec![0; 8]), None);
    let f = r.unwrap_err();
    assert_eq!(
        (f.kind, f.message.as_str()),
        (FaultKind::Function, "load of I32 at 1000 outside the image")
    );
}

#[test]
fn checks() {
    let prog = |v: i64, dynamic: bool| {
        let mut code = vec![c(0, v), c(1, -2), c(2, 5)];
        code.push(if dynamic {
            Inst::CheckDyn {
                kind: CheckKind::Index,
                val: 0,
                lo: 1,
                hi: 2,
                site: 1,
            }
        } else {
            Inst::Check {
                kind: CheckKind::Subrange,
                val: 0,
                lo: -2,
                hi: 5,
                site: 1,
            }
        });
        code.extend([st(0, 0), Inst::Ret]);
        program(vec![func(&[I64; 3], code)], vec![0; 8])
    };
    for v in [-2, 5, 0] {
        assert!(both(prog(v, false), None).0.is_ok());
        assert!(both(prog(v, true), None).0.is_ok());
    }
    let f = both(prog(6, false), None).0.unwrap_err();
    assert_eq!(
        (f.kind, f.message.as_str()),
        (FaultKind::SubrangeViolation, "value 6 outside -2..5")
    );
    let f = both(prog(i64::MIN, true), None).0.unwrap_err();
    assert_eq!(f.kind, FaultKind::IndexOutOfBounds);
    assert_eq!(f.site.location, "t.st:2:5");
}

#[test]
fn calls_with_instances_and_now() {
    // F0 calls F1 with this = 16 twice; F1 increments this.0 and stores now at this.8.
    let f0 = func(
        &[],
        vec![
            Inst::Call {
                func: 1,
                this: Addr::abs(16),
            },
            Inst::Call {
                func: 1,
                this: Addr::abs(16),
            },
            Inst::Ret,
        ],
    );
    let f1 = func(
        &[I64; 3],
        vec![
            Inst::Load {
                dst: 0,
                ty: MemTy::I64,
                addr: Addr::this(0),
            },
            c(1, 1),
            Inst::Int {
                op: IntOp::Add,
                dst: 0,
                a: 0,
                b: 1,
            },
            Inst::Store {
                src: 0,
                ty: MemTy::I64,
                addr: Addr::this(0),
            },
            Inst::Now { dst: 2 },
            Inst::Store {
                src: 2,
                ty: MemTy::I64,
                addr: Addr::this(8),
            },
            Inst::Ret,
        ],
    );
    let (r, img) = both(program(vec![f0, f1], vec![0; 32]), None);
    assert!(r.is_ok());
    assert_eq!((i64_at(&img, 16), i64_at(&img, 24)), (4, 7_000_000));
}

#[test]
fn string_builtins_through_the_shared_implementation() {
    // s1 (at 0, cap 8) := 'ab'; s2 (at 10, cap 8) := CONCAT(s1, s1); len at 20.
    let mut init = vec![0u8; 32];
    init[0..4].copy_from_slice(&[2, 0, b'a', b'b']);
    let mut f = func(
        &[I64; 5],
        vec![
            c(0, 10),
            c(1, 8),
            c(2, 0),
            Inst::Builtin {
                op: Builtin::Str(StrFn::Concat, false),
                dst: None,
                first: 0,
                count: 4,
                site: 0,
            },
            Inst::Builtin {
                op: Builtin::Str(StrFn::Len, false),
                dst: Some(3),
                first: 4,
                count: 1,
                site: 0,
            },
            Inst::Store {
                src: 3,
                ty: MemTy::I16,
                addr: Addr::abs(20),
            },
            c(4, 9),
            Inst::Builtin {
                op: Builtin::Str(StrFn::Mid, false),
                dst: None,
                first: 5,
                count: 5,
                site: 1,
            },
            Inst::Ret,
        ],
    );
    f.args = vec![0, 1, 2, 2, 0, 0, 1, 2, 1, 4];
    let (r, img) = both(program(vec![f], init), None);
    assert_eq!(&img[10..16], &[4, 0, b'a', b'b', b'a', b'b']);
    assert_eq!(&img[20..22], &[4, 0]);
    let f = r.unwrap_err();
    assert_eq!(f.kind, FaultKind::StringIndex);
}

#[test]
fn watchdog_faults_at_the_interpreters_instruction() {
    // An endless loop over several statements; every budget from 1 to 40
    // must stop at the same statement with the same stores done.
    let mut f = func(
        &[I64; 2],
        vec![
            c(1, 1),
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
            st(0, 0),
            Inst::Load {
                dst: 0,
                ty: MemTy::I64,
                addr: Addr::abs(8),
            },
            Inst::Int {
                op: IntOp::Sub,
                dst: 0,
                a: 0,
                b: 1,
            },
            st(0, 8),
            Inst::Jump { target: 1 },
            Inst::Ret,
        ],
    );
    f.stmt_sites = vec![(1, 0), (4, 1)];
    for budget in 1..40 {
        let (r, _) = both(program(vec![f.clone()], vec![0; 16]), Some(budget));
        let fault = r.unwrap_err();
        assert_eq!(fault.kind, FaultKind::Watchdog);
        assert_eq!(
            fault.message,
            format!("watchdog: more than {budget} instructions in one run")
        );
    }
}

#[test]
fn watchdog_counts_instructions_of_callees() {
    let f0 = func(
        &[],
        vec![
            Inst::Call {
                func: 1,
                this: Addr::abs(0),
            },
            Inst::Jump { target: 0 },
        ],
    );
    let f1 = func(&[I64; 1], vec![c(0, 1), st(0, 0), Inst::Ret]);
    for budget in [1, 2, 3, 4, 5, 9, 10, 11] {
        let (r, _) = both(
            program(vec![f0.clone(), f1.clone()], vec![0; 8]),
            Some(budget),
        );
        assert_eq!(r.unwrap_err().kind, FaultKind::Watchdog);
    }
}

#[test]
fn recursion_is_refused_with_a_reason() {
    let f0 = func(
        &[],
        vec![
            Inst::Call {
                func: 0,
                this: Addr::abs(0),
            },
            Inst::Ret,
        ],
    );
    match Jit::new(program(vec![f0], vec![0; 8])) {
        Err(JitError::Unsupported(m)) => assert!(m.contains("recursive call of F"), "{m}"),
        Err(e) => panic!("{e}"),
        Ok(_) => panic!("accepted a recursive program"),
    }
}

#[test]
fn an_invalid_program_is_refused() {
    let f0 = func(&[], vec![Inst::Jump { target: 9 }]);
    assert!(matches!(
        Jit::new(program(vec![f0], vec![0; 8])),
        Err(JitError::Invalid(_))
    ));
}

#[test]
fn inlined_callees_fault_as_themselves() {
    // F1 (small, inlined) divides this.0 by this.8; F0 calls it twice, the
    // second time on an instance whose divisor is 0; and once with a `this`
    // outside the image (the out-of-line checked variant runs).
    let f1 = func(
        &[I64; 3],
        vec![
            Inst::Load {
                dst: 0,
                ty: MemTy::I64,
                addr: Addr::this(0),
            },
            Inst::Load {
                dst: 1,
                ty: MemTy::I64,
                addr: Addr::this(8),
            },
            Inst::Div {
                signed: true,
                dst: 2,
                a: 0,
                b: 1,
                site: 1,
            },
            Inst::Store {
                src: 2,
                ty: MemTy::I64,
                addr: Addr::this(16),
            },
            Inst::Ret,
        ],
    );
    let mut init = vec![0u8; 48];
    init[0] = 9;
    init[8] = 3;
    let prog = |second: u32| {
        let f0 = func(
            &[],
            vec![
                Inst::Call {
                    func: 1,
                    this: Addr::abs(0),
                },
                Inst::Call {
                    func: 1,
                    this: Addr::abs(second),
                },
                Inst::Ret,
            ],
        );
        program(vec![f0, f1.clone()], init.clone())
    };
    let (r, img) = both(prog(24), None);
    let f = r.unwrap_err();
    assert_eq!(
        (f.kind, f.site.location.as_str()),
        (FaultKind::DivisionByZero, "t.st:2:5")
    );
    assert_eq!(i64_at(&img, 16), 3);
    let (r, _) = both(prog(40), None);
    let f = r.unwrap_err();
    assert_eq!(
        (f.kind, f.message.as_str()),
        (FaultKind::Function, "load of I64 at 48 outside the image")
    );
    assert_eq!(f.site.pou, "F");
    // The watchdog inside the inlined callee, at every budget.
    // Call, 5 instructions, Call, 5 instructions, Ret: 13.
    for budget in 1..16 {
        let (r, _) = both(prog(0), Some(budget));
        assert_eq!(r.is_err(), budget < 13, "budget {budget}");
    }
}
