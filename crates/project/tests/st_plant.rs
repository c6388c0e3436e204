//! Plants written in ST (`[plant] program = "plant.st"`): the interface
//! their PROGRAM gives, their clock, and the errors E310–E315 at their
//! places.

use automat_base::{render, SourceMap};
use automat_plant::{Dir, Kind, Rng, Value};
use automat_project::{bind, build, load, Project, Sim};
use std::path::{Path, PathBuf};

const CONTROLLER: &str = "PROGRAM Ctrl
VAR
    motor AT %QX0.0 : BOOL;
    speed : INT;
    at_end AT %IX0.0 : BOOL;
    pos : REAL;
    Button : BOOL;
END_VAR
motor := Button;
END_PROGRAM
";

/// A plant whose figures are exact: it counts its runs, integrates `dt`
/// while the motor runs, and has a TON on the plant's clock.
const PLANT: &str = "PROGRAM Belt
VAR_INPUT
    motor : BOOL;
    speed : INT;
END_VAR
VAR_OUTPUT
    at_end : BOOL;
    pos : REAL;
    Button : BOOL;
END_VAR
VAR
    dt : LREAL;
    runs : DINT;
    moved : LREAL;
    t : TON;
    label : STRING;
END_VAR
runs := runs + 1;
IF motor THEN
    moved := moved + dt;
