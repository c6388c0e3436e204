//! Name resolution and structural checks of a chart, before code is
//! generated: unknown and duplicate names (E121, E122, E131), initial steps
//! (E123, E124, per chart and macro body), macro-steps' exit steps and
//! transitions crossing a macro body's edge (E121), associations (E125,
//! E126, E128, E129) and the warnings
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

use super::flat::Flat;
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
    /// Per transition: the indexes of its known FROM and TO steps; a
    /// macro-step is followed by its body's exit step (FROM) or initial
    /// step (TO), and so on down nested macro-steps.
    pub from: Vec<Vec<usize>>,
    pub to: Vec<Vec<usize>>,
    /// Per step: the index in `macros` when it is a macro-step.
    pub macro_of: Vec<Option<usize>>,
    /// Per macro-step of the flat chart (same order as `Flat::macros`).
    pub macros: Vec<MacroR>,
    /// Step and action names that are also variables of the POU: their
    /// instances get hidden names (the variable keeps the name).
    pub clash: HashSet<Symbol>,
}

/// A macro-step, resolved.
pub(super) struct MacroR {
    /// Its index in the flat chart's steps.
    pub step: usize,
    /// Its body's initial and exit steps, when known.
    pub entry: Option<usize>,
    pub exit: Option<usize>,
    /// Every step of its body and of the bodies nested in it that is not a
    /// macro-step itself: the macro-step is active while one of them is.
    pub body: Vec<usize>,
}

/// Resolves the names of the flat chart against itself and the POU's
/// variables.
pub(super) fn resolve(
    flat: &Flat,
    vars: &HashSet<Symbol>,
    interner: &Interner,
    diags: &mut Vec<Diagnostic>,
) -> Resolved {
    let chart = &flat.chart;
    let mut r = Resolved {
        step_ok: vec![false; chart.steps.len()],
        action_ok: vec![false; chart.actions.len()],
        step_of: HashMap::new(),
        action_of: HashMap::new(),
        from: Vec::new(),
        to: Vec::new(),
        macro_of: vec![None; chart.steps.len()],
        macros: Vec::new(),
        clash: HashSet::new(),
    };
    for (k, m) in flat.macros.iter().enumerate() {
        if let Some(x) = r.macro_of.get_mut(m.step) {
            *x = Some(k);
        }
    }
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
    resolve_macros(flat, &mut r, interner, diags);
    let mut tnames: HashMap<Symbol, Span> = HashMap::new();
    for (ti, t) in chart.transitions.iter().enumerate() {
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
        let level = flat.trans_level.get(ti).copied().unwrap_or(0);
        let from = step_list(flat, &r, level, &t.from, "FROM", interner, diags);
        let to = step_list(flat, &r, level, &t.to, "TO", interner, diags);
        let from = expand(&r, from, |m| m.exit);
        let to = expand(&r, to, |m| m.entry);
        r.from.push(from);
        r.to.push(to);
    }
    r
}

/// The entry, exit and body of each macro-step (E121 for an exit step that
/// is not in the body; a body without an initial step is E123 in [`check`]).
fn resolve_macros(flat: &Flat, r: &mut Resolved, interner: &Interner, diags: &mut Vec<Diagnostic>) {
    for (k, m) in flat.macros.iter().enumerate() {
        let level = k + 1;
        let in_body = |i: usize| flat.step_level.get(i) == Some(&level);
        let entry = (0..flat.chart.steps.len()).find(|&i| {
            in_body(i)
                && r.step_ok.get(i).copied().unwrap_or(false)
                && flat.written_initial.get(i).copied().unwrap_or(false)
        });
        let mname = flat
            .chart
            .steps
            .get(m.step)
            .map_or("?", |s| interner.name(s.name.sym));
        let xname = interner.name(m.exit.sym);
        let exit = match r.step_of.get(&m.exit.sym) {
            Some(&i) if in_body(i) => Some(i),
            Some(_) => {
                diags.push(Diagnostic::error(
                    Code::E121,
                    m.exit.span,
                    format!(
                        "the exit step `{xname}` of macro-step `{mname}` is not a step of its body"
                    ),
                ));
                None
            }
            None => {
                diags.push(Diagnostic::error(
                    Code::E121,
                    m.exit.span,
                    format!("unknown exit step `{xname}` of macro-step `{mname}`"),
                ));
                None
            }
        };
        let body = (0..flat.chart.steps.len())
            .filter(|&i| {
                r.step_ok.get(i).copied().unwrap_or(false)
                    && r.macro_of.get(i).copied().flatten().is_none()
                    && flat
                        .step_level
                        .get(i)
                        .is_some_and(|&l| flat.nested_in(l, level))
            })
            .collect();
        r.macros.push(MacroR {
            step: m.step,
            entry,
            exit,
            body,
        });
    }
}

