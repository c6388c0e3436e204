//! Preparing a scenario: every name, type and action resolved against the
//! program and its plant (all the errors at once), each expectation made a
//! [`Check`] with its window and the first scan it can be judged at.

use super::*;

/// A scenario resolved against a program and its plant: the timed actions
/// to schedule on the [`Sim`] and the [`Judge`] of its expectations and
/// reactions.
pub struct Prepared {
    pub actions: Vec<(i64, Action)>,
    pub judge: Judge,
}

fn start_of(scope: &Scope, a: &Anchor, refs: &mut Vec<Ref>) -> Result<Start, Diagnostic> {
    Ok(match a {
        Anchor::Time(t) => Start::Time(*t),
        Anchor::Event(e) => Start::Event(scope.event(e, refs)?),
    })
}

/// Resolves every name, type and action of `scn` (all the errors at once).
pub fn prepare(scope: &Scope, scn: &Scenario) -> Result<Prepared, Vec<Diagnostic>> {
    let mut errors = Vec::new();
    let mut refs = Vec::new();
    let mut checks = Vec::new();
    for e in &scn.expects {
        match check_of(scope, e, &mut refs) {
            Ok(c) => checks.push(c),
            Err(d) => errors.push(d),
        }
    }
    let mut actions = Vec::new();
    let mut pending = Vec::new();
    let mut failures = Vec::new();
    for a in &scn.actions {
        match scope.actions(a) {
            Ok((list, located)) => {
                actions.extend(list);
                for w in located {
                    // Due before the first scan: found in the initial image.
                    if w.at_ns <= 0 {
                        match w.loc.place(&scope.program.initial_image) {
                            Ok(place) => actions.push((
                                w.at_ns,
                                Action::Write {
                                    place,
                                    value: w.value,
                                },
                            )),
                            Err(e) => failures.push(set_failure(&w, e)),
                        }
                    } else {
                        pending.push(w);
                    }
                }
            }
            Err(d) => errors.push(d),
        }
    }
    let mut reactions = Vec::new();
    for r in &scn.reactions {
        let action = ast::Action {
            at_ns: 0,
            kind: r.kind.clone(),
            line: r.line,
        };
        match (scope.event(&r.event, &mut refs), scope.actions(&action)) {
            (Ok(event), Ok((actions, located))) => reactions.push(React {
                event,
                delay_ns: r.delay_ns,
                actions,
                located,
            }),
            (Err(d), _) | (_, Err(d)) => errors.push(d),
        }
    }
    if !errors.is_empty() {
        // In the file's order (expectations were checked first).
        errors.sort_by_key(|d| d.span.start);
        return Err(errors);
    }
    let n = refs.len();
    let mut always = Vec::new();
    for r in &reactions {
        r.event.refs(&mut always);
    }
    Ok(Prepared {
        actions,
        judge: Judge {
            refs,
            vals: Vec::with_capacity(n),
            prev: Vec::with_capacity(n),
            always,
            read_at: vec![0; n],
            scans: 0,
            started: false,
            checks,
            reactions,
            failures,
            last_ns: 0,
            duration_ns: scn.duration_ns,
            pending,
            cycle_ns: 0,
        },
    })
}

/// Resolves one expectation.
pub fn check_expect(scope: &Scope, e: &ast::Expect, refs: &mut Vec<Ref>) -> Result<(), Diagnostic> {
    check_of(scope, e, refs).map(|_| ())
}

pub(super) fn check_of(
    scope: &Scope,
    e: &ast::Expect,
    refs: &mut Vec<Ref>,
) -> Result<Check, Diagnostic> {
    // Windows over which count(...) counts: `at`, `always`, `during`.
    let mut ctx = match e.when {
        When::At(_) | When::Always { .. } | When::During { .. } => Ctx::counting(),
        When::Within { .. } | When::Stable { .. } => Ctx::default(),
    };
    let cond = match e.when {
        When::Stable { .. } => scope.value_in(&e.cond, refs, &mut ctx)?,
        _ => scope.condition_in(&e.cond, refs, &mut ctx)?,
    };
    let win = match &e.when {
        When::At(t) => Win::At(*t),
        When::Within { after, within } => Win::Within {
            after: start_of(scope, after, refs)?,
            within: *within,
        },
        When::Always { from, to } => Win::Always {
            from: *from,
            to: *to,
        },
        When::During { from, to } => Win::During {
            from: *from,
            to: *to,
        },
        When::Stable { after, for_ns } => Win::Stable {
            after: start_of(scope, after, refs)?,
            for_ns: *for_ns,
        },
    };
    let mut names = Vec::new();
    cond.refs(&mut names);
    let counts = ctx.counts.unwrap_or_default();
    for c in &counts {
        c.refs(&mut names);
    }
    let mut reads = names.clone();
    let mut uses_prev = cond.uses_prev() || counts.iter().any(Cond::uses_prev);
    if let Win::Within {
        after: Start::Event(ev),
        ..
    }
    | Win::Stable {
        after: Start::Event(ev),
        ..
    } = &win
    {
        ev.refs(&mut reads);
        uses_prev |= ev.uses_prev();
    }
    // The counts as written, for the failure's values (the checker numbers
    // them left to right, as this walk meets them).
    let mut spans = Vec::new();
    count_spans(&e.cond, &mut spans);
    let count_texts = spans
        .iter()
        .map(|s| {
            let from = s.start.saturating_sub(e.span.start) as usize;
            let to = s.end.saturating_sub(e.span.start) as usize;
            e.text.get(from..to).unwrap_or("count").to_string()
        })
        .collect();
    let wake_ns = wake_of(&win, !counts.is_empty());
    Ok(Check {
        win,
        wake_ns,
        counters: vec![0.0; counts.len()],
        count_texts,
        counts,
        cond,
        text: e.text.clone(),
        line: e.line,
        names,
        reads,
        uses_prev,
        done: false,
        open: VecDeque::new(),
        seen: false,
        reference: Val::B(false),
    })
}

/// When a check starts to matter (see `Check::wake_ns`), from the cases of
/// [`judge`]: a window's counters count from its start, an `at` line
/// decides at its time, a `within`/`stable` after a time from that time;
/// a check anchored on an event looks at every scan.
pub(super) fn wake_of(win: &Win, counts: bool) -> i64 {
    match win {
        Win::At(_) if counts => i64::MIN,
        Win::At(at) => *at,
        Win::Within {
            after: Start::Time(after),
            within,
        } => after.saturating_add(1).min(after.saturating_add(*within)),
        Win::Always { from, to } => (*from).min(to.unwrap_or(i64::MAX)),
        Win::During { from, to } if counts => (*from).min(*to),
        Win::During { to, .. } => *to,
        Win::Stable {
            after: Start::Time(a),
            for_ns,
        } => (*a).min(a.saturating_add(*for_ns)),
        Win::Within { .. } | Win::Stable { .. } => i64::MIN,
    }
}

/// The spans of the `count(...)` calls in `e`, left to right.
pub(super) fn count_spans(e: &ast::Expr, out: &mut Vec<automat_base::Span>) {
    use ast::{Expr, Func};
    match e {
        Expr::Call(Func::Count, _, span) => out.push(*span),
        Expr::Call(_, args, _) => args.iter().for_each(|a| count_spans(a, out)),
        Expr::Not(x) | Expr::Neg(x, _) => count_spans(x, out),
        Expr::Logic(_, a, b) | Expr::Cmp(_, a, b) | Expr::Arith(_, a, b) => {
            count_spans(a, out);
            count_spans(b, out);
        }
        Expr::Ref(_) | Expr::Lit(..) => {}
    }
}
