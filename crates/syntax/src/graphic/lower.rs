//! A network as Structured Text statements, in execution order.
//!
//! Each element becomes the ST it means (IEC 61131-3 §8.2, §8.3):
//! - The left rail is `TRUE`. Several wires into one input are a wired OR.
//! - A contact computes its power flow into a hidden BOOL `__ld_n<id>`:
//!   `in AND v`, `in AND NOT v` (negated), `in AND (v AND NOT m)` with
//!   `m := v` after (rising edge; `NOT v AND m` falling), `m` a hidden BOOL
//!   memory updated on every evaluation.
//! - A coil passes its input on (`__ld_n<id> := in`) and writes `v := in`,
//!   `v := NOT in` (negated), `IF in THEN v := TRUE` (set) or `:= FALSE`
//!   (reset), `v := in AND NOT m; m := in` (rising; falling likewise).
//! - A block with an instance is a call statement `inst(EN := …, IN := …)`
//!   whose outputs are read as `inst.Q` / `inst.ENO`; a block without one is
//!   a function whose call is written where its result is used (a function
//!   whose result is not used is a call statement), `ENO => __ld_eno<id>`.
//!   Unconnected inputs of a function block keep their value; of a function
//!   they are E173. A negated pin is `NOT`; an edge on an input pin feeds
//!   the block a pulse computed as for contacts.
//! - Output variables assign, in-out variables assign when their input is
//!   connected, input variables and in-out variables read their expression.
//! - A jump is `IF in THEN GOTO label`, a return `IF in THEN RETURN`, a label
//!   marks its place; connectors and continuations are one wire.
//!
//! Order: when any element of an FBD body has a non-zero
//! `executionOrderId`, the statements follow it (elements without one come
//! after, by position). Otherwise the order is data flow: an element runs
//! after every element it reads from, rungs (connected groups of elements,
//! the rails not counted) one after the other from the top, and ties are
//! broken by position, top to bottom then left to right. A loop of wires is
//! E174: feedback goes through a variable (the reader sees the value of the
//! previous write).

use super::generated::Generated;
use super::model::*;
use super::text::Text;
use automat_base::{Code, Diagnostic, Span};
use std::collections::HashMap;

mod order;
use order::order;

pub use super::jumps::{GOTO_MARK, LABEL_MARK};

/// Blocks of one vendor's tool that are not IEC 61131-3 blocks.
const VENDOR_BLOCKS: &[(&str, &str)] = &[
    ("python_eval", "Beremiz"),
    ("python_poll", "Beremiz"),
    ("python_gear", "Beremiz"),
];

/// Where a body is being lowered: its POU and what its element ids are
/// called (both for messages: "POU `P`, localId 7: ...").
pub struct PouCtx {
    name: String,
    id_word: String,
}

impl PouCtx {
    pub fn new(name: &str, _function: bool) -> PouCtx {
        PouCtx {
            name: name.to_string(),
            id_word: "localId".to_string(),
        }
    }

    /// Messages name an element as `{word} {id}` (default `localId`).
    pub fn with_id_word(mut self, word: &str) -> PouCtx {
        self.id_word = word.to_string();
        self
    }

    pub fn pou(&self) -> &str {
        &self.name
    }
}

/// A piece of the generated Structured Text: words the lowering writes
/// (standing for the span of the element they come from) or text copied
/// from an element (mapped byte for byte).
#[derive(Clone, Debug)]
pub enum Piece {
    Gen(String, Span),
    Copy(Text),
}

/// A lowered network: the hidden BOOLs it needs (`__ld_n<id>` power flows,
/// `__ld_m<id>` edge memories, `__ld_eno<id>` …), its statements in
/// execution order, and what is wrong with it (E171–E177).
#[derive(Clone, Debug)]
pub struct Lowered {
    pub hidden: Vec<String>,
    pub statements: Vec<Piece>,
    pub diagnostics: Vec<Diagnostic>,
    /// Where the declarations of the hidden variables stand (the start of
    /// the first element).
    pub at: Span,
}

