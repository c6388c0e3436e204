//! The CODESYS heap's size from the command line (`--lib codesys:heap=SIZE`)
//! and from automat.toml (`[codesys] heap`), end to end: 8 LINTs (72 bytes
//! with the block header) do not fit a 64-byte heap, and fit the default.

use std::path::PathBuf;
use std::process::Command;

const PROGRAM: &str = "PROGRAM Main\nVAR p : POINTER TO LINT; full : BOOL; END_VAR\n    p := __NEW(LINT, 8);\n    full := p = 0;\nEND_PROGRAM\n";

fn scratch(tag: &str, toml: Option<&str>) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("automat-cli-heap-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    std::fs::write(dir.join("main.st"), PROGRAM).expect("source");
    if let Some(t) = toml {
        std::fs::write(dir.join("automat.toml"), t).expect("toml");
    }
    dir
}

fn run(args: &[&str]) -> (Option<i32>, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_automat"))
        .args(args)
        .output()
        .expect("automat runs");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn the_heap_size_from_the_command_line() {
    let dir = scratch("lib", None);
    let file = dir.join("main.st");
    let file = file.to_str().unwrap_or_default();
    let small = run(&[
        "run",
        "--lib",
        "codesys:heap=64B",
        "--cycles",
        "1",
        "--print",
        "full",
        file,
    ]);
    assert_eq!(small, (Some(0), "full = TRUE\n".into(), String::new()));
    let default = run(&[
        "run", "--lib", "codesys", "--cycles", "1", "--print", "full", file,
    ]);
    assert_eq!(default, (Some(0), "full = FALSE\n".into(), String::new()));
    let (code, _, err) = run(&["run", "--lib", "codesys:heap=1KB", "--cycles", "1", file]);
    assert_eq!(code, Some(2));
    assert_eq!(
        err,
        "error: --lib: heap size `1KB`: unknown unit `kb` (write bytes, `KiB` or `MiB`: `256KiB`)\n"
    );
    let (code, _, err) = run(&["check", "--lib", "codesys:stack=1", file]);
    assert_eq!(code, Some(2));
    assert!(
        err.contains("unknown setting `stack=1` of library `codesys`"),
        "{err}"
    );
}

#[test]
fn the_heap_size_from_the_project_file() {
    let toml = "[project]\nname = \"h\"\nlibraries = [\"codesys\"]\n\n[codesys]\nheap = \"64B\"\n";
    let dir = scratch("toml", Some(toml));
    let d = dir.to_str().unwrap_or_default();
    let (code, out, err) = run(&["run", "--cycles", "1", "--print", "full", d]);
    assert_eq!((code, out.as_str()), (Some(0), "full = TRUE\n"), "{err}");
}
