//! Graphical SFC bodies (`<SFC>`) as textual SFC, which the ST parser reads
//! and desugars like a `.st` chart.
//!
//! Steps become `STEP`/`INITIAL_STEP` with the associations of the action
//! blocks wired to them; each transition becomes `TRANSITION FROM … TO …`
//! with the steps found by following its wires back (through selection
//! divergences and simultaneous convergences) and forward (through
//! simultaneous divergences, selection convergences and jumps to a step).
//! Conditions are inline ST or IL, a reference to a transition of the
//! POU, or a wire to input variables and contacts in the body (`wired`); actions are the POU's actions or inline bodies of an action block
//! (named `__ab<localId>_<n>`).

use crate::xml::{self, Text};
use crate::Imp;
use automat_base::Code;
use roxmltree::Node;
use std::collections::HashMap;

/// The wires of one body: element by `localId`, and who reads whom.
struct Wires<'a, 'i> {
    by_id: HashMap<u32, Node<'a, 'i>>,
    readers: HashMap<u32, Vec<u32>>,
}

fn local_id(n: Node) -> Option<u32> {
    xml::attr_str(n, "localId").and_then(|v| v.trim().parse().ok())
}

/// The `refLocalId`s of an element's own `connectionPointIn`s.
fn sources(n: Node) -> Vec<u32> {
    xml::children(n, "connectionPointIn")
        .flat_map(|cp| xml::children(cp, "connection"))
        .filter_map(|c| xml::attr_str(c, "refLocalId").and_then(|v| v.trim().parse().ok()))
        .collect()
}

/// Text without one trailing `;` (an ST condition may end with one).
fn without_semicolon(t: &Text) -> Text {
    let t = t.trimmed();
    match t.text.strip_suffix(';') {
        Some(s) => Text {
            text: s.to_string(),
            raw: t
                .raw
                .get(..=s.len())
                .map(<[u32]>::to_vec)
                .unwrap_or_default(),
        }
        .trimmed(),
        None => t,
    }
}

