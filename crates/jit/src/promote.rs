//! Scalar variables of the current instance kept in Cranelift variables
//! across a function, and the facts that let array accesses skip checks.
//!
//! Why: lowering reads and writes every variable through the image, so a
//! loop counter's value went through memory on each iteration (a store,
//! then a load on the loop-carried path: several cycles per iteration
//! where native code spends one). Here a promoted slot is still stored to
//! the image on every assignment (the image stays exact after each
//! instruction, so faults see what the interpreter leaves), but its loads
//! read the variable, which always holds what the image holds: it is
//! (re)loaded at the entry and after anything that may write the slot
//! some other way (calls, copies, builtins, absolute stores, register
//! stores not proved elsewhere).
//!
//! A slot is promoted only when every `This` access overlapping its bytes
//! in the function is a `Load`/`Store` of exactly its offset and type, and
//! only in code whose `This` accesses are proved inside the image (no
//! check to keep). Block-local facts (`Fact`): after `Check lo..hi` a
//! register's value is in that range; `AddrOf This+k` plus such an index
//! (times a constant) is `this + [a, b]`. A register access whose every
//! byte lies in `this .. this + extent` (proved at the entry) needs no
//! bounds check and cannot touch a slot outside its range.

use automat_ir::code::{Base, Func, Inst, IntOp, MemTy, Reg};
use std::collections::HashMap;

/// Promote at most this many slots per function: each is reloaded after a
/// call or an unproved store.
pub const MAX_SLOTS: usize = 32;

/// Promote nothing in a function longer than this many IR instructions.
/// A promoted slot is a Cranelift variable live across the whole function,
/// and the register allocator's time grows faster than linearly with the
/// length of such live ranges. A body of 20,000 statements took 1.41 s to
/// compile with promotion and 0.69 s without (`benches/compile_size.rs`).
/// Promotion pays in loops, and the loops of a body that long are a small
/// part of it, so nothing measurable is lost. The compute kernels are
/// hundreds of instructions long.
pub const MAX_CODE: usize = 16_384;

/// What is known about a register inside the current block.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fact {
    /// Its value is in `lo..=hi`.
    Range(i64, i64),
    /// It holds the absolute offset `this + [lo, hi]`.
    This(i64, i64),
}

/// The slots worth promoting in `f`: (offset, type), most used first.
pub fn slots(f: &Func) -> Vec<(u32, MemTy)> {
    if f.code.len() > MAX_CODE {
        return Vec::new();
    }
    // Every This access: (offset, size, exact scalar (ty) or None).
    let mut accesses: Vec<(u32, u32, Option<MemTy>)> = Vec::new();
    for inst in &f.code {
        match *inst {
            Inst::Load { ty, addr, .. } | Inst::Store { ty, addr, .. }
                if addr.base == Base::This =>
            {
                accesses.push((addr.offset, ty.size(), Some(ty)))
            }
            Inst::LoadBit { addr, .. } | Inst::StoreBit { addr, .. } if addr.base == Base::This => {
                accesses.push((addr.offset, 1, None))
            }
            Inst::Copy { dst, src, len } => {
                for a in [dst, src] {
                    if a.base == Base::This {
                        accesses.push((a.offset, len, None));
                    }
                }
            }
            _ => {}
        }
    }
    let mut uses: HashMap<(u32, MemTy), usize> = HashMap::new();
    for &(off, _, ty) in &accesses {
        if let Some(ty) = ty {
            *uses.entry((off, ty)).or_insert(0) += 1;
        }
    }
    let overlaps = |a: u32, n: u32, b: u32, m: u32| {
        (a as u64) < b as u64 + m as u64 && (b as u64) < a as u64 + n as u64
    };
    let mut out: Vec<((u32, MemTy), usize)> = uses
        .into_iter()
        .filter(|&((off, ty), n)| {
            n >= 2
                && accesses.iter().all(|&(o, s, t)| {
                    !overlaps(off, ty.size(), o, s) || (o == off && t == Some(ty))
                })
        })
        .collect();
    out.sort_by(|a, b| b.1.cmp(&a.1).then(a.0 .0.cmp(&b.0 .0)));
    out.into_iter().take(MAX_SLOTS).map(|(k, _)| k).collect()
}

