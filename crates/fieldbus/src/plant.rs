//! A virtual plant as a Modbus TCP device (`automat plant NAME
//! --modbus-server ADDR:PORT`), so any PLC can control it.
//!
//! The map follows the model's signal order ([`PlantMap::of`]): BOOL
//! sensors and operator signals are discrete inputs 0, 1, …; BOOL
//! actuators are coils 0, 1, …, then the BOOL operator signals follow as
//! coils too (an HMI or a test presses a button by writing its coil, the
//! PLC reads it as a discrete input); integer sensors are one input
//! register each (0..=65535, a negative value in two's complement), real
//! sensors two (IEEE 754 single, high word first), then every observable
//! quantity as a real; integer and real actuators likewise in the
//! holding registers. The plant advances in real time (× `speed`) in its
//! own step on the caller's thread; the server threads only copy values.

use crate::pdu::{Exception, Table};
use crate::server::Device;
use automat_plant::{Dir, Kind, Plant, Rng, Value};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// What one Modbus address carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Item {
    /// A signal (index into `signals()`).
    Signal(usize),
    /// Word `word` (0 = high) of a real or integer signal of `width`
    /// registers.
    SignalWord { signal: usize, word: u8, width: u8 },
    /// Word `word` of a quantity, as a real.
    QuantityWord { quantity: usize, word: u8 },
}

/// The device's four tables.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PlantMap {
    pub coils: Vec<Item>,
    pub discrete: Vec<Item>,
    pub input: Vec<Item>,
    pub holding: Vec<Item>,
}

fn words(list: &mut Vec<Item>, signal: usize, kind: Kind) {
    let width = if kind == Kind::Real { 2 } else { 1 };
    for word in 0..width {
        list.push(Item::SignalWord {
            signal,
            word,
            width,
        });
    }
}

impl PlantMap {
    pub fn of(plant: &dyn Plant) -> PlantMap {
        let mut m = PlantMap::default();
        let signals = plant.signals();
        for (i, s) in signals.iter().enumerate() {
            match (s.dir, s.kind) {
                (Dir::Sensor | Dir::Operator, Kind::Bool) => m.discrete.push(Item::Signal(i)),
                (Dir::Actuator, Kind::Bool) => m.coils.push(Item::Signal(i)),
                (Dir::Sensor | Dir::Operator, k) => words(&mut m.input, i, k),
                (Dir::Actuator, k) => words(&mut m.holding, i, k),
            }
        }
        for (i, s) in signals.iter().enumerate() {
            if s.dir == Dir::Operator {
                match s.kind {
                    Kind::Bool => m.coils.push(Item::Signal(i)),
                    k => words(&mut m.holding, i, k),
                }
            }
        }
        for q in 0..plant.quantities().len() {
            for word in 0..2 {
                m.input.push(Item::QuantityWord { quantity: q, word });
            }
        }
        m
    }

    /// The map for people, one line per address range of a value.
    pub fn describe(&self, plant: &dyn Plant) -> String {
        let signals = plant.signals();
        let quantities = plant.quantities();
        let mut out = String::new();
        for (title, table) in [
            ("coils (FC 1, 5, 15)", &self.coils),
            ("discrete inputs (FC 2)", &self.discrete),
            ("input registers (FC 4)", &self.input),
            ("holding registers (FC 3, 6, 16)", &self.holding),
        ] {
            out.push_str(&format!("{title}:\n"));
            if table.is_empty() {
                out.push_str("  (none)\n");
            }
            for (a, item) in table.iter().enumerate() {
                let line = match *item {
                    Item::Signal(i) => signals.get(i).map(|s| {
                        format!("  {a:>5}  {:<12} BOOL  {:?}: {}\n", s.name, s.dir, s.doc)
                    }),
                    Item::SignalWord {
                        signal,
                        word: 0,
                        width,
                    } => signals.get(signal).map(|s| {
                        let (ty, range) = if width == 2 {
                            ("REAL", format!("{a}-{}", a + 1))
                        } else {
                            ("INT ", a.to_string())
                        };
                        format!(
                            "  {range:>5}  {:<12} {ty}  {:?}: {}\n",
                            s.name, s.dir, s.doc
                        )
                    }),
                    Item::QuantityWord { quantity, word: 0 } => quantities.get(quantity).map(|q| {
                        format!(
                            "  {:>5}  {:<12} REAL  quantity [{}]: {}\n",
                            format!("{a}-{}", a + 1),
                            format!("plant.{}", q.name),
                            q.unit,
                            q.doc
                        )
                    }),
                    _ => None,
                };
                out.push_str(&line.unwrap_or_default());
            }
        }
        out.push_str("REAL values: IEEE 754 single precision, high word first.\n");
        out
    }
}

/// Values shared by the plant's loop and the server's threads.
#[derive(Debug)]
struct State {
    values: Vec<Value>,
    quantities: Vec<f64>,
    /// Writes from clients not yet given to the plant.
    pending: Vec<Option<Value>>,
}

/// The plant's side of the server.
pub struct PlantDevice {
    pub map: PlantMap,
    kinds: Vec<Kind>,
    writable: Vec<bool>,
    state: Mutex<State>,
}

fn lock(m: &Mutex<State>) -> std::sync::MutexGuard<'_, State> {
    m.lock().unwrap_or_else(|p| p.into_inner())
}

fn int_word(v: i64) -> u16 {
    v.clamp(-32_768, 65_535) as i32 as u16
}

fn real_word(v: f64, word: u8) -> u16 {
    let bits = (v as f32).to_bits();
    if word == 0 {
        (bits >> 16) as u16
    } else {
        bits as u16
    }
}

