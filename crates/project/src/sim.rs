//! The coupling of a plant model to the scan, with the overrides scenarios
//! and the operator view inject.
//!
//! At each scan at PLC time t, before the tasks run ([`Sim::sync`]):
//! 1. the actuators are read from their bound variables (the output image
//!    of the last scan; a stuck actuator gives its stuck value instead) and
//!    set on the model;
//! 2. the model advances from its time to t in steps of exactly
//!    `step_ns()` (the remainder waits for the next scan);
//! 3. the actions due at or before t are applied, in time order (so a
//!    press at 1 s is seen by the scan at 1 s);
//! 4. sensor and operator values, after overrides (stuck value; noise on
//!    Int/Real sensors), are written into their bound variables.
//!
//! Reading the actuators at the start of the next scan is the same as
//! reading them at the end of this one: nothing writes them in between.

use crate::bind::Binding;
use crate::image;
use automat_plant::{Dir, Kind, Plant, Rng, Value};
use automat_runtime::Place;

/// Something done to the plant or the PLC at an instant.
#[derive(Clone, Debug, PartialEq)]
pub enum Action {
    /// Sets an operator (or actuator) signal on the model.
    Set {
        signal: usize,
        value: Value,
    },
    /// From now on the PLC sees `value` for this sensor (or the model sees
    /// it for this actuator), whatever the model or the PLC says.
    Stuck {
        signal: usize,
        value: Value,
    },
    Unstick {
        signal: usize,
    },
    /// Uniform noise of ± `amplitude` on an Int/Real sensor (0 removes it).
    Noise {
        signal: usize,
        amplitude: f64,
    },
    /// A model command (`plant bottle capped=0`).
    Command {
        name: String,
        args: Vec<(String, f64)>,
    },
    /// Writes a PLC variable once (`set Ctrl.mode = 2` on a variable that
    /// is not a signal).
    Write {
        place: Place,
        value: Value,
    },
}

/// The plant, its bindings and overrides, advancing with the scan.
pub struct Sim {
    plant: Box<dyn Plant>,
    bindings: Vec<Binding>,
    /// Binding indexes of actuators, and of sensors and operator signals.
    actuators: Vec<usize>,
    inputs: Vec<usize>,
    stuck: Vec<Option<Value>>,
    noise: Vec<f64>,
    rng: Rng,
    noise_rng: Rng,
    model_ns: i64,
    /// Actions by time (stable for equal times), and the next one due.
    actions: Vec<(i64, Action)>,
    next_action: usize,
    /// Errors of model commands met during the run (reported by callers).
    pub errors: Vec<(i64, String)>,
    /// PLC time of the last sync.
    pub now_ns: i64,
    /// The PLC stopped on a fault or a stop request ([`Sim::safe_state`]).
    halted: bool,
    /// The actuator values latched by [`Sim::safe_state`], by signal.
    safe: Vec<Option<Value>>,
    /// The plant time at which the model reported a fault
    /// ([`Plant::fault`]: a plant written in ST whose program stopped).
    pub plant_fault_ns: Option<i64>,
}

impl Sim {
    pub fn new(plant: Box<dyn Plant>, bindings: Vec<Binding>, seed: u64) -> Sim {
        let n = plant.signals().len();
        let dir = |b: &Binding| plant.signals().get(b.signal).map(|s| s.dir);
        let actuators = (0..bindings.len())
            .filter(|&i| bindings.get(i).and_then(dir) == Some(Dir::Actuator))
            .collect();
        let inputs = (0..bindings.len())
            .filter(|&i| {
                bindings
                    .get(i)
                    .and_then(dir)
                    .is_some_and(|d| d != Dir::Actuator)
            })
            .collect();
        Sim {
            plant,
            bindings,
            actuators,
            inputs,
            stuck: vec![None; n],
            noise: vec![0.0; n],
            rng: Rng::new(seed),
            noise_rng: Rng::new(seed ^ 0x005E_ED0F_401E),
            model_ns: 0,
            actions: Vec::new(),
            next_action: 0,
            errors: Vec::new(),
            now_ns: 0,
            halted: false,
            safe: vec![None; n],
            plant_fault_ns: None,
        }
    }

    pub fn plant(&self) -> &dyn Plant {
        self.plant.as_ref()
    }

    pub fn bindings(&self) -> &[Binding] {
        &self.bindings
    }

    /// The binding of a signal, if it is bound.
    pub fn binding_of(&self, signal: usize) -> Option<&Binding> {
        self.bindings.iter().find(|b| b.signal == signal)
    }

    /// The override of a signal, if stuck.
    pub fn stuck(&self, signal: usize) -> Option<Value> {
        self.stuck.get(signal).copied().flatten()
    }

    /// Schedules `action` at PLC time `at_ns` (after the actions already
    /// scheduled for the same time). An action in the past runs at the
    /// next sync.
    pub fn schedule(&mut self, at_ns: i64, action: Action) {
        // Searched from the end: scenario reactions schedule at the latest
        // time, so a long run stays linear.
        let pending = self.actions.get(self.next_action..).unwrap_or(&[]);
        let pos = pending
            .iter()
            .rposition(|(t, _)| *t <= at_ns)
            .map_or(self.next_action, |p| p + self.next_action + 1);
        self.actions.insert(pos, (at_ns, action));
    }

