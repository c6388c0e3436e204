//! The PL7 (Schneider Premium/Micro) way of using Grafcet, as a flavour of
//! the textual SFC (`--lib pl7`).
//!
//! Spelling (`text`): steps are named `%Xi` (`%X3.T` its time), system bits
//! `%Si` and words `%SWi` are written as in PL7, actions are associated
//! with the PL7 sections `P1` (on activation), `N1` (continuous), `P0` (on
//! deactivation); a transition written without a condition never fires.
//!
//! System objects (hidden globals, declared once, VAR_EXTERNAL added to
//! every POU that names one and to every chart):
//! - `%S20` TRUE during the first cycle after a cold start, `%S1` during
//!   the first cycle after a warm start (RETAIN values restored): a RETAIN
//!   global remembers that the PLC ran before; each POU that uses them
//!   starts with the (idempotent) update, which clears them once PLC time
//!   has moved past the first cycle;
//! - `%S21` (initialise), `%S22` (reset), `%S23` (freeze): read by every
//!   chart at the start of its call; while one is set the chart does not
//!   evolve in that call (its transitions cannot fire). At the end of the
//!   call `%S21` leaves every active step and enters the initial steps;
//!   else `%S22` leaves every active step (one request per cycle, `%S21`
//!   first, as PL7 handles them). The request is for the whole CHART
//!   section: the last chart program of the section (the last SFC PROGRAM
//!   in text order, the order the section runs them) clears it after its
//!   own handling, so every chart of the section sees it and POST sees it
//!   cleared. `%S23` stays until the program clears it. Steps left or
//!   entered so behave as after a firing: P0 / P1 sections and final scans
//!   run in the next call;
//! - `%SW20` / `%SW21`: the number of active steps and of enabled
//!   transitions (all preceding steps active) of the whole section: each
//!   chart adds its counts after its call to hidden totals, which the last
//!   chart program publishes and resets.
//!
//! Charts in FUNCTION_BLOCKs (not PL7, allowed by the SFC flavour) follow
//! the requests and add to the totals like any chart; in a project without
//! a chart PROGRAM each of them clears and publishes after itself.
//!
//! Step objects `%Xi` are global as in PL7 (`steps`).
//!
//! The chart's transitions are recognised in the desugared code by their
//! fire flags `__sfc_t<n>` (the representation `desugar::sfc` documents);
//! the PL7 conformance cases fail loudly if that representation changes.

mod order;
mod steps;
pub mod text;

use crate::build;
use crate::walk::{self, Visitor};
use automat_base::{Diagnostic, Interner, Span, Symbol};
use automat_syntax::ast::sfc::Chart;
use automat_syntax::ast::{
    BinaryOp, Body, Expr, ExprKind, Ident, Item, Lang, Pou, PouKind, Retain, SourceUnit, Stmt,
    StmtKind, VarBlock, VarKind,
};

/// The system objects: (hidden name, type).
const SYSTEM: &[(&str, &str)] = &[
    ("_S1", "BOOL"),
    ("_S20", "BOOL"),
    ("_S21", "BOOL"),
    ("_S22", "BOOL"),
    ("_S23", "BOOL"),
    ("_SW20", "INT"),
    ("_SW21", "INT"),
    // The counts of the charts run so far in this cycle.
    ("__pl7_sw20", "INT"),
    ("__pl7_sw21", "INT"),
    ("__pl7_booted", "BOOL"),
    ("__pl7_boot_time", "TIME"),
];

/// Set when the PLC has run once (RETAIN: tells a warm start from a cold one).
const RAN: &str = "__pl7_ran";

