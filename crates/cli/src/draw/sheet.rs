//! An LD, FBD or graphical SFC sheet of a PLCopen file as a diagram (the
//! plot's shapes, so the SVG and PNG writers are the timing diagram's).
//!
//! Positions: the file's, moved so the leftmost/topmost element is at
//! `MARGIN`; sizes the file's, or a default per kind. A sheet where an
//! element has no position or two elements share one (hand-written files
//! often put everything at 0,0) is laid out automatically: columns by data-flow depth (an element one column right
//! of every element it reads from), rows in file order (SFC: rows by
//! depth, action blocks right of their step). Pin positions (`relPosition`)
//! are the file's unless all are 0,0 or the sheet is laid out. Wires use the route
//! points the file stores; otherwise they go from the output pin to the
//! input pin with one vertical segment half-way (LD, FBD) or one horizontal
//! segment half-way (SFC).
//!
//! Classes of the SVG elements: `rail`, `contact`, `coil`, `block`,
//! `variable`, `label`, `jump`, `return`, `connector`, `continuation`,
//! `step`, `initial-step`, `macro-step`, `transition`, `divergence`,
//! `jump-step`, `action`, `comment`, `wire`, `negation`, and `text-*` for the
//! texts of each.

use super::{text_w, Pen};
use automat_plcopen::sheet::{NodeKind, Pin, Sheet, SheetLang, SheetNode};
use std::collections::HashMap;

pub const MARGIN: f64 = 40.0;
/// Pin spacing of a block, and the height of its title row.
const PIN: f64 = 20.0;

/// A node placed: its box in diagram coordinates.
#[derive(Clone, Copy)]
struct Placed<'a> {
    n: &'a SheetNode,
    x: f64,
    y: f64,
    w: f64,
    h: f64,
}

fn default_size(n: &SheetNode) -> (f64, f64) {
    use NodeKind::*;
    let tw = text_w(&n.text);
    match n.kind {
        LeftRail | RightRail => (
            3.0,
            40.0f64.max(20.0 * n.ins.len().max(n.outs.len()) as f64),
        ),
        Contact | Coil => (21.0, 20.0),
        Block => {
            let widest_in = n.ins.iter().map(|p| text_w(&p.name)).fold(0.0, f64::max);
            let widest_out = n.outs.iter().map(|p| text_w(&p.name)).fold(0.0, f64::max);
            let w = (widest_in + widest_out + 24.0).max(tw + 16.0).max(60.0);
            (w, PIN * (1 + n.ins.len().max(n.outs.len()).max(1)) as f64)
        }
        InVar | OutVar | InOutVar | Label | Jump | Connector | Continuation => {
            ((tw + 14.0).max(40.0), 20.0)
        }
        Return => (60.0, 20.0),
        Step | MacroStep => ((tw + 16.0).max(50.0), 30.0),
        Transition => (20.0, 2.0),
        SelectionDivergence | SelectionConvergence => (60.0, 1.0),
        SimultaneousDivergence | SimultaneousConvergence => (60.0, 3.0),
        JumpStep => (12.0, 13.0),
        ActionBlock => {
            let w = n
                .actions
                .iter()
                .map(|(_, a)| text_w(a))
                .fold(60.0, f64::max);
            (w + 50.0, 20.0 * n.actions.len().max(1) as f64)
        }
        Comment => ((tw + 12.0).clamp(60.0, 400.0), 30.0),
    }
}