/// The fact `inst` establishes for its destination, from the facts of its
/// operands (`None`: nothing known).
/// `extent`: how far past `this` is proved inside the image; an address
/// `this + k` beyond it is not tracked (its u32 sum might wrap).
pub fn derive(inst: &Inst, facts: &HashMap<Reg, Fact>, extent: u64) -> Option<(Reg, Fact)> {
    let fact = |r: Reg| facts.get(&r).copied();
    match *inst {
        Inst::IConst { dst, value } => Some((dst, Fact::Range(value, value))),
        Inst::Mov { dst, src } => fact(src).map(|f| (dst, f)),
        Inst::AddrOf { dst, addr } if addr.base == Base::This && addr.offset as u64 <= extent => {
            let k = addr.offset as i64;
            Some((dst, Fact::This(k, k)))
        }
        Inst::Int { op, dst, a, b } => {
            let (fa, fb) = (fact(a)?, fact(b)?);
            let f = match (op, fa, fb) {
                (IntOp::Add, Fact::Range(a0, a1), Fact::Range(b0, b1)) => {
                    Fact::Range(a0.checked_add(b0)?, a1.checked_add(b1)?)
                }
                (IntOp::Add, Fact::This(a0, a1), Fact::Range(b0, b1))
                | (IntOp::Add, Fact::Range(b0, b1), Fact::This(a0, a1)) => {
                    Fact::This(a0.checked_add(b0)?, a1.checked_add(b1)?)
                }
                (IntOp::Sub, Fact::Range(a0, a1), Fact::Range(b0, b1)) => {
                    Fact::Range(a0.checked_sub(b1)?, a1.checked_sub(b0)?)
                }
                (IntOp::Mul, Fact::Range(a0, a1), Fact::Range(c, c2)) if c == c2 && c >= 0 => {
                    Fact::Range(a0.checked_mul(c)?, a1.checked_mul(c)?)
                }
                (IntOp::Mul, Fact::Range(c, c2), Fact::Range(a0, a1)) if c == c2 && c >= 0 => {
                    Fact::Range(a0.checked_mul(c)?, a1.checked_mul(c)?)
                }
                _ => return None,
            };
            Some((dst, f))
        }
        _ => None,
    }
}

/// The register `inst` writes, if any (facts about it end there).
pub fn writes(inst: &Inst) -> Option<Reg> {
    let mut reads = Vec::new();
    match *inst {
        Inst::Builtin { dst, .. } => dst,
        _ => crate::locals::access(inst, &mut reads).0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use automat_ir::code::{Addr, RegClass};

    fn func(code: Vec<Inst>) -> Func {
        Func {
            code,
            regs: vec![RegClass::I64; 8],
            ..Func::default()
        }
    }

    fn load(dst: Reg, ty: MemTy, off: u32) -> Inst {
        Inst::Load {
            dst,
            ty,
            addr: Addr::this(off),
        }
    }

    fn store(src: Reg, ty: MemTy, off: u32) -> Inst {
        Inst::Store {
            src,
            ty,
            addr: Addr::this(off),
        }
    }

    #[test]
    fn slots_are_exact_and_reused() {
        let f = func(vec![
            load(0, MemTy::I32, 8),
            store(0, MemTy::I32, 8),
            // Used once: not worth it.
            load(1, MemTy::I32, 16),
            // Overlapped by a narrower access: not promoted.
            load(2, MemTy::I32, 24),
            store(2, MemTy::I32, 24),
            load(3, MemTy::U8, 25),
            // A bit access on the same byte: not promoted.
            load(4, MemTy::U8, 32),
            store(4, MemTy::U8, 32),
            Inst::LoadBit {
                dst: 5,
                addr: Addr::this(32),
                bit: 1,
            },
            Inst::Ret,
        ]);
        assert_eq!(slots(&f), vec![(8, MemTy::I32)]);
    }

    #[test]
    fn a_function_longer_than_max_code_promotes_nothing() {
        // A slot loaded and stored in each of many statements.
        let body = |n: usize| {
            let mut code: Vec<Inst> = (0..n)
                .flat_map(|_| [load(0, MemTy::I32, 8), store(0, MemTy::I32, 8)])
                .collect();
            code.push(Inst::Ret);
            func(code)
        };
        assert_eq!(slots(&body(MAX_CODE / 2 - 1)), vec![(8, MemTy::I32)]);
        assert_eq!(slots(&body(MAX_CODE / 2 + 1)), vec![]);
    }

    #[test]
    fn facts_follow_index_arithmetic() {
        let mut facts = HashMap::new();
        facts.insert(1, Fact::Range(0, 9));
        let d = |i: Inst, f: &HashMap<Reg, Fact>| derive(&i, f, 100);
        assert_eq!(
            d(
                Inst::AddrOf {
                    dst: 2,
                    addr: Addr::this(40)
                },
                &facts
            ),
            Some((2, Fact::This(40, 40)))
        );
        // Beyond the proved extent an address is not tracked.
        assert_eq!(
            d(
                Inst::AddrOf {
                    dst: 2,
                    addr: Addr::this(101)
                },
                &facts
            ),
            None
        );
        facts.insert(2, Fact::This(40, 40));
        facts.insert(3, Fact::Range(4, 4));
        let mul = Inst::Int {
            op: IntOp::Mul,
            dst: 4,
            a: 1,
            b: 3,
        };
        assert_eq!(d(mul, &facts), Some((4, Fact::Range(0, 36))));
        facts.insert(4, Fact::Range(0, 36));
        let add = Inst::Int {
            op: IntOp::Add,
            dst: 5,
            a: 2,
            b: 4,
        };
        assert_eq!(d(add, &facts), Some((5, Fact::This(40, 76))));
        // An unknown operand: nothing known.
        let add = Inst::Int {
            op: IntOp::Add,
            dst: 5,
            a: 2,
            b: 7,
        };
        assert_eq!(d(add, &facts), None);
    }
}
