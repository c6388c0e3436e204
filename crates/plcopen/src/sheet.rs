//! The drawing sheet of a graphical body (LD, FBD, SFC) as the file gives
//! it: every element with its `localId`, position, size, text and pins, and
//! every wire with the route points the file stores. `automat draw` lays it
//! out (positions of the file when present) and renders it; nothing here
//! is about execution (that is `graph/`).

use crate::xml;
use roxmltree::{Document, Node, ParsingOptions};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SheetLang {
    Ld,
    Fbd,
    Sfc,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NodeKind {
    LeftRail,
    RightRail,
    Contact,
    Coil,
    Block,
    InVar,
    OutVar,
    InOutVar,
    Label,
    Jump,
    Return,
    Connector,
    Continuation,
    Step,
    MacroStep,
    Transition,
    SelectionDivergence,
    SelectionConvergence,
    SimultaneousDivergence,
    SimultaneousConvergence,
    JumpStep,
    ActionBlock,
    Comment,
}

/// One wire into an input pin: from output `from_pin` of element `from`,
/// through the `points` the file stores (may be empty).
#[derive(Clone, Debug, PartialEq)]
pub struct Wire {
    pub from: u32,
    pub from_pin: Option<String>,
    pub points: Vec<(f64, f64)>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Pin {
    /// `formalParameter` (blocks), empty otherwise.
    pub name: String,
    pub negated: bool,
    /// `P`/`N` for a rising/falling edge pin, empty otherwise.
    pub edge: &'static str,
    /// `relPosition` as the file gives it.
    pub rel: Option<(f64, f64)>,
    pub wires: Vec<Wire>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct SheetNode {
    pub id: u32,
    pub kind: NodeKind,
    /// `position` (None when the file gives none).
    pub pos: Option<(f64, f64)>,
    /// `width`/`height` when the file gives them (non-zero).
    pub size: Option<(f64, f64)>,
    /// The variable, expression, type name, label, step name, condition.
    pub text: String,
    /// A block's instance name.
    pub instance: String,
    /// What a contact or coil does: "", "/", "P", "N", "S", "R" (negated,
    /// edges, set, reset); "initial" for an initial step.
    pub mark: &'static str,
    pub ins: Vec<Pin>,
    pub outs: Vec<Pin>,
    /// Action block lines: (qualifier, action or inline body).
    pub actions: Vec<(String, String)>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Sheet {
    pub pou: String,
    pub lang: SheetLang,
    pub nodes: Vec<SheetNode>,
}

/// What a file holds for a POU name.
#[derive(Clone, Debug, PartialEq)]
pub enum Found {
    Sheet(Sheet),
    /// The POU's body is text (`ST`, `IL`): nothing to draw from the file.
    Textual(String),
    NotHere,
}

fn num(n: Node, a: &str) -> Option<f64> {
    xml::attr_str(n, a)
        .and_then(|v| v.trim().parse::<f64>().ok())
        .filter(|v| v.is_finite())
}

fn point(n: Node) -> Option<(f64, f64)> {
    Some((num(n, "x")?, num(n, "y")?))
}

fn text_of(n: Node) -> String {
    let t: String = n
        .descendants()
        .filter(|d| d.is_text())
        .filter_map(|d| d.text())
        .collect();
    t.split_whitespace().collect::<Vec<_>>().join(" ")
}

fn pin(cp: Option<Node>, var: Option<Node>) -> Pin {
    let mut wires = Vec::new();
    if let Some(cp) = cp {
        for c in xml::children(cp, "connection") {
            let Some(from) = xml::attr_str(c, "refLocalId").and_then(|v| v.trim().parse().ok())
            else {
                continue;
            };
            wires.push(Wire {
                from,
                from_pin: xml::attr_str(c, "formalParameter")
                    .map(|s| s.trim().to_string())
                    .filter(|s| !s.is_empty()),
                points: xml::children(c, "position").filter_map(point).collect(),
            });
        }
    }
    Pin {
        name: var
            .and_then(|v| xml::attr_str(v, "formalParameter"))
            .unwrap_or("")
            .trim()
            .to_string(),
        negated: var.is_some_and(|v| xml::flag(v, "negated")),
        edge: match var.and_then(|v| xml::attr_str(v, "edge")) {
            Some("rising") => "P",
            Some("falling") => "N",
            _ => "",
        },
        rel: cp
            .and_then(|c| xml::child(c, "relPosition"))
            .and_then(point),
        wires,
    }
}

fn kind_of(tag: &str) -> Option<NodeKind> {
    use NodeKind::*;
    Some(match tag {
        "leftPowerRail" => LeftRail,
        "rightPowerRail" => RightRail,
        "contact" => Contact,
        "coil" => Coil,
        "block" => Block,
        "inVariable" => InVar,
        "outVariable" => OutVar,
        "inOutVariable" => InOutVar,
        "label" => Label,
        "jump" => Jump,
        "return" => Return,
        "connector" => Connector,
        "continuation" => Continuation,
        "step" => Step,
        "macroStep" => MacroStep,
        "transition" => Transition,
        "selectionDivergence" => SelectionDivergence,
        "selectionConvergence" => SelectionConvergence,
        "simultaneousDivergence" => SimultaneousDivergence,
        "simultaneousConvergence" => SimultaneousConvergence,
        "jumpStep" => JumpStep,
        "actionBlock" => ActionBlock,
        "comment" => Comment,
        _ => return None,
    })
}

fn node(e: Node) -> Option<SheetNode> {
    use NodeKind::*;
    let kind = kind_of(e.tag_name().name())?;
    let id = xml::attr_str(e, "localId")?.trim().parse().ok()?;
    let child_text = |c: &str| xml::child(e, c).map(text_of).unwrap_or_default();
    let attr = |a: &str| xml::attr_str(e, a).unwrap_or("").trim().to_string();
    let text = match kind {
        Contact | Coil => child_text("variable"),
        InVar | OutVar | InOutVar => child_text("expression"),
        Block => attr("typeName"),
        Label | Jump => attr("label"),
        Connector | Continuation | Step | MacroStep => attr("name"),
        JumpStep => attr("targetName"),
        Comment => child_text("content"),
        Transition => match xml::child(e, "condition") {
            Some(c) => match xml::child(c, "reference") {
                Some(r) => xml::attr_str(r, "name").unwrap_or("").trim().to_string(),
                None => xml::child(c, "inline").map(text_of).unwrap_or_default(),
            },
            None => String::new(),
        },
        _ => String::new(),
    };
    let mark = match kind {
        Contact | Coil => match (
            xml::flag(e, "negated"),
            xml::attr_str(e, "edge"),
            xml::attr_str(e, "storage"),
        ) {
            (_, _, Some("set")) => "S",
            (_, _, Some("reset")) => "R",
            (_, Some("rising"), _) => "P",
            (_, Some("falling"), _) => "N",
            (true, _, _) => "/",
            _ => "",
        },
        InVar | OutVar if xml::flag(e, "negated") => "/",
        Step if xml::flag(e, "initialStep") => "initial",
        _ => "",
    };
    let mut ins = Vec::new();
    let mut outs = Vec::new();
    if kind == Block {
        for (sec, inout) in [("inputVariables", false), ("inOutVariables", true)] {
            if let Some(s) = xml::child(e, sec) {
                for v in xml::children(s, "variable") {
                    ins.push(pin(xml::child(v, "connectionPointIn"), Some(v)));
                    if inout {
                        let mut o = pin(xml::child(v, "connectionPointOut"), Some(v));
                        o.wires.clear();
                        outs.push(o);
                    }
                }
            }
        }
        if let Some(s) = xml::child(e, "outputVariables") {
            for v in xml::children(s, "variable") {
                outs.push(pin(xml::child(v, "connectionPointOut"), Some(v)));
            }
        }
    } else {
        for cp in xml::children(e, "connectionPointIn") {
            ins.push(pin(Some(cp), None));
        }
        // Transitions in Beremiz may carry their condition as a wire.
        if let Some(cp) =
            xml::child(e, "condition").and_then(|c| xml::child(c, "connectionPointIn"))
        {
            ins.push(pin(Some(cp), None));
        }
        for cp in xml::children(e, "connectionPointOut") {
            outs.push(pin(Some(cp), None));
        }
    }
    let mut actions = Vec::new();
    if kind == ActionBlock {
        for a in xml::children(e, "action") {
            let q = xml::attr_str(a, "qualifier")
                .unwrap_or("N")
                .trim()
                .to_string();
            let dur = xml::attr_str(a, "duration").unwrap_or("").trim();
            let q = if dur.is_empty() {
                q
            } else {
                format!("{q}, {dur}")
            };
            let what = match xml::child(a, "reference") {
                Some(r) => xml::attr_str(r, "name").unwrap_or("").trim().to_string(),
                None => xml::child(a, "inline").map(text_of).unwrap_or_default(),
            };
            actions.push((q, what));
        }
    }
    let size = match (num(e, "width"), num(e, "height")) {
        (Some(w), Some(h)) if w > 0.0 && h > 0.0 => Some((w, h)),
        _ => None,
    };
    Some(SheetNode {
        id,
        kind,
        pos: xml::child(e, "position").and_then(point),
        size,
        text,
        instance: attr("instanceName"),
        mark,
        ins,
        outs,
        actions,
    })
}

/// The sheet of POU `pou` (names compared without case) in PLCopen file
/// text `src`. Err when the text is not XML.
pub fn sheet(src: &str, pou: &str) -> Result<Found, String> {
    let opts = ParsingOptions {
        allow_dtd: false,
        nodes_limit: crate::NODES_LIMIT,
        ..ParsingOptions::default()
    };
    let doc = Document::parse_with_options(src, opts).map_err(|e| e.to_string())?;
    let Some(p) = doc.descendants().find(|n| {
        xml::is(*n, "pou")
            && xml::attr_str(*n, "name").is_some_and(|v| v.trim().eq_ignore_ascii_case(pou))
    }) else {
        return Ok(Found::NotHere);
    };
    let Some(body) = xml::child(p, "body").and_then(|b| xml::elements(b).next()) else {
        return Ok(Found::Textual("no body".into()));
    };
    let lang = match body.tag_name().name() {
        "LD" => SheetLang::Ld,
        "FBD" => SheetLang::Fbd,
        "SFC" => SheetLang::Sfc,
        other => return Ok(Found::Textual(other.to_string())),
    };
    let nodes = xml::elements(body).filter_map(node).collect();
    Ok(Found::Sheet(Sheet {
        pou: xml::attr_str(p, "name").unwrap_or(pou).trim().to_string(),
        lang,
        nodes,
    }))
}

/// The POUs of PLCopen file text `src` whose body is LD or FBD, in file
/// order (what the HMI draws live; SFC charts have their own view). Empty
/// when the text is not XML.
pub fn graphical_pous(src: &str) -> Vec<String> {
    let opts = ParsingOptions {
        allow_dtd: false,
        nodes_limit: crate::NODES_LIMIT,
        ..ParsingOptions::default()
    };
    let Ok(doc) = Document::parse_with_options(src, opts) else {
        return Vec::new();
    };
    doc.descendants()
        .filter(|n| xml::is(*n, "pou"))
        .filter(|p| {
            xml::child(*p, "body")
                .and_then(|b| xml::elements(b).next())
                .is_some_and(|b| matches!(b.tag_name().name(), "LD" | "FBD"))
        })
        .filter_map(|p| xml::attr_str(p, "name").map(|n| n.trim().to_string()))
        .collect()
}
