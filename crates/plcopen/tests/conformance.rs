//! The PLCopen cases of the execution conformance corpus
//! (`tests/conformance/plcopen_*.xml`) on both engines, with the runner of
//! `automat test`. `crates/cli/tests/conformance.rs` runs them too, with the
//! whole corpus; this harness keeps the importer's own test loop short.

use automat_scenario::conformance::{judge, Backend, Verdict};
use std::path::PathBuf;

fn corpus() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../tests/conformance")
}

fn cases() -> Vec<(String, String)> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(corpus())
        .unwrap_or_else(|e| panic!("{}: {e}", corpus().display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "xml"))
        .collect();
    files.sort();
    files
        .iter()
        .map(|p| {
            let name = p
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            let text = std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{name}: {e}"));
            (name, text)
        })
        .collect()
}

fn run(backend: Backend) {
    let cases = cases();
    assert!(cases.len() >= 7, "PLCopen cases missing: {}", cases.len());
    let mut failed = Vec::new();
    for (name, text) in &cases {
        match judge(name, text, backend) {
            Verdict::Passed => {}
            Verdict::Failed(m) | Verdict::Pending(m) | Verdict::KnownBug(m) => failed.push(m),
        }
    }
    assert!(
        failed.is_empty(),
        "{} of {} failed:\n{}",
        failed.len(),
        cases.len(),
        failed.join("\n")
    );
}

#[test]
fn plcopen_cases_interpreter() {
    run(Backend::Interp);
}

#[test]
fn plcopen_cases_jit() {
    run(Backend::Jit);
}

/// Prints the ST a case is read as: `PLCOPEN_SHOW=name.xml cargo test -p
/// automat-plcopen --test conformance show -- --nocapture`.
#[test]
fn show() {
    let Ok(want) = std::env::var("PLCOPEN_SHOW") else {
        return;
    };
    for (name, text) in cases().into_iter().filter(|(n, _)| *n == want) {
        let (st, diags) = automat_plcopen::generated_st(automat_base::FileId(0), &text);
        println!("==== {name}\n{st}\n{diags:#?}");
    }
}
