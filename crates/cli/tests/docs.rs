//! Documentation generated from code stays equal to the code.

#[test]
fn diagnostics_doc_is_current() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/diagnostics.md");
    let on_disk = std::fs::read_to_string(path).unwrap_or_default();
    let generated = automat_base::codes::markdown();
    if on_disk != generated {
        if std::env::var_os("UPDATE_DOCS").is_some() {
            std::fs::write(path, &generated).expect("write docs/diagnostics.md");
        } else {
            panic!("docs/diagnostics.md is stale: run `UPDATE_DOCS=1 cargo test -p automat --test docs`");
        }
    }
}
