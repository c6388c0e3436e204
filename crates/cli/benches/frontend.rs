//! Front-end benchmark: parse and check a generated project of ≥ 50,000 lines
//! of ST and report lines per second.
//!
//! `cargo bench -p automat --bench frontend` (add `-- --modules N` to resize).
//! Besides absolute figures it reports each phase relative to a reference
//! measured in the same run on the same text (splitting it into
//! whitespace-separated words), so figures from different machines compare.

#[path = "gen.rs"]
mod gen;

use automat_base::{Interner, SourceMap};
use std::hint::black_box;
use std::time::{Duration, Instant};

fn best_of<F: FnMut()>(runs: usize, mut f: F) -> Duration {
    (0..runs)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed()
        })
        .min()
        .unwrap_or_default()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let modules = args
        .iter()
        .position(|a| a == "--modules")
        .and_then(|i| args.get(i + 1))
        .and_then(|v| v.parse().ok())
        .unwrap_or(400usize);
    let runs = 5;
    let files = gen::project(modules);
    let lines = gen::line_count(&files);
    let bytes: usize = files.iter().map(|(_, t)| t.len()).sum();
    let mut map = SourceMap::new();
    for (name, text) in &files {
        map.add(name.clone(), text.clone());
    }

    let reference = best_of(runs, || {
        let words: usize = files
            .iter()
            .map(|(_, t)| t.split_ascii_whitespace().count())
            .sum();
        black_box(words);
    });
    let parse = best_of(runs, || {
        let mut interner = Interner::new();
        for (id, file) in map.files() {
            black_box(automat_syntax::parse(id, &file.text, &mut interner));
        }
    });
    let mut errors = 0;
    let check = best_of(runs, || {
        let mut interner = Interner::new();
        let (_, analysis) = automat_sema::check_sources(&map, &mut interner);
        errors = analysis.diagnostics.iter().filter(|d| d.is_error()).count();
        black_box(analysis);
    });

    let per_sec = |d: Duration| lines as f64 / d.as_secs_f64().max(1e-9);
    let ratio = |d: Duration| d.as_secs_f64() / reference.as_secs_f64().max(1e-9);
    println!(
        "front end: {} files, {} POUs, {} lines, {:.1} MB (best of {} runs, one core)",
        files.len(),
        modules * 3,
        lines,
        bytes as f64 / 1e6,
        runs
    );
    println!("| phase | time | lines/s | × reference |");
    println!("|---|---|---|---|");
    for (name, d) in [
        ("reference: split into words", reference),
        ("parse", parse),
        ("parse + check", check),
    ] {
        println!(
            "| {name} | {:.1} ms | {:.0} | {:.1} |",
            d.as_secs_f64() * 1e3,
            per_sec(d),
            ratio(d)
        );
    }
    if errors > 0 {
        eprintln!("warning: the generated project has {errors} errors: the figures are not representative");
        std::process::exit(1);
    }
}
