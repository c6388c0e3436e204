//! Virtual plants: the machines of the sources as models with named sensors
//! and actuators and a physical state advanced in fixed integration steps.
//!
//! Invariants:
//! - A model is deterministic: the same actuator values, commands and step
//!   sizes give the same sensor values (randomness only from [`Rng`] seeded
//!   by the caller).
//! - A model never reads a clock; time advances only through [`Plant::step`].
//! - A model knows nothing about the PLC, bindings, scenarios or faults:
//!   the framework binds its signals to PLC variables, overrides sensors
//!   (stuck, noise) and actuators (motor that does not move) around it.

pub mod models;

/// Which way a signal flows, seen from the PLC.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dir {
    /// Computed by the plant, read by the PLC (limit switches, photocells,
    /// transducers).
    Sensor,
    /// Set by a person (push-buttons, selector switches), read by the PLC;
    /// the model may read it too but never computes it.
    Operator,
    /// Written by the PLC, moves the plant (motors, valves, lamps).
    Actuator,
}

/// The value type of a signal, as the PLC sees it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Bool,
    /// An integer (raw analog value such as 819..4095, a counter, a word).
    Int,
    /// A real number (engineering units).
    Real,
}

/// One signal of a model: the source's own name (`Pornire`, `l1`, `M1S`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Signal {
    pub name: &'static str,
    pub dir: Dir,
    pub kind: Kind,
    /// One line for people: what it is in the machine.
    pub doc: &'static str,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    Bool(bool),
    Int(i64),
    Real(f64),
}

impl Value {
    pub fn as_bool(self) -> bool {
        match self {
            Value::Bool(b) => b,
            Value::Int(i) => i != 0,
            Value::Real(r) => r != 0.0,
        }
    }
    pub fn as_f64(self) -> f64 {
        match self {
            Value::Bool(b) => f64::from(u8::from(b)),
            Value::Int(i) => i as f64,
            Value::Real(r) => r,
        }
    }
}

/// A physical quantity of the model shown to people and usable in
/// scenario assertions as `plant.<name>` (a position, a level, a count).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Quantity {
    pub name: &'static str,
    pub unit: &'static str,
    pub doc: &'static str,
}

/// A model of one machine.
pub trait Plant {
    /// The model's name as used in project files (`crane`).
    fn name(&self) -> &'static str;
    /// Every signal, in a fixed order; indices below refer to it. (Borrowed
    /// from the model, not `'static`: a plant written in ST learns its
    /// signals from its program.)
    fn signals(&self) -> &[Signal];
    /// Every observable quantity, in a fixed order.
    fn quantities(&self) -> &[Quantity];
    /// The integration step the dynamics need, in nanoseconds; the framework
    /// calls [`Plant::step`] with exactly this `dt` (several times per scan
    /// when the scan is longer).
    fn step_ns(&self) -> i64 {
        1_000_000
    }
    /// Sets an actuator or operator signal (index into `signals()`); other
    /// indices are ignored.
    fn set(&mut self, signal: usize, value: Value);
    /// The current value of any signal (for sensors: what the plant computes
    /// now; for actuators/operator signals: the last value set).
    fn get(&self, signal: usize) -> Value;
    /// The current value of a quantity (index into `quantities()`).
    fn quantity(&self, index: usize) -> f64;
    /// Advances the physics by `dt_ns`.
    fn step(&mut self, dt_ns: i64, rng: &mut Rng);
    /// A model-specific command from a scenario or the operator view
    /// (`bottle capped=0`, `package size=large`), or a parameter
    /// (`set ambient=20`). Unknown commands or keys are errors that name the
    /// model's known ones.
    fn command(&mut self, name: &str, args: &[(&str, f64)]) -> Result<(), String> {
        let _ = args;
        Err(format!("the {} model has no command `{name}`", self.name()))
    }
    /// Why the model stopped, if it did: a plant written in ST whose program
    /// faulted (a division by zero, an endless loop) freezes and says so
    /// here; the built-in models never fault.
    fn fault(&self) -> Option<String> {
        None
    }
    /// Commands this model accepts, with a one-line description each.
    fn commands(&self) -> &'static [(&'static str, &'static str)] {
        &[]
    }
    /// The animated picture a viewer (the web HMI) draws for this model,
    /// by name (`crane`, `tank-temperature`, `trains`), from the model's
    /// quantities and signals; `None`: the signal panel alone. A viewer
    /// that does not know the name shows the panel too, so a model may
    /// declare a mimic before a viewer draws it.
    fn mimic(&self) -> Option<&'static str> {
        None
    }
}

/// A small deterministic generator (xorshift64*) for models and noise, so
/// runs with the same seed give identical traces.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    pub fn next_u64(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}
