//! A8, automatic bottle filling and capping (problem 8 of the textbook's
//! chapter 5; processes digest A8).
//!
//! A conveyor (`Banda`) carries bottles past a filling station (photocell
//! `st_de_reumplut`) and, one pitch further, a capping station (photocell
//! `st_plina`). Cylinder A works the volumetric doser (`F1` up, `F2` down:
//! one dose per down stroke); cylinder C brings a cap from the stack (`F5`)
//! to under cylinder B (`F6`); the three-position cylinder B takes it at
//! the middle position (`F7`), pushes it onto the bottle (`F4`) and goes back
//! up (`F3`); the screwing head (`Insurubare`) turns the cap until its
//! rotation limit (`senzor_rotire`).
//!
//! Geometry and times (the source gives none): bottles 60 mm across on a
//! belt at 0.1 m/s; the filling station at 1.0 m, the capping station at
//! 1.3 m (a pitch of 0.3 m), bottles leave at 2.0 m. A photocell sees a
//! bottle whose centre is within 30 mm of its station. An operator (an
//! unscrambler) puts a bottle at the start of the belt every 0.3 m of belt
//! travel (`set random=1`: every 0.15..0.45 m, drawn from the `Rng`, for the
//! source's Propunere); the first three stand at 0.1, 0.4 and 0.7 m.
//! Strokes: A 1 s, B 1 s (F7 at 40 % of it, ±1 %), C 0.5 s; the cap is
//! tight after 1.5 s of screwing, when the rotation limit trips; the head
//! springs back when `Insurubare` goes off.
//!
//! A dose goes into the bottle in the filling window, else it is spilt. B
//! takes the cap at F7 when C stands at F6 with one; a cap pushed down to
//! F4 goes onto the bottle in the capping window (else it is lost), and the
//! bottle is capped when the screwing completes. B below F7 while C is not
//! back at F5 is a crash (counted once per contact). Bottles leaving the
//! belt are `good` (one dose, capped) or `bad`.

use super::pneumatic::{positive, Drive};
use super::{q, sig};
use crate::{Dir, Plant, Quantity, Rng, Signal, Value};

const SIGNALS: &[Signal] = &[
    sig("F1", Dir::Sensor, "cylinder A (doser) up"),
    sig("F2", Dir::Sensor, "cylinder A (doser) down: one dose given"),
    sig("F3", Dir::Sensor, "cylinder B up"),
    sig("F4", Dir::Sensor, "cylinder B down, on the bottle"),
    sig("F5", Dir::Sensor, "cylinder C left, at the cap stack"),
    sig("F6", Dir::Sensor, "cylinder C right, under B"),
    sig("F7", Dir::Sensor, "cylinder B at the cap pick-up position"),
    sig(
        "senzor_rotire",
        Dir::Sensor,
        "rotation limit of the screwing device",
    ),
    sig(
        "st_de_reumplut",
        Dir::Sensor,
        "photocell: bottle at the filling station",
    ),
    sig(
        "st_plina",
        Dir::Sensor,
        "photocell: bottle at the capping station",
    ),
    sig("Banda", Dir::Actuator, "conveyor"),
    sig("A_avans", Dir::Actuator, "cylinder A down (dose)"),
    sig("A_retragere", Dir::Actuator, "cylinder A up"),
    sig("B_avans", Dir::Actuator, "cylinder B down"),
    sig("B_retragere", Dir::Actuator, "cylinder B up"),
    sig("C_avans", Dir::Actuator, "cylinder C toward B (F6)"),
    sig(
        "C_retragere",
        Dir::Actuator,
        "cylinder C back to the stack (F5)",
    ),
    sig("Insurubare", Dir::Actuator, "screw the cap on"),
];

const QUANTITIES: &[Quantity] = &[
    q("good", "", "bottles that left filled once and capped"),
    q(
        "bad",
        "",
        "bottles that left empty, overfilled or without a tight cap",
    ),
    q("on_belt", "", "bottles on the belt"),
    q("spilt", "", "doses given with no bottle below"),
    q("caps_lost", "", "caps pushed down with no bottle below"),
    q(
        "crashes",
        "",
        "B driven below F7 while C was not back at F5",
    ),
    q("conflicts", "ms", "time a cylinder got both of its coils"),
    q(
        "fill_bottle",
        "",
        "doses in the bottle at the filling station (-1: none)",
    ),
    q(
        "cap_bottle",
        "",
        "1 when the bottle at the capping station is capped (-1: none)",
    ),
];

