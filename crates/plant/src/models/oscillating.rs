//! A2, the oscillating mobile (problem 2 of the textbook's chapter 5;
//! processes digest A2).
//!
//! A carriage ("mobil") runs on a lead screw turned by one reversible motor:
//! contactor `MD` (Cd) drives it right, `MS` (Cs) left. Limit switch `L0`
//! marks the left end, which is the origin, and `L1` the right end. The
//! operator has four push-buttons: `M` (start the oscillation), `P` (stop
//! at the end of the stroke under way), `E` (run back to the origin at once)
//! and `RST` (re-arm after `E`; "R" in the text).
//!
//! Parameters (the digest gives none): a 1 m screw travelled at 0.2 m/s, so
//! one stroke takes 5 s and a full period 10 s, long enough to see in a
//! timing diagram and short enough for a test of three periods in half a
//! minute. A limit switch is on within 1 % of the stroke of its end
//! (digest §0.2). The carriage starts at the origin. The position is a
//! [`Drive`]: the stroke time travelled in whole nanoseconds, so the switches
//! trip at the same step on every run.
//!
//! Both contactors at once do not move the screw (they are interlocked) and
//! count as `conflicts`: a controller bug that scenarios assert never
//! happens. `right_ends`/`left_ends` count arrivals at `L1`/`L0`, so a
//! scenario can assert how many strokes ran. `end_stops` counts collisions
//! with the screw's mechanical ends: each time the motor drives the
//! carriage into the end it has reached (past the switch at 1 %, 50 ms of
//! travel before it).

use super::pneumatic::{positive, Drive};
use super::sig;
use crate::{Dir, Plant, Quantity, Rng, Signal, Value};

const SIGNALS: &[Signal] = &[
    sig("M", Dir::Operator, "start-oscillation push-button"),
    sig(
        "P",
        Dir::Operator,
        "stop push-button (stop at the end of the stroke)",
    ),
    sig(
        "E",
        Dir::Operator,
        "retract-to-origin push-button (immediate)",
    ),
    sig(
        "RST",
        Dir::Operator,
        "restart push-button (R), re-arms after E",
    ),
    sig("L0", Dir::Sensor, "left limit switch (origin)"),
    sig("L1", Dir::Sensor, "right limit switch"),
    sig("MS", Dir::Actuator, "motor to the left (contactor Cs)"),
    sig("MD", Dir::Actuator, "motor to the right (contactor Cd)"),
];

const QUANTITIES: &[Quantity] = &[
    Quantity {
        name: "x",
        unit: "m",
        doc: "carriage position from the origin (left end)",
    },
    Quantity {
        name: "right_ends",
        unit: "",
        doc: "arrivals at the right limit switch L1",
    },
    Quantity {
        name: "left_ends",
        unit: "",
        doc: "arrivals at the left limit switch L0",
    },
    Quantity {
        name: "conflicts",
        unit: "ms",
        doc: "time both contactors were on together",
    },
    Quantity {
        name: "end_stops",
        unit: "",
        doc: "collisions with a mechanical end (the motor driving past a limit switch)",
    },
];

// Signal indices, in the order of SIGNALS.
const BUTTONS: std::ops::Range<usize> = 0..4;
const L0: usize = 4;
const L1: usize = 5;
const MS: usize = 6;
const MD: usize = 7;

/// The carriage and its buttons.
#[derive(Clone, Debug)]
pub struct Oscillating {
    screw: Drive,
    /// Screw length in metres (for `x` only; the switches work on fractions).
    length_m: f64,
    /// M, P, E, RST as last set.
    buttons: [bool; 4],
    right_ends: u64,
    left_ends: u64,
    /// Switch states after the previous step, for counting arrivals.
    was_l0: bool,
    was_l1: bool,
    end_stops: u64,
    /// The motor pushed into an end in the last step (a collision counts
    /// once, when it starts).
    pushing: bool,
}

impl Default for Oscillating {
    fn default() -> Self {
        Oscillating::new()
    }
}

