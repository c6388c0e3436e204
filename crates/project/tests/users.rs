//! `[users.NAME]` in automat.toml: the network API's logins.

use automat_base::{Diagnostic, FileId};
use automat_project::Project;
use std::path::PathBuf;

const HEAD: &str = "[project]\nname = \"p\"\n";

/// Parses `text` as the automat.toml of a folder holding one source.
fn parse(tag: &str, text: &str) -> Result<Project, Vec<Diagnostic>> {
    let dir: PathBuf =
        std::env::temp_dir().join(format!("automat-users-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    std::fs::write(dir.join("main.st"), "PROGRAM Main END_PROGRAM\n").expect("source");
    automat_project::file::parse(&dir.join("automat.toml"), FileId(0), text)
}

#[test]
fn users_are_read_with_their_role_and_hash() {
    let text = format!(
        "{HEAD}[users.ada]\nrole = \"viewer\"\npassword = \"$argon2id$v=19$x\"\n[users.otto]\nrole = \"operator\"\npassword = \"h\"\n"
    );
    let p = parse("ok", &text).expect("parses");
    let users: Vec<(&str, &str, &str)> = p
        .users
        .iter()
        .map(|u| (u.name.as_str(), u.role.as_str(), u.password_hash.as_str()))
        .collect();
    assert_eq!(
        users,
        [
            ("ada", "viewer", "$argon2id$v=19$x"),
            ("otto", "operator", "h")
        ]
    );
}

#[test]
fn an_unknown_role_or_field_is_an_error_at_its_place() {
    let text = format!("{HEAD}[users.ada]\nrole = \"admin\"\npassword = \"h\"\n");
    let e = parse("role", &text).unwrap_err();
    assert_eq!(
        e[0].message,
        "user `ada`: role `admin` is not viewer, operator or engineer"
    );
    let text = format!("{HEAD}[users.ada]\nrole = \"viewer\"\npassword = \"h\"\npw = 1\n");
    let e = parse("field", &text).unwrap_err();
    assert!(
        e[0].message.contains("unknown field `pw`"),
        "{}",
        e[0].message
    );
}
