//! Which IR registers live inside one basic block, so that they can share
//! Cranelift variables with the block-local registers of other blocks.
//!
//! Why: lowering gives every expression fresh registers, and Cranelift's
//! SSA builder keeps, per variable, a table indexed by block. With one
//! variable per register a body of n statements costs n registers × n
//! blocks of memory (7 GB for 20,000 statements). A register that is
//! written in a block before any read there and never touched in another
//! block needs no value from elsewhere: it can use the variable of a pool
//! slot, the k-th such register of its class in that block. The pool has
//! as many variables per class as the busiest block needs.
//!
//! Conservative where unsure: a register read before it is written in its
//! block, or touched in two blocks, or used by a builtin (whose argument
//! and result registers are handled through slots), keeps its own variable.

use automat_ir::code::{Addr, Base, Func, Inst, Reg};

/// Registers `inst` reads and the one it writes; `false` when the
/// instruction's registers must all keep variables of their own.
pub(crate) fn access(inst: &Inst, reads: &mut Vec<Reg>) -> (Option<Reg>, bool) {
    let base = |a: &Addr, out: &mut Vec<Reg>| {
        if let Base::Reg(r) = a.base {
            out.push(r);
        }
    };
    let w = match *inst {
        Inst::IConst { dst, .. }
        | Inst::F32Const { dst, .. }
        | Inst::F64Const { dst, .. }
        | Inst::Now { dst } => Some(dst),
        Inst::Mov { dst, src }
        | Inst::Neg { dst, src }
        | Inst::Not { dst, src }
        | Inst::Wrap { dst, src, .. }
        | Inst::FResize { dst, src, .. } => {
            reads.push(src);
            Some(dst)
        }
        Inst::Load { dst, addr, .. }
        | Inst::LoadBit { dst, addr, .. }
        | Inst::AddrOf { dst, addr } => {
            base(&addr, reads);
            Some(dst)
        }
        Inst::Store { src, addr, .. } | Inst::StoreBit { src, addr, .. } => {
            reads.push(src);
            base(&addr, reads);
            None
        }
        Inst::Copy { dst, src, .. } => {
            base(&dst, reads);
            base(&src, reads);
            None
        }
        Inst::Int { dst, a, b, .. }
        | Inst::Div { dst, a, b, .. }
        | Inst::Rem { dst, a, b, .. }
        | Inst::ICmp { dst, a, b, .. }
        | Inst::Float { dst, a, b, .. }
        | Inst::FCmp { dst, a, b, .. }
        | Inst::Shift { dst, a, n: b, .. } => {
            reads.extend([a, b]);
            Some(dst)
        }
        Inst::Check { val, .. } => {
            reads.push(val);
            None
        }
        Inst::CheckDyn { val, lo, hi, .. } => {
            reads.extend([val, lo, hi]);
            None
        }
        Inst::Branch { cond, .. } => {
            reads.push(cond);
            None
        }
        Inst::Call { this, .. } => {
            base(&this, reads);
            None
        }
        Inst::Jump { .. } | Inst::Ret => None,
        Inst::Builtin { .. } => return (None, false),
    };
    (w, true)
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Seen {
    Never,
    /// Written first in this block (block number).
    In(u32),
    Shared,
}

/// Per register of `f`: `Some(k)` when it is block-local, `k` its slot
/// among the block-local registers of its class in its block. `lead` marks
/// the instructions that start a block.
pub fn slots(f: &Func, lead: &[bool]) -> Vec<Option<u32>> {
    let n = f.regs.len();
    let mut seen = vec![Seen::Never; n];
    let mut block = 0u32;
    let mut reads = Vec::new();
    for (pc, inst) in f.code.iter().enumerate() {
        if pc > 0 && lead.get(pc).copied().unwrap_or(true) {
            block += 1;
        }
        reads.clear();
        let (write, ok) = access(inst, &mut reads);
        if !ok {
            if let Inst::Builtin {
                dst, first, count, ..
            } = *inst
            {
                for &r in f.builtin_args(first, count).iter().chain(dst.as_ref()) {
                    if let Some(s) = seen.get_mut(r as usize) {
                        *s = Seen::Shared;
                    }
                }
            }
            continue;
        }
        for &r in &reads {
            if let Some(s) = seen.get_mut(r as usize) {
                if *s != Seen::In(block) {
                    *s = Seen::Shared;
                }
            }
        }
        if let Some(s) = write.and_then(|w| seen.get_mut(w as usize)) {
            match *s {
                Seen::Never => *s = Seen::In(block),
                Seen::In(b) if b == block => {}
                _ => *s = Seen::Shared,
            }
        }
    }
    // Slots in order of register number within each block and class.
    let mut next: std::collections::HashMap<(u32, u8), u32> = std::collections::HashMap::new();
    seen.iter()
        .zip(&f.regs)
        .map(|(s, class)| match *s {
            Seen::In(b) => {
                let k = next.entry((b, *class as u8)).or_insert(0);
                let slot = *k;
                *k += 1;
                Some(slot)
            }
            _ => None,
        })
        .collect()
}
