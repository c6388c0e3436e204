//! A plant written in Structured Text: `[plant] program = "plant.st"`.
//!
//! The file holds one PROGRAM (and any functions and function blocks it
//! uses). It is compiled by the same compiler as the controller and run by
//! the interpreter, once per plant step (`[plant] step`, default 10 ms), at
//! the plant's own clock: `TON`s of the plant count plant time.
//!
//! The PROGRAM's variables become the model's interface:
//! - `VAR_INPUT`: actuators, written by the controller (motors, valves);
//! - `VAR_OUTPUT`: sensors, read by the controller (limit switches, levels),
//!   or operator signals when listed in `[plant] operators` (push-buttons a
//!   scenario presses; the plant may read them but never writes them);
//! - every top-level BOOL, number or enumeration variable (inputs, outputs
//!   and `VAR`) is also a quantity, `plant.NAME` in scenarios, traces and
//!   the live view;
//! - a `VAR dt : REAL` (or LREAL) holds the step in seconds at every run.
//!
//! Signals bind to the controller by name like the built-in models' (see
//! [`crate::bind`]); `[bind]` maps a signal to another path or a direct
//! address. Errors point into the plant file or `automat.toml`: E310 the
//! file cannot be read, E311 not exactly one PROGRAM, E312 an unbound
//! VAR_INPUT, E313 (warning) an unbound VAR_OUTPUT, E314 a signal of a type
//! signals cannot have, E315 an unknown operator signal.
//!
//! A fault of the plant program (a division by zero, an endless loop cut
//! by [`STEP_BUDGET`]) freezes the plant and is reported by
//! [`Plant::fault`].

use automat_base::{Code, Diagnostic, FileId, Interner, SourceMap, Span};
use automat_engine::Engine;
use automat_iec::Elementary as E;
use automat_ir::{Program, ProgramInstance};
use automat_lower::{lower, LowerOptions};
use automat_plant::{Dir, Kind, Plant, Quantity, Rng, Signal, Value};
use automat_runtime::{resolve, Place, PlaceType};
use automat_syntax::ast::{Item, PouKind, VarKind};
use std::collections::BTreeSet;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

/// The plant step without `[plant] step`.
pub const DEFAULT_STEP_NS: i64 = 10_000_000;

/// Instructions one plant step may execute: a plant program that loops
/// forever faults deterministically instead of hanging the run. A real
/// plant step runs a few hundred.
pub const STEP_BUDGET: u64 = 10_000_000;

/// `[plant] program = ...` as the project file says it.
#[derive(Clone, Debug, PartialEq)]
pub struct StPlantSpec {
    /// The file, joined to the project folder.
    pub path: PathBuf,
    /// The file as written (the model's name in messages: `plant.st`).
    pub written: String,
    /// The `program` value in `automat.toml`.
    pub span: Span,
    pub step_ns: i64,
    /// `[plant] operators`: VAR_OUTPUTs that are operator signals.
    pub operators: Vec<(String, Span)>,
    /// The compiled program, filled by [`crate::file::load`].
    pub compiled: Option<Arc<Compiled>>,
}

/// One top-level variable of the plant PROGRAM.
#[derive(Clone, Debug, PartialEq)]
pub struct StVar {
    /// As declared.
    pub name: String,
    /// `None` for a `VAR` (a quantity only).
    pub dir: Option<Dir>,
    pub kind: Kind,
    pub place: Place,
    /// The declaration in the plant file (in the caller's source map).
    pub span: Span,
}

/// The checked plant program.
#[derive(Clone, Debug, PartialEq)]
pub struct Compiled {
    pub program: Program,
    pub instance: ProgramInstance,
    pub vars: Vec<StVar>,
    /// Warnings of the compiler, rendered.
    pub warnings: String,
}

impl Compiled {
    /// The declaration of a signal by name (for binding diagnostics).
    pub fn var(&self, name: &str) -> Option<&StVar> {
        self.vars.iter().find(|v| v.name.eq_ignore_ascii_case(name))
    }
}

