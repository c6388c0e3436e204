//! A3, bottles without a cap (problem 3 of the textbook's chapter 5;
//! processes digest A3).
//!
//! Capped bottles leave the capping stage on belt 1 (`Banda_1`), equally
//! spaced. A photoelectric sensor `F` sees a bottle and an inductive sensor
//! `I` sees its metal cap; both look at the same spot, which is also the
//! ejection zone. The ejector (`Expulzare`) pushes the bottle in front of it
//! sideways onto belt 2 (`Banda_2`), which carries rejects to a bin.
//!
//! Parameters (the digest gives none; chosen so bottles arrive every 2.5 s
//! and the sensors see each one for 0.7 s, many scans):
//! - belt 1 at 0.1 m/s; a new bottle is put on it at x = 0 every 0.25 m of
//!   belt travel (bottle 1 at once); bottles are 70 mm wide;
//! - the sensor spot (and the ejector) at x = 0.5 m: `F` is on while a
//!   bottle's centre is within 35 mm of it, so bottle n first covers it
//!   after 0.465 + 0.25·(n−1) m of travel (4.65 s of running for bottle 1);
//! - bottles leave belt 1 at x = 1.0 m (to the packing: `passed`);
//! - the ejector is single-acting with a spring return: it extends in
//!   0.3 s while `Expulzare` is on and retracts as fast when it is off; at
//!   full extension every bottle in the zone goes onto belt 2;
//! - belt 2 at 0.2 m/s carries a reject 0.6 m to the bin (3 s).
//!
//! Positions are whole nanometres so sensors switch at the same step on
//! every run. Every bottle is capped unless a scenario says otherwise
//! (`bottle capped=0`, `bottle n=5 capped=0 count=4`) or the `capless_rate`
//! parameter draws capless bottles from the [`Rng`].

use super::pneumatic::{positive, Drive};
use super::{q, sig};
use crate::{Dir, Plant, Quantity, Rng, Signal, Value};
use std::collections::VecDeque;

const SIGNALS: &[Signal] = &[
    sig("M", Dir::Operator, "start push-button (belt 1)"),
    sig("R", Dir::Operator, "re-arm push-button"),
    sig(
        "Pc",
        Dir::Operator,
        "reset-to-zero and alarm-off push-button",
    ),
    sig("I", Dir::Sensor, "inductive detector: cap present"),
    sig("F", Dir::Sensor, "photoelectric detector: bottle present"),
    sig("Banda_1", Dir::Actuator, "belt 1 motor (bottles)"),
    sig("Banda_2", Dir::Actuator, "belt 2 motor (rejects)"),
    sig("Alarma", Dir::Actuator, "alarm lamp (Alarmă)"),
    sig("Expulzare", Dir::Actuator, "ejector of capless bottles"),
];

const QUANTITIES: &[Quantity] = &[
    q("bottles", "", "bottles put on belt 1"),
    q("passed", "", "bottles that left belt 1 to the packing"),
    q(
        "capless_passed",
        "",
        "capless bottles that reached the packing (missed)",
    ),
    q("ejected", "", "bottles pushed onto belt 2"),
    q("wrong_ejections", "", "capped bottles pushed onto belt 2"),
    q("on_belt2", "", "rejects on belt 2, not yet in the bin"),
    q("rejected", "", "rejects in the bin"),
    q("travel", "m", "belt 1 travel since the start"),
];

// Signal indices, in the order of SIGNALS.
const BUTTONS: std::ops::Range<usize> = 0..3;
const I: usize = 3;
const F: usize = 4;
const BANDA_1: usize = 5;
const BANDA_2: usize = 6;
const ALARMA: usize = 7;
const EXPULZARE: usize = 8;

const NM_PER_M: f64 = 1e9;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Bottle {
    /// Centre, nm from the infeed of its belt.
    x: i64,
    capped: bool,
}

/// The two belts, the sensors and the ejector.
#[derive(Clone, Debug)]
pub struct Capping {
    belt1: Vec<Bottle>,
    belt2: Vec<Bottle>,
    ejector: Drive,
    /// M, R, Pc as last set.
    buttons: [bool; 3],
    banda_1: bool,
    banda_2: bool,
    alarma: bool,
    /// Belt 1 travel in nm, and where the next bottle is due.
    travel: i64,
    next_at: i64,
    /// Number of the last bottle put on belt 1 (1-based).
    count: u64,
    /// Cap state of the next bottles put on (front first).
    queued: VecDeque<bool>,
    /// Cap state of bottles by number.
    by_number: Vec<(u64, bool)>,
    capless_rate: f64,
    passed: u64,
    capless_passed: u64,
    ejected: u64,
    wrong_ejections: u64,
    rejected: u64,
    // Geometry in nm, speeds in m/s (= nm/ns).
    spacing: i64,
    half_width: i64,
    sensor: i64,
    end1: i64,
    end2: i64,
    speed1: f64,
    speed2: f64,
}