impl PlantDevice {
    pub fn new(plant: &dyn Plant) -> PlantDevice {
        let signals = plant.signals();
        PlantDevice {
            map: PlantMap::of(plant),
            kinds: signals.iter().map(|s| s.kind).collect(),
            writable: signals.iter().map(|s| s.dir != Dir::Sensor).collect(),
            state: Mutex::new(State {
                values: (0..signals.len()).map(|i| plant.get(i)).collect(),
                quantities: (0..plant.quantities().len())
                    .map(|q| plant.quantity(q))
                    .collect(),
                pending: vec![None; signals.len()],
            }),
        }
    }

    fn table(&self, t: Table) -> &[Item] {
        match t {
            Table::Coils => &self.map.coils,
            Table::DiscreteInputs => &self.map.discrete,
            Table::InputRegisters => &self.map.input,
            Table::HoldingRegisters => &self.map.holding,
        }
    }

    fn items(&self, t: Table, addr: u16, count: usize) -> Result<&[Item], Exception> {
        self.table(t)
            .get(usize::from(addr)..usize::from(addr) + count)
            .ok_or(Exception::IllegalDataAddress)
    }

    /// The value a signal shows: a pending write, else the plant's.
    fn current(s: &State, i: usize) -> Value {
        s.pending
            .get(i)
            .copied()
            .flatten()
            .or_else(|| s.values.get(i).copied())
            .unwrap_or(Value::Bool(false))
    }

    /// Gives the writes of clients to the plant and takes its new values.
    pub fn exchange(&self, plant: &mut dyn Plant) {
        let mut s = lock(&self.state);
        for (i, p) in s.pending.iter_mut().enumerate() {
            if let Some(v) = p.take() {
                plant.set(i, v);
            }
        }
        for (i, v) in s.values.iter_mut().enumerate() {
            *v = plant.get(i);
        }
        for (q, v) in s.quantities.iter_mut().enumerate() {
            *v = plant.quantity(q);
        }
    }
}

impl Device for PlantDevice {
    fn read_bits(&self, table: Table, addr: u16, count: u16) -> Result<Vec<bool>, Exception> {
        let items = self.items(table, addr, usize::from(count))?;
        let s = lock(&self.state);
        Ok(items
            .iter()
            .map(|it| match it {
                Item::Signal(i) => Self::current(&s, *i).as_bool(),
                _ => false,
            })
            .collect())
    }

    fn read_registers(&self, table: Table, addr: u16, count: u16) -> Result<Vec<u16>, Exception> {
        let items = self.items(table, addr, usize::from(count))?;
        let s = lock(&self.state);
        Ok(items
            .iter()
            .map(|it| match *it {
                Item::SignalWord {
                    signal,
                    word,
                    width,
                } => match (Self::current(&s, signal), width) {
                    (v, 2) => real_word(v.as_f64(), word),
                    (Value::Int(i), _) => int_word(i),
                    (v, _) => int_word(v.as_f64().round() as i64),
                },
                Item::QuantityWord { quantity, word } => {
                    real_word(s.quantities.get(quantity).copied().unwrap_or(0.0), word)
                }
                Item::Signal(_) => 0,
            })
            .collect())
    }

    fn write_coils(&self, addr: u16, values: &[bool]) -> Result<(), Exception> {
        let items = self.items(Table::Coils, addr, values.len())?;
        let mut s = lock(&self.state);
        for (it, v) in items.iter().zip(values) {
            if let Item::Signal(i) = it {
                if let Some(p) = s.pending.get_mut(*i) {
                    *p = Some(Value::Bool(*v));
                }
            }
        }
        Ok(())
    }

    fn write_registers(&self, addr: u16, values: &[u16]) -> Result<(), Exception> {
        let items = self.items(Table::HoldingRegisters, addr, values.len())?;
        let mut s = lock(&self.state);
        // A real is taken whole or not at all: both its words in this write.
        for (k, (it, v)) in items.iter().zip(values).enumerate() {
            let Item::SignalWord {
                signal,
                word,
                width,
            } = *it
            else {
                continue;
            };
            if !self.writable.get(signal).copied().unwrap_or(false) {
                return Err(Exception::IllegalDataAddress);
            }
            let value = if width == 2 {
                if word != 0 {
                    continue;
                }
                let Some(low) = values.get(k + 1) else {
                    return Err(Exception::IllegalDataValue);
                };
                Value::Real(f64::from(f32::from_bits(
                    (u32::from(*v) << 16) | u32::from(*low),
                )))
            } else if self.kinds.get(signal) == Some(&Kind::Real) {
                Value::Real(f64::from(*v))
            } else {
                Value::Int(i64::from(*v))
            };
            if let Some(p) = s.pending.get_mut(signal) {
                *p = Some(value);
            }
        }
        Ok(())
    }
}

/// Runs `plant` in real time × `speed` until `stop` (or `duration` of
/// wall time), exchanging values with `dev` every step.
pub fn run(
    plant: &mut dyn Plant,
    dev: &Arc<PlantDevice>,
    seed: u64,
    speed: f64,
    stop: &AtomicBool,
    duration: Option<Duration>,
) {
    let step = plant.step_ns().max(1);
    let mut rng = Rng::new(seed);
    let start = Instant::now();
    let mut t: i64 = 0;
    while !stop.load(Ordering::Relaxed) {
        let wall = start.elapsed();
        if duration.is_some_and(|d| wall >= d) {
            break;
        }
        let now = (wall.as_nanos() as f64 * speed) as i64;
        dev.exchange(plant);
        let mut n = 0;
        while t.saturating_add(step) <= now && n < 100_000 {
            plant.step(step, &mut rng);
            t += step;
            n += 1;
        }
        if n >= 100_000 {
            // Far behind (a stalled machine): do not try to catch up.
            t = now;
        }
        dev.exchange(plant);
        std::thread::sleep(Duration::from_millis(1));
    }
}
