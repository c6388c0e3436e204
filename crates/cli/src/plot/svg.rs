//! A timing diagram as a student draws it, in SVG written by hand: one row
//! per signal, the name on the left; booleans as steps (high/low), analog
//! values as a line between their minimum and maximum (both written on the
//! left), other values (active SFC steps, enumeration states) as bands
//! with their value written inside; a time axis with round ticks below.
//!
//! Layout (pixels): width 900; names right-aligned at x = 132; the plot
//! runs from x = 140 to x = 880; rows start at y = 10, are 30 high (70 for
//! analog values) with 6 between them; the axis is 10 below the last row.

use super::csv::{Column, Series, Trace};
use std::fmt::Write;

pub const WIDTH: f64 = 900.0;
pub const LEFT: f64 = 140.0;
pub const RIGHT: f64 = 880.0;
pub const TOP: f64 = 10.0;
const GAP: f64 = 6.0;
const ROW: f64 = 30.0;
const ANALOG_ROW: f64 = 70.0;
const AXIS_H: f64 = 30.0;

/// A coordinate with at most 2 decimals, trailing zeros dropped.
fn n(x: f64) -> String {
    let s = format!("{x:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.to_string()
    }
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A duration for an axis label: `1.5s`, `200ms`, `1m30s`.
fn label_time(ns: i64) -> String {
    let s = automat_iec::format::format_duration(ns, false);
    s.strip_prefix("T#").unwrap_or(&s).to_string()
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

fn bool_row(out: &mut String, sc: &Scale, times: &[i64], vals: &[bool], y: f64) {
    let level = |b: bool| if b { y + 5.0 } else { y + ROW - 5.0 };
    let mut d = String::new();
    let mut prev = None;
    for (i, (&t, &v)) in times.iter().zip(vals).enumerate() {
        let x = sc.x(t);
        match prev {
            None => {
                let _ = write!(d, "M{} {}", n(x), n(level(v)));
            }
            Some(p) if p != v => {
                let _ = write!(d, " H{} V{}", n(x), n(level(v)));
            }
            _ => {}
        }
        prev = Some(v);
        if i + 1 == vals.len() {
            let _ = write!(d, " H{}", n(end_x(sc, times, i)));
        }
    }
    let _ = writeln!(
        out,
        r#"<path class="bool" d="{d}" fill="none" stroke="black" stroke-width="1.5"/>"#
    );
}

fn analog_row(out: &mut String, sc: &Scale, times: &[i64], vals: &[f64], y: f64) {
    let lo = vals.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = vals.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let (lo, hi) = if lo.is_finite() { (lo, hi) } else { (0.0, 0.0) };
    let range = if hi > lo { hi - lo } else { 1.0 };
    let top = y + 5.0;
    let bottom = y + ANALOG_ROW - 5.0;
    let yv = |v: f64| bottom - (v - lo) / range * (bottom - top);
    let mut d = String::new();
    for (i, (&t, &v)) in times.iter().zip(vals).enumerate() {
        let _ = write!(
            d,
            "{}{} {}",
            if i == 0 { "M" } else { " L" },
            n(sc.x(t)),
            n(yv(v))
        );
    }
    let _ = writeln!(
        out,
        r#"<path class="analog" d="{d}" fill="none" stroke="navy" stroke-width="1.5"/>"#
    );
    for (v, yy) in [(hi, top + 8.0), (lo, bottom)] {
        let _ = writeln!(
            out,
            r#"<text class="range" x="{}" y="{}" text-anchor="end" font-size="9">{}</text>"#,
            n(LEFT - 8.0),
            n(yy),
            esc(&crate_fmt(v))
        );
    }
}

fn crate_fmt(v: f64) -> String {
    let s = format!("{v:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

fn band_row(out: &mut String, sc: &Scale, times: &[i64], vals: &[String], y: f64) {
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
        let _ = writeln!(
            out,
            r##"<rect class="band" x="{}" y="{}" width="{}" height="{}" fill="#dde8f5" stroke="#5577aa"/>"##,
            n(x0),
            n(y + 3.0),
            n(x1 - x0),
            n(ROW - 6.0)
        );
        if x1 - x0 >= 7.0 * label.chars().count() as f64 + 4.0 {
            let _ = writeln!(
                out,
                r#"<text class="step" x="{}" y="{}" font-size="10">{}</text>"#,
                n(x0 + 3.0),
                n(y + ROW / 2.0 + 4.0),
                esc(label)
            );
        }
        i = j + 1;
    }
}

/// The diagram of `trace` (all its columns, in order).
pub fn render(trace: &Trace) -> String {
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
    let height = TOP + rows + AXIS_H + 10.0;
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif">"#,
        w = n(WIDTH),
        h = n(height)
    );
    let _ = writeln!(out, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let mut y = TOP;
    for c in &trace.columns {
        let h = row_height(c);
        let _ = writeln!(
            out,
            r#"<text class="name" x="{}" y="{}" text-anchor="end" font-size="12">{}</text>"#,
            n(LEFT - 8.0),
            n(y + h / 2.0 + 4.0),
            esc(&c.name)
        );
        match &c.series {
            Series::Bool(v) => bool_row(&mut out, &sc, &trace.times, v, y),
            Series::Analog(v) => analog_row(&mut out, &sc, &trace.times, v, y),
            Series::Bands(v) => band_row(&mut out, &sc, &trace.times, v, y),
        }
        y += h + GAP;
    }
    let axis_y = y + 4.0;
    let _ = writeln!(
        out,
        r#"<line class="axis" x1="{}" y1="{a}" x2="{}" y2="{a}" stroke="black"/>"#,
        n(LEFT),
        n(RIGHT),
        a = n(axis_y)
    );
    let step = tick_step(end - t0);
    let mut t = (t0 + step - 1).div_euclid(step) * step;
    while t <= end {
        let x = n(sc.x(t));
        let _ = writeln!(
            out,
            r#"<line class="tick" x1="{x}" y1="{}" x2="{x}" y2="{}" stroke="black"/>"#,
            n(axis_y),
            n(axis_y + 5.0)
        );
        let _ = writeln!(
            out,
            r#"<text class="time" x="{x}" y="{}" text-anchor="middle" font-size="10">{}</text>"#,
            n(axis_y + 17.0),
            label_time(t)
        );
        t = match t.checked_add(step) {
            Some(t) => t,
            None => break,
        };
    }
    out.push_str("</svg>\n");
    out
}

#[cfg(test)]
#[path = "svg_tests.rs"]
mod tests;