/// Rewrites the PL7 charts and system objects of the user units. Returns
/// the byte ranges (file, start, end) of transitions written without a
/// condition: the parser's "missing condition" error there is void.
pub fn rewrite(
    units: &mut [SourceUnit],
    is_user: &dyn Fn(&SourceUnit) -> bool,
    texts: &dyn Fn(&SourceUnit) -> String,
    interner: &mut Interner,
    diags: &mut Vec<Diagnostic>,
) -> Vec<Span> {
    let system: Vec<Symbol> = SYSTEM.iter().map(|(n, _)| interner.intern(n)).collect();
    let mut conditionless = Vec::new();
    let mut any = false;
    // The chart that ends the CHART section: the last SFC PROGRAM in file
    // and text order (the order `sections` runs the Sequential section in).
    let last_chart: Option<Symbol> = units
        .iter()
        .filter(|u| is_user(u))
        .flat_map(|u| u.items.iter())
        .filter_map(|i| match i {
            Item::Pou(p) if p.kind == PouKind::Program && matches!(p.lang, Lang::Sfc(_)) => {
                Some(p.name.sym)
            }
            _ => None,
        })
        .last();
    for unit in units.iter_mut().filter(|u| is_user(u)) {
        let text = texts(unit);
        for item in &mut unit.items {
            let Item::Pou(p) = item else { continue };
            if p.kind == PouKind::Function {
                continue;
            }
            let chart = match &p.lang {
                Lang::Sfc(c) => Some((**c).clone()),
                _ => None,
            };
            if let Some(c) = &chart {
                conditionless.extend(
                    crate::empty::missing_conditions(c, &text)
                        .into_iter()
                        .map(|(_, span)| span),
                );
            }
            let mut seen = Seen {
                system: &system,
                found: false,
            };
            let Body::St(stmts) = &mut p.body;
            walk::stmts(stmts, &mut seen);
            if !seen.found && chart.is_none() {
                continue;
            }
            any = true;
            externals(p, interner);
            if let Some(c) = &chart {
                let last = match last_chart {
                    Some(l) => l == p.name.sym,
                    None => true,
                };
                chart_code(p, c, last, interner);
                let Body::St(stmts) = &mut p.body;
                order::sections_in_pl7_order(stmts, c, interner);
            }
            system_prologue(p, interner);
        }
    }
    if any {
        if let Some(first) = units.iter_mut().find(|u| is_user(u)) {
            globals(first, interner);
        }
    }
    // After the chart code above: the mirrors are written last.
    steps::rewrite(units, is_user, interner, diags);
    conditionless
}

/// Whether a body names a system object.
struct Seen<'a> {
    system: &'a [Symbol],
    found: bool,
}

impl Visitor for Seen<'_> {
    fn expr(&mut self, e: &mut Expr) {
        if let ExprKind::Name(id) = e.kind {
            self.found |= self.system.contains(&id.sym);
        }
    }
}

fn block(
    kind: VarKind,
    retain: Retain,
    decls: Vec<automat_syntax::ast::VarDecl>,
    span: Span,
) -> VarBlock {
    VarBlock {
        kind,
        constant: false,
        retain,
        decls,
        span,
    }
}

fn globals(unit: &mut SourceUnit, interner: &mut Interner) {
    let span = Span::default();
    let decls = SYSTEM
        .iter()
        .map(|(n, ty)| {
            build::var(
                build::ident(interner, n, span),
                build::ident(interner, ty, span),
            )
        })
        .collect();
    unit.items.push(Item::Globals(block(
        VarKind::Global,
        Retain::Unspecified,
        decls,
        span,
    )));
    let ran = vec![build::var(
        build::ident(interner, RAN, span),
        build::ident(interner, "BOOL", span),
    )];
    unit.items.push(Item::Globals(block(
        VarKind::Global,
        Retain::Retain,
        ran,
        span,
    )));
}

fn externals(p: &mut Pou, interner: &mut Interner) {
    let span = p.name.span;
    let mut decls: Vec<_> = SYSTEM
        .iter()
        .map(|(n, ty)| {
            build::var(
                build::ident(interner, n, span),
                build::ident(interner, ty, span),
            )
        })
        .collect();
    decls.push(build::var(
        build::ident(interner, RAN, span),
        build::ident(interner, "BOOL", span),
    ));
    p.var_blocks
        .push(block(VarKind::External, Retain::Unspecified, decls, span));
}

/// `%S1` / `%S20` at the very start of the body.
fn system_prologue(p: &mut Pou, interner: &mut Interner) {
    let sp = p.name.span;
    let id = |interner: &mut Interner, n: &str| build::ident(interner, n, sp);
    let booted = id(interner, "__pl7_booted");
    let boot_time = id(interner, "__pl7_boot_time");
    let ran = id(interner, RAN);
    let s1 = id(interner, "_S1");
    let s20 = id(interner, "_S20");
    let scan = id(interner, "__SCAN_TIME");
    let first = vec![
        build::assign(build::name(booted), build::bool_lit(true, sp), sp),
        build::assign(build::name(boot_time), build::call0(scan), sp),
        build::assign(build::name(s1), build::name(ran), sp),
        build::assign(build::name(s20), build::not(build::name(ran), sp), sp),
        build::assign(build::name(ran), build::bool_lit(true, sp), sp),
    ];
    let later = vec![
        build::assign(build::name(s1), build::bool_lit(false, sp), sp),
        build::assign(build::name(s20), build::bool_lit(false, sp), sp),
    ];
    let moved = build::binary(BinaryOp::Ne, build::call0(scan), build::name(boot_time), sp);
    let stmt = build::if_chain(
        vec![(build::not(build::name(booted), sp), first), (moved, later)],
        sp,
    );
    let Body::St(stmts) = &mut p.body;
    stmts.insert(0, stmt);
}