/// Data-flow columns for a sheet without positions.
fn auto_positions(sheet: &Sheet) -> HashMap<u32, (f64, f64)> {
    let ids: HashMap<u32, usize> = sheet
        .nodes
        .iter()
        .enumerate()
        .map(|(i, n)| (n.id, i))
        .collect();
    let mut depth = vec![0usize; sheet.nodes.len()];
    // Longest path by relaxation, at most one round per node (a loop of
    // wires stops growing there).
    for _ in 0..sheet.nodes.len().min(500) {
        let mut changed = false;
        for (i, n) in sheet.nodes.iter().enumerate() {
            for w in n.ins.iter().flat_map(|p| &p.wires) {
                if let Some(&j) = ids.get(&w.from) {
                    if depth[j] + 1 > depth[i] && j != i {
                        depth[i] = depth[j] + 1;
                        changed = true;
                    }
                }
            }
        }
        if !changed {
            break;
        }
    }
    let vertical = sheet.lang == SheetLang::Sfc;
    let mut next = HashMap::<usize, f64>::new();
    let mut out = HashMap::new();
    for (i, n) in sheet.nodes.iter().enumerate() {
        if n.kind == NodeKind::ActionBlock {
            continue;
        }
        let (w, h) = n.size.unwrap_or_else(|| default_size(n));
        let d = depth[i];
        let slot = next.entry(d).or_insert(0.0);
        let p = if vertical {
            (*slot, d as f64 * 70.0)
        } else {
            (d as f64 * 150.0, *slot)
        };
        // SFC: room on the right for the step's action blocks.
        *slot += if vertical { w + 240.0 } else { h + 30.0 };
        out.insert(n.id, p);
    }
    // Action blocks right of their step.
    for n in sheet
        .nodes
        .iter()
        .filter(|n| n.kind == NodeKind::ActionBlock)
    {
        let step = n
            .ins
            .iter()
            .flat_map(|p| &p.wires)
            .find_map(|w| Some((*ids.get(&w.from)?, *out.get(&w.from)?)));
        let p = match step {
            Some((j, (x, y))) => {
                let s = &sheet.nodes[j];
                let (w, _) = s.size.unwrap_or_else(|| default_size(s));
                (x + w + 30.0, y)
            }
            None => (0.0, 0.0),
        };
        out.insert(n.id, p);
    }
    out
}

/// Whether the file's positions can be drawn: every element has one and no
/// two share one (files written by tools; a hand-written file often puts
/// every element at 0,0).
fn positions_usable(sheet: &Sheet) -> bool {
    let mut seen = std::collections::HashSet::new();
    sheet.nodes.iter().all(|n| match n.pos {
        Some((x, y)) => seen.insert((x.to_bits(), y.to_bits())),
        None => false,
    })
}

fn place(sheet: &Sheet) -> Vec<Placed<'_>> {
    let auto = !positions_usable(sheet);
    let autop = if auto {
        auto_positions(sheet)
    } else {
        HashMap::new()
    };
    let pos = |n: &SheetNode| {
        if auto {
            autop.get(&n.id).copied().unwrap_or((0.0, 0.0))
        } else {
            n.pos.unwrap_or((0.0, 0.0))
        }
    };
    let minx = sheet
        .nodes
        .iter()
        .map(|n| pos(n).0)
        .fold(f64::INFINITY, f64::min);
    let miny = sheet
        .nodes
        .iter()
        .map(|n| pos(n).1)
        .fold(f64::INFINITY, f64::min);
    // Room above for the texts written over an element.
    let (ox, oy) = (MARGIN - minx, MARGIN - miny);
    sheet
        .nodes
        .iter()
        .map(|n| {
            let (x, y) = pos(n);
            let (w, h) = n.size.unwrap_or_else(|| default_size(n));
            Placed {
                n,
                x: x + ox,
                y: y + oy,
                w,
                h,
            }
        })
        .collect()
}

fn rel_or(p: &Pin, ignore_rel: bool) -> Option<(f64, f64)> {
    if ignore_rel {
        return None;
    }
    p.rel.filter(|&(x, y)| x != 0.0 || y != 0.0)
}

/// Where input pin `i` of `p` is.
fn in_point(p: &Placed, i: usize, lang: SheetLang, auto: bool) -> (f64, f64) {
    if let Some((rx, ry)) = p.n.ins.get(i).and_then(|pin| rel_or(pin, auto)) {
        return (p.x + rx, p.y + ry);
    }
    let n = p.n.ins.len().max(1) as f64;
    match p.n.kind {
        NodeKind::Block => (p.x, p.y + PIN * (i as f64 + 1.5)),
        NodeKind::RightRail => (p.x, p.y + p.h * (i as f64 + 0.5) / n),
        NodeKind::ActionBlock => (p.x, p.y + 10.0),
        NodeKind::SelectionConvergence | NodeKind::SimultaneousConvergence => {
            (p.x + p.w * (i as f64 + 0.5) / n, p.y)
        }
        _ if lang == SheetLang::Sfc => (p.x + p.w / 2.0, p.y),
        _ => (p.x, p.y + p.h / 2.0),
    }
}

