//! Source folders with symbolic-link loops: `automat check` and
//! `automat test` read every file once and say once what they left out.
#![cfg(unix)]

use std::os::unix::fs::symlink;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn automat(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_automat"))
        .args(args)
        .output()
        .expect("run automat")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("automat-links-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

const MAIN: &str = "PROGRAM Main\nVAR x : INT; END_VAR\nx := x + 1;\nEND_PROGRAM\n";

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

fn d(p: &Path) -> String {
    p.display().to_string()
}

#[test]
fn a_link_to_the_parent_is_skipped_with_one_warning() {
    let dir = scratch("up");
    std::fs::create_dir(dir.join("sub")).unwrap();
    std::fs::write(dir.join("sub/main.st"), MAIN).unwrap();
    symlink("..", dir.join("sub/up")).unwrap();
    let out = automat(&["check", &d(&dir)]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert_eq!(text(&out.stdout), "");
    assert_eq!(
        text(&out.stderr),
        format!(
            "warning: {}: a symbolic link back to {} (a loop): not followed\n",
            d(&dir.join("sub/up")),
            d(&dir)
        )
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn two_links_into_each_other_end_and_each_file_is_read_once() {
    // Before, this ran forever with growing memory; a file read twice
    // would be a duplicate POU (E010).
    let dir = scratch("pair");
    std::fs::create_dir(dir.join("a")).unwrap();
    std::fs::create_dir(dir.join("b")).unwrap();
    std::fs::write(dir.join("a/main.st"), MAIN).unwrap();
    std::fs::write(
        dir.join("b/lib.st"),
        "FUNCTION Twice : INT\nVAR_INPUT v : INT; END_VAR\nTwice := v * 2;\nEND_FUNCTION\n",
    )
    .unwrap();
    symlink("../b", dir.join("a/to_b")).unwrap();
    symlink("../a", dir.join("b/to_a")).unwrap();
    let out = automat(&["check", &d(&dir)]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stdout));
    assert_eq!(text(&out.stdout), "");
    assert_eq!(
        text(&out.stderr),
        format!(
            "warning: {}: a symbolic link back to {} (a loop): not followed (and 1 more)\n",
            d(&dir.join("a/to_b/to_a")),
            d(&dir.join("a"))
        )
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_project_source_folder_with_a_loop_is_read_once() {
    let dir = scratch("project");
    std::fs::write(
        dir.join("automat.toml"),
        "[project]\nname = \"loop\"\nsources = [\"src\"]\n",
    )
    .unwrap();
    std::fs::create_dir(dir.join("src")).unwrap();
    std::fs::write(dir.join("src/main.st"), MAIN).unwrap();
    symlink(".", dir.join("src/again")).unwrap();
    let warning = format!(
        "warning: {}: a symbolic link back to {} (a loop): not followed\n",
        d(&dir.join("src/again")),
        d(&dir.join("src"))
    );
    let out = automat(&["check", &d(&dir)]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stdout));
    assert_eq!(text(&out.stdout), "");
    assert_eq!(text(&out.stderr), warning);
    // `automat test` searches the same folder: the loop is skipped there too.
    let out = automat(&["test", &d(&dir)]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stdout));
    assert_eq!(text(&out.stdout), "0 passed, 0 failed\n");
    assert_eq!(
        text(&out.stderr),
        format!(
            "warning: {}: a symbolic link back to {} (a loop): not followed\n",
            d(&dir.join("src/again")),
            d(&dir.join("src"))
        )
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
