//! A textual SFC chart laid out automatically (it has no positions).
//!
//! Steps are placed in rows by their distance from the initial step(s)
//! (breadth first over the transitions; steps never reached come last),
//! left to right in a row in the order they are written. Each transition
//! is a bar below its preceding steps, its condition (the text as written)
//! on its right; several transitions out of one step are side by side
//! under a selection-divergence line. A successor in a lower row is wired
//! to; a successor in the same or an earlier row is drawn as a jump: an
//! arrow with the step's name (IEC 61131-3 §8.3, the graphical jump).
//! Several preceding or following steps get the double line of a
//! simultaneous convergence or divergence. Action associations are boxes
//! right of their step: qualifier (and time), then the action.
//!
//! Same classes as `sheet.rs`.

use super::sheet::MARGIN;
use super::{text_w, Pen};
use automat_base::Interner;
use automat_syntax::ast::sfc::{Chart, Condition};
use std::collections::{HashMap, VecDeque};

const ROW: f64 = 110.0;
const COL: f64 = 220.0;
const STEP_H: f64 = 30.0;

fn key(interner: &Interner, sym: automat_base::Symbol) -> String {
    interner.name(sym).to_ascii_uppercase()
}

fn slice(src: &str, s: automat_base::Span) -> String {
    let t = src
        .get(s.start as usize..s.end as usize)
        .unwrap_or("")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    if t.chars().count() > 40 {
        let mut c: String = t.chars().take(37).collect();
        c.push_str("...");
        c
    } else {
        t
    }
}

