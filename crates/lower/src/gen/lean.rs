//! Whole-program passes after code generation that make the IR leaner for
//! every backend (each dispatched instruction costs the interpreter time;
//! each store costs the JIT a bounds check):
//! - The hidden EN/ENO bytes of function-block instances (what `fb.ENO`
//!   reads) are written after every call; when no code anywhere reads or
//!   writes `fb.EN`/`fb.ENO` of a block without a declared ENO, nothing can
//!   observe them (they are not in the symbol table), so the stores go.
//! - Pure instructions whose result register nothing reads go (the dummy
//!   result of an FB call, constants made for removed stores).

use super::peep;
use automat_ir::code::{Addr, Base, Func, Inst, MemTy, Reg};
use rustc_hash::FxHashSet;

/// What code generation recorded about the hidden EN/ENO bytes.
#[derive(Default)]
pub struct Hidden {
    /// Some code accessed `fb.EN` / `fb.ENO` through the hidden bytes.
    pub read: bool,
    /// (function index, address) of every hidden-byte store after a call.
    pub stores: FxHashSet<(u32, Addr)>,
}

/// Applies the passes to every function (`funcs[i]` is POU `i`).
pub fn finish(funcs: &mut [Func], hidden: &Hidden) {
    for (i, f) in funcs.iter_mut().enumerate() {
        let mut changed = false;
        if !hidden.read && !hidden.stores.is_empty() {
            let keep: Vec<bool> = f
                .code
                .iter()
                .map(|inst| {
                    !matches!(inst, Inst::Store { ty: MemTy::U8, addr, .. }
                        if hidden.stores.contains(&(i as u32, *addr)))
                })
                .collect();
            changed |= peep::remove(f, &keep);
        }
        // Each round removes at least one instruction or stops.
        while drop_unread(f) {
            changed = true;
        }
        if changed {
            peep::tidy(f);
        }
    }
}

/// The registers `inst` reads.
fn reads(inst: &Inst, f: &Func, out: &mut Vec<Reg>) {
    let base = |a: &Addr, out: &mut Vec<Reg>| {
        if let Base::Reg(r) = a.base {
            out.push(r);
        }
    };
    match inst {
        Inst::IConst { .. }
        | Inst::F32Const { .. }
        | Inst::F64Const { .. }
        | Inst::Now { .. }
        | Inst::Jump { .. }
        | Inst::Ret => {}
        Inst::Mov { src, .. }
        | Inst::Neg { src, .. }
        | Inst::Not { src, .. }
        | Inst::Wrap { src, .. }
        | Inst::FResize { src, .. } => out.push(*src),
        Inst::Load { addr, .. } | Inst::LoadBit { addr, .. } | Inst::AddrOf { addr, .. } => {
            base(addr, out)
        }
        Inst::Store { src, addr, .. } | Inst::StoreBit { src, addr, .. } => {
            out.push(*src);
            base(addr, out);
        }
        Inst::Copy { dst, src, .. } => {
            base(dst, out);
            base(src, out);
        }
        Inst::Int { a, b, .. }
        | Inst::Div { a, b, .. }
        | Inst::Rem { a, b, .. }
        | Inst::ICmp { a, b, .. }
        | Inst::Float { a, b, .. }
        | Inst::FCmp { a, b, .. } => out.extend([*a, *b]),
        Inst::Shift { a, n, .. } => out.extend([*a, *n]),
        Inst::Check { val, .. } => out.push(*val),
        Inst::CheckDyn { val, lo, hi, .. } => out.extend([*val, *lo, *hi]),
        Inst::Builtin { first, count, .. } => out.extend(f.builtin_args(*first, *count)),
        Inst::Branch { cond, .. } => out.push(*cond),
        Inst::Call { this, .. } => base(this, out),
    }
}

/// The register a side-effect-free, never-faulting instruction writes.
fn pure_dst(inst: &Inst) -> Option<Reg> {
    match *inst {
        Inst::IConst { dst, .. }
        | Inst::F32Const { dst, .. }
        | Inst::F64Const { dst, .. }
        | Inst::Mov { dst, .. }
        | Inst::AddrOf { dst, .. }
        | Inst::Int { dst, .. }
        | Inst::Neg { dst, .. }
        | Inst::Not { dst, .. }
        | Inst::Wrap { dst, .. }
        | Inst::Shift { dst, .. }
        | Inst::ICmp { dst, .. }
        | Inst::Float { dst, .. }
        | Inst::FCmp { dst, .. }
        | Inst::FResize { dst, .. } => Some(dst),
        _ => None,
    }
}

/// Removes pure instructions whose result no instruction reads; whether
/// any went.
fn drop_unread(f: &mut Func) -> bool {
    let mut read = vec![false; f.regs.len()];
    let mut buf = Vec::new();
    for inst in &f.code {
        buf.clear();
        reads(inst, f, &mut buf);
        for r in &buf {
            if let Some(x) = read.get_mut(*r as usize) {
                *x = true;
            }
        }
    }
    let keep: Vec<bool> = f
        .code
        .iter()
        .map(|inst| pure_dst(inst).is_none_or(|d| read.get(d as usize).copied().unwrap_or(true)))
        .collect();
    peep::remove(f, &keep)
}

#[cfg(test)]
mod tests {
    use super::*;
    use automat_ir::code::{IntOp, RegClass};

    #[test]
    fn unread_results_and_hidden_stores_go_jumps_follow() {
        let mut f = Func::new("F");
        f.regs = vec![RegClass::I64; 4];
        f.code = vec![
            Inst::IConst { dst: 0, value: 1 },
            Inst::Store {
                src: 0,
                ty: MemTy::U8,
                addr: Addr::abs(8),
            },
            Inst::IConst { dst: 1, value: 5 },
            Inst::Int {
                op: IntOp::Add,
                dst: 2,
                a: 1,
                b: 1,
            },
            Inst::IConst { dst: 3, value: 7 },
            Inst::Branch {
                cond: 3,
                then: 2,
                els: 6,
            },
            Inst::Ret,
        ];
        f.stmt_sites = vec![(0, 0), (2, 1)];
        let mut h = Hidden::default();
        h.stores.insert((0, Addr::abs(8)));
        let mut funcs = vec![f];
        finish(&mut funcs, &h);
        let f = &funcs[0];
        assert_eq!(
            f.code,
            vec![
                Inst::IConst { dst: 3, value: 7 },
                Inst::Branch {
                    cond: 3,
                    then: 0,
                    els: 2
                },
                Inst::Ret,
            ]
        );
        // A hidden byte some code reads stays.
        let mut g = Func::new("G");
        g.regs = vec![RegClass::I64];
        g.code = vec![
            Inst::IConst { dst: 0, value: 1 },
            Inst::Store {
                src: 0,
                ty: MemTy::U8,
                addr: Addr::abs(8),
            },
            Inst::Ret,
        ];
        h.read = true;
        let mut funcs = vec![g.clone()];
        finish(&mut funcs, &h);
        assert_eq!(funcs[0].code, g.code);
    }
}
