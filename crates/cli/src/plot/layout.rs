//! The timing diagram as a list of shapes in pixel coordinates: the one
//! layout both writers draw (`svg.rs` prints it, `png.rs` rasterises it),
//! so the SVG and the PNG of a trace show the same thing at the same place.
//!
//! Layout (pixels): width 900; names right-aligned at x = 132; the plot
//! runs from x = 140 to x = 880; rows start at y = 10, are 30 high (70 for
//! analog values) with 6 between them; the axis is 10 below the last row.

use super::csv::{Column, Series, Trace};

pub const WIDTH: f64 = 900.0;
pub const LEFT: f64 = 140.0;
pub const RIGHT: f64 = 880.0;
pub const TOP: f64 = 10.0;
const GAP: f64 = 6.0;
pub const ROW: f64 = 30.0;
const ANALOG_ROW: f64 = 70.0;
const AXIS_H: f64 = 30.0;

/// Where a text's x is: its start, middle or end (SVG `text-anchor`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Anchor {
    Start,
    Middle,
    End,
}

/// One step of a path, as in SVG path data (absolute coordinates).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Seg {
    Move(f64, f64),
    Line(f64, f64),
    Horizontal(f64),
    Vertical(f64),
}

/// A colour of the diagram (both writers map it to the same RGB).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ink {
    Black,
    Navy,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A 1.5 px wide unfilled line through `segs`.
    Path {
        class: &'static str,
        segs: Vec<Seg>,
        ink: Ink,
    },
    /// A band of constant value: light blue filled, darker blue outline.
    Band { x: f64, y: f64, w: f64, h: f64 },
    /// A 1 px black line.
    Line {
        class: &'static str,
        x1: f64,
        y1: f64,
        x2: f64,
        y2: f64,
    },
    /// A 1.5 px black outline (drawings: blocks, steps, variables).
    Rect {
        class: &'static str,
        x: f64,
        y: f64,
        w: f64,
        h: f64,
    },
    /// A 1.5 px black circle outline (drawings: negated pins).
    Circle {
        class: &'static str,
        cx: f64,
        cy: f64,
        r: f64,
    },
    /// Black text whose baseline is at `y`.
    Text {
        class: &'static str,
        x: f64,
        y: f64,
        anchor: Anchor,
        size: u32,
        text: String,
    },
}

/// A diagram: its size and its shapes in drawing order over a white page.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagram {
    pub width: f64,
    pub height: f64,
    pub shapes: Vec<Shape>,
}

/// A duration for an axis label: `1.5s`, `200ms`, `1m30s`.
fn label_time(ns: i64) -> String {
    let s = automat_iec::format::format_duration(ns, false);
    s.strip_prefix("T#").unwrap_or(&s).to_string()
}

