//! Two-armed `IF`s that only assign one variable, compiled without a jump.
//!
//! Why: a branch the processor cannot predict (the CRC-32's
//! `IF (crc AND 1) = 1 THEN crc := SHR(crc, 1) XOR poly; ELSE
//! crc := SHR(crc, 1);` on data bits) costs a pipeline flush on about every second run, more
//! than both arms together. When each arm is one basic block of
//! instructions that cannot fault or be observed (constants, moves,
//! integer and float arithmetic, shifts, compares, loads of the instance)
//! ending in a store of the same instance slot, both arms are computed
//! and the stored value is chosen by the condition (a `select`, a `cmov`
//! on x86). What the program can observe is the same: the one store
//! happens with the chosen arm's value, no arm can fault, and registers
//! the arms write live only inside their block (`locals.rs`), so no later
//! code reads them. Only in code without the instruction budget (whose
//! count per block would differ) and whose `This` accesses need no check
//! (checked by the caller).

use automat_ir::code::{Base, Inst};
use std::collections::HashMap;
use std::ops::Range;

/// One arm: its pure instructions, then the index of its store.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Arm {
    pub pure: Range<usize>,
    pub store: usize,
}

/// A branch both of whose arms store the same slot, and where they join.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diamond {
    pub then: Arm,
    pub els: Arm,
    pub join: u32,
}

fn pure(inst: &Inst) -> bool {
    match *inst {
        Inst::IConst { .. }
        | Inst::F32Const { .. }
        | Inst::F64Const { .. }
        | Inst::Mov { .. }
        | Inst::Int { .. }
        | Inst::Neg { .. }
        | Inst::Not { .. }
        | Inst::Wrap { .. }
        | Inst::Shift { .. }
        | Inst::ICmp { .. }
        | Inst::Float { .. }
        | Inst::FCmp { .. }
        | Inst::FResize { .. } => true,
        Inst::Load { addr, .. } => addr.base == Base::This,
        _ => false,
    }
}

/// The arm starting at `start` (a block only the branch enters): its
/// pure part, its store and where it continues.
fn arm(code: &[Inst], lead: &[bool], local: &[Option<u32>], start: usize) -> Option<(Arm, u32)> {
    // Entered only by the branch: the instruction before ends a block
    // without falling through.
    if !matches!(
        code.get(start.checked_sub(1)?)?,
        Inst::Jump { .. } | Inst::Branch { .. } | Inst::Ret
    ) {
        return None;
    }
    let mut end = start + 1;
    while end < code.len() && !lead.get(end).copied().unwrap_or(true) {
        end += 1;
    }
    let (last, next) = match code.get(end - 1)? {
        Inst::Jump { target } => (end - 1, *target),
        i if !matches!(i, Inst::Branch { .. } | Inst::Ret | Inst::Call { .. }) => (end, end as u32),
        _ => return None,
    };
    let store = last.checked_sub(1)?;
    // Its source register must be the arm's own too: the select writes it.
    let local_reg = |r: u32| local.get(r as usize).copied().flatten().is_some();
    match code.get(store)? {
        Inst::Store { addr, src, .. }
            if store >= start && addr.base == Base::This && local_reg(*src) => {}
        _ => return None,
    }
    let mut reads = Vec::new();
    for inst in code.get(start..store)? {
        if !pure(inst) {
            return None;
        }
        let (w, ok) = crate::locals::access(inst, &mut reads);
        // Every register it writes lives only in this block.
        if !ok || w.is_some_and(|r| !local_reg(r)) {
            return None;
        }
    }
    Some((
        Arm {
            pure: start..store,
            store,
        },
        next,
    ))
}

