//! Robustness of `automat plot`: trace CSVs (written by example scenario
//! runs, and by hand in the `--trace` form) are mutated in many
//! deterministic ways (`crates/scenario/tests/support/mutate.rs`) and read
//! with `csv::parse`. It must return a trace or an error naming its line;
//! every trace that reads is laid out (all coordinates finite), written as
//! SVG (no `NaN`/`inf` in it) and, for every 50th, as PNG. Nothing may
//! panic or hang. The limits (columns, PNG height) have their own tests.

#[path = "../../../scenario/tests/support/mutate.rs"]
mod mutate;

use super::csv::{self, Series, Trace};
use super::layout::{layout, Seg, Shape};
use super::{png, svg};
use automat_base::SourceMap;
use mutate::{brief, guarded, mutate, Rng};
use std::path::Path;
use std::time::{Duration, Instant};

/// Mutants of each trace: about 3 000 in all.
const MUTANTS: usize = 400;
const CASE_LIMIT: Duration = Duration::from_secs(5);

const WORDS: &[&str] = &[
    "time",
    "TRUE",
    "FALSE",
    "T#0s",
    "T#10ms",
    "T#1000000000000000000ns",
    "T#106751d",
    "T#-10ms",
    "1.7976931348623157e308",
    "-1.7976931348623157e308",
    "5e-324",
    "-",
    "A#B",
    "Type#",
    "#",
    "\"a,b\"",
    "\"\"\"\"",
    ",",
    ",,,,,,,,",
    "'abc'",
];

const NESTS: &[(&str, &str)] = &[(",", ""), ("\"", ""), ("\"\"", ""), ("T#1s,", "")];

/// A trace written by hand in the `--trace` form: quoted cells, strings,
/// steps bands, a huge and a tiny number, uneven times.
const HAND: &str = "time,Main.b,Main.x,\"Main.arr[1, 2]\",steps(Main),Main.s,Main.t\n\
T#0s,FALSE,0,-3,Init,'',T#0s\n\
T#10ms,TRUE,1.5,1e300,Init Run,\"'a,b'\",T#1s\n\
T#20ms,TRUE,-2.25,-1e300,Run,\"'q\"\"uote'\",T#2s\n\
T#1h,FALSE,3,0,-,'x',T#3s\n\
T#1000000000000000000ns,TRUE,4,5e-324,Stop,'',T#106751d\n";

/// The trace of `svg_tests.rs`.
const SMALL: &str = "time,b,x,s\n\
T#0s,FALSE,0,A#Up\n\
T#10ms,TRUE,1,A#Up\n\
T#20ms,TRUE,2,A#Right\n\
T#30ms,FALSE,1,A#Right\n";

/// The CSV trace of an example scenario, run for `ns` of PLC time.
fn example_trace(example: &str, scenario: &str, ns: i64) -> Option<String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let dir = root.join(example);
    let mut map = SourceMap::new();
    let project = automat_project::load(&dir.join("automat.toml"), &mut map).ok()?;
    let (program, _) = automat_project::build::compile(
        &project.sources,
        project.program.clone(),
        &project.libraries,
    )
    .ok()?;
    let path = dir.join("scenarios").join(scenario);
    let text = std::fs::read_to_string(&path).ok()?;
    let file = map.add(path.display().to_string(), text.clone());
    let mut scn = automat_scenario::parse(&text, file, "s").ok()?;
    scn.duration_ns = scn.duration_ns.min(ns);
    let mut out = Vec::new();
    automat_scenario::run(&program, &project, &scn, Some(&mut out)).ok()?;
    String::from_utf8(out).ok()
}

fn finite_shapes(trace: &Trace) -> Result<(), String> {
    let d = layout(trace);
    let mut xs = vec![d.width, d.height];
    for s in &d.shapes {
        match s {
            Shape::Path { segs, .. } => {
                for g in segs {
                    match *g {
                        Seg::Move(x, y) | Seg::Line(x, y) => xs.extend([x, y]),
                        Seg::Horizontal(v) | Seg::Vertical(v) => xs.push(v),
                    }
                }
            }
            Shape::Band { x, y, w, h } | Shape::Rect { x, y, w, h, .. } => {
                xs.extend([*x, *y, *w, *h])
            }
            Shape::Circle { cx, cy, r, .. } => xs.extend([*cx, *cy, *r]),
            Shape::Line { x1, y1, x2, y2, .. } => xs.extend([*x1, *y1, *x2, *y2]),
            Shape::Text { x, y, .. } => xs.extend([*x, *y]),
        }
    }
    match xs.iter().find(|x| !x.is_finite()) {
        Some(x) => Err(format!("a coordinate is {x}")),
        None => Ok(()),
    }
}

