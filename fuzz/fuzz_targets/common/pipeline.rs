//! The whole `automat check` pipeline on one source text: parse, dialect
//! rewrites, semantic checks, lowering, rendering. Shared by the `check`,
//! `il` and `sfc` targets (each compiles it in by `#[path]`).

use automat_base::{render, Interner, SourceMap};

/// Checks `text` as `automat check` does (with the dialect chosen by
/// `dialect`: 0 none, 1 ISaGRAF, 2 PL7, 3 CODESYS): it must never panic, hang or
/// overflow the stack; every diagnostic span lies inside its file; the
/// text and JSON reports render.
pub fn check(text: &str, dialect: u8) {
    let names: &[&str] = match dialect % 4 {
        0 => &[],
        1 => &["isagraf"],
        2 => &["pl7"],
        _ => &["codesys"],
    };
    let Ok(dialects) = automat_dialect::parse_names(names) else {
        return;
    };
    let mut map = SourceMap::new();
    map.add("fuzz.st", text.to_string());
    automat_dialect::add_libraries(&mut map, &dialects);
    let mut interner = Interner::new();
    let (units, analysis) = automat_dialect::check_sources(&map, &mut interner, &dialects);
    let mut diags = analysis.diagnostics.clone();
    if !analysis.has_errors() {
        diags.extend(automat_lower::check(&units, &analysis, &interner, &map));
    }
    for d in &diags {
        if d.span.file.0 as usize >= map.len() {
            continue; // a whole-program diagnostic (Span::default()) is file 0
        }
        let len = map.get(d.span.file).text.len();
        assert!(
            d.span.start <= d.span.end && d.span.end as usize <= len,
            "{}: span {:?} outside its file",
            d.message,
            d.span
        );
    }
    let _ = render::render_report(&map, &diags);
    let _ = render::render_json(&map, &diags);
}
