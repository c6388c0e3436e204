//! A5, the package elevator / classifier (problem 5 of the textbook's
//! chapter 5; processes digest A5).
//!
//! Packages come in on belt 0 (`Banda_0`) onto a weighing section whose
//! transducer (`traductor_cantar`, 4–20 mA → 819..4095 for 0..100) tells
//! small from large; photocell `Foto_0` sees a package there. Belt 1
//! (`Banda_1`) carries it to the elevator platform (`Foto_1`); cylinder C
//! (`C_ridicare`/`C_coborare`, switches `C0`/`C1`) lifts it; at the top
//! cylinder A (`A_avansat`/`A_retras`, `A0`/`A1`) pushes small packages onto
//! belt 2 and cylinder B (`B_avansat`/`B_retras`, `B0`/`B1`) large ones onto
//! belt 3. All cylinders are double-acting on closed-centre valves
//! ([`Drive`]): neither coil = stand still, both = a `conflicts` fault.
//!
//! Geometry and timing (the digest gives none; chosen to be plain and
//! slow enough to watch): positions are package centres along the line,
//! in metres from the infeed. Belt 0 runs from 0 to 1.1 m, the weighing
//! section is 0.8..1.2 m and `Foto_0` sees a centre within 0.9..1.1 m; belt 1
//! runs from 1.1 m to the platform at 2.0 m. Both belts move at 0.2 m/s; a
//! package is 0.2 m long and needs 0.05 m of gap to the one ahead. A package
//! goes onto the platform when its centre reaches 1.95 m with the platform
//! down and empty (before that it waits at 1.8 m). The scale reading rises
//! linearly to the weight in 0.2 s after a package comes onto the section
//! (the digest's 0.5 s settling time is longer). Strokes: A and B 0.8 s,
//! C 1.5 s. A package leaves the platform when A or B is fully advanced with
//! the platform fully up; it counts as `missorted` if it went the wrong way
//! (small: 5..40, large: over 40, as the digest's suggested constants).
//!
//! What a wrong program does to the machine is counted: `collisions`, each
//! lowering of the platform (C retracting) while pusher A or B is not
//! retracted (the pusher stands over the shaft); `jams`, each package
//! pushed onto belt 2 or 3 while the one before still lies at its head.
//! Belts 2 and 3 run at the line's speed: a package clears the head after
//! 1.25 s of running (its 0.2 m and a 0.05 m gap).

use super::pneumatic::{positive, Drive};
use super::q;
use super::tank_temperature::raw_4_20;
use crate::{Dir, Kind, Plant, Quantity, Rng, Signal, Value};
use std::collections::VecDeque;

const SIGNALS: &[Signal] = &[
    sig("Foto_0", Dir::Sensor, Kind::Bool, "package on the scale"),
    sig(
        "Foto_1",
        Dir::Sensor,
        Kind::Bool,
        "package on the platform (down)",
    ),
    sig("A0", Dir::Sensor, Kind::Bool, "cylinder A retracted"),
    sig("A1", Dir::Sensor, Kind::Bool, "cylinder A advanced"),
    sig("B0", Dir::Sensor, Kind::Bool, "cylinder B retracted"),
    sig("B1", Dir::Sensor, Kind::Bool, "cylinder B advanced"),
    sig("C0", Dir::Sensor, Kind::Bool, "cylinder C (platform) down"),
    sig("C1", Dir::Sensor, Kind::Bool, "cylinder C (platform) up"),
    sig(
        "traductor_cantar",
        Dir::Sensor,
        Kind::Int,
        "scale transducer, raw 819..4095 (0..100)",
    ),
    sig(
        "Banda_0",
        Dir::Actuator,
        Kind::Bool,
        "belt 0 (infeed and scale)",
    ),
    sig(
        "Banda_1",
        Dir::Actuator,
        Kind::Bool,
        "belt 1 (to the platform)",
    ),
    sig(
        "Banda_2",
        Dir::Actuator,
        Kind::Bool,
        "belt 2 (small packages)",
    ),
    sig(
        "Banda_3",
        Dir::Actuator,
        Kind::Bool,
        "belt 3 (large packages)",
    ),
    sig("A_avansat", Dir::Actuator, Kind::Bool, "advance cylinder A"),
    sig("A_retras", Dir::Actuator, Kind::Bool, "retract cylinder A"),
    sig("B_avansat", Dir::Actuator, Kind::Bool, "advance cylinder B"),
    sig("B_retras", Dir::Actuator, Kind::Bool, "retract cylinder B"),
    sig(
        "C_ridicare",
        Dir::Actuator,
        Kind::Bool,
        "raise the platform",
    ),
    sig(
        "C_coborare",
        Dir::Actuator,
        Kind::Bool,
        "lower the platform (coborâre)",
    ),
];

