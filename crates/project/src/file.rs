//! `automat.toml`: reading the project file into a [`Project`].
//!
//! Every error is a [`Diagnostic`] whose span points into the project file
//! (added to the caller's [`SourceMap`]), so it renders as
//! `examples/crane/automat.toml:7:9: error[E301]: ...`.
//!
//! Sources: the `sources` list (files or folders, relative to the project
//! file; folders searched recursively for `*.st`), or by default every
//! `*.st` file directly beside `automat.toml` (not in sub-folders, so a
//! folder of variants or scenarios is never compiled by accident).
//!
//! `[retain]`: `file` (relative to the project folder; `automat run
//! --retain` wins), `save_every` (a duration: the RETAIN variables are also
//! saved that often while running; `"0s"`: only at stop; default 10 s),
//! `optional` (a RETAIN path that fails
//! the start-up check is a warning, not an error). `[safe_state]`: the safe
//! value of an output whose safe value is not 0/FALSE, by variable path,
//! direct address or actuator signal name: `"Ctrl.valve_nc" = true`,
//! `"%QW2" = 100` (dotted keys unquoted, `Ctrl.valve_nc = true`, mean the
//! same); values are booleans, numbers or IEC literals in a string
//! (`"T#5s"`, `"Mode#Hand"`).

use crate::folder::{Entry, Walk};
use automat_base::{Code, Diagnostic, FileId, SourceMap, Span};
use automat_plant::{models, Plant};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use toml::Spanned;

use crate::tasks::TaskSpec;
use automat_ir::TaskWatchdog;

/// The project file's name.
pub const FILE_NAME: &str = "automat.toml";

/// Default period of the cyclic task without a CONFIGURATION.
pub const DEFAULT_CYCLE_NS: i64 = 10_000_000;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    project: RawProject,
    plant: Option<RawPlant>,
    #[serde(default)]
    bind: BTreeMap<Spanned<String>, Spanned<String>>,
    retain: Option<RawRetain>,
    #[serde(default)]
    safe_state: BTreeMap<Spanned<String>, toml::Value>,
    #[serde(default)]
    users: BTreeMap<String, RawUser>,
    #[serde(default)]
    tasks: BTreeMap<Spanned<String>, RawTask>,
    runtime: Option<RawRuntime>,
    codesys: Option<RawCodesys>,
    /// `[modbus]`: read and checked by `automat-fieldbus` from the same
    /// text (it needs the compiled program).
    #[serde(default)]
    #[allow(dead_code)]
    modbus: Option<serde::de::IgnoredAny>,
    /// `[opcua]`: read and checked by `automat-opcua` from the same text.
    #[serde(default)]
    #[allow(dead_code)]
    opcua: Option<serde::de::IgnoredAny>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRuntime {
    #[serde(default)]
    realtime: bool,
    priority: Option<Spanned<i64>>,
    cpus: Option<Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTask {
    watchdog: Option<Spanned<String>>,
    sensitivity: Option<Spanned<i64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRetain {
    file: Option<Spanned<String>>,
    save_every: Option<Spanned<String>>,
    #[serde(default)]
    optional: bool,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawUser {
    role: Spanned<String>,
    password: String,
}

/// One `[users.NAME]` table: who may use the network API (`automat run
/// --listen`), with which role, and the argon2id hash of the password
/// (made by `automat passwd`; checked by the server, never printed).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UserSpec {
    pub name: String,
    /// `viewer`, `operator` or `engineer`.
    pub role: String,
    pub password_hash: String,
}

/// The roles of the network API, least rights first.
pub const ROLES: [&str; 3] = ["viewer", "operator", "engineer"];

/// `[codesys]`: settings of the CODESYS dialect.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCodesys {
    /// The heap of `__NEW`/`__DELETE` (`"256KiB"`).
    heap: Option<Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawProject {
    name: String,
    #[serde(default)]
    description: String,
    sources: Option<Vec<Spanned<String>>>,
    program: Option<String>,
    cycle_time: Option<Spanned<String>>,
    #[serde(default)]
    libraries: Vec<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPlant {
    model: Option<Spanned<String>>,
    /// A plant written in ST (`crate::st_plant`), instead of `model`.
    program: Option<Spanned<String>>,
    step: Option<Spanned<String>>,
    #[serde(default)]
    operators: Vec<Spanned<String>>,
    seed: Option<u64>,
    #[serde(default)]
    params: BTreeMap<Spanned<String>, Spanned<f64>>,
}

/// One `[bind]` entry: `signal = "target"`.
#[derive(Clone, Debug, PartialEq)]
pub struct BindSpec {
    pub signal: String,
    pub signal_span: Span,
    /// A variable path (`Ctrl.M1S`) or a direct address (`%QX3.1`).
    pub target: String,
    pub target_span: Span,
}

/// The `[plant]` table.
#[derive(Clone, Debug, PartialEq)]
pub struct PlantSpec {
    /// A built-in model's name, or for a plant in ST the file as written.
    pub model: String,
    /// `model = ...` (or `program = ...`) in the project file.
    pub model_span: Span,
    /// `program = "plant.st"`: the plant is that PROGRAM.
    pub program: Option<crate::st_plant::StPlantSpec>,
    pub seed: u64,
    /// `[plant.params]`, applied as `command("set", [(key, value)])`.
    pub params: Vec<(String, f64, Span)>,
    pub bind: Vec<BindSpec>,
}

/// The `[retain]` table.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct RetainSpec {
    /// The RETAIN file, relative paths already joined to the project folder.
    pub file: Option<PathBuf>,
    /// `save_every`: the period of saves while running, in PLC time (0:
    /// only at stop; `None`: the runner's default).
    pub save_every_ns: Option<i64>,
    /// `optional = true`: a failed start-up check of the path is a warning.
    pub optional: bool,
}

/// `[runtime]` of `automat.toml`.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct RuntimeSpec {
    /// `realtime = true`: every real-time run is in real-time mode.
    pub realtime: bool,
    /// `priority` and `cpus` (also for `automat run --realtime`).
    pub settings: automat_runtime::realtime::Realtime,
}

/// One `[safe_state]` entry: the safe value of an output.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SafeSpec {
    /// A variable path, direct address or actuator signal name.
    pub target: String,
    /// The value as an IEC literal (`TRUE`, `100`, `2.5`, `T#5s`).
    pub value: String,
    /// The key in the project file.
    pub span: Span,
}