impl Default for Capping {
    fn default() -> Self {
        Capping::new()
    }
}

fn nm(m: f64) -> i64 {
    (m * NM_PER_M).round() as i64
}

impl Capping {
    /// Belts stopped and empty; bottle 1 goes on as soon as belt 1 runs.
    pub fn new() -> Capping {
        Capping {
            belt1: Vec::new(),
            belt2: Vec::new(),
            ejector: Drive::new(0.3),
            buttons: [false; 3],
            banda_1: false,
            banda_2: false,
            alarma: false,
            travel: 0,
            next_at: 0,
            count: 0,
            queued: VecDeque::new(),
            by_number: Vec::new(),
            capless_rate: 0.0,
            passed: 0,
            capless_passed: 0,
            ejected: 0,
            wrong_ejections: 0,
            rejected: 0,
            spacing: nm(0.25),
            half_width: nm(0.035),
            sensor: nm(0.5),
            end1: nm(1.0),
            end2: nm(0.6),
            speed1: 0.1,
            speed2: 0.2,
        }
    }

    /// The bottle in front of the sensors, if any.
    fn at_sensor(&self) -> Option<&Bottle> {
        self.belt1
            .iter()
            .find(|b| (b.x - self.sensor).abs() <= self.half_width)
    }

    /// Puts the next bottle on belt 1 at the infeed.
    fn load(&mut self, rng: &mut Rng) {
        self.count += 1;
        let n = self.count;
        let drawn = self.capless_rate > 0.0 && rng.unit() < self.capless_rate;
        let capped = if let Some(c) = self.queued.pop_front() {
            c
        } else if let Some(&(_, c)) = self.by_number.iter().find(|(k, _)| *k == n) {
            c
        } else {
            !drawn
        };
        self.belt1.push(Bottle { x: 0, capped });
    }

    fn bottle_command(&mut self, args: &[(&str, f64)]) -> Result<(), String> {
        let (mut n, mut capped, mut count) = (None, None, 1u64);
        for &(k, v) in args {
            if !v.is_finite() || v < 0.0 {
                return Err(format!("capping: `{k}` must be a number >= 0"));
            }
            match k {
                "n" if v >= 1.0 => n = Some(v as u64),
                "n" => return Err("capping: bottle numbers start at 1".into()),
                "capped" => capped = Some(v != 0.0),
                "count" => count = (v as u64).clamp(1, 10_000),
                _ => {
                    return Err(format!(
                        "capping: unknown argument `{k}` of `bottle` (known: capped, n, count)"
                    ))
                }
            }
        }
        let capped = capped.ok_or("capping: `bottle` needs `capped=0` or `capped=1`")?;
        match n {
            Some(first) => {
                for k in first..first.saturating_add(count) {
                    self.by_number.retain(|(m, _)| *m != k);
                    self.by_number.push((k, capped));
                }
            }
            None => self.queued.extend((0..count).map(|_| capped)),
        }
        Ok(())
    }

    fn set_param(&mut self, key: &str, v: f64) -> Result<(), String> {
        match key {
            "speed1" => self.speed1 = positive("capping", key, v)?.min(100.0),
            "speed2" => self.speed2 = positive("capping", key, v)?.min(100.0),
            "spacing" => {
                // at least one bottle width, so bottles never overlap
                let s = nm(positive("capping", key, v)?.min(100.0));
                self.spacing = s.max(2 * self.half_width);
            }
            "eject_time" => self.ejector.set_stroke(positive("capping", key, v)?),
            "capless_rate" if (0.0..=1.0).contains(&v) => self.capless_rate = v,
            "capless_rate" => return Err("capping: `capless_rate` must be in 0..1".into()),
            _ => {
                return Err(format!(
                    "capping: unknown parameter `{key}` \
                     (known: speed1, speed2, spacing, eject_time, capless_rate)"
                ))
            }
        }
        Ok(())
    }
}

