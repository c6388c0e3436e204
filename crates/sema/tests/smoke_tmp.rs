use automat_base::{render, Interner, SourceMap};
use std::path::Path;

fn files_of(p: &Path) -> Vec<std::path::PathBuf> {
    if p.is_dir() {
        let mut v: Vec<_> = std::fs::read_dir(p)
            .unwrap()
            .map(|e| e.unwrap().path())
            .collect();
        v.sort();
        v.into_iter().flat_map(|x| files_of(&x)).collect()
    } else if p.extension().is_some_and(|e| e == "st") {
        vec![p.to_path_buf()]
    } else {
        vec![]
    }
}

fn expected(map: &SourceMap) -> Vec<(String, u32, String)> {
    let mut out = vec![];
    for (_, f) in map.files() {
        for (i, line) in f.text.lines().enumerate() {
            if let Some(pos) = line.find("//~") {
                for c in line[pos + 3..].split_whitespace() {
                    if c.starts_with('E') || c.starts_with('W') {
                        out.push((f.name.clone(), i as u32 + 1, c.to_string()));
                    }
                }
            }
        }
    }
    out.sort();
    out
}

fn run(p: &Path) -> bool {
    let mut map = SourceMap::new();
    for f in files_of(p) {
        let bytes = std::fs::read(&f).unwrap();
        let text: String = match String::from_utf8(bytes.clone()) {
            Ok(s) => s,
            Err(_) => bytes.iter().map(|&b| b as char).collect(),
        };
        map.add(f.display().to_string(), text);
    }
    let mut interner = Interner::new();
    let (_u, a) = automat_sema::check_sources(&map, &mut interner);
    let mut got: Vec<(String, u32, String)> = a
        .diagnostics
        .iter()
        .map(|d| {
            let f = map.get(d.span.file);
            (
                f.name.clone(),
                f.line_col(d.span.start).0,
                d.code.as_str().to_string(),
            )
        })
        .collect();
    got.sort();
    let want = expected(&map);
    if got != want {
        println!("==== {}", p.display());
        for w in &want {
            if !got.contains(w) {
                println!("  missing {} line {}", w.2, w.1);
            }
        }
        for d in &a.diagnostics {
            let f = map.get(d.span.file);
            let k = (
                f.name.clone(),
                f.line_col(d.span.start).0,
                d.code.as_str().to_string(),
            );
            if !want.contains(&k) {
                print!("  extra {}", render::render_human(&map, d));
            }
        }
        return false;
    }
    true
}

#[test]
fn corpus_tmp() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/corpus");
    let only = std::env::var("ONLY").unwrap_or_default();
    let mut bad = 0;
    let mut n = 0;
    for sub in ["valid", "invalid"] {
        let mut entries: Vec<_> = std::fs::read_dir(root.join(sub))
            .unwrap()
            .map(|e| e.unwrap().path())
            .collect();
        entries.sort();
        for e in entries {
            if !only.is_empty() && !e.display().to_string().contains(&only) {
                continue;
            }
            n += 1;
            if !run(&e) {
                bad += 1;
            }
        }
    }
    if only.is_empty() || "library".contains(&only) {
        n += 1;
        if !run(&root.join("library")) {
            bad += 1;
        }
    }
    println!("{bad} of {n} failed");
}

#[path = "../../cli/benches/gen.rs"]
mod gen;

#[test]
#[ignore]
fn timing_tmp() {
    let files = gen::project(400);
    let lines = gen::line_count(&files);
    let mut interner = Interner::new();
    let units: Vec<_> = files.iter().enumerate().map(|(i, (_, t))| automat_syntax::parse(automat_base::FileId(i as u32), t, &mut interner).unit).collect();
    let mut best = f64::MAX;
    for _ in 0..20 {
        let t = std::time::Instant::now();
        let a = automat_sema::check(&units, &mut interner);
        let d = t.elapsed().as_secs_f64();
        assert!(a.diagnostics.is_empty());
        drop(a);
        best = best.min(d);
    }
    println!("check only: {:.1} ms, {:.0} lines/s", best * 1e3, lines as f64 / best);
}

#[test]
#[ignore]
fn timing_breakdown_tmp() {
    let files = gen::project(400);
    let mut map = SourceMap::new();
    for (n, t) in &files { map.add(n.clone(), t.clone()); }
    for _ in 0..5 {
        let t0 = std::time::Instant::now();
        let mut interner = Interner::new();
        let units: Vec<_> = map.files().map(|(id, f)| automat_syntax::parse(id, &f.text, &mut interner).unit).collect();
        let t1 = std::time::Instant::now();
        let a = automat_sema::check(&units, &mut interner);
        let t2 = std::time::Instant::now();
        drop(a);
        let t3 = std::time::Instant::now();
        drop(units);
        let t4 = std::time::Instant::now();
        drop(interner);
        let t5 = std::time::Instant::now();
        println!("parse {:.1} check {:.1} drop-model {:.1} drop-ast {:.1} drop-interner {:.1}",
            (t1-t0).as_secs_f64()*1e3, (t2-t1).as_secs_f64()*1e3, (t3-t2).as_secs_f64()*1e3, (t4-t3).as_secs_f64()*1e3, (t5-t4).as_secs_f64()*1e3);
    }
}

#[test]
fn sizes_tmp() {
    use automat_sema::*;
    println!("Var {} Typed {} Value {} Init {} TypeKind {} Pou {} DirectAddress {}",
        std::mem::size_of::<model::Var>(), std::mem::size_of::<Typed>(), std::mem::size_of::<value::Value>(),
        std::mem::size_of::<value::Init>(), std::mem::size_of::<types::TypeKind>(), std::mem::size_of::<model::Pou>(),
        std::mem::size_of::<automat_syntax::ast::DirectAddress>());
}
