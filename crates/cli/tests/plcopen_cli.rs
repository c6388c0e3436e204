//! PLCopen XML on the command line: `check` and `run` on a folder mixing a
//! `.xml` and a `.st` file, a bad file's diagnostics at its XML line:col,
//! and `export` whose output runs the same.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn automat(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_automat"))
        .args(args)
        .output()
        .expect("run automat")
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("automat-plcopen-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

/// A function block in LD (a seal-in rung: q := (start OR q) AND NOT stop).
const LATCH: &str = r#"<project xmlns="http://www.plcopen.org/xml/tc6_0201">
<types><dataTypes/><pous>
<pou name="Latch" pouType="functionBlock">
<interface>
<inputVars><variable name="start"><type><BOOL/></type></variable><variable name="stop"><type><BOOL/></type></variable></inputVars>
<outputVars><variable name="q"><type><BOOL/></type></variable></outputVars>
</interface>
<body><LD>
<leftPowerRail localId="1"><connectionPointOut/></leftPowerRail>
<contact localId="2"><position x="50" y="20"/><connectionPointIn><connection refLocalId="1"/></connectionPointIn><connectionPointOut/><variable>start</variable></contact>
<contact localId="3"><position x="50" y="60"/><connectionPointIn><connection refLocalId="1"/></connectionPointIn><connectionPointOut/><variable>q</variable></contact>
<contact localId="4" negated="true"><position x="120" y="20"/><connectionPointIn><connection refLocalId="2"/><connection refLocalId="3"/></connectionPointIn><connectionPointOut/><variable>stop</variable></contact>
<coil localId="5"><position x="200" y="20"/><connectionPointIn><connection refLocalId="4"/></connectionPointIn><connectionPointOut/><variable>q</variable></coil>
</LD></body>
</pou>
</pous></types><instances><configurations/></instances></project>
"#;

/// The program in ST: start in scan 2 only, stop in scan 5.
const MAIN: &str = "PROGRAM Main
VAR n : INT; l : Latch; on : BOOL; END_VAR
n := n + 1;
l(start := n = 2, stop := n = 5);
on := l.q;
END_PROGRAM
";

fn project(name: &str) -> PathBuf {
    let d = dir(name);
    std::fs::write(d.join("latch.xml"), LATCH).expect("write");
    std::fs::write(d.join("main.st"), MAIN).expect("write");
    d
}

fn run_on(path: &Path, cycles: &str) -> (Option<i32>, String, String) {
    let p = path.to_string_lossy().into_owned();
    let out = automat(&["run", &p, "--cycles", cycles, "--print", "Main.on"]);
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn a_folder_mixing_xml_and_st_checks_and_runs() {
    let d = project("mixed");
    let p = d.to_string_lossy().into_owned();
    let out = automat(&["check", &p]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    assert_eq!(run_on(&d, "4").1, "Main.on = TRUE\n");
    assert_eq!(run_on(&d, "5").1, "Main.on = FALSE\n");
}

#[test]
fn xml_errors_point_at_the_element() {
    let d = dir("bad");
    let bad = LATCH.replace(
        "<connection refLocalId=\"4\"/>",
        "<connection refLocalId=\"40\"/>",
    );
    std::fs::write(d.join("latch.xml"), bad).expect("write");
    let f = d.join("latch.xml").to_string_lossy().into_owned();
    let out = automat(&["check", &f]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{text}");
    assert!(
        text.contains(
            "latch.xml:13:64: error[E172]: POU `Latch`, localId 5: a connection names localId 40"
        ),
        "{text}"
    );
}

#[test]
fn export_writes_a_project_that_runs_the_same() {
    let d = project("export");
    let out_file = d.join("out").with_extension("xml");
    let p = d.to_string_lossy().into_owned();
    let o = out_file.to_string_lossy().into_owned();
    let out = automat(&["export", &p, "-o", &o]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let xml = std::fs::read_to_string(&out_file).expect("exported");
    assert!(
        xml.contains("<pou name=\"Main\" pouType=\"program\">"),
        "{xml}"
    );
    assert!(
        xml.contains("<contact localId=\"4\" negated=\"true\">"),
        "{xml}"
    );
    // Only the exported file: the same behaviour.
    let only = dir("export-only").join("project.xml");
    std::fs::write(&only, &xml).expect("write");
    assert_eq!(run_on(&only, "4").1, "Main.on = TRUE\n");
    assert_eq!(run_on(&only, "5").1, "Main.on = FALSE\n");
    // A project TC6 cannot hold is E178, exit 1.
    let g = dir("export-global");
    std::fs::write(g.join("g.st"), "VAR_GLOBAL x : INT; END_VAR\nPROGRAM P VAR_EXTERNAL x : INT; END_VAR x := 1; END_PROGRAM\n").expect("write");
    let gp = g.to_string_lossy().into_owned();
    let out = automat(&["export", &gp, "-o", &o]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("error[E178]"));
}

#[test]
fn draw_writes_svg_and_png() {
    let d = project("draw");
    let svg = d.join("latch.svg");
    let png = d.join("latch.png");
    let p = d.to_string_lossy().into_owned();
    for out in [&svg, &png] {
        let o = automat(&["draw", &p, "--pou", "latch", "-o", &out.to_string_lossy()]);
        assert_eq!(
            o.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    let text = std::fs::read_to_string(&svg).unwrap_or_default();
    assert!(text.starts_with("<svg "), "{text}");
    assert_eq!(text.matches("class=\"text-contact\"").count(), 3);
    assert_eq!(text.matches("class=\"text-coil\"").count(), 1);
    let bytes = std::fs::read(&png).unwrap_or_default();
    assert!(bytes.starts_with(b"\x89PNG"));
    // An ST POU, an unknown POU, a bad extension.
    let o = automat(&["draw", &p, "--pou", "Main", "-o", &svg.to_string_lossy()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("textual body without an SFC chart"));
    let o = automat(&["draw", &p, "--pou", "Nope", "-o", &svg.to_string_lossy()]);
    assert_eq!(o.status.code(), Some(1));
    let bad = d.join("latch.gif").to_string_lossy().into_owned();
    let o = automat(&["draw", &p, "--pou", "Latch", "-o", &bad]);
    assert_eq!(o.status.code(), Some(2));
}

/// `automat export` refuses object-oriented units (E178, exit 1, no file
/// written): TC6 2.01 has no element for methods, classes or interfaces.
#[test]
fn export_refuses_object_orientation() {
    let d = dir("export-oop");
    let src = d.join("oop.st");
    std::fs::write(
        &src,
        "FUNCTION_BLOCK Counter\nVAR_OUTPUT n : INT; END_VAR\nMETHOD Inc : INT\n    n := n + 1;\n    Inc := n;\nEND_METHOD\nEND_FUNCTION_BLOCK\n\
         PROGRAM Main\nVAR c : Counter; x : INT; END_VAR\n    x := c.Inc();\nEND_PROGRAM\n",
    )
    .expect("write");
    let out_file = d.join("out.xml");
    let (s, o) = (
        src.to_string_lossy().into_owned(),
        out_file.to_string_lossy().into_owned(),
    );
    let out = automat(&["export", &s, "-o", &o]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("oop.st:1:16: error[E178]: function block `Counter` has methods, inheritance or interfaces, which TC6 2.01 XML cannot hold"),
        "{err}"
    );
    assert!(!out_file.exists());
    // The same project runs.
    let run = automat(&["run", &s, "--cycles", "2", "--print", "x"]);
    assert_eq!(String::from_utf8_lossy(&run.stdout), "x = 2\n");
}

/// `automat export` refuses namespaces and a POU's USING (E178, exit 1):
/// TC6 2.01 has no element for them; the project still runs.
#[test]
fn export_refuses_namespaces() {
    let d = dir("export-namespace");
    let src = d.join("ns.st");
    std::fs::write(
        &src,
        "NAMESPACE Motion\nFUNCTION Two : INT\n    Two := 2;\nEND_FUNCTION\nEND_NAMESPACE\n\
         PROGRAM Main\nUSING Motion;\nVAR x : INT; END_VAR\n    x := Two() + Motion.Two();\nEND_PROGRAM\n",
    )
    .expect("write");
    let out_file = d.join("out.xml");
    let (s, o) = (
        src.to_string_lossy().into_owned(),
        out_file.to_string_lossy().into_owned(),
    );
    let out = automat(&["export", &s, "-o", &o]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        err.matches("error[E178]: a NAMESPACE (or a POU's USING) has no place in TC6 2.01 XML")
            .count(),
        2,
        "{err}"
    );
    assert!(err.contains("ns.st:1:1: error[E178]"), "{err}");
    assert!(!out_file.exists());
    let run = automat(&["run", &s, "--cycles", "1", "--print", "x"]);
    assert_eq!(String::from_utf8_lossy(&run.stdout), "x = 4\n");
}

/// `automat draw` of a chart with a macro-step (the conformance case
/// `plcopen_macrostep`): the chart as drawn in the file, the macro-step as
/// its box with the two bars (its body is a chart of its own, not drawn
/// inside it).
#[test]
fn draw_a_chart_with_a_macro_step() {
    let case =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/conformance/plcopen_macrostep.xml");
    let d = dir("draw-macro");
    let svg = d.join("chart.svg");
    let c = case.to_string_lossy().into_owned();
    let o = automat(&["draw", &c, "--pou", "Chart", "-o", &svg.to_string_lossy()]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let text = std::fs::read_to_string(&svg).unwrap_or_default();
    assert!(text.starts_with("<svg "), "{text}");
    assert_eq!(text.matches("class=\"macro-step\"").count(), 3, "{text}");
    assert_eq!(text.matches("class=\"initial-step\"").count(), 2, "{text}");
    assert_eq!(text.matches("class=\"text-step\"").count(), 2, "{text}");
    assert_eq!(text.matches("class=\"transition\"").count(), 4, "{text}");
    assert!(text.contains(">M<") && text.contains(">S0<"), "{text}");
}
