//! Sequential Function Charts → Structured Text.
//!
//! A chart becomes ordinary ST code over hidden state, so that checking,
//! lowering and every backend see nothing new ("SFC is lowered to the same
//! IR as ST: step flags and action state are memory").
//!
//! # Representation
//! - Each step is an instance, named as the step, of the hidden function
//!   block `__SFC_STEP` (`__SFC_INITIAL_STEP` for the initial step, whose
//!   `X` starts TRUE). Its outputs `X` (BOOL) and `T` (TIME) are what ST,
//!   IL and the CLI read as `s.X` and `s.T`; being outputs, user code cannot
//!   write them (E042). Its hidden inputs `__E`/`__L` keep "entered"/"left"
//!   by the last firing until the next one (the P, P1 and P0 qualifiers).
//! - Each ACTION is an instance, named as the action, of `__SFC_ACTION`
//!   (an ACTION_CONTROL in the manner of IEC 61131-3), whose outputs are
//!   `a.Q` and `a.A`; a BOOL variable named in an association gets a hidden
//!   instance `__sfc_vN` and is assigned its Q.
//! - Hidden variables of the POU: `__sfc_run`/`__sfc_last`/`__sfc_dt` (the
//!   PLC time of the previous call and the time since it) and one fire flag
//!   `__sfc_tN` per transition. The hidden blocks are in
//!   `crates/sema/src/stdlib/sfc.st`.
//!
//! # One call (docs/semantics.md § Sequential Function Chart)
//! 0. `__sfc_dt` := PLC time since the previous call (0 on the first).
//! 1. Every step: `T += dt` while active.
//! 2. Every action control is fed from the associations of the steps
//!    active now (the duration and step time of its active timed
//!    association first); a BOOL variable gets its Q; then the bodies of
//!    the actions whose A is TRUE run, in declaration order.
//! 3. Transitions, in precedence order (PRIORITY ascending, transitions
//!    without one after those with one, then declaration order): a fire
//!    flag is TRUE when every preceding step is active, no transition of
//!    higher precedence sharing a preceding step fires, and the condition
//!    (evaluated only then) is TRUE. No step changes before every flag is
//!    known, so enabling uses the snapshot of the start of the phase.
//!    Then every step is told whether it was left and/or entered: entered
//!    wins (X TRUE, T reset), so a step left and re-entered stays active.
//!
//! A chart in a FUNCTION is refused (E120): it keeps state between calls.

mod build;
mod check;
mod gen;
pub(crate) mod scope;

use crate::ast::sfc::Chart;
use crate::ast::{PouKind, Stmt, VarBlock};
use automat_base::{Code, Diagnostic, Interner, Span, Symbol};
use std::collections::HashSet;

/// The ST body and hidden declarations of a chart (nothing after E120).
pub(crate) fn desugar(
    chart: &Chart,
    kind: PouKind,
    var_blocks: &[VarBlock],
    span: Span,
    interner: &mut Interner,
    diags: &mut Vec<Diagnostic>,
) -> (Vec<Stmt>, Option<VarBlock>) {
    if kind == PouKind::Function {
        diags.push(Diagnostic::error(
            Code::E120,
            span,
            "a FUNCTION cannot be a chart: steps keep state between calls; make it a FUNCTION_BLOCK",
        ));
        return (Vec::new(), None);
    }
    // Macro-steps come from graphical importers; their expansion into the
    // flat chart is not written yet, and running the chart without it
    // would be wrong, so it is refused.
    if let Some(s) = chart.steps.iter().find(|s| s.macro_body.is_some()) {
        diags.push(Diagnostic::error(
            Code::E091,
            s.span,
            "macro-steps cannot be executed yet",
        ));
        return (Vec::new(), None);
    }
    let vars: HashSet<Symbol> = var_blocks
        .iter()
        .flat_map(|b| b.decls.iter())
        .flat_map(|d| d.names.iter().map(|n| n.sym))
        .collect();
    let resolved = check::resolve(chart, &vars, interner, diags);
    check::check(chart, &resolved, &vars, span, interner, diags);
    let (stmts, block) = gen::generate(chart, &resolved, &vars, span, interner);
    (stmts, Some(block))
}