impl Lowered {
    /// `VAR <hidden> : BOOL; ... END_VAR` (nothing when there is none), to
    /// go after the POU's own declarations.
    pub fn write_vars(&self, out: &mut Generated) {
        if self.hidden.is_empty() {
            return;
        }
        out.gen("\nVAR\n", self.at);
        for h in &self.hidden {
            out.gen(&format!("{h} : BOOL;\n"), self.at);
        }
        out.gen("END_VAR\n", self.at);
    }

    /// The statements, one per line.
    pub fn write_statements(&self, out: &mut Generated) {
        for p in &self.statements {
            match p {
                Piece::Gen(s, sp) => out.gen(s, *sp),
                Piece::Copy(t) => out.copy(t),
            }
        }
    }

    /// The hidden declarations, an empty line, then the statements: the
    /// body of a POU whose declarations were written before.
    pub fn write(&self, out: &mut Generated) {
        self.write_vars(out);
        out.gen("\n", self.at);
        self.write_statements(out);
    }

    /// The statements as plain text (for looking at what a network means).
    pub fn statements_text(&self) -> String {
        let mut g = Generated::default();
        self.write_statements(&mut g);
        g.text
    }
}

struct L<'n> {
    net: &'n Network,
    pou: String,
    id_word: String,
    by_id: HashMap<u32, usize>,
    connectors: HashMap<String, usize>,
    /// Function blocks whose ENO some element reads.
    eno_read: Vec<bool>,
    /// Elements reading each element's result (not its ENO).
    readers: Vec<Vec<usize>>,
    hidden: Vec<String>,
    diags: Vec<(Code, Span, String)>,
    /// Inline expansions in progress (a loop among them is E174).
    expanding: Vec<usize>,
}

fn is_function(e: &Element) -> bool {
    matches!(&e.kind, Kind::Block { instance: None, .. })
}

/// The EN pin of a block (a function without it wired is still called).
fn is_en(p: &PinIn) -> bool {
    p.formal
        .as_deref()
        .is_some_and(|f| f.eq_ignore_ascii_case("EN"))
}

/// Elements that are statements of their own.
fn is_statement(e: &Element) -> bool {
    match &e.kind {
        Kind::Contact { .. }
        | Kind::Coil { .. }
        | Kind::OutVar { .. }
        | Kind::Label { .. }
        | Kind::Jump { .. }
        | Kind::Return => true,
        Kind::InOutVar { .. } => e.inputs.iter().any(|p| !p.conns.is_empty()),
        Kind::Block { instance, .. } => instance.is_some(),
        _ => false,
    }
}

impl<'n> L<'n> {
    fn err(&mut self, code: Code, span: Span, el: &Element, msg: impl std::fmt::Display) {
        self.diags.push((
            code,
            span,
            format!("POU `{}`, {} {}: {msg}", self.pou, self.id_word, el.id),
        ));
    }