/// A loaded project file.
#[derive(Clone, Debug)]
pub struct Project {
    /// The folder of `automat.toml`.
    pub dir: PathBuf,
    /// `automat.toml` in the caller's source map.
    pub file: FileId,
    pub name: String,
    pub description: String,
    /// The Structured Text files to compile, sorted.
    pub sources: Vec<PathBuf>,
    /// The PROGRAM to run when there is no CONFIGURATION.
    pub program: Option<String>,
    pub cycle_time_ns: i64,
    /// Vendor dialects (`libraries = ["isagraf"]`, like `automat run --lib`).
    pub libraries: Vec<String>,
    pub plant: Option<PlantSpec>,
    pub retain: RetainSpec,
    /// `[safe_state]`, in the file's key order.
    pub safe_state: Vec<SafeSpec>,
    pub users: Vec<UserSpec>,
    /// `[tasks.NAME]` tables, applied with [`crate::tasks::apply`].
    pub tasks: Vec<TaskSpec>,
    /// `[runtime]`: the real-time mode of real-time runs.
    pub runtime: RuntimeSpec,
    /// What loading has to say without failing: source files or folders
    /// reached twice through symbolic links (see [`crate::folder`]), as
    /// `warning: ...` lines for the caller to print.
    pub warnings: Vec<String>,
}

