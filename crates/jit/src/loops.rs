//! Value ranges of promoted slots at every block entry, carried across
//! loops, so that a loop's array accesses, overflow guards and 32-bit
//! re-wraps are proved away where the interpreter's result cannot differ.
//!
//! Why: the facts of `promote.rs` are block-local, and a loop counter is
//! loaded afresh in every block, so `flags[i]` inside `FOR i := 0 TO n`
//! was checked on every iteration, the FOR's overflow guard `i + 1 <=
//! 2147483647` tested, and `i := i + 1` re-wrapped to 32 bits. Here an
//! interval analysis over the function's blocks (forward, joins at block
//! entries, widening to the type's bounds at loop headers so it ends)
//! learns from the branches: on the taken edge of `IF i <= n` the slot of
//! `i` is at most `n`. `translate.rs` seeds each block with these ranges
//! (`Tx::seed`), and the block-local facts do the rest: a `Check` they
//! prove is not emitted, a decided comparison is a constant, a `Branch` on
//! a constant is a jump, a `Wrap` (or the re-wrap of a promoted store) of a
//! value already in the type's range is the value itself.
//!
//! Sound because a range only ever over-approximates: stores the analysis
//! cannot place (calls, copies, builtins, absolute or unproved register
//! stores) make every slot unknown again, and a failed `Check` faults, so
//! past it the value is in range. Code compiled with a budget keeps these
//! facts too: they do not move any fault site, they remove checks that
//! cannot fail.

use crate::promote::{self, Fact};
use automat_ir::code::{Base, Cmp, Func, Inst, MemTy, Reg};
use std::collections::{BTreeMap, HashMap};

/// An interval of i64 values, both ends included.
pub type Span = (i64, i64);

/// Functions with more blocks than this are not analysed (compile time
/// stays linear in the program's size).
const MAX_BLOCKS: usize = 4096;
/// Passes over the blocks before giving up (widening ends it far sooner).
const MAX_PASSES: usize = 12;
/// At most this many registers are carried between blocks (the ones
/// lowering reads in several blocks, as a FOR's end, step and limit), so
/// the work per block stays bounded.
const MAX_CARRIED: usize = 64;

/// The values a load of `ty` can give (None: not an integer).
pub fn type_span(ty: MemTy) -> Option<Span> {
    Some(match ty {
        MemTy::I8 => (i8::MIN as i64, i8::MAX as i64),
        MemTy::U8 => (0, u8::MAX as i64),
        MemTy::I16 => (i16::MIN as i64, i16::MAX as i64),
        MemTy::U16 => (0, u16::MAX as i64),
        MemTy::I32 => (i32::MIN as i64, i32::MAX as i64),
        MemTy::U32 => (0, u32::MAX as i64),
        MemTy::I64 => (i64::MIN, i64::MAX),
        MemTy::F32 | MemTy::F64 => return None,
    })
}

/// Whether every value of `s` is stored and loaded back unchanged by `ty`.
pub fn fits(s: Span, ty: MemTy) -> bool {
    type_span(ty).is_some_and(|(lo, hi)| lo <= s.0 && s.1 <= hi)
}

/// `promote::derive` plus comparisons decided by their operands' ranges
/// and wraps of values already in range.
pub fn derive(inst: &Inst, facts: &HashMap<Reg, Fact>, extent: u64) -> Option<(Reg, Fact)> {
    let range = |r: Reg| match facts.get(&r) {
        Some(&Fact::Range(a, b)) => Some((a, b)),
        _ => None,
    };
    match *inst {
        Inst::ICmp {
            cmp,
            signed,
            dst,
            a,
            b,
        } => {
            let (x, y) = (range(a), range(b));
            let d = match (x, y) {
                (Some(x), Some(y)) if signed || (x.0 >= 0 && y.0 >= 0) => decide(cmp, x, y),
                _ => None,
            };
            Some((
                dst,
                match d {
                    Some(true) => Fact::Range(1, 1),
                    Some(false) => Fact::Range(0, 0),
                    None => Fact::Range(0, 1),
                },
            ))
        }
        Inst::Wrap { dst, src, ty } => {
            let s = range(src).filter(|&s| fits(s, ty)).or(type_span(ty))?;
            Some((dst, Fact::Range(s.0, s.1)))
        }
        _ => promote::derive(inst, facts, extent),
    }
}

