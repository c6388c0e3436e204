//! Sessions over small programs and the example projects, on the
//! interpreter and the virtual clock, stopped until a test steps them.

#![allow(dead_code)]

use automat_base::SourceMap;
use automat_engine::Engine;
use automat_project::{bind, build, Sim};
use automat_runtime::{ClockMode, SystemClock};
use automat_session::{Config, Control, Parts, Session};
use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

pub fn config() -> Config {
    Config {
        cycle_time_ns: 10_000_000,
        clock: ClockMode::Virtual,
        monotonic: Box::new(SystemClock::new()),
        running: false,
        stop: Arc::new(AtomicBool::new(false)),
        retain: None,
        safe: None,
        realtime: None,
        wait_after_fault: true,
    }
}

/// A session over one ST source text (no plant).
pub fn source(text: &str) -> Session {
    source_with(text, config())
}

/// A folder of its own for one test's files.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("automat-session-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// [`source`] with the caller's configuration.
pub fn source_with(text: &str, config: Config) -> Session {
    source_file("main.st", text, config)
}

/// A session over one source file named `name` (`main.st`, `main.slc`).
pub fn source_file(name: &str, text: &str, config: Config) -> Session {
    // One folder per call: tests run in parallel, several on one text.
    static NEXT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("automat-session-{}-{n}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let file = dir.join(name);
    std::fs::write(&file, text).expect("write source");
    let (program, _) = build::compile(&[file], None, &[]).unwrap_or_else(|e| panic!("{}", e.text));
    let program = Arc::new(program);
    let p = (*program).clone();
    Session::start(
        program,
        config,
        Box::new(move || {
            Ok(Parts {
                exec: Box::new(Engine::new(p)),
                sim: None,
                observer: None,
                exchange: None,
            })
        }),
    )
    .expect("session")
}

pub fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
}

/// A session over an example project with its plant.
pub fn project(name: &str) -> Session {
    let toml = example(name).join("automat.toml");
    let mut map = SourceMap::new();
    let project = automat_project::load(&toml, &mut map).expect("project");
    let (program, _) = build::compile(
        &project.sources,
        project.program.clone(),
        &project.libraries,
    )
    .unwrap_or_else(|e| panic!("{}", e.text));
    let cycle = project.cycle_time_ns;
    let program = Arc::new(program);
    let p = (*program).clone();
    let mut cfg = config();
    cfg.cycle_time_ns = cycle;
    Session::start(
        program,
        cfg,
        Box::new(move || {
            let plant = project
                .new_plant()
                .map_err(|_| "plant".to_string())?
                .ok_or("no plant")?;
            let spec = project.plant.clone().ok_or("no plant")?;
            let (bindings, _) = bind(&spec, plant.as_ref(), &p);
            let bindings = bindings.ok_or("bindings")?;
            let sim = Sim::new(plant, bindings, spec.seed);
            Ok(Parts {
                exec: Box::new(Engine::new(p)),
                sim: Some(Rc::new(RefCell::new(sim))),
                observer: None,
                exchange: None,
            })
        }),
    )
    .expect("session")
}

/// The value of one path now.
pub fn get(s: &Session, path: &str) -> String {
    s.read(&[path.to_string()]).expect("read")[0].1.clone()
}

pub fn step(s: &Session, n: u64) {
    s.control(Control::Step(n)).expect("step");
}

/// Steps one scan at a time, collecting the value of `path` after each.
pub fn series(s: &Session, path: &str, scans: usize) -> Vec<String> {
    (0..scans)
        .map(|_| {
            step(s, 1);
            get(s, path)
        })
        .collect()
}
