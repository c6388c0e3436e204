//! A1, the crane (problem 1 of the textbook's chapter 5; processes digest A1).
//!
//! A gantry crane moves a hook over a rectangle: a horizontal motor (M1,
//! `M1S` to the left, `M1D` to the right) and a vertical motor (M2, `M2S`
//! up, `M2J` down) at constant speed; four limit switches mark the ends
//! (`l1` bottom, `l2` top, `l3` left, `l4` right); the operator starts a
//! cycle with the push-button `Pornire`.
//!
//! Geometry (the digest gives none; chosen so a cycle takes about half a
//! minute, as in the textbook's timing diagram): `x` in metres from the
//! left end (0) to the right end (10 m), `y` from the bottom (0) to the top
//! (5 m); 2 m/s horizontally, 1 m/s vertically. A limit switch is on within
//! 1 % of the stroke of its end (0.1 m horizontally, 0.05 m vertically).
//! The hook stops at the mechanical ends. Positions are kept in whole
//! nanometres so limit switches trip at exactly the same step every run
//! (no drift from adding binary fractions).
//!
//! A motor driven both ways at once does not move (the reversing contactors
//! are interlocked) and counts a `conflicts` step: a controller bug that
//! scenarios assert never happens. `cycles` counts returns to rest
//! position 1 (bottom-left) after having left it. `end_stops` counts
//! collisions with a mechanical end: each time a motor drives the hook
//! into an end it has reached (past its limit switch, which a right program
//! obeys within a scan: 1 % of the stroke is 50 ms of travel).

use super::sig;
use crate::{Dir, Plant, Quantity, Rng, Signal, Value};

const SIGNALS: &[Signal] = &[
    sig("Pornire", Dir::Operator, "start push-button"),
    sig("l1", Dir::Sensor, "lower limit switch (hook at the bottom)"),
    sig("l2", Dir::Sensor, "upper limit switch (hook at the top)"),
    sig("l3", Dir::Sensor, "left limit switch"),
    sig("l4", Dir::Sensor, "right limit switch"),
    sig("M1S", Dir::Actuator, "horizontal motor, to the left"),
    sig("M1D", Dir::Actuator, "horizontal motor, to the right"),
    sig("M2S", Dir::Actuator, "vertical motor, up"),
    sig("M2J", Dir::Actuator, "vertical motor, down"),
];

const QUANTITIES: &[Quantity] = &[
    Quantity {
        name: "x",
        unit: "m",
        doc: "hook position from the left end",
    },
    Quantity {
        name: "y",
        unit: "m",
        doc: "hook height above the bottom",
    },
    Quantity {
        name: "cycles",
        unit: "",
        doc: "returns to rest position 1 after leaving it",
    },
    Quantity {
        name: "conflicts",
        unit: "ms",
        doc: "time a motor was driven both ways at once",
    },
    Quantity {
        name: "end_stops",
        unit: "",
        doc: "collisions with a mechanical end (a motor driving past its limit switch)",
    },
];

// Signal indices, in the order of SIGNALS.
const PORNIRE: usize = 0;
const NM_PER_M: i64 = 1_000_000_000;
const M1S: usize = 5;
const M2J: usize = 8;

/// The crane's state.
#[derive(Clone, Debug)]
pub struct Crane {
    /// Positions in nm.
    x: i64,
    y: i64,
    pornire: bool,
    /// M1S, M1D, M2S, M2J as last set.
    motors: [bool; 4],
    cycles: u64,
    conflict_ns: i64,
    away_from_rest: bool,
    end_stops: u64,
    /// Whether each motor (M1S, M1D, M2S, M2J) pushed into its end in the
    /// last step: a collision counts once, when it starts.
    pushing: [bool; 4],
    /// Travel in nm.
    x_max: i64,
    y_max: i64,
    /// m/s, i.e. nm/ns.
    speed_h: f64,
    speed_v: f64,
}

impl Default for Crane {
    fn default() -> Self {
        Crane::new()
    }
}

impl Crane {
    /// At rest position 1 (bottom-left), motors off.
    pub fn new() -> Crane {
        Crane {
            x: 0,
            y: 0,
            pornire: false,
            motors: [false; 4],
            cycles: 0,
            conflict_ns: 0,
            away_from_rest: false,
            end_stops: 0,
            pushing: [false; 4],
            x_max: 10 * NM_PER_M,
            y_max: 5 * NM_PER_M,
            speed_h: 2.0,
            speed_v: 1.0,
        }
    }

    // A switch is on within 1 % of its end: pos/max <= 1/100 or >= 99/100.
    fn l1(&self) -> bool {
        i128::from(self.y) * 100 <= i128::from(self.y_max)
    }
    fn l2(&self) -> bool {
        i128::from(self.y) * 100 >= i128::from(self.y_max) * 99
    }
    fn l3(&self) -> bool {
        i128::from(self.x) * 100 <= i128::from(self.x_max)
    }
    fn l4(&self) -> bool {
        i128::from(self.x) * 100 >= i128::from(self.x_max) * 99
    }