/// `steps` with each macro-step followed by the step `pick` gives of its
/// body, down nested macro-steps (an unknown one ends the chain).
fn expand(r: &Resolved, steps: Vec<usize>, pick: impl Fn(&MacroR) -> Option<usize>) -> Vec<usize> {
    let mut out = Vec::with_capacity(steps.len());
    for s in steps {
        out.push(s);
        let mut cur = s;
        // Each link goes one level deeper, so at most one per macro-step.
        for _ in 0..r.macros.len() {
            let Some(next) = r
                .macro_of
                .get(cur)
                .copied()
                .flatten()
                .and_then(|k| r.macros.get(k))
                .and_then(&pick)
            else {
                break;
            };
            if out.contains(&next) {
                break;
            }
            out.push(next);
            cur = next;
        }
    }
    out
}

/// Why a transition of `level` cannot name a step of level `l`.
fn other_level(flat: &Flat, level: usize, l: usize, name: &str, interner: &Interner) -> String {
    let macro_name = |lv: usize| {
        lv.checked_sub(1)
            .and_then(|k| flat.macros.get(k))
            .and_then(|m| flat.chart.steps.get(m.step))
            .map_or("?", |s| interner.name(s.name.sym))
    };
    if flat.nested_in(l, level) {
        // The macro-step of the transition's level whose body holds the step.
        let mut lv = l;
        for _ in 0..flat.macros.len() {
            match flat.parent(lv) {
                Some(p) if p != level && p < lv => lv = p,
                _ => break,
            }
        }
        let m = macro_name(lv);
        format!("step `{name}` is inside macro-step `{m}`: a transition enters or leaves its body through `{m}`")
    } else {
        let m = macro_name(level);
        format!("step `{name}` is outside the body of macro-step `{m}`: a transition of a macro body links steps of that body")
    }
}