END_IF;
pos := LREAL_TO_REAL(moved) * INT_TO_REAL(speed);
t(IN := motor, PT := T#500ms);
at_end := t.Q;
END_PROGRAM
";

/// A project folder `automat.toml`, `ctrl.st` and `plant.st` (each `None`
/// leaves the file out).
fn folder(tag: &str, toml_plant: &str, plant: Option<&str>, ctrl: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("automat-stplant-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    std::fs::write(
        dir.join("automat.toml"),
        format!("[project]\nname = \"p\"\n\n[plant]\n{toml_plant}"),
    )
    .expect("toml");
    std::fs::write(dir.join("ctrl.st"), ctrl).expect("controller");
    if let Some(p) = plant {
        std::fs::write(dir.join("plant.st"), p).expect("plant");
    }
    dir
}

fn open(dir: &Path) -> (Result<Project, String>, SourceMap) {
    let mut map = SourceMap::new();
    let r = load(&dir.join("automat.toml"), &mut map).map_err(|d| render::render_report(&map, &d));
    (r, map)
}

/// The rendered errors of loading, binding included.
fn errors(tag: &str, toml_plant: &str, plant: Option<&str>, ctrl: &str) -> String {
    let dir = folder(tag, toml_plant, plant, ctrl);
    let (p, map) = open(&dir);
    let text = match p {
        Err(e) => e,
        Ok(p) => {
            let plant = p.new_plant().expect("plant").expect("some plant");
            let (program, _) = build::compile(&p.sources, None, &[]).expect("controller compiles");
            let spec = p.plant.as_ref().expect("spec");
            let (_, diags) = bind(spec, plant.as_ref(), &program);
            render::render_report(&map, &diags)
        }
    };
    // Paths differ per machine: keep them relative to the folder.
    text.replace(&format!("{}/", dir.display()), "")
}

#[test]
fn the_program_gives_signals_quantities_and_runs_on_the_plant_clock() {
    let dir = folder(
        "run",
        "program = \"plant.st\"\nstep = \"10ms\"\noperators = [\"Button\"]\n\n[plant.params]\nspeed = 3\n",
        Some(PLANT),
        CONTROLLER,
    );
    let (p, _) = open(&dir);
    let p = p.expect("loads");
    // plant.st is no source of the controller, though it lies beside it.
    assert_eq!(p.sources, [dir.join("ctrl.st")]);
    let mut plant = p.new_plant().expect("builds").expect("a plant");
    assert_eq!(plant.name(), "plant.st");
    assert_eq!(plant.step_ns(), 10_000_000);
    let sigs: Vec<(&str, Dir, Kind)> = plant
        .signals()
        .iter()
        .map(|s| (s.name, s.dir, s.kind))
        .collect();
    assert_eq!(
        sigs,
        [
            ("motor", Dir::Actuator, Kind::Bool),
            ("speed", Dir::Actuator, Kind::Int),
            ("at_end", Dir::Sensor, Kind::Bool),
            ("pos", Dir::Sensor, Kind::Real),
            ("Button", Dir::Operator, Kind::Bool),
        ]
    );
    let qs: Vec<&str> = plant.quantities().iter().map(|q| q.name).collect();
    // the STRING and the TON are no quantities
    assert_eq!(
        qs,
        ["motor", "speed", "at_end", "pos", "Button", "dt", "runs", "moved"]
    );
    // [plant.params] set the variable
    assert_eq!(plant.get(1), Value::Int(3));
    let mut rng = Rng::new(1);
    plant.set(0, Value::Bool(true));
    // a sensor cannot be set from outside
    plant.set(2, Value::Bool(true));
    assert_eq!(plant.get(2), Value::Bool(false));
    for _ in 0..50 {
        plant.step(10_000_000, &mut rng);
    }
    assert_eq!(plant.quantity(6), 50.0);
    // The TON saw the motor first at the run at 10 ms of plant time: its
    // 500 ms end with the run at 510 ms.
    assert_eq!(plant.get(2), Value::Bool(false), "TON at 500 ms");
    // dt = 0.01 s per run: 50 runs moved 0.5 s, pos = 0.5 * 3
    assert!((plant.quantity(7) - 0.5).abs() < 1e-12);
    assert_eq!(plant.get(3), Value::Real(1.5));
    assert_eq!(plant.quantity(5), 0.01);
    plant.step(10_000_000, &mut rng);
    assert_eq!(
        plant.get(2),
        Value::Bool(true),
        "TON at 510 ms of plant time"
    );
    assert_eq!(
        plant.command("set", &[("speed", 2.0)]),
        Ok(()),
        "a scenario's `plant set`"
    );
    assert_eq!(plant.get(1), Value::Int(2));
    assert_eq!(
        plant.command("set", &[("nope", 2.0)]),
        Err("the plant.st plant has no variable `nope` (it has: motor, speed, at_end, pos, Button, dt, runs, moved)".into())
    );
    assert_eq!(plant.fault(), None);
}

#[test]
fn bound_to_the_controller_through_the_scan_coupling() {
    let dir = folder(
        "sim",
        "program = \"plant.st\"\nstep = \"5ms\"\noperators = [\"Button\"]\n\n[plant.params]\nspeed = 1\n",
        Some(PLANT),
        CONTROLLER,
    );
    let (p, _) = open(&dir);
    let p = p.expect("loads");
    let plant = p.new_plant().expect("builds").expect("a plant");
    let (program, _) = build::compile(&p.sources, None, &[]).expect("compiles");
    let spec = p.plant.as_ref().expect("spec");
    let (bindings, diags) = bind(spec, plant.as_ref(), &program);
    assert_eq!(diags, []);
    let bindings = bindings.expect("bound");
    let paths: Vec<&str> = bindings.iter().map(|b| b.path.as_str()).collect();
    assert_eq!(paths, ["motor", "speed", "at_end", "pos", "Button"]);
    let mut sim = Sim::new(plant, bindings, 1);
    let mut image = program.initial_image.clone();
    image.resize(program.image_size as usize, 0);
    let motor = automat_runtime::resolve(&program, "Ctrl.motor").expect("motor");
    automat_project::image::write(&mut image, &motor, Value::Bool(true));
    // an actuator comes from the controller, whatever [plant.params] said
    let speed = automat_runtime::resolve(&program, "Ctrl.speed").expect("speed");
    automat_project::image::write(&mut image, &speed, Value::Int(2));
    // 1 s of PLC time at a 5 ms plant step: 200 runs of the plant
    sim.sync(1_000_000_000, &mut image);
    assert_eq!(sim.plant().quantity(6), 200.0);
    let at_end = automat_runtime::resolve(&program, "Ctrl.at_end").expect("at_end");
    let pos = automat_runtime::resolve(&program, "Ctrl.pos").expect("pos");
    assert_eq!(
        automat_project::image::read(&image, &at_end),
        Some(Value::Bool(true))
    );
    let Some(Value::Real(pos)) = automat_project::image::read(&image, &pos) else {
        panic!("pos is REAL");
    };
    assert!((pos - 2.0).abs() < 1e-6, "{pos}");
}

#[test]
fn a_fault_freezes_the_plant_and_says_where() {
    let plant = "PROGRAM P\nVAR_OUTPUT at_end : BOOL; END_VAR\nVAR n : INT; z : INT; END_VAR\nn := n + 1;\nIF n = 3 THEN n := n / z; END_IF;\nEND_PROGRAM\n";
    let dir = folder("fault", "program = \"plant.st\"\n", Some(plant), CONTROLLER);
    let (p, _) = open(&dir);
    let mut plant = p.expect("loads").new_plant().expect("b").expect("p");
    let mut rng = Rng::new(1);
    for _ in 0..5 {
        plant.step(10_000_000, &mut rng);
    }
    let why = plant
        .fault()
        .expect("faulted")
        .replace(&format!("{}/", dir.display()), "");
    assert!(
        why.starts_with("the plant program stopped at plant time 30 ms: plant.st:5:"),
        "{why}"
    );
    assert!(why.contains("division by zero"), "{why}");
    assert_eq!(plant.quantity(1), 3.0, "frozen at the third run");
}

#[test]
fn e310_the_file_cannot_be_read() {
    let e = errors("e310", "program = \"missing.st\"\n", None, CONTROLLER);
    assert!(
        e.starts_with("automat.toml:5:11: error[E310]: cannot read the plant program `"),
        "{e}"
    );
}

#[test]
fn e311_one_program_no_configuration() {
    let e = errors(
        "e311a",
        "program = \"plant.st\"\n",
        Some("FUNCTION F : INT F := 1; END_FUNCTION\n"),
        CONTROLLER,
    );
    assert!(
        e.starts_with("plant.st:1:1: error[E311]: the plant program `plant.st` has no PROGRAM"),
        "{e}"
    );
    let e = errors(
        "e311b",
        "program = \"plant.st\"\n",
        Some("PROGRAM A END_PROGRAM\nPROGRAM B END_PROGRAM\n"),
        CONTROLLER,
    );
    assert!(
        e.starts_with(
            "plant.st:2:9: error[E311]: the plant program `plant.st` has a second PROGRAM"
        ),
        "{e}"
    );
    let e = errors(
        "e311c",
        "program = \"plant.st\"\n",
        Some("PROGRAM A END_PROGRAM\nCONFIGURATION C RESOURCE R ON PLC PROGRAM I : A; END_RESOURCE END_CONFIGURATION\n"),
        CONTROLLER,
    );
    assert!(
        e.starts_with("plant.st:2:15: error[E311]: a plant program has no CONFIGURATION"),
        "{e}"
    );
}

#[test]
fn compile_errors_of_the_plant_point_into_its_file() {
    let e = errors(
        "sema",
        "program = \"plant.st\"\n",
        Some("PROGRAM P\nVAR_OUTPUT x : BOOL; END_VAR\nx := nothing;\nEND_PROGRAM\n"),
        CONTROLLER,
    );
    assert!(e.starts_with("plant.st:3:6: error[E"), "{e}");
}

#[test]
fn e312_e313_unbound_signals_at_their_declaration() {
    let plant = "PROGRAM P\nVAR_INPUT\n    valve : BOOL;\nEND_VAR\nVAR_OUTPUT\n    float : BOOL;\nEND_VAR\nEND_PROGRAM\n";
    let e = errors("e312", "program = \"plant.st\"\n", Some(plant), CONTROLLER);
    assert!(
        e.starts_with("plant.st:3:5: error[E312]: VAR_INPUT `valve` of the plant program `plant.st` is bound to nothing"),
        "{e}"
    );
    assert!(
        e.contains("plant.st:6:5: warning[E313]: VAR_OUTPUT `float` of the plant program `plant.st` is bound to nothing"),
        "{e}"
    );
    // a [bind] entry binds it elsewhere
    let e = errors(
        "e312bind",
        "program = \"plant.st\"\n\n[bind]\nvalve = \"%QX0.0\"\nfloat = \"at_end\"\n",
        Some(plant),
        CONTROLLER,
    );
    assert_eq!(e, "");
}

#[test]
fn e314_e315_signal_types_and_operators() {
    let plant =
        "PROGRAM P\nVAR_OUTPUT\n    msg : STRING;\n    at_end : BOOL;\nEND_VAR\nEND_PROGRAM\n";
    let e = errors(
        "e314",
        "program = \"plant.st\"\noperators = [\"at_end\", \"Knob\"]\n",
        Some(plant),
        CONTROLLER,
    );
    assert!(
        e.starts_with("plant.st:3:5: error[E314]: plant signal `msg` is no BOOL, integer, bit string, enumeration or real"),
        "{e}"
    );
    assert!(
        e.contains(
            "automat.toml:6:24: error[E315]: operator `Knob` is no VAR_OUTPUT of `plant.st`"
        ),
        "{e}"
    );
}

#[test]
fn model_or_program_exactly_one() {
    let e = errors(
        "both",
        "model = \"crane\"\nprogram = \"plant.st\"\n",
        Some(PLANT),
        CONTROLLER,
    );
    assert!(
        e.starts_with("automat.toml:5:9: error[E300]: [plant] has both `model` and `program`"),
        "{e}"
    );
    let e = errors("neither", "seed = 3\n", None, CONTROLLER);
    assert!(
        e.starts_with(
            "automat.toml:1:1: error[E300]: [plant] needs `model` (a built-in model) or `program`"
        ),
        "{e}"
    );
    let e = errors(
        "step",
        "model = \"crane\"\nstep = \"5ms\"\n",
        None,
        CONTROLLER,
    );
    assert!(
        e.starts_with("automat.toml:6:8: error[E300]: [plant] `step` is for a plant written in ST"),
        "{e}"
    );
    let e = errors(
        "step0",
        "program = \"plant.st\"\nstep = \"0s\"\n",
        Some(PLANT),
        CONTROLLER,
    );
    assert!(
        e.starts_with("automat.toml:6:8: error[E300]: [plant] step must be longer than 0"),
        "{e}"
    );
}