/// Every branch of `code` that can become a select, by its index.
pub fn diamonds(code: &[Inst], lead: &[bool], local: &[Option<u32>]) -> HashMap<u32, Diamond> {
    // How many jumps and branches enter each instruction.
    let mut entries = vec![0u32; code.len() + 1];
    for inst in code {
        let targets = match *inst {
            Inst::Jump { target } => [Some(target), None],
            Inst::Branch { then, els, .. } => [Some(then), Some(els)],
            _ => [None, None],
        };
        for t in targets.into_iter().flatten() {
            if let Some(n) = entries.get_mut(t as usize) {
                *n += 1;
            }
        }
    }
    let mut out = HashMap::new();
    for (pc, inst) in code.iter().enumerate() {
        let Inst::Branch { then, els, .. } = *inst else {
            continue;
        };
        let once = |t: u32| t as usize > pc && entries.get(t as usize) == Some(&1);
        if then == els || !once(then) || !once(els) {
            continue;
        }
        let (Some((t, tj)), Some((e, ej))) = (
            arm(code, lead, local, then as usize),
            arm(code, lead, local, els as usize),
        ) else {
            continue;
        };
        let same = match (code.get(t.store), code.get(e.store)) {
            (
                Some(Inst::Store { ty: a, addr: x, .. }),
                Some(Inst::Store { ty: b, addr: y, .. }),
            ) => a == b && x == y,
            _ => false,
        };
        if same && tj == ej {
            out.insert(
                pc as u32,
                Diamond {
                    then: t,
                    els: e,
                    join: tj,
                },
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use automat_ir::code::{Addr, Func, IntOp, MemTy, RegClass, ShiftOp};

    fn shr(dst: u32, a: u32, n: u32) -> Inst {
        Inst::Shift {
            op: ShiftOp::Shr,
            width: 32,
            dst,
            a,
            n,
        }
    }

    /// `IF c THEN x := SHR(x, 1) XOR k; ELSE x := SHR(x, 1); END_IF;`
    /// with `x` at `this + 4`, as lowering emits it.
    fn crc_step(else_store: Addr) -> Func {
        let x = Addr::this(4);
        let load = |dst| Inst::Load {
            dst,
            ty: MemTy::U32,
            addr: x,
        };
        let code = vec![
            load(0),
            Inst::Branch {
                cond: 0,
                then: 2,
                els: 9,
            },
            // 2..9: the then arm, ending in a jump to the join.
            load(1),
            Inst::IConst { dst: 2, value: 1 },
            shr(3, 1, 2),
            Inst::IConst {
                dst: 4,
                value: 0xEDB8_8320,
            },
            Inst::Int {
                op: IntOp::Xor,
                dst: 5,
                a: 3,
                b: 4,
            },
            Inst::Store {
                src: 5,
                ty: MemTy::U32,
                addr: x,
            },
            Inst::Jump { target: 13 },
            // 9..13: the else arm, falling into the join.
            load(6),
            Inst::IConst { dst: 7, value: 1 },
            shr(8, 6, 7),
            Inst::Store {
                src: 8,
                ty: MemTy::U32,
                addr: else_store,
            },
            Inst::Ret,
        ];
        Func {
            code,
            regs: vec![RegClass::I64; 9],
            ..Func::default()
        }
    }

    fn found(f: &Func) -> HashMap<u32, Diamond> {
        let lead = crate::translate::leaders(&f.code);
        diamonds(&f.code, &lead, &crate::locals::slots(f, &lead))
    }

    #[test]
    fn two_stores_of_one_slot_become_a_select() {
        let d = found(&crc_step(Addr::this(4)));
        let want = Diamond {
            then: Arm {
                pure: 2..7,
                store: 7,
            },
            els: Arm {
                pure: 9..12,
                store: 12,
            },
            join: 13,
        };
        assert_eq!(d.get(&1), Some(&want));
        assert_eq!(d.len(), 1);
    }

    #[test]
    fn arms_storing_different_slots_keep_the_branch() {
        assert!(found(&crc_step(Addr::this(8))).is_empty());
    }

    #[test]
    fn an_arm_that_can_fault_keeps_the_branch() {
        let mut f = crc_step(Addr::this(4));
        if let Some(i) = f.code.get_mut(4) {
            *i = Inst::Div {
                signed: false,
                dst: 3,
                a: 1,
                b: 2,
                site: 0,
            };
        }
        assert!(found(&f).is_empty());
    }
}
