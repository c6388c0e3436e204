//! Name resolution and structural checks of a chart, before code is
//! generated: unknown and duplicate names (E121, E122, E131), initial steps
//! (E123, E124), associations (E125, E126, E128, E129) and the warnings
//! about unreachable steps, steps without a way out and unused actions
//! (W120–W122).
//!
//! Which steps can be active together is found by exploring the chart's
//! reachable markings (sets of active steps), firing one enabled transition
//! at a time with every condition assumed possible. Firing several
//! transitions in one call reaches nothing more (transitions that fire
//! together share no preceding step, so they can fire one after the other),
//! so the exploration covers every marking the chart can reach. It stops at
//! [`MAX_MARKINGS`]; past that, reachability falls back to a structural
//! fixpoint and "active together" to "in one step".

use crate::ast::sfc::{Chart, Qualifier};
use automat_base::{Code, Diagnostic, Interner, Span, Symbol};
use std::collections::{HashMap, HashSet, VecDeque};

/// How many markings the exploration visits at most.
const MAX_MARKINGS: usize = 4096;

/// What the names of a chart denote.
pub(super) struct Resolved {
    /// Whether each step of `chart.steps` takes part (a duplicate does not).
    pub step_ok: Vec<bool>,
    /// Whether each action of `chart.actions` takes part.
    pub action_ok: Vec<bool>,
    /// Step and action names → their index.
    pub step_of: HashMap<Symbol, usize>,
    pub action_of: HashMap<Symbol, usize>,
    /// Per transition: the indexes of its known FROM and TO steps.
    pub from: Vec<Vec<usize>>,
    pub to: Vec<Vec<usize>>,
    /// Step and action names that are also variables of the POU: their
    /// instances get hidden names (the variable keeps the name).
    pub clash: HashSet<Symbol>,
}

/// Resolves the names of `chart` against itself and the POU's variables.
pub(super) fn resolve(
    chart: &Chart,
    vars: &HashSet<Symbol>,
    interner: &Interner,
    diags: &mut Vec<Diagnostic>,
) -> Resolved {
    let mut r = Resolved {
        step_ok: vec![false; chart.steps.len()],
        action_ok: vec![false; chart.actions.len()],
        step_of: HashMap::new(),
        action_of: HashMap::new(),
        from: Vec::new(),
        to: Vec::new(),
        clash: HashSet::new(),
    };
    // Steps and actions share one namespace: both are instances of the POU.
    let mut seen: HashMap<Symbol, Span> = HashMap::new();
    let names = chart
        .steps
        .iter()
        .map(|s| (s.name, true))
        .chain(chart.actions.iter().map(|a| (a.name, false)));
    let (mut si, mut ai) = (0usize, 0usize);
    for (name, is_step) in names {
        let idx = if is_step { si } else { ai };
        if is_step {
            si += 1;
        } else {
            ai += 1;
        }
        let what = if is_step { "step" } else { "action" };
        if let Some(&first) = seen.get(&name.sym) {
            diags.push(
                Diagnostic::error(
                    Code::E122,
                    name.span,
                    format!(
                        "`{}` is declared twice in this chart",
                        interner.name(name.sym)
                    ),
                )
                .with_label(first, "first declared here"),
            );
            continue;
        }
        seen.insert(name.sym, name.span);
        if vars.contains(&name.sym) {
            diags.push(Diagnostic::error(
                Code::E122,
                name.span,
                format!(
                    "the {what} `{}` has the name of a variable of this POU",
                    interner.name(name.sym)
                ),
            ));
            r.clash.insert(name.sym);
        }
        if is_step {
            r.step_ok[idx] = true;
            r.step_of.insert(name.sym, idx);
        } else {
            r.action_ok[idx] = true;
            r.action_of.insert(name.sym, idx);
        }
    }
    let mut tnames: HashMap<Symbol, Span> = HashMap::new();
    for t in &chart.transitions {
        if let Some(n) = t.name {
            if let Some(&first) = tnames.get(&n.sym) {
                diags.push(
                    Diagnostic::error(
                        Code::E122,
                        n.span,
                        format!("transition `{}` is declared twice", interner.name(n.sym)),
                    )
                    .with_label(first, "first declared here"),
                );
            } else {
                tnames.insert(n.sym, n.span);
            }
        }
        let from = step_list(&r, &t.from, "FROM", interner, diags);
        let to = step_list(&r, &t.to, "TO", interner, diags);
        r.from.push(from);
        r.to.push(to);
    }
    r
}

