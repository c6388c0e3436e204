//! Simulated time per wall second for every example project with its
//! controller: the project's first scenario (`normal.scn` when there is
//! one) run on the virtual clock, best of 3 runs.
//! `cargo bench -p automat --bench plants` prints a Markdown table.

use automat_base::SourceMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

fn scenario_of(dir: &Path) -> Option<PathBuf> {
    let mut list: Vec<PathBuf> = std::fs::read_dir(dir.join("scenarios"))
        .ok()?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "scn"))
        .collect();
    list.sort();
    let normal = list
        .iter()
        .find(|p| p.file_stem().is_some_and(|s| s == "normal"))
        .cloned();
    normal.or_else(|| list.into_iter().next())
}

/// The best wall time of 3 runs of `f`, in seconds (NaN when one fails).
fn best_of(mut f: impl FnMut() -> bool) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..3 {
        let start = Instant::now();
        if !f() {
            return f64::NAN;
        }
        best = best.min(start.elapsed().as_secs_f64());
    }
    best
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(&root)
        .map(|r| r.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    dirs.sort();
    println!("plants: simulated PLC time per wall second, each example with its controller and scenario checks (best of 3, one core)\n");
    println!("| example | scenario | simulated | interpreter | × real time | JIT | × real time | JIT compile (once) |");
    println!("|---|---|---|---|---|---|---|---|");
    for dir in dirs {
        let toml = dir.join("automat.toml");
        let Some(scn_path) = scenario_of(&dir).filter(|_| toml.is_file()) else {
            continue;
        };
        let name = dir
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let mut map = SourceMap::new();
        let Ok(project) = automat_project::load(&toml, &mut map) else {
            println!("| {name} | - | project does not load | | |");
            continue;
        };
        let Ok((program, _)) = automat_project::build::compile(
            &project.sources,
            project.program.clone(),
            &project.libraries,
        ) else {
            println!("| {name} | - | does not compile | | |");
            continue;
        };
        let text = std::fs::read_to_string(&scn_path).unwrap_or_default();
        let file = map.add(scn_path.display().to_string(), text.clone());
        let Ok(scn) = automat_scenario::parse(&text, file, "scenario") else {
            println!("| {name} | - | scenario does not parse | | |");
            continue;
        };
        // Each backend from cold (the JIT's compile time included), best
        // of 3; both run the same scans with the same results.
        let interp = best_of(|| {
            let e = automat_engine::Engine::new(program.clone());
            automat_scenario::run_on::<_, std::io::Sink>(&program, e, &project, &scn, None).is_ok()
        });
        // The JIT's compile time is paid once per load; the run after it
        // is what a long simulation sees.
        let mut compile = f64::INFINITY;
        let jit = best_of(|| {
            let start = Instant::now();
            let Ok(j) = automat_jit::Jit::new(program.clone()) else {
                return false;
            };
            compile = compile.min(start.elapsed().as_secs_f64());
            automat_scenario::run_on::<_, std::io::Sink>(&program, j, &project, &scn, None).is_ok()
        }) - compile;
        let sim = scn.duration_ns as f64 / 1e9;
        let stem = scn_path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        println!(
            "| {name} | {stem} | {sim:.0} s | {:.1} ms | {:.0}× | {:.1} ms | {:.0}× | {:.1} ms |",
            interp * 1e3,
            sim / interp,
            jit * 1e3,
            sim / jit,
            compile * 1e3
        );
    }
}
