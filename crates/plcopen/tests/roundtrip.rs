//! Import → export → import keeps behaviour: every conformance case
//! (`tests/conformance/*.st` and `*.xml`) that passes is exported with
//! `automat_plcopen::export`, given its expectation header back (in an XML
//! comment) and run again; it must pass the same expectations. Each export
//! must also be valid against the TC6 2.01 schema (`xmllint --schema` on
//! `shared/standards/tc6_xml_v201.xsd`, beside the repository; `.ci/run`
//! installs `libxml2-utils`).
//!
//! Left out, and counted: cases of a vendor dialect (their rewrites work on
//! the ST text), cases expecting a fault (the expected line is an ST line),
//! and projects TC6 cannot hold (E178: a VAR_GLOBAL outside a
//! configuration, the object-oriented `oop_*` cases).

use automat_base::{Code, Interner, SourceMap};
use automat_scenario::conformance::{is_conformance, judge, Backend, Verdict};
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn schema() -> PathBuf {
    let rel = "shared/standards/tc6_xml_v201.xsd";
    let candidates = [root().join("..").join(rel), root().join("../..").join(rel)];
    candidates
        .iter()
        .find(|p| p.exists())
        .cloned()
        .unwrap_or_else(|| panic!("the TC6 schema is not at {}", candidates[0].display()))
}

/// The case's `(* … *)` header, made fit for an XML comment.
fn header(text: &str) -> Option<String> {
    let t = text.trim_start();
    let t = t.strip_prefix("<!--").map_or(t, str::trim_start);
    let body = t.strip_prefix("(*")?;
    let end = body.find("*)")?;
    // An inline ` -- ` note goes to a line of its own (a `note:` line is
    // free text); XML comments cannot hold `--`.
    Some(
        body.get(..end)?
            .replace(" -- ", "\n   note: ")
            .replace("--", "note:"),
    )
}

fn validate(name: &str, xml: &str, dir: &Path) -> Result<(), String> {
    let path = dir.join(format!("{name}.export.xml"));
    std::fs::write(&path, xml).map_err(|e| e.to_string())?;
    let out = Command::new("xmllint")
        .arg("--noout")
        .arg("--schema")
        .arg(schema())
        .arg(&path)
        .output()
        .map_err(|e| format!("xmllint (Debian package libxml2-utils) did not run: {e}"))?;
    if out.status.success() {
        Ok(())
    } else {
        Err(String::from_utf8_lossy(&out.stderr).into_owned())
    }
}

#[test]
fn export_then_import_keeps_behaviour() {
    let dir = root().join("tests/conformance");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    files.retain(|p| p.extension().is_some_and(|x| x == "st" || x == "xml"));
    files.sort();
    let tmp = std::env::temp_dir().join(format!("automat-roundtrip-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).expect("temp dir");
    let (mut passed, mut dialect, mut fault, mut no_tc6) = (0, 0, 0, Vec::new());
    let mut failures = Vec::new();
    for f in &files {
        let name = f
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let text = std::fs::read_to_string(f).unwrap_or_default();
        if !is_conformance(&text) {
            continue;
        }
        let Some(head) = header(&text) else { continue };
        if head.contains("libraries:") {
            dialect += 1;
            continue;
        }
        if head.contains("expect-fault:") {
            fault += 1;
            continue;
        }
        if judge(&name, &text, Backend::Interp) != Verdict::Passed {
            continue;
        }
        let mut map = SourceMap::new();
        map.add(name.clone(), text.clone());
        let mut interner = Interner::new();
        let (units, analysis) = automat_dialect::check_sources(&map, &mut interner, &[]);
        assert!(!analysis.has_errors(), "{name} passed but does not check");
        let xml = match automat_plcopen::export(&units, &map, &name) {
            Ok(x) => x,
            Err(d) if d.iter().all(|d| d.code == Code::E178) => {
                no_tc6.push(name);
                continue;
            }
            Err(d) => panic!("{name}: {d:?}"),
        };
        if let Err(e) = validate(&name, &xml, &tmp) {
            failures.push(format!("{name}: not valid TC6 2.01:\n{e}"));
            continue;
        }
        let body = xml.split_once("?>\n").map_or(xml.as_str(), |(_, b)| b);
        let again = format!("<!--(*{head}*)-->\n{body}");
        let exported = format!("{name}.xml");
        match judge(&exported, &again, Backend::Interp) {
            Verdict::Passed => passed += 1,
            v => failures.push(format!("{name}: after export: {v:?}")),
        }
    }
    let _ = std::fs::remove_dir_all(&tmp);
    eprintln!(
        "round trip: {passed} cases passed after export; left out: {dialect} of a dialect, {fault} expecting a fault, {} not expressible in TC6 ({})",
        no_tc6.len(),
        no_tc6.join(", ")
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(
        passed >= 60,
        "only {passed} cases went through the round trip"
    );
}

/// The hand-written TC6 2.01 cases are valid against the schema too (the
/// 2.0 case has the other namespace).
#[test]
fn the_tc6_201_cases_are_valid() {
    let dir = root().join("tests/conformance");
    let mut n = 0;
    for e in std::fs::read_dir(&dir)
        .expect("corpus")
        .filter_map(Result::ok)
    {
        let p = e.path();
        let text = std::fs::read_to_string(&p).unwrap_or_default();
        if p.extension().is_some_and(|x| x == "xml") && text.contains("tc6_0201") {
            let out = Command::new("xmllint")
                .arg("--noout")
                .arg("--schema")
                .arg(schema())
                .arg(&p)
                .output()
                .expect("xmllint (Debian package libxml2-utils)");
            assert!(
                out.status.success(),
                "{}",
                String::from_utf8_lossy(&out.stderr)
            );
            n += 1;
        }
    }
    assert!(n >= 6, "only {n} TC6 2.01 cases");
}