/// Names as `&'static str` for [`Signal`] and [`Quantity`]: each distinct
/// name is leaked once and shared by every later plant, so a test run
/// building a plant per scenario does not grow memory.
fn intern(name: &str) -> &'static str {
    static NAMES: Mutex<BTreeSet<&'static str>> = Mutex::new(BTreeSet::new());
    let mut names = match NAMES.lock() {
        Ok(g) => g,
        Err(poisoned) => poisoned.into_inner(),
    };
    if let Some(n) = names.get(name) {
        return n;
    }
    let leaked: &'static str = Box::leak(name.to_string().into_boxed_str());
    names.insert(leaked);
    leaked
}

fn kind_of(ty: &PlaceType) -> Option<Kind> {
    match ty {
        PlaceType::Elementary(E::Bool) => Some(Kind::Bool),
        PlaceType::Elementary(e) if e.is_real() => Some(Kind::Real),
        PlaceType::Elementary(e) if e.is_num() || e.is_bit_string() => Some(Kind::Int),
        PlaceType::Enum { .. } => Some(Kind::Int),
        _ => None,
    }
}

/// Points the diagnostics of the private source map (one file, id 0) at
/// the plant file in the caller's map.
fn remap(mut diags: Vec<Diagnostic>, file: FileId) -> Vec<Diagnostic> {
    for d in &mut diags {
        d.span.file = file;
        for l in &mut d.labels {
            l.span.file = file;
        }
    }
    diags
}

