//! Sequential Function Charts as written (IEC 61131-3 textual SFC, and the
//! model graphical importers build). Desugared into ST statements and hidden
//! variables by the parser (`desugar::sfc`); this tree is kept for tools
//! (chart animation, graphical editors and importers).
//!
//! The chart is a bipartite graph: steps and transitions, each transition
//! naming the steps it leaves (`from`) and enters (`to`). Simultaneous
//! divergence/convergence is a transition with several `to`/`from` steps;
//! alternative divergence/convergence is several transitions sharing a
//! `from`/`to` step. Graphical forms map onto the same model: a jump to a
//! step is a transition whose `jump` flag is set (drawn as an arrow to a
//! named step instead of a line), and a macro-step carries its own body.

use super::{Expr, Ident, Stmt};
use automat_base::Span;

/// A chart: steps, transitions and actions of one POU body, in source order
/// (the order matters: actions run in declaration order and, between
/// transitions without PRIORITY, the one declared first wins).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Chart {
    pub steps: Vec<Step>,
    pub transitions: Vec<Transition>,
    pub actions: Vec<Action>,
}

impl Chart {
    /// This chart and the chart of every macro-step body in it, nested ones
    /// included, depth first in source order (a body right after the chart
    /// that holds it, before the next macro-step's). This is the order in
    /// which `desugar::sfc` flattens a chart: tools walking every step,
    /// transition or action of a chart with macro-steps use it.
    pub fn charts(&self) -> Vec<&Chart> {
        // An explicit stack, not recursion: an importer's nesting has no
        // depth limit.
        let mut out = Vec::new();
        let mut stack = vec![self];
        while let Some(c) = stack.pop() {
            out.push(c);
            let bodies = c.steps.iter().filter_map(|s| s.macro_body.as_deref());
            let at = stack.len();
            stack.extend(bodies.map(|b| &b.chart));
            stack[at..].reverse();
        }
        out
    }
}

/// `[INITIAL_]STEP name: associations END_STEP`
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    pub name: Ident,
    pub initial: bool,
    pub assocs: Vec<Assoc>,
    /// A macro-step (graphical charts): a sub-chart entered through its
    /// initial step and left when its `exit` step is active and a
    /// transition out of the macro-step fires (the rules are in the module
    /// comment of `desugar::sfc`). `initial` and `assocs` keep their
    /// meaning: an initial macro-step starts with its body's initial step
    /// active, and its associations are active while any step of its body is.
    pub macro_body: Option<Box<MacroBody>>,
    pub span: Span,
}

/// The body of a macro-step.
#[derive(Clone, Debug, PartialEq)]
pub struct MacroBody {
    pub chart: Chart,
    /// The step that must be active before the macro-step can be left.
    pub exit: Ident,
}

/// An action qualifier (IEC 61131-3 table of action qualifiers).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Qualifier {
    /// Non-stored: active while the step is.
    N,
    /// Overriding reset of the stored qualifiers.
    R,
    /// Set (stored).
    S,
    /// Time limited.
    L,
    /// Time delayed.
    D,
    /// Pulse: active for one call.
    P,
    /// Stored and time delayed.
    SD,
    /// Delayed and stored.
    DS,
    /// Stored and time limited.
    SL,
    /// Pulse on the association's activation (rising edge).
    P1,
    /// Pulse on the association's deactivation (falling edge).
    P0,
}

impl Qualifier {
    /// The qualifier spelled `text` (any case).
    pub fn parse(text: &str) -> Option<Qualifier> {
        Some(match text.to_ascii_uppercase().as_str() {
            "N" => Qualifier::N,
            "R" => Qualifier::R,
            "S" => Qualifier::S,
            "L" => Qualifier::L,
            "D" => Qualifier::D,
            "P" => Qualifier::P,
            "SD" => Qualifier::SD,
            "DS" => Qualifier::DS,
            "SL" => Qualifier::SL,
            "P1" => Qualifier::P1,
            "P0" => Qualifier::P0,
            _ => return None,
        })
    }

    /// Whether the qualifier takes a duration (`L, T#5s`).
    pub fn is_timed(self) -> bool {
        matches!(
            self,
            Qualifier::L | Qualifier::D | Qualifier::SD | Qualifier::DS | Qualifier::SL
        )
    }

    pub fn name(self) -> &'static str {
        match self {
            Qualifier::N => "N",
            Qualifier::R => "R",
            Qualifier::S => "S",
            Qualifier::L => "L",
            Qualifier::D => "D",
            Qualifier::P => "P",
            Qualifier::SD => "SD",
            Qualifier::DS => "DS",
            Qualifier::SL => "SL",
            Qualifier::P1 => "P1",
            Qualifier::P0 => "P0",
        }
    }
}

/// `name(qualifier [, time] {, indicator});` inside a step: `name` is an
/// ACTION of the chart or a BOOL variable (assigned the action's Q).
#[derive(Clone, Debug, PartialEq)]
pub struct Assoc {
    pub name: Ident,
    /// `N` when none is written.
    pub qualifier: Qualifier,
    /// The duration of a timed qualifier: a TIME literal or variable.
    pub time: Option<Expr>,
    /// Indicator variables (kept for tools; no execution meaning).
    pub indicators: Vec<Ident>,
    pub span: Span,
}

/// `TRANSITION [name] [(PRIORITY := n)] FROM steps TO steps := cond; END_TRANSITION`
#[derive(Clone, Debug, PartialEq)]
pub struct Transition {
    pub name: Option<Ident>,
    /// Lower wins among transitions sharing a preceding step.
    pub priority: Option<u32>,
    pub from: Vec<Ident>,
    pub to: Vec<Ident>,
    /// Graphical charts: the successor is drawn as a jump to a step.
    pub jump: bool,
    pub cond: Condition,
    pub span: Span,
}

/// A transition condition.
#[derive(Clone, Debug, PartialEq)]
pub enum Condition {
    /// `:= expr;`
    St(Expr),
    /// `: <IL>`: the instructions as written, their ST rewriting, and the
    /// current result at the end of the list (the condition), read after
    /// `stmts` ran.
    Il {
        il: Box<super::il::IlBody>,
        stmts: Vec<Stmt>,
        result: Expr,
    },
    /// Nothing parsed (after a syntax error); never fires.
    Missing,
}

/// `ACTION name: body END_ACTION`
#[derive(Clone, Debug, PartialEq)]
pub struct Action {
    pub name: Ident,
    pub body: ActionBody,
    pub span: Span,
}

/// The code of an action as written.
#[derive(Clone, Debug, PartialEq)]
pub enum ActionBody {
    St(Vec<Stmt>),
    /// IL instructions and their ST rewriting.
    Il {
        il: Box<super::il::IlBody>,
        stmts: Vec<Stmt>,
    },
}

impl ActionBody {
    /// The ST statements that execute the action.
    pub fn stmts(&self) -> &[Stmt] {
        match self {
            ActionBody::St(s) | ActionBody::Il { stmts: s, .. } => s,
        }
    }
}
