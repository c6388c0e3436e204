//! Binding the plant's signals to the PLC: checked once, when the program
//! is loaded.
//!
//! Rules (the contract in `crates/plant/README.md`):
//! - a `[bind]` entry binds a signal to a variable path or direct address;
//! - every other signal binds by name: to the variable of the same name
//!   (case-insensitive) in the single PROGRAM instance, or a global;
//! - a BOOL signal needs a BOOL variable; an Int or Real signal a numeric
//!   one (integer, bit string or real);
//! - an actuator bound to nothing is an error (E305), a sensor or operator
//!   signal bound to nothing a warning (E306): the PLC never sees it; for a
//!   plant written in ST the same are E312 and E313, at the declaration in
//!   the plant file.

use crate::file::PlantSpec;
use automat_base::{Code, Diagnostic, Span};
use automat_iec::Elementary as E;
use automat_ir::Program;
use automat_plant::{Dir, Kind, Plant};
use automat_runtime::{resolve, Place, PlaceType};

/// One bound signal.
#[derive(Clone, Debug, PartialEq)]
pub struct Binding {
    /// Index into the model's `signals()`.
    pub signal: usize,
    /// The variable path or address as written (or the signal name).
    pub path: String,
    pub place: Place,
}

fn kind_name(k: Kind) -> &'static str {
    match k {
        Kind::Bool => "BOOL",
        Kind::Int => "an integer",
        Kind::Real => "a real",
    }
}

fn type_name(t: &PlaceType) -> String {
    match t {
        PlaceType::Elementary(e) => e.name().to_string(),
        PlaceType::Enum { name, .. } => name.clone(),
        PlaceType::String { .. } => "STRING".into(),
        PlaceType::WString { .. } => "WSTRING".into(),
    }
}

/// Whether a signal of kind `k` may be bound to a place of type `t`.
pub fn compatible(k: Kind, t: &PlaceType) -> bool {
    let PlaceType::Elementary(e) = t else {
        return false;
    };
    match k {
        Kind::Bool => *e == E::Bool,
        Kind::Int | Kind::Real => e.is_num() || e.is_bit_string(),
    }
}

/// E312 / E313: a signal of a plant in ST bound to nothing.
fn st_unbound(st: &crate::st_plant::StPlantSpec, name: &str, dir: Dir, span: Span) -> Diagnostic {
    if dir == Dir::Actuator {
        Diagnostic::error(
            Code::E312,
            span,
            format!(
                "VAR_INPUT `{name}` of the plant program `{}` is bound to nothing: the controller has no variable `{name}` and [bind] has no entry for it",
                st.written
            ),
        )
        .with_note(format!("add `{name} = \"<controller variable or %Q address>\"` under [bind] in automat.toml"))
    } else {
        Diagnostic::warning(
            Code::E313,
            span,
            format!(
                "VAR_OUTPUT `{name}` of the plant program `{}` is bound to nothing: the controller does not see it",
                st.written
            ),
        )
    }
}

/// Binds every signal of `plant`; the diagnostics (errors and warnings)
/// point into the project file. `None` when there is any error.
pub fn bind(
    spec: &PlantSpec,
    plant: &dyn Plant,
    program: &Program,
) -> (Option<Vec<Binding>>, Vec<Diagnostic>) {
    let signals = plant.signals();
    let mut diags = Vec::new();
    let mut explicit: Vec<Option<(String, Span)>> = vec![None; signals.len()];
    for b in &spec.bind {
        match signals
            .iter()
            .position(|s| s.name.eq_ignore_ascii_case(&b.signal))
        {
            Some(i) => {
                if let Some(slot) = explicit.get_mut(i) {
                    *slot = Some((b.target.clone(), b.target_span));
                }
            }
            None => diags.push(
                Diagnostic::error(
                    Code::E302,
                    b.signal_span,
                    format!("the {} model has no signal `{}`", plant.name(), b.signal),
                )
                .with_note(format!(
                    "its signals: {}",
                    signals
                        .iter()
                        .map(|s| s.name)
                        .collect::<Vec<_>>()
                        .join(", ")
                )),
            ),
        }
    }
    let mut out = Vec::new();
    for (i, (s, ex)) in signals.iter().zip(&explicit).enumerate() {
        let (path, span) = match ex {
            Some((t, span)) => (t.clone(), *span),
            None => (s.name.to_string(), spec.model_span),
        };
        let place = match resolve(program, &path) {
            Ok(p) => p,
            Err(e) => {
                // A plant in ST: the message points at the declaration.
                let decl = spec
                    .program
                    .as_ref()
                    .and_then(|st| Some((st, st.compiled.as_ref()?.var(s.name)?)));
                if let (None, Some((st, v))) = (ex, decl) {
                    diags.push(st_unbound(st, s.name, s.dir, v.span));
                    continue;
                }
                if ex.is_some() {
                    diags.push(Diagnostic::error(
                        Code::E303,
                        span,
                        format!("signal `{}` is bound to `{path}`: {e}", s.name),
                    ));
                } else if s.dir == Dir::Actuator {
                    diags.push(
                        Diagnostic::error(
                            Code::E305,
                            span,
                            format!(
                                "actuator `{}` of the {} model is bound to nothing: no [bind] entry and no variable `{}`",
                                s.name,
                                plant.name(),
                                s.name
                            ),
                        )
                        .with_note(format!("add `{} = \"<variable or %Q address>\"` under [bind]", s.name)),
                    );
                } else {
                    diags.push(Diagnostic::warning(
                        Code::E306,
                        span,
                        format!(
                            "{} `{}` of the {} model is bound to nothing: the PLC does not see it",
                            if s.dir == Dir::Sensor {
                                "sensor"
                            } else {
                                "operator signal"
                            },
                            s.name,
                            plant.name()
                        ),
                    ));
                }
                continue;
            }
        };
        if !compatible(s.kind, &place.ty) {
            diags.push(Diagnostic::error(
                Code::E304,
                span,
                format!(
                    "signal `{}` is {} but `{path}` is {}",
                    s.name,
                    kind_name(s.kind),
                    type_name(&place.ty)
                ),
            ));
            continue;
        }
        out.push(Binding {
            signal: i,
            path,
            place,
        });
    }
    let ok = !diags.iter().any(Diagnostic::is_error);
    (ok.then_some(out), diags)
}
