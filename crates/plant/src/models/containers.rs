//! A9, automatic filling of containers A, B and C (problem 9 of the
//! textbook's chapter 5; processes digest A9).
//!
//! Belt 1 (`Banda_1`) brings the containers C, B, A, in that order, to the
//! end of the belt, which is position 1 of the platform (detector `Poz_A`,
//! under valve A). Cylinder D (`D_avans`/`D_retragere`) moves the platform
//! carriage; the containers standing on it move with it, one pitch per
//! position, to positions 2 (`Poz_B`, valve B) and 3 (`Poz_C`, valve C).
//! Cylinder E (`E_avans`/`E_retragere`, advance limit `Lim_4`) pushes the
//! container at position 1 onto belt 2 (`Banda_2`).
//!
//! Geometry and times (the source gives none): a pitch of 0.3 m; belt 1 at
//! 0.2 m/s with the containers (0.2 m wide) first at 0.5, 1.0 and 1.5 m
//! before its end; D travels two pitches in 2 s (0.3 m/s), E its stroke in
//! 1 s; a detector sees a container whose centre is within 10 mm of its
//! position; a valve pours 1 l/s into a container whose centre is within
//! 0.1 m below it (so litres = seconds open), otherwise onto the floor.
//! An ejected container leaves the entry of belt 2 after 2 s of belt 2.
//!
//! The source declares no sensor for "E retracted" or "D home"; as the
//! digest proposes, the model adds the virtual sensors `E0` and `D0` (within
//! 1 % of the stroke of the retracted end).
//!
//! Faults counted in `crashes`: D moving while E is out, a container pushed
//! by the carriage against the end of belt 1, an ejection onto a belt 2 that
//! is still occupied. `good` counts ejected containers whose contents match
//! the filling table within 0.05 l of each liquid.

use super::pneumatic::{positive, Drive};
use super::{q, sig};
use crate::{Dir, Plant, Quantity, Rng, Signal, Value};

const SIGNALS: &[Signal] = &[
    sig(
        "Poz_A",
        Dir::Sensor,
        "detector 1: a container at position 1 (valve A, E)",
    ),
    sig(
        "Poz_B",
        Dir::Sensor,
        "detector 2: a container at position 2 (valve B)",
    ),
    sig(
        "Poz_C",
        Dir::Sensor,
        "detector 3: a container at position 3 (valve C)",
    ),
    sig("Lim_4", Dir::Sensor, "detector 4: cylinder E advanced"),
    sig(
        "E0",
        Dir::Sensor,
        "cylinder E retracted (virtual sensor, not in the source)",
    ),
    sig(
        "D0",
        Dir::Sensor,
        "cylinder D home (virtual sensor, not in the source)",
    ),
    sig("Banda_1", Dir::Actuator, "belt 1: brings the containers"),
    sig(
        "Banda_2",
        Dir::Actuator,
        "belt 2: takes the filled containers away",
    ),
    sig(
        "D_avans",
        Dir::Actuator,
        "cylinder D advance (carriage toward position 3)",
    ),
    sig("D_retragere", Dir::Actuator, "cylinder D retract"),
    sig("E_avans", Dir::Actuator, "cylinder E advance (eject)"),
    sig("E_retragere", Dir::Actuator, "cylinder E retract"),
    sig(
        "Valva_A",
        Dir::Actuator,
        "valve of liquid A (over position 1)",
    ),
    sig(
        "Valva_B",
        Dir::Actuator,
        "valve of liquid B (over position 2)",
    ),
    sig(
        "Valva_C",
        Dir::Actuator,
        "valve of liquid C (over position 3)",
    ),
];

const QUANTITIES: &[Quantity] = &[
    q("A_a", "l", "liquid A in container A"),
    q("A_b", "l", "liquid B in container A"),
    q("A_c", "l", "liquid C in container A"),
    q("B_a", "l", "liquid A in container B"),
    q("B_b", "l", "liquid B in container B"),
    q("B_c", "l", "liquid C in container B"),
    q("C_a", "l", "liquid A in container C"),
    q("C_b", "l", "liquid B in container C"),
    q("C_c", "l", "liquid C in container C"),
    q(
        "spilt",
        "l",
        "liquid poured with no container under the valve",
    ),
    q("ejected", "", "containers pushed onto belt 2"),
    q("good", "", "ejected containers filled as the table says"),
    q(
        "crashes",
        "",
        "mechanical collisions (see the model's docs)",
    ),
    q("carriage", "m", "cylinder D's travel from home"),
    q(
        "A_pos",
        "m",
        "position of container A (0 = position 1, 0.3 = position 2, ...)",
    ),
    q("B_pos", "m", "position of container B"),
    q("C_pos", "m", "position of container C"),
];

const BANDA_1: usize = 6;
const VALVA_A: usize = 12;

const UM: i64 = 1_000_000;
const PITCH: i64 = 300_000;
const WIDTH: i64 = 200_000;
const DETECT: i64 = 10_000;
/// The filling table, litres of A, B, C, for containers A, B, C.
const TABLE: [[f64; 3]; 3] = [[5.0, 0.0, 0.0], [7.0, 7.0, 0.0], [8.0, 5.0, 3.0]];

