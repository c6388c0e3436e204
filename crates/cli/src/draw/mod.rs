//! `automat draw`: the drawing of one POU's graphical body (LD rungs, FBD
//! networks, SFC charts) as SVG or PNG, with the timing diagram's shapes and
//! writers (`plot/`). A POU of a PLCopen file is drawn from its sheet
//! (`sheet.rs`: the file's positions); a textual SFC chart of an `.st` file
//! is laid out automatically (`chart.rs`).

mod chart;
pub mod live;
mod sheet;

use crate::plot::layout::{Anchor, Diagram, Ink, Seg, Shape};
use crate::plot::{png, svg};
use crate::{files, Outcome};
use automat_plcopen::sheet::Found;
use clap::Args;
use std::path::{Path, PathBuf};

/// Draw one POU's LD, FBD or SFC body as SVG or PNG.
///
/// LD rungs, FBD networks and graphical SFC charts of PLCopen XML files are
/// drawn where the file places them; a textual SFC chart (an ST POU with
/// INITIAL_STEP ... END_TRANSITION) is laid out automatically, steps by
/// their distance from the initial step. See docs/drawings.md. Exits with 0
/// when written, 1 when the POU is not found or has no graphical body, 2
/// when a path cannot be read or written.
#[derive(Args)]
pub struct DrawArgs {
    /// Source files or directories (searched recursively for *.st, *.xml).
    #[arg(required = true, value_name = "PATH")]
    paths: Vec<PathBuf>,
    /// The POU to draw.
    #[arg(long, value_name = "NAME")]
    pou: String,
    /// The drawing to write: `*.svg` or `*.png`.
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    output: PathBuf,
}

/// The width a text takes (the PNG font's advance; the SVG's 11 px
/// sans-serif is about as wide).
pub fn text_w(t: &str) -> f64 {
    6.0 * t.chars().count() as f64
}

/// Collects the shapes of a drawing and how far they reach.
#[derive(Default)]
pub struct Pen {
    pub shapes: Vec<Shape>,
    max_x: f64,
    max_y: f64,
}

impl Pen {
    fn reach(&mut self, x: f64, y: f64) {
        if x.is_finite() && y.is_finite() {
            self.max_x = self.max_x.max(x);
            self.max_y = self.max_y.max(y);
        }
    }

    pub fn path(&mut self, class: &'static str, pts: &[(f64, f64)]) {
        let mut segs = Vec::with_capacity(pts.len());
        for (i, &(x, y)) in pts.iter().enumerate() {
            self.reach(x, y);
            segs.push(if i == 0 {
                Seg::Move(x, y)
            } else {
                Seg::Line(x, y)
            });
        }
        if segs.len() >= 2 {
            self.shapes.push(Shape::Path {
                class,
                segs,
                ink: Ink::Black,
            });
        }
    }

    pub fn rect(&mut self, class: &'static str, x: f64, y: f64, w: f64, h: f64) {
        self.reach(x + w, y + h);
        self.shapes.push(Shape::Rect { class, x, y, w, h });
    }

    pub fn circle(&mut self, class: &'static str, cx: f64, cy: f64, r: f64) {
        self.reach(cx + r, cy + r);
        self.shapes.push(Shape::Circle { class, cx, cy, r });
    }

    /// `anchor`: 's' start, 'm' middle, 'e' end.
    pub fn text(&mut self, class: &'static str, x: f64, y: f64, anchor: char, t: &str) {
        if t.is_empty() {
            return;
        }
        let w = text_w(t);
        let (anchor, right) = match anchor {
            'm' => (Anchor::Middle, x + w / 2.0),
            'e' => (Anchor::End, x),
            _ => (Anchor::Start, x + w),
        };
        self.reach(right, y + 4.0);
        self.shapes.push(Shape::Text {
            class,
            x,
            y,
            anchor,
            size: 11,
            text: t.to_string(),
        });
    }

    /// The diagram with a title line, `MARGIN` around the shapes.
    pub fn finish(mut self, title: &str) -> Diagram {
        let mut shapes = Vec::with_capacity(self.shapes.len() + 1);
        shapes.push(Shape::Text {
            class: "title",
            x: 8.0,
            y: 16.0,
            anchor: Anchor::Start,
            size: 11,
            text: title.to_string(),
        });
        let title_w = text_w(title) + 8.0;
        shapes.append(&mut self.shapes);
        Diagram {
            width: (self.max_x.max(title_w) + sheet::MARGIN).ceil(),
            height: (self.max_y + sheet::MARGIN).ceil(),
            shapes,
        }
    }
}

