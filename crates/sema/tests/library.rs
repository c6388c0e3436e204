//! The vendor-style utility library (`tests/corpus/library/`, all files one
//! project) must check without any diagnostic.

use automat_base::{render, Interner, SourceMap};
use std::path::Path;

#[test]
fn utility_library_checks_clean() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/corpus/library");
    let mut paths: Vec<_> = std::fs::read_dir(&dir)
        .map(|d| d.filter_map(|e| e.ok()).map(|e| e.path()).collect())
        .unwrap_or_default();
    paths.retain(|p| p.extension().is_some_and(|e| e == "st"));
    paths.sort();
    assert!(!paths.is_empty(), "no library sources in {}", dir.display());
    let mut map = SourceMap::new();
    for p in &paths {
        let bytes = std::fs::read(p).expect("read library file");
        // Latin-1 fallback, as the CLI reads files.
        let text = String::from_utf8(bytes.clone())
            .unwrap_or_else(|_| bytes.iter().map(|&b| b as char).collect());
        let name = p
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        map.add(name, text);
    }
    let mut interner = Interner::new();
    let (_, analysis) = automat_sema::check_sources(&map, &mut interner);
    assert!(
        analysis.diagnostics.is_empty(),
        "{}",
        render::render_report(&map, &analysis.diagnostics)
    );
}
