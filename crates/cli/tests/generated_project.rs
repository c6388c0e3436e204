//! The benchmark's generated project must check clean, or the benchmark would
//! measure error paths instead of the real front end.

#[path = "../benches/gen.rs"]
mod gen;

use automat_base::{render, Interner, SourceMap};

#[test]
fn generated_project_checks_clean() {
    let files = gen::project(6);
    assert!(
        gen::line_count(&files) > 6 * 140,
        "{}",
        gen::line_count(&files)
    );
    let mut map = SourceMap::new();
    for (name, text) in &files {
        map.add(name.clone(), text.clone());
    }
    let mut interner = Interner::new();
    let (units, analysis) = automat_sema::check_sources(&map, &mut interner);
    assert_eq!(units.len(), 7);
    let report = render::render_report(&map, &analysis.diagnostics);
    assert!(analysis.diagnostics.is_empty(), "{report}");
}
