//! The dialect rewrites never panic: every file of the front-end and
//! conformance corpora, whole and cut at several places (broken input),
//! goes through `check_sources` with the chart dialects (ISaGRAF and PL7)
//! on, and again with the CODESYS dialect.

use automat_base::{Interner, SourceMap};
use automat_dialect::{add_libraries, check_sources, Dialect};
use std::path::{Path, PathBuf};

fn st_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(rd) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<PathBuf> = rd.filter_map(|e| e.ok().map(|e| e.path())).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            st_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "st") {
            out.push(p);
        }
    }
}

#[test]
fn rewrites_survive_every_corpus_file_and_its_prefixes() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests");
    let mut files = Vec::new();
    for sub in ["corpus/valid", "corpus/invalid", "conformance", "vendor"] {
        st_files(&root.join(sub), &mut files);
    }
    assert!(
        files.len() > 50,
        "corpus not found under {}",
        root.display()
    );
    for dialects in [
        &[Dialect::Isagraf, Dialect::Pl7][..],
        &[Dialect::Codesys][..],
    ] {
        for f in &files {
            let text = std::fs::read_to_string(f).unwrap_or_default();
            let mut cuts: Vec<usize> = (1..5).map(|k| text.len() * k / 5).collect();
            cuts.push(text.len());
            for cut in cuts {
                let mut cut = cut;
                while !text.is_char_boundary(cut) {
                    cut -= 1;
                }
                let mut map = SourceMap::new();
                map.add(f.display().to_string(), &text[..cut]);
                add_libraries(&mut map, dialects);
                let mut interner = Interner::new();
                let _ = check_sources(&map, &mut interner, dialects);
            }
        }
    }
}
