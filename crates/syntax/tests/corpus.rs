//! The shared corpus (`tests/corpus/` at the repository root) from the
//! parser's side: every file must produce exactly the syntax errors
//! (E001–E007, the IL parser's, and the chart checks E120–E131 that
//! `parse` runs on each textual SFC) that its `//~ Ennn` comments announce
//! (`//~^` for the line above), and no other. Warnings and codes from later
//! stages are ignored here (the checker's harness judges them).

use automat_base::{FileId, Interner, SourceFile};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn st_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        // Vendor-dialect projects are annotated for `--lib`:
        // crates/dialect/tests/corpus.rs checks them.
        let name = p.file_name().map(|n| n.to_string_lossy().into_owned());
        if name.is_some_and(|n| n.starts_with("isagraf_") || n.starts_with("pl7_")) {
            continue;
        }
        if p.is_dir() {
            st_files(&p, out);
        } else if p.extension().is_some_and(|x| x.eq_ignore_ascii_case("st")) {
            out.push(p);
        }
    }
}

fn is_syntax_code(code: &str) -> bool {
    matches!(
        code,
        "E001" | "E002" | "E003" | "E004" | "E005" | "E006" | "E007"
            // The IL codes the parser reports (E105–E107 are the checker's).
            | "E100" | "E101" | "E102" | "E103" | "E104" | "E108" | "E109" | "E110"
            // The chart checks of `desugar::sfc` (E127 is the checker's).
            | "E120" | "E121" | "E122" | "E123" | "E124" | "E125" | "E126"
            | "E128" | "E129" | "E130" | "E131"
    )
}

/// `line -> codes` announced by `//~` comments.
fn expected(text: &str) -> BTreeMap<u32, Vec<String>> {
    let mut map: BTreeMap<u32, Vec<String>> = BTreeMap::new();
    for (i, line) in text.lines().enumerate() {
        let Some(pos) = line.find("//~") else {
            continue;
        };
        let mut rest = &line[pos + 3..];
        let mut target = i as u32 + 1;
        while let Some(r) = rest.strip_prefix('^') {
            target -= 1;
            rest = r;
        }
        for code in rest.split_whitespace() {
            if is_syntax_code(code) {
                map.entry(target).or_default().push(code.to_string());
            }
        }
    }
    map
}

#[test]
fn corpus_syntax_diagnostics_match_the_annotations() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/corpus");
    let mut files = Vec::new();
    st_files(&root, &mut files);
    files.sort();
    let mut failures = Vec::new();
    for f in &files {
        let Ok(bytes) = std::fs::read(f) else {
            continue;
        };
        let text = String::from_utf8_lossy(&bytes);
        let mut interner = Interner::new();
        let parsed = automat_syntax::parse(FileId(0), &text, &mut interner);
        let sf = SourceFile::new("f", text.as_ref());
        let mut got: BTreeMap<u32, Vec<String>> = BTreeMap::new();
        for d in parsed
            .diagnostics
            .iter()
            .filter(|d| is_syntax_code(d.code.as_str()))
        {
            let line = sf.line_col(d.span.start).0;
            got.entry(line)
                .or_default()
                .push(d.code.as_str().to_string());
        }
        let want = expected(&text);
        if got != want {
            let detail: Vec<String> = parsed
                .diagnostics
                .iter()
                .map(|d| {
                    format!(
                        "  {}:{} {}",
                        sf.line_col(d.span.start).0,
                        d.code.as_str(),
                        d.message
                    )
                })
                .collect();
            failures.push(format!(
                "{}: expected {:?}, got {:?}\n{}",
                f.display(),
                want,
                got,
                detail.join("\n")
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