pub fn draw(chart: &Chart, src: &str, interner: &Interner) -> Pen {
    let names: Vec<String> = chart
        .steps
        .iter()
        .map(|s| key(interner, s.name.sym))
        .collect();
    let index: HashMap<&str, usize> = names
        .iter()
        .enumerate()
        .map(|(i, n)| (n.as_str(), i))
        .collect();
    let step_of = |sym| index.get(key(interner, sym).as_str()).copied();
    // Rows: breadth first from the initial steps.
    let mut rank: Vec<Option<usize>> = vec![None; chart.steps.len()];
    let mut queue = VecDeque::new();
    for (i, s) in chart.steps.iter().enumerate() {
        if s.initial {
            rank[i] = Some(0);
            queue.push_back(i);
        }
    }
    if queue.is_empty() && !chart.steps.is_empty() {
        rank[0] = Some(0);
        queue.push_back(0);
    }
    while let Some(i) = queue.pop_front() {
        let r = rank[i].unwrap_or(0);
        for t in &chart.transitions {
            if !t.from.iter().any(|f| step_of(f.sym) == Some(i)) {
                continue;
            }
            for to in &t.to {
                if let Some(j) = step_of(to.sym) {
                    if rank[j].is_none() {
                        rank[j] = Some(r + 1);
                        queue.push_back(j);
                    }
                }
            }
        }
    }
    let last = rank.iter().flatten().max().copied().unwrap_or(0);
    let rank: Vec<usize> = rank.iter().map(|r| r.unwrap_or(last + 1)).collect();
    // Columns in writing order within a row.
    let mut col = vec![0usize; chart.steps.len()];
    let mut used: HashMap<usize, usize> = HashMap::new();
    for (i, &r) in rank.iter().enumerate() {
        let c = used.entry(r).or_insert(0);
        col[i] = *c;
        *c += 1;
    }
    let mut pen = Pen::default();
    // Step boxes: (x, y, w).
    let boxes: Vec<(f64, f64, f64)> = chart
        .steps
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let w = (text_w(interner.name(s.name.sym)) + 16.0).max(50.0);
            (
                MARGIN + col[i] as f64 * COL,
                MARGIN + rank[i] as f64 * ROW,
                w,
            )
        })
        .collect();
    for (i, s) in chart.steps.iter().enumerate() {
        let (x, y, w) = boxes[i];
        let class = if s.initial { "initial-step" } else { "step" };
        pen.rect(class, x, y, w, STEP_H);
        if s.initial {
            pen.rect(class, x + 3.0, y + 3.0, w - 6.0, STEP_H - 6.0);
        }
        pen.text(
            "text-step",
            x + w / 2.0,
            y + STEP_H / 2.0 + 4.0,
            'm',
            interner.name(s.name.sym),
        );
        // Associations on the right.
        for (k, a) in s.assocs.iter().enumerate() {
            let ax = x + w + 20.0;
            let ay = y + 20.0 * k as f64;
            if k == 0 {
                pen.path("wire", &[(x + w, y + 10.0), (ax, y + 10.0)]);
            }
            let q = match &a.time {
                Some(t) => format!("{}, {}", a.qualifier.name(), slice(src, t.span)),
                None => a.qualifier.name().to_string(),
            };
            let qw = (text_w(&q) + 10.0).max(30.0);
            let name = interner.name(a.name.sym);
            pen.rect("action", ax, ay, qw, 20.0);
            pen.rect("action", ax + qw, ay, text_w(name) + 12.0, 20.0);
            pen.text("text-qualifier", ax + qw / 2.0, ay + 14.0, 'm', &q);
            pen.text("text-action", ax + qw + 6.0, ay + 14.0, 's', name);
        }
    }
    // Transitions out of each step, for the selection-divergence offsets.
    let mut outs: HashMap<usize, Vec<usize>> = HashMap::new();
    for (ti, t) in chart.transitions.iter().enumerate() {
        if let Some(f) = t.from.first().and_then(|f| step_of(f.sym)) {
            outs.entry(f).or_default().push(ti);
        }
    }
    for (ti, t) in chart.transitions.iter().enumerate() {
        let from: Vec<usize> = t.from.iter().filter_map(|f| step_of(f.sym)).collect();
        let to: Vec<usize> = t.to.iter().filter_map(|f| step_of(f.sym)).collect();
        let Some(&first) = from.first() else {
            continue;
        };
        let centre = |i: usize| boxes[i].0 + boxes[i].2 / 2.0;
        let bottom = from
            .iter()
            .map(|&i| boxes[i].1 + STEP_H)
            .fold(0.0, f64::max);
        let siblings = outs.get(&first).map_or(&[][..], |v| v.as_slice());
        let k = siblings.iter().position(|&x| x == ti).unwrap_or(0);
        let m = siblings.len().max(1);
        let mut tx = from.iter().map(|&i| centre(i)).sum::<f64>() / from.len() as f64;
        tx += (k as f64 - (m as f64 - 1.0) / 2.0) * 90.0;
        let ty = bottom + 40.0;
        // Into the bar.
        if from.len() > 1 {
            let lo = from
                .iter()
                .map(|&i| centre(i))
                .fold(f64::INFINITY, f64::min);
            let hi = from.iter().map(|&i| centre(i)).fold(0.0, f64::max);
            let cy = bottom + 15.0;
            for &i in &from {
                pen.path("wire", &[(centre(i), boxes[i].1 + STEP_H), (centre(i), cy)]);
            }
            pen.path("divergence", &[(lo, cy), (hi, cy)]);
            pen.path("divergence", &[(lo, cy + 3.0), (hi, cy + 3.0)]);
            pen.path("wire", &[(tx, cy + 3.0), (tx, ty)]);
        } else if m > 1 {
            let c = centre(first);
            let dy = bottom + 15.0;
            pen.path("wire", &[(c, bottom), (c, dy)]);
            pen.path("divergence", &[(c.min(tx), dy), (c.max(tx), dy)]);
            pen.path("wire", &[(tx, dy), (tx, ty)]);
        } else {
            pen.path("wire", &[(centre(first), bottom), (tx, bottom), (tx, ty)]);
        }
        pen.path("transition", &[(tx - 10.0, ty), (tx + 10.0, ty)]);
        pen.path(
            "transition",
            &[(tx - 10.0, ty + 1.0), (tx + 10.0, ty + 1.0)],
        );
        let cond = match &t.cond {
            Condition::St(e) => slice(src, e.span),
            Condition::Il { .. } => "IL".to_string(),
            Condition::Missing => String::new(),
        };
        let cond = match &t.name {
            Some(n) if cond.is_empty() => interner.name(n.sym).to_string(),
            _ => cond,
        };
        pen.text("text-transition", tx + 16.0, ty + 4.0, 's', &cond);
        // Out of the bar: wires down to later rows, jumps otherwise.
        let r_from = from.iter().map(|&i| rank[i]).max().unwrap_or(0);
        let below = ty + 20.0;
        if to.len() > 1 {
            let lo = to.iter().map(|&i| centre(i)).fold(tx, f64::min);
            let hi = to.iter().map(|&i| centre(i)).fold(tx, f64::max);
            pen.path("wire", &[(tx, ty), (tx, below)]);
            pen.path("divergence", &[(lo, below), (hi, below)]);
            pen.path("divergence", &[(lo, below + 3.0), (hi, below + 3.0)]);
        }
        for &j in &to {
            let start = if to.len() > 1 {
                (centre(j), below + 3.0)
            } else {
                (tx, ty)
            };
            if rank[j] > r_from && !t.jump {
                let top = boxes[j].1;
                let mid = top - 12.0;
                pen.path(
                    "wire",
                    &[start, (start.0, mid), (centre(j), mid), (centre(j), top)],
                );
            } else {
                // IEC jump: an arrow down with the target's name.
                let (ax, ay) = (start.0, start.1 + 14.0);
                pen.path("wire", &[start, (ax, ay)]);
                pen.path(
                    "jump-step",
                    &[
                        (ax - 6.0, ay),
                        (ax + 6.0, ay),
                        (ax, ay + 12.0),
                        (ax - 6.0, ay),
                    ],
                );
                pen.text(
                    "text-jump-step",
                    ax + 10.0,
                    ay + 11.0,
                    's',
                    interner.name(chart.steps[j].name.sym),
                );
            }
        }
    }
    pen
}
