//! The LD and FBD drawings the HMI shows live (`GET /api/v1/drawings`):
//! each graphical POU of the PLCopen files drawn as `automat draw` draws
//! it, with the box of every element and, per element, the variables whose
//! values go on it, relative to an instance of the POU (the server
//! resolves them against the running program). The SLC-500 program files
//! too (`slc_drawings`).

use super::sheet::{boxes, draw, Boxed};
use crate::plot::svg;
use automat_online::drawings::{Drawing, Element, Pin};
use automat_plcopen::sheet::{Found, NodeKind, Sheet, SheetLang, SheetNode};

fn kind_name(k: NodeKind) -> &'static str {
    use NodeKind::*;
    match k {
        LeftRail => "left-rail",
        RightRail => "right-rail",
        Contact => "contact",
        Coil => "coil",
        Block => "block",
        InVar => "in-variable",
        OutVar => "out-variable",
        InOutVar => "in-out-variable",
        Label => "label",
        Jump => "jump",
        Return => "return",
        Connector => "connector",
        Continuation => "continuation",
        Comment => "comment",
        _ => "other",
    }
}

/// A variable path (`x`, `Ctrl.x`, `a[3].b`), not an expression: only
/// those are watched.
fn is_path(t: &str) -> bool {
    t.chars()
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && t.chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '.' | '[' | ']'))
}

/// The file's own name: the page is for the operator, not the folder
/// layout of the machine it runs on.
fn short_name(file: &str) -> String {
    std::path::Path::new(file)
        .file_name()
        .map_or(file.to_string(), |n| n.to_string_lossy().into_owned())
}

/// The element of box `b` (node `n`), before any live value is named.
fn element(b: &Boxed, n: &SheetNode) -> Element {
    Element {
        id: b.id,
        kind: kind_name(b.kind),
        text: n.text.clone(),
        x: b.x,
        y: b.y,
        w: b.w,
        h: b.h,
        power: None,
        value: None,
        pins: Vec::new(),
    }
}

/// Sheet `s` of `file` drawn as `automat draw` draws it, titled
/// `POU (lang, file name)`, with its live `elements`.
fn drawing(
    s: &Sheet,
    lang: &'static str,
    file: &str,
    runs_in: Option<String>,
    dialect: Option<&'static str>,
    elements: Vec<Element>,
) -> Drawing {
    let title = format!("{} ({lang}, {})", s.pou, short_name(file));
    let diagram = draw(s).finish(&title);
    Drawing {
        pou: s.pou.clone(),
        runs_in,
        dialect,
        lang,
        file: file.to_string(),
        svg: svg::diagram(&diagram),
        width: diagram.width,
        height: diagram.height,
        elements,
    }
}

/// The drawings of every LD and FBD POU in the PLCopen files of `map`.
pub fn drawings(map: &automat_base::SourceMap) -> Vec<Drawing> {
    let mut out = Vec::new();
    for (_, f) in map.files() {
        if !automat_plcopen::is_plcopen_file(&f.name) {
            continue;
        }
        for pou in automat_plcopen::sheet::graphical_pous(&f.text) {
            let Ok(Found::Sheet(s)) = automat_plcopen::sheet::sheet(&f.text, &pou) else {
                continue;
            };
            let lang = if s.lang == SheetLang::Ld { "LD" } else { "FBD" };
            let mut elements = Vec::new();
            for (b, n) in boxes(&s).into_iter().zip(&s.nodes) {
                let mut e = element(&b, n);
                match b.kind {
                    NodeKind::Contact | NodeKind::Coil => {
                        e.power = Some(format!("__ld_n{}", b.id));
                    }
                    NodeKind::InVar | NodeKind::OutVar | NodeKind::InOutVar if is_path(&n.text) => {
                        e.value = Some(n.text.clone());
                    }
                    NodeKind::Block if is_path(&n.instance) => {
                        let pins = b.ins.iter().map(|p| (p, false));
                        for ((name, (x, y)), output) in pins.chain(b.outs.iter().map(|p| (p, true)))
                        {
                            if name.is_empty() {
                                continue;
                            }
                            e.pins.push(Pin {
                                name: name.clone(),
                                x: *x,
                                y: *y,
                                output,
                                path: format!("{}.{name}", n.instance),
                            });
                        }
                    }
                    _ => {}
                }
                elements.push(e);
            }
            out.push(drawing(&s, lang, &f.name, None, None, elements));
        }
    }
    out.extend(slc_drawings(map));
    out
}

/// The SLC-500 program files, drawn as `automat draw` draws them: contacts
/// and coils framed by their power flow (the `__ld_n<id>` the rung's
/// network keeps in the program `SLC`), the bit each names, a timer's or
/// counter's ACC beside its ENO.
fn slc_drawings(map: &automat_base::SourceMap) -> Vec<Drawing> {
    let mut out = Vec::new();
    for ls in automat_dialect::slc_live_sheets(map) {
        let s = &ls.sheet;
        let mut elements = Vec::new();
        for (b, n) in boxes(s).into_iter().zip(&s.nodes) {
            let live = ls.live.iter().find(|l| l.node == b.id);
            let eno = b.outs.iter().find(|p| p.0 == "ENO").map(|p| p.1);
            let pins = match (live, eno) {
                (Some(l), Some((x, y))) => l
                    .pins
                    .iter()
                    .map(|(name, path)| Pin {
                        name: name.clone(),
                        x,
                        y,
                        output: true,
                        path: path.clone(),
                    })
                    .collect(),
                _ => Vec::new(),
            };
            elements.push(Element {
                power: live.and_then(|l| l.power.clone()),
                value: live.and_then(|l| l.value.clone()),
                pins,
                ..element(&b, n)
            });
        }
        let runs_in = Some("SLC".to_string());
        out.push(drawing(s, "LD", &ls.file, runs_in, Some("slc"), elements));
    }
    out
}
