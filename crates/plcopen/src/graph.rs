//! TC6 XML `<LD>` / `<FBD>` bodies into the syntax layer's graphical
//! network model (`automat_syntax::graphic`), which lowers them.

use crate::xml;
use crate::Imp;
use automat_base::Code;
use automat_syntax::graphic::model::*;
use roxmltree::Node;

fn edge(n: Node) -> EdgeKind {
    match xml::attr_str(n, "edge") {
        Some("rising") => EdgeKind::Rising,
        Some("falling") => EdgeKind::Falling,
        _ => EdgeKind::None,
    }
}

/// Reads the elements of a body; unknown elements are E171 and left out.
pub(crate) fn network(imp: &mut Imp, body: Node, pou: &str) -> Network {
    let lang = if body.tag_name().name() == "LD" {
        GraphLang::Ld
    } else {
        GraphLang::Fbd
    };
    let mut elements = Vec::new();
    for e in xml::elements(body) {
        if let Some(el) = element(imp, e, pou) {
            elements.push(el);
        }
    }
    Network { lang, elements }
}

fn element(imp: &mut Imp, e: Node, pou: &str) -> Option<Element> {
    let tag = e.tag_name().name();
    if matches!(tag, "comment" | "addData" | "documentation") {
        return None;
    }
    let span = imp.span(e);
    let Some(id) = xml::attr_str(e, "localId").and_then(|v| v.trim().parse::<u32>().ok()) else {
        imp.error(
            Code::E171,
            span,
            format!("POU `{pou}`: `{tag}` without a numeric `localId`"),
        );
        return None;
    };
    let text_of = |imp: &mut Imp, child: &str| -> Option<xml::Text> {
        let t = xml::child(e, child).map(|c| xml::content(imp.src, c).trimmed());
        match t {
            Some(t) if !t.text.is_empty() && crate::decl::safe_expr(&t.text) => Some(t),
            Some(t) if !t.text.is_empty() => {
                let sp = t.span(imp.file);
                imp.error(
                    Code::E171,
                    sp,
                    format!(
                        "POU `{pou}`, localId {id}: `{}` is not an expression",
                        t.text
                    ),
                );
                None
            }
            _ => {
                imp.error(
                    Code::E171,
                    span,
                    format!("POU `{pou}`, localId {id}: `{tag}` without `{child}`"),
                );
                None
            }
        }
    };
    let name_of = |imp: &mut Imp, attr: &str| imp.name_attr(e, attr, "a name");
    let kind = match tag {
        "leftPowerRail" => Kind::LeftRail,
        "rightPowerRail" => Kind::RightRail,
        "contact" => Kind::Contact {
            negated: xml::flag(e, "negated"),
            edge: edge(e),
            var: text_of(imp, "variable")?,
        },
        "coil" => Kind::Coil {
            negated: xml::flag(e, "negated"),
            storage: match xml::attr_str(e, "storage") {
                Some("set") => Storage::Set,
                Some("reset") => Storage::Reset,
                _ => Storage::None,
            },
            edge: edge(e),
            var: text_of(imp, "variable")?,
        },
        "block" => Kind::Block {
            type_name: name_of(imp, "typeName")?,
            instance: match xml::attr_str(e, "instanceName") {
                Some(s) if !s.trim().is_empty() => Some(name_of(imp, "instanceName")?),
                _ => None,
            },
        },
        "inVariable" => Kind::InVar {
            negated: xml::flag(e, "negated"),
            expr: text_of(imp, "expression")?,
        },
        "outVariable" => Kind::OutVar {
            negated: xml::flag(e, "negated"),
            expr: text_of(imp, "expression")?,
        },
        "inOutVariable" => Kind::InOutVar {
            expr: text_of(imp, "expression")?,
        },
        "label" => Kind::Label {
            name: name_of(imp, "label")?,
        },
        "jump" => Kind::Jump {
            label: name_of(imp, "label")?,
        },
        "return" => Kind::Return,
        "connector" => Kind::Connector {
            name: name_of(imp, "name")?.text.to_ascii_uppercase(),
        },
        "continuation" => Kind::Continuation {
            name: name_of(imp, "name")?.text.to_ascii_uppercase(),
        },
        "vendorElement" => {
            let msg = format!(
                "POU `{pou}`, localId {id}: {}, not an IEC 61131-3 element: automat cannot run it",
                vendor_element(imp.src, e)
            );
            imp.error(Code::E171, span, msg);
            return None;
        }
        _ => {
            imp.error(
                Code::E171,
                span,
                format!(
                    "POU `{pou}`, localId {id}: `{tag}` is not an LD or FBD element automat reads"
                ),
            );
            return None;
        }
    };
    let (x, y) = xml::child(e, "position").map_or((0.0, 0.0), |p| {
        let f = |a| {
            xml::attr_str(p, a)
                .and_then(|v| v.trim().parse::<f64>().ok())
                .unwrap_or(0.0)
        };
        (f("x"), f("y"))
    });
    let order = xml::attr_str(e, "executionOrderId")
        .and_then(|v| v.trim().parse::<u32>().ok())
        .filter(|&o| o > 0);
    let mut inputs = Vec::new();
    let mut outputs = Vec::new();
    if tag == "block" {
        if let Some(iv) = xml::child(e, "inputVariables") {
            for v in xml::children(iv, "variable") {
                inputs.push(pin_in(imp, v, Some(v), false));
            }
        }
        if let Some(iv) = xml::child(e, "inOutVariables") {
            for v in xml::children(iv, "variable") {
                inputs.push(pin_in(imp, v, Some(v), true));
            }
        }
        if let Some(ov) = xml::child(e, "outputVariables") {
            for v in xml::children(ov, "variable") {
                outputs.push(PinOut {
                    formal: xml::attr_str(v, "formalParameter").map(|s| s.trim().to_string()),
                    negated: xml::flag(v, "negated"),
                });
            }
        }
    } else {
        // A right rail has one input per rung; every other element one.
        for cp in xml::children(e, "connectionPointIn") {
            inputs.push(pin_in(imp, cp, None, false));
        }
        if xml::child(e, "connectionPointOut").is_some() {
            outputs.push(PinOut {
                formal: None,
                negated: false,
            });
        }
    }
    Some(Element {
        id,
        kind,
        x,
        y,
        order,
        span,
        inputs,
        outputs,
    })
}

