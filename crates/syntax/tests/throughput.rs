//! Lexer and parser throughput on a project of typical ST (the samples,
//! repeated into 300 files of ~360 lines). Ignored by default: timing needs a
//! release build and a quiet machine.
//!
//! ```sh
//! cargo test --release -p automat-syntax --test throughput -- --ignored --nocapture
//! ```

use automat_base::{FileId, Interner};
use std::time::{Duration, Instant};

#[test]
#[ignore]
fn lines_per_second() {
    let samples = [
        include_str!("samples/math.st"),
        include_str!("samples/traffic.st"),
        include_str!("samples/plant.st"),
    ];
    let files: Vec<String> = (0..300).map(|i| samples[i % 3].repeat(4)).collect();
    let lines: usize = files.iter().map(|f| f.lines().count()).sum();
    let bytes: usize = files.iter().map(|f| f.len()).sum();
    let mut interner = Interner::new();
    let mut best_lex = Duration::MAX;
    let mut best_parse = Duration::MAX;
    for _ in 0..10 {
        let t = Instant::now();
        for f in &files {
            let mut diags = Vec::new();
            let lexed = automat_syntax::lexer::lex(FileId(0), f, &mut interner, &mut diags);
            assert!(diags.is_empty() && lexed.toks.len() > 1);
        }
        best_lex = best_lex.min(t.elapsed());
        let t = Instant::now();
        for f in &files {
            let parsed = automat_syntax::parse(FileId(0), f, &mut interner);
            assert!(parsed.diagnostics.is_empty());
        }
        best_parse = best_parse.min(t.elapsed());
    }
    let per_sec = |d: Duration| lines as f64 / d.as_secs_f64();
    println!(
        "{lines} lines, {} KiB: lex {best_lex:?} ({:.1} M lines/s), lex + parse {best_parse:?} ({:.1} M lines/s)",
        bytes >> 10,
        per_sec(best_lex) / 1e6,
        per_sec(best_parse) / 1e6,
    );
}
