//! The example programs of the vendor dialects (`tests/dialect/*/`), each a
//! project folder named after its dialect, compiled with that dialect and
//! run on the virtual clock (10 ms scans): the values after given scans are
//! exact.

use automat_base::{render, Interner, SourceMap};
use automat_dialect::Dialect;
use automat_engine::Engine;
use automat_lower::{lower, LowerOptions};
use automat_runtime::io::NoIo;
use automat_runtime::scan::Env;
use automat_runtime::{resolve, run, value, ClockMode, Limit, RunConfig, SystemClock};
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

fn example(name: &str) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/dialect")
        .join(name);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "st"))
        .collect();
    files.sort();
    files
}

/// Compiles the files of a project with a dialect (it must check clean).
fn compile(files: &[(String, String)], dialect: Dialect) -> automat_ir::Program {
    let mut map = SourceMap::new();
    for (name, text) in files {
        map.add(name.clone(), text.clone());
    }
    automat_dialect::add_libraries(&mut map, &[dialect]);
    let mut interner = Interner::new();
    let (units, analysis) = automat_dialect::check_sources(&map, &mut interner, &[dialect]);
    assert!(
        analysis.diagnostics.is_empty(),
        "the project should check clean:\n{}",
        render::render_report(&map, &analysis.diagnostics)
    );
    lower(
        &units,
        &analysis,
        &interner,
        &map,
        &LowerOptions { program: None },
    )
    .unwrap_or_else(|d| panic!("{}", render::render_report(&map, &d)))
}

/// Runs `cycles` scans of 10 ms on the virtual clock from PLC time 0.
fn scans(engine: &mut Engine, cycles: u64) {
    let cfg = RunConfig {
        cycle_time_ns: 10_000_000,
        clock: ClockMode::Virtual,
        limit: Limit::Cycles(cycles),
    };
    let stop = AtomicBool::new(false);
    let (mut inputs, mut outputs) = (NoIo, NoIo);
    let mut observer = ();
    let mut env = Env {
        clock: &mut SystemClock::new(),
        inputs: &mut inputs,
        outputs: &mut outputs,
        observer: &mut observer,
        stop: &stop,
    };
    run(engine, &cfg, &mut env).unwrap_or_else(|e| panic!("{e}"));
}

fn values(engine: &Engine, paths: &[&str]) -> Vec<String> {
    paths
        .iter()
        .map(|p| {
            let place = resolve(engine.program(), p).unwrap_or_else(|e| panic!("{p}: {e}"));
            value::format(engine.image(), &place)
        })
        .collect()
}

/// Runs the example for `cycles` scans; the printed values of `paths`.
fn run_example(name: &str, dialect: Dialect, cycles: u64, paths: &[&str]) -> Vec<String> {
    let files: Vec<(String, String)> = example(name)
        .iter()
        .map(|f| {
            let text =
                std::fs::read_to_string(f).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
            (f.display().to_string(), text)
        })
        .collect();
    let mut engine = Engine::new(compile(&files, dialect));
    scans(&mut engine, cycles);
    values(&engine, paths)
}

#[test]
fn isagraf_mixer() {
    let paths = [
        "level",
        "Batch.GS3.x",
        "Batch.GS1.x",
        "agitator",
        "Agitator.GS11.x",
        "mix_time",
        "batches",
    ];
    let at = |cycles| run_example("isagraf_mixer", Dialect::Isagraf, cycles, &paths);
    // Filled to 80 % in scan 14; GS3 starts the child and the timer.
    assert_eq!(
        at(15),
        ["90.0", "TRUE", "FALSE", "TRUE", "FALSE", "T#0s", "0"]
    );
    // The child rests after 100 ms of agitation, then agitates again.
    assert_eq!(
        at(25),
        ["90.0", "TRUE", "FALSE", "FALSE", "TRUE", "T#100ms", "0"]
    );
    assert_eq!(
        at(28),
        ["90.0", "TRUE", "FALSE", "TRUE", "FALSE", "T#130ms", "0"]
    );
    // 200 ms of mixing: GS4 drains, the child is killed, the batch counted.
    assert_eq!(
        at(36),
        ["90.0", "FALSE", "FALSE", "FALSE", "FALSE", "T#210ms", "1"]
    );
    assert_eq!(
        at(45),
        ["0.0", "FALSE", "TRUE", "FALSE", "FALSE", "T#210ms", "1"]
    );
}