const fn sig(name: &'static str, dir: Dir, kind: Kind, doc: &'static str) -> Signal {
    Signal {
        name,
        dir,
        kind,
        doc,
    }
}

const QUANTITIES: &[Quantity] = &[
    q("queue", "", "packages waiting at the infeed"),
    q("on_line", "", "packages on belts 0 and 1 and the platform"),
    q("small_out", "", "packages pushed onto belt 2"),
    q("large_out", "", "packages pushed onto belt 3"),
    q("missorted", "", "packages pushed onto the wrong belt"),
    q("weight", "", "scale reading, 0..100"),
    q("platform", "", "platform height: 0 down .. 1 up"),
    q("conflicts", "ms", "time a cylinder had both coils on"),
    q("removed", "", "packages taken off the scale by hand"),
    q(
        "collisions",
        "",
        "platform lowered while pusher A or B was not retracted",
    ),
    q(
        "jams",
        "",
        "packages pushed onto belt 2 or 3 onto the one before",
    ),
];

// Signal indices, in the order of SIGNALS.
const FOTO_0: usize = 0;
const FOTO_1: usize = 1;
const TRADUCTOR: usize = 8;
const BANDA_0: usize = 9;
const BANDA_3: usize = 12;
const A_AVANSAT: usize = 13;
const C_COBORARE: usize = 18;

