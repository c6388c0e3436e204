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

/// A child's body: the first-call deactivation, the chart, then the
/// command handling. Commands act after the chart, as a firing does: a step
/// activated by GSTART counts its time from the next call, and its pulse
/// actions run there.
pub(super) fn child_code(
    p: &mut Pou,
    own: &[Symbol],
    interner: &mut Interner,
    diags: &mut Vec<Diagnostic>,
) {
    let Some(chart) = steps_of(p, interner, diags) else {
        return;
    };
    let sp = p.name.span;
    let (cmd, stat) = hidden(interner, p.name.sym, sp);
    let f = build::bool_lit(false, sp);
    let t = build::bool_lit(true, sp);
    let boolean = build::ident(interner, "BOOL", sp);
    let boot = build::ident(interner, "__gboot", sp);
    let mut decls = vec![build::var(boot, boolean)];
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
    start.push(set(1));
    kill.push(set(0));
    freeze.push(set(2));
    restart.push(set(1));
    let is = |a: Ident, v: i128| {
        build::binary(
            automat_syntax::ast::BinaryOp::Eq,
            build::name(a),
            build::int_lit(v, sp),
            sp,
        )
    };
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
    locals(p, decls);
    let Body::St(stmts) = &mut p.body;
    let chart_code = std::mem::replace(stmts, prologue);
    stmts.extend(chart_code);
    stmts.extend(epilogue);
}