#[test]
fn pl7_drill() {
    let paths = [
        "pos",
        "Chart._X0.X",
        "Chart._X1.X",
        "Chart._X2.X",
        "Chart._X3.X",
        "down_cmd",
        "up_cmd",
        "spindle",
        "holes",
        "lamp",
    ];
    let at = |cycles| run_example("pl7_drill", Dialect::Pl7, cycles, &paths);
    let row = |s: &str| s.split(' ').map(str::to_string).collect::<Vec<_>>();
    // The part arrives in scan 3: %X1's P1 starts the spindle, N1 lowers.
    assert_eq!(
        at(4),
        row("0 FALSE TRUE FALSE FALSE TRUE FALSE TRUE 0 TRUE")
    );
    // Down at 100 % in scan 8: %X2 dwells; %X1's P0 stopped the feed.
    assert_eq!(
        at(9),
        row("100 FALSE FALSE TRUE FALSE FALSE FALSE TRUE 0 TRUE")
    );
    // 50 ms later %X3 raises the drill.
    assert_eq!(
        at(14),
        row("100 FALSE FALSE FALSE TRUE FALSE TRUE TRUE 0 TRUE")
    );
    // Up in scan 16; %X3's P0 counts the hole; the next part is drilled.
    assert_eq!(
        at(17),
        row("0 FALSE TRUE FALSE FALSE FALSE FALSE FALSE 1 TRUE")
    );
    // PRL sets %S21 in scan 30: the chart is back in %X0 at its end.
    assert_eq!(
        at(30),
        row("0 TRUE FALSE FALSE FALSE FALSE TRUE TRUE 1 FALSE")
    );
    assert_eq!(
        at(31),
        row("0 FALSE TRUE FALSE FALSE FALSE FALSE FALSE 2 TRUE")
    );
}

/// PL7 %S20 / %S1: the first cycle after a cold start, then after a warm
/// start (RETAIN values restored from a file, as `automat run --retain`).
#[test]
fn pl7_cold_and_warm_start() {
    let text = "PROGRAM Main
VAR
    cold_seen, warm_seen : INT;
END_VAR
    IF %S20 THEN
        cold_seen := cold_seen + 1;
    END_IF;
    IF %S1 THEN
        warm_seen := warm_seen + 1;
    END_IF;
END_PROGRAM
";
    let program = compile(&[("start.st".into(), text.into())], Dialect::Pl7);
    let paths = ["_S20", "_S1", "Main.cold_seen", "Main.warm_seen"];
    // Each `scans` call is a new run from PLC time 0: one engine per check.
    let cold = |cycles| {
        let mut e = Engine::new(program.clone());
        scans(&mut e, cycles);
        e
    };
    assert_eq!(values(&cold(1), &paths), ["TRUE", "FALSE", "1", "0"]);
    let ran = cold(3);
    assert_eq!(values(&ran, &paths), ["FALSE", "FALSE", "1", "0"]);
    let file = std::env::temp_dir().join(format!("automat-pl7-{}.retain", std::process::id()));
    automat_runtime::retain::save(&program, &file, ran.image()).unwrap_or_else(|e| panic!("{e}"));
    let warm = |cycles| {
        let mut e = Engine::new(program.clone());
        let loaded = automat_runtime::retain::load(&program, &file, e.image_mut());
        assert!(matches!(loaded, automat_runtime::retain::Loaded::Warm));
        scans(&mut e, cycles);
        e
    };
    let (one, three) = (warm(1), warm(3));
    let _ = std::fs::remove_file(&file);
    assert_eq!(values(&one, &paths), ["FALSE", "TRUE", "0", "1"]);
    assert_eq!(values(&three, &paths), ["FALSE", "FALSE", "0", "1"]);
}
