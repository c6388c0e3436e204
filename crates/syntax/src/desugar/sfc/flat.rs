//! Macro-steps flattened into one chart (the rules are in the parent
//! module's comment, § Macro-steps).
//!
//! Every step, transition and action of the chart and of every macro body
//! (nested ones included) is put into one flat [`Chart`], in the order of
//! [`Chart::charts`]: the chart's own, then each body's, depth first. A
//! macro-step stays a step of the flat chart (its instance carries `M.X`
//! and `M.T`) but loses its body. Each element remembers its *level*: 0 for
//! the chart itself, `k + 1` for the body of `macros[k]`; a transition only
//! links steps of its own level, and a level has its own initial step.

use crate::ast::sfc::{Chart, Step};
use crate::ast::Ident;

/// A chart with its macro bodies spliced in.
pub(super) struct Flat {
    /// No step of it has a `macro_body`; `initial` is *effective*: a step
    /// is initial when it is written INITIAL_STEP and every macro-step
    /// holding it is initial too (the body's entry of an initial
    /// macro-step starts active).
    pub chart: Chart,
    /// Per step of `chart`: its level.
    pub step_level: Vec<usize>,
    /// Per step of `chart`: written INITIAL_STEP in its own level (for a
    /// body: the step entered when its macro-step is).
    pub written_initial: Vec<bool>,
    /// Per transition of `chart`: its level.
    pub trans_level: Vec<usize>,
    /// Level `k + 1` is the body of `macros[k]`.
    pub macros: Vec<Macro>,
}

/// One macro-step of the flat chart.
pub(super) struct Macro {
    /// Its index in `Flat::chart.steps`.
    pub step: usize,
    /// The step of its body that must be active before it can be left.
    pub exit: Ident,
}

impl Flat {
    /// The level that holds level `level` (`None` for the chart itself).
    pub fn parent(&self, level: usize) -> Option<usize> {
        let m = self.macros.get(level.checked_sub(1)?)?;
        self.step_level.get(m.step).copied()
    }

    /// Whether level `level` is `within` or nested inside it.
    pub fn nested_in(&self, mut level: usize, within: usize) -> bool {
        // Each parent is a level created before its child, so the walk ends.
        loop {
            if level == within {
                return true;
            }
            match self.parent(level) {
                Some(p) if p < level => level = p,
                _ => return false,
            }
        }
    }
}

/// Flattens `chart` (no recursion: an importer's nesting has no limit).
pub(super) fn flatten(chart: &Chart) -> Flat {
    let mut f = Flat {
        chart: Chart::default(),
        step_level: Vec::new(),
        written_initial: Vec::new(),
        trans_level: Vec::new(),
        macros: Vec::new(),
    };
    // (chart, its level, whether its initial step starts active)
    let mut stack = vec![(chart, 0usize, true)];
    while let Some((c, level, live)) = stack.pop() {
        let mut bodies = Vec::new();
        for s in &c.steps {
            let initial = s.initial && live;
            if let Some(body) = &s.macro_body {
                f.macros.push(Macro {
                    step: f.chart.steps.len(),
                    exit: body.exit,
                });
                bodies.push((&body.chart, f.macros.len(), initial));
            }
            f.chart.steps.push(Step {
                name: s.name,
                initial,
                assocs: s.assocs.clone(),
                macro_body: None,
                span: s.span,
            });
            f.step_level.push(level);
            f.written_initial.push(s.initial);
        }
        for t in &c.transitions {
            f.chart.transitions.push(t.clone());
            f.trans_level.push(level);
        }
        f.chart.actions.extend(c.actions.iter().cloned());
        // Depth first in source order: the first body is popped next.
        stack.extend(bodies.into_iter().rev());
    }
    f
}