/// `x cmp y` when every pair of values gives the same answer.
fn decide(cmp: Cmp, x: Span, y: Span) -> Option<bool> {
    let lt = (x.1 < y.0)
        .then_some(true)
        .or((x.0 >= y.1).then_some(false));
    let le = (x.1 <= y.0)
        .then_some(true)
        .or((x.0 > y.1).then_some(false));
    let eq = if x.0 == x.1 && y.0 == y.1 && x.0 == y.0 {
        Some(true)
    } else if x.1 < y.0 || y.1 < x.0 {
        Some(false)
    } else {
        None
    };
    match cmp {
        Cmp::Lt => lt,
        Cmp::Le => le,
        Cmp::Gt => le.map(|v| !v),
        Cmp::Ge => lt.map(|v| !v),
        Cmp::Eq => eq,
        Cmp::Ne => eq.map(|v| !v),
    }
}

/// The part of `x` for which `x cmp y` can hold for some value of `y`
/// (None: for no value).
fn refine(cmp: Cmp, x: Span, y: Span) -> Option<Span> {
    let (lo, hi) = match cmp {
        Cmp::Lt => (x.0, x.1.min(y.1.checked_sub(1)?)),
        Cmp::Le => (x.0, x.1.min(y.1)),
        Cmp::Gt => (x.0.max(y.0.checked_add(1)?), x.1),
        Cmp::Ge => (x.0.max(y.0), x.1),
        Cmp::Eq => (x.0.max(y.0), x.1.min(y.1)),
        Cmp::Ne => x,
    };
    (lo <= hi).then_some((lo, hi))
}

fn negate(c: Cmp) -> Cmp {
    match c {
        Cmp::Lt => Cmp::Ge,
        Cmp::Le => Cmp::Gt,
        Cmp::Gt => Cmp::Le,
        Cmp::Ge => Cmp::Lt,
        Cmp::Eq => Cmp::Ne,
        Cmp::Ne => Cmp::Eq,
    }
}

/// `a cmp b` as `b (swap cmp) a`.
fn swap(c: Cmp) -> Cmp {
    match c {
        Cmp::Lt => Cmp::Gt,
        Cmp::Le => Cmp::Ge,
        Cmp::Gt => Cmp::Lt,
        Cmp::Ge => Cmp::Le,
        e => e,
    }
}

/// What is known at a block's entry: slot ranges by offset (only those
/// narrower than the type's) and register ranges (registers carried
/// between blocks, as the FOR loop's end, step and overflow limit are).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Known {
    pub slots: Vec<(u32, Span)>,
    pub regs: Vec<(Reg, Span)>,
}

/// Slot ranges (by index in the analysed slots) and register ranges.
type State = (Vec<Span>, BTreeMap<Reg, Span>);