    /// The travel of a motor driven by `neg`/`pos` at `speed` m/s during
    /// `dt_ns`, in nm (0 when driven both ways or not at all).
    fn travel(neg: bool, pos: bool, speed: f64, dt_ns: i64) -> i64 {
        let d = (speed * dt_ns as f64).round() as i64;
        match (neg, pos) {
            (true, false) => -d,
            (false, true) => d,
            _ => 0,
        }
    }

    fn set_param(&mut self, key: &str, v: f64) -> Result<(), String> {
        if !v.is_finite() {
            return Err(format!("crane: `{key}` must be a finite number"));
        }
        let nm = (v.clamp(0.0, 1e6) * NM_PER_M as f64).round() as i64;
        match key {
            "x" => self.x = nm,
            "y" => self.y = nm,
            "speed_h" if v > 0.0 => self.speed_h = v.min(1e3),
            "speed_v" if v > 0.0 => self.speed_v = v.min(1e3),
            "width" if v > 0.0 => self.x_max = nm,
            "height" if v > 0.0 => self.y_max = nm,
            "speed_h" | "speed_v" | "width" | "height" => {
                return Err(format!("crane: `{key}` must be greater than 0"))
            }
            _ => {
                return Err(format!(
                "crane: unknown parameter `{key}` (known: x, y, speed_h, speed_v, width, height)"
            ))
            }
        }
        self.x = self.x.clamp(0, self.x_max);
        self.y = self.y.clamp(0, self.y_max);
        Ok(())
    }
}