/// The hold flag before the chart, the gate on its transitions, and the
/// `%S21` / `%S22` handling and the counts after it; the `last` chart of
/// the section also clears the request and publishes the counts.
fn chart_code(p: &mut Pou, chart: &Chart, last: bool, interner: &mut Interner) {
    let sp = p.name.span;
    let id = |interner: &mut Interner, n: &str| build::ident(interner, n, sp);
    let hold = id(interner, "__pl7_hold");
    let boolean = id(interner, "BOOL");
    p.var_blocks.push(block(
        VarKind::Local,
        Retain::Unspecified,
        vec![build::var(hold, boolean)],
        sp,
    ));
    let (s21, s22, s23) = (
        id(interner, "_S21"),
        id(interner, "_S22"),
        id(interner, "_S23"),
    );
    let (sw20, sw21) = (id(interner, "_SW20"), id(interner, "_SW21"));
    let (n20, n21) = (id(interner, "__pl7_sw20"), id(interner, "__pl7_sw21"));
    let or = |a: Expr, b: Expr| build::binary(BinaryOp::Or, a, b, sp);
    let set_hold = build::assign(
        build::name(hold),
        or(or(build::name(s21), build::name(s22)), build::name(s23)),
        sp,
    );
    let Body::St(stmts) = &mut p.body;
    let flag_prefix = "__sfc_t";
    for s in stmts.iter_mut() {
        if fires(s, flag_prefix, interner) {
            gate(s, hold);
        }
    }
    let f = || build::bool_lit(false, sp);
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
    let mut init = Vec::new();
    let mut reset = Vec::new();
    let mut count = Vec::new();
    let inc = |v: Ident| {
        build::assign(
            build::name(v),
            build::binary(BinaryOp::Add, build::name(v), build::int_lit(1, sp), sp),
            sp,
        )
    };
    for s in &chart.steps {
        let x = build::member(interner, s.name, "X", sp);
        if s.initial {
            init.push(step_call(interner, s.name, build::bool_lit(true, sp), f()));
        } else {
            init.push(step_call(interner, s.name, f(), x.clone()));
        }
        reset.push(step_call(interner, s.name, f(), x.clone()));
        count.push(build::if_then(x, vec![inc(n20)], sp));
    }
    for t in &chart.transitions {
        let mut terms = t.from.iter().map(|s| build::member(interner, *s, "X", sp));
        let Some(first) = terms.next() else { continue };
        let enabled = terms.fold(first, |a, b| build::binary(BinaryOp::And, a, b, sp));
        count.push(build::if_then(enabled, vec![inc(n21)], sp));
    }
    if last {
        init.push(build::assign(build::name(s21), f(), sp));
        reset.push(build::assign(build::name(s22), f(), sp));
        for (shown, total) in [(sw20, n20), (sw21, n21)] {
            count.push(build::assign(build::name(shown), build::name(total), sp));
            count.push(build::assign(build::name(total), build::int_lit(0, sp), sp));
        }
    }
    stmts.insert(0, set_hold);
    stmts.push(build::if_chain(
        vec![(build::name(s21), init), (build::name(s22), reset)],
        sp,
    ));
    stmts.extend(count);
}

/// Whether a top-level statement of the chart code is a transition test:
/// an IF whose code sets a fire flag `__sfc_t<n>` to TRUE.
fn fires(s: &Stmt, prefix: &str, interner: &Interner) -> bool {
    let StmtKind::If { branches, .. } = &s.kind else {
        return false;
    };
    branches
        .iter()
        .any(|b| b.body.iter().any(|s| sets_flag(s, prefix, interner)))
}

fn sets_flag(s: &Stmt, prefix: &str, interner: &Interner) -> bool {
    match &s.kind {
        StmtKind::Assign { target, .. } => match target.kind {
            ExprKind::Name(id) => {
                let n = interner.name(id.sym);
                n.len() > prefix.len()
                    && n.get(..prefix.len())
                        .is_some_and(|p| p.eq_ignore_ascii_case(prefix))
                    && n.get(prefix.len()..)
                        .is_some_and(|r| r.bytes().all(|b| b.is_ascii_digit()))
            }
            _ => false,
        },
        StmtKind::If { branches, .. } => branches
            .iter()
            .any(|b| b.body.iter().any(|s| sets_flag(s, prefix, interner))),
        _ => false,
    }
}

/// `IF c THEN` → `IF c AND NOT hold THEN` (first branch: a transition
/// test has one).
fn gate(s: &mut Stmt, hold: Ident) {
    if let StmtKind::If { branches, .. } = &mut s.kind {
        if let Some(b) = branches.first_mut() {
            let sp = b.cond.span;
            let cond = std::mem::replace(&mut b.cond, build::bool_lit(false, sp));
            b.cond = build::binary(
                BinaryOp::And,
                cond,
                build::not(build::name(Ident { span: sp, ..hold }), sp),
                sp,
            );
        }
    }
}
