//! PL7 runs the action sections of a call in the order P0 (of the steps
//! being left), P1 (of the steps being entered), N1 (of the active steps),
//! and an N1 section ends with its step: no final scan ("all actions are
//! memorised": what N1 switched on, a P0 section switches off).
//!
//! The desugared chart runs action bodies in declaration order, each as a
//! top-level `IF <action>.A THEN <body> END_IF` (consecutive statements,
//! the representation `desugar::sfc` documents); this reorders those
//! statements, stably, by the action's first section: P0, then P1, then
//! the others; and an action associated only with N1 is guarded by its Q
//! (active while a step is) instead of A (which adds the final scan).

use automat_base::{Interner, Symbol};
use automat_syntax::ast::sfc::{Chart, Qualifier};
use automat_syntax::ast::{ExprKind, Stmt, StmtKind};

/// 0 for P0 actions, 1 for P1, 2 for the rest.
fn rank(chart: &Chart, action: Symbol) -> u8 {
    let mut best = 2;
    for s in &chart.steps {
        for a in s.assocs.iter().filter(|a| a.name.sym == action) {
            best = best.min(match a.qualifier {
                Qualifier::P0 => 0,
                Qualifier::P1 => 1,
                _ => 2,
            });
        }
    }
    best
}

/// The action whose body a statement runs (`IF a.A THEN ...`), if any.
fn body_of(s: &Stmt, chart: &Chart, interner: &Interner) -> Option<Symbol> {
    let StmtKind::If {
        branches,
        else_body,
    } = &s.kind
    else {
        return None;
    };
    let ([b], None) = (branches.as_slice(), else_body) else {
        return None;
    };
    let ExprKind::Member { base, member } = &b.cond.kind else {
        return None;
    };
    let ExprKind::Name(inst) = base.kind else {
        return None;
    };
    let is_a = interner.name(member.sym).eq_ignore_ascii_case("A");
    let is_action = chart.actions.iter().any(|a| a.name.sym == inst.sym);
    (is_a && is_action).then_some(inst.sym)
}

/// Reorders the action bodies of a chart's code in place.
pub fn sections_in_pl7_order(stmts: &mut [Stmt], chart: &Chart, interner: &mut Interner) {
    let Some(first) = stmts
        .iter()
        .position(|s| body_of(s, chart, interner).is_some())
    else {
        return;
    };
    let len = stmts.get(first..).map_or(0, |rest| {
        rest.iter()
            .take_while(|s| body_of(s, chart, interner).is_some())
            .count()
    });
    let Some(run) = stmts.get_mut(first..first + len) else {
        return;
    };
    run.sort_by_key(|s| body_of(s, chart, interner).map_or(2, |a| rank(chart, a)));
    let q = interner.intern("Q");
    for s in run.iter_mut() {
        let Some(action) = body_of(s, chart, interner) else {
            continue;
        };
        if !only_n(chart, action) {
            continue;
        }
        if let StmtKind::If { branches, .. } = &mut s.kind {
            if let Some(ExprKind::Member { member, .. }) =
                branches.first_mut().map(|b| &mut b.cond.kind)
            {
                member.sym = q;
            }
        }
    }
}

/// Whether every association of an action is N (N1).
fn only_n(chart: &Chart, action: Symbol) -> bool {
    chart
        .steps
        .iter()
        .flat_map(|s| s.assocs.iter())
        .filter(|a| a.name.sym == action)
        .all(|a| a.qualifier == Qualifier::N)
}