impl Project {
    /// A new model instance as the project configures it (parameters set).
    /// `None` when the project has no `[plant]`.
    pub fn new_plant(&self) -> Result<Option<Box<dyn Plant>>, Vec<Diagnostic>> {
        let Some(spec) = &self.plant else {
            return Ok(None);
        };
        let built =
            match &spec.program {
                Some(st) => match &st.compiled {
                    Some(c) => Some(Box::new(crate::st_plant::StPlant::new(st, Arc::clone(c)))
                        as Box<dyn Plant>),
                    // Read with `parse` alone (no source map for the plant file).
                    None => {
                        return Err(vec![Diagnostic::error(
                            Code::E310,
                            st.span,
                            format!("the plant program `{}` was not compiled", st.written),
                        )])
                    }
                },
                None => models::by_name(&spec.model),
            };
        let Some(mut plant) = built else {
            return Err(vec![Diagnostic::error(
                Code::E301,
                spec.model_span,
                format!("unknown plant model `{}`", spec.model),
            )
            .with_note(format!("known models: {}", models::NAMES.join(", ")))]);
        };
        let mut errors = Vec::new();
        for (key, value, span) in &spec.params {
            if let Err(e) = plant.command("set", &[(key.as_str(), *value)]) {
                errors.push(Diagnostic::error(
                    Code::E307,
                    *span,
                    format!("plant parameter `{key}` refused: {e}"),
                ));
            }
        }
        if errors.is_empty() {
            Ok(Some(plant))
        } else {
            Err(errors)
        }
    }
}

/// The project file of `path`: `path` itself when it is a file, else
/// `path/automat.toml` when that exists.
pub fn project_file(path: &Path) -> Option<PathBuf> {
    if path.is_dir() {
        let f = path.join(FILE_NAME);
        f.is_file().then_some(f)
    } else if path.file_name().is_some_and(|n| n == FILE_NAME) {
        Some(path.to_path_buf())
    } else {
        None
    }
}

/// The nearest `automat.toml` in the folder of `path` or above it.
pub fn find_above(path: &Path) -> Option<PathBuf> {
    let mut dir = if path.is_dir() {
        Some(path)
    } else {
        path.parent()
    };
    while let Some(d) = dir {
        let f = d.join(FILE_NAME);
        if f.is_file() {
            return Some(f);
        }
        dir = d.parent();
    }
    None
}

fn span_of(file: FileId, r: std::ops::Range<usize>) -> Span {
    let c = |x: usize| u32::try_from(x).unwrap_or(u32::MAX);
    Span::new(file, c(r.start), c(r.end))
}

/// Reads and checks `automat.toml` at `path` (the text goes into `map`).
pub fn load(path: &Path, map: &mut SourceMap) -> Result<Project, Vec<Diagnostic>> {
    // Not read whole when it is far too big (a device, a huge file).
    let big = std::fs::metadata(path).is_ok_and(|m| m.len() > MAX_FILE_BYTES as u64 * 4);
    if big {
        let file = map.add(path.display().to_string(), String::new());
        return Err(vec![Diagnostic::error(
            Code::E300,
            Span::new(file, 0, 0),
            format!("the project file is larger than the {MAX_FILE_BYTES} bytes a project file may have"),
        )]);
    }
    let text = std::fs::read_to_string(path).map_err(|e| {
        let file = map.add(path.display().to_string(), String::new());
        vec![Diagnostic::error(
            Code::E300,
            Span::new(file, 0, 0),
            format!("cannot read the project file: {e}"),
        )]
    })?;
    let file = map.add(path.display().to_string(), text.clone());
    let mut project = parse(path, file, &text)?;
    if let Some(st) = project.plant.as_mut().and_then(|p| p.program.as_mut()) {
        let compiled = crate::st_plant::compile(st, map)?;
        if !compiled.warnings.is_empty() {
            project
                .warnings
                .push(compiled.warnings.trim_end().to_string());
        }
        st.compiled = Some(Arc::new(compiled));
    }
    Ok(project)
}

/// The largest project file read: a real one is a few KB; a bigger one is
/// a mistake (or hostile) and would take seconds to parse.
pub const MAX_FILE_BYTES: usize = 1 << 20;

