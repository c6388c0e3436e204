//! The timing diagram (see `layout.rs`) in SVG written by hand: one row
//! per signal, the name on the left; booleans as steps (high/low), analog
//! values as a line between their minimum and maximum (both written on the
//! left), other values (active SFC steps, enumeration states) as bands
//! with their value written inside; a time axis with round ticks below.

use super::csv::Trace;
use super::layout::{layout, Anchor, Diagram, Ink, Seg, Shape};
use std::fmt::Write;

#[cfg(test)]
use super::layout::tick_step;

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

fn path_data(segs: &[Seg]) -> String {
    let mut d = String::new();
    for (i, s) in segs.iter().enumerate() {
        let sep = if i == 0 { "" } else { " " };
        let _ = match *s {
            Seg::Move(x, y) => write!(d, "{sep}M{} {}", n(x), n(y)),
            Seg::Line(x, y) => write!(d, "{sep}L{} {}", n(x), n(y)),
            Seg::Horizontal(x) => write!(d, "{sep}H{}", n(x)),
            Seg::Vertical(y) => write!(d, "{sep}V{}", n(y)),
        };
    }
    d
}

fn shape(out: &mut String, s: &Shape) {
    let _ = match s {
        Shape::Path { class, segs, ink } => writeln!(
            out,
            r#"<path class="{class}" d="{}" fill="none" stroke="{}" stroke-width="1.5"/>"#,
            path_data(segs),
            match ink {
                Ink::Black => "black",
                Ink::Navy => "navy",
            }
        ),
        Shape::Band { x, y, w, h } => writeln!(
            out,
            r##"<rect class="band" x="{}" y="{}" width="{}" height="{}" fill="#dde8f5" stroke="#5577aa"/>"##,
            n(*x),
            n(*y),
            n(*w),
            n(*h)
        ),
        Shape::Rect { class, x, y, w, h } => writeln!(
            out,
            r#"<rect class="{class}" x="{}" y="{}" width="{}" height="{}" fill="white" stroke="black" stroke-width="1.5"/>"#,
            n(*x),
            n(*y),
            n(*w),
            n(*h)
        ),
        Shape::Circle { class, cx, cy, r } => writeln!(
            out,
            r#"<circle class="{class}" cx="{}" cy="{}" r="{}" fill="white" stroke="black" stroke-width="1.5"/>"#,
            n(*cx),
            n(*cy),
            n(*r)
        ),
        Shape::Line {
            class,
            x1,
            y1,
            x2,
            y2,
        } => writeln!(
            out,
            r#"<line class="{class}" x1="{}" y1="{}" x2="{}" y2="{}" stroke="black"/>"#,
            n(*x1),
            n(*y1),
            n(*x2),
            n(*y2)
        ),
        Shape::Text {
            class,
            x,
            y,
            anchor,
            size,
            text,
        } => {
            let anchor = match anchor {
                Anchor::Start => "",
                Anchor::Middle => r#" text-anchor="middle""#,
                Anchor::End => r#" text-anchor="end""#,
            };
            writeln!(
                out,
                r#"<text class="{class}" x="{}" y="{}"{anchor} font-size="{size}">{}</text>"#,
                n(*x),
                n(*y),
                esc(text)
            )
        }
    };
}

/// The diagram of `trace` (all its columns, in order).
pub fn render(trace: &Trace) -> String {
    diagram(&layout(trace))
}

/// Any diagram (a timing diagram, a drawing of `automat draw`) as SVG.
pub fn diagram(d: &Diagram) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif">"#,
        w = n(d.width),
        h = n(d.height)
    );
    let _ = writeln!(out, r#"<rect width="100%" height="100%" fill="white"/>"#);
    for s in &d.shapes {
        shape(&mut out, s);
    }
    out.push_str("</svg>\n");
    out
}

#[cfg(test)]
#[path = "svg_tests.rs"]
mod tests;