impl Plant for Capping {
    fn name(&self) -> &'static str {
        "capping"
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
            BANDA_1 => self.banda_1 = on,
            BANDA_2 => self.banda_2 = on,
            ALARMA => self.alarma = on,
            EXPULZARE => {
                self.ejector.advance = on;
                self.ejector.retract = !on;
            }
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
            I => self.at_sensor().is_some_and(|b| b.capped),
            F => self.at_sensor().is_some(),
            BANDA_1 => self.banda_1,
            BANDA_2 => self.banda_2,
            ALARMA => self.alarma,
            EXPULZARE => self.ejector.advance,
            i => self.buttons.get(i).copied().unwrap_or(false),
        })
    }

    fn quantity(&self, index: usize) -> f64 {
        match index {
            0 => self.count as f64,
            1 => self.passed as f64,
            2 => self.capless_passed as f64,
            3 => self.ejected as f64,
            4 => self.wrong_ejections as f64,
            5 => self.belt2.len() as f64,
            6 => self.rejected as f64,
            7 => self.travel as f64 / NM_PER_M,
            _ => 0.0,
        }
    }

    fn step(&mut self, dt_ns: i64, rng: &mut Rng) {
        if self.banda_1 {
            // bottles go on before the belt moves, so bottle 1 starts at 0
            if self.travel >= self.next_at {
                self.load(rng);
                self.next_at = self.next_at.saturating_add(self.spacing);
            }
            let d = (self.speed1 * dt_ns as f64).round() as i64;
            self.travel = self.travel.saturating_add(d);
            for b in &mut self.belt1 {
                b.x = b.x.saturating_add(d);
            }
            let end = self.end1;
            // at most one bottle leaves per step; no allocation otherwise
            while let Some(i) = self.belt1.iter().position(|b| b.x >= end) {
                let gone = self.belt1.remove(i);
                self.passed += 1;
                self.capless_passed += u64::from(!gone.capped);
            }
        }
        if self.banda_2 {
            let d = (self.speed2 * dt_ns as f64).round() as i64;
            for b in &mut self.belt2 {
                b.x = b.x.saturating_add(d);
            }
            let before = self.belt2.len();
            let end = self.end2;
            self.belt2.retain(|b| b.x < end);
            self.rejected += (before - self.belt2.len()) as u64;
        }
        self.ejector.step(dt_ns);
        if self.ejector.extended() {
            let (sensor, w) = (self.sensor, self.half_width);
            let (pushed, kept): (Vec<Bottle>, Vec<Bottle>) =
                self.belt1.iter().partition(|b| (b.x - sensor).abs() <= w);
            self.belt1 = kept;
            self.ejected += pushed.len() as u64;
            self.wrong_ejections += pushed.iter().filter(|b| b.capped).count() as u64;
            self.belt2
                .extend(pushed.into_iter().map(|b| Bottle { x: 0, ..b }));
        }
    }

    fn command(&mut self, name: &str, args: &[(&str, f64)]) -> Result<(), String> {
        match name {
            "set" => args.iter().try_for_each(|(k, v)| self.set_param(k, *v)),
            "bottle" => self.bottle_command(args),
            _ => Err(format!(
                "the capping model has no command `{name}` (known: set, bottle)"
            )),
        }
    }

    fn commands(&self) -> &'static [(&'static str, &'static str)] {
        &[
            (
                "set",
                "parameters: speed1, speed2 (m/s), spacing (m), eject_time (s), capless_rate (0..1)",
            ),
            (
                "bottle",
                "capped=0|1 [n=K] [count=N]: cap state of the next N bottles put on belt 1, \
                 or of bottles K..K+N-1",
            ),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(c: &mut Capping, ms: i64) {
        let mut rng = Rng::new(1);
        for _ in 0..ms {
            c.step(1_000_000, &mut rng);
        }
    }

    fn fi(c: &Capping) -> (bool, bool) {
        (c.get(F).as_bool(), c.get(I).as_bool())
    }

    fn on(c: &mut Capping, signal: usize, v: bool) {
        c.set(signal, Value::Bool(v));
    }

    #[test]
    fn nothing_moves_before_belt_1_runs() {
        let mut c = Capping::new();
        run(&mut c, 1000);
        assert_eq!(c.quantity(0), 0.0);
        assert_eq!(fi(&c), (false, false));
    }

    #[test]
    fn bottles_reach_the_sensors_every_two_and_a_half_seconds() {
        let mut c = Capping::new();
        on(&mut c, BANDA_1, true);
        run(&mut c, 4649);
        assert_eq!(fi(&c), (false, false));
        run(&mut c, 1);
        // 0.465 m: the edge of bottle 1 covers the spot; it is capped
        assert_eq!(fi(&c), (true, true));
        assert_eq!(c.quantity(0), 2.0, "bottle 2 went on at 2.5 s");
        run(&mut c, 700);
        assert_eq!(fi(&c), (true, true));
        run(&mut c, 1);
        assert_eq!(fi(&c), (false, false));
        run(&mut c, 2500 - 701 - 1);
        assert_eq!(fi(&c), (false, false));
        run(&mut c, 1);
        assert_eq!(fi(&c), (true, true));
        // bottle 1 reaches the end of belt 1 after 10 s
        run(&mut c, 10_000 - 7150);
        assert_eq!((c.quantity(1), c.quantity(7)), (1.0, 1.0));
    }

    #[test]
    fn a_capless_bottle_is_seen_by_f_only_and_ejected_onto_belt_2() {
        let mut c = Capping::new();
        assert_eq!(c.command("bottle", &[("n", 2.0), ("capped", 0.0)]), Ok(()));
        on(&mut c, BANDA_1, true);
        run(&mut c, 7150);
        assert_eq!(fi(&c), (true, false), "bottle 2 is capless");
        on(&mut c, BANDA_1, false);
        on(&mut c, EXPULZARE, true);
        run(&mut c, 296);
        assert_eq!(fi(&c), (true, false));
        run(&mut c, 1);
        // 99 % of the 0.3 s stroke: the bottle is off belt 1
        assert_eq!(fi(&c), (false, false));
        assert_eq!(
            (c.quantity(3), c.quantity(4), c.quantity(5)),
            (1.0, 0.0, 1.0)
        );
        on(&mut c, EXPULZARE, false);
        on(&mut c, BANDA_2, true);
        run(&mut c, 2999);
        assert_eq!(c.quantity(6), 0.0);
        run(&mut c, 1);
        assert_eq!((c.quantity(5), c.quantity(6)), (0.0, 1.0));
    }

    #[test]
    fn a_capless_bottle_that_is_not_ejected_counts_as_missed() {
        let mut c = Capping::new();
        assert_eq!(c.command("bottle", &[("capped", 0.0)]), Ok(()));
        on(&mut c, BANDA_1, true);
        run(&mut c, 10_000);
        assert_eq!((c.quantity(1), c.quantity(2)), (1.0, 1.0));
    }

    #[test]
    fn ejecting_a_capped_bottle_is_counted() {
        let mut c = Capping::new();
        on(&mut c, BANDA_1, true);
        run(&mut c, 4800);
        on(&mut c, BANDA_1, false);
        on(&mut c, EXPULZARE, true);
        run(&mut c, 400);
        assert_eq!((c.quantity(3), c.quantity(4)), (1.0, 1.0));
    }

    #[test]
    fn numbered_and_queued_cap_states() {
        let mut c = Capping::new();
        assert_eq!(
            c.command("bottle", &[("n", 3.0), ("capped", 0.0), ("count", 2.0)]),
            Ok(())
        );
        on(&mut c, BANDA_1, true);
        let mut rng = Rng::new(1);
        for _ in 0..5 {
            c.load(&mut rng);
        }
        let caps: Vec<bool> = c.belt1.iter().map(|b| b.capped).collect();
        assert_eq!(caps, [true, true, false, false, true]);
        assert!(c
            .command("bottle", &[("n", 0.0), ("capped", 0.0)])
            .is_err_and(|e| e.contains("start at 1")));
        assert!(c
            .command("bottle", &[("n", 1.0)])
            .is_err_and(|e| e.contains("needs `capped")));
        assert!(c
            .command("bottle", &[("colour", 1.0)])
            .is_err_and(|e| e.contains("unknown argument `colour`")));
    }

    #[test]
    fn capless_rate_draws_from_the_rng_deterministically() {
        let draw = || {
            let mut c = Capping::new();
            assert_eq!(c.command("set", &[("capless_rate", 0.5)]), Ok(()));
            let mut rng = Rng::new(7);
            for _ in 0..40 {
                c.load(&mut rng);
            }
            c.belt1.iter().filter(|b| !b.capped).count()
        };
        let n = draw();
        assert_eq!(n, draw());
        assert!((10..=30).contains(&n), "{n}");
    }

    #[test]
    fn parameters() {
        let mut c = Capping::new();
        assert_eq!(
            c.command(
                "set",
                &[("speed1", 0.2), ("spacing", 0.5), ("eject_time", 1.0)]
            ),
            Ok(())
        );
        on(&mut c, BANDA_1, true);
        run(&mut c, 2325);
        assert!(c.get(F).as_bool());
        assert!(c
            .command("set", &[("capless_rate", 2.0)])
            .is_err_and(|e| e.contains("0..1")));
        assert!(c
            .command("set", &[("speed3", 1.0)])
            .is_err_and(|e| e.contains("unknown parameter `speed3`")));
        assert!(c
            .command("fill", &[])
            .is_err_and(|e| e.contains("no command `fill`")));
    }
}