/// The known steps of a FROM/TO list (E121 for unknown ones, E131 for repeats).
fn step_list(
    r: &Resolved,
    list: &[crate::ast::Ident],
    what: &str,
    interner: &Interner,
    diags: &mut Vec<Diagnostic>,
) -> Vec<usize> {
    let mut out: Vec<usize> = Vec::new();
    for id in list {
        match r.step_of.get(&id.sym) {
            Some(&i) if out.contains(&i) => diags.push(Diagnostic::error(
                Code::E131,
                id.span,
                format!(
                    "step `{}` is listed twice in this {what} list",
                    interner.name(id.sym)
                ),
            )),
            Some(&i) => out.push(i),
            None => diags.push(Diagnostic::error(
                Code::E121,
                id.span,
                format!("unknown step `{}` in {what}", interner.name(id.sym)),
            )),
        }
    }
    out
}

/// The checks that need resolved names.
pub(super) fn check(
    chart: &Chart,
    r: &Resolved,
    vars: &HashSet<Symbol>,
    chart_span: Span,
    interner: &Interner,
    diags: &mut Vec<Diagnostic>,
) {
    let initial: Vec<usize> = (0..chart.steps.len())
        .filter(|&i| r.step_ok[i] && chart.steps.get(i).is_some_and(|s| s.initial))
        .collect();
    match initial.as_slice() {
        [] => diags.push(Diagnostic::error(
            Code::E123,
            chart_span,
            "this chart has no INITIAL_STEP",
        )),
        [first, rest @ ..] => {
            for &i in rest {
                if let (Some(s), Some(f)) = (chart.steps.get(i), chart.steps.get(*first)) {
                    diags.push(
                        Diagnostic::error(
                            Code::E124,
                            s.name.span,
                            "a chart has exactly one INITIAL_STEP",
                        )
                        .with_label(f.name.span, "the first initial step"),
                    );
                }
            }
        }
    }
    check_assocs(chart, r, vars, interner, diags);
    let markings = explore(chart, r, &initial);
    check_timed(chart, r, markings.as_ref(), interner, diags);
    if !initial.is_empty() {
        let reach = match &markings {
            Some(m) => m
                .iter()
                .fold(vec![false; chart.steps.len()], |mut acc, mk| {
                    for (i, a) in mk.iter().enumerate() {
                        if *a {
                            if let Some(x) = acc.get_mut(i) {
                                *x = true;
                            }
                        }
                    }
                    acc
                }),
            None => fixpoint(chart.steps.len(), r, &initial),
        };
        for (i, s) in chart.steps.iter().enumerate() {
            if r.step_ok[i] && !reach.get(i).copied().unwrap_or(true) {
                diags.push(Diagnostic::warning(
                    Code::W120,
                    s.name.span,
                    format!(
                        "step `{}` can never become active",
                        interner.name(s.name.sym)
                    ),
                ));
            }
        }
    }
    for (i, s) in chart.steps.iter().enumerate() {
        if r.step_ok[i] && !r.from.iter().any(|f| f.contains(&i)) {
            diags.push(Diagnostic::warning(
                Code::W121,
                s.name.span,
                format!(
                    "no transition leaves step `{}`: once active, it stays active",
                    interner.name(s.name.sym)
                ),
            ));
        }
    }
}

/// E125, E126, E129 and W122.
fn check_assocs(
    chart: &Chart,
    r: &Resolved,
    vars: &HashSet<Symbol>,
    interner: &Interner,
    diags: &mut Vec<Diagnostic>,
) {
    let mut used = vec![false; chart.actions.len()];
    // Per action name: the first SD and the first SL association.
    let mut sd_sl: HashMap<(Symbol, bool), Span> = HashMap::new();
    for (si, step) in chart.steps.iter().enumerate() {
        if !r.step_ok[si] {
            continue;
        }
        for a in &step.assocs {
            let name = interner.name(a.name.sym);
            let action = r.action_of.get(&a.name.sym).copied();
            match action {
                Some(i) => {
                    if let Some(u) = used.get_mut(i) {
                        *u = true;
                    }
                }
                None if vars.contains(&a.name.sym) => {
                    if matches!(a.qualifier, Qualifier::P1 | Qualifier::P0) {
                        diags.push(Diagnostic::error(
                            Code::E126,
                            a.span,
                            format!(
                                "`{}` runs code once: `{name}` is a variable, not an ACTION",
                                a.qualifier.name()
                            ),
                        ));
                    }
                }
                None => diags.push(Diagnostic::error(
                    Code::E125,
                    a.name.span,
                    format!("`{name}` is neither an ACTION of this chart nor a variable"),
                )),
            }
            let q = a.qualifier;
            if q.is_timed() && a.time.is_none() {
                diags.push(Diagnostic::error(
                    Code::E126,
                    a.span,
                    format!(
                        "the qualifier `{}` needs a duration: `{name}({}, T#5s)`",
                        q.name(),
                        q.name()
                    ),
                ));
            } else if !q.is_timed() {
                if let Some(t) = &a.time {
                    diags.push(Diagnostic::error(
                        Code::E126,
                        t.span,
                        format!("the qualifier `{}` takes no duration", q.name()),
                    ));
                }
            }
            if matches!(q, Qualifier::SD | Qualifier::SL) {
                let is_sd = q == Qualifier::SD;
                sd_sl.entry((a.name.sym, is_sd)).or_insert(a.span);
                if let Some(&other) = sd_sl.get(&(a.name.sym, !is_sd)) {
                    diags.push(
                        Diagnostic::error(
                            Code::E129,
                            a.span,
                            format!("`{name}` cannot be both SD and SL"),
                        )
                        .with_label(other, "the other one"),
                    );
                }
            }
        }
    }
    for (i, a) in chart.actions.iter().enumerate() {
        if r.action_ok[i] && !used.get(i).copied().unwrap_or(true) {
            diags.push(Diagnostic::warning(
                Code::W122,
                a.name.span,
                format!(
                    "action `{}` is associated with no step and never runs",
                    interner.name(a.name.sym)
                ),
            ));
        }
    }
}