/// Parses the text of a project file already in a source map as `file`.
pub fn parse(path: &Path, file: FileId, text: &str) -> Result<Project, Vec<Diagnostic>> {
    if text.len() > MAX_FILE_BYTES {
        return Err(vec![Diagnostic::error(
            Code::E300,
            Span::new(file, 0, 0),
            format!(
                "the project file has {} bytes, more than the {} a project file may have",
                text.len(),
                MAX_FILE_BYTES
            ),
        )]);
    }
    let raw: RawFile = toml::from_str(text).map_err(|e| {
        let span = e.span().map_or(Span::new(file, 0, 0), |r| span_of(file, r));
        vec![Diagnostic::error(
            Code::E300,
            span,
            format!("invalid project file: {}", e.message().trim_end()),
        )]
    })?;
    let dir = path
        .parent()
        .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
    let dir = if dir.as_os_str().is_empty() {
        PathBuf::from(".")
    } else {
        dir
    };
    let mut errors = Vec::new();
    let cycle_time_ns = match &raw.project.cycle_time {
        None => DEFAULT_CYCLE_NS,
        Some(ct) => match automat_runtime::timearg::parse_duration(ct.get_ref()) {
            Ok(ns) if ns > 0 => ns,
            Ok(_) => {
                errors.push(Diagnostic::error(
                    Code::E300,
                    span_of(file, ct.span()),
                    "cycle_time must be longer than 0",
                ));
                DEFAULT_CYCLE_NS
            }
            Err(e) => {
                errors.push(Diagnostic::error(
                    Code::E300,
                    span_of(file, ct.span()),
                    format!("cycle_time: {e}"),
                ));
                DEFAULT_CYCLE_NS
            }
        },
    };
    let mut walk = Walk::new();
    let sources = match sources(&dir, file, raw.project.sources.as_deref(), &mut walk) {
        Ok(s) => s,
        Err(d) => {
            errors.push(d);
            Vec::new()
        }
    };
    let mut sources = sources;
    let plant = raw.plant.map(|p| {
        let program = plant_program(&dir, file, &p, &mut errors);
        if let Some(st) = &program {
            // The plant's file is no source of the controller, even beside
            // automat.toml where sources are found by default.
            let same = |a: &Path| {
                a == st.path.as_path()
                    || a.canonicalize().ok().zip(st.path.canonicalize().ok()).is_some_and(|(x, y)| x == y)
            };
            sources.retain(|s| !same(s));
            if sources.is_empty() {
                errors.push(Diagnostic::error(
                    Code::E308,
                    Span::new(file, 0, 0),
                    format!(
                        "the project has no Structured Text sources besides its plant program (*.st in {})",
                        dir.display()
                    ),
                ));
            }
        }
        let (model, model_span) = match (&p.model, &program) {
            (Some(m), _) => (m.get_ref().clone(), span_of(file, m.span())),
            (None, Some(st)) => (st.written.clone(), st.span),
            (None, None) => (String::new(), Span::new(file, 0, 0)),
        };
        PlantSpec {
        model,
        model_span,
        program,
        seed: p.seed.unwrap_or(1),
        params: p
            .params
            .into_iter()
            .map(|(k, v)| (k.get_ref().clone(), *v.get_ref(), span_of(file, k.span())))
            .collect(),
        bind: raw
            .bind
            .into_iter()
            .map(|(k, v)| BindSpec {
                signal: k.get_ref().clone(),
                signal_span: span_of(file, k.span()),
                target: v.get_ref().clone(),
                target_span: span_of(file, v.span()),
            })
            .collect(),
    }
    });
    let retain = retain_spec(&dir, file, raw.retain, &mut errors);
    let mut safe_state = Vec::new();
    for (k, v) in raw.safe_state {
        let span = span_of(file, k.span());
        safe_values(k.get_ref().clone(), &v, span, &mut safe_state, &mut errors);
    }
    let mut users = Vec::new();
    for (name, u) in raw.users {
        let role = u.role.get_ref().clone();
        if !ROLES.contains(&role.as_str()) {
            errors.push(Diagnostic::error(
                Code::E300,
                span_of(file, u.role.span()),
                format!("user `{name}`: role `{role}` is not viewer, operator or engineer"),
            ));
        }
        users.push(UserSpec {
            name,
            role,
            password_hash: u.password,
        });
    }
    let tasks = raw
        .tasks
        .into_iter()
        .map(|(name, t)| task_spec(file, name, t, &mut errors))
        .collect();
    let runtime = raw
        .runtime
        .map(|r| runtime_spec(file, r, &mut errors))
        .unwrap_or_default();
    let mut libraries = raw.project.libraries;
    if let Some(c) = raw.codesys {
        codesys_settings(file, c, &mut libraries, &mut errors);
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    Ok(Project {
        dir,
        file,
        name: raw.project.name,
        description: raw.project.description,
        sources,
        program: raw.project.program,
        cycle_time_ns,
        libraries,
        plant,
        tasks,
        retain,
        safe_state,
        users,
        runtime,
        warnings: walk.warning().into_iter().collect(),
    })
}

/// `[plant] program`, `step` and `operators` checked (the program is
/// compiled by [`load`]); exactly one of `model` and `program`.
fn plant_program(
    dir: &Path,
    file: FileId,
    p: &RawPlant,
    errors: &mut Vec<Diagnostic>,
) -> Option<crate::st_plant::StPlantSpec> {
    let Some(prog) = &p.program else {
        if p.model.is_none() {
            errors.push(Diagnostic::error(
                Code::E300,
                Span::new(file, 0, 0),
                "[plant] needs `model` (a built-in model) or `program` (a plant written in ST)",
            ));
        }
        for (what, span) in [
            ("step", p.step.as_ref().map(|s| s.span())),
            ("operators", p.operators.first().map(|s| s.span())),
        ] {
            if let Some(r) = span {
                errors.push(Diagnostic::error(
                    Code::E300,
                    span_of(file, r),
                    format!(
                        "[plant] `{what}` is for a plant written in ST (`program = \"plant.st\"`)"
                    ),
                ));
            }
        }
        return None;
    };
    let span = span_of(file, prog.span());
    if let Some(m) = &p.model {
        errors.push(
            Diagnostic::error(
                Code::E300,
                span_of(file, m.span()),
                "[plant] has both `model` and `program`: a plant is a built-in model or a PROGRAM in ST",
            )
            .with_label(span, "the program"),
        );
    }
    let step_ns = match &p.step {
        None => crate::st_plant::DEFAULT_STEP_NS,
        Some(st) => match automat_runtime::timearg::parse_duration(st.get_ref()) {
            Ok(ns) if ns > 0 => ns,
            Ok(_) => {
                errors.push(Diagnostic::error(
                    Code::E300,
                    span_of(file, st.span()),
                    "[plant] step must be longer than 0",
                ));
                crate::st_plant::DEFAULT_STEP_NS
            }
            Err(e) => {
                errors.push(Diagnostic::error(
                    Code::E300,
                    span_of(file, st.span()),
                    format!("[plant] step: {e}"),
                ));
                crate::st_plant::DEFAULT_STEP_NS
            }
        },
    };
    Some(crate::st_plant::StPlantSpec {
        path: dir.join(prog.get_ref()),
        written: prog.get_ref().clone(),
        span,
        step_ns,
        operators: p
            .operators
            .iter()
            .map(|o| (o.get_ref().clone(), span_of(file, o.span())))
            .collect(),
        compiled: None,
    })
}

/// `[runtime]`: `realtime = true`, `priority` (SCHED_FIFO 1..99, default
/// 80), `cpus` (`"1"`, `"0,2-3"`).
/// `[codesys] heap = "256KiB"`: checked here, and carried as the setting
/// of the `codesys` library (`codesys:heap=262144`, as `--lib` takes it).
fn codesys_settings(
    file: FileId,
    raw: RawCodesys,
    libraries: &mut [String],
    errors: &mut Vec<Diagnostic>,
) {
    let Some(heap) = raw.heap else { return };
    let at = span_of(file, heap.span());
    let bytes = match automat_dialect::parse_heap_size(heap.get_ref()) {
        Ok(b) => b,
        Err(e) => {
            errors.push(Diagnostic::error(Code::E300, at, format!("heap: {e}")));
            return;
        }
    };
    let codesys = libraries.iter_mut().find(|l| {
        automat_dialect::Dialect::from_name(l) == Some(automat_dialect::Dialect::Codesys)
    });
    match codesys {
        Some(l) => *l = format!("{}:heap={bytes}", l.trim()),
        None => errors.push(Diagnostic::error(
            Code::E300,
            at,
            "heap: `[codesys]` sets the CODESYS dialect, which this project does not use: add `libraries = [\"codesys\"]` to `[project]`",
        )),
    }
}

fn runtime_spec(file: FileId, raw: RawRuntime, errors: &mut Vec<Diagnostic>) -> RuntimeSpec {
    use automat_runtime::realtime::{parse_cpus, Realtime};
    let mut rt = Realtime::default();
    if let Some(p) = &raw.priority {
        match i32::try_from(*p.get_ref()) {
            Ok(v) if (1..=99).contains(&v) => rt.priority = v,
            _ => errors.push(Diagnostic::error(
                Code::E300,
                span_of(file, p.span()),
                format!(
                    "priority: {} is out of range: SCHED_FIFO priorities are 1 to 99",
                    p.get_ref()
                ),
            )),
        }
    }
    if let Some(c) = &raw.cpus {
        match parse_cpus(c.get_ref()) {
            Ok(cpus) => rt.cpus = cpus,
            Err(e) => errors.push(Diagnostic::error(
                Code::E300,
                span_of(file, c.span()),
                format!("cpus: {e}"),
            )),
        }
    }
    RuntimeSpec {
        realtime: raw.realtime,
        settings: rt,
    }
}

fn retain_spec(
    dir: &Path,
    file: FileId,
    raw: Option<RawRetain>,
    errors: &mut Vec<Diagnostic>,
) -> RetainSpec {
    let Some(raw) = raw else {
        return RetainSpec::default();
    };
    let save_every_ns = raw.save_every.and_then(|every| {
        let span = span_of(file, every.span());
        match automat_runtime::timearg::parse_duration(every.get_ref()) {
            Ok(ns) => Some(ns),
            Err(e) => {
                errors.push(Diagnostic::error(
                    Code::E300,
                    span,
                    format!("save_every: {e}"),
                ));
                None
            }
        }
    });
    RetainSpec {
        file: raw.file.map(|f| dir.join(f.get_ref())),
        save_every_ns,
        optional: raw.optional,
    }
}

/// The `[safe_state]` entries under `key` (a dotted key is a nested table:
/// `Ctrl.valve = true` is `{"Ctrl": {"valve": true}}`).
fn safe_values(
    key: String,
    value: &toml::Value,
    span: Span,
    out: &mut Vec<SafeSpec>,
    errors: &mut Vec<Diagnostic>,
) {
    let text = match value {
        toml::Value::Boolean(b) => if *b { "TRUE" } else { "FALSE" }.to_string(),
        toml::Value::Integer(i) => i.to_string(),
        toml::Value::Float(f) if f.is_finite() => format!("{f:?}"),
        toml::Value::String(s) => s.clone(),
        toml::Value::Table(t) => {
            for (k, v) in t {
                safe_values(format!("{key}.{k}"), v, span, out, errors);
            }
            return;
        }
        _ => {
            errors.push(Diagnostic::error(
                Code::E300,
                span,
                format!(
                    "[safe_state] `{key}`: a safe value is a boolean, a number or an IEC literal in a string"
                ),
            ));
            return;
        }
    };
    out.push(SafeSpec {
        target: key,
        value: text,
        span,
    });
}

/// One `[tasks.NAME]` table checked: `watchdog` a duration > 0 or `off`,
/// `sensitivity` ≥ 1 and only with a watchdog time.
fn task_spec(
    file: FileId,
    name: Spanned<String>,
    t: RawTask,
    errors: &mut Vec<Diagnostic>,
) -> TaskSpec {
    let name_span = span_of(file, name.span());
    let name = name.into_inner();
    let mut watchdog = TaskWatchdog::Default;
    if let Some(w) = &t.watchdog {
        match automat_runtime::watchdog::parse_watchdog(w.get_ref()) {
            Ok(v) => watchdog = v,
            Err(e) => errors.push(Diagnostic::error(
                Code::E300,
                span_of(file, w.span()),
                format!("[tasks.{name}] watchdog: {e}"),
            )),
        }
    }
    if let Some(s) = &t.sensitivity {
        let span = span_of(file, s.span());
        let failed = t.watchdog.is_some() && watchdog == TaskWatchdog::Default;
        match (u32::try_from(*s.get_ref()).ok().filter(|n| *n >= 1), &mut watchdog) {
            (Some(n), TaskWatchdog::Limit { sensitivity, .. }) => *sensitivity = n,
            // The watchdog itself was refused above.
            (Some(_), _) if failed => {}
            (Some(_), _) => errors.push(Diagnostic::error(
                Code::E300,
                span,
                format!("[tasks.{name}] sensitivity needs a watchdog time (`watchdog = \"100ms\"`)"),
            )),
            (None, _) => errors.push(Diagnostic::error(
                Code::E300,
                span,
                format!(
                    "[tasks.{name}] sensitivity must be a whole number of consecutive overruns, 1 or more (not {})",
                    s.get_ref()
                ),
            )),
        }
    }
    TaskSpec {
        name,
        name_span,
        watchdog,
    }
}

/// A source file: `*.st`, PLCopen TC6 XML (`*.xml`), or a file of the FST
/// dialect (`*.stl`, `allocation.txt`), which is read only with `libraries = ["fst"]`,
/// an Allen-Bradley SLC-500 ladder file (`*.slc`),
/// or a CODESYS V2.3 text export (`*.exp`).
fn is_st(p: &Path) -> bool {
    p.extension()
        .and_then(|e| e.to_str())
        // PLCopen TC6 XML sources sit beside the ST ones.
        .is_some_and(|e| e.eq_ignore_ascii_case("st") || e.eq_ignore_ascii_case("xml"))
        || automat_dialect::is_fst_file(&p.to_string_lossy())
        || automat_dialect::is_slc_file(&p.to_string_lossy())
        || automat_dialect::is_export_file(&p.to_string_lossy())
}

/// Every `*.st` under `dir` (recursively when `deep`), sorted, each file
/// once.
fn st_files(dir: &Path, deep: bool, walk: &mut Walk, out: &mut Vec<PathBuf>) -> Result<(), String> {
    let mut keep = |e: Entry| match e {
        Entry::Dir(_) => deep,
        Entry::File(p) => is_st(p),
    };
    walk.dir(dir, &mut keep, out)
}

fn sources(
    dir: &Path,
    file: FileId,
    listed: Option<&[Spanned<String>]>,
    walk: &mut Walk,
) -> Result<Vec<PathBuf>, Diagnostic> {
    let mut out = Vec::new();
    match listed {
        None => st_files(dir, false, walk, &mut out).map_err(|e| {
            Diagnostic::error(
                Code::E308,
                Span::new(file, 0, 0),
                format!("cannot list {e}"),
            )
        })?,
        Some(list) => {
            for s in list {
                let p = dir.join(s.get_ref());
                let err = |why: String| {
                    Diagnostic::error(
                        Code::E308,
                        span_of(file, s.span()),
                        format!("source `{}`: {why}", s.get_ref()),
                    )
                };
                if p.is_dir() {
                    st_files(&p, true, walk, &mut out).map_err(err)?;
                } else if p.is_file() {
                    if walk.first_visit(&p).map_err(err)? {
                        out.push(p);
                    }
                } else {
                    return Err(err("no such file or folder".into()));
                }
            }
        }
    }
    if out.is_empty() {
        return Err(Diagnostic::error(
            Code::E308,
            Span::new(file, 0, 0),
            format!(
                "the project has no Structured Text sources (*.st in {})",
                dir.display()
            ),
        ));
    }
    Ok(out)
}