/// A number for a range label: at most 3 decimals, trailing zeros dropped.
fn label_number(v: f64) -> String {
    let s = format!("{v:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// A round tick step (1, 2 or 5 × 10^k ns) giving at most 10 ticks.
pub fn tick_step(span_ns: i64) -> i64 {
    let mut step: i64 = 1;
    loop {
        for m in [1, 2, 5] {
            let s = step.saturating_mul(m);
            if span_ns / s <= 10 {
                return s;
            }
        }
        if step > i64::MAX / 10 {
            return step;
        }
        step *= 10;
    }
}

struct Scale {
    t0: i64,
    span: f64,
}

impl Scale {
    fn x(&self, t: i64) -> f64 {
        LEFT + (t.saturating_sub(self.t0)) as f64 / self.span * (RIGHT - LEFT)
    }
}

fn row_height(c: &Column) -> f64 {
    match c.series {
        Series::Analog(_) => ANALOG_ROW,
        _ => ROW,
    }
}

/// The x where sample `i` ends (the next sample's time, or the plot's end).
fn end_x(sc: &Scale, times: &[i64], i: usize) -> f64 {
    times.get(i + 1).map_or(RIGHT, |&t| sc.x(t))
}

fn bool_row(out: &mut Vec<Shape>, sc: &Scale, times: &[i64], vals: &[bool], y: f64) {
    let level = |b: bool| if b { y + 5.0 } else { y + ROW - 5.0 };
    let mut segs = Vec::new();
    let mut prev = None;
    for (i, (&t, &v)) in times.iter().zip(vals).enumerate() {
        let x = sc.x(t);
        match prev {
            None => segs.push(Seg::Move(x, level(v))),
            Some(p) if p != v => {
                segs.push(Seg::Horizontal(x));
                segs.push(Seg::Vertical(level(v)));
            }
            _ => {}
        }
        prev = Some(v);
        if i + 1 == vals.len() {
            segs.push(Seg::Horizontal(end_x(sc, times, i)));
        }
    }
    out.push(Shape::Path {
        class: "bool",
        segs,
        ink: Ink::Black,
    });
}

fn analog_row(out: &mut Vec<Shape>, sc: &Scale, times: &[i64], vals: &[f64], y: f64) {
    let lo = vals.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = vals.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let (lo, hi) = if lo.is_finite() { (lo, hi) } else { (0.0, 0.0) };
    // Halves: `hi - lo` of -1e308 and 1e308 is infinite and made every y
    // NaN (`NaN` in the SVG path). Halving is exact, so ordinary values
    // land where `(v - lo) / (hi - lo)` puts them.
    let range = if hi > lo { hi / 2.0 - lo / 2.0 } else { 1.0 };
    let top = y + 5.0;
    let bottom = y + ANALOG_ROW - 5.0;
    let yv = |v: f64| bottom - (v / 2.0 - lo / 2.0) / range * (bottom - top);
    let segs = times
        .iter()
        .zip(vals)
        .enumerate()
        .map(|(i, (&t, &v))| {
            if i == 0 {
                Seg::Move(sc.x(t), yv(v))
            } else {
                Seg::Line(sc.x(t), yv(v))
            }
        })
        .collect();
    out.push(Shape::Path {
        class: "analog",
        segs,
        ink: Ink::Navy,
    });
    for (v, yy) in [(hi, top + 8.0), (lo, bottom)] {
        out.push(Shape::Text {
            class: "range",
            x: LEFT - 8.0,
            y: yy,
            anchor: Anchor::End,
            size: 9,
            text: label_number(v),
        });
    }
}

fn band_row(out: &mut Vec<Shape>, sc: &Scale, times: &[i64], vals: &[String], y: f64) {
    let mut i = 0;
    while i < vals.len() {
        let mut j = i;
        while vals.get(j + 1) == vals.get(i) {
            j += 1;
        }
        let x0 = times.get(i).map_or(LEFT, |&t| sc.x(t));
        let x1 = end_x(sc, times, j);
        let v = vals.get(i).map(String::as_str).unwrap_or("");
        // Only the part after `Type#` is written: the step's name.
        let label = v.rsplit('#').next().unwrap_or(v);
        out.push(Shape::Band {
            x: x0,
            y: y + 3.0,
            w: x1 - x0,
            h: ROW - 6.0,
        });
        if x1 - x0 >= 7.0 * label.chars().count() as f64 + 4.0 {
            out.push(Shape::Text {
                class: "step",
                x: x0 + 3.0,
                y: y + ROW / 2.0 + 4.0,
                anchor: Anchor::Start,
                size: 10,
                text: label.to_string(),
            });
        }
        i = j + 1;
    }
}

/// The diagram of `trace` (all its columns, in order).
pub fn layout(trace: &Trace) -> Diagram {
    let t0 = trace.times.first().copied().unwrap_or(0);
    let t1 = trace.times.last().copied().unwrap_or(0);
    // The last sample is drawn for one more sampling period.
    let period = match trace.times.as_slice() {
        [.., a, b] => b.saturating_sub(*a),
        _ => 0,
    };
    let end = t1.saturating_add(period);
    let sc = Scale {
        t0,
        span: if end > t0 { (end - t0) as f64 } else { 1.0 },
    };
    let rows: f64 = trace.columns.iter().map(|c| row_height(c) + GAP).sum();
    let mut shapes = Vec::new();
    let mut y = TOP;
    for c in &trace.columns {
        let h = row_height(c);
        shapes.push(Shape::Text {
            class: "name",
            x: LEFT - 8.0,
            y: y + h / 2.0 + 4.0,
            anchor: Anchor::End,
            size: 12,
            text: c.name.clone(),
        });
        match &c.series {
            Series::Bool(v) => bool_row(&mut shapes, &sc, &trace.times, v, y),
            Series::Analog(v) => analog_row(&mut shapes, &sc, &trace.times, v, y),
            Series::Bands(v) => band_row(&mut shapes, &sc, &trace.times, v, y),
        }
        y += h + GAP;
    }
    let axis_y = y + 4.0;
    shapes.push(Shape::Line {
        class: "axis",
        x1: LEFT,
        y1: axis_y,
        x2: RIGHT,
        y2: axis_y,
    });
    let step = tick_step(end - t0);
    let mut t = (t0 + step - 1).div_euclid(step) * step;
    while t <= end {
        let x = sc.x(t);
        shapes.push(Shape::Line {
            class: "tick",
            x1: x,
            y1: axis_y,
            x2: x,
            y2: axis_y + 5.0,
        });
        shapes.push(Shape::Text {
            class: "time",
            x,
            y: axis_y + 17.0,
            anchor: Anchor::Middle,
            size: 10,
            text: label_time(t),
        });
        t = match t.checked_add(step) {
            Some(t) => t,
            None => break,
        };
    }
    Diagram {
        width: WIDTH,
        height: TOP + rows + AXIS_H + 10.0,
        shapes,
    }
}