/// E128: two timed associations of one action active together.
fn check_timed(
    chart: &Chart,
    r: &Resolved,
    markings: Option<&HashSet<Vec<bool>>>,
    interner: &Interner,
    diags: &mut Vec<Diagnostic>,
) {
    // Per action name: its timed associations as (step, span), source order.
    let mut timed: HashMap<Symbol, Vec<(usize, Span)>> = HashMap::new();
    for (si, step) in chart.steps.iter().enumerate() {
        if !r.step_ok[si] {
            continue;
        }
        for a in step.assocs.iter().filter(|a| a.qualifier.is_timed()) {
            timed.entry(a.name.sym).or_default().push((si, a.span));
        }
    }
    let together = |x: usize, y: usize| {
        x == y
            || markings.is_some_and(|m| {
                m.iter().any(|mk| {
                    mk.get(x).copied().unwrap_or(false) && mk.get(y).copied().unwrap_or(false)
                })
            })
    };
    let mut list: Vec<(&Symbol, &Vec<(usize, Span)>)> = timed.iter().collect();
    list.sort_by_key(|(_, v)| v.first().map(|(_, s)| s.start));
    for (sym, assocs) in list {
        for (j, &(sj, span)) in assocs.iter().enumerate() {
            if let Some(&(_, first)) = assocs.iter().take(j).find(|&&(si, _)| together(si, sj)) {
                diags.push(
                    Diagnostic::error(
                        Code::E128,
                        span,
                        format!(
                            "`{}` has two timed associations that can be active together",
                            interner.name(*sym)
                        ),
                    )
                    .with_label(first, "the other one"),
                );
            }
        }
    }
}

/// Every marking reachable from the initial steps, or `None` when there
/// are more than [`MAX_MARKINGS`] (or no initial step).
fn explore(chart: &Chart, r: &Resolved, initial: &[usize]) -> Option<HashSet<Vec<bool>>> {
    if initial.is_empty() {
        return None;
    }
    let n = chart.steps.len();
    let mut start = vec![false; n];
    for &i in initial {
        *start.get_mut(i)? = true;
    }
    let mut seen = HashSet::new();
    let mut queue = VecDeque::new();
    seen.insert(start.clone());
    queue.push_back(start);
    while let Some(m) = queue.pop_front() {
        for (from, to) in r.from.iter().zip(&r.to) {
            if from.is_empty() || !from.iter().all(|&i| m.get(i).copied().unwrap_or(false)) {
                continue;
            }
            let mut next = m.clone();
            for &i in from {
                *next.get_mut(i)? = false;
            }
            for &i in to {
                *next.get_mut(i)? = true;
            }
            if !seen.contains(&next) {
                if seen.len() >= MAX_MARKINGS {
                    return None;
                }
                seen.insert(next.clone());
                queue.push_back(next);
            }
        }
    }
    Some(seen)
}

/// Steps that structural reasoning cannot rule out: a transition can fire
/// once each of its preceding steps can be active.
fn fixpoint(n: usize, r: &Resolved, initial: &[usize]) -> Vec<bool> {
    let mut reach = vec![false; n];
    for &i in initial {
        if let Some(x) = reach.get_mut(i) {
            *x = true;
        }
    }
    let mut changed = true;
    while changed {
        changed = false;
        for (from, to) in r.from.iter().zip(&r.to) {
            if from.is_empty() || !from.iter().all(|&i| reach.get(i).copied().unwrap_or(false)) {
                continue;
            }
            for &i in to {
                if let Some(x) = reach.get_mut(i) {
                    if !*x {
                        *x = true;
                        changed = true;
                    }
                }
            }
        }
    }
    reach
}
