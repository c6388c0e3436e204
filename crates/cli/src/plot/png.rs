//! The timing diagram (see `layout.rs`) rasterised with tiny-skia and
//! encoded as PNG: lines and bands anti-aliased exactly where the SVG has
//! them, text in the built-in bitmap font (`font.rs`), set on whole pixels
//! so it stays sharp.

use super::csv::Trace;
use super::font;
use super::layout::{layout, Anchor, Diagram, Ink, Seg, Shape};
use tiny_skia::{
    Color, Paint, Path, PathBuilder, Pixmap, PremultipliedColorU8, Rect, Stroke, Transform,
};

fn paint(r: u8, g: u8, b: u8) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color_rgba8(r, g, b, 255);
    p.anti_alias = true;
    p
}

fn ink(i: Ink) -> Paint<'static> {
    match i {
        Ink::Black => paint(0, 0, 0),
        Ink::Navy => paint(0, 0, 128),
    }
}

fn stroke(pm: &mut Pixmap, path: Option<Path>, p: &Paint, width: f32) {
    if let Some(path) = path {
        let s = Stroke {
            width,
            ..Stroke::default()
        };
        pm.stroke_path(&path, p, &s, Transform::identity(), None);
    }
}

fn path(pm: &mut Pixmap, segs: &[Seg], p: &Paint) {
    let mut pb = PathBuilder::new();
    let (mut cx, mut cy) = (0.0f32, 0.0f32);
    for s in segs {
        match *s {
            Seg::Move(x, y) => {
                (cx, cy) = (x as f32, y as f32);
                pb.move_to(cx, cy);
            }
            Seg::Line(x, y) => {
                (cx, cy) = (x as f32, y as f32);
                pb.line_to(cx, cy);
            }
            Seg::Horizontal(x) => {
                cx = x as f32;
                pb.line_to(cx, cy);
            }
            Seg::Vertical(y) => {
                cy = y as f32;
                pb.line_to(cx, cy);
            }
        }
    }
    stroke(pm, pb.finish(), p, 1.5);
}

/// Sets one pixel black (outside the page: nothing).
fn dot(pm: &mut Pixmap, x: i32, y: i32) {
    let (w, h) = (pm.width() as i32, pm.height() as i32);
    if x < 0 || y < 0 || x >= w || y >= h {
        return;
    }
    let i = (y as usize) * (w as usize) + x as usize;
    if let (Some(px), Some(black)) = (
        pm.pixels_mut().get_mut(i),
        PremultipliedColorU8::from_rgba(0, 0, 0, 255),
    ) {
        *px = black;
    }
}

fn text(pm: &mut Pixmap, x: f64, y: f64, anchor: Anchor, t: &str) {
    let w = font::text_width(t);
    let x = x.round() as i32;
    let x0 = match anchor {
        Anchor::Start => x,
        Anchor::Middle => x.saturating_sub(w / 2),
        Anchor::End => x.saturating_sub(w),
    };
    font::dots(t, x0, y.round() as i32, |dx, dy| dot(pm, dx, dy));
}

/// The tallest PNG written, in pixels.
pub const MAX_HEIGHT: u32 = 16_384;

/// The diagram of `trace` as a pixmap (white page).
pub fn raster(trace: &Trace) -> Result<Pixmap, String> {
    raster_diagram(&layout(trace))
}

/// Any diagram (a timing diagram, a drawing of `automat draw`) as a pixmap.
pub fn raster_diagram(d: &Diagram) -> Result<Pixmap, String> {
    let (w, h) = (d.width.ceil() as u32, d.height.ceil() as u32);
    // Pixmap::new takes up to 2 GB (i32 bytes); a trace of a few thousand
    // columns asked for that much. 16384 rows (59 MB: 200 to 450 rows of the
    // diagram) is as tall as common viewers show.
    if h > MAX_HEIGHT {
        return Err(format!(
            "a {w}×{h} pixel diagram is too large for a PNG (at most {MAX_HEIGHT} pixels high): \
             choose fewer columns with --signals, or write an SVG"
        ));
    }
    let mut pm = Pixmap::new(w, h)
        .ok_or_else(|| format!("a {w}×{h} pixel diagram is too large for a PNG"))?;
    pm.fill(Color::WHITE);
    for s in &d.shapes {
        match s {
            Shape::Path { segs, ink: i, .. } => path(&mut pm, segs, &ink(*i)),
            Shape::Band { x, y, w, h } => {
                if let Some(r) = Rect::from_xywh(*x as f32, *y as f32, *w as f32, *h as f32) {
                    pm.fill_rect(r, &paint(0xdd, 0xe8, 0xf5), Transform::identity(), None);
                    stroke(
                        &mut pm,
                        Some(PathBuilder::from_rect(r)),
                        &paint(0x55, 0x77, 0xaa),
                        1.0,
                    );
                }
            }
            Shape::Rect { x, y, w, h, .. } => {
                if let Some(r) = Rect::from_xywh(*x as f32, *y as f32, *w as f32, *h as f32) {
                    pm.fill_rect(r, &paint(255, 255, 255), Transform::identity(), None);
                    stroke(
                        &mut pm,
                        Some(PathBuilder::from_rect(r)),
                        &paint(0, 0, 0),
                        1.5,
                    );
                }
            }
            Shape::Circle { cx, cy, r, .. } => {
                let c = PathBuilder::from_circle(*cx as f32, *cy as f32, *r as f32);
                if let Some(c) = &c {
                    pm.fill_path(
                        c,
                        &paint(255, 255, 255),
                        tiny_skia::FillRule::Winding,
                        Transform::identity(),
                        None,
                    );
                }
                stroke(&mut pm, c, &paint(0, 0, 0), 1.5);
            }
            Shape::Line { x1, y1, x2, y2, .. } => {
                // A 1 px line on pixel centres is one sharp row or column.
                let mut pb = PathBuilder::new();
                pb.move_to(*x1 as f32 + 0.5, *y1 as f32 + 0.5);
                pb.line_to(*x2 as f32 + 0.5, *y2 as f32 + 0.5);
                stroke(&mut pm, pb.finish(), &paint(0, 0, 0), 1.0);
            }
            Shape::Text {
                x,
                y,
                anchor,
                text: t,
                ..
            } => text(&mut pm, *x, *y, *anchor, t),
        }
    }
    Ok(pm)
}

/// The diagram of `trace` as PNG bytes.
pub fn render(trace: &Trace) -> Result<Vec<u8>, String> {
    raster(trace)?
        .encode_png()
        .map_err(|e| format!("cannot encode the PNG: {e}"))
}

/// Any diagram as PNG bytes.
pub fn encode(d: &Diagram) -> Result<Vec<u8>, String> {
    raster_diagram(d)?
        .encode_png()
        .map_err(|e| format!("cannot encode the PNG: {e}"))
}

#[cfg(test)]
#[path = "png_tests.rs"]
mod tests;
