//! Part C, three model trains on their own tracks (the Polish TSX Micro /
//! PL7 lab; processes digest Part C).
//!
//! Each locomotive runs on an independent straight track with an end
//! sensor at each end (`Left1`/`Right1` = %I1.0/%I1.1, ... ). The PLC
//! gives each train a direction bit (`Dir1` = %Q2.0, TRUE = right) and a
//! speed word 0…10000 (`Speed1` = %QW4.0 in PL7).
//!
//! Parameters, as the digest proposes: a track of 1 m; an end sensor is on
//! while the train is within 2 cm of its end; below a speed word of 4000
//! the train does not move (rolling resistance), above it
//! v = 0.05 m/s + 0.3 m/s · (word − 4000) / 6000 (0.15 m/s at 6000,
//! 0.35 m/s at 10000). Words outside 0…10000 are clamped. Buffer stops
//! stand 5 cm beyond each end: reaching one is a crash (counted once per
//! contact) and the train stops there. The trains start at 0.5, 0.3 and
//! 0.7 m from the left end.
//!
//! `dir_faults` counts direction changes while the train was moving (the
//! source: the direction bit only changes while the speed is 0).

use super::q;
use crate::{Dir, Kind, Plant, Quantity, Rng, Signal, Value};

const SIGNALS: &[Signal] = &[
    s(
        "Left1",
        Dir::Sensor,
        Kind::Bool,
        "track 1, left end sensor (%I1.0)",
    ),
    s(
        "Right1",
        Dir::Sensor,
        Kind::Bool,
        "track 1, right end sensor (%I1.1)",
    ),
    s(
        "Left2",
        Dir::Sensor,
        Kind::Bool,
        "track 2, left end sensor (%I1.2)",
    ),
    s(
        "Right2",
        Dir::Sensor,
        Kind::Bool,
        "track 2, right end sensor (%I1.3)",
    ),
    s(
        "Left3",
        Dir::Sensor,
        Kind::Bool,
        "track 3, left end sensor (%I1.4)",
    ),
    s(
        "Right3",
        Dir::Sensor,
        Kind::Bool,
        "track 3, right end sensor (%I1.5)",
    ),
    s(
        "Dir1",
        Dir::Actuator,
        Kind::Bool,
        "train 1 direction, TRUE = right (%Q2.0)",
    ),
    s(
        "Dir2",
        Dir::Actuator,
        Kind::Bool,
        "train 2 direction (%Q2.1)",
    ),
    s(
        "Dir3",
        Dir::Actuator,
        Kind::Bool,
        "train 3 direction (%Q2.2)",
    ),
    s(
        "Speed1",
        Dir::Actuator,
        Kind::Int,
        "train 1 speed word 0..10000 (%QW4.0)",
    ),
    s(
        "Speed2",
        Dir::Actuator,
        Kind::Int,
        "train 2 speed word (%QW4.1)",
    ),
    s(
        "Speed3",
        Dir::Actuator,
        Kind::Int,
        "train 3 speed word (%QW4.2)",
    ),
];

const fn s(name: &'static str, dir: Dir, kind: Kind, doc: &'static str) -> Signal {
    Signal {
        name,
        dir,
        kind,
        doc,
    }
}

const QUANTITIES: &[Quantity] = &[
    q("x1", "m", "train 1 position from the left end"),
    q("x2", "m", "train 2 position"),
    q("x3", "m", "train 3 position"),
    q("v1", "m/s", "train 1 speed (signed, + = right)"),
    q("v2", "m/s", "train 2 speed"),
    q("v3", "m/s", "train 3 speed"),
    q(
        "trips1",
        "",
        "train 1: arrivals at the end opposite to its previous one",
    ),
    q("trips2", "", "train 2: arrivals"),
    q("trips3", "", "train 3: arrivals"),
    q("crashes", "", "trains that ran into a buffer stop"),
    q("dir_faults", "", "direction changes while moving"),
];

const DIR1: usize = 6;
const SPEED1: usize = 9;
const UM_PER_M: i64 = 1_000_000;
const SENSOR_UM: i64 = 20_000;
const BUFFER_UM: i64 = 50_000;

#[derive(Clone, Debug, Default)]
struct Train {
    x: i64,
    right: bool,
    word: i64,
    /// µm/s of the last step, signed.
    v: i64,
    /// The end last reached: 0 none, -1 left, 1 right.
    last_end: i8,
    trips: u32,
    at_buffer: bool,
}