impl Plant for Crane {
    fn name(&self) -> &'static str {
        "crane"
    }
    fn mimic(&self) -> Option<&'static str> {
        Some("crane")
    }
    fn signals(&self) -> &'static [Signal] {
        SIGNALS
    }
    fn quantities(&self) -> &'static [Quantity] {
        QUANTITIES
    }
    fn step_ns(&self) -> i64 {
        1_000_000
    }

    fn set(&mut self, signal: usize, value: Value) {
        let on = value.as_bool();
        match signal {
            PORNIRE => self.pornire = on,
            M1S..=M2J => {
                if let Some(m) = self.motors.get_mut(signal - M1S) {
                    *m = on;
                }
            }
            _ => {}
        }
    }

    fn get(&self, signal: usize) -> Value {
        Value::Bool(match signal {
            PORNIRE => self.pornire,
            1 => self.l1(),
            2 => self.l2(),
            3 => self.l3(),
            4 => self.l4(),
            M1S..=M2J => self.motors.get(signal - M1S).copied().unwrap_or(false),
            _ => false,
        })
    }

    fn quantity(&self, index: usize) -> f64 {
        match index {
            0 => self.x as f64 / NM_PER_M as f64,
            1 => self.y as f64 / NM_PER_M as f64,
            2 => self.cycles as f64,
            3 => self.conflict_ns as f64 / 1e6,
            4 => self.end_stops as f64,
            _ => 0.0,
        }
    }

    fn step(&mut self, dt_ns: i64, _rng: &mut Rng) {
        let [m1s, m1d, m2s, m2j] = self.motors;
        if (m1s && m1d) || (m2s && m2j) {
            self.conflict_ns = self.conflict_ns.saturating_add(dt_ns);
        }
        let dx = Crane::travel(m1s, m1d, self.speed_h, dt_ns);
        let dy = Crane::travel(m2j, m2s, self.speed_v, dt_ns);
        self.x = self.x.saturating_add(dx).clamp(0, self.x_max);
        self.y = self.y.saturating_add(dy).clamp(0, self.y_max);
        // A motor driving (alone in its axis) into the end it stands at.
        let pushing = [
            m1s && !m1d && self.x == 0,
            m1d && !m1s && self.x == self.x_max,
            m2s && !m2j && self.y == self.y_max,
            m2j && !m2s && self.y == 0,
        ];
        for (now, was) in pushing.iter().zip(&self.pushing) {
            if *now && !*was {
                self.end_stops += 1;
            }
        }
        self.pushing = pushing;
        let at_rest = self.l1() && self.l3();
        if !at_rest {
            self.away_from_rest = true;
        } else if self.away_from_rest {
            self.away_from_rest = false;
            self.cycles += 1;
        }
    }

    fn command(&mut self, name: &str, args: &[(&str, f64)]) -> Result<(), String> {
        match name {
            "set" => args.iter().try_for_each(|(k, v)| self.set_param(k, *v)),
            _ => Err(format!(
                "the crane model has no command `{name}` (known: set)"
            )),
        }
    }

    fn commands(&self) -> &'static [(&'static str, &'static str)] {
        &[(
            "set",
            "parameters: x, y (hook position, m), speed_h, speed_v (m/s), width, height (m)",
        )]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const M1D: usize = 6;
    const M2S: usize = 7;

    fn run(c: &mut Crane, ms: i64) {
        let mut rng = Rng::new(1);
        for _ in 0..ms {
            c.step(1_000_000, &mut rng);
        }
    }

    fn switches(c: &Crane) -> [bool; 4] {
        [1, 2, 3, 4].map(|i| c.get(i).as_bool())
    }

    #[test]
    fn starts_at_rest_one() {
        let c = Crane::new();
        assert_eq!(switches(&c), [true, false, true, false]);
        assert_eq!((c.quantity(0), c.quantity(1)), (0.0, 0.0));
    }

    #[test]
    fn moves_up_at_one_metre_per_second_and_trips_l2_at_99_percent() {
        let mut c = Crane::new();
        c.set(M2S, Value::Bool(true));
        run(&mut c, 100);
        assert_eq!(c.quantity(1), 0.1);
        assert_eq!(switches(&c), [false, false, true, false]);
        run(&mut c, 4840);
        // 4.94 m: not yet at the top
        assert!(!c.get(2).as_bool());
        run(&mut c, 10);
        // 4.95 m = 99 % of 5 m
        assert!(c.get(2).as_bool(), "y = {}", c.quantity(1));
        run(&mut c, 2000);
        assert_eq!(c.quantity(1), 5.0);
    }

    #[test]
    fn moves_right_at_two_metres_per_second_and_trips_l4() {
        let mut c = Crane::new();
        c.set(M1D, Value::Bool(true));
        run(&mut c, 4940);
        assert!(!c.get(4).as_bool());
        run(&mut c, 10);
        assert!(c.get(4).as_bool(), "x = {}", c.quantity(0));
        assert_eq!(switches(&c), [true, false, false, true]);
        c.set(M1D, Value::Bool(false));
        c.set(M1S, Value::Bool(true));
        run(&mut c, 5000);
        assert_eq!(c.quantity(0), 0.0);
        assert_eq!(switches(&c), [true, false, true, false]);
    }

    #[test]
    fn both_directions_do_not_move_and_count_as_conflict() {
        let mut c = Crane::new();
        c.set(M2S, Value::Bool(true));
        c.set(M2J, Value::Bool(true));
        run(&mut c, 250);
        assert_eq!(c.quantity(1), 0.0);
        assert_eq!(c.quantity(3), 250.0);
    }

    #[test]
    fn driving_into_an_end_counts_one_collision_each_time() {
        let mut c = Crane::new();
        c.set(M2S, Value::Bool(true));
        // 4.95 m: l2 trips; a right program stops here
        run(&mut c, 4950);
        assert!(c.get(2).as_bool());
        assert_eq!(c.quantity(4), 0.0);
        // 5.0 m after 5 s: the hook hits the top
        run(&mut c, 49);
        assert_eq!(c.quantity(4), 0.0);
        run(&mut c, 1);
        assert_eq!(c.quantity(1), 5.0);
        assert_eq!(c.quantity(4), 1.0);
        // pushing on is the same collision
        run(&mut c, 500);
        assert_eq!(c.quantity(4), 1.0);
        // off and on again: a second one
        c.set(M2S, Value::Bool(false));
        run(&mut c, 10);
        c.set(M2S, Value::Bool(true));
        run(&mut c, 1);
        assert_eq!(c.quantity(4), 2.0);
        // at rest 1 (bottom-left) driving left is a collision too
        let mut c = Crane::new();
        c.set(M1S, Value::Bool(true));
        run(&mut c, 1);
        assert_eq!(c.quantity(4), 1.0);
    }

    #[test]
    fn a_round_trip_counts_one_cycle() {
        let mut c = Crane::new();
        c.set(M2S, Value::Bool(true));
        run(&mut c, 1000);
        assert_eq!(c.quantity(2), 0.0);
        c.set(M2S, Value::Bool(false));
        c.set(M2J, Value::Bool(true));
        run(&mut c, 1000);
        assert_eq!(c.quantity(2), 1.0);
    }

    #[test]
    fn parameters_and_unknown_commands() {
        let mut c = Crane::new();
        assert_eq!(c.command("set", &[("x", 10.0), ("y", 2.0)]), Ok(()));
        assert_eq!(switches(&c), [false, false, false, true]);
        assert!(c
            .command("set", &[("speed_h", 0.0)])
            .is_err_and(|e| e.contains("greater than 0")));
        assert!(c
            .command("set", &[("depth", 1.0)])
            .is_err_and(|e| e.contains("unknown parameter `depth`")));
        assert!(c
            .command("jump", &[])
            .is_err_and(|e| e.contains("no command `jump`")));
    }

    #[test]
    fn pornire_is_kept_as_set() {
        let mut c = Crane::new();
        c.set(PORNIRE, Value::Bool(true));
        assert_eq!(c.get(PORNIRE), Value::Bool(true));
        c.set(PORNIRE, Value::Bool(false));
        assert_eq!(c.get(PORNIRE), Value::Bool(false));
    }
}