/// A pin: a block `variable` (formal, negated, edge; wires in its
/// `connectionPointIn`) or a bare `connectionPointIn`.
fn pin_in(imp: &mut Imp, n: Node, var: Option<Node>, in_out: bool) -> PinIn {
    let cp = if var.is_some() {
        xml::child(n, "connectionPointIn")
    } else {
        Some(n)
    };
    let mut conns = Vec::new();
    if let Some(cp) = cp {
        for c in xml::children(cp, "connection") {
            let from = xml::attr_str(c, "refLocalId").and_then(|v| v.trim().parse::<u32>().ok());
            let span = imp.span(c);
            match from {
                Some(from) => conns.push(Conn {
                    from,
                    formal: xml::attr_str(c, "formalParameter")
                        .map(|s| s.trim().to_string())
                        .filter(|s| !s.is_empty()),
                    span,
                }),
                None => imp.error(
                    Code::E171,
                    span,
                    "a `connection` without a numeric `refLocalId`",
                ),
            }
        }
    }
    PinIn {
        formal: var
            .and_then(|v| xml::attr_str(v, "formalParameter"))
            .map(|s| s.trim().to_string()),
        negated: var.is_some_and(|v| xml::flag(v, "negated")),
        edge: var.map_or(EdgeKind::None, edge),
        in_out,
        conns,
        span: imp.span(n),
    }
}

/// What names a `vendorElement`: the tool whose data it carries (the
/// `name` of its `addData` entries, a URI such as Beremiz's) and the text
/// the tool shows for it (`alternativeText`).
pub(crate) fn vendor_element(src: &str, e: Node) -> String {
    let vendors: Vec<&str> = xml::child(e, "addData")
        .into_iter()
        .flat_map(|a| xml::children(a, "data"))
        .filter_map(|d| xml::attr_str(d, "name"))
        .map(str::trim)
        .filter(|n| !n.is_empty())
        .collect();
    let alt = xml::child(e, "alternativeText")
        .map(|a| xml::formatted(src, a).trimmed().text)
        .unwrap_or_default();
    let alt: String = alt.split_whitespace().collect::<Vec<_>>().join(" ");
    let alt: String = alt.chars().take(60).collect();
    let what = if alt.is_empty() {
        String::new()
    } else {
        format!(" `{alt}`")
    };
    match vendors.as_slice() {
        [] => format!("a vendor's element{what} (no `addData` names its tool)"),
        vs => format!("a vendor's element{what} of `{}`", vs.join("`, `")),
    }
}
