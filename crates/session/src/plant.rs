//! The plant seen and operated by clients: what `automat run --live`'s
//! `press Pornire` does, for the network API and the web HMI.
//!
//! The plant lives on the scan thread (models need not be `Send`), so
//! both reading it and operating it are commands run there between two
//! scans: a view is consistent with one scan, and an operation is
//! scheduled on the plant at the PLC time of the last scan, so the next
//! scan sees it (as a typed `press` in the live view).

use automat_plant::{Dir, Kind, Value};
use automat_project::{Action, Sim};

use crate::Error;

/// One signal of the model with the value it has now.
#[derive(Clone, Debug, PartialEq)]
pub struct SignalView {
    pub name: String,
    /// `sensor`, `actuator` or `operator`.
    pub dir: &'static str,
    /// `BOOL`, `INT` or `REAL`.
    pub kind: &'static str,
    pub doc: String,
    /// For sensors and operator inputs, what the PLC is given (a stuck
    /// value included); for actuators, what the model was last given.
    pub value: Value,
    /// The PLC variable or address it is bound to, if bound.
    pub bound: Option<String>,
    /// Held at a value by `set` on a sensor or actuator (see [`Op::Set`]).
    pub stuck: bool,
}

#[derive(Clone, Debug, PartialEq)]
pub struct QuantityView {
    pub name: String,
    pub unit: String,
    pub doc: String,
    pub value: f64,
}

/// The plant as the last scan left it.
#[derive(Clone, Debug, PartialEq)]
pub struct View {
    /// The model's name (`crane`).
    pub model: String,
    /// The picture the model declares ([`automat_plant::Plant::mimic`]).
    pub mimic: Option<String>,
    /// PLC time of the last synchronisation with the scan.
    pub now_ns: i64,
    pub signals: Vec<SignalView>,
    pub quantities: Vec<QuantityView>,
    /// The model's commands with their descriptions.
    pub commands: Vec<(String, String)>,
}

/// An operator's action on the plant.
#[derive(Clone, Debug, PartialEq)]
pub enum Op {
    /// Presses a BOOL operator input; with `for_ns`, releases it that much
    /// PLC time later.
    Press {
        signal: String,
        for_ns: Option<i64>,
    },
    Release {
        signal: String,
    },
    /// An operator input takes the value; a sensor or actuator is held at
    /// it (stuck, a toggled switch or a jammed contactor) until `Unstick`.
    Set {
        signal: String,
        value: String,
    },
    Unstick {
        signal: String,
    },
}

fn dir_name(d: Dir) -> &'static str {
    match d {
        Dir::Sensor => "sensor",
        Dir::Actuator => "actuator",
        Dir::Operator => "operator",
    }
}

fn kind_name(k: Kind) -> &'static str {
    match k {
        Kind::Bool => "BOOL",
        Kind::Int => "INT",
        Kind::Real => "REAL",
    }
}

pub(crate) fn view(sim: &mut Sim) -> View {
    let n = sim.plant().signals().len();
    let signals = (0..n)
        .filter_map(|i| {
            let s = *sim.plant().signals().get(i)?;
            let value = sim.stuck(i).unwrap_or_else(|| sim.plant().get(i));
            Some(SignalView {
                name: s.name.to_string(),
                dir: dir_name(s.dir),
                kind: kind_name(s.kind),
                doc: s.doc.to_string(),
                value,
                bound: sim.binding_of(i).map(|b| b.path.clone()),
                stuck: sim.stuck(i).is_some(),
            })
        })
        .collect();
    let plant = sim.plant();
    View {
        model: plant.name().to_string(),
        mimic: plant.mimic().map(str::to_string),
        now_ns: sim.now_ns,
        signals,
        quantities: plant
            .quantities()
            .iter()
            .enumerate()
            .map(|(i, q)| QuantityView {
                name: q.name.to_string(),
                unit: q.unit.to_string(),
                doc: q.doc.to_string(),
                value: plant.quantity(i),
            })
            .collect(),
        commands: plant
            .commands()
            .iter()
            .map(|(c, d)| (c.to_string(), d.to_string()))
            .collect(),
    }
}

