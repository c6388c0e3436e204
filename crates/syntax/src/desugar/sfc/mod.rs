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
//!
//! # Macro-steps (graphical charts; IEC 60848 Grafcet macro-steps)
//! There is no textual syntax: importers build `Step::macro_body` and call
//! [`desugar_chart`]. The chart is flattened first (`flat.rs`), so the
//! scheme above runs unchanged over one set of steps:
//! - Names: the steps and actions of every body share the chart's one
//!   namespace and keep their names (unique across the chart and all its
//!   bodies, E122 otherwise): a body step `inner` of `M` is the instance
//!   `inner`, read as `inner.X`/`inner.T` anywhere in the POU (conditions
//!   and actions of the body name their steps as written). Flat order: the
//!   chart's own steps, transitions and actions, then each body's, depth
//!   first in source order (`Chart::charts`); so actions of a body run
//!   after the chart's, and without PRIORITY a transition of the chart
//!   wins over one of a body sharing a preceding step.
//! - Structure: a transition links steps of its own chart or body (E121
//!   for a step inside or outside a macro body); each body has exactly one
//!   INITIAL_STEP, its entry (E123, E124), and `exit` is a step of the body
//!   (E121).
//! - Entering: a transition that enters `M` enters the body's initial step
//!   (and, when that is a macro-step, its initial step, and so on) in the
//!   same firing. An INITIAL_STEP macro-step starts with its entry active.
//! - Leaving: a transition that leaves `M` is enabled when the body's exit
//!   step is active (its test is `exit.X`), and firing it leaves the exit
//!   step (nested: the exit of the exit, and so on). Other body steps still
//!   active stay active (and so does `M`: a well-formed body has only its
//!   exit step active by then).
//! - `M` is a step instance like the others. `M.X` is TRUE exactly while a
//!   step of its body (nested bodies included) is active: set by a firing
//!   that enters `M`, cleared by the first firing after which no body step
//!   is active. `M.T` is the time since `M` was last entered (reset by a
//!   firing that enters it, even when it was active; counts while `M.X`;
//!   kept after it is left), so a body's entry step and `M` agree on T
//!   until the entry is left. Associations of `M` are those of a step
//!   active while `M.X` (P/P1 on entering `M`, P0 on leaving it). In
//!   phase 3 the macro-steps are updated after every other step, from their
//!   body steps' new flags (`__L := M.X AND NOT (b1.X OR ...)`).
//! - A `jump` transition is an ordinary transition: the flag only tells
//!   tools how it was drawn.

mod build;
mod check;
mod flat;
mod gen;
pub(crate) mod scope;

use crate::ast::sfc::Chart;
use crate::ast::{Body, Lang, Pou, PouKind, Stmt, VarBlock};
use automat_base::{Code, Diagnostic, Interner, Span, Symbol};
use std::collections::HashSet;

/// The importers' entry (PLCopen XML and other graphical charts): rewrites
/// the chart of `pou.lang` (`Lang::Sfc`, macro-steps allowed) into
/// `pou.body`, and appends the chart's hidden declarations to
/// `pou.var_blocks`, exactly as the parser does for a textual chart.
/// `pou.var_blocks` must hold the POU's own declarations only (not the
/// hidden block of an earlier desugaring); an IL text in the chart must
/// already be rewritten (`Condition::Il::stmts`, `ActionBody::Il::stmts`)
/// with its hidden `__CR` declared. Returns the diagnostics (chart checks
/// E120–E131, W120–W122), unsorted; chart-wide ones point at the chart's
/// elements (from the first to the last of the chart itself, as the parser
/// does; `pou.span` for an empty chart). A POU that is not a chart is left
/// as it is.
pub fn desugar_chart(pou: &mut Pou, interner: &mut Interner) -> Vec<Diagnostic> {
    let mut diags = Vec::new();
    let Lang::Sfc(chart) = &pou.lang else {
        return diags;
    };
    let spans = chart
        .steps
        .iter()
        .map(|s| s.span)
        .chain(chart.transitions.iter().map(|t| t.span))
        .chain(chart.actions.iter().map(|a| a.span))
        .filter(|s| s.file == pou.span.file);
    let span = spans.reduce(|a, b| a.to(b)).unwrap_or(pou.span);
    let (stmts, block) = desugar(chart, pou.kind, &pou.var_blocks, span, interner, &mut diags);
    pou.body = Body::St(stmts);
    pou.var_blocks.extend(block);
    diags
}

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
    let vars: HashSet<Symbol> = var_blocks
        .iter()
        .flat_map(|b| b.decls.iter())
        .flat_map(|d| d.names.iter().map(|n| n.sym))
        .collect();
    let flat = flat::flatten(chart);
    let resolved = check::resolve(&flat, &vars, interner, diags);
    check::check(&flat, &resolved, &vars, span, interner, diags);
    let (stmts, block) = gen::generate(&flat.chart, &resolved, &vars, span, interner);
    (stmts, Some(block))
}