/// Where output `pin` (a formal name, or the first output) of `p` is.
fn out_point(p: &Placed, pin: Option<&str>, lang: SheetLang, auto: bool) -> (f64, f64) {
    let i = pin
        .and_then(|name| {
            p.n.outs
                .iter()
                .position(|o| o.name.eq_ignore_ascii_case(name))
        })
        .unwrap_or(0);
    if let Some((rx, ry)) = p.n.outs.get(i).and_then(|pin| rel_or(pin, auto)) {
        return (p.x + rx, p.y + ry);
    }
    let n = p.n.outs.len().max(1) as f64;
    match p.n.kind {
        NodeKind::Block => (p.x + p.w, p.y + PIN * (i as f64 + 1.5)),
        NodeKind::LeftRail => (p.x + p.w, p.y + p.h * (i as f64 + 0.5) / n),
        // A step's second output is its action link, on its right.
        NodeKind::Step | NodeKind::MacroStep if i == 1 => (p.x + p.w, p.y + p.h / 2.0),
        NodeKind::SelectionDivergence | NodeKind::SimultaneousDivergence => {
            (p.x + p.w * (i as f64 + 0.5) / n, p.y + p.h)
        }
        _ if lang == SheetLang::Sfc => (p.x + p.w / 2.0, p.y + p.h),
        _ => (p.x + p.w, p.y + p.h / 2.0),
    }
}

fn element(pen: &mut Pen, p: &Placed) {
    use NodeKind::*;
    let n = p.n;
    let (x, y, w, h) = (p.x, p.y, p.w, p.h);
    let (cx, cy) = (x + w / 2.0, y + h / 2.0);
    match n.kind {
        LeftRail | RightRail => {
            pen.path("rail", &[(cx, y), (cx, y + h)]);
            pen.path("rail", &[(cx - 1.0, y), (cx - 1.0, y + h)]);
        }
        Contact => {
            pen.path("contact", &[(x, cy), (x + 6.0, cy)]);
            pen.path("contact", &[(x + 6.0, y), (x + 6.0, y + h)]);
            pen.path("contact", &[(x + w - 6.0, y), (x + w - 6.0, y + h)]);
            pen.path("contact", &[(x + w - 6.0, cy), (x + w, cy)]);
            mark(pen, n.mark, cx, cy, h);
            pen.text("text-contact", cx, y - 4.0, 'm', &n.text);
        }
        Coil => {
            pen.path("coil", &[(x, cy), (x + 4.0, cy)]);
            pen.path("coil", &arc(x + 10.0, cy, h / 2.0, true));
            pen.path("coil", &arc(x + w - 10.0, cy, h / 2.0, false));
            pen.path("coil", &[(x + w - 4.0, cy), (x + w, cy)]);
            mark(pen, n.mark, cx, cy, h);
            pen.text("text-coil", cx, y - 4.0, 'm', &n.text);
        }
        Block => {
            pen.rect("block", x, y, w, h);
            pen.text("text-block", cx, y + 14.0, 'm', &n.text);
            if !n.instance.is_empty() {
                pen.text("text-instance", cx, y - 4.0, 'm', &n.instance);
            }
            for (i, pin) in n.ins.iter().enumerate() {
                let py = y + PIN * (i as f64 + 1.5);
                pen.text(
                    "text-pin",
                    x + 4.0,
                    py + 4.0,
                    's',
                    &format!("{}{}", pin.edge, pin.name),
                );
                if pin.negated {
                    pen.circle("negation", x - 3.0, py, 3.0);
                }
            }
            for (i, pin) in n.outs.iter().enumerate() {
                let py = y + PIN * (i as f64 + 1.5);
                pen.text("text-pin", x + w - 4.0, py + 4.0, 'e', &pin.name);
                if pin.negated {
                    pen.circle("negation", x + w + 3.0, py, 3.0);
                }
            }
        }
        InVar | OutVar | InOutVar => {
            pen.rect("variable", x, y, w, h);
            pen.text("text-variable", cx, y + h / 2.0 + 4.0, 'm', &n.text);
            if n.mark == "/" {
                let nx = if n.kind == InVar {
                    x + w + 3.0
                } else {
                    x - 3.0
                };
                pen.circle("negation", nx, cy, 3.0);
            }
        }
        Label => pen.text("text-label", x, cy + 4.0, 's', &format!("{}:", n.text)),
        Jump => {
            pen.path("jump", &[(x, cy), (x + 12.0, cy)]);
            pen.path(
                "jump",
                &[(x + 8.0, cy - 4.0), (x + 12.0, cy), (x + 8.0, cy + 4.0)],
            );
            pen.text("text-jump", x + 16.0, cy + 4.0, 's', &n.text);
        }
        Return => pen.text("text-return", x, cy + 4.0, 's', "<RETURN>"),
        Connector | Continuation => {
            let class = if n.kind == Connector {
                "connector"
            } else {
                "continuation"
            };
            pen.path(
                class,
                &[
                    (x, y),
                    (x + w - 8.0, y),
                    (x + w, cy),
                    (x + w - 8.0, y + h),
                    (x, y + h),
                    (x, y),
                ],
            );
            pen.text(
                if n.kind == Connector {
                    "text-connector"
                } else {
                    "text-continuation"
                },
                x + 4.0,
                cy + 4.0,
                's',
                &n.text,
            );
        }
        Step => {
            let initial = n.mark == "initial";
            pen.rect(if initial { "initial-step" } else { "step" }, x, y, w, h);
            if initial {
                pen.rect("initial-step", x + 3.0, y + 3.0, w - 6.0, h - 6.0);
            }
            pen.text("text-step", cx, cy + 4.0, 'm', &n.text);
        }
        MacroStep => {
            pen.rect("macro-step", x, y, w, h);
            pen.path("macro-step", &[(x, y + 4.0), (x + w, y + 4.0)]);
            pen.path("macro-step", &[(x, y + h - 4.0), (x + w, y + h - 4.0)]);
            pen.text("text-step", cx, cy + 4.0, 'm', &n.text);
        }
        Transition => {
            pen.path("transition", &[(x, cy), (x + w, cy)]);
            pen.path("transition", &[(x, cy + 1.0), (x + w, cy + 1.0)]);
            pen.text(
                "text-transition",
                x + w + 6.0,
                cy + 4.0,
                's',
                &short(&n.text),
            );
        }
        SelectionDivergence | SelectionConvergence => {
            pen.path("divergence", &[(x, y), (x + w, y)]);
        }
        SimultaneousDivergence | SimultaneousConvergence => {
            pen.path("divergence", &[(x, y), (x + w, y)]);
            pen.path("divergence", &[(x, y + h), (x + w, y + h)]);
        }
        JumpStep => {
            pen.path("jump-step", &[(x, y), (x + w, y), (cx, y + h), (x, y)]);
            pen.text("text-jump-step", x + w + 4.0, y + h, 's', &n.text);
        }
        ActionBlock => {
            for (i, (q, a)) in n.actions.iter().enumerate() {
                let ry = y + 20.0 * i as f64;
                pen.rect("action", x, ry, 40.0, 20.0);
                pen.rect("action", x + 40.0, ry, w - 40.0, 20.0);
                pen.text("text-qualifier", x + 20.0, ry + 14.0, 'm', q);
                pen.text("text-action", x + 44.0, ry + 14.0, 's', &short(a));
            }
        }
        Comment => {
            pen.rect("comment", x, y, w, h);
            pen.text("text-comment", x + 4.0, y + 14.0, 's', &short(&n.text));
        }
    }
}