impl Oscillating {
    /// At the origin, motor off: 1 m at 0.2 m/s.
    pub fn new() -> Oscillating {
        Oscillating {
            screw: Drive::new(5.0),
            length_m: 1.0,
            buttons: [false; 4],
            right_ends: 0,
            left_ends: 0,
            was_l0: true,
            was_l1: false,
            end_stops: 0,
            pushing: false,
        }
    }

    fn set_param(&mut self, key: &str, v: f64) -> Result<(), String> {
        match key {
            // The stroke time follows from length / speed; keep the fraction.
            "length" => {
                let speed = self.length_m / self.screw.stroke_s();
                self.length_m = positive("oscillating", key, v)?;
                self.screw.set_stroke(self.length_m / speed);
            }
            "speed" => self
                .screw
                .set_stroke(self.length_m / positive("oscillating", key, v)?),
            "x" if v.is_finite() => self.screw.place(v / self.length_m),
            "x" => return Err("oscillating: `x` must be a finite number".into()),
            _ => {
                return Err(format!(
                    "oscillating: unknown parameter `{key}` (known: length, speed, x)"
                ))
            }
        }
        self.was_l0 = self.screw.retracted();
        self.was_l1 = self.screw.extended();
        Ok(())
    }
}

impl Plant for Oscillating {
    fn name(&self) -> &'static str {
        "oscillating"
    }
    fn signals(&self) -> &'static [Signal] {
        SIGNALS
    }
    fn quantities(&self) -> &'static [Quantity] {
        QUANTITIES
    }

    fn set(&mut self, signal: usize, value: Value) {
        let on = value.as_bool();
        match signal {
            MS => self.screw.retract = on,
            MD => self.screw.advance = on,
            i if BUTTONS.contains(&i) => {
                if let Some(b) = self.buttons.get_mut(i) {
                    *b = on;
                }
            }
            _ => {}
        }
    }

    fn get(&self, signal: usize) -> Value {
        Value::Bool(match signal {
            L0 => self.screw.retracted(),
            L1 => self.screw.extended(),
            MS => self.screw.retract,
            MD => self.screw.advance,
            i => self.buttons.get(i).copied().unwrap_or(false),
        })
    }

    fn quantity(&self, index: usize) -> f64 {
        match index {
            0 => self.screw.fraction() * self.length_m,
            1 => self.right_ends as f64,
            2 => self.left_ends as f64,
            3 => self.screw.conflict_ns as f64 / 1e6,
            4 => self.end_stops as f64,
            _ => 0.0,
        }
    }

    fn step(&mut self, dt_ns: i64, _rng: &mut Rng) {
        self.screw.step(dt_ns);
        let f = self.screw.fraction();
        let (adv, ret) = (self.screw.advance, self.screw.retract);
        let pushing = (adv && !ret && f >= 1.0) || (ret && !adv && f <= 0.0);
        if pushing && !self.pushing {
            self.end_stops += 1;
        }
        self.pushing = pushing;
        let (l0, l1) = (self.screw.retracted(), self.screw.extended());
        if l0 && !self.was_l0 {
            self.left_ends += 1;
        }
        if l1 && !self.was_l1 {
            self.right_ends += 1;
        }
        (self.was_l0, self.was_l1) = (l0, l1);
    }

    fn command(&mut self, name: &str, args: &[(&str, f64)]) -> Result<(), String> {
        match name {
            "set" => args.iter().try_for_each(|(k, v)| self.set_param(k, *v)),
            _ => Err(format!(
                "the oscillating model has no command `{name}` (known: set)"
            )),
        }
    }

    fn commands(&self) -> &'static [(&'static str, &'static str)] {
        &[(
            "set",
            "parameters: length (m), speed (m/s), x (carriage position, m)",
        )]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(o: &mut Oscillating, ms: i64) {
        let mut rng = Rng::new(1);
        for _ in 0..ms {
            o.step(1_000_000, &mut rng);
        }
    }

    fn switches(o: &Oscillating) -> (bool, bool) {
        (o.get(L0).as_bool(), o.get(L1).as_bool())
    }

    #[test]
    fn starts_at_the_origin() {
        let o = Oscillating::new();
        assert_eq!(switches(&o), (true, false));
        assert_eq!(o.quantity(0), 0.0);
    }

    #[test]
    fn a_right_stroke_takes_five_seconds_and_trips_l1_at_99_percent() {
        let mut o = Oscillating::new();
        o.set(MD, Value::Bool(true));
        run(&mut o, 50);
        // 1 % of the stroke = 50 ms: L0 opens after it
        assert_eq!(switches(&o), (true, false));
        run(&mut o, 1);
        assert_eq!(switches(&o), (false, false));
        run(&mut o, 4898);
        assert_eq!(o.quantity(0), 0.9898);
        assert_eq!(switches(&o), (false, false));
        run(&mut o, 1);
        assert_eq!(switches(&o), (false, true));
        assert_eq!(o.quantity(1), 1.0);
        run(&mut o, 1000);
        assert_eq!(o.quantity(0), 1.0);
        assert_eq!(o.quantity(1), 1.0, "staying at the end is one arrival");
    }

    #[test]
    fn driving_into_an_end_counts_one_collision() {
        let mut o = Oscillating::new();
        o.set(MD, Value::Bool(true));
        // L1 at 4950 ms; the end at 5000 ms
        run(&mut o, 4999);
        assert!(o.get(L1).as_bool());
        assert_eq!(o.quantity(4), 0.0);
        run(&mut o, 1);
        assert_eq!(o.quantity(4), 1.0);
        run(&mut o, 300);
        assert_eq!(o.quantity(4), 1.0, "pushing on is one collision");
        // the origin: driving left there is a collision too
        let mut o = Oscillating::new();
        o.set(MS, Value::Bool(true));
        run(&mut o, 1);
        assert_eq!(o.quantity(4), 1.0);
    }

    #[test]
    fn a_full_period_counts_one_arrival_at_each_end() {
        let mut o = Oscillating::new();
        o.set(MD, Value::Bool(true));
        run(&mut o, 5000);
        o.set(MD, Value::Bool(false));
        o.set(MS, Value::Bool(true));
        run(&mut o, 2500);
        assert_eq!(o.quantity(0), 0.5);
        run(&mut o, 2500);
        assert_eq!(switches(&o), (true, false));
        assert_eq!((o.quantity(1), o.quantity(2)), (1.0, 1.0));
    }

    #[test]
    fn both_contactors_do_not_move_and_count_as_conflict() {
        let mut o = Oscillating::new();
        o.set(MD, Value::Bool(true));
        o.set(MS, Value::Bool(true));
        run(&mut o, 120);
        assert_eq!(o.quantity(0), 0.0);
        assert_eq!(o.quantity(3), 120.0);
    }

    #[test]
    fn parameters_and_errors() {
        let mut o = Oscillating::new();
        assert_eq!(o.command("set", &[("length", 2.0), ("speed", 0.5)]), Ok(()));
        o.set(MD, Value::Bool(true));
        run(&mut o, 2000);
        assert_eq!(o.quantity(0), 1.0);
        assert_eq!(o.command("set", &[("x", 2.0)]), Ok(()));
        assert_eq!(switches(&o), (false, true));
        assert!(o
            .command("set", &[("speed", -1.0)])
            .is_err_and(|e| e.contains("greater than 0")));
        assert!(o
            .command("set", &[("height", 1.0)])
            .is_err_and(|e| e.contains("unknown parameter `height`")));
        assert!(o
            .command("go", &[])
            .is_err_and(|e| e.contains("no command `go`")));
    }

    #[test]
    fn buttons_are_kept_as_set() {
        let mut o = Oscillating::new();
        for i in BUTTONS {
            o.set(i, Value::Bool(true));
            assert_eq!(o.get(i), Value::Bool(true));
        }
        // a sensor cannot be set
        o.set(L1, Value::Bool(true));
        assert_eq!(o.get(L1), Value::Bool(false));
    }
}