/// One mutant; true when it read as a trace.
fn case(text: &str, png_too: bool) -> bool {
    let lines = text.lines().count().max(1);
    let trace = match csv::parse(text) {
        Err(e) => {
            if let Some(rest) = e.strip_prefix("line ") {
                let n: usize = rest
                    .split(':')
                    .next()
                    .and_then(|n| n.parse().ok())
                    .unwrap_or_else(|| panic!("no line number in {e:?}"));
                assert!(n >= 1 && n <= lines, "line {n} of {lines}: {e}");
            } else {
                assert_eq!(e, "the trace is empty");
            }
            return false;
        }
        Ok(t) => t,
    };
    assert!(trace.columns.len() < csv::MAX_COLUMNS);
    assert!(trace.times.windows(2).all(|w| w[0] <= w[1]));
    for c in &trace.columns {
        let n = match &c.series {
            Series::Bool(v) => v.len(),
            Series::Analog(v) => v.len(),
            Series::Bands(v) => v.len(),
        };
        assert_eq!(n, trace.times.len(), "column {}", c.name);
    }
    if let Err(e) = finite_shapes(&trace) {
        panic!("{e}");
    }
    let s = svg::render(&trace);
    assert!(s.ends_with("</svg>\n"));
    assert!(
        !s.contains("NaN") && !s.contains("inf\""),
        "NaN or inf in the SVG"
    );
    if png_too {
        if let Ok(bytes) = png::render(&trace) {
            assert!(bytes.starts_with(b"\x89PNG"));
        }
    }
    true
}

#[test]
fn mutated_traces_never_crash() {
    let mut inputs: Vec<(String, String)> =
        vec![("hand".into(), HAND.into()), ("small".into(), SMALL.into())];
    for (ex, scn) in [
        ("crane", "normal.scn"),
        ("pid-temperature", "normal.scn"),
        ("carwash", "normal.scn"),
        ("festo-distribution", "normal.scn"),
    ] {
        let t =
            example_trace(ex, scn, 500_000_000).unwrap_or_else(|| panic!("no trace of {ex}/{scn}"));
        inputs.push((format!("{ex}/{scn}"), t));
    }
    let start = Instant::now();
    let (mut cases, mut valid) = (0, 0);
    let mut failures = Vec::new();
    for (k, (name, src)) in inputs.iter().enumerate() {
        // The unmutated trace draws.
        assert!(
            case(src, true),
            "{name} does not read: {:?}",
            csv::parse(src).err()
        );
        for m in 0..MUTANTS {
            let seed = (k * 1_000 + m) as u64;
            let mut rng = Rng::new(seed);
            let bytes = mutate(&mut rng, src.as_bytes(), WORDS, NESTS);
            // `automat plot` reads the trace as UTF-8 text.
            let text = String::from_utf8_lossy(&bytes).into_owned();
            let mut ok = false;
            let r = guarded(&format!("{name} seed {seed}"), CASE_LIMIT, || {
                ok = case(&text, m % 50 == 0);
            });
            cases += 1;
            valid += usize::from(ok);
            if let Err(e) = r {
                failures.push(format!("{e}\n  input: {:?}", brief(&text, 400)));
            }
        }
    }
    eprintln!(
        "traces: {} inputs, {cases} mutants ({valid} valid) in {:?}",
        inputs.len(),
        start.elapsed()
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A header of a million columns, or a row of a million cells, is refused
/// at once (it used to become a million columns and a diagram 36 million
/// pixels high).
#[test]
fn a_million_columns_is_an_error() {
    let wide = format!(
        "time{}\nT#0s{}\n",
        ",a".repeat(1_000_000),
        ",1".repeat(1_000_000)
    );
    let e = csv::parse(&wide).unwrap_err();
    assert_eq!(
        e,
        "line 1: more than 10000 columns; a trace has at most 10000"
    );
    let row = format!("time,a\nT#0s{}\n", ",1".repeat(1_000_000));
    assert_eq!(
        csv::parse(&row).unwrap_err(),
        "line 2: more than 2 cells, the header has 2"
    );
    // The most columns a trace may have still draw.
    let most = format!(
        "time{}\nT#0s{}\n",
        ",a".repeat(csv::MAX_COLUMNS - 1),
        ",1".repeat(csv::MAX_COLUMNS - 1)
    );
    let trace = csv::parse(&most).unwrap_or_else(|e| panic!("{e}"));
    assert!(svg::render(&trace).ends_with("</svg>\n"));
    // ... but not as a PNG: 10 000 analog rows are 760 000 pixels high.
    let e = png::render(&trace).unwrap_err();
    assert!(e.contains("at most 16384 pixels high"), "{e}");
}

/// A time of 10^18 ns (31 years) and the largest TIME draw a few ticks,
/// without looping over the time span.
#[test]
fn huge_times_draw_a_few_ticks() {
    for t in [
        "T#1000000000000000000ns",
        "T#106751d23h47m16s854ms775us807ns",
    ] {
        let text = format!("time,b\nT#0s,TRUE\n{t},FALSE\n{t},TRUE\n");
        let trace = csv::parse(&text).unwrap_or_else(|e| panic!("{e}"));
        let d = layout(&trace);
        let ticks = d
            .shapes
            .iter()
            .filter(|s| matches!(s, Shape::Line { class: "tick", .. }))
            .count();
        assert!((2..=11).contains(&ticks), "{ticks} ticks");
        assert!(png::render(&trace).is_ok());
    }
}

/// Found while writing this test: an analog column from -1e308 to 1e308 made
/// every y NaN (`hi - lo` is infinite), and the SVG path said `NaN`.
#[test]
fn an_analog_range_wider_than_f64_draws() {
    let trace =
        csv::parse("time,x\nT#0s,-1e308\nT#1s,1e308\nT#2s,0\n").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(finite_shapes(&trace), Ok(()));
    let s = svg::render(&trace);
    // From the bottom (y 75) to the top (y 15) of the row, 0 in the middle.
    assert!(s.contains(r#"d="M140 75 L386.67 15 L633.33 45""#), "{s}");
}
