//! `--lib` on `automat check` and `automat run`: the vendor dialects from
//! the command line (docs/vendor-dialects.md).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/dialect")
        .join(name)
}

fn automat(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_automat"))
        .args(args)
        .output()
        .expect("run automat")
}

fn path(p: &Path) -> &str {
    p.to_str().unwrap_or(".")
}

#[test]
fn check_needs_the_dialect_and_refuses_unknown_ones() {
    let mixer = example("isagraf_mixer");
    assert_eq!(
        automat(&["check", "--lib", "isagraf", path(&mixer)])
            .status
            .code(),
        Some(0)
    );
    assert_eq!(automat(&["check", path(&mixer)]).status.code(), Some(1));
    let bad = automat(&["check", "--lib", "siemens", path(&mixer)]);
    assert_eq!(bad.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&bad.stderr),
        "error: --lib: unknown library `siemens` (known: isagraf, pl7, fst, codesys)\n"
    );
}

#[test]
fn run_with_a_dialect_prints_exact_values() {
    let drill = example("pl7_drill");
    let out = automat(&[
        "run",
        "--lib",
        "pl7",
        path(&drill),
        "--cycles",
        "31",
        "--print",
        "holes",
        "--print",
        "Chart._X1.X",
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        String::from_utf8_lossy(&out.stdout),
        "holes = 2\nChart._X1.X = TRUE\n"
    );
    let mixer = example("isagraf_mixer");
    let out = automat(&[
        "run",
        "--lib",
        "isagraf",
        path(&mixer),
        "--cycles",
        "45",
        "--print",
        "batches",
        "--print",
        "mix_time",
    ]);
    assert_eq!(
        String::from_utf8_lossy(&out.stdout),
        "batches = 1\nmix_time = T#210ms\n"
    );
}