/// A text cut to what fits one line of a drawing.
fn short(t: &str) -> String {
    const MAX: usize = 48;
    if t.chars().count() <= MAX {
        t.to_string()
    } else {
        let mut s: String = t.chars().take(MAX - 3).collect();
        s.push_str("...");
        s
    }
}

/// The letter or slash inside a contact or coil.
fn mark(pen: &mut Pen, m: &str, cx: f64, cy: f64, h: f64) {
    match m {
        "" => {}
        "/" => pen.path(
            "negation",
            &[
                (cx + 4.0, cy - h / 2.0 + 2.0),
                (cx - 4.0, cy + h / 2.0 - 2.0),
            ],
        ),
        _ => pen.text("text-mark", cx, cy + 4.0, 'm', m),
    }
}

/// A coil's parenthesis as a polyline (`left`: opening).
fn arc(x: f64, cy: f64, r: f64, left: bool) -> Vec<(f64, f64)> {
    (0..=8)
        .map(|i| {
            let a = std::f64::consts::PI * (i as f64 / 8.0 - 0.5) * 0.8;
            let dx = r * 0.5 * (1.0 - a.cos());
            (
                if left { x - 6.0 + dx } else { x + 6.0 - dx },
                cy + r * a.sin(),
            )
        })
        .collect()
}

