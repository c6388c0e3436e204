//! Reads arbitrary bytes (as lossy UTF-8, as `automat plot` reads its
//! file) as a trace CSV and, when that succeeds, lays the diagram out and
//! writes it as SVG: nothing may panic or hang, an error names its line,
//! and every coordinate is finite.
//!
//! `automat` is a binary crate, so its `plot` reader, layout and SVG writer
//! are compiled in here from their sources (they use only std,
//! automat-runtime and automat-iec). The PNG writer is left out: it only
//! rasterises the same layout with tiny-skia.
#![no_main]

#[allow(dead_code)]
#[path = "../../crates/cli/src/plot/csv.rs"]
mod csv;
#[allow(dead_code)]
#[path = "../../crates/cli/src/plot/layout.rs"]
mod layout;
#[allow(dead_code)]
#[path = "../../crates/cli/src/plot/svg.rs"]
mod svg;

use layout::{Seg, Shape};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let trace = match csv::parse(&text) {
        Ok(t) => t,
        Err(e) => {
            assert!(e.starts_with("line ") || e == "the trace is empty", "{e}");
            return;
        }
    };
    let d = layout::layout(&trace);
    for s in &d.shapes {
        let xs: Vec<f64> = match s {
            Shape::Path { segs, .. } => segs
                .iter()
                .flat_map(|g| match *g {
                    Seg::Move(x, y) | Seg::Line(x, y) => vec![x, y],
                    Seg::Horizontal(v) | Seg::Vertical(v) => vec![v],
                })
                .collect(),
            Shape::Band { x, y, w, h } => vec![*x, *y, *w, *h],
            Shape::Line { x1, y1, x2, y2, .. } => vec![*x1, *y1, *x2, *y2],
            Shape::Rect { x, y, w, h, .. } => vec![*x, *y, *w, *h],
            Shape::Circle { cx, cy, r, .. } => vec![*cx, *cy, *r],
            Shape::Text { x, y, .. } => vec![*x, *y],
        };
        assert!(xs.iter().all(|x| x.is_finite()), "{s:?}");
    }
    assert!(svg::render(&trace).ends_with("</svg>\n"));
});