impl Imp<'_> {
    /// The chart of a POU: its elements, the POU's actions, then the inline
    /// actions of its action blocks. Returns the macro-steps met, whose
    /// bodies `pou.rs` writes after the POU (see `macros.rs`).
    pub fn sfc<'a, 'i>(
        &mut self,
        body: Node<'a, 'i>,
        pou: Node<'a, 'i>,
        pou_name: &str,
    ) -> Vec<Node<'a, 'i>> {
        let (actions, macros) = self.sfc_elements(body, pou, pou_name);
        if let Some(acts) = xml::child(pou, "actions") {
            for a in xml::children(acts, "action") {
                let Some(name) = self.name_attr(a, "name", "an action's name") else {
                    continue;
                };
                let Some(lang) = xml::child(a, "body").and_then(|b| {
                    xml::elements(b).find(|l| matches!(l.tag_name().name(), "ST" | "IL"))
                }) else {
                    let sp = self.span(a);
                    self.error(
                        Code::E171,
                        sp,
                        format!(
                            "action `{}`: only ST and IL action bodies are supported",
                            name.text
                        ),
                    );
                    continue;
                };
                self.gen("\nACTION ", a);
                self.out.copy(&name);
                self.gen(":\n", a);
                let t = xml::formatted(self.src, lang);
                self.out.copy(&t);
                self.gen("\nEND_ACTION\n", a);
            }
        }
        self.inline_actions(actions);
        macros
    }

    /// Inline action bodies as the chart's ACTIONs.
    fn inline_actions(&mut self, actions: Vec<(String, Text, Node)>) {
        for (name, text, at) in actions {
            self.gen(&format!("\nACTION {name}:\n"), at);
            self.out.copy(&text);
            self.gen("\nEND_ACTION\n", at);
        }
    }

    /// The body of a macro-step (its `SFC`): elements and inline actions.
    pub fn macro_chart<'a, 'i>(
        &mut self,
        body: Node<'a, 'i>,
        pou: Node<'a, 'i>,
        pou_name: &str,
    ) -> Vec<Node<'a, 'i>> {
        let (actions, macros) = self.sfc_elements(body, pou, pou_name);
        self.inline_actions(actions);
        macros
    }

    /// Steps, macro-steps and transitions of one chart (a POU's or a
    /// macro-step's body), with the inline actions and macro-steps found.
    #[allow(clippy::type_complexity)]
    fn sfc_elements<'a, 'i>(
        &mut self,
        body: Node<'a, 'i>,
        pou: Node<'a, 'i>,
        pou_name: &str,
    ) -> (Vec<(String, Text, Node<'a, 'i>)>, Vec<Node<'a, 'i>>) {
        let mut w = Wires {
            by_id: HashMap::new(),
            readers: HashMap::new(),
        };
        for e in xml::elements(body) {
            let Some(id) = local_id(e) else { continue };
            if w.by_id.insert(id, e).is_some() {
                let sp = self.span(e);
                self.error(
                    Code::E172,
                    sp,
                    format!("POU `{pou_name}`: two elements share localId {id}"),
                );
            }
            for s in sources(e) {
                w.readers.entry(s).or_default().push(id);
            }
        }
        let mut actions: Vec<(String, Text, Node)> = Vec::new();
        let mut macros = Vec::new();
        self.gen("\n", body);
        for e in xml::elements(body) {
            match e.tag_name().name() {
                "step" => {
                    self.step(e, &w, pou_name, &mut actions);
                }
                // A step here; its body becomes `Step::macro_body` after
                // parsing (`macros.rs`).
                "macroStep" => {
                    if self.step(e, &w, pou_name, &mut actions) {
                        macros.push(e);
                    }
                }
                "transition" => self.transition(e, &w, pou, pou_name),
                "selectionDivergence"
                | "selectionConvergence"
                | "simultaneousDivergence"
                | "simultaneousConvergence"
                | "jumpStep"
                | "actionBlock"
                | "comment"
                | "addData" => {}
                // Read through the wired condition of a transition.
                "inVariable" | "contact" | "leftPowerRail" => {}
                "vendorElement" => {
                    let sp = self.span(e);
                    let what = crate::graph::vendor_element(self.src, e);
                    self.error(
                        Code::E171,
                        sp,
                        format!("POU `{pou_name}`: {what}, not an IEC 61131-3 element: automat cannot run it"),
                    );
                }
                other => {
                    let sp = self.span(e);
                    self.error(
                        Code::E171,
                        sp,
                        format!("POU `{pou_name}`: `{other}` in an SFC body is not supported"),
                    );
                }
            }
        }
        (actions, macros)
    }

    /// A step or macro-step with the associations of its action blocks;
    /// false when it has no usable name (nothing written).
    fn step<'a, 'i>(
        &mut self,
        e: Node<'a, 'i>,
        w: &Wires<'a, 'i>,
        pou_name: &str,
        actions: &mut Vec<(String, Text, Node<'a, 'i>)>,
    ) -> bool {
        let Some(name) = self.name_attr(e, "name", "a step's name") else {
            return false;
        };
        self.gen(
            if xml::flag(e, "initialStep") {
                "INITIAL_STEP "
            } else {
                "STEP "
            },
            e,
        );
        self.out.copy(&name);
        self.gen(":\n", e);
        let id = local_id(e).unwrap_or(u32::MAX);
        for r in w.readers.get(&id).into_iter().flatten() {
            let Some(block) = w.by_id.get(r).filter(|b| xml::is(**b, "actionBlock")) else {
                continue;
            };
            for (k, a) in xml::children(*block, "action").enumerate() {
                let q = xml::attr_str(a, "qualifier").unwrap_or("N").trim();
                if automat_syntax::ast::sfc::Qualifier::parse(q).is_none() {
                    let sp = self.span(a);
                    self.error(
                        Code::E171,
                        sp,
                        format!("POU `{pou_name}`: unknown action qualifier `{q}`"),
                    );
                    continue;
                }
                if let Some(rf) = xml::child(a, "reference") {
                    let Some(n) = self.name_attr(rf, "name", "an action's name") else {
                        continue;
                    };
                    self.out.copy(&n);
                } else if let Some(lang) = xml::child(a, "inline").and_then(|i| {
                    xml::elements(i).find(|l| matches!(l.tag_name().name(), "ST" | "IL"))
                }) {
                    let bid = local_id(*block).unwrap_or(0);
                    let n = format!("__ab{bid}_{k}");
                    self.gen(&n, a);
                    actions.push((n, xml::formatted(self.src, lang), a));
                } else {
                    let sp = self.span(a);
                    self.error(
                        Code::E171,
                        sp,
                        format!("POU `{pou_name}`: an action without a reference or an ST/IL body"),
                    );
                    continue;
                }
                self.gen("(", a);
                self.gen(q, a);
                if let Some(d) = xml::attr(self.src, a, "duration").map(|d| d.trimmed()) {
                    if !d.text.is_empty() {
                        self.gen(", ", a);
                        self.expr_text(&d, a, false);
                    }
                }
                self.gen(");\n", a);
            }
        }
        self.gen("END_STEP\n", e);
        true
    }

    /// Steps before a transition (through selection divergences and
    /// simultaneous convergences).
    fn back(&mut self, id: u32, w: &Wires, seen: &mut Vec<u32>, out: &mut Vec<Text>) {
        if seen.contains(&id) {
            return;
        }
        seen.push(id);
        let Some(&e) = w.by_id.get(&id) else { return };
        match e.tag_name().name() {
            "step" | "macroStep" => out.extend(xml::attr(self.src, e, "name").map(|t| t.trimmed())),
            "selectionDivergence" | "simultaneousConvergence" => {
                for s in sources(e) {
                    self.back(s, w, seen, out);
                }
            }
            _ => {}
        }
    }

    /// Steps after a transition (through simultaneous divergences,
    /// selection convergences and jumps).
    fn forward(&mut self, id: u32, w: &Wires, seen: &mut Vec<u32>, out: &mut Vec<Text>) {
        for r in w.readers.get(&id).into_iter().flatten() {
            if seen.contains(r) {
                continue;
            }
            seen.push(*r);
            let Some(&e) = w.by_id.get(r) else { continue };
            match e.tag_name().name() {
                "step" | "macroStep" => {
                    out.extend(xml::attr(self.src, e, "name").map(|t| t.trimmed()))
                }
                "jumpStep" => out.extend(xml::attr(self.src, e, "targetName").map(|t| t.trimmed())),
                "simultaneousDivergence" | "selectionConvergence" => self.forward(*r, w, seen, out),
                _ => {}
            }
        }
    }

    fn transition(&mut self, e: Node, w: &Wires, pou: Node, pou_name: &str) {
        let id = local_id(e).unwrap_or(u32::MAX);
        let (mut from, mut to) = (Vec::new(), Vec::new());
        for s in sources(e) {
            self.back(s, w, &mut vec![id], &mut from);
        }
        self.forward(id, w, &mut vec![id], &mut to);
        let sp = self.span(e);
        if from.is_empty() || to.is_empty() {
            self.error(
                Code::E173,
                sp,
                format!(
                    "POU `{pou_name}`, localId {id}: the transition has no step {}",
                    if from.is_empty() {
                        "before it"
                    } else {
                        "after it"
                    }
                ),
            );
            return;
        }
        if from
            .iter()
            .chain(&to)
            .any(|t| !crate::names::is_identifier(&t.text))
        {
            self.error(
                Code::E177,
                sp,
                format!("POU `{pou_name}`, localId {id}: a step name is not an identifier"),
            );
            return;
        }
        self.gen("TRANSITION ", e);
        if let Some(p) = xml::attr_str(e, "priority")
            .map(str::trim)
            .filter(|p| p.chars().all(|c| c.is_ascii_digit()) && !p.is_empty())
        {
            self.gen(&format!("(PRIORITY := {p}) "), e);
        }
        self.gen("FROM ", e);
        self.step_list(&from, e);
        self.gen(" TO ", e);
        self.step_list(&to, e);
        let cond = xml::child(e, "condition");
        let inline = cond
            .and_then(|c| xml::child(c, "inline"))
            .and_then(|i| xml::elements(i).find(|l| matches!(l.tag_name().name(), "ST" | "IL")));
        let referenced = cond.and_then(|c| xml::child(c, "reference")).and_then(|r| {
            let name = xml::attr_str(r, "name")?.trim().to_string();
            let ts = xml::child(pou, "transitions")?;
            let t = xml::children(ts, "transition").find(|t| {
                xml::attr_str(*t, "name").is_some_and(|n| n.trim().eq_ignore_ascii_case(&name))
            })?;
            xml::child(t, "body")
                .and_then(|b| xml::elements(b).find(|l| matches!(l.tag_name().name(), "ST" | "IL")))
        });
        let wired = cond.and_then(|c| xml::child(c, "connectionPointIn"));
        if let (None, None, Some(cp)) = (inline, referenced, wired) {
            self.gen(" := ", e);
            self.wired(cp, w, pou_name, 0);
            self.gen(";\nEND_TRANSITION\n", e);
            return;
        }
        match inline.or(referenced) {
            Some(lang) if lang.tag_name().name() == "IL" => {
                self.gen(" :\n", e);
                let t = xml::formatted(self.src, lang);
                self.out.copy(&t);
                self.gen("\nEND_TRANSITION\n", e);
            }
            Some(lang) => {
                let t = xml::formatted(self.src, lang).trimmed();
                let t = match t.text.strip_prefix(":=") {
                    Some(_) => Text {
                        text: t.text.get(2..).unwrap_or("").to_string(),
                        raw: t.raw.get(2..).map(<[u32]>::to_vec).unwrap_or_default(),
                    },
                    None => t,
                };
                self.gen(" := ", e);
                let t = without_semicolon(&t);
                self.expr_text(&t, lang, true);
                self.gen(";\nEND_TRANSITION\n", e);
            }
            None => {
                self.error(
                    Code::E171,
                    sp,
                    format!("POU `{pou_name}`, localId {id}: the transition's condition is neither inline ST/IL, a reference to a transition of the POU, nor a wire"),
                );
                self.gen(" := FALSE;\nEND_TRANSITION\n", e);
            }
        }
    }

    /// A condition given by a wire (Beremiz): the OR of the wires into `cp`,
    /// each an input variable (`NOT` when negated), a left power rail
    /// (TRUE) or a normally open / negated contact (its input AND its
    /// variable). Edge contacts need a memory a condition cannot keep, and
    /// blocks are not read here: E171.
    fn wired(&mut self, cp: Node, w: &Wires, pou_name: &str, depth: u32) {
        let conns: Vec<u32> = xml::children(cp, "connection")
            .filter_map(|c| xml::attr_str(c, "refLocalId").and_then(|v| v.trim().parse().ok()))
            .collect();
        if conns.is_empty() {
            let sp = self.span(cp);
            self.error(
                Code::E173,
                sp,
                format!("POU `{pou_name}`: a transition condition's wire is not connected"),
            );
            self.gen("FALSE", cp);
            return;
        }
        self.gen("(", cp);
        for (k, id) in conns.into_iter().enumerate() {
            if k > 0 {
                self.gen(" OR ", cp);
            }
            self.wired_source(cp, id, w, pou_name, depth + 1);
        }
        self.gen(")", cp);
    }

    fn wired_source(&mut self, at: Node, id: u32, w: &Wires, pou_name: &str, depth: u32) {
        /// Deeper than any drawn condition: a loop of wires.
        const MAX_DEPTH: u32 = 60;
        let Some(&n) = w.by_id.get(&id) else {
            let sp = self.span(at);
            self.error(
                Code::E172,
                sp,
                format!("POU `{pou_name}`: a transition condition's wire names localId {id}, which the body does not have"),
            );
            self.gen("FALSE", at);
            return;
        };
        if depth > MAX_DEPTH {
            let sp = self.span(n);
            self.error(
                Code::E174,
                sp,
                format!("POU `{pou_name}`, localId {id}: a transition condition's wires loop (or chain more than {MAX_DEPTH} elements)"),
            );
            self.gen("FALSE", n);
            return;
        }
        let text_of = |imp: &Imp, child: &str| {
            xml::child(n, child).map(|c| xml::content(imp.src, c).trimmed())
        };
        match n.tag_name().name() {
            "leftPowerRail" => self.gen("TRUE", n),
            "inVariable" => {
                if xml::flag(n, "negated") {
                    self.gen("NOT ", n);
                }
                let t = text_of(self, "expression").unwrap_or_default();
                self.expr_text(&t, n, true);
            }
            "contact" if xml::attr_str(n, "edge").is_some_and(|e| e.trim() != "none") => {
                let sp = self.span(n);
                self.error(
                    Code::E171,
                    sp,
                    format!("POU `{pou_name}`, localId {id}: an edge contact in a transition condition (a condition keeps no memory)"),
                );
                self.gen("FALSE", n);
            }
            "contact" => {
                self.gen("(", n);
                match xml::child(n, "connectionPointIn") {
                    Some(cp) => self.wired(cp, w, pou_name, depth),
                    None => {
                        let sp = self.span(n);
                        self.error(
                            Code::E175,
                            sp,
                            format!(
                                "POU `{pou_name}`, localId {id}: nothing is connected on the left"
                            ),
                        );
                        self.gen("FALSE", n);
                    }
                }
                self.gen(" AND ", n);
                if xml::flag(n, "negated") {
                    self.gen("NOT ", n);
                }
                let t = text_of(self, "variable").unwrap_or_default();
                self.expr_text(&t, n, true);
                self.gen(")", n);
            }
            other => {
                let sp = self.span(n);
                self.error(
                    Code::E171,
                    sp,
                    format!("POU `{pou_name}`, localId {id}: `{other}` in a transition condition (input variables, contacts and a left power rail are read)"),
                );
                self.gen("FALSE", n);
            }
        }
    }

    fn step_list(&mut self, steps: &[Text], at: Node) {
        let many = steps.len() > 1;
        if many {
            self.gen("(", at);
        }
        for (k, s) in steps.iter().enumerate() {
            if k > 0 {
                self.gen(", ", at);
            }
            self.out.copy(s);
        }
        if many {
            self.gen(")", at);
        }
    }
}