/// Small (true) or large by the digest's limits; None for an underweight
/// (error) package.
fn is_small(weight: f64) -> Option<bool> {
    if weight < 5.0 {
        None
    } else {
        Some(weight <= 40.0)
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
struct Package {
    /// Centre, nm from the infeed.
    p: i64,
    weight: f64,
}

/// The classifier.
#[derive(Clone, Debug)]
pub struct Sorter {
    /// Packages on belts 0 and 1, front (largest p) first.
    line: Vec<Package>,
    platform: Option<Package>,
    queue: VecDeque<f64>,
    /// A, B, C.
    cyl: [Drive; 3],
    /// Banda_0..Banda_3 as last set.
    belts: [bool; 4],
    /// Time the package now on the weighing section has been there.
    on_scale_ns: i64,
    small_out: u64,
    large_out: u64,
    missorted: u64,
    removed: u64,
    speed: f64,
    collisions: u64,
    /// Lowering onto a pusher in the last step (counted when it starts).
    colliding: bool,
    jams: u64,
    /// Belt running time still needed to clear the heads of belts 2 and 3.
    head_busy_ns: [i64; 2],
}

impl Default for Sorter {
    fn default() -> Self {
        Sorter::new()
    }
}

// Geometry, nm.
const BELT0_END: i64 = 1_100_000_000;
const SCALE_FROM: i64 = 800_000_000;
const SCALE_TO: i64 = 1_200_000_000;
const FOTO0_FROM: i64 = 900_000_000;
const WAIT_AT: i64 = 1_800_000_000;
const ONTO_PLATFORM: i64 = 1_950_000_000;
const PITCH: i64 = 250_000_000;
const SETTLE_NS: i64 = 200_000_000;
/// Running time of belt 2 or 3 until a package has left its head.
const HEAD_CLEAR_NS: i64 = 1_250_000_000;

impl Sorter {
    /// Empty line, platform down, cylinders retracted.
    pub fn new() -> Sorter {
        Sorter {
            line: Vec::new(),
            platform: None,
            queue: VecDeque::new(),
            cyl: [Drive::new(0.8), Drive::new(0.8), Drive::new(1.5)],
            belts: [false; 4],
            on_scale_ns: 0,
            small_out: 0,
            large_out: 0,
            missorted: 0,
            removed: 0,
            speed: 0.2,
            collisions: 0,
            colliding: false,
            jams: 0,
            head_busy_ns: [0; 2],
        }
    }

    fn on_scale(&self) -> Option<&Package> {
        self.line
            .iter()
            .find(|k| (SCALE_FROM..=SCALE_TO).contains(&k.p))
    }

    /// The scale reading in engineering units (0..100).
    fn weight(&self) -> f64 {
        self.on_scale().map_or(0.0, |k| {
            k.weight * (self.on_scale_ns.min(SETTLE_NS) as f64 / SETTLE_NS as f64)
        })
    }

    fn platform_down(&self) -> bool {
        self.cyl[2].retracted()
    }

    fn move_line(&mut self, dt_ns: i64) {
        let d = (self.speed * dt_ns as f64).round() as i64;
        let platform_free = self.platform.is_none() && self.platform_down();
        let mut limit = if platform_free { i64::MAX } else { WAIT_AT };
        for k in &mut self.line {
            let runs = if k.p <= BELT0_END {
                self.belts[0]
            } else {
                self.belts[1]
            };
            if runs {
                k.p = k.p.saturating_add(d).min(limit).max(k.p);
            }
            limit = k.p - PITCH;
        }
        if platform_free {
            if let Some(first) = self.line.first().copied() {
                if first.p >= ONTO_PLATFORM {
                    self.line.remove(0);
                    self.platform = Some(first);
                }
            }
        }
        // a new package comes on when belt 0 runs and the infeed is clear
        let clear = self.line.last().is_none_or(|k| k.p >= PITCH);
        if self.belts[0] && clear {
            if let Some(w) = self.queue.pop_front() {
                self.line.push(Package { p: 0, weight: w });
            }
        }
    }

    fn push_off(&mut self) {
        let top = self.cyl[2].extended();
        let (a, b) = (self.cyl[0].extended(), self.cyl[1].extended());
        if !top || !(a || b) {
            return;
        }
        if let Some(k) = self.platform.take() {
            let to_small = a;
            let head = usize::from(!to_small);
            if let Some(busy) = self.head_busy_ns.get_mut(head) {
                if *busy > 0 {
                    self.jams += 1;
                }
                *busy = HEAD_CLEAR_NS;
            }
            if to_small {
                self.small_out += 1;
            } else {
                self.large_out += 1;
            }
            if is_small(k.weight) != Some(to_small) {
                self.missorted += 1;
            }
        }
    }

    fn package_command(&mut self, args: &[(&str, f64)]) -> Result<(), String> {
        let (mut weight, mut count) = (None, 1);
        for &(k, v) in args {
            match k {
                "weight" if v.is_finite() && (0.0..=100.0).contains(&v) => weight = Some(v),
                "count" if v.is_finite() && v >= 0.0 => count = v.min(1e4) as usize,
                "weight" => return Err("sorter: `weight` must be in 0..100".into()),
                _ => {
                    return Err(format!(
                        "sorter: bad argument `{k}` of `package` (known: weight 0..100, count >= 0)"
                    ))
                }
            }
        }
        let w = weight.ok_or("sorter: `package` needs `weight=…` (0..100)")?;
        self.queue.extend(std::iter::repeat_n(w, count));
        Ok(())
    }
}

impl Plant for Sorter {
    fn name(&self) -> &'static str {
        "sorter"
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
            BANDA_0..=BANDA_3 => {
                if let Some(b) = self.belts.get_mut(signal - BANDA_0) {
                    *b = on;
                }
            }
            A_AVANSAT..=C_COBORARE => {
                let i = signal - A_AVANSAT;
                if let Some(c) = self.cyl.get_mut(i / 2) {
                    if i.is_multiple_of(2) {
                        c.advance = on;
                    } else {
                        c.retract = on;
                    }
                }
            }
            _ => {}
        }
    }

    fn get(&self, signal: usize) -> Value {
        match signal {
            FOTO_0 => Value::Bool(
                self.line
                    .iter()
                    .any(|k| (FOTO0_FROM..=BELT0_END).contains(&k.p)),
            ),
            FOTO_1 => Value::Bool(self.platform.is_some() && self.platform_down()),
            2..=7 => {
                let i = signal - 2;
                Value::Bool(self.cyl.get(i / 2).is_some_and(|c| {
                    if i.is_multiple_of(2) {
                        c.retracted()
                    } else {
                        c.extended()
                    }
                }))
            }
            TRADUCTOR => Value::Int(raw_4_20(self.weight(), 100.0)),
            BANDA_0..=BANDA_3 => Value::Bool(self.belts.get(signal - BANDA_0) == Some(&true)),
            A_AVANSAT..=C_COBORARE => {
                let i = signal - A_AVANSAT;
                Value::Bool(self.cyl.get(i / 2).is_some_and(|c| {
                    if i.is_multiple_of(2) {
                        c.advance
                    } else {
                        c.retract
                    }
                }))
            }
            _ => Value::Bool(false),
        }
    }

    fn quantity(&self, index: usize) -> f64 {
        match index {
            0 => self.queue.len() as f64,
            1 => (self.line.len() + usize::from(self.platform.is_some())) as f64,
            2 => self.small_out as f64,
            3 => self.large_out as f64,
            4 => self.missorted as f64,
            5 => self.weight(),
            6 => self.cyl[2].fraction(),
            7 => self.cyl.iter().map(|c| c.conflict_ns).sum::<i64>() as f64 / 1e6,
            8 => self.removed as f64,
            9 => self.collisions as f64,
            10 => self.jams as f64,
            _ => 0.0,
        }
    }

    fn step(&mut self, dt_ns: i64, _rng: &mut Rng) {
        let before = self.on_scale().map(|k| k.p);
        for c in &mut self.cyl {
            c.step(dt_ns);
        }
        let [a, b, c] = &self.cyl;
        let lowering = c.retract && !c.advance && c.fraction() > 0.0;
        let colliding = lowering && !(a.retracted() && b.retracted());
        if colliding && !self.colliding {
            self.collisions += 1;
        }
        self.colliding = colliding;
        for (busy, runs) in self.head_busy_ns.iter_mut().zip(&self.belts[2..]) {
            if *runs {
                *busy = (*busy - dt_ns).max(0);
            }
        }
        self.move_line(dt_ns);
        self.push_off();
        // the settling clock restarts when another package comes on
        match (before, self.on_scale().map(|k| k.p)) {
            (Some(_), Some(_)) => self.on_scale_ns = self.on_scale_ns.saturating_add(dt_ns),
            _ => self.on_scale_ns = 0,
        }
    }

    fn command(&mut self, name: &str, args: &[(&str, f64)]) -> Result<(), String> {
        match name {
            "package" => self.package_command(args),
            "remove" => {
                let at = self.on_scale().map(|k| k.p);
                match at {
                    Some(p) => {
                        self.line.retain(|k| k.p != p);
                        self.removed += 1;
                        Ok(())
                    }
                    None => Err("sorter: `remove`: no package on the scale".into()),
                }
            }
            "set" => args.iter().try_for_each(|&(k, v)| match k {
                "speed" => {
                    self.speed = positive("sorter", k, v)?.min(100.0);
                    Ok(())
                }
                _ => Err(format!("sorter: unknown parameter `{k}` (known: speed)")),
            }),
            _ => Err(format!(
                "the sorter model has no command `{name}` (known: package, remove, set)"
            )),
        }
    }

    fn commands(&self) -> &'static [(&'static str, &'static str)] {
        &[
            (
                "package",
                "weight=W [count=N]: N packages of weight W (0..100) arrive at the infeed",
            ),
            ("remove", "take the package on the scale off by hand"),
            ("set", "parameters: speed (m/s, both belts)"),
        ]
    }
}

#[cfg(test)]
#[path = "sorter_tests.rs"]
mod tests;