#[derive(Clone, Debug)]
pub struct Trains {
    t: [Train; 3],
    len: i64,
    crashes: u32,
    dir_faults: u32,
}

impl Default for Trains {
    fn default() -> Self {
        Trains::new()
    }
}

/// µm/s for a speed word.
fn speed(word: i64) -> i64 {
    let w = word.clamp(0, 10_000);
    if w < 4_000 {
        0
    } else {
        50_000 + 300_000 * (w - 4_000) / 6_000
    }
}

impl Trains {
    pub fn new() -> Trains {
        let at = |x| Train {
            x,
            ..Train::default()
        };
        Trains {
            t: [at(500_000), at(300_000), at(700_000)],
            len: UM_PER_M,
            crashes: 0,
            dir_faults: 0,
        }
    }

    fn left(&self, i: usize) -> bool {
        self.t.get(i).is_some_and(|t| t.x.abs() <= SENSOR_UM)
    }
    fn right(&self, i: usize) -> bool {
        self.t
            .get(i)
            .is_some_and(|t| (t.x - self.len).abs() <= SENSOR_UM)
    }

    fn set_param(&mut self, key: &str, v: f64) -> Result<(), String> {
        if !v.is_finite() {
            return Err(format!("trains: `{key}` must be a finite number"));
        }
        let um = (v.clamp(-0.05, 100.0) * UM_PER_M as f64).round() as i64;
        match key {
            "x1" | "x2" | "x3" => {
                let i = usize::from(key.as_bytes().get(1).copied().unwrap_or(b'1') - b'1');
                if let Some(t) = self.t.get_mut(i) {
                    t.x = um.clamp(-BUFFER_UM, self.len + BUFFER_UM);
                }
            }
            "length" if v >= 0.1 => self.len = um,
            "length" => return Err("trains: `length` must be at least 0.1 m".into()),
            _ => {
                return Err(format!(
                    "trains: unknown parameter `{key}` (known: x1, x2, x3 (m), length (m))"
                ))
            }
        }
        Ok(())
    }
}

