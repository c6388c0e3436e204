//! A4, the automatic car-wash station (problem 4 of the textbook's chapter
//! 5; processes digest A4).
//!
//! A conveyor (`Banda`) carries vehicles through four posts: soaking
//! (`Inmuiere`), detergent (`Detergent`), rinsing (`Clatire`), drying
//! (`Uscare`). Photocells `Foto_1`..`Foto_4` sit at the posts and `Foto_5` at
//! the exit; each is on while a vehicle body covers it. A barrier at the
//! entrance (motor `Bariera_sus`/`Bariera_jos`, limit switches
//! `Limita_SUS`/`Limita_JOS`) and a traffic light (`Semafor`) close the
//! station while it is full.
//!
//! Parameters (the digest suggests a constant speed, vehicles shorter than
//! the post spacing and a 3 s barrier stroke; the rest is chosen):
//! - the conveyor runs at 0.4 m/s and drags vehicles by rollers every 4 m
//!   (as real car-wash conveyors do): a waiting vehicle drives on when a
//!   roller passes the entrance (every 10 s of running) and the barrier is
//!   fully up, so a queue loads exactly one vehicle per post;
//! - vehicles are 3 m long; the barrier is at x = 0, the photocells at
//!   3.5, 7.5, 11.5, 15.5 and 19.5 m (4 m apart, `Foto_1` far enough in that
//!   the vehicle has cleared the barrier when it reaches it, and half a
//!   metre before a roller pitch so the barrier starts down before the next
//!   roller comes); a vehicle leaves at 24.5 m (its rear 2 m past `Foto_5`);
//! - the barrier strokes in 3 s; a limit switch is on within 1 % of its end.
//!
//! Vehicles arrive by the `vehicle` command (`vehicle count=5`) or every
//! `arrival_every` seconds. Each vehicle records which posts were working
//! while it stood at them: one that leaves without all four counts as
//! `unwashed`. A barrier that is not fully up while a vehicle is under it
//! counts a `barrier_hits` (once per vehicle); both barrier motors at once
//! count `conflicts`.

use super::pneumatic::{positive, Drive};
use super::{q, sig};
use crate::{Dir, Plant, Quantity, Rng, Signal, Value};

const SIGNALS: &[Signal] = &[
    sig("Start", Dir::Operator, "start contact"),
    sig("Limita_SUS", Dir::Sensor, "barrier upper limit switch"),
    sig("Limita_JOS", Dir::Sensor, "barrier lower limit switch"),
    sig("Foto_1", Dir::Sensor, "photocell of post 1 (soaking)"),
    sig("Foto_2", Dir::Sensor, "photocell of post 2 (detergent)"),
    sig("Foto_3", Dir::Sensor, "photocell of post 3 (rinsing)"),
    sig("Foto_4", Dir::Sensor, "photocell of post 4 (drying)"),
    sig("Foto_5", Dir::Sensor, "photocell at the exit"),
    sig("Banda", Dir::Actuator, "conveyor"),
    sig("Bariera_sus", Dir::Actuator, "barrier motor, up"),
    sig("Bariera_jos", Dir::Actuator, "barrier motor, down"),
    sig("Semafor", Dir::Actuator, "traffic light (no entry)"),
    sig("Inmuiere", Dir::Actuator, "soaking post (Înmuiere)"),
    sig("Detergent", Dir::Actuator, "detergent post"),
    sig("Clatire", Dir::Actuator, "rinsing post (Clătire)"),
    sig("Uscare", Dir::Actuator, "drying post"),
];

const QUANTITIES: &[Quantity] = &[
    q("queue", "", "vehicles waiting at the entrance"),
    q("inside", "", "vehicles on the conveyor"),
    q("entered", "", "vehicles that drove onto the conveyor"),
    q(
        "washed",
        "",
        "vehicles that left through every working post",
    ),
    q("unwashed", "", "vehicles that left having missed a post"),
    q("barrier", "", "barrier position: 0 up .. 1 down"),
    q(
        "barrier_hits",
        "",
        "vehicles under a barrier that was not fully up",
    ),
    q("conflicts", "ms", "time both barrier motors were on"),
    q("travel", "m", "conveyor travel since the start"),
];