    fn el(&self, i: usize) -> &'n Element {
        let net: &'n Network = self.net;
        &net.elements[i.min(net.elements.len().saturating_sub(1))]
    }

    /// The elements a connection reads through (continuations resolved).
    fn target(&mut self, c: &Conn, reader: &Element) -> Option<usize> {
        let Some(&i) = self.by_id.get(&c.from) else {
            self.err(
                Code::E172,
                c.span,
                reader,
                format!(
                    "a connection names localId {}, which is not in this body",
                    c.from
                ),
            );
            return None;
        };
        Some(i)
    }

    fn connector_of(&mut self, i: usize) -> Option<usize> {
        let e = self.el(i);
        let Kind::Continuation { name } = &e.kind else {
            return Some(i);
        };
        match self.connectors.get(name) {
            Some(&c) => Some(c),
            None => {
                self.err(
                    Code::E172,
                    e.span,
                    e,
                    format!("continuation `{name}` has no connector"),
                );
                None
            }
        }
    }

    /// The value of an input pin (its wires ORed, negated when the pin is).
    fn pin(&mut self, out: &mut Vec<Piece>, el: &Element, pin: &PinIn) {
        if pin.negated {
            out.push(Piece::Gen("NOT ".into(), pin.span));
        }
        let many = pin.conns.len() > 1 || pin.negated;
        if many {
            out.push(Piece::Gen("(".into(), pin.span));
        }
        for (k, c) in pin.conns.iter().enumerate() {
            if k > 0 {
                out.push(Piece::Gen(" OR ".into(), c.span));
            }
            self.source(out, el, c);
        }
        if pin.conns.is_empty() {
            out.push(Piece::Gen("FALSE".into(), pin.span));
        }
        if many {
            out.push(Piece::Gen(")".into(), pin.span));
        }
    }

    /// The value a wire carries.
    fn source(&mut self, out: &mut Vec<Piece>, reader: &Element, c: &Conn) {
        let Some(i) = self.target(c, reader).and_then(|i| self.connector_of(i)) else {
            out.push(Piece::Gen("FALSE".into(), c.span));
            return;
        };
        let e = self.el(i);
        let sp = c.span;
        match &e.kind {
            Kind::LeftRail => out.push(Piece::Gen("TRUE".into(), sp)),
            Kind::Contact { .. } | Kind::Coil { .. } => {
                out.push(Piece::Gen(format!("__ld_n{}", e.id), sp))
            }
            Kind::InVar { negated, expr } => {
                out.push(Piece::Gen(if *negated { "NOT (" } else { "(" }.into(), sp));
                out.push(Piece::Copy(expr.clone()));
                out.push(Piece::Gen(")".into(), sp));
            }
            Kind::InOutVar { expr } => {
                out.push(Piece::Gen("(".into(), sp));
                out.push(Piece::Copy(expr.clone()));
                out.push(Piece::Gen(")".into(), sp));
            }
            Kind::Block {
                type_name,
                instance,
            } => {
                let formal = c
                    .formal
                    .clone()
                    .or_else(|| e.outputs.first().and_then(|o| o.formal.clone()))
                    .unwrap_or_default();
                let negated = e.outputs.iter().any(|o| {
                    o.negated
                        && o.formal
                            .as_deref()
                            .unwrap_or("")
                            .eq_ignore_ascii_case(&formal)
                });
                if negated {
                    out.push(Piece::Gen("NOT ".into(), sp));
                }
                match instance {
                    Some(inst) => {
                        out.push(Piece::Copy(inst.clone()));
                        out.push(Piece::Gen(format!(".{formal}"), sp));
                    }
                    None if formal.eq_ignore_ascii_case("ENO") => {
                        out.push(Piece::Gen(format!("__ld_eno{}", e.id), sp))
                    }
                    None => {
                        if self.expanding.contains(&i) {
                            self.err(
                                Code::E174,
                                e.span,
                                e,
                                "this block's output comes back to its own input without a variable",
                            );
                            out.push(Piece::Gen("FALSE".into(), sp));
                            return;
                        }
                        self.expanding.push(i);
                        self.call(out, e, type_name);
                        self.expanding.pop();
                    }
                }
            }
            Kind::Connector { .. } => {
                if self.expanding.contains(&i) {
                    self.err(Code::E174, e.span, e, "a connector loops back to itself");
                    out.push(Piece::Gen("FALSE".into(), sp));
                    return;
                }
                self.expanding.push(i);
                let msg = "the connector's input is not connected";
                self.first_input(out, e, Code::E173, msg, sp);
                self.expanding.pop();
            }
            _ => {
                self.err(
                    Code::E172,
                    c.span,
                    reader,
                    format!("a connection reads localId {}, which has no output", e.id),
                );
                out.push(Piece::Gen("FALSE".into(), sp));
            }
        }
    }

    /// The standard functions spelled as ST operators (`AND` cannot be
    /// called by name in ST): `(a AND b AND …)`, `(NOT a)`, `(a MOD b)`.
    fn operator(&mut self, out: &mut Vec<Piece>, e: &Element, callee: &Text) -> bool {
        let op = callee.text.to_ascii_uppercase();
        if !matches!(op.as_str(), "AND" | "OR" | "XOR" | "NOT" | "MOD") {
            return false;
        }
        let ins: Vec<&PinIn> = e.inputs.iter().filter(|p| !is_en(p)).collect();
        let en = ins.len() < e.inputs.len();
        if en || self.reads_eno(e) {
            self.err(
                Code::E171,
                e.span,
                e,
                format!("EN/ENO on the `{op}` operator block are not supported"),
            );
        }
        let arity_ok = match op.as_str() {
            "NOT" => ins.len() == 1,
            "MOD" => ins.len() == 2,
            _ => ins.len() >= 2,
        };
        if !arity_ok {
            self.err(
                Code::E171,
                e.span,
                e,
                format!("`{op}` with {} inputs", ins.len()),
            );
            out.push(Piece::Gen("FALSE".into(), e.span));
            return true;
        }
        out.push(Piece::Gen(
            if op == "NOT" { "(NOT " } else { "(" }.into(),
            e.span,
        ));
        for (k, p) in ins.iter().enumerate() {
            if k > 0 {
                out.push(Piece::Gen(format!(" {op} "), p.span));
            }
            if p.conns.is_empty() {
                self.unconnected(e, p, &op);
                out.push(Piece::Gen("FALSE".into(), p.span));
            } else {
                out.push(Piece::Gen("(".into(), p.span));
                self.pin(out, e, p);
                out.push(Piece::Gen(")".into(), p.span));
            }
        }
        out.push(Piece::Gen(")".into(), e.span));
        true
    }

    /// A VAR_IN_OUT pin: the variable itself (no parentheses: it is
    /// written), so the wire must come from a variable element.
    fn in_out_arg(&mut self, out: &mut Vec<Piece>, e: &Element, p: &PinIn) {
        let var = match p.conns.as_slice() {
            [c] => self
                .by_id
                .get(&c.from)
                .copied()
                .map(|i| self.el(i))
                .and_then(|s| match &s.kind {
                    Kind::InVar {
                        negated: false,
                        expr,
                    }
                    | Kind::InOutVar { expr } => Some(expr.clone()),
                    _ => None,
                }),
            _ => None,
        };
        match var {
            Some(t) => out.push(Piece::Copy(t)),
            None => {
                let formal = p.formal.clone().unwrap_or_default();
                self.err(
                    Code::E171,
                    p.span,
                    e,
                    format!("the VAR_IN_OUT pin `{formal}` must be wired to one variable"),
                );
                out.push(Piece::Gen("FALSE".into(), p.span));
            }
        }
    }

    /// `F(IN1 := …, …, ENO => __ld_eno<id>)` or `inst(EN := …, IN := …)`.
    fn call(&mut self, out: &mut Vec<Piece>, e: &Element, callee: &Text) {
        if is_function(e) && self.operator(out, e, callee) {
            return;
        }
        out.push(Piece::Copy(callee.clone()));
        out.push(Piece::Gen("(".into(), e.span));
        let mut first = true;
        for (k, p) in e.inputs.iter().enumerate() {
            let formal = p.formal.clone().unwrap_or_default();
            if p.conns.is_empty() {
                if is_function(e) && !is_en(p) {
                    self.unconnected(e, p, &callee.text);
                }
                continue;
            }
            if !super::is_identifier(&formal) {
                self.err(
                    Code::E177,
                    p.span,
                    e,
                    format!("pin `{formal}` is not an identifier"),
                );
                continue;
            }
            if !first {
                out.push(Piece::Gen(", ".into(), p.span));
            }
            first = false;
            out.push(Piece::Gen(format!("{formal} := "), p.span));
            if p.in_out {
                self.in_out_arg(out, e, p);
            } else if p.edge != EdgeKind::None {
                out.push(Piece::Gen(format!("__ld_e{}_{k}", e.id), p.span));
            } else {
                self.pin(out, e, p);
            }
        }
        if is_function(e) && self.reads_eno(e) {
            if !first {
                out.push(Piece::Gen(", ".into(), e.span));
            }
            out.push(Piece::Gen(format!("ENO => __ld_eno{}", e.id), e.span));
            self.hidden.push(format!("__ld_eno{}", e.id));
        }
        out.push(Piece::Gen(")".into(), e.span));
    }

    /// Edge-detected input pins of a block: their pulses before the call.
    fn pin_edges(&mut self, out: &mut Vec<Piece>, e: &Element) {
        for (k, p) in e.inputs.iter().enumerate() {
            if p.edge == EdgeKind::None || p.conns.is_empty() {
                continue;
            }
            let (v, m, pulse) = (
                format!("__ld_v{}_{k}", e.id),
                format!("__ld_m{}_{k}", e.id),
                format!("__ld_e{}_{k}", e.id),
            );
            out.push(Piece::Gen(format!("{v} := "), p.span));
            let plain = PinIn {
                edge: EdgeKind::None,
                ..p.clone()
            };
            self.pin(out, e, &plain);
            let test = if p.edge == EdgeKind::Rising {
                format!(";\n{pulse} := {v} AND NOT {m};\n{m} := {v};\n")
            } else {
                format!(";\n{pulse} := NOT {v} AND {m};\n{m} := {v};\n")
            };
            out.push(Piece::Gen(test, p.span));
            self.hidden.extend([v, m, pulse]);
        }
    }

    /// The left connection of a contact or coil (E175 when missing).
    fn left(&mut self, out: &mut Vec<Piece>, e: &Element) {
        let msg = "nothing is connected on the left";
        self.first_input(out, e, Code::E175, msg, e.span);
    }

    /// The connected input of an output variable, jump or return.
    fn input(&mut self, out: &mut Vec<Piece>, e: &Element, what: &str) {
        let msg = format!("the input of this {what} is not connected");
        self.first_input(out, e, Code::E173, msg, e.span);
    }

    /// The element's first input pin, or `code` and a `FALSE` at `at` when
    /// nothing is wired to it (so the generated text still parses).
    fn first_input(
        &mut self,
        out: &mut Vec<Piece>,
        e: &Element,
        code: Code,
        msg: impl std::fmt::Display,
        at: Span,
    ) {
        match e.inputs.first() {
            Some(p) if !p.conns.is_empty() => self.pin(out, e, p),
            _ => {
                self.err(code, e.span, e, msg);
                out.push(Piece::Gen("FALSE".into(), at));
            }
        }
    }

    /// E173 for the input pin `p` of the call to `callee` left unwired.
    fn unconnected(&mut self, e: &Element, p: &PinIn, callee: &str) {
        let formal = p.formal.as_deref().unwrap_or_default();
        let msg = format!("input `{formal}` of `{callee}` is not connected");
        self.err(Code::E173, p.span, e, msg);
    }

    /// Whether some element reads this function's ENO (so the call names
    /// `ENO => __ld_eno<id>`).
    fn reads_eno(&self, e: &Element) -> bool {
        let idx = self.by_id.get(&e.id).copied().unwrap_or(0);
        self.eno_read.get(idx).copied().unwrap_or(false)
    }

    fn statement(&mut self, out: &mut Vec<Piece>, i: usize) {
        let e = self.el(i);
        let sp = e.span;
        let g = |out: &mut Vec<Piece>, s: String| out.push(Piece::Gen(s, sp));
        // An element missing its input is reported and left out, so the
        // checker does not add errors about a value that is not there.
        let unwired = e.inputs.first().is_none_or(|p| p.conns.is_empty());
        match &e.kind {
            Kind::Contact { .. } | Kind::Coil { .. } if unwired => {
                self.err(Code::E175, e.span, e, "nothing is connected on the left");
                return;
            }
            Kind::OutVar { .. } | Kind::Jump { .. } | Kind::Return if unwired => {
                let what = match e.kind {
                    Kind::OutVar { .. } => "output variable",
                    Kind::Jump { .. } => "jump",
                    _ => "return",
                };
                self.err(
                    Code::E173,
                    e.span,
                    e,
                    format!("the input of this {what} is not connected"),
                );
                return;
            }
            _ => {}
        }
        match &e.kind {
            Kind::Contact { negated, edge, var } => {
                let n = format!("__ld_n{}", e.id);
                let m = format!("__ld_m{}", e.id);
                g(out, format!("{n} := "));
                self.left(out, e);
                match edge {
                    EdgeKind::None => {
                        g(out, if *negated { " AND NOT (" } else { " AND (" }.into());
                        out.push(Piece::Copy(var.clone()));
                        g(out, ");\n".into());
                    }
                    EdgeKind::Rising | EdgeKind::Falling => {
                        let rising = *edge == EdgeKind::Rising;
                        g(out, if rising { " AND (" } else { " AND NOT (" }.into());
                        out.push(Piece::Copy(var.clone()));
                        g(
                            out,
                            format!(") AND {}{m};\n{m} := ", if rising { "NOT " } else { "" }),
                        );
                        out.push(Piece::Copy(var.clone()));
                        g(out, ";\n".into());
                        self.hidden.push(m);
                    }
                }
                self.hidden.push(n);
            }
            Kind::Coil {
                negated,
                storage,
                edge,
                var,
            } => {
                let n = format!("__ld_n{}", e.id);
                let m = format!("__ld_m{}", e.id);
                g(out, format!("{n} := "));
                self.left(out, e);
                g(out, ";\n".into());
                match (storage, edge) {
                    (Storage::Set, _) | (Storage::Reset, _) => {
                        g(out, format!("IF {n} THEN "));
                        out.push(Piece::Copy(var.clone()));
                        g(
                            out,
                            format!(
                                " := {}; END_IF;\n",
                                if *storage == Storage::Set {
                                    "TRUE"
                                } else {
                                    "FALSE"
                                }
                            ),
                        );
                    }
                    (Storage::None, EdgeKind::None) => {
                        out.push(Piece::Copy(var.clone()));
                        g(
                            out,
                            format!(" := {}{n};\n", if *negated { "NOT " } else { "" }),
                        );
                    }
                    (Storage::None, edge) => {
                        out.push(Piece::Copy(var.clone()));
                        let pulse = if *edge == EdgeKind::Rising {
                            format!("{n} AND NOT {m}")
                        } else {
                            format!("NOT {n} AND {m}")
                        };
                        g(out, format!(" := {pulse};\n{m} := {n};\n"));
                        self.hidden.push(m);
                    }
                }
                self.hidden.push(n);
            }
            Kind::OutVar { negated, expr } => {
                out.push(Piece::Copy(expr.clone()));
                g(out, if *negated { " := NOT (" } else { " := (" }.into());
                self.input(out, e, "output variable");
                g(out, ");\n".into());
            }
            Kind::InOutVar { expr } => {
                out.push(Piece::Copy(expr.clone()));
                g(out, " := (".into());
                self.input(out, e, "in-out variable");
                g(out, ");\n".into());
            }
            Kind::Block {
                type_name,
                instance,
            } => {
                if let Some((_, vendor)) = VENDOR_BLOCKS
                    .iter()
                    .find(|(b, _)| b.eq_ignore_ascii_case(&type_name.text))
                {
                    let msg = format!(
                        "unknown function block `{}`: a {vendor} block, not an IEC 61131-3 one",
                        type_name.text
                    );
                    self.err(Code::E176, e.span, e, msg);
                    return;
                }
                if instance.is_none()
                    && matches!(
                        type_name.text.to_ascii_uppercase().as_str(),
                        "AND" | "OR" | "XOR" | "NOT" | "MOD"
                    )
                {
                    // An operator whose result nothing reads does nothing.
                    return;
                }
                self.pin_edges(out, e);
                let callee = instance.clone().unwrap_or_else(|| type_name.clone());
                self.call(out, e, &callee);
                g(out, ";\n".into());
            }
            Kind::Label { name } => {
                g(out, format!("{LABEL_MARK} := "));
                out.push(Piece::Copy(name.clone()));
                g(out, ";\n".into());
            }
            Kind::Jump { label } => {
                g(out, "IF ".into());
                self.input(out, e, "jump");
                g(out, format!(" THEN {GOTO_MARK} := "));
                out.push(Piece::Copy(label.clone()));
                g(out, "; END_IF;\n".into());
            }
            Kind::Return => {
                g(out, "IF ".into());
                self.input(out, e, "return");
                g(out, " THEN RETURN; END_IF;\n".into());
            }
            _ => {}
        }
    }

    /// The statements that evaluate function `j` (they inline its call).
    fn hosts(&self, j: usize, acc: &mut Vec<usize>, seen: &mut Vec<usize>) {
        for &r in self.readers.get(j).into_iter().flatten() {
            if seen.contains(&r) {
                continue;
            }
            seen.push(r);
            let e = self.el(r);
            if is_statement(e) {
                acc.push(r);
            } else if is_function(e) {
                self.hosts(r, acc, seen);
            }
        }
    }

    /// The statement elements `i` reads from (through functions and
    /// connectors), for the data-flow order.
    fn deps(&self, root: usize, i: usize, acc: &mut Vec<usize>, seen: &mut Vec<usize>) {
        let e = self.el(i);
        for p in &e.inputs {
            for c in &p.conns {
                let Some(&mut_j) = self.by_id.get(&c.from) else {
                    continue;
                };
                let mut j = mut_j;
                if let Kind::Continuation { name } = &self.el(j).kind {
                    match self.connectors.get(name) {
                        Some(&k) => j = k,
                        None => continue,
                    }
                }
                if seen.contains(&j) {
                    continue;
                }
                seen.push(j);
                let s = self.el(j);
                if is_statement(s) {
                    acc.push(j);
                } else if is_function(s) || matches!(s.kind, Kind::Connector { .. }) {
                    if is_function(s)
                        && c.formal
                            .as_deref()
                            .is_some_and(|f| f.eq_ignore_ascii_case("ENO"))
                    {
                        // The function's ENO is set where its result is used.
                        if self.readers[j].is_empty() {
                            acc.push(j);
                        }
                        // Of several, the first by position (the others
                        // set the same ENO again).
                        let mut hs = Vec::new();
                        self.hosts(j, &mut hs, &mut vec![j]);
                        hs.retain(|&r| r != root);
                        let net = self.net;
                        let at =
                            |r: usize| (net.elements[r].y, net.elements[r].x, net.elements[r].id);
                        let first = hs.into_iter().min_by(|a, b| {
                            at(*a)
                                .partial_cmp(&at(*b))
                                .unwrap_or(std::cmp::Ordering::Equal)
                        });
                        acc.extend(first);
                    }
                    self.deps(root, j, acc, seen);
                }
            }
        }
    }
}

