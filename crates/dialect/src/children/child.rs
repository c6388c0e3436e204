//! The child's side: a first-call deactivation before its chart, the
//! command handling after it (the scheme is in the parent module).

use super::{hidden, locals, FREEZE, KILL, RESTART, START};
use crate::build;
use automat_base::{Code, Diagnostic, Interner, Symbol};
use automat_syntax::ast::sfc::Chart;
use automat_syntax::ast::{Body, Expr, Ident, Lang, Pou};

/// The steps of a child (top level of its chart), or E158.
fn steps_of(p: &Pou, interner: &Interner, diags: &mut Vec<Diagnostic>) -> Option<Chart> {
    match &p.lang {
        Lang::Sfc(chart) => Some((**chart).clone()),
        _ => {
            diags.push(Diagnostic::error(
                Code::E158,
                p.name.span,
                format!(
                    "`{}` is controlled as a child chart but is not written in SFC",
                    interner.name(p.name.sym)
                ),
            ));
            None
        }
    }
}

/// A child's body: the first-call deactivation, the chart (gated), the
/// parent's `edges` (when the child has children by association), then the
/// command handling. Commands act after the chart, as a firing does: a step
/// activated by GSTART counts its time from the next call, and its pulse
/// actions run there.
///
/// The chart code (action control, boolean-action assignments, action
/// bodies, transitions) runs only while the child is active, and in the one
/// call after a kill or a freeze of an active child (the deactivation's
/// final scan: N actions with Q FALSE, P0 after a kill). An ISaGRAF child
/// that is not active is not executed: otherwise the Q = FALSE of its
/// boolean actions would be written over what another chart drives, in
/// every cycle. While skipped, the chart's clock is kept up to date, so the
/// first call after a start counts one period, as a running chart would.
/// `p.body` must be the chart code alone (the timer rewrite comes later).
pub(super) fn child_code(
    p: &mut Pou,
    own: &[Symbol],
    edges: Vec<automat_syntax::ast::Stmt>,
    interner: &mut Interner,
    diags: &mut Vec<Diagnostic>,
) {
    let Some(chart) = steps_of(p, interner, diags) else {
        let Body::St(stmts) = &mut p.body;
        stmts.extend(edges);
        return;
    };
    let sp = p.name.span;
    let (cmd, stat) = hidden(interner, p.name.sym, sp);
    let f = build::bool_lit(false, sp);
    let t = build::bool_lit(true, sp);
    let boolean = build::ident(interner, "BOOL", sp);
    let boot = build::ident(interner, "__gboot", sp);
    let last_call = build::ident(interner, "__gfinal", sp);
    let mut decls = vec![build::var(boot, boolean), build::var(last_call, boolean)];
    // s(__TICK := FALSE, __E := e, __L := l);
    let step_call = |interner: &mut Interner, s: Ident, e: Expr, l: Expr| {
        build::call_stmt(
            interner,
            s,
            vec![
                ("__TICK", build::bool_lit(false, sp)),
                ("__E", e),
                ("__L", l),
            ],
            sp,
        )
    };
    let mut quiet_off = Vec::new();
    let mut kill = Vec::new();
    let mut freeze = Vec::new();
    let mut restart = Vec::new();
    let mut start = Vec::new();
    for (i, s) in chart.steps.iter().enumerate() {
        let step = s.name;
        let saved = build::ident(interner, &format!("__gfrz_{i}"), sp);
        decls.push(build::var(saved, boolean));
        let x = build::member(interner, step, "X", sp);
        // Leave without the P0 pulse: a second call clears `__L`.
        quiet_off.push(step_call(interner, step, f.clone(), x.clone()));
        quiet_off.push(step_call(interner, step, f.clone(), f.clone()));
        kill.push(step_call(interner, step, f.clone(), x.clone()));
        freeze.push(build::assign(build::name(saved), x.clone(), sp));
        restart.push(step_call(interner, step, build::name(saved), f.clone()));
        restart.push(step_call(interner, step, f.clone(), f.clone()));
        if s.initial {
            start.push(step_call(interner, step, t.clone(), f.clone()));
        }
    }
    freeze.extend(quiet_off.iter().cloned());
    for c in own {
        let (ccmd, _) = hidden(interner, *c, sp);
        kill.push(build::assign(
            build::name(ccmd),
            build::int_lit(KILL, sp),
            sp,
        ));
        freeze.push(build::assign(
            build::name(ccmd),
            build::int_lit(FREEZE, sp),
            sp,
        ));
    }
    let set = |v: i128| build::assign(build::name(stat), build::int_lit(v, sp), sp);
    let is = |a: Ident, v: i128| {
        build::binary(
            automat_syntax::ast::BinaryOp::Eq,
            build::name(a),
            build::int_lit(v, sp),
            sp,
        )
    };
    // The final call: after the kill of an active child (a frozen one
    // had its final call after the freeze) and after a freeze.
    kill.insert(0, build::assign(build::name(last_call), is(stat, 1), sp));
    freeze.push(build::assign(build::name(last_call), t.clone(), sp));
    start.push(set(1));
    kill.push(set(0));
    freeze.push(set(2));
    restart.push(set(1));
    let and = |a: Expr, b: Expr| build::binary(automat_syntax::ast::BinaryOp::And, a, b, sp);
    let ne = |a: Ident, v: i128| build::not(is(a, v), sp);
    let mut boot_body = quiet_off;
    boot_body.push(build::assign(build::name(boot), t.clone(), sp));
    let prologue = vec![build::if_then(
        build::not(build::name(boot), sp),
        boot_body,
        sp,
    )];
    let epilogue = vec![
        build::if_chain(
            vec![
                (and(is(cmd, START), is(stat, 0)), start),
                (and(is(cmd, KILL), ne(stat, 0)), kill),
                (and(is(cmd, FREEZE), is(stat, 1)), freeze),
                (and(is(cmd, RESTART), is(stat, 2)), restart),
            ],
            sp,
        ),
        build::assign(build::name(cmd), build::int_lit(0, sp), sp),
    ];
    // The chart's clock (`__sfc_run`, `__sfc_last` of the SFC desugaring),
    // kept while the chart is skipped; absent when the chart was refused.
    let declared = |name: &str| {
        p.var_blocks
            .iter()
            .flat_map(|b| b.decls.iter())
            .flat_map(|d| d.names.iter())
            .any(|n| interner.name(n.sym) == name)
    };
    let mut skipped = Vec::new();
    if declared("__sfc_run") && declared("__sfc_last") {
        let run = build::ident(interner, "__sfc_run", sp);
        let last = build::ident(interner, "__sfc_last", sp);
        let scan = build::ident(interner, "__SCAN_TIME", sp);
        skipped.push(build::assign(build::name(run), t.clone(), sp));
        skipped.push(build::assign(build::name(last), build::call0(scan), sp));
    }
    let runs = build::binary(
        automat_syntax::ast::BinaryOp::Or,
        is(stat, 1),
        build::name(last_call),
        sp,
    );
    locals(p, decls);
    let Body::St(stmts) = &mut p.body;
    let chart_code = std::mem::replace(stmts, prologue);
    stmts.push(build::if_else(runs, chart_code, skipped, sp));
    stmts.push(build::assign(build::name(last_call), f.clone(), sp));
    stmts.extend(edges);
    stmts.extend(epilogue);
}