    /// Steps 1–4 of the module comment for the scan at `t`.
    pub fn sync(&mut self, t: i64, image: &mut [u8]) {
        self.now_ns = t;
        for &bi in &self.actuators {
            let Some(b) = self.bindings.get(bi) else {
                continue;
            };
            let v = match self.stuck.get(b.signal).copied().flatten() {
                Some(v) => Some(v),
                None if self.halted => self.safe.get(b.signal).copied().flatten(),
                None => image::read(image, &b.place),
            };
            if let Some(v) = v {
                self.plant.set(b.signal, v);
            }
        }
        let step = self.plant.step_ns().max(1);
        while self.model_ns.saturating_add(step) <= t {
            self.plant.step(step, &mut self.rng);
            self.model_ns += step;
            // Asked only until it happens: a faulted plant stays faulted.
            if self.plant_fault_ns.is_none() && self.plant.fault().is_some() {
                self.plant_fault_ns = Some(self.model_ns);
            }
        }
        while let Some((at, _)) = self.actions.get(self.next_action) {
            if *at > t {
                break;
            }
            let action = self.actions[self.next_action].1.clone();
            self.next_action += 1;
            self.apply(t, action, image);
        }
        self.write_inputs(image);
    }

    /// The PLC stopped in its safe state, which the runtime wrote into
    /// `image` (every variable an actuator is bound to at its safe value,
    /// see [`crate::safe`]): from now on the model gets those values, as a
    /// real PLC's outputs stay in their safe state, whatever is written to
    /// the variables afterwards. A value that cannot be read is 0/FALSE. (A
    /// stuck actuator keeps its stuck value: that fault is in the
    /// hardware.) Applied to the model at once, so anything reading it
    /// after the run sees it.
    pub fn safe_state(&mut self, image: &[u8]) {
        self.halted = true;
        for &bi in &self.actuators {
            let Some(b) = self.bindings.get(bi) else {
                continue;
            };
            let signal = b.signal;
            let latched = image::read(image, &b.place).or_else(|| self.safe_value(signal));
            if let Some(slot) = self.safe.get_mut(signal) {
                *slot = latched;
            }
            let v = match self.stuck.get(signal).copied().flatten() {
                Some(v) => Some(v),
                None => latched,
            };
            if let Some(v) = v {
                self.plant.set(signal, v);
            }
        }
    }

    /// The PLC runs again after a fault (an online restart): actuators
    /// follow the image again.
    pub fn resume(&mut self) {
        self.halted = false;
    }

    /// Whether [`Sim::safe_state`] was applied.
    pub fn halted(&self) -> bool {
        self.halted
    }

    /// 0/FALSE of a signal's kind.
    fn safe_value(&self, signal: usize) -> Option<Value> {
        Some(match self.plant.signals().get(signal)?.kind {
            Kind::Bool => Value::Bool(false),
            Kind::Int => Value::Int(0),
            Kind::Real => Value::Real(0.0),
        })
    }

    /// The value the PLC sees for a sensor/operator signal now.
    pub fn input_value(&mut self, signal: usize) -> Value {
        if let Some(v) = self.stuck.get(signal).copied().flatten() {
            return v;
        }
        let v = self.plant.get(signal);
        let a = self.noise.get(signal).copied().unwrap_or(0.0);
        if a == 0.0 {
            return v;
        }
        let n = (self.noise_rng.unit() * 2.0 - 1.0) * a;
        match (v, self.plant.signals().get(signal).map(|s| s.kind)) {
            (Value::Int(i), _) => Value::Int(i.saturating_add(n.round() as i64)),
            (Value::Real(r), _) => Value::Real(r + n),
            (v, _) => v,
        }
    }

    fn write_inputs(&mut self, image: &mut [u8]) {
        for k in 0..self.inputs.len() {
            let Some(&bi) = self.inputs.get(k) else {
                continue;
            };
            let Some(signal) = self.bindings.get(bi).map(|b| b.signal) else {
                continue;
            };
            let v = self.input_value(signal);
            // The place borrowed again, not cloned: this runs every scan.
            if let Some(b) = self.bindings.get(bi) {
                image::write(image, &b.place, v);
            }
        }
    }

    fn apply(&mut self, t: i64, action: Action, image: &mut [u8]) {
        match action {
            Action::Set { signal, value } => self.plant.set(signal, value),
            Action::Stuck { signal, value } => {
                if let Some(s) = self.stuck.get_mut(signal) {
                    *s = Some(value);
                }
            }
            Action::Unstick { signal } => {
                if let Some(s) = self.stuck.get_mut(signal) {
                    *s = None;
                }
            }
            Action::Noise { signal, amplitude } => {
                let numeric = self
                    .plant
                    .signals()
                    .get(signal)
                    .is_some_and(|s| s.kind != Kind::Bool);
                if let (Some(n), true) = (self.noise.get_mut(signal), numeric) {
                    *n = amplitude.abs();
                }
            }
            Action::Command { name, args } => {
                let args: Vec<(&str, f64)> = args.iter().map(|(k, v)| (k.as_str(), *v)).collect();
                if let Err(e) = self.plant.command(&name, &args) {
                    self.errors.push((t, e));
                }
            }
            Action::Write { place, value } => image::write(image, &place, value),
        }
    }
}

#[cfg(test)]
#[path = "sim_tests.rs"]
mod tests;