#[derive(Clone, Debug, PartialEq)]
enum Place {
    /// On belt 1 or the platform, at this many µm from position 1
    /// (negative: still on belt 1).
    At(i64),
    Ejected,
}

#[derive(Clone, Debug)]
struct Container {
    /// 0 = A, 1 = B, 2 = C.
    id: usize,
    place: Place,
    /// Litres × 10^6 (µl) of liquids A, B, C.
    ul: [i64; 3],
}

#[derive(Clone, Debug)]
pub struct Containers {
    banda: [bool; 2],
    valves: [bool; 3],
    d: Drive,
    e: Drive,
    items: Vec<Container>,
    belt2_busy_ns: i64,
    spilt_ul: i64,
    ejected: u32,
    good: u32,
    crashes: u32,
    /// µm/s
    belt_speed: i64,
    /// µl/s
    flow: i64,
    /// A crash already counted for the current contact (count once).
    in_contact: bool,
}

impl Default for Containers {
    fn default() -> Self {
        Containers::new()
    }
}

impl Containers {
    pub fn new() -> Containers {
        let mut c = Containers {
            banda: [false; 2],
            valves: [false; 3],
            d: Drive::new(2.0),
            e: Drive::new(1.0),
            items: Vec::new(),
            belt2_busy_ns: 0,
            spilt_ul: 0,
            ejected: 0,
            good: 0,
            crashes: 0,
            belt_speed: UM / 5,
            flow: UM,
            in_contact: false,
        };
        c.batch(500_000);
        c
    }

    /// Puts a new set C, B, A on belt 1, the first `gap` µm behind the last
    /// container on the belt (or the belt's end), 0.5 m apart.
    fn batch(&mut self, gap: i64) {
        let last = self
            .items
            .iter()
            .filter_map(|c| match c.place {
                Place::At(p) if p < 0 => Some(p),
                _ => None,
            })
            .min()
            .unwrap_or(0);
        self.items.retain(|c| c.place != Place::Ejected);
        for (k, id) in [2usize, 1, 0].into_iter().enumerate() {
            self.items.retain(|c| c.id != id);
            self.items.push(Container {
                id,
                place: Place::At(last - gap - 500_000 * k as i64),
                ul: [0; 3],
            });
        }
    }

    fn detector(&self, at: i64) -> bool {
        self.items
            .iter()
            .any(|c| matches!(c.place, Place::At(p) if (p - at).abs() <= DETECT))
    }

    fn carriage(&self) -> i64 {
        self.d.position(2 * PITCH)
    }

    fn step_belt1(&mut self, dt_ns: i64) {
        if !self.banda[0] {
            return;
        }
        let dx = per_dt(self.belt_speed, dt_ns);
        // The belt carries what is on it (p < 0) up to its end stop, or up to
        // the container in front.
        let mut order: Vec<usize> = (0..self.items.len()).collect();
        order.sort_by_key(|&i| match self.items.get(i).map(|c| &c.place) {
            Some(Place::At(p)) => -*p,
            _ => i64::MAX,
        });
        let mut limit = 0;
        for i in order {
            let Some(c) = self.items.get_mut(i) else {
                continue;
            };
            let Place::At(p) = c.place else { continue };
            if p >= 0 {
                // on the platform: blocks the belt's end when it stands there
                if p < WIDTH {
                    limit = limit.min(p - WIDTH);
                }
                continue;
            }
            let np = (p + dx).min(limit);
            c.place = Place::At(np.max(p));
            limit = np.max(p) - WIDTH;
        }
    }

    fn step_platform(&mut self, dt_ns: i64) {
        let before = self.carriage();
        self.d.step(dt_ns);
        let dp = self.carriage() - before;
        let e_out = !self.e.retracted();
        if dp != 0 && e_out && !self.in_contact {
            self.crashes += 1;
            self.in_contact = true;
        }
        // The carriage's pockets catch every container on the platform and
        // one that stands within the detector's window at the end of belt 1
        // (the belt stops there as soon as `Poz_A` sees it).
        let mut blocked = false;
        for c in &mut self.items {
            if let Place::At(p) = c.place {
                if p >= -DETECT {
                    let np = p + dp;
                    if np < -DETECT {
                        blocked = true;
                    }
                    c.place = Place::At(np.max(-DETECT));
                }
            }
        }
        if blocked && !self.in_contact {
            self.crashes += 1;
        }
        self.in_contact = (dp != 0 && e_out) || blocked;
    }

