//! `[codesys] heap = "SIZE"` in automat.toml: the CODESYS heap's size,
//! carried as the `codesys` library's setting; a bad value is an error at
//! its place in the file.

use automat_base::{Diagnostic, FileId, SourceMap};
use automat_project::Project;
use std::path::PathBuf;

const HEAP_PROGRAM: &str = "PROGRAM Main\nVAR p : POINTER TO LINT; full : BOOL; END_VAR\n    p := __NEW(LINT, 8);\n    full := p = 0;\nEND_PROGRAM\n";

fn dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("automat-heap-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    std::fs::write(dir.join("main.st"), HEAP_PROGRAM).expect("source");
    dir
}

fn parse(tag: &str, text: &str) -> Result<Project, Vec<Diagnostic>> {
    automat_project::file::parse(&dir(tag).join("automat.toml"), FileId(0), text)
}

/// The rendered errors of a bad project file.
fn errors(tag: &str, text: &str) -> String {
    let diags = parse(tag, text).expect_err("refused");
    let mut map = SourceMap::new();
    map.add("automat.toml", text);
    automat_base::render::render_report(&map, &diags)
}

#[test]
fn the_heap_setting_reaches_the_library() {
    let text = "[project]\nname = \"h\"\nlibraries = [\"codesys\"]\n\n[codesys]\nheap = \"64B\"\n";
    let p = parse("ok", text).expect("parses");
    assert_eq!(p.libraries, ["codesys:heap=64"]);
    assert!(automat_project::build::compile(&p.sources, None, &p.libraries).is_ok());
    let p = parse(
        "default",
        "[project]\nname = \"h\"\nlibraries = [\"codesys\"]\n",
    )
    .expect("parses");
    assert_eq!(p.libraries, ["codesys"]);
}

#[test]
fn a_bad_heap_is_an_error_at_its_value() {
    let report = errors(
        "bad",
        "[project]\nname = \"h\"\nlibraries = [\"codesys\"]\n\n[codesys]\nheap = \"100KB\"\n",
    );
    assert!(
        report.starts_with("automat.toml:6:8: error[E300]: heap: heap size `100KB`: unknown unit `kb` (write bytes, `KiB` or `MiB`: `256KiB`)"),
        "{report}"
    );
    let report = errors(
        "odd",
        "[project]\nname = \"h\"\nlibraries = [\"codesys\"]\n[codesys]\nheap = \"20\"\n",
    );
    assert!(
        report.starts_with(
            "automat.toml:5:8: error[E300]: heap: heap size `20` (20 bytes) is not a multiple of 8"
        ),
        "{report}"
    );
    let report = errors(
        "nolib",
        "[project]\nname = \"h\"\n[codesys]\nheap = \"1MiB\"\n",
    );
    assert!(
        report.starts_with("automat.toml:4:8: error[E300]: heap: `[codesys]` sets the CODESYS dialect, which this project does not use"),
        "{report}"
    );
    let report = errors(
        "key",
        "[project]\nname = \"h\"\n[codesys]\nstack = \"1MiB\"\n",
    );
    assert!(report.contains("unknown field `stack`"), "{report}");
}
