//! `automat draw`: the drawings checked by their structure (which elements,
//! how many, where) on the conformance cases and examples.

use super::diagram_of;
use crate::plot::layout::{Diagram, Shape};
use crate::plot::{png, svg};
use automat_base::SourceMap;

fn root() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn draw(rel: &str, pou: &str) -> Diagram {
    let text = std::fs::read_to_string(root().join(rel)).unwrap_or_default();
    let mut map = SourceMap::new();
    map.add(rel, &text);
    match diagram_of(&map, pou) {
        Ok(d) => d,
        Err(e) => panic!("{rel}: {e}"),
    }
}

fn count(svg: &str, class: &str) -> usize {
    svg.matches(&format!("class=\"{class}\"")).count()
}

fn rects(d: &Diagram, class: &str) -> Vec<(f64, f64, f64, f64)> {
    d.shapes
        .iter()
        .filter_map(|s| match s {
            Shape::Rect {
                class: c,
                x,
                y,
                w,
                h,
            } if *c == class => Some((*x, *y, *w, *h)),
            _ => None,
        })
        .collect()
}

fn texts(d: &Diagram, class: &str) -> Vec<(f64, f64, String)> {
    d.shapes
        .iter()
        .filter_map(|s| match s {
            Shape::Text {
                class: c,
                x,
                y,
                text,
                ..
            } if *c == class => Some((*x, *y, text.clone())),
            _ => None,
        })
        .collect()
}