/// The index of the signal called `name` (case-insensitive, as in
/// scenarios), or the error naming the model's signals.
fn signal_of(sim: &Sim, name: &str) -> Result<usize, Error> {
    let plant = sim.plant();
    plant
        .signals()
        .iter()
        .position(|s| s.name.eq_ignore_ascii_case(name.trim()))
        .ok_or_else(|| {
            let names: Vec<&str> = plant.signals().iter().map(|s| s.name).collect();
            Error::Path(format!(
                "the {} model has no signal `{}`; its signals: {}",
                plant.name(),
                name.trim(),
                names.join(", ")
            ))
        })
}

/// `text` as a value of `kind`: `TRUE`/`FALSE`/`1`/`0` for BOOL, an
/// integer for INT, a number for REAL.
fn parse_value(kind: Kind, text: &str, signal: &str) -> Result<Value, Error> {
    let t = text.trim();
    let bad = |what: &str| Error::Value(format!("`{signal}`: expected {what}, got `{t}`"));
    match kind {
        Kind::Bool => match t.to_ascii_uppercase().as_str() {
            "TRUE" | "1" => Ok(Value::Bool(true)),
            "FALSE" | "0" => Ok(Value::Bool(false)),
            _ => Err(bad("TRUE or FALSE (BOOL)")),
        },
        Kind::Int => t
            .replace('_', "")
            .parse::<i64>()
            .map(Value::Int)
            .map_err(|_| bad("an integer (INT)")),
        Kind::Real => t
            .replace('_', "")
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .map(Value::Real)
            .ok_or_else(|| bad("a number (REAL)")),
    }
}

/// Schedules `op` on the plant for the next scan.
pub(crate) fn apply(sim: &mut Sim, op: &Op) -> Result<(), Error> {
    let now = sim.now_ns;
    let press = |sim: &Sim, name: &str| -> Result<usize, Error> {
        let i = signal_of(sim, name)?;
        let s = sim.plant().signals().get(i).copied();
        if s.is_none_or(|s| s.dir != Dir::Operator || s.kind != Kind::Bool) {
            return Err(Error::Refused(format!(
                "`{}` is not a BOOL operator input: press and release apply to push-buttons; `set` holds a sensor or actuator",
                name.trim()
            )));
        }
        Ok(i)
    };
    match op {
        Op::Press { signal, for_ns } => {
            let i = press(sim, signal)?;
            if for_ns.is_some_and(|d| d <= 0) {
                return Err(Error::Value("`for_ms` must be more than 0".into()));
            }
            sim.schedule(
                now,
                Action::Set {
                    signal: i,
                    value: Value::Bool(true),
                },
            );
            if let Some(d) = for_ns {
                sim.schedule(
                    now.saturating_add(*d),
                    Action::Set {
                        signal: i,
                        value: Value::Bool(false),
                    },
                );
            }
        }
        Op::Release { signal } => {
            let i = press(sim, signal)?;
            sim.schedule(
                now,
                Action::Set {
                    signal: i,
                    value: Value::Bool(false),
                },
            );
        }
        Op::Set { signal, value } => {
            let i = signal_of(sim, signal)?;
            let Some(s) = sim.plant().signals().get(i).copied() else {
                return Err(Error::Path(format!("no signal `{signal}`")));
            };
            let value = parse_value(s.kind, value, s.name)?;
            let action = if s.dir == Dir::Operator {
                Action::Set { signal: i, value }
            } else {
                Action::Stuck { signal: i, value }
            };
            sim.schedule(now, action);
        }
        Op::Unstick { signal } => {
            let i = signal_of(sim, signal)?;
            if sim.stuck(i).is_none() {
                return Err(Error::Refused(format!("`{}` is not held", signal.trim())));
            }
            sim.schedule(now, Action::Unstick { signal: i });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_parse_by_kind() {
        assert_eq!(parse_value(Kind::Bool, "true", "a"), Ok(Value::Bool(true)));
        assert_eq!(parse_value(Kind::Bool, "0", "a"), Ok(Value::Bool(false)));
        assert_eq!(parse_value(Kind::Int, "4_000", "a"), Ok(Value::Int(4000)));
        assert_eq!(parse_value(Kind::Real, "20.5", "a"), Ok(Value::Real(20.5)));
        assert_eq!(
            parse_value(Kind::Int, "x", "Speed1"),
            Err(Error::Value(
                "`Speed1`: expected an integer (INT), got `x`".into()
            ))
        );
        assert!(parse_value(Kind::Real, "inf", "a").is_err());
    }
}