/// The ranges of the slots `slots` (offset, type) and of registers at the
/// entry of every reachable block, keyed by the block's first
/// instruction. `extent`: the proved extent of `this`
/// (`promote::derive`). Empty when the analysis does not settle.
pub fn entry_ranges(
    f: &Func,
    lead: &[bool],
    slots: &[(u32, MemTy)],
    extent: u64,
) -> HashMap<usize, Known> {
    let slots: Vec<(u32, MemTy, Span)> = slots
        .iter()
        .filter_map(|&(off, ty)| type_span(ty).map(|s| (off, ty, s)))
        .collect();
    let code = &f.code;
    let starts: Vec<usize> = (0..code.len())
        .filter(|&pc| lead.get(pc).copied().unwrap_or(false))
        .collect();
    if slots.is_empty() || starts.len() > MAX_BLOCKS {
        return HashMap::new();
    }
    let top: Vec<Span> = slots.iter().map(|s| s.2).collect();
    let mut at: HashMap<usize, State> = HashMap::new();
    at.insert(0, (top, BTreeMap::new()));
    // Registers read in several blocks; a block-local one is written in
    // its block before it is read, nothing to carry.
    let local = crate::locals::slots(f, lead);
    let carried: Vec<bool> = local.iter().map(|s| s.is_none()).collect();
    let a = Analysis {
        f,
        slots: &slots,
        extent,
        carried,
    };
    let mut settled = false;
    for _ in 0..MAX_PASSES {
        let mut changed = false;
        for (k, &start) in starts.iter().enumerate() {
            let Some(state) = at.get(&start).cloned() else {
                continue;
            };
            let end = starts.get(k + 1).copied().unwrap_or(code.len());
            for (to, out) in a.block(start, end, state) {
                let back = to <= start;
                match at.get_mut(&to) {
                    None => {
                        at.insert(to, out);
                        changed = true;
                    }
                    Some((old, regs)) => {
                        let before = regs.len();
                        regs.retain(|r, o| match out.1.get(r) {
                            Some(n) if n.0 >= o.0 && n.1 <= o.1 => true,
                            // A register's growing range is not widened:
                            // at a loop header it is forgotten.
                            Some(n) if !back => {
                                *o = (o.0.min(n.0), o.1.max(n.1));
                                changed = true;
                                true
                            }
                            _ => false,
                        });
                        changed |= regs.len() != before;
                        for ((o, n), s) in old.iter_mut().zip(&out.0).zip(&slots) {
                            let j = (o.0.min(n.0), o.1.max(n.1));
                            if j != *o {
                                // At a loop header a growing bound jumps to
                                // the type's: the passes end.
                                *o = if back {
                                    (
                                        if j.0 < o.0 { s.2 .0 } else { j.0 },
                                        if j.1 > o.1 { s.2 .1 } else { j.1 },
                                    )
                                } else {
                                    j
                                };
                                changed = true;
                            }
                        }
                    }
                }
            }
        }
        if !changed {
            settled = true;
            break;
        }
    }
    if !settled {
        return HashMap::new();
    }
    at.into_iter()
        .map(|(pc, (st, regs))| {
            let slots = st
                .iter()
                .zip(&slots)
                .filter(|(s, t)| **s != t.2)
                .map(|(s, t)| (t.0, *s))
                .collect();
            let regs = regs.into_iter().collect();
            (pc, Known { slots, regs })
        })
        .collect()
}

struct Analysis<'a> {
    f: &'a Func,
    slots: &'a [(u32, MemTy, Span)],
    extent: u64,
    /// By register: whether its range is carried to other blocks.
    carried: Vec<bool>,
}