/// The drawing of POU `pou` in the files `map` holds.
pub fn diagram_of(map: &automat_base::SourceMap, pou: &str) -> Result<Diagram, String> {
    for (_, f) in map.files() {
        if !automat_plcopen::is_plcopen_file(&f.name) {
            continue;
        }
        match automat_plcopen::sheet::sheet(&f.text, pou) {
            Ok(Found::Sheet(s)) => {
                let lang = match s.lang {
                    automat_plcopen::sheet::SheetLang::Ld => "LD",
                    automat_plcopen::sheet::SheetLang::Fbd => "FBD",
                    automat_plcopen::sheet::SheetLang::Sfc => "SFC",
                };
                let title = format!("{} ({lang}, {})", s.pou, f.name);
                return Ok(sheet::draw(&s).finish(&title));
            }
            Ok(Found::Textual(lang)) => {
                return Err(format!(
                    "{}: POU `{pou}` has an {lang} body: only LD, FBD and SFC bodies are drawn",
                    f.name
                ))
            }
            Ok(Found::NotHere) => {}
            Err(e) => return Err(format!("{}: not well-formed XML: {e}", f.name)),
        }
    }
    // SLC-500 ladder: a program file's rungs, laid out automatically.
    if map
        .files()
        .any(|(_, f)| automat_dialect::is_slc_file(&f.name))
    {
        if let Some(s) = automat_dialect::slc_sheet(map, pou) {
            let title = format!("{} (SLC-500 ladder)", s.pou);
            return Ok(sheet::draw(&s).finish(&title));
        }
    }
    let mut interner = automat_base::Interner::new();
    for (id, f) in map.files() {
        if automat_plcopen::is_plcopen_file(&f.name) || automat_dialect::is_slc_file(&f.name) {
            continue;
        }
        let parsed = automat_syntax::parse(id, &f.text, &mut interner);
        for item in &parsed.unit.items {
            let automat_syntax::ast::Item::Pou(p) = item else {
                continue;
            };
            if !interner.name(p.name.sym).eq_ignore_ascii_case(pou) {
                continue;
            }
            return match &p.lang {
                automat_syntax::ast::Lang::Sfc(c) => {
                    let title = format!("{} (SFC, {})", interner.name(p.name.sym), f.name);
                    Ok(chart::draw(c, &f.text, &interner).finish(&title))
                }
                _ => Err(format!(
                    "{}: POU `{pou}` has a textual body without an SFC chart: only LD, FBD and SFC bodies are drawn",
                    f.name
                )),
            };
        }
    }
    Err(format!("no POU named `{pou}` in the sources"))
}

fn write(d: &Diagram, output: &Path) -> Result<(), String> {
    let ext = output
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("svg") => std::fs::write(output, svg::diagram(d)),
        Some("png") => std::fs::write(output, png::encode(d)?),
        _ => {
            return Err(format!(
                "{}: the drawing is written as SVG or PNG; name the output `*.svg` or `*.png`",
                output.display()
            ))
        }
    }
    .map_err(|e| format!("{}: {e}", output.display()))
}

pub fn run(args: &DrawArgs) -> Outcome {
    let mut sources = Vec::new();
    let mut plain = Vec::new();
    for p in &args.paths {
        match automat_project::project_file(p) {
            Some(toml) => {
                let mut map = automat_base::SourceMap::new();
                match automat_project::load(&toml, &mut map) {
                    Ok(project) => sources.extend(project.sources),
                    Err(d) => {
                        eprint!("{}", automat_base::render::render_report(&map, &d));
                        return Outcome::ProgramErrors;
                    }
                }
            }
            None => plain.push(p.clone()),
        }
    }
    if !plain.is_empty() {
        match files::collect(&plain) {
            Ok(f) => sources.extend(f),
            Err(e) => {
                eprintln!("error: {e}");
                return Outcome::BadInput;
            }
        }
    }
    let map = match files::load(&sources) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("error: {e}");
            return Outcome::BadInput;
        }
    };
    let d = match diagram_of(&map, &args.pou) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("error: {e}");
            return Outcome::ProgramErrors;
        }
    };
    match write(&d, &args.output) {
        Ok(()) => Outcome::Ok,
        Err(e) => {
            eprintln!("error: {e}");
            Outcome::BadInput
        }
    }
}

#[cfg(test)]
#[path = "tests.rs"]
mod tests;