    fn step_eject(&mut self, dt_ns: i64) {
        let was_extended = self.e.extended();
        self.e.step(dt_ns);
        if self.banda[1] {
            self.belt2_busy_ns = (self.belt2_busy_ns - dt_ns).max(0);
        }
        if !self.e.extended() || was_extended {
            return;
        }
        let Some(c) = self
            .items
            .iter_mut()
            .find(|c| matches!(c.place, Place::At(p) if p.abs() <= WIDTH / 2))
        else {
            return;
        };
        c.place = Place::Ejected;
        let ok = TABLE.get(c.id).is_some_and(|t| {
            t.iter()
                .zip(c.ul)
                .all(|(want, ul)| (ul as f64 / 1e6 - want).abs() <= 0.05)
        });
        self.ejected += 1;
        self.good += u32::from(ok);
        if self.belt2_busy_ns > 0 {
            self.crashes += 1;
        }
        self.belt2_busy_ns = 2_000_000_000;
    }

    fn step_valves(&mut self, dt_ns: i64) {
        let amount = per_dt(self.flow, dt_ns);
        for (liquid, open) in self.valves.into_iter().enumerate() {
            if !open {
                continue;
            }
            let at = PITCH * liquid as i64;
            let under = self
                .items
                .iter_mut()
                .find(|c| matches!(c.place, Place::At(p) if (p - at).abs() <= WIDTH / 2));
            match under.and_then(|c| c.ul.get_mut(liquid)) {
                Some(v) => *v += amount,
                None => self.spilt_ul += amount,
            }
        }
    }

    fn container(&self, id: usize) -> Option<&Container> {
        self.items.iter().find(|c| c.id == id)
    }

    fn set_param(&mut self, key: &str, v: f64) -> Result<(), String> {
        match key {
            "belt_speed" => self.belt_speed = (positive("containers", key, v)?.min(10.0) * 1e6) as i64,
            "flow" => self.flow = (positive("containers", key, v)?.min(1e3) * 1e6) as i64,
            "d_time" => self.d.set_stroke(positive("containers", key, v)?),
            "e_time" => self.e.set_stroke(positive("containers", key, v)?),
            _ => {
                return Err(format!(
                    "containers: unknown parameter `{key}` (known: belt_speed (m/s), flow (l/s), d_time, e_time (s))"
                ))
            }
        }
        Ok(())
    }
}

fn per_dt(per_s: i64, dt_ns: i64) -> i64 {
    (i128::from(per_s) * i128::from(dt_ns) / 1_000_000_000) as i64
}

impl Plant for Containers {
    fn name(&self) -> &'static str {
        "containers"
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
            6 | 7 => {
                if let Some(b) = self.banda.get_mut(signal - BANDA_1) {
                    *b = on;
                }
            }
            8 => self.d.advance = on,
            9 => self.d.retract = on,
            10 => self.e.advance = on,
            11 => self.e.retract = on,
            12..=14 => {
                if let Some(v) = self.valves.get_mut(signal - VALVA_A) {
                    *v = on;
                }
            }
            _ => {}
        }
    }

    fn get(&self, signal: usize) -> Value {
        Value::Bool(match signal {
            0 => self.detector(0),
            1 => self.detector(PITCH),
            2 => self.detector(2 * PITCH),
            3 => self.e.extended(),
            4 => self.e.retracted(),
            5 => self.d.retracted(),
            6 | 7 => self.banda.get(signal - BANDA_1).copied().unwrap_or(false),
            8 => self.d.advance,
            9 => self.d.retract,
            10 => self.e.advance,
            11 => self.e.retract,
            12..=14 => self.valves.get(signal - VALVA_A).copied().unwrap_or(false),
            _ => false,
        })
    }

    fn quantity(&self, index: usize) -> f64 {
        match index {
            0..=8 => self
                .container(index / 3)
                .and_then(|c| c.ul.get(index % 3))
                .map_or(0.0, |&ul| ul as f64 / 1e6),
            9 => self.spilt_ul as f64 / 1e6,
            10 => f64::from(self.ejected),
            11 => f64::from(self.good),
            12 => f64::from(self.crashes),
            13 => self.carriage() as f64 / 1e6,
            14..=16 => match self.container(index - 14).map(|c| &c.place) {
                Some(Place::At(p)) => *p as f64 / 1e6,
                _ => -1.0,
            },
            _ => 0.0,
        }
    }

    fn step(&mut self, dt_ns: i64, _rng: &mut Rng) {
        self.step_belt1(dt_ns);
        self.step_platform(dt_ns);
        self.step_eject(dt_ns);
        self.step_valves(dt_ns);
    }

    fn command(&mut self, name: &str, args: &[(&str, f64)]) -> Result<(), String> {
        match name {
            "set" => args.iter().try_for_each(|(k, v)| self.set_param(k, *v)),
            "batch" => {
                self.batch(500_000);
                Ok(())
            }
            _ => Err(format!(
                "the containers model has no command `{name}` (known: set, batch)"
            )),
        }
    }

    fn commands(&self) -> &'static [(&'static str, &'static str)] {
        &[
            (
                "set",
                "parameters: belt_speed (m/s), flow (l/s), d_time, e_time (stroke times, s)",
            ),
            (
                "batch",
                "puts a new set of containers C, B, A on belt 1 (their contents start empty)",
            ),
        ]
    }
}

#[cfg(test)]
#[path = "containers_tests.rs"]
mod tests;
