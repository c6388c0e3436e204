//! A last pass over a finished function: jumps that land on jumps go
//! straight to the final target, and jumps to the next instruction (the
//! end of an IF branch without ELSE, say) are removed. Every dispatched
//! instruction costs the interpreter time, and these do nothing.

use automat_ir::code::{Func, Inst};

/// Tidies the control flow of `f` in place.
pub fn tidy(f: &mut Func) {
    thread_jumps(f);
    // Removing one jump can make the one before it a jump to the next
    // instruction; every round removes at least one, so this ends.
    while drop_jumps_to_next(f) {}
}

/// Where control really goes when it reaches `t`: past any chain of
/// unconditional jumps (at most `code.len()` of them, so a jump cycle
/// cannot make this loop forever).
fn final_target(code: &[Inst], mut t: u32) -> u32 {
    for _ in 0..code.len() {
        match code.get(t as usize) {
            Some(Inst::Jump { target }) if *target != t => t = *target,
            _ => break,
        }
    }
    t
}

fn thread_jumps(f: &mut Func) {
    for i in 0..f.code.len() {
        let new = match f.code.get(i) {
            Some(Inst::Jump { target }) => Inst::Jump {
                target: final_target(&f.code, *target),
            },
            Some(Inst::Branch { cond, then, els }) => Inst::Branch {
                cond: *cond,
                then: final_target(&f.code, *then),
                els: final_target(&f.code, *els),
            },
            _ => continue,
        };
        if let Some(slot) = f.code.get_mut(i) {
            *slot = new;
        }
    }
}

/// Whether any jump was removed.
fn drop_jumps_to_next(f: &mut Func) -> bool {
    let keep: Vec<bool> = f
        .code
        .iter()
        .enumerate()
        .map(|(i, inst)| !matches!(inst, Inst::Jump { target } if *target as usize == i + 1))
        .collect();
    if keep.iter().all(|&k| k) {
        return false;
    }
    let code = std::mem::take(&mut f.code);
    let kept = code
        .into_iter()
        .zip(&keep)
        .filter(|(_, &k)| k)
        .map(|(inst, _)| inst)
        .collect();
    rebuild(f, &keep, Vec::new(), kept);
    true
}

/// Removes the instructions whose `keep` flag is false (jump targets and
/// statement starts move to the next kept instruction); whether any went.
pub fn remove(f: &mut Func, keep: &[bool]) -> bool {
    if keep.len() != f.code.len() || keep.iter().all(|&k| k) {
        return false;
    }
    let code = std::mem::take(&mut f.code);
    let kept = code
        .into_iter()
        .zip(keep)
        .filter(|(_, &k)| k)
        .map(|(inst, _)| inst)
        .collect();
    rebuild(f, keep, Vec::new(), kept);
    true
}

/// Sets `f.code` to `prefix` followed by `kept` (the instructions whose
/// `keep` flag is set, in order), moving jump targets and statement starts
/// along: a removed instruction's index becomes that of the next kept one.
fn rebuild(f: &mut Func, keep: &[bool], prefix: Vec<Inst>, kept: Vec<Inst>) {
    let mut map = Vec::with_capacity(keep.len() + 1);
    let mut n = prefix.len() as u32;
    for &k in keep {
        map.push(n);
        if k {
            n += 1;
        }
    }
    map.push(n);
    let at = |t: u32| map.get(t as usize).copied().unwrap_or(t);
    f.code = prefix;
    f.code.extend(kept.into_iter().map(|inst| match inst {
        Inst::Jump { target } => Inst::Jump { target: at(target) },
        Inst::Branch { cond, then, els } => Inst::Branch {
            cond,
            then: at(then),
            els: at(els),
        },
        other => other,
    }));
    for s in &mut f.stmt_sites {
        s.0 = at(s.0);
    }
    // A statement whose first instructions moved now starts where the
    // next one does (a WHILE with a constant condition and its body):
    // the outer statement keeps the place, so the watchdog still names
    // the loop.
    f.stmt_sites.dedup_by_key(|s| s.0);
}
