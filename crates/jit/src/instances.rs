//! Which functions always run on an instance that lies inside the image.
//!
//! A function's `This` accesses run unchecked when `this + extent` is inside
//! the image; the general way to know is a check at entry, with a checked
//! twin of the whole function for when it fails (`compile.rs`). Most PLC
//! code never needs that twin: program instances sit at offsets the
//! lowering fixed, and FB instances are members of them, called with a
//! `This`- or `Abs`-based address. For such a *static* function the
//! instance is proved inside the image here, once, from the call graph, so
//! it is compiled once, without the entry check; this halves the code of
//! large programs (a thousand FB calls in one body).
//!
//! `bound(f)` is how far past `this` a call of `f` can reach: its own
//! `This` accesses and, through `This`-based calls, its callees' bounds.
//! Roots (program instances of the tasks) are static when
//! `offset + bound <= image size`; a callee is static when every call of it
//! is from a static caller with a `This`-based address (or an `Abs` one
//! whose `offset + bound` fits). A call through a register (arrays of FB
//! instances, references, VAR_IN_OUT) makes its callee dynamic, and so
//! every function it reaches through `This`-based calls.

use crate::translate::this_extent;
use automat_ir::code::{Base, Inst};
use automat_ir::Program;

/// Offsets at or past this are treated as unknown (wrapped negatives).
const SANE: u64 = 1 << 31;

/// Per function: `Some(bound)` when it is static, `None` when it needs the
/// entry check and its checked twin. With no tasks (tests that run
/// functions directly on any instance) every function is dynamic.
pub fn static_bounds(program: &Program) -> Vec<Option<u64>> {
    let n = program.funcs.len();
    let roots: Vec<(usize, u64)> = program
        .tasks
        .iter()
        .flat_map(|t| t.programs.iter())
        .map(|p| (p.func as usize, p.instance_offset as u64))
        .collect();
    if roots.is_empty() {
        return vec![None; n];
    }
    let order = callees_first(program);
    let mut bound = vec![0u64; n];
    for &f in &order {
        let Some(func) = program.funcs.get(f) else {
            continue;
        };
        let mut b = this_extent(func);
        for inst in &func.code {
            if let Inst::Call { func: g, this } = *inst {
                if this.base == Base::This {
                    let gb = bound.get(g as usize).copied().unwrap_or(u64::MAX / 4);
                    b = b.max((this.offset as u64).saturating_add(gb));
                }
            }
        }
        if let Some(x) = bound.get_mut(f) {
            *x = b;
        }
    }
    let size = program.image_size as u64;
    let fits = |offset: u64, f: usize| {
        offset < SANE
            && bound
                .get(f)
                .is_some_and(|b| offset.saturating_add(*b) <= size)
    };
    // Dynamic until proved static; callers before callees.
    let mut dynamic = vec![false; n];
    let mut reached = vec![false; n];
    for &(f, offset) in &roots {
        if let Some(r) = reached.get_mut(f) {
            *r = true;
        }
        if !fits(offset, f) {
            if let Some(d) = dynamic.get_mut(f) {
                *d = true;
            }
        }
    }
    for &f in order.iter().rev() {
        let Some(func) = program.funcs.get(f) else {
            continue;
        };
        let caller_dynamic = dynamic.get(f).copied().unwrap_or(true);
        for inst in &func.code {
            if let Inst::Call { func: g, this } = *inst {
                let g = g as usize;
                let callee_dynamic = match this.base {
                    Base::This => caller_dynamic || this.offset as u64 >= SANE,
                    Base::Abs => !fits(this.offset as u64, g),
                    Base::Reg(_) => true,
                };
                if let Some(r) = reached.get_mut(g) {
                    *r = true;
                }
                if callee_dynamic {
                    if let Some(d) = dynamic.get_mut(g) {
                        *d = true;
                    }
                }
            }
        }
    }
    (0..n)
        .map(|f| {
            let st = reached.get(f).copied().unwrap_or(false)
                && !dynamic.get(f).copied().unwrap_or(true);
            st.then(|| bound.get(f).copied().unwrap_or(0))
        })
        .collect()
}

/// The functions in an order where every callee comes before its callers
/// (the call graph is acyclic: `check_calls`); unreachable ones included.
fn callees_first(program: &Program) -> Vec<usize> {
    let n = program.funcs.len();
    let mut done = vec![false; n];
    let mut order = Vec::with_capacity(n);
    for root in 0..n {
        if done.get(root).copied().unwrap_or(true) {
            continue;
        }
        // (function, next instruction to look at)
        let mut stack = vec![(root, 0usize)];
        while let Some((f, i)) = stack.last_mut() {
            let f = *f;
            let code = program
                .funcs
                .get(f)
                .map(|x| x.code.as_slice())
                .unwrap_or(&[]);
            let next = code
                .iter()
                .enumerate()
                .skip(*i)
                .find_map(|(k, inst)| match inst {
                    Inst::Call { func, .. } => Some((k, *func as usize)),
                    _ => None,
                });
            match next {
                Some((k, g)) => {
                    *i = k + 1;
                    if !done.get(g).copied().unwrap_or(true) && !stack.iter().any(|s| s.0 == g) {
                        stack.push((g, 0));
                    }
                }
                None => {
                    stack.pop();
                    if let Some(d) = done.get_mut(f) {
                        if !*d {
                            *d = true;
                            order.push(f);
                        }
                    }
                }
            }
        }
    }
    order
}