#[test]
fn ld_rungs_at_the_files_positions() {
    let d = draw("tests/conformance/plcopen_ld_contacts_coils.xml", "Ladder");
    let s = svg::diagram(&d);
    // 9 contacts (4 paths each), 9 coils (4 paths each), 2 rails (2 lines each).
    assert_eq!(count(&s, "text-contact"), 9);
    assert_eq!(count(&s, "contact"), 36);
    assert_eq!(count(&s, "text-coil"), 9);
    assert_eq!(count(&s, "coil"), 36);
    assert_eq!(count(&s, "rail"), 4);
    // Leftmost element x = 10, topmost y = 10: both moved to 40. Contact 2
    // at (60, 50) is at (90, 80); its variable is written over its middle.
    assert!(
        s.contains(r#"<text class="text-contact" x="100.5" y="76" text-anchor="middle" font-size="11">a</text>"#),
        "{s}"
    );
    assert!(
        s.contains(r#"<path class="contact" d="M90 90 L96 90""#),
        "{s}"
    );
    // Marks: negated contact 3 (a slash), edges P and N, S and R coils,
    // the negated coil 12 (a slash).
    let marks: Vec<String> = texts(&d, "text-mark").into_iter().map(|t| t.2).collect();
    assert_eq!(marks, ["P", "N", "S", "R", "P", "N"]);
    assert_eq!(count(&s, "negation"), 2);
    // One wire per connection of the file (19, and 7 into the right rail).
    assert_eq!(count(&s, "wire"), 26);
}

#[test]
fn fbd_blocks_pins_and_negations() {
    let d = draw("tests/conformance/plcopen_fbd_order.xml", "Flow");
    let blocks = rects(&d, "block");
    assert_eq!(blocks.len(), 7);
    // i2 (Inc) at (100, 50): minima are x 10, y 50.
    assert!(blocks.contains(&(130.0, 40.0, 80.0, 60.0)), "{blocks:?}");
    let pins: Vec<String> = texts(&d, "text-pin").into_iter().map(|t| t.2).collect();
    assert_eq!(pins.iter().filter(|p| *p == "IN1").count(), 4);
    assert!(
        pins.contains(&"v".to_string()),
        "in-out pin of Bump: {pins:?}"
    );
    let inst: Vec<String> = texts(&d, "text-instance")
        .into_iter()
        .map(|t| t.2)
        .collect();
    assert_eq!(inst, ["i1", "i2", "b1"]);
    let s = svg::diagram(&d);
    // The AND block's negated IN1 and OUT.
    assert_eq!(count(&s, "negation"), 2);
    // 10 input, 5 output and 1 in-out variables.
    assert_eq!(count(&s, "variable"), 16);
}

#[test]
fn fbd_connectors_jumps_and_returns() {
    let d = draw("tests/conformance/plcopen_fbd_connectors_jumps.xml", "Fj");
    let s = svg::diagram(&d);
    assert_eq!(count(&s, "text-connector"), 1);
    assert_eq!(count(&s, "text-continuation"), 2);
    assert_eq!(count(&s, "text-jump"), 1);
    assert_eq!(count(&s, "text-return"), 1);
    assert_eq!(texts(&d, "text-label")[0].2, "L1:");
    // The negated input variable and the negated output variable.
    assert_eq!(count(&s, "negation"), 2);
}

#[test]
fn textual_sfc_is_laid_out_by_rows() {
    let d = draw("examples/crane/crane.st", "Crane");
    let s = svg::diagram(&d);
    // GS1 initial (two rects), GS2..GS8.
    assert_eq!(count(&s, "initial-step"), 2);
    assert_eq!(count(&s, "step"), 7);
    // 8 transitions (two lines each), the last one a jump back to GS1.
    assert_eq!(count(&s, "transition"), 16);
    let jumps = texts(&d, "text-jump-step");
    assert_eq!(jumps.len(), 1);
    assert_eq!(jumps[0].2, "GS1");
    // One column, one row (110 px) per step, in chart order.
    let steps = texts(&d, "text-step");
    let names: Vec<&str> = steps.iter().map(|t| t.2.as_str()).collect();
    assert_eq!(
        names,
        ["GS1", "GS2", "GS3", "GS4", "GS5", "GS6", "GS7", "GS8"]
    );
    for (i, (x, y, _)) in steps.iter().enumerate() {
        assert_eq!(*x, steps[0].0);
        assert_eq!(*y, 59.0 + 110.0 * i as f64, "{names:?}");
    }
    // Conditions as written; actions with their qualifiers.
    let conds: Vec<String> = texts(&d, "text-transition")
        .into_iter()
        .map(|t| t.2)
        .collect();
    assert!(
        conds.contains(&"GS5.t >= DWELL_TIME".to_string()),
        "{conds:?}"
    );
    let acts: Vec<String> = texts(&d, "text-action").into_iter().map(|t| t.2).collect();
    assert!(acts.contains(&"WatchStart".to_string()), "{acts:?}");
}

#[test]
fn graphical_sfc_without_usable_positions_is_laid_out() {
    // The case puts several elements at one position: laid out by depth.
    let d = draw("tests/conformance/plcopen_sfc.xml", "Chart");
    let steps = texts(&d, "text-step");
    let names: Vec<&str> = steps.iter().map(|t| t.2.as_str()).collect();
    assert_eq!(names, ["Init", "Fill", "A", "B"]);
    // Init above Fill above A; A and B side by side.
    assert!(steps[0].1 < steps[1].1 && steps[1].1 < steps[2].1);
    assert_eq!(steps[2].1, steps[3].1);
    assert!(steps[2].0 < steps[3].0);
    let s = svg::diagram(&d);
    assert_eq!(count(&s, "initial-step"), 2);
    assert_eq!(count(&s, "divergence"), 4);
    assert_eq!(count(&s, "text-jump-step"), 1);
    let q: Vec<String> = texts(&d, "text-qualifier")
        .into_iter()
        .map(|t| t.2)
        .collect();
    assert_eq!(q, ["N", "N", "S"]);
}

#[test]
fn png_has_the_diagrams_size() {
    let d = draw("examples/crane-ld/crane.xml", "Crane");
    let pm = match png::raster_diagram(&d) {
        Ok(p) => p,
        Err(e) => panic!("{e}"),
    };
    assert_eq!(pm.width() as f64, d.width);
    assert_eq!(pm.height() as f64, d.height);
    // Black ink somewhere (rails, contacts).
    assert!(pm.pixels().iter().any(|p| p.red() < 50 && p.alpha() == 255));
}

#[test]
fn what_cannot_be_drawn() {
    let mut map = SourceMap::new();
    map.add("p.st", "PROGRAM P VAR x : INT; END_VAR x := 1; END_PROGRAM");
    let e = diagram_of(&map, "P").err().unwrap_or_default();
    assert!(e.contains("textual body without an SFC chart"), "{e}");
    let e = diagram_of(&map, "Q").err().unwrap_or_default();
    assert_eq!(e, "no POU named `Q` in the sources");
    let mut map = SourceMap::new();
    map.add("bad.xml", "<project><types><pous><pou name=\"P\"><body>");
    let e = diagram_of(&map, "P").err().unwrap_or_default();
    assert!(e.starts_with("bad.xml: not well-formed XML"), "{e}");
    let mut map = SourceMap::new();
    map.add(
        "st.xml",
        r#"<project><types><pous><pou name="P" pouType="program"><body><ST><xhtml:p xmlns:xhtml="http://www.w3.org/1999/xhtml">x := 1;</xhtml:p></ST></body></pou></pous></types></project>"#,
    );
    let e = diagram_of(&map, "p").err().unwrap_or_default();
    assert!(e.contains("POU `p` has an ST body"), "{e}");
}

/// What the HMI's live drawings hold (`GET /api/v1/drawings` before the
/// server resolves the paths): the crane's LD with every contact's and
/// coil's power flow, the PID loop's FBD with the pins of its block
/// instance and the variables of its variable elements.
#[test]
fn live_drawings_of_the_ld_and_fbd_examples() {
    let mut map = SourceMap::new();
    for rel in [
        "examples/crane-ld/crane.xml",
        "examples/pid-temperature-fbd/pid.xml",
    ] {
        let text = std::fs::read_to_string(root().join(rel)).unwrap_or_default();
        map.add(rel, &text);
    }
    let ds = super::live::drawings(&map);
    let names: Vec<(&str, &str)> = ds.iter().map(|d| (d.pou.as_str(), d.lang)).collect();
    assert_eq!(
        names,
        [
            ("Crane", "LD"),
            ("Avg4", "FBD"),
            ("Measure", "FBD"),
            ("Reg_temp", "FBD"),
            ("Output", "FBD")
        ]
    );
    let crane = &ds[0];
    assert!(crane.svg.starts_with("<svg ") && crane.svg.contains("class=\"contact\""));
    // Contact 23 (X7 drives M1S), placed where the drawing puts it.
    let c23 = crane
        .elements
        .iter()
        .find(|e| e.id == 23)
        .expect("contact 23");
    assert_eq!(
        (c23.kind, c23.text.as_str(), c23.x, c23.y, c23.w, c23.h),
        ("contact", "X7", 80.0, 300.0, 21.0, 20.0)
    );
    assert_eq!(c23.power.as_deref(), Some("__ld_n23"));
    let powered = crane.elements.iter().filter(|e| e.power.is_some()).count();
    let ld = crane
        .elements
        .iter()
        .filter(|e| matches!(e.kind, "contact" | "coil"))
        .count();
    assert_eq!((powered, ld), (64, 64));
    let measure = &ds[2];
    let filter = measure
        .elements
        .iter()
        .find(|e| e.id == 4)
        .expect("block 4");
    let pins: Vec<(&str, bool, &str, f64, f64)> = filter
        .pins
        .iter()
        .map(|p| (p.name.as_str(), p.output, p.path.as_str(), p.x, p.y))
        .collect();
    assert_eq!(pins, [("XOUT", true, "Filter.XOUT", 377.0, 150.0)]);
    let raw = measure
        .elements
        .iter()
        .find(|e| e.id == 1)
        .expect("variable 1");
    assert_eq!(
        (raw.kind, raw.value.as_deref()),
        ("in-variable", Some("T_raw"))
    );
}

/// An SLC-500 program file is drawn as rungs: the crane's 15 rungs, one
/// rail each, its 24 XIC contacts, 4 OTE and 18 OTL/OTU coils, the OSRs and
/// the TON as boxes, each operand with its symbol.
#[test]
fn slc_rungs_are_drawn_as_ladder() {
    let d = draw("examples/crane-slc/crane.slc", "LAD2");
    let s = svg::diagram(&d);
    // A rail is two shapes (its bar and its pin).
    assert_eq!(count(&s, "rail"), 30);
    // Four strokes per contact and per coil.
    assert_eq!(count(&s, "contact"), 24 * 4);
    assert_eq!(count(&s, "coil"), 22 * 4);
    assert_eq!(count(&s, "block"), 3);
    assert!(s.contains("Pornire I:1/1"));
    assert!(s.contains("T4:0/DN"));
    assert!(s.contains("rung 6: R5: step 5 action"));
    // The symbol table's descriptions above their operands (the symbol
    // and address are the element's text), shortened to fit the column:
    // 15 rung comments, 13 notes.
    assert!(s.contains(">cycle start push-button</text>"), "{s}");
    assert!(s.contains(">one scan on each press ...</text>"), "{s}");
    assert_eq!(count(&s, "text-comment"), 28);
    // By the file's name too.
    assert_eq!(
        svg::diagram(&draw("examples/crane-slc/crane.slc", "main")),
        s
    );
}

/// The SLC crane's ladder in the HMI's live drawings: LAD 2 as `automat
/// draw` draws it, run in the program `SLC`, its contacts and coils framed
/// by the `__ld_n<id>` power flow of the rung networks (its boxes too),
/// each showing its
/// bit, the dwell timer its ACC.
#[test]
fn live_drawings_of_the_slc_ladder() {
    let mut map = SourceMap::new();
    let rel = "examples/crane-slc/crane.slc";
    let text = std::fs::read_to_string(root().join(rel)).unwrap_or_default();
    map.add(rel, &text);
    let ds = super::live::drawings(&map);
    let names: Vec<(&str, &str, Option<&str>)> = ds
        .iter()
        .map(|d| (d.pou.as_str(), d.lang, d.runs_in.as_deref()))
        .collect();
    assert_eq!(names, [("LAD 2 MAIN", "LD", Some("SLC"))]);
    let lad = &ds[0];
    assert!(lad.svg.starts_with("<svg ") && lad.svg.contains("class=\"contact\""));
    assert!(lad.svg.contains(">cycle start push-button</text>"));
    let shown = |text: &str| {
        lad.elements
            .iter()
            .find(|e| e.text == text)
            .map(|e| (e.kind, e.power.clone(), e.value.clone(), e.pins.len()))
    };
    // R0: OSR B3/0 (ids 1, 2: the rung network's rail and `__rc`
    // contact): a box, its frame the power into it (the coil on
    // `__bin<k>` standing for it, id 3). R1a: XIC Pornire (ids 7, 8 the
    // rail and `__rc` contact after R0's six elements).
    let osr = lad.elements.iter().find(|e| e.text.starts_with("OSR"));
    assert!(
        osr.is_some_and(|e| e.power.as_deref() == Some("__ld_n3") && e.kind == "block"),
        "{osr:?}"
    );
    assert_eq!(
        shown("Pornire I:1/1"),
        Some(("contact", Some("__ld_n9".into()), Some("I:1/1".into()), 0))
    );
    let unframed: Vec<&str> = lad
        .elements
        .iter()
        .filter(|e| matches!(e.kind, "contact" | "coil" | "block") && e.power.is_none())
        .map(|e| e.text.as_str())
        .collect();
    assert!(
        unframed.is_empty(),
        "every contact, coil and box has its power flow: {unframed:?}"
    );
    let ton = lad.elements.iter().find(|e| e.text.starts_with("TON"));
    let pins: Vec<(&str, &str)> = ton
        .map(|e| {
            e.pins
                .iter()
                .map(|p| (p.name.as_str(), p.path.as_str()))
                .collect()
        })
        .unwrap_or_default();
    assert_eq!(pins, [("ACC", "T4:0.ACC")]);
}
