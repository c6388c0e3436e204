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

/// Calls `visit(block, inst, regs, write)` for each instruction of `f` with
/// the number of its basic block (`lead` marks the instructions that start
/// one). `regs` are the registers it reads and `write` the one it writes;
/// for a builtin, `regs` are its argument and result registers and `write`
/// is `None`, and `own` is set: they must keep variables of their own.
fn walk(f: &Func, lead: &[bool], mut visit: impl FnMut(u32, &Inst, &[Reg], Option<Reg>, bool)) {
    let mut block = 0u32;
    let mut reads = Vec::new();
    for (pc, inst) in f.code.iter().enumerate() {
        if pc > 0 && lead.get(pc).copied().unwrap_or(true) {
            block += 1;
        }
        reads.clear();
        let (write, ok) = access(inst, &mut reads);
        if ok {
            visit(block, inst, &reads, write, false);
        } else if let Inst::Builtin {
            dst, first, count, ..
        } = *inst
        {
            reads.extend(f.builtin_args(first, count).iter().chain(dst.as_ref()));
            visit(block, inst, &reads, None, true);
        }
    }
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
    walk(f, lead, |block, _, reads, write, own| {
        for &r in reads {
            if let Some(s) = seen.get_mut(r as usize) {
                if own || *s != Seen::In(block) {
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
    });
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

/// Per register of `f` that is not block-local (`slots` gives it no slot):
/// `Some(k)`, the k-th variable of its class in a second pool shared by
/// registers whose live blocks do not overlap; `None` for a register that
/// keeps a variable of its own (one used by a builtin, or every register
/// when the loops are too tangled to work out cheaply).
///
/// Why: a register touched in several blocks (a FOR loop's bound, a value
/// carried over an IF) kept its own variable, and the SSA builder's table
/// per variable is indexed by block, so a body of many loops cost
/// registers × blocks of memory (700 MB for 20,000 statements with 2,000
/// FOR loops). Lowering writes every register before it reads it on every
/// path, so two registers whose live ranges do not overlap can share one
/// variable. A register's live range is taken as the blocks from the
/// first to the last that touch it, in code order, widened to the whole of
/// every loop (a backward jump's target to its source) it overlaps but
/// does not contain, since its value may go round that loop's back edge.
pub fn shared(f: &Func, lead: &[bool]) -> Vec<Option<u32>> {
    let n = f.regs.len();
    let local = slots(f, lead);
    // The block of each instruction, each register's first and last
    // block, the registers a builtin touches, and the loops.
    let mut span: Vec<Option<(u32, u32)>> = vec![None; n];
    let mut own = vec![false; n];
    let mut block_of = Vec::with_capacity(f.code.len() + 1);
    let mut block = 0u32;
    for pc in 0..=f.code.len() {
        if pc > 0 && lead.get(pc).copied().unwrap_or(true) {
            block += 1;
        }
        block_of.push(block);
    }
    let blocks = block as usize + 1;
    let mut loops: Vec<(u32, u32)> = Vec::new();
    walk(f, lead, |b, inst, reads, write, builtin| {
        for &r in reads.iter().chain(write.as_ref()) {
            if builtin {
                if let Some(o) = own.get_mut(r as usize) {
                    *o = true;
                }
            } else if let Some(s) = span.get_mut(r as usize) {
                *s = Some(s.map_or((b, b), |(lo, hi)| (lo.min(b), hi.max(b))));
            }
        }
        let targets = match *inst {
            Inst::Jump { target } => [Some(target), None],
            Inst::Branch { then, els, .. } => [Some(then), Some(els)],
            _ => [None, None],
        };
        for t in targets.into_iter().flatten() {
            if let Some(&h) = block_of.get(t as usize) {
                if h <= b {
                    loops.push((h, b));
                }
            }
        }
    });
    // Per block, the widest loop containing it: [lo, hi]. Bounded work,
    // else every register keeps its own variable (as before).
    let mut cover: Vec<(u32, u32)> = (0..blocks as u32).map(|x| (x, x)).collect();
    let work: usize = loops.iter().map(|&(h, l)| (l - h) as usize + 1).sum();
    if work > 64 * (blocks + f.code.len()) {
        return vec![None; n];
    }
    for &(h, l) in &loops {
        for c in cover.iter_mut().take(l as usize + 1).skip(h as usize) {
            *c = (c.0.min(h), c.1.max(l));
        }
    }
    let widen = |(mut lo, mut hi): (u32, u32)| {
        // Each round takes in the loops containing an end; the range only
        // grows, so this stops.
        loop {
            let (a, b) = (cover.get(lo as usize), cover.get(hi as usize));
            let nlo = lo.min(a.map_or(lo, |c| c.0)).min(b.map_or(lo, |c| c.0));
            let nhi = hi.max(a.map_or(hi, |c| c.1)).max(b.map_or(hi, |c| c.1));
            if (nlo, nhi) == (lo, hi) {
                return (lo, hi);
            }
            (lo, hi) = (nlo, nhi);
        }
    };
    // Interval colouring per class: registers by start; a variable is
    // free again once the range that held it ended before this start.
    let mut order: Vec<(u32, u32, usize)> = (0..n)
        .filter(|&r| local.get(r).copied().flatten().is_none() && !own[r])
        .filter_map(|r| span[r].map(&widen).map(|(lo, hi)| (lo, hi, r)))
        .collect();
    order.sort_unstable();
    let mut out = vec![None; n];
    // Per class: (end, variable) of the variables in use, and the free ones.
    let mut busy: [std::collections::BinaryHeap<std::cmp::Reverse<(u32, u32)>>; 3] =
        Default::default();
    let mut free: [Vec<u32>; 3] = Default::default();
    let mut count = [0u32; 3];
    for (lo, hi, r) in order {
        let c = f.regs.get(r).map_or(0, |c| *c as usize).min(2);
        let (Some(busy), Some(free), Some(count)) =
            (busy.get_mut(c), free.get_mut(c), count.get_mut(c))
        else {
            continue;
        };
        while let Some(&std::cmp::Reverse((end, v))) = busy.peek() {
            if end >= lo {
                break;
            }
            busy.pop();
            free.push(v);
        }
        let v = free.pop().unwrap_or_else(|| {
            *count += 1;
            *count - 1
        });
        busy.push(std::cmp::Reverse((hi, v)));
        out[r] = Some(v);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use automat_ir::code::RegClass;

    fn func(code: Vec<Inst>, regs: usize) -> Func {
        Func {
            code,
            regs: vec![RegClass::I64; regs],
            ..Func::default()
        }
    }

    fn konst(dst: Reg) -> Inst {
        Inst::IConst { dst, value: 1 }
    }

    fn mov(dst: Reg, src: Reg) -> Inst {
        Inst::Mov { dst, src }
    }

    #[test]
    fn registers_over_disjoint_blocks_share_a_variable() {
        // r0 lives over blocks 0-1, r1 over blocks 2-3: one variable.
        // r2 overlaps r1 (blocks 3-4): a second one.
        let f = func(
            vec![
                konst(0),
                Inst::Jump { target: 2 },
                mov(3, 0),
                Inst::Jump { target: 4 },
                konst(1),
                Inst::Jump { target: 6 },
                mov(4, 1),
                konst(2),
                Inst::Jump { target: 9 },
                mov(5, 2),
                Inst::Ret,
            ],
            6,
        );
        let lead = crate::translate::leaders(&f.code);
        let s = shared(&f, &lead);
        assert_eq!((s[0], s[1], s[2]), (Some(0), Some(0), Some(1)));
        // Block-local registers take no variable of this pool.
        assert_eq!((s[3], s[4], s[5]), (None, None, None));
    }

    #[test]
    fn a_register_carried_round_a_loop_keeps_its_variable_over_the_loop() {
        // r0 is written before the loop (block 0) and read at its header
        // (block 1); the loop runs to block 3, whose back edge carries r0
        // round. r1, written and read in blocks 2-3 only, must not share
        // r0's variable, or its writes would reach r0's next read.
        let f = func(
            vec![
                konst(0),
                Inst::Jump { target: 2 },
                mov(2, 0),
                Inst::Branch {
                    cond: 2,
                    then: 4,
                    els: 8,
                },
                konst(1),
                Inst::Jump { target: 6 },
                mov(3, 1),
                Inst::Jump { target: 2 },
                Inst::Ret,
            ],
            4,
        );
        let lead = crate::translate::leaders(&f.code);
        let s = shared(&f, &lead);
        assert!(s[0].is_some() && s[1].is_some());
        assert_ne!(s[0], s[1]);
    }
}