// Signal indices, in the order of SIGNALS.
const START: usize = 0;
const LIMITA_SUS: usize = 1;
const LIMITA_JOS: usize = 2;
const FOTO_1: usize = 3;
const FOTO_5: usize = 7;
const BANDA: usize = 8;
const BARIERA_SUS: usize = 9;
const BARIERA_JOS: usize = 10;
const SEMAFOR: usize = 11;
const INMUIERE: usize = 12;
const USCARE: usize = 15;

const NM_PER_M: f64 = 1e9;

fn nm(m: f64) -> i64 {
    (m * NM_PER_M).round() as i64
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Vehicle {
    /// Front, nm from the barrier.
    front: i64,
    /// Bit k: post k+1 was working while the vehicle covered its photocell.
    served: u8,
    hit: bool,
}

/// The station.
#[derive(Clone, Debug)]
pub struct Carwash {
    vehicles: Vec<Vehicle>,
    barrier: Drive,
    start: bool,
    banda: bool,
    semafor: bool,
    /// The four post outputs as last set.
    posts: [bool; 4],
    queue: u64,
    entered: u64,
    washed: u64,
    unwashed: u64,
    hits: u64,
    travel: i64,
    next_roller: i64,
    /// Time to the next automatic arrival, and its period (0 = none).
    arrival_in: i64,
    arrival_every: i64,
    // Geometry in nm, speed in m/s (= nm/ns).
    cells: [i64; 5],
    length: i64,
    pitch: i64,
    exit: i64,
    speed: f64,
}

impl Default for Carwash {
    fn default() -> Self {
        Carwash::new()
    }
}

impl Carwash {
    /// Empty station, barrier up, conveyor stopped, nobody waiting.
    pub fn new() -> Carwash {
        Carwash {
            vehicles: Vec::new(),
            barrier: Drive::new(3.0),
            start: false,
            banda: false,
            semafor: false,
            posts: [false; 4],
            queue: 0,
            entered: 0,
            washed: 0,
            unwashed: 0,
            hits: 0,
            travel: 0,
            next_roller: 0,
            arrival_in: 0,
            arrival_every: 0,
            cells: [3.5, 7.5, 11.5, 15.5, 19.5].map(nm),
            length: nm(3.0),
            pitch: nm(4.0),
            exit: nm(24.5),
            speed: 0.4,
        }
    }

    fn covers(&self, v: &Vehicle, cell: i64) -> bool {
        v.front >= cell && v.front - self.length < cell
    }

    /// Photocell `k` (0-based) sees a vehicle.
    fn foto(&self, k: usize) -> bool {
        self.cells
            .get(k)
            .is_some_and(|&c| self.vehicles.iter().any(|v| self.covers(v, c)))
    }

    fn set_param(&mut self, key: &str, v: f64) -> Result<(), String> {
        match key {
            "speed" => self.speed = positive("carwash", key, v)?.min(100.0),
            "barrier_time" => self.barrier.set_stroke(positive("carwash", key, v)?),
            "arrival_every" if v.is_finite() && v >= 0.0 => {
                self.arrival_every = (v.min(1e6) * 1e9).round() as i64;
                self.arrival_in = self.arrival_every;
            }
            "arrival_every" => return Err("carwash: `arrival_every` must be >= 0".into()),
            _ => {
                return Err(format!(
                    "carwash: unknown parameter `{key}` (known: speed, barrier_time, arrival_every)"
                ))
            }
        }
        Ok(())
    }

    fn run_conveyor(&mut self, dt_ns: i64) {
        let d = (self.speed * dt_ns as f64).round() as i64;
        self.travel = self.travel.saturating_add(d);
        for v in &mut self.vehicles {
            v.front = v.front.saturating_add(d);
        }
        // a roller passes the entrance: the first waiting vehicle drives on
        // if the barrier is fully up
        if self.travel >= self.next_roller {
            let on_roller = self.travel - self.next_roller;
            self.next_roller = self.next_roller.saturating_add(self.pitch);
            if self.queue > 0 && self.barrier.retracted() {
                self.queue -= 1;
                self.entered += 1;
                self.vehicles.push(Vehicle {
                    front: on_roller,
                    served: 0,
                    hit: false,
                });
            }
        }
        let exit = self.exit;
        while let Some(i) = self.vehicles.iter().position(|v| v.front >= exit) {
            let v = self.vehicles.remove(i);
            if v.served == 0b1111 {
                self.washed += 1;
            } else {
                self.unwashed += 1;
            }
        }
    }
}

impl Plant for Carwash {
    fn name(&self) -> &'static str {
        "carwash"
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
            START => self.start = on,
            BANDA => self.banda = on,
            BARIERA_SUS => self.barrier.retract = on,
            BARIERA_JOS => self.barrier.advance = on,
            SEMAFOR => self.semafor = on,
            INMUIERE..=USCARE => {
                if let Some(p) = self.posts.get_mut(signal - INMUIERE) {
                    *p = on;
                }
            }
            _ => {}
        }
    }

    fn get(&self, signal: usize) -> Value {
        Value::Bool(match signal {
            START => self.start,
            LIMITA_SUS => self.barrier.retracted(),
            LIMITA_JOS => self.barrier.extended(),
            FOTO_1..=FOTO_5 => self.foto(signal - FOTO_1),
            BANDA => self.banda,
            BARIERA_SUS => self.barrier.retract,
            BARIERA_JOS => self.barrier.advance,
            SEMAFOR => self.semafor,
            INMUIERE..=USCARE => self.posts.get(signal - INMUIERE).copied().unwrap_or(false),
            _ => false,
        })
    }

    fn quantity(&self, index: usize) -> f64 {
        match index {
            0 => self.queue as f64,
            1 => self.vehicles.len() as f64,
            2 => self.entered as f64,
            3 => self.washed as f64,
            4 => self.unwashed as f64,
            5 => self.barrier.fraction(),
            6 => self.hits as f64,
            7 => self.barrier.conflict_ns as f64 / 1e6,
            8 => self.travel as f64 / NM_PER_M,
            _ => 0.0,
        }
    }

    fn step(&mut self, dt_ns: i64, _rng: &mut Rng) {
        if self.arrival_every > 0 {
            self.arrival_in -= dt_ns;
            if self.arrival_in <= 0 {
                self.queue += 1;
                self.arrival_in += self.arrival_every;
            }
        }
        self.barrier.step(dt_ns);
        if self.banda {
            self.run_conveyor(dt_ns);
        }
        let barrier_up = self.barrier.retracted();
        let (cells, length, posts) = (self.cells, self.length, self.posts);
        let mut hits = 0;
        for v in &mut self.vehicles {
            if !barrier_up && !v.hit && v.front - length < 0 {
                v.hit = true;
                hits += 1;
            }
            for (k, (&cell, &on)) in cells.iter().zip(posts.iter()).enumerate() {
                if on && v.front >= cell && v.front - length < cell {
                    v.served |= 1 << k;
                }
            }
        }
        self.hits += hits;
    }

    fn command(&mut self, name: &str, args: &[(&str, f64)]) -> Result<(), String> {
        match name {
            "set" => args.iter().try_for_each(|(k, v)| self.set_param(k, *v)),
            "vehicle" => {
                let mut count = 1;
                for &(k, v) in args {
                    match k {
                        "count" if v.is_finite() && v >= 0.0 => count = v.min(1e4) as u64,
                        _ => {
                            return Err(format!(
                                "carwash: bad argument `{k}` of `vehicle` (known: count >= 0)"
                            ))
                        }
                    }
                }
                self.queue += count;
                Ok(())
            }
            _ => Err(format!(
                "the carwash model has no command `{name}` (known: set, vehicle)"
            )),
        }
    }

    fn commands(&self) -> &'static [(&'static str, &'static str)] {
        &[
            (
                "set",
                "parameters: speed (m/s), barrier_time (s), arrival_every (s, 0 = none)",
            ),
            ("vehicle", "[count=N]: N vehicles arrive at the entrance"),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(c: &mut Carwash, ms: i64) {
        let mut rng = Rng::new(1);
        for _ in 0..ms {
            c.step(1_000_000, &mut rng);
        }
    }

    fn fotos(c: &Carwash) -> [bool; 5] {
        [0, 1, 2, 3, 4].map(|k| c.get(FOTO_1 + k).as_bool())
    }

    fn on(c: &mut Carwash, signal: usize, v: bool) {
        c.set(signal, Value::Bool(v));
    }

    #[test]
    fn starts_empty_with_the_barrier_up() {
        let c = Carwash::new();
        assert!(c.get(LIMITA_SUS).as_bool() && !c.get(LIMITA_JOS).as_bool());
        assert_eq!(fotos(&c), [false; 5]);
    }

    #[test]
    fn a_vehicle_covers_each_photocell_for_7_5_seconds() {
        let mut c = Carwash::new();
        assert_eq!(c.command("vehicle", &[]), Ok(()));
        on(&mut c, BANDA, true);
        run(&mut c, 1);
        assert_eq!((c.quantity(0), c.quantity(1)), (0.0, 1.0));
        // front 0.4 mm after 1 ms: at 3.5 m after 8.75 s
        run(&mut c, 8748);
        assert_eq!(fotos(&c), [false; 5]);
        run(&mut c, 1);
        assert_eq!(fotos(&c), [true, false, false, false, false]);
        run(&mut c, 7499);
        assert_eq!(fotos(&c), [true, false, false, false, false]);
        run(&mut c, 1);
        assert_eq!(fotos(&c), [false; 5]);
        run(&mut c, 2500);
        assert_eq!(fotos(&c), [false, true, false, false, false]);
        // leaves at 24.5 m: 61.25 s; no post was working
        run(&mut c, 61_250 - 18_750 - 1);
        assert_eq!(c.quantity(1), 1.0);
        run(&mut c, 1);
        assert_eq!(
            (c.quantity(1), c.quantity(3), c.quantity(4)),
            (0.0, 0.0, 1.0)
        );
    }

    #[test]
    fn a_queue_loads_one_vehicle_per_roller_four_metres_apart() {
        let mut c = Carwash::new();
        assert_eq!(c.command("vehicle", &[("count", 5.0)]), Ok(()));
        on(&mut c, BANDA, true);
        run(&mut c, 38_750);
        // v1 at 15.5 m (Foto_4) ... v4 at 3.5 m (Foto_1); v5 waits for 40 s
        assert_eq!(fotos(&c), [true, true, true, true, false]);
        assert_eq!((c.quantity(0), c.quantity(2)), (1.0, 4.0));
    }

    #[test]
    fn working_posts_wash_and_a_closed_barrier_stops_entry() {
        let mut c = Carwash::new();
        assert_eq!(c.command("vehicle", &[("count", 2.0)]), Ok(()));
        for p in INMUIERE..=USCARE {
            on(&mut c, p, true);
        }
        on(&mut c, BANDA, true);
        run(&mut c, 1);
        on(&mut c, BARIERA_JOS, true);
        run(&mut c, 3000);
        assert!(c.get(LIMITA_JOS).as_bool());
        // the first vehicle was still under the barrier
        assert_eq!(c.quantity(6), 1.0);
        run(&mut c, 70_000);
        assert_eq!(
            (c.quantity(2), c.quantity(3), c.quantity(0)),
            (1.0, 1.0, 1.0)
        );
    }

    #[test]
    fn barrier_strokes_in_three_seconds_and_both_motors_conflict() {
        let mut c = Carwash::new();
        on(&mut c, BARIERA_JOS, true);
        run(&mut c, 2969);
        assert!(!c.get(LIMITA_JOS).as_bool());
        run(&mut c, 1);
        assert!(c.get(LIMITA_JOS).as_bool());
        on(&mut c, BARIERA_SUS, true);
        run(&mut c, 100);
        assert_eq!(c.quantity(7), 100.0);
        on(&mut c, BARIERA_JOS, false);
        run(&mut c, 3000);
        assert!(c.get(LIMITA_SUS).as_bool());
    }

    #[test]
    fn automatic_arrivals_and_errors() {
        let mut c = Carwash::new();
        assert_eq!(c.command("set", &[("arrival_every", 2.0)]), Ok(()));
        run(&mut c, 6000);
        assert_eq!(c.quantity(0), 3.0);
        assert!(c
            .command("vehicle", &[("count", -1.0)])
            .is_err_and(|e| e.contains("count >= 0")));
        assert!(c
            .command("set", &[("speed", 0.0)])
            .is_err_and(|e| e.contains("greater than 0")));
        assert!(c
            .command("set", &[("width", 1.0)])
            .is_err_and(|e| e.contains("unknown parameter `width`")));
        assert!(c
            .command("wash", &[])
            .is_err_and(|e| e.contains("no command `wash`")));
    }
}