impl Analysis<'_> {
    fn slot(&self, addr: automat_ir::code::Addr, ty: MemTy) -> Option<usize> {
        if addr.base != Base::This {
            return None;
        }
        self.slots
            .iter()
            .position(|s| s.0 == addr.offset && s.1 == ty)
    }

    /// Runs the block `start..end` from `state`: its successors with the
    /// slot ranges on each edge (an edge no value can take is left out).
    fn block(&self, start: usize, end: usize, state: State) -> Vec<(usize, State)> {
        let (mut state, regs) = state;
        let mut facts: HashMap<Reg, Fact> = regs
            .iter()
            .map(|(&r, &(a, b))| (r, Fact::Range(a, b)))
            .collect();
        // Registers holding the current value of a slot.
        let mut holds: HashMap<Reg, usize> = HashMap::new();
        // Registers holding a comparison of two registers, still valid.
        let mut cmps: HashMap<Reg, (Cmp, bool, Reg, Reg)> = HashMap::new();
        let top = |s: &mut Vec<Span>| {
            for (x, t) in s.iter_mut().zip(self.slots) {
                *x = t.2;
            }
        };
        for pc in start..end {
            let Some(inst) = self.f.code.get(pc) else {
                return Vec::new();
            };
            let written = promote::writes(inst);
            if let Some(d) = written {
                cmps.retain(|&k, &mut (_, _, a, b)| k != d && a != d && b != d);
            }
            match *inst {
                Inst::Load { dst, ty, addr } if self.slot(addr, ty).is_some() => {
                    let k = self.slot(addr, ty).unwrap_or(0);
                    let s = state.get(k).copied().unwrap_or((i64::MIN, i64::MAX));
                    facts.insert(dst, Fact::Range(s.0, s.1));
                    holds.insert(dst, k);
                    continue;
                }
                Inst::Store { src, ty, addr } if self.slot(addr, ty).is_some() => {
                    let k = self.slot(addr, ty).unwrap_or(0);
                    let s = match facts.get(&src) {
                        Some(&Fact::Range(a, b)) if fits((a, b), ty) => (a, b),
                        _ => type_span(ty).unwrap_or((i64::MIN, i64::MAX)),
                    };
                    if let Some(x) = state.get_mut(k) {
                        *x = s;
                    }
                    holds.retain(|_, v| *v != k);
                    continue;
                }
                Inst::Store { addr, .. } | Inst::StoreBit { addr, .. }
                    if matches!(addr.base, Base::Reg(_)) =>
                {
                    let size = match *inst {
                        Inst::Store { ty, .. } => ty.size(),
                        _ => 1,
                    };
                    match self.proved(addr, size, &facts) {
                        Some((lo, end)) => {
                            for (k, t) in self.slots.iter().enumerate() {
                                let (o, n) = (t.0 as u64, t.1.size() as u64);
                                if o < end && lo < o + n {
                                    if let Some(x) = state.get_mut(k) {
                                        *x = t.2;
                                    }
                                    holds.retain(|_, v| *v != k);
                                }
                            }
                        }
                        None => {
                            top(&mut state);
                            holds.clear();
                        }
                    }
                }
                Inst::Store { addr, .. } | Inst::StoreBit { addr, .. }
                    if addr.base == Base::This => {}
                Inst::Store { .. }
                | Inst::StoreBit { .. }
                | Inst::Copy { .. }
                | Inst::Builtin { .. }
                | Inst::Call { .. } => {
                    top(&mut state);
                    holds.clear();
                }
                _ => {}
            }
            match *inst {
                Inst::Check { val, lo, hi, .. } => {
                    let (lo, hi) = match facts.get(&val) {
                        Some(&Fact::Range(a, b)) => (lo.max(a), hi.min(b)),
                        _ => (lo, hi),
                    };
                    if lo > hi {
                        // Faults on every value: nothing follows.
                        return Vec::new();
                    }
                    facts.insert(val, Fact::Range(lo, hi));
                    if let Some(x) = holds.get(&val).and_then(|&k| state.get_mut(k)) {
                        *x = (x.0.max(lo), x.1.min(hi));
                    }
                }
                Inst::Mov { dst, src } => {
                    let f = facts.get(&src).copied();
                    let h = holds.get(&src).copied();
                    let c = cmps.get(&src).copied();
                    facts.remove(&dst);
                    holds.remove(&dst);
                    if let Some(f) = f {
                        facts.insert(dst, f);
                    }
                    if let Some(h) = h {
                        holds.insert(dst, h);
                    }
                    if let Some(c) = c {
                        cmps.insert(dst, c);
                    }
                }
                _ => {
                    if let Some(d) = written {
                        let new = derive(inst, &facts, self.extent);
                        facts.remove(&d);
                        holds.remove(&d);
                        if let Some((r, f)) = new {
                            facts.insert(r, f);
                        }
                        if let Inst::ICmp {
                            cmp,
                            signed,
                            dst,
                            a,
                            b,
                        } = *inst
                        {
                            if dst != a && dst != b {
                                cmps.insert(dst, (cmp, signed, a, b));
                            }
                        }
                    }
                }
            }
        }
        let mut regs: BTreeMap<Reg, Span> = facts
            .iter()
            .filter(|(r, _)| self.carried.get(**r as usize).copied().unwrap_or(false))
            .filter_map(|(&r, f)| match *f {
                Fact::Range(a, b) => Some((r, (a, b))),
                Fact::This(..) => None,
            })
            .collect();
        while regs.len() > MAX_CARRIED {
            regs.pop_last();
        }
        let state = (state, regs);
        let last = end.checked_sub(1).and_then(|pc| self.f.code.get(pc));
        match last {
            Some(Inst::Jump { target }) => vec![(*target as usize, state)],
            Some(Inst::Ret) => Vec::new(),
            Some(&Inst::Branch { cond, then, els }) => {
                let mut out = Vec::new();
                for (to, taken) in [(then as usize, true), (els as usize, false)] {
                    match facts.get(&cond) {
                        Some(&Fact::Range(1, 1)) if !taken => continue,
                        Some(&Fact::Range(0, 0)) if taken => continue,
                        _ => {}
                    }
                    let mut st = state.clone();
                    if let Some(&(cmp, signed, a, b)) = cmps.get(&cond) {
                        let cmp = if taken { cmp } else { negate(cmp) };
                        if !self.narrow(cmp, signed, a, b, &facts, &holds, &mut st.0) {
                            continue;
                        }
                    }
                    out.push((to, st));
                }
                out
            }
            _ => vec![(end, state)],
        }
    }

    /// Narrows the slots `a` and `b` hold to what `a cmp b` leaves; false
    /// when no value can satisfy it.
    #[allow(clippy::too_many_arguments)]
    fn narrow(
        &self,
        cmp: Cmp,
        signed: bool,
        a: Reg,
        b: Reg,
        facts: &HashMap<Reg, Fact>,
        holds: &HashMap<Reg, usize>,
        st: &mut [Span],
    ) -> bool {
        let range = |r: Reg| match facts.get(&r) {
            Some(&Fact::Range(x, y)) => Some((x, y)),
            _ => None,
        };
        let (Some(x), Some(y)) = (range(a), range(b)) else {
            return true;
        };
        // An unsigned comparison orders like a signed one when both sides
        // are non-negative.
        if !signed && (x.0 < 0 || y.0 < 0) {
            return true;
        }
        for (r, c, other) in [(a, cmp, y), (b, swap(cmp), x)] {
            let Some(&k) = holds.get(&r) else { continue };
            let Some(s) = st.get_mut(k) else { continue };
            match refine(c, *s, other) {
                Some(n) => *s = n,
                None => return false,
            }
        }
        true
    }

    /// The bytes `this + [lo, end)` a register access may touch, when the
    /// facts prove them (as `Tx::proved_range`).
    fn proved(
        &self,
        a: automat_ir::code::Addr,
        size: u32,
        facts: &HashMap<Reg, Fact>,
    ) -> Option<(u64, u64)> {
        let Base::Reg(r) = a.base else { return None };
        let Some(&Fact::This(lo, hi)) = facts.get(&r) else {
            return None;
        };
        let off = a.offset as i32 as i64;
        let lo = lo.checked_add(off)?;
        let end = hi.checked_add(off)?.checked_add(size as i64)?;
        (lo >= 0 && end as u64 <= self.extent).then_some((lo as u64, end as u64))
    }
}