/// The drawing of `sheet`.
pub fn draw(sheet: &Sheet) -> Pen {
    let placed = place(sheet);
    let auto = !positions_usable(sheet);
    let by_id: HashMap<u32, &Placed> = placed.iter().map(|p| (p.n.id, p)).collect();
    let mut pen = Pen::default();
    // How far each rail must reach to meet its wires.
    let mut reach: HashMap<u32, (f64, f64)> = HashMap::new();
    let mut grow = |id: u32, y: f64| {
        let r = reach.entry(id).or_insert((y, y));
        r.0 = r.0.min(y);
        r.1 = r.1.max(y);
    };
    // Wires first, elements over them.
    for p in &placed {
        // The offset from the file's coordinates to the diagram's.
        let (ox, oy) = p.n.pos.map_or((0.0, 0.0), |(fx, fy)| (p.x - fx, p.y - fy));
        for (i, pin) in p.n.ins.iter().enumerate() {
            let mut to = in_point(p, i, sheet.lang, auto);
            for w in &pin.wires {
                let Some(src) = by_id.get(&w.from) else {
                    continue;
                };
                let mut from = out_point(src, w.from_pin.as_deref(), sheet.lang, auto);
                // A rail without pin positions meets its wire level.
                if src.n.kind == NodeKind::LeftRail && rail_unpinned(&src.n.outs, auto) {
                    from.1 = to.1;
                    grow(src.n.id, to.1);
                }
                if p.n.kind == NodeKind::RightRail && rail_unpinned(&p.n.ins, auto) {
                    to.1 = from.1;
                    grow(p.n.id, from.1);
                }
                let pts: Vec<(f64, f64)> = if w.points.len() >= 2 && !auto {
                    w.points.iter().map(|&(x, y)| (x + ox, y + oy)).collect()
                } else if sheet.lang == SheetLang::Sfc && p.n.kind != NodeKind::ActionBlock {
                    let my = (from.1 + to.1) / 2.0;
                    vec![from, (from.0, my), (to.0, my), to]
                } else if to.0 < from.0 + 20.0 {
                    // Backwards: out to the right, across, in from the left.
                    let my = (from.1 + to.1) / 2.0;
                    vec![
                        from,
                        (from.0 + 10.0, from.1),
                        (from.0 + 10.0, my),
                        (to.0 - 10.0, my),
                        (to.0 - 10.0, to.1),
                        to,
                    ]
                } else {
                    let mx = (from.0 + to.0) / 2.0;
                    vec![from, (mx, from.1), (mx, to.1), to]
                };
                pen.path("wire", &pts);
            }
        }
    }
    for p in &placed {
        let mut q = Placed { n: p.n, ..*p };
        if let Some(&(lo, hi)) = reach.get(&p.n.id) {
            let top = q.y.min(lo - 10.0);
            q.h = (q.y + q.h).max(hi + 10.0) - top;
            q.y = top;
        }
        element(&mut pen, &q);
    }
    pen
}

/// Whether a rail's pins have no positions of their own.
fn rail_unpinned(pins: &[Pin], auto: bool) -> bool {
    auto || pins.iter().all(|o| rel_or(o, false).is_none())
}

/// Where an element of a sheet is drawn (diagram coordinates) and where
/// its pins are, for a live view that marks elements and shows pin values
/// over the drawing.
pub struct Boxed {
    pub id: u32,
    pub kind: NodeKind,
    pub x: f64,
    pub y: f64,
    pub w: f64,
    pub h: f64,
    /// (formal name, point) of each input pin, then of each output pin.
    pub ins: Vec<(String, (f64, f64))>,
    pub outs: Vec<(String, (f64, f64))>,
}

/// The boxes of every element of `sheet`, placed as [`draw`] places them.
pub fn boxes(sheet: &Sheet) -> Vec<Boxed> {
    let auto = !positions_usable(sheet);
    place(sheet)
        .iter()
        .map(|p| Boxed {
            id: p.n.id,
            kind: p.n.kind,
            x: p.x,
            y: p.y,
            w: p.w,
            h: p.h,
            ins: (0..p.n.ins.len())
                .map(|i| (p.n.ins[i].name.clone(), in_point(p, i, sheet.lang, auto)))
                .collect(),
            outs: p
                .n
                .outs
                .iter()
                .map(|o| {
                    (
                        o.name.clone(),
                        out_point(p, Some(&o.name), sheet.lang, auto),
                    )
                })
                .collect(),
        })
        .collect()
}
