//! Macro-steps of graphical SFC bodies (`<macroStep>` with its `<body><SFC>`)
//! into `Step::macro_body`, so the syntax layer's flattening runs them.
//!
//! How: the macro-step is written as an ordinary `STEP` of its chart, and
//! its body as a hidden `FUNCTION_BLOCK __macroN` after the POU, whose chart
//! the ST parser reads like any other (conditions, actions, IL). After
//! parsing, [`attach`] takes each hidden block out of the unit, moves its
//! chart into the step as its `macro_body` (nested bodies first), and
//! desugars the POU again with `automat_syntax::desugar_chart`, in place of
//! the parser's desugaring of the chart without bodies.
//!
//! The exit step: TC6 2.01 does not mark it. It is the one step of the body
//! that no transition of the body leaves; none or several is E179, naming
//! the macro-step's `localId` and POU (the macro-step then stays a plain
//! step without a body, so the rest of the file is still checked).

use crate::xml;
use crate::Imp;
use automat_base::{Code, Diagnostic, Interner, Span};
use automat_syntax::ast::sfc::{Chart, MacroBody};
use automat_syntax::ast::{Item, Lang, Pou, VarBlock};
use automat_syntax::Parsed;
use roxmltree::Node;
use std::collections::{HashMap, VecDeque};

/// One macro-step whose body was written as a hidden function block.
pub(crate) struct Link {
    /// The POU (as named in the file) whose chart holds it, at any depth.
    host: String,
    /// The XML `pou` element of `host`.
    host_span: Span,
    /// The generated POU whose chart holds the step: `host` or a body.
    parent: String,
    /// The macro-step's name.
    step: String,
    /// The hidden function block holding its body.
    hidden: String,
    local_id: String,
    /// The `macroStep` element.
    span: Span,
}

impl<'s> Imp<'s> {
    /// Writes the bodies of `macros` (macro-steps of the chart of POU `pou`)
    /// and of the macro-steps inside them, each as a hidden function block.
    pub fn macro_bodies<'a, 'i>(
        &mut self,
        macros: Vec<Node<'a, 'i>>,
        pou: Node<'a, 'i>,
        name: &str,
    ) {
        let mut queue: VecDeque<(Node, String)> =
            macros.into_iter().map(|m| (m, name.to_string())).collect();
        while let Some((m, parent)) = queue.pop_front() {
            let step = xml::attr_str(m, "name").unwrap_or("").trim().to_string();
            let local_id = xml::attr_str(m, "localId")
                .unwrap_or("?")
                .trim()
                .to_string();
            let Some(chart) = xml::child(m, "body").and_then(|b| xml::child(b, "SFC")) else {
                let sp = self.span(m);
                self.error(
                    Code::E171,
                    sp,
                    format!(
                        "POU `{name}`, localId {local_id}: macro-step `{step}` has no SFC body"
                    ),
                );
                continue;
            };
            let hidden = format!("__macro{}", self.macros.len());
            self.gen(&format!("\nFUNCTION_BLOCK {hidden}\n"), m);
            let inner = self.macro_chart(chart, pou, name);
            self.gen("\nEND_FUNCTION_BLOCK\n", m);
            queue.extend(inner.into_iter().map(|n| (n, hidden.clone())));
            self.macros.push(Link {
                host: name.to_string(),
                host_span: self.span(pou),
                parent,
                step,
                hidden,
                local_id,
                span: self.span(m),
            });
        }
    }
}

/// The chart checks of the SFC desugaring (E120–E131, W120–W131): those of
/// a POU with macro-steps are redone on the whole chart.
fn is_chart_check(d: &Diagnostic) -> bool {
    d.code
        .as_str()
        .get(1..)
        .and_then(|n| n.parse::<u32>().ok())
        .is_some_and(|n| (120..=131).contains(&n))
}

/// The parser's hidden block of a chart (its clock `__sfc_run` is in it).
fn is_chart_block(b: &VarBlock, interner: &Interner) -> bool {
    b.decls
        .iter()
        .flat_map(|d| d.names.iter())
        .any(|n| interner.name(n.sym) == "__sfc_run")
}

fn pou_named<'p>(items: &'p mut [Item], name: &str, interner: &Interner) -> Option<&'p mut Pou> {
    items.iter_mut().find_map(|i| match i {
        Item::Pou(p) if interner.name(p.name.sym).eq_ignore_ascii_case(name) => Some(p),
        _ => None,
    })
}