/// Reads, compiles and checks the plant program; its text goes into `map`
/// so every diagnostic renders as `plant.st:line:col`.
pub fn compile(spec: &StPlantSpec, map: &mut SourceMap) -> Result<Compiled, Vec<Diagnostic>> {
    let text = std::fs::read_to_string(&spec.path).map_err(|e| {
        vec![Diagnostic::error(
            Code::E310,
            spec.span,
            format!(
                "cannot read the plant program `{}`: {e}",
                spec.path.display()
            ),
        )]
    })?;
    let name = spec.path.display().to_string();
    let file = map.add(name.clone(), text.clone());
    // The compiler checks every file of its map: the plant gets its own.
    let mut own = SourceMap::new();
    own.add(name, text);
    let mut interner = Interner::new();
    let (units, analysis) = automat_dialect::check_sources(&own, &mut interner, &[]);
    if analysis.has_errors() {
        return Err(remap(analysis.diagnostics, file));
    }
    let mut programs = Vec::new();
    for u in &units {
        for item in &u.items {
            match item {
                Item::Pou(p) if p.kind == PouKind::Program => programs.push(p),
                Item::Config(c) => {
                    return Err(remap(
                        vec![Diagnostic::error(
                            Code::E311,
                            c.name.span,
                            "a plant program has no CONFIGURATION: the plant runs its one PROGRAM every plant step",
                        )],
                        file,
                    ))
                }
                _ => {}
            }
        }
    }
    let pou = match programs.as_slice() {
        [one] => *one,
        [] => {
            return Err(vec![Diagnostic::error(
            Code::E311,
            Span::new(file, 0, 0),
            format!("the plant program `{}` has no PROGRAM", spec.written),
        )
        .with_note(
            "a plant is `PROGRAM Name VAR_INPUT (actuators) VAR_OUTPUT (sensors) ... END_PROGRAM`",
        )])
        }
        [first, second, ..] => {
            return Err(remap(
                vec![Diagnostic::error(
                    Code::E311,
                    second.name.span,
                    format!(
                        "the plant program `{}` has a second PROGRAM: the plant is one PROGRAM",
                        spec.written
                    ),
                )
                .with_label(first.name.span, "the first")],
                file,
            ))
        }
    };
    let program = lower(&units, &analysis, &interner, &own, &LowerOptions::default())
        .map_err(|d| remap(d, file))?;
    let prog_name = interner.name(pou.name.sym).to_string();
    let Some(instance) = program
        .tasks
        .first()
        .and_then(|t| t.programs.first())
        .cloned()
    else {
        return Err(vec![Diagnostic::error(
            Code::E311,
            Span::new(file, pou.name.span.start, pou.name.span.end),
            "the plant PROGRAM has no instance to run",
        )]);
    };
    let mut vars = Vec::new();
    let mut errors = Vec::new();
    for block in &pou.var_blocks {
        let dir = match block.kind {
            VarKind::Input => Some(Dir::Actuator),
            VarKind::Output => Some(Dir::Sensor),
            VarKind::Local => None,
            _ => continue,
        };
        for decl in &block.decls {
            for id in &decl.names {
                let var = interner.name(id.sym).to_string();
                let span = Span::new(file, id.span.start, id.span.end);
                let place = resolve(&program, &format!("{prog_name}.{var}")).ok();
                let kind = place.as_ref().and_then(|p| kind_of(&p.ty));
                match (place, kind) {
                    (Some(place), Some(kind)) => {
                        let operator = spec
                            .operators
                            .iter()
                            .any(|(o, _)| o.eq_ignore_ascii_case(&var));
                        let dir = match dir {
                            Some(Dir::Sensor) if operator => Some(Dir::Operator),
                            d => d,
                        };
                        vars.push(StVar {
                            name: var,
                            dir,
                            kind,
                            place,
                            span,
                        });
                    }
                    // A STRING, TIME, array or instance in VAR is the
                    // plant's own business; as a signal it cannot be bound.
                    _ if dir.is_none() => {}
                    _ => errors.push(Diagnostic::error(
                        Code::E314,
                        span,
                        format!(
                            "plant signal `{var}` is no BOOL, integer, bit string, enumeration or real"
                        ),
                    )),
                }
            }
        }
    }
    for (o, span) in &spec.operators {
        let ok = vars
            .iter()
            .any(|v| v.name.eq_ignore_ascii_case(o) && v.dir == Some(Dir::Operator));
        if !ok {
            errors.push(
                Diagnostic::error(
                    Code::E315,
                    *span,
                    format!("operator `{o}` is no VAR_OUTPUT of `{}`", spec.written),
                )
                .with_note(format!(
                    "its VAR_OUTPUTs: {}",
                    vars.iter()
                        .filter(|v| matches!(v.dir, Some(Dir::Sensor | Dir::Operator)))
                        .map(|v| v.name.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                )),
            );
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    let warnings = if analysis.diagnostics.is_empty() {
        String::new()
    } else {
        automat_base::render::render_report(&own, &analysis.diagnostics)
    };
    Ok(Compiled {
        program,
        instance,
        vars,
        warnings,
    })
}

/// The running plant program.
pub struct StPlant {
    name: &'static str,
    compiled: Arc<Compiled>,
    engine: Engine,
    /// Indices into `compiled.vars` of the signals, in `signals` order.
    signal_vars: Vec<usize>,
    signals: Vec<Signal>,
    quantities: Vec<Quantity>,
    step_ns: i64,
    now_ns: i64,
    fault: Option<String>,
    /// A `VAR dt : REAL` (or LREAL), given the step in seconds before
    /// every run so the physics need not repeat `[plant] step`.
    dt: Option<Place>,
    /// The instance run each step (a copy, so a step does not allocate).
    instance: ProgramInstance,
}

impl StPlant {
    pub fn new(spec: &StPlantSpec, compiled: Arc<Compiled>) -> StPlant {
        let mut engine = Engine::new(compiled.program.clone());
        engine.set_budget(STEP_BUDGET);
        let mut signal_vars = Vec::new();
        let mut signals = Vec::new();
        for (i, v) in compiled.vars.iter().enumerate() {
            let Some(dir) = v.dir else { continue };
            signal_vars.push(i);
            signals.push(Signal {
                name: intern(&v.name),
                dir,
                kind: v.kind,
                doc: match dir {
                    Dir::Actuator => "a VAR_INPUT of the plant program",
                    Dir::Sensor => "a VAR_OUTPUT of the plant program",
                    Dir::Operator => "an operator VAR_OUTPUT of the plant program",
                },
            });
        }
        let quantities = compiled
            .vars
            .iter()
            .map(|v| Quantity {
                name: intern(&v.name),
                unit: "",
                doc: "a variable of the plant program",
            })
            .collect();
        let dt = compiled
            .var("dt")
            .filter(|v| v.dir.is_none() && v.kind == Kind::Real)
            .map(|v| v.place.clone());
        StPlant {
            dt,
            instance: compiled.instance.clone(),
            name: intern(&spec.written),
            compiled,
            engine,
            signal_vars,
            signals,
            quantities,
            step_ns: spec.step_ns,
            now_ns: 0,
            fault: None,
        }
    }

    fn signal_var(&self, signal: usize) -> Option<&StVar> {
        self.compiled.vars.get(*self.signal_vars.get(signal)?)
    }

    fn zero(kind: Kind) -> Value {
        match kind {
            Kind::Bool => Value::Bool(false),
            Kind::Int => Value::Int(0),
            Kind::Real => Value::Real(0.0),
        }
    }
}

impl Plant for StPlant {
    fn name(&self) -> &'static str {
        self.name
    }
    fn signals(&self) -> &[Signal] {
        &self.signals
    }
    fn quantities(&self) -> &[Quantity] {
        &self.quantities
    }
    fn step_ns(&self) -> i64 {
        self.step_ns
    }
    fn set(&mut self, signal: usize, value: Value) {
        // Field by field, so the image is written without copying the place
        // (this runs for every actuator at every scan).
        let Some(v) = self
            .signal_vars
            .get(signal)
            .and_then(|&i| self.compiled.vars.get(i))
        else {
            return;
        };
        if v.dir == Some(Dir::Sensor) {
            return;
        }
        crate::image::write(self.engine.image_mut(), &v.place, value);
    }
    fn get(&self, signal: usize) -> Value {
        let Some(v) = self.signal_var(signal) else {
            return Value::Bool(false);
        };
        crate::image::read(self.engine.image(), &v.place).unwrap_or(Self::zero(v.kind))
    }
    fn quantity(&self, index: usize) -> f64 {
        self.compiled
            .vars
            .get(index)
            .and_then(|v| crate::image::read(self.engine.image(), &v.place))
            .map_or(0.0, Value::as_f64)
    }
    fn step(&mut self, dt_ns: i64, _rng: &mut Rng) {
        if self.fault.is_some() {
            return;
        }
        self.now_ns = self.now_ns.saturating_add(dt_ns);
        if let Some(p) = &self.dt {
            crate::image::write(self.engine.image_mut(), p, Value::Real(dt_ns as f64 / 1e9));
        }
        if let Err(f) = self.engine.run_program(&self.instance, self.now_ns) {
            self.fault = Some(format!(
                "the plant program stopped at plant time {} ms: {f}",
                self.now_ns / 1_000_000
            ));
        }
    }
    /// `set NAME=VALUE ...` writes variables of the plant program
    /// (`[plant.params]`, or `plant set capacity=500` in a scenario).
    fn command(&mut self, name: &str, args: &[(&str, f64)]) -> Result<(), String> {
        if !name.eq_ignore_ascii_case("set") {
            return Err(format!(
                "the {} plant has no command `{name}` (it has: set NAME=VALUE)",
                self.name
            ));
        }
        for (key, value) in args {
            let Some(v) = self.compiled.var(key) else {
                return Err(format!(
                    "the {} plant has no variable `{key}` (it has: {})",
                    self.name,
                    self.compiled
                        .vars
                        .iter()
                        .map(|v| v.name.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                ));
            };
            let value = match v.kind {
                Kind::Bool => Value::Bool(*value != 0.0),
                Kind::Int => Value::Int(value.round() as i64),
                Kind::Real => Value::Real(*value),
            };
            let place = v.place.clone();
            crate::image::write(self.engine.image_mut(), &place, value);
        }
        Ok(())
    }
    fn commands(&self) -> &'static [(&'static str, &'static str)] {
        &[("set", "NAME=VALUE: writes a variable of the plant program")]
    }
    fn fault(&self) -> Option<String> {
        self.fault.clone()
    }
}