/// The known steps of a FROM/TO list of a transition of `level` (E121 for
/// unknown ones and for steps of another level, E131 for repeats).
fn step_list(
    flat: &Flat,
    r: &Resolved,
    level: usize,
    list: &[crate::ast::Ident],
    what: &str,
    interner: &Interner,
    diags: &mut Vec<Diagnostic>,
) -> Vec<usize> {
    let mut out: Vec<usize> = Vec::new();
    for id in list {
        let at = r.step_of.get(&id.sym).copied();
        let other = at
            .and_then(|i| flat.step_level.get(i))
            .copied()
            .filter(|&l| l != level);
        if let Some(l) = other {
            // A duplicate of this level has the name (E122 was reported).
            let dup = flat
                .chart
                .steps
                .iter()
                .zip(&flat.step_level)
                .any(|(s, &sl)| sl == level && s.name.sym == id.sym);
            if dup {
                continue;
            }
            diags.push(Diagnostic::error(
                Code::E121,
                id.span,
                other_level(flat, level, l, interner.name(id.sym), interner),
            ));
            continue;
        }
        match at {
            Some(i) if out.contains(&i) => diags.push(Diagnostic::error(
                Code::E131,
                id.span,
                format!(
                    "step `{}` is listed twice in this {what} list",
                    interner.name(id.sym)
                ),
            )),
            Some(i) => out.push(i),
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
    flat: &Flat,
    r: &Resolved,
    vars: &HashSet<Symbol>,
    chart_span: Span,
    interner: &Interner,
    diags: &mut Vec<Diagnostic>,
) {
    let chart = &flat.chart;
    check_initial(flat, r, chart_span, interner, diags);
    // The steps active at the start (an initial macro-step's entry too).
    let initial: Vec<usize> = (0..chart.steps.len())
        .filter(|&i| r.step_ok[i] && chart.steps.get(i).is_some_and(|s| s.initial))
        .collect();
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
        // The steps of a body without an initial step (E123) are never
        // entered: that is the error, not more warnings.
        let unentered: Vec<usize> = r
            .macros
            .iter()
            .enumerate()
            .filter(|(_, m)| m.entry.is_none())
            .map(|(k, _)| k + 1)
            .collect();
        let in_unentered = |i: usize| {
            flat.step_level
                .get(i)
                .is_some_and(|&l| unentered.iter().any(|&u| flat.nested_in(l, u)))
        };
        for (i, s) in chart.steps.iter().enumerate() {
            if r.step_ok[i] && !reach.get(i).copied().unwrap_or(true) && !in_unentered(i) {
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
    // A macro-step's exit is left with the macro-step: the warning is the
    // macro-step's.
    let exits: HashSet<usize> = r.macros.iter().filter_map(|m| m.exit).collect();
    for (i, s) in chart.steps.iter().enumerate() {
        if r.step_ok[i] && !exits.contains(&i) && !r.from.iter().any(|f| f.contains(&i)) {
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

/// E123, E124: one initial step in the chart and in each macro body (as
/// written in it: a body's initial step is its entry).
fn check_initial(
    flat: &Flat,
    r: &Resolved,
    chart_span: Span,
    interner: &Interner,
    diags: &mut Vec<Diagnostic>,
) {
    let steps = &flat.chart.steps;
    check_networks(flat, r, chart_span, diags);
    for level in 1..=flat.macros.len() {
        let written = |i: usize| {
            flat.step_level.get(i) == Some(&level)
                && flat.written_initial.get(i).copied().unwrap_or(false)
        };
        // An initial step that is a duplicate (E122) is not reported again.
        if (0..steps.len()).any(|i| written(i) && !r.step_ok[i]) {
            continue;
        }
        let initial: Vec<usize> = (0..steps.len())
            .filter(|&i| r.step_ok[i] && written(i))
            .collect();
        let mac = level
            .checked_sub(1)
            .and_then(|k| flat.macros.get(k))
            .and_then(|m| steps.get(m.step));
        match (initial.as_slice(), mac) {
            ([], None) => diags.push(Diagnostic::error(
                Code::E123,
                chart_span,
                "this chart has no INITIAL_STEP",
            )),
            ([], Some(m)) => diags.push(Diagnostic::error(
                Code::E123,
                m.name.span,
                format!(
                    "the body of macro-step `{}` has no INITIAL_STEP: it is the step entered with the macro-step",
                    interner.name(m.name.sym)
                ),
            )),
            ([first, rest @ ..], _) => {
                let what = if mac.is_some() {
                    "a macro-step's body has exactly one INITIAL_STEP"
                } else {
                    "a chart has exactly one INITIAL_STEP"
                };
                for &i in rest {
                    if let (Some(s), Some(f)) = (steps.get(i), steps.get(*first)) {
                        diags.push(
                            Diagnostic::error(Code::E124, s.name.span, what)
                                .with_label(f.name.span, "the first initial step"),
                        );
                    }
                }
            }
        }
    }
}

/// E123, E124 for the chart itself: IEC 61131-3 lets a POU hold several
/// SFC networks (steps linked through transitions; a macro-step's body
/// belongs to its network), each with exactly one initial step.
fn check_networks(flat: &Flat, r: &Resolved, chart_span: Span, diags: &mut Vec<Diagnostic>) {
    let steps = &flat.chart.steps;
    let n = steps.len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let join = |parent: &mut Vec<usize>, a: usize, b: usize| {
        if a < n && b < n {
            let (ra, rb) = (root(parent, a), root(parent, b));
            parent[ra.max(rb)] = ra.min(rb);
        }
    };
    for (from, to) in r.from.iter().zip(&r.to) {
        let mut linked = from.iter().chain(to);
        if let Some(&first) = linked.next() {
            for &other in linked {
                join(&mut parent, first, other);
            }
        }
    }
    for (i, &level) in flat.step_level.iter().enumerate() {
        if let Some(m) = level.checked_sub(1).and_then(|k| flat.macros.get(k)) {
            join(&mut parent, i, m.step);
        }
    }
    let top = |i: usize| flat.step_level.get(i) == Some(&0);
    let written = |i: usize| top(i) && flat.written_initial.get(i).copied().unwrap_or(false);
    // An initial step that is a duplicate (E122) is not reported again.
    if (0..n).any(|i| written(i) && !r.step_ok[i]) {
        return;
    }
    // Per network (by its root), in the order of its first step.
    let mut networks: Vec<(usize, usize, Vec<usize>)> = Vec::new();
    for i in (0..n).filter(|&i| top(i) && r.step_ok[i]) {
        let root = root(&mut parent, i);
        let at = match networks.iter().position(|(r0, ..)| *r0 == root) {
            Some(k) => k,
            None => {
                networks.push((root, i, Vec::new()));
                networks.len() - 1
            }
        };
        if written(i) {
            networks[at].2.push(i);
        }
    }
    if networks.iter().all(|(.., initial)| initial.is_empty()) {
        diags.push(Diagnostic::error(
            Code::E123,
            chart_span,
            "this chart has no INITIAL_STEP",
        ));
        return;
    }
    for (_, first_step, initial) in &networks {
        match initial.as_slice() {
            [] => {
                if let Some(s) = steps.get(*first_step) {
                    diags.push(Diagnostic::error(
                        Code::E123,
                        s.name.span,
                        "this SFC network (the steps linked to this one through transitions) has no INITIAL_STEP",
                    ));
                }
            }
            [first, rest @ ..] => {
                for &i in rest {
                    if let (Some(s), Some(f)) = (steps.get(i), steps.get(*first)) {
                        diags.push(
                            Diagnostic::error(
                                Code::E124,
                                s.name.span,
                                "an SFC network has exactly one INITIAL_STEP (this step is linked through transitions to another initial step)",
                            )
                            .with_label(f.name.span, "the first initial step"),
                        );
                    }
                }
            }
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
            // A macro-step is active while a step of its body is (one whose
            // body has no initial step, E123, counts as a plain step).
            for m in r.macros.iter().filter(|m| m.entry.is_some()) {
                let on = m
                    .body
                    .iter()
                    .any(|&b| next.get(b).copied().unwrap_or(false));
                *next.get_mut(m.step)? = on;
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