impl crate::translate::Tx<'_, '_> {
    /// At the start of the block at `pc`: what `entry_ranges` knows of the
    /// promoted slots becomes the range of their current values.
    pub(crate) fn seed(&mut self, known: &HashMap<usize, Known>, pc: usize) {
        let Some(k) = known.get(&pc) else { return };
        for &(r, (a, b)) in &k.regs {
            self.facts.insert(r, Fact::Range(a, b));
        }
        for &(off, s) in &k.slots {
            if let Some(&(_, var)) = self.promoted.get(&off) {
                let v = self.b.use_var(var);
                self.ranges.insert(v, s);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use automat_ir::code::{Addr, CheckKind, IntOp, RegClass};

    /// `FOR i := 0 TO 9 DO a[i] := 1; END_FOR` as lowering emits it, with
    /// `a` at this+0 (10 bytes) and `i` at this+12.
    fn for_loop() -> Func {
        let i = |dst| Inst::Load {
            dst,
            ty: MemTy::I32,
            addr: Addr::this(12),
        };
        let code = vec![
            Inst::IConst { dst: 0, value: 0 },
            Inst::Store {
                src: 0,
                ty: MemTy::I32,
                addr: Addr::this(12),
            },
            Inst::IConst { dst: 1, value: 9 },
            Inst::IConst { dst: 2, value: 1 },
            Inst::IConst {
                dst: 3,
                value: i32::MAX as i64,
            },
            // 5: the header.
            i(4),
            Inst::ICmp {
                cmp: Cmp::Le,
                signed: true,
                dst: 5,
                a: 4,
                b: 1,
            },
            Inst::Branch {
                cond: 5,
                then: 8,
                els: 20,
            },
            // 8: the body.
            i(6),
            Inst::Check {
                kind: CheckKind::Index,
                val: 6,
                lo: 0,
                hi: 9,
                site: 1,
            },
            Inst::AddrOf {
                dst: 7,
                addr: Addr::this(0),
            },
            Inst::Int {
                op: IntOp::Add,
                dst: 8,
                a: 7,
                b: 6,
            },
            Inst::Store {
                src: 2,
                ty: MemTy::U8,
                addr: Addr {
                    base: Base::Reg(8),
                    offset: 0,
                },
            },
            i(9),
            Inst::Int {
                op: IntOp::Add,
                dst: 10,
                a: 9,
                b: 2,
            },
            Inst::ICmp {
                cmp: Cmp::Le,
                signed: true,
                dst: 11,
                a: 10,
                b: 3,
            },
            Inst::Branch {
                cond: 11,
                then: 17,
                els: 20,
            },
            // 17: the increment.
            Inst::Store {
                src: 10,
                ty: MemTy::I32,
                addr: Addr::this(12),
            },
            Inst::Jump { target: 5 },
            Inst::Ret,
            // 20
            Inst::Ret,
        ];
        Func {
            code,
            regs: vec![RegClass::I64; 12],
            ..Func::default()
        }
    }

    #[test]
    fn a_for_loop_counter_is_bounded_in_its_body() {
        let f = for_loop();
        let lead = crate::translate::leaders(&f.code);
        let known = entry_ranges(&f, &lead, &[(12, MemTy::I32)], 16);
        let body = known.get(&8).cloned().unwrap_or_default();
        assert_eq!(body.slots, vec![(12, (0, 9))]);
        // The end, step and limit set in the first block reach the body.
        assert!(body.regs.contains(&(1, (9, 9))));
        assert!(body.regs.contains(&(3, (i32::MAX as i64, i32::MAX as i64))));
        // The increment stores 1..=10, which fits: at the header i is
        // widened to 0..=DINT's maximum (never negative).
        let inc = known.get(&17).cloned().unwrap_or_default();
        assert_eq!(inc.slots, vec![(12, (0, 9))]);
        let head = known.get(&5).cloned().unwrap_or_default();
        assert_eq!(head.slots, vec![(12, (0, i32::MAX as i64))]);
        // The exit is reached only from the header (the guard is decided).
        let exit = known.get(&20).cloned().unwrap_or_default();
        assert_eq!(exit.slots, vec![(12, (10, i32::MAX as i64))]);
    }

    #[test]
    fn an_unplaced_store_forgets_the_slots() {
        let mut f = for_loop();
        // A store to an absolute address: it may hit i.
        if let Some(c) = f.code.get_mut(12) {
            *c = Inst::Store {
                src: 2,
                ty: MemTy::U8,
                addr: Addr {
                    base: Base::Abs,
                    offset: 0,
                },
            };
        }
        let lead = crate::translate::leaders(&f.code);
        let known = entry_ranges(&f, &lead, &[(12, MemTy::I32)], 16);
        let inc = known.get(&17).cloned().unwrap_or_default();
        assert_eq!(inc.slots, vec![]);
    }

    #[test]
    fn comparisons_decide_and_refine() {
        assert_eq!(decide(Cmp::Le, (1, 10), (10, 10)), Some(true));
        assert_eq!(decide(Cmp::Le, (1, 11), (10, 10)), None);
        assert_eq!(decide(Cmp::Gt, (11, 20), (10, 10)), Some(true));
        assert_eq!(decide(Cmp::Eq, (3, 3), (3, 3)), Some(true));
        assert_eq!(decide(Cmp::Ne, (0, 2), (3, 9)), Some(true));
        assert_eq!(refine(Cmp::Lt, (0, 100), (10, 10)), Some((0, 9)));
        assert_eq!(refine(Cmp::Ge, (0, 100), (10, 20)), Some((10, 100)));
        assert_eq!(refine(Cmp::Gt, (0, 5), (10, 10)), None);
        assert_eq!(refine(Cmp::Le, (0, 5), (i64::MIN, i64::MIN)), None);
        // A wrap keeps a value in range, and bounds one that is not.
        let mut facts = HashMap::new();
        facts.insert(1, Fact::Range(0, 300));
        let w = |ty| Inst::Wrap { dst: 2, src: 1, ty };
        assert_eq!(
            derive(&w(MemTy::I32), &facts, 0),
            Some((2, Fact::Range(0, 300)))
        );
        assert_eq!(
            derive(&w(MemTy::U8), &facts, 0),
            Some((2, Fact::Range(0, 255)))
        );
    }
}