const BANDA: usize = 10;
const INSURUBARE: usize = 17;
const FILL_AT: i64 = 1_000_000;
const CAP_AT: i64 = 1_300_000;
const END_AT: i64 = 2_000_000;
const WINDOW: i64 = 30_000;
const PITCH: i64 = 300_000;
const F7_AT: f64 = 0.4;
const SCREW_NS: i64 = 1_500_000_000;

#[derive(Clone, Debug, Default)]
struct Bottle {
    /// µm along the belt.
    x: i64,
    doses: u32,
    cap_on: bool,
    capped: bool,
}

#[derive(Clone, Debug)]
pub struct Bottling {
    banda: bool,
    insurubare: bool,
    a: Drive,
    b: Drive,
    c: Drive,
    c_cap: bool,
    b_cap: bool,
    screw_ns: i64,
    bottles: Vec<Bottle>,
    next_gap: i64,
    random: bool,
    good: u32,
    bad: u32,
    spilt: u32,
    caps_lost: u32,
    crashes: u32,
    in_crash: bool,
    /// µm/s
    speed: i64,
}

impl Default for Bottling {
    fn default() -> Self {
        Bottling::new()
    }
}

impl Bottling {
    pub fn new() -> Bottling {
        let at = |x| Bottle {
            x,
            ..Bottle::default()
        };
        Bottling {
            banda: false,
            insurubare: false,
            a: Drive::new(1.0),
            b: Drive::new(1.0),
            c: Drive::new(0.5),
            c_cap: true,
            b_cap: false,
            screw_ns: 0,
            bottles: vec![at(700_000), at(400_000), at(100_000)],
            next_gap: PITCH,
            random: false,
            good: 0,
            bad: 0,
            spilt: 0,
            caps_lost: 0,
            crashes: 0,
            in_crash: false,
            speed: 100_000,
        }
    }

    fn at_station(&self, at: i64) -> Option<&Bottle> {
        self.bottles.iter().find(|b| (b.x - at).abs() <= WINDOW)
    }
    fn at_station_mut(&mut self, at: i64) -> Option<&mut Bottle> {
        self.bottles.iter_mut().find(|b| (b.x - at).abs() <= WINDOW)
    }

    fn step_belt(&mut self, dt_ns: i64, rng: &mut Rng) {
        if !self.banda {
            return;
        }
        let dx = (i128::from(self.speed) * i128::from(dt_ns) / 1_000_000_000) as i64;
        for b in &mut self.bottles {
            b.x += dx;
        }
        for b in self.bottles.iter().filter(|b| b.x >= END_AT) {
            if b.doses == 1 && b.capped {
                self.good += 1;
            } else {
                self.bad += 1;
            }
        }
        self.bottles.retain(|b| b.x < END_AT);
        let last = self.bottles.last().map_or(END_AT, |b| b.x);
        if last >= self.next_gap {
            self.bottles.push(Bottle {
                x: last - self.next_gap,
                ..Bottle::default()
            });
            self.next_gap = if self.random {
                150_000 + (rng.unit() * 300_000.0) as i64
            } else {
                PITCH
            };
        }
    }

    fn step_doser(&mut self, dt_ns: i64) {
        let was_down = self.a.extended();
        self.a.step(dt_ns);
        if self.a.extended() && !was_down {
            match self.at_station_mut(FILL_AT) {
                Some(b) => b.doses += 1,
                None => self.spilt += 1,
            }
        }
    }

    fn step_caps(&mut self, dt_ns: i64) {
        self.c.step(dt_ns);
        if self.c.retracted() && !self.c_cap {
            self.c_cap = true;
        }
        let was_down = self.b.extended();
        self.b.step(dt_ns);
        if self.b.near(F7_AT) && self.c.extended() && self.c_cap && !self.b_cap {
            self.c_cap = false;
            self.b_cap = true;
        }
        let crash = self.b.fraction() > F7_AT + 0.01 && !self.c.retracted();
        if crash && !self.in_crash {
            self.crashes += 1;
        }
        self.in_crash = crash;
        if self.b.extended() && !was_down && self.b_cap {
            self.b_cap = false;
            match self.at_station_mut(CAP_AT) {
                Some(b) => b.cap_on = true,
                None => self.caps_lost += 1,
            }
        }
        if self.insurubare {
            self.screw_ns = (self.screw_ns + dt_ns).min(SCREW_NS);
        } else {
            self.screw_ns = 0;
        }
        if self.screw_ns >= SCREW_NS && self.b.extended() {
            if let Some(b) = self.at_station_mut(CAP_AT) {
                if b.cap_on {
                    b.capped = true;
                }
            }
        }
    }