impl Plant for Trains {
    fn name(&self) -> &'static str {
        "trains"
    }
    fn mimic(&self) -> Option<&'static str> {
        Some("trains")
    }
    fn signals(&self) -> &'static [Signal] {
        SIGNALS
    }
    fn quantities(&self) -> &'static [Quantity] {
        QUANTITIES
    }

    fn set(&mut self, signal: usize, value: Value) {
        match signal {
            DIR1..=8 => {
                if let Some(t) = self.t.get_mut(signal - DIR1) {
                    let right = value.as_bool();
                    if right != t.right && t.v != 0 {
                        self.dir_faults += 1;
                    }
                    t.right = right;
                }
            }
            SPEED1..=11 => {
                if let Some(t) = self.t.get_mut(signal - SPEED1) {
                    t.word = match value {
                        Value::Bool(b) => i64::from(b),
                        Value::Int(i) => i,
                        Value::Real(r) if r.is_finite() => r.round().clamp(-1e9, 1e9) as i64,
                        Value::Real(_) => 0,
                    };
                }
            }
            _ => {}
        }
    }

    fn get(&self, signal: usize) -> Value {
        match signal {
            0..=5 if signal.is_multiple_of(2) => Value::Bool(self.left(signal / 2)),
            0..=5 => Value::Bool(self.right(signal / 2)),
            DIR1..=8 => Value::Bool(self.t.get(signal - DIR1).is_some_and(|t| t.right)),
            SPEED1..=11 => Value::Int(self.t.get(signal - SPEED1).map_or(0, |t| t.word)),
            _ => Value::Bool(false),
        }
    }

    fn quantity(&self, index: usize) -> f64 {
        let t = |i: usize| self.t.get(i % 3).cloned().unwrap_or_default();
        match index {
            0..=2 => t(index).x as f64 / UM_PER_M as f64,
            3..=5 => t(index).v as f64 / UM_PER_M as f64,
            6..=8 => f64::from(t(index).trips),
            9 => f64::from(self.crashes),
            10 => f64::from(self.dir_faults),
            _ => 0.0,
        }
    }

    fn step(&mut self, dt_ns: i64, _rng: &mut Rng) {
        let len = self.len;
        for t in &mut self.t {
            let v = speed(t.word) * if t.right { 1 } else { -1 };
            let dx = (i128::from(v) * i128::from(dt_ns) / 1_000_000_000) as i64;
            let x = t.x + dx;
            let hit = x <= -BUFFER_UM || x >= len + BUFFER_UM;
            if hit && !t.at_buffer {
                self.crashes += 1;
            }
            t.at_buffer = hit;
            t.x = x.clamp(-BUFFER_UM, len + BUFFER_UM);
            t.v = if hit { 0 } else { v };
            let end = if t.x.abs() <= SENSOR_UM {
                -1
            } else if (t.x - len).abs() <= SENSOR_UM {
                1
            } else {
                0
            };
            if end != 0 && end != t.last_end {
                if t.last_end != 0 {
                    t.trips += 1;
                }
                t.last_end = end;
            }
        }
    }

    fn command(&mut self, name: &str, args: &[(&str, f64)]) -> Result<(), String> {
        match name {
            "set" => args.iter().try_for_each(|(k, v)| self.set_param(k, *v)),
            _ => Err(format!(
                "the trains model has no command `{name}` (known: set)"
            )),
        }
    }

    fn commands(&self) -> &'static [(&'static str, &'static str)] {
        &[(
            "set",
            "parameters: x1, x2, x3 (train positions, m), length (track, m)",
        )]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(p: &mut Trains, ms: i64) {
        let mut rng = Rng::new(1);
        for _ in 0..ms {
            p.step(1_000_000, &mut rng);
        }
    }

    #[test]
    fn signal_table_matches_the_indices() {
        assert_eq!(SIGNALS.get(DIR1).map(|s| s.name), Some("Dir1"));
        assert_eq!(SIGNALS.get(SPEED1).map(|s| s.name), Some("Speed1"));
        assert_eq!(SIGNALS.get(5).map(|s| s.name), Some("Right3"));
    }

    #[test]
    fn speed_curve() {
        assert_eq!(speed(3_999), 0);
        assert_eq!(speed(4_000), 50_000);
        assert_eq!(speed(6_000), 150_000);
        assert_eq!(speed(10_000), 350_000);
        assert_eq!(speed(99_999), 350_000);
        assert_eq!(speed(-5), 0);
    }

    #[test]
    fn runs_left_to_the_sensor_and_right_to_the_other() {
        let mut p = Trains::new();
        p.set(SPEED1, Value::Int(6_000));
        // 0.5 m to 0.02 m at 0.15 m/s = 3.2 s
        run(&mut p, 3_199);
        assert_eq!(p.get(0), Value::Bool(false));
        run(&mut p, 1);
        assert_eq!(p.get(0), Value::Bool(true));
        assert_eq!(p.quantity(0), 0.02);
        assert_eq!(p.quantity(3), -0.15);
        p.set(SPEED1, Value::Int(0));
        run(&mut p, 1);
        p.set(DIR1, Value::Bool(true));
        p.set(SPEED1, Value::Int(10_000));
        run(&mut p, 2_743);
        assert_eq!(p.get(1), Value::Bool(true), "x = {}", p.quantity(0));
        assert_eq!(p.quantity(6), 1.0);
        assert_eq!(p.quantity(10), 0.0);
        // the others did not move
        assert_eq!((p.quantity(1), p.quantity(2)), (0.3, 0.7));
    }

    #[test]
    fn a_weak_word_does_not_move_the_train() {
        let mut p = Trains::new();
        p.set(SPEED1 + 1, Value::Int(3_999));
        run(&mut p, 1_000);
        assert_eq!(p.quantity(1), 0.3);
    }

    #[test]
    fn buffer_stop_crash_and_direction_fault() {
        let mut p = Trains::new();
        p.set(SPEED1 + 2, Value::Int(10_000));
        p.set(DIR1 + 2, Value::Bool(true));
        run(&mut p, 1_000);
        // 0.7 + 0.35 = 1.05: at the buffer
        assert_eq!(p.quantity(9), 1.0);
        assert_eq!(p.quantity(2), 1.05);
        run(&mut p, 1_000);
        assert_eq!(p.quantity(9), 1.0);
        p.set(DIR1 + 1, Value::Bool(true));
        assert_eq!(p.quantity(10), 0.0);
        p.set(SPEED1 + 1, Value::Int(5_000));
        run(&mut p, 10);
        p.set(DIR1 + 1, Value::Bool(false));
        assert_eq!(p.quantity(10), 1.0);
    }

    #[test]
    fn parameters() {
        let mut p = Trains::new();
        assert!(p.command("set", &[("x2", 0.01)]).is_ok());
        assert_eq!(p.get(2), Value::Bool(true));
        assert!(p.command("set", &[("length", 0.0)]).is_err());
        assert!(p.command("set", &[("x9", 0.0)]).is_err());
        assert!(p.command("go", &[]).is_err());
    }
}