/// Lowers a network to its hidden variables and statements (never panics:
/// what is wrong is in [`Lowered::diagnostics`]).
pub fn lower(net: &Network, ctx: &PouCtx) -> Lowered {
    let n = net.elements.len();
    let mut l = L {
        net,
        pou: ctx.pou().to_string(),
        id_word: ctx.id_word.clone(),
        by_id: HashMap::new(),
        connectors: HashMap::new(),
        eno_read: vec![false; n],
        readers: vec![Vec::new(); n],
        hidden: Vec::new(),
        diags: Vec::new(),
        expanding: Vec::new(),
    };
    for (i, e) in net.elements.iter().enumerate() {
        if l.by_id.insert(e.id, i).is_some() {
            l.err(Code::E172, e.span, e, "two elements share this localId");
        }
        if let Kind::Connector { name } = &e.kind {
            l.connectors.insert(name.clone(), i);
        }
    }
    for (i, e) in net.elements.iter().enumerate() {
        for p in &e.inputs {
            for c in &p.conns {
                if let Some(&j) = l.by_id.get(&c.from) {
                    if c.formal
                        .as_deref()
                        .is_some_and(|f| f.eq_ignore_ascii_case("ENO"))
                    {
                        l.eno_read[j] = true;
                    } else {
                        l.readers[j].push(i);
                    }
                }
            }
        }
    }
    // A function whose result nothing reads is a statement of its own.
    let own: Vec<bool> = net
        .elements
        .iter()
        .enumerate()
        .map(|(i, e)| is_statement(e) || (is_function(e) && l.readers[i].is_empty()))
        .collect();
    let order = order(&mut l, &own);
    let mut body = Vec::new();
    for i in order {
        l.statement(&mut body, i);
    }
    let diagnostics = std::mem::take(&mut l.diags)
        .into_iter()
        .map(|(code, span, msg)| Diagnostic::error(code, span, msg))
        .collect();
    let mut hidden = std::mem::take(&mut l.hidden);
    hidden.sort();
    hidden.dedup();
    let at = net.elements.first().map_or(Span::default(), |e| e.span);
    Lowered {
        hidden,
        statements: body,
        diagnostics,
        at: Span::new(at.file, at.start, at.start),
    }
}