    fn set_param(&mut self, key: &str, v: f64) -> Result<(), String> {
        match key {
            "random" => self.random = v != 0.0,
            "speed" => self.speed = (positive("bottling", key, v)?.min(10.0) * 1e6) as i64,
            "a_time" => self.a.set_stroke(positive("bottling", key, v)?),
            "b_time" => self.b.set_stroke(positive("bottling", key, v)?),
            "c_time" => self.c.set_stroke(positive("bottling", key, v)?),
            _ => {
                return Err(format!(
                    "bottling: unknown parameter `{key}` (known: random (0/1), speed (m/s), a_time, b_time, c_time (s))"
                ))
            }
        }
        Ok(())
    }

    fn drive(&mut self, signal: usize) -> Option<(&mut Drive, bool)> {
        let d = match signal {
            11 | 12 => &mut self.a,
            13 | 14 => &mut self.b,
            15 | 16 => &mut self.c,
            _ => return None,
        };
        Some((d, signal % 2 == 1))
    }
}

impl Plant for Bottling {
    fn name(&self) -> &'static str {
        "bottling"
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
            BANDA => self.banda = on,
            INSURUBARE => self.insurubare = on,
            _ => {
                if let Some((d, advance)) = self.drive(signal) {
                    if advance {
                        d.advance = on;
                    } else {
                        d.retract = on;
                    }
                }
            }
        }
    }

    fn get(&self, signal: usize) -> Value {
        Value::Bool(match signal {
            0 => self.a.retracted(),
            1 => self.a.extended(),
            2 => self.b.retracted(),
            3 => self.b.extended(),
            4 => self.c.retracted(),
            5 => self.c.extended(),
            6 => self.b.near(F7_AT),
            7 => self.screw_ns >= SCREW_NS,
            8 => self.at_station(FILL_AT).is_some(),
            9 => self.at_station(CAP_AT).is_some(),
            BANDA => self.banda,
            INSURUBARE => self.insurubare,
            11 => self.a.advance,
            12 => self.a.retract,
            13 => self.b.advance,
            14 => self.b.retract,
            15 => self.c.advance,
            16 => self.c.retract,
            _ => false,
        })
    }

    fn quantity(&self, index: usize) -> f64 {
        match index {
            0 => f64::from(self.good),
            1 => f64::from(self.bad),
            2 => self.bottles.len() as f64,
            3 => f64::from(self.spilt),
            4 => f64::from(self.caps_lost),
            5 => f64::from(self.crashes),
            6 => (self.a.conflict_ns + self.b.conflict_ns + self.c.conflict_ns) as f64 / 1e6,
            7 => self
                .at_station(FILL_AT)
                .map_or(-1.0, |b| f64::from(b.doses)),
            8 => self
                .at_station(CAP_AT)
                .map_or(-1.0, |b| f64::from(u8::from(b.capped))),
            _ => 0.0,
        }
    }

    fn step(&mut self, dt_ns: i64, rng: &mut Rng) {
        self.step_belt(dt_ns, rng);
        self.step_doser(dt_ns);
        self.step_caps(dt_ns);
    }

    fn command(&mut self, name: &str, args: &[(&str, f64)]) -> Result<(), String> {
        match name {
            "set" => args.iter().try_for_each(|(k, v)| self.set_param(k, *v)),
            _ => Err(format!(
                "the bottling model has no command `{name}` (known: set)"
            )),
        }
    }

    fn commands(&self) -> &'static [(&'static str, &'static str)] {
        &[(
            "set",
            "parameters: random (0/1: bottles at random spacing), speed (m/s), a_time, b_time, c_time (stroke times, s)",
        )]
    }
}

#[cfg(test)]
#[path = "bottling_tests.rs"]
mod tests;
