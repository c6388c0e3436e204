//! `[retain]` and `[safe_state]` of `automat.toml`: exact readings and
//! errors with their positions.

use automat_base::{Code, FileId};
use automat_project::{file, RetainSpec};
use std::path::{Path, PathBuf};

fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../cli/tests/fixtures/fault_safe_state/automat.toml")
}

fn parse(extra: &str) -> Result<automat_project::Project, Vec<automat_base::Diagnostic>> {
    let text = format!("[project]\nname = \"t\"\n{extra}");
    file::parse(&fixture(), FileId(0), &text)
}

#[test]
fn retain_table_is_read_with_the_project_folder() {
    let p = parse("[retain]\nfile = \"state/plc.retain\"\nsave_every = \"10s\"\noptional = true\n")
        .unwrap_or_else(|d| panic!("{d:?}"));
    let dir = fixture()
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    assert_eq!(
        p.retain,
        RetainSpec {
            file: Some(dir.join("state/plc.retain")),
            save_every_ns: Some(10_000_000_000),
            optional: true,
        }
    );
    assert_eq!(
        parse("").map(|p| p.retain).ok(),
        Some(RetainSpec::default())
    );
}

#[test]
fn retain_errors_point_at_the_value() {
    let text = "[retain]\nsave_every = \"-1s\"\n";
    let d = parse(text).unwrap_err();
    assert_eq!(d.len(), 1);
    assert_eq!(d[0].code, Code::E300);
    assert_eq!(
        d[0].message,
        "save_every: `-1s` is negative; a duration must be 0 or more"
    );
    let at = "[project]\nname = \"t\"\n[retain]\nsave_every = ".len() as u32;
    assert_eq!((d[0].span.start, d[0].span.end), (at, at + 5));
    // 0: only at stop.
    let p = parse("[retain]\nsave_every = \"0s\"\n").unwrap_or_else(|d| panic!("{d:?}"));
    assert_eq!(p.retain.save_every_ns, Some(0));
    let d = parse("[retain]\nsave_every = \"soon\"\n").unwrap_err();
    assert!(d[0].message.starts_with("save_every: "), "{}", d[0].message);
    let d = parse("[retain]\nevery = \"1s\"\n").unwrap_err();
    assert!(
        d[0].message.contains("unknown field `every`"),
        "{}",
        d[0].message
    );
}

#[test]
fn safe_values_by_quoted_or_dotted_keys() {
    let p = parse(
        "[safe_state]\n\"%QX0.1\" = true\nCtrl.speed = -5\nCtrl.level = 2.5\nCtrl.t = \"T#1s\"\n",
    )
    .unwrap_or_else(|d| panic!("{d:?}"));
    let got: Vec<(&str, &str)> = p
        .safe_state
        .iter()
        .map(|s| (s.target.as_str(), s.value.as_str()))
        .collect();
    assert_eq!(
        got,
        [
            ("%QX0.1", "TRUE"),
            ("Ctrl.level", "2.5"),
            ("Ctrl.speed", "-5"),
            ("Ctrl.t", "T#1s"),
        ]
    );
    let d = parse("[safe_state]\nx = [1, 2]\n").unwrap_err();
    assert_eq!(
        d[0].message,
        "[safe_state] `x`: a safe value is a boolean, a number or an IEC literal in a string"
    );
}

#[test]
fn safe_values_are_checked_against_the_program() {
    let project = parse("[safe_state]\n\"Ctrl.n\" = 70000\nnope = true\n\"Ctrl.M2S\" = true\n")
        .unwrap_or_else(|d| panic!("{d:?}"));
    let sources = vec![fixture().with_file_name("ctrl.st")];
    let (program, _) = automat_project::build::compile(&sources, None, &[])
        .unwrap_or_else(|e| panic!("{}", e.text));
    let d = automat_project::safe::build(&project, &program, None).unwrap_err();
    let msgs: Vec<&str> = d.iter().map(|d| d.message.as_str()).collect();
    assert_eq!(msgs.len(), 2, "{msgs:?}");
    assert!(
        msgs[0].starts_with("[safe_state] `Ctrl.n`: `70000` is not a valid INT literal"),
        "{msgs:?}"
    );
    assert!(msgs[1].starts_with("[safe_state] `nope`: "), "{msgs:?}");
    let ok = parse("[safe_state]\n\"Ctrl.M2S\" = true\n").unwrap_or_else(|d| panic!("{d:?}"));
    let safe =
        automat_project::safe::build(&ok, &program, None).unwrap_or_else(|d| panic!("{d:?}"));
    let mut image = program.initial_image.clone();
    safe.apply(&mut image);
    let place = automat_runtime::resolve(&program, "Ctrl.M2S").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(automat_runtime::value::format(&image, &place), "TRUE");
    assert_eq!(safe.describe(), "Ctrl.M2S set to TRUE");
}