/// The one step of `chart` no transition leaves, or the message why not.
fn exit_step(chart: &Chart, interner: &Interner) -> Result<automat_syntax::ast::Ident, String> {
    let ends: Vec<_> = chart
        .steps
        .iter()
        .filter(|s| {
            !chart
                .transitions
                .iter()
                .any(|t| t.from.iter().any(|f| f.sym == s.name.sym))
        })
        .map(|s| s.name)
        .collect();
    match ends.as_slice() {
        [one] => Ok(*one),
        [] => Err("every step of its body is left by a transition".to_string()),
        many => Err(format!(
            "{} steps of its body are left by no transition ({})",
            many.len(),
            many.iter()
                .map(|s| format!("`{}`", interner.name(s.sym)))
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

/// Moves each hidden body into its macro-step and desugars the POUs that
/// hold macro-steps again (see the module comment).
pub(crate) fn attach(parsed: &mut Parsed, links: &[Link], interner: &mut Interner) {
    if links.is_empty() {
        return;
    }
    parsed.diagnostics.retain(|d| {
        !(is_chart_check(d)
            && links.iter().any(|l| {
                l.host_span.file == d.span.file
                    && l.host_span.start <= d.span.start
                    && d.span.start < l.host_span.end
            }))
    });
    let mut bodies: HashMap<String, Pou> = HashMap::new();
    for item in std::mem::take(&mut parsed.unit.items) {
        match item {
            // By name and by place: a POU of the file named `__macroN` is
            // not taken for a body.
            Item::Pou(p)
                if links.iter().any(|l| {
                    l.hidden == interner.name(p.name.sym)
                        && p.span.file == l.span.file
                        && l.span.start <= p.span.start
                        && p.span.start < l.span.end
                }) =>
            {
                bodies.insert(interner.name(p.name.sym).to_string(), p);
            }
            other => parsed.unit.items.push(other),
        }
    }
    // Hidden blocks of IL texts in the bodies (`__CR`), for their host.
    let mut il_blocks: Vec<(String, VarBlock)> = Vec::new();
    // A body's link comes after its parent's: the deepest bodies first.
    for l in links.iter().rev() {
        let Some(body) = bodies.remove(&l.hidden) else {
            continue;
        };
        let Lang::Sfc(chart) = body.lang else {
            continue;
        };
        let exit = match exit_step(&chart, interner) {
            Ok(e) => e,
            Err(why) => {
                parsed.diagnostics.push(Diagnostic::error(
                    Code::E179,
                    l.span,
                    format!(
                        "POU `{}`, localId {}: macro-step `{}` has no exit step: {why}; its exit step must be the one step of its body that no transition leaves",
                        l.host, l.local_id, l.step
                    ),
                ));
                continue;
            }
        };
        for b in body.var_blocks {
            if !is_chart_block(&b, interner) {
                il_blocks.push((l.host.clone(), b));
            }
        }
        let parent = match bodies.get_mut(&l.parent) {
            Some(p) => Some(p),
            None => pou_named(&mut parsed.unit.items, &l.parent, interner),
        };
        let Some(Lang::Sfc(pc)) = parent.map(|p| &mut p.lang) else {
            continue;
        };
        let step = pc
            .steps
            .iter_mut()
            .find(|s| interner.name(s.name.sym).eq_ignore_ascii_case(&l.step));
        if let Some(s) = step {
            s.macro_body = Some(Box::new(MacroBody {
                chart: *chart,
                exit,
            }));
        }
    }
    let mut hosts: Vec<&str> = links.iter().map(|l| l.host.as_str()).collect();
    hosts.dedup();
    for host in hosts {
        let Some(p) = pou_named(&mut parsed.unit.items, host, interner) else {
            continue;
        };
        p.var_blocks.retain(|b| !is_chart_block(b, interner));
        for (_, b) in il_blocks.iter().filter(|(h, _)| h == host) {
            let mut b = b.clone();
            let declared = |n: &automat_syntax::ast::Ident, p: &Pou| {
                p.var_blocks
                    .iter()
                    .flat_map(|v| v.decls.iter())
                    .flat_map(|d| d.names.iter())
                    .any(|m| m.sym == n.sym)
            };
            b.decls.retain(|d| !d.names.iter().any(|n| declared(n, p)));
            if !b.decls.is_empty() {
                p.var_blocks.push(b);
            }
        }
        let diags = automat_syntax::desugar_chart(p, interner);
        parsed.diagnostics.extend(diags);
    }
    parsed.diagnostics.sort_by_key(|d| d.span.start);
}
