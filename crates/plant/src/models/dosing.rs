//! A7, automatic dosing and mixing (problem 7 of the textbook's chapter 5;
//! processes digest A7).
//!
//! Scale C weighs product A (valve `Valva_A`) and then product B
//! (`Valva_B`) and empties into the pivoting mixer (`Valva_C`); a conveyor
//! (`Mt`) brings soluble briquettes one at a time, which fall down a chute
//! past the passage detector `d` into the mixer. The mixer turns
//! (`Rotire`) and pivots (`Piv_dreapta` to tilt and discharge,
//! `Piv_stanga` back upright).
//!
//! Parameters (the source gives none; chosen for a cycle of about a minute):
//! - the scale: `A` is on from `ref_a` = 20 kg, `B` from `ref_b` = 35 kg
//!   (A + B), `Z` (scale empty) at or below 0.1 kg; valves A and B pour
//!   2 kg/s, valve C empties the scale at 5 kg/s (so A takes 10 s, B 7.5 s,
//!   C 7 s). Capacity 60 kg: anything beyond is spilt.
//! - the briquette belt: 1 m long, 0.1 m/s, briquettes every 0.25 m of belt
//!   (an operator keeps it loaded; the first four lie at 0.9, 0.65, 0.4,
//!   0.15 m). A briquette leaving the belt falls for 300 ms; `d` sees it
//!   from 100 ms to 200 ms of its fall (a passage detector in the chute),
//!   then it lands in the mixer. So `d` pulses once per briquette fed, and
//!   the belt can stop on a pulse without leaving a briquette on the edge.
//! - the mixer pivots from upright (`Lim_stanga`, within 1 % of the travel)
//!   to tilted (`Lim_dreapta`) in 4 s; from half-tilted on it discharges
//!   20 kg/s of liquid and all its briquettes. Discharging while not
//!   turning counts as `unmixed` kg (the source: rotation continues while
//!   the mixer empties).
//!
//! Quantities count `batches`: the mixer came back upright after a
//! discharge that left it empty.

use super::pneumatic::{positive, Drive};
use super::{q, sig};
use crate::{Dir, Plant, Quantity, Rng, Signal, Value};

const SIGNALS: &[Signal] = &[
    sig("Start", Dir::Operator, "feed push-button (I:1/1)"),
    sig(
        "A",
        Dir::Sensor,
        "scale: weight of product A reached (I:1/2)",
    ),
    sig("B", Dir::Sensor, "scale: weight of A + B reached (I:1/3)"),
    sig("Z", Dir::Sensor, "scale at zero (I:1/4)"),
    sig(
        "Lim_dreapta",
        Dir::Sensor,
        "mixer tilted right, discharging (I:1/5)",
    ),
    sig(
        "d",
        Dir::Sensor,
        "briquette passage detector in the chute (I:1/6)",
    ),
    sig("Lim_stanga", Dir::Sensor, "mixer upright (I:1/7)"),
    sig(
        "Valva_A",
        Dir::Actuator,
        "valve of product A onto the scale (O:3/1)",
    ),
    sig(
        "Valva_B",
        Dir::Actuator,
        "valve of product B onto the scale (O:3/2)",
    ),
    sig(
        "Valva_C",
        Dir::Actuator,
        "valve emptying the scale into the mixer (O:3/3)",
    ),
    sig("Mt", Dir::Actuator, "briquette conveyor motor (O:3/4)"),
    sig("Rotire", Dir::Actuator, "mixer rotation motor (O:3/5)"),
    sig(
        "Piv_dreapta",
        Dir::Actuator,
        "pivot the mixer right (tilt) (O:3/6)",
    ),
    sig(
        "Piv_stanga",
        Dir::Actuator,
        "pivot the mixer left (upright) (O:3/7)",
    ),
];

const QUANTITIES: &[Quantity] = &[
    q("scale", "kg", "weight on scale C"),
    q("mixer", "kg", "liquid in the mixer"),
    q("briquettes", "", "briquettes in the mixer"),
    q("angle", "", "mixer tilt, 0 upright .. 1 tilted"),
    q(
        "mixing",
        "s",
        "time the mixer turned with something in it since the last discharge",
    ),
    q(
        "batches",
        "",
        "discharges completed (mixer back upright and empty)",
    ),
    q("fed", "", "briquettes that fell into the mixer"),
    q(
        "unmixed",
        "kg",
        "liquid discharged while the mixer was not turning",
    ),
    q("spilt", "kg", "product spilt from an overfull scale"),
    q(
        "conflicts",
        "ms",
        "time the pivot motor was driven both ways",
    ),
];

const START: usize = 0;
const VALVA_A: usize = 7;
const PIV_DREAPTA: usize = 12;
const PIV_STANGA: usize = 13;

const MG_PER_KG: i64 = 1_000_000;
const UM_PER_M: i64 = 1_000_000;
/// Fall time of a briquette and the window in which `d` sees it.
const FALL_NS: i64 = 300_000_000;
const SEEN_FROM_NS: i64 = 100_000_000;
const SEEN_UNTIL_NS: i64 = 200_000_000;

#[derive(Clone, Debug)]
pub struct Dosing {
    start: bool,
    /// Valva_A, Valva_B, Valva_C, Mt, Rotire as last set.
    outs: [bool; 5],
    pivot: Drive,
    scale_mg: i64,
    mixer_mg: i64,
    mixer_briquettes: u32,
    /// Briquette positions on the belt, µm from its start, first = nearest
    /// the end.
    belt: Vec<i64>,
    /// Time each falling briquette has fallen, ns.
    falling: Vec<i64>,
    mixing_ns: i64,
    batches: u32,
    fed: u32,
    unmixed_mg: i64,
    spilt_mg: i64,
    discharged: bool,
    // parameters
    ref_a_mg: i64,
    ref_b_mg: i64,
    zero_mg: i64,
    capacity_mg: i64,
    /// mg/s
    flow_a: i64,
    flow_b: i64,
    flow_c: i64,
    discharge: i64,
    /// µm/s
    belt_speed: i64,
    belt_len: i64,
    spacing: i64,
}

impl Default for Dosing {
    fn default() -> Self {
        Dosing::new()
    }
}

impl Dosing {
    pub fn new() -> Dosing {
        Dosing {
            start: false,
            outs: [false; 5],
            pivot: Drive::new(4.0),
            scale_mg: 0,
            mixer_mg: 0,
            mixer_briquettes: 0,
            belt: vec![900_000, 650_000, 400_000, 150_000],
            falling: Vec::new(),
            mixing_ns: 0,
            batches: 0,
            fed: 0,
            unmixed_mg: 0,
            spilt_mg: 0,
            discharged: false,
            ref_a_mg: 20 * MG_PER_KG,
            ref_b_mg: 35 * MG_PER_KG,
            zero_mg: MG_PER_KG / 10,
            capacity_mg: 60 * MG_PER_KG,
            flow_a: 2 * MG_PER_KG,
            flow_b: 2 * MG_PER_KG,
            flow_c: 5 * MG_PER_KG,
            discharge: 20 * MG_PER_KG,
            belt_speed: UM_PER_M / 10,
            belt_len: UM_PER_M,
            spacing: UM_PER_M / 4,
        }
    }

    fn a(&self) -> bool {
        self.scale_mg >= self.ref_a_mg
    }
    fn b(&self) -> bool {
        self.scale_mg >= self.ref_b_mg
    }
    fn z(&self) -> bool {
        self.scale_mg <= self.zero_mg
    }
    fn d(&self) -> bool {
        self.falling
            .iter()
            .any(|&t| (SEEN_FROM_NS..SEEN_UNTIL_NS).contains(&t))
    }

    fn step_scale(&mut self, dt_ns: i64) {
        let [va, vb, vc, ..] = self.outs;
        let inflow =
            per_dt(self.flow_a, dt_ns) * i64::from(va) + per_dt(self.flow_b, dt_ns) * i64::from(vb);
        self.scale_mg += inflow;
        if self.scale_mg > self.capacity_mg {
            self.spilt_mg += self.scale_mg - self.capacity_mg;
            self.scale_mg = self.capacity_mg;
        }
        if vc {
            let out = per_dt(self.flow_c, dt_ns).min(self.scale_mg);
            self.scale_mg -= out;
            self.mixer_mg += out;
        }
    }

    fn step_belt(&mut self, dt_ns: i64) {
        for t in &mut self.falling {
            *t += dt_ns;
        }
        let landed = self.falling.iter().filter(|&&t| t >= FALL_NS).count() as u32;
        self.falling.retain(|&t| t < FALL_NS);
        self.mixer_briquettes += landed;
        self.fed += landed;
        if !self.outs[3] {
            return;
        }
        let dx = per_dt(self.belt_speed, dt_ns);
        for p in &mut self.belt {
            *p += dx;
        }
        let len = self.belt_len;
        // The part of the step travelled beyond the end counts as falling.
        let speed = self.belt_speed.max(1);
        for &p in self.belt.iter().filter(|&&p| p >= len) {
            let over_ns = (i128::from(p - len) * 1_000_000_000 / i128::from(speed)) as i64;
            self.falling.push(over_ns);
        }
        self.belt.retain(|&p| p < len);
        // The operator lays a new briquette as soon as there is room.
        let last = self.belt.last().copied().unwrap_or(len);
        if last >= self.spacing {
            self.belt.push(last - self.spacing);
        }
    }

    fn step_mixer(&mut self, dt_ns: i64) {
        let rotating = self.outs[4];
        let full = self.mixer_mg > 0 || self.mixer_briquettes > 0;
        if rotating && full {
            self.mixing_ns += dt_ns;
        }
        self.pivot.step(dt_ns);
        if self.pivot.fraction() >= 0.5 && full {
            let out = per_dt(self.discharge, dt_ns).min(self.mixer_mg);
            self.mixer_mg -= out;
            if !rotating {
                self.unmixed_mg += out;
            }
            self.mixer_briquettes = 0;
            if self.mixer_mg == 0 {
                self.discharged = true;
            }
        }
        if self.discharged && self.pivot.retracted() {
            self.discharged = false;
            self.batches += 1;
            self.mixing_ns = 0;
        }
    }

    fn set_param(&mut self, key: &str, v: f64) -> Result<(), String> {
        let kg = |v: f64| (v * MG_PER_KG as f64).round() as i64;
        match key {
            "scale" => self.scale_mg = kg(v.clamp(0.0, 1e3)),
            "ref_a" => self.ref_a_mg = kg(positive("dosing", key, v)?.min(1e3)),
            "ref_b" => self.ref_b_mg = kg(positive("dosing", key, v)?.min(1e3)),
            "flow_a" => self.flow_a = kg(positive("dosing", key, v)?.min(1e3)),
            "flow_b" => self.flow_b = kg(positive("dosing", key, v)?.min(1e3)),
            "flow_c" => self.flow_c = kg(positive("dosing", key, v)?.min(1e3)),
            "belt_speed" => {
                self.belt_speed = (positive("dosing", key, v)?.min(10.0) * UM_PER_M as f64) as i64
            }
            "pivot_time" => self.pivot.set_stroke(positive("dosing", key, v)?),
            "angle" => self.pivot.place(v),
            _ => {
                return Err(format!(
                    "dosing: unknown parameter `{key}` (known: scale, ref_a, ref_b, flow_a, flow_b, flow_c, belt_speed, pivot_time, angle)"
                ))
            }
        }
        Ok(())
    }
}

/// What a rate per second gives in `dt_ns`.
fn per_dt(per_s: i64, dt_ns: i64) -> i64 {
    (i128::from(per_s) * i128::from(dt_ns) / 1_000_000_000) as i64
}

impl Plant for Dosing {
    fn name(&self) -> &'static str {
        "dosing"
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
            PIV_DREAPTA => self.pivot.advance = on,
            PIV_STANGA => self.pivot.retract = on,
            _ => {
                if let Some(o) = signal
                    .checked_sub(VALVA_A)
                    .and_then(|i| self.outs.get_mut(i))
                {
                    *o = on;
                }
            }
        }
    }

    fn get(&self, signal: usize) -> Value {
        Value::Bool(match signal {
            START => self.start,
            1 => self.a(),
            2 => self.b(),
            3 => self.z(),
            4 => self.pivot.extended(),
            5 => self.d(),
            6 => self.pivot.retracted(),
            PIV_DREAPTA => self.pivot.advance,
            PIV_STANGA => self.pivot.retract,
            _ => signal
                .checked_sub(VALVA_A)
                .and_then(|i| self.outs.get(i))
                .copied()
                .unwrap_or(false),
        })
    }

    fn quantity(&self, index: usize) -> f64 {
        let kg = |mg: i64| mg as f64 / MG_PER_KG as f64;
        match index {
            0 => kg(self.scale_mg),
            1 => kg(self.mixer_mg),
            2 => f64::from(self.mixer_briquettes),
            3 => self.pivot.fraction(),
            4 => self.mixing_ns as f64 / 1e9,
            5 => f64::from(self.batches),
            6 => f64::from(self.fed),
            7 => kg(self.unmixed_mg),
            8 => kg(self.spilt_mg),
            9 => self.pivot.conflict_ns as f64 / 1e6,
            _ => 0.0,
        }
    }

    fn step(&mut self, dt_ns: i64, _rng: &mut Rng) {
        self.step_scale(dt_ns);
        self.step_belt(dt_ns);
        self.step_mixer(dt_ns);
    }

    fn command(&mut self, name: &str, args: &[(&str, f64)]) -> Result<(), String> {
        match name {
            "set" => args.iter().try_for_each(|(k, v)| self.set_param(k, *v)),
            "empty_belt" => {
                self.belt.clear();
                Ok(())
            }
            _ => Err(format!(
                "the dosing model has no command `{name}` (known: set, empty_belt)"
            )),
        }
    }

    fn commands(&self) -> &'static [(&'static str, &'static str)] {
        &[
            (
                "set",
                "parameters: scale (kg), ref_a, ref_b (kg), flow_a, flow_b, flow_c (kg/s), belt_speed (m/s), pivot_time (s), angle (0..1)",
            ),
            ("empty_belt", "takes every briquette off the conveyor (the operator stops loading until it has moved 0.25 m)"),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const VALVA_B: usize = 8;
    const VALVA_C: usize = 9;
    const MT: usize = 10;
    const ROTIRE: usize = 11;

    fn run(p: &mut Dosing, ms: i64) {
        let mut rng = Rng::new(1);
        for _ in 0..ms {
            p.step(1_000_000, &mut rng);
        }
    }
    fn on(p: &mut Dosing, s: usize, v: bool) {
        p.set(s, Value::Bool(v));
    }
    fn b(p: &Dosing, s: usize) -> bool {
        p.get(s).as_bool()
    }

    #[test]
    fn initial_state() {
        let p = Dosing::new();
        let sensors: Vec<bool> = (1..=6).map(|s| b(&p, s)).collect();
        assert_eq!(sensors, [false, false, true, false, false, true]);
    }

    #[test]
    fn scale_thresholds_at_the_exact_weights() {
        let mut p = Dosing::new();
        on(&mut p, VALVA_A, true);
        run(&mut p, 9_999);
        assert!(!b(&p, 1));
        assert!(!b(&p, 3), "not at zero any more");
        run(&mut p, 1);
        assert!(b(&p, 1));
        assert_eq!(p.quantity(0), 20.0);
        on(&mut p, VALVA_A, false);
        on(&mut p, VALVA_B, true);
        run(&mut p, 7_499);
        assert!(!b(&p, 2));
        run(&mut p, 1);
        assert!(b(&p, 2));
        assert_eq!(p.quantity(0), 35.0);
        on(&mut p, VALVA_B, false);
        on(&mut p, VALVA_C, true);
        run(&mut p, 6_979);
        // 0.105 kg left
        assert!(!b(&p, 3));
        run(&mut p, 1);
        assert!(b(&p, 3));
        run(&mut p, 100);
        assert_eq!((p.quantity(0), p.quantity(1)), (0.0, 35.0));
    }

    #[test]
    fn briquettes_pulse_d_once_each_and_land() {
        let mut p = Dosing::new();
        on(&mut p, MT, true);
        // the first lies at 0.9 m: leaves the belt at 1 s, seen 1.1..1.2 s
        run(&mut p, 1_099);
        assert!(!b(&p, 5));
        run(&mut p, 1);
        assert!(b(&p, 5));
        run(&mut p, 99);
        assert!(b(&p, 5));
        run(&mut p, 1);
        assert!(!b(&p, 5));
        run(&mut p, 99);
        assert_eq!(p.quantity(2), 0.0);
        run(&mut p, 1);
        assert_eq!(p.quantity(2), 1.0);
        // the second (0.65 m) is seen from 3.6 s
        run(&mut p, 2_299);
        assert!(!b(&p, 5));
        run(&mut p, 2);
        assert!(b(&p, 5));
        // stopping the belt does not stop a falling briquette
        on(&mut p, MT, false);
        run(&mut p, 1_000);
        assert_eq!(p.quantity(6), 2.0);
        assert!(!b(&p, 5));
    }

    #[test]
    fn belt_keeps_loaded_at_the_spacing() {
        let mut p = Dosing::new();
        on(&mut p, MT, true);
        run(&mut p, 60_000);
        // 6 m of belt = 24 briquettes, plus the four of the start minus the
        // ones still on the belt or falling
        assert_eq!(p.belt.len(), 4);
        assert_eq!(p.quantity(6) as usize + p.falling.len(), 24);
    }

    #[test]
    fn pivot_discharge_and_batch() {
        let mut p = Dosing::new();
        assert!(p.command("set", &[("scale", 35.0)]).is_ok());
        on(&mut p, VALVA_C, true);
        run(&mut p, 8_000);
        on(&mut p, ROTIRE, true);
        on(&mut p, PIV_DREAPTA, true);
        run(&mut p, 3_959);
        assert!(!b(&p, 4) && !b(&p, 6));
        run(&mut p, 1);
        assert!(b(&p, 4));
        // from 50 % (2 s) on it pours 20 kg/s: 35 kg are out in 1.75 s
        assert_eq!(p.quantity(1), 0.0);
        on(&mut p, PIV_DREAPTA, false);
        on(&mut p, PIV_STANGA, true);
        run(&mut p, 4_000);
        assert!(b(&p, 6));
        assert_eq!(p.quantity(5), 1.0);
        assert_eq!(p.quantity(7), 0.0);
        assert_eq!(p.quantity(1), 0.0);
    }

    #[test]
    fn discharging_without_rotation_is_unmixed() {
        let mut p = Dosing::new();
        p.mixer_mg = 10 * MG_PER_KG;
        on(&mut p, PIV_DREAPTA, true);
        run(&mut p, 4_000);
        assert_eq!(p.quantity(7), 10.0);
    }

    #[test]
    fn parameters() {
        let mut p = Dosing::new();
        assert!(p.command("set", &[("ref_a", 5.0)]).is_ok());
        on(&mut p, VALVA_A, true);
        run(&mut p, 2_500);
        assert!(b(&p, 1));
        assert!(p.command("set", &[("ref_a", -1.0)]).is_err());
        assert!(p
            .command("set", &[("colour", 1.0)])
            .is_err_and(|e| e.contains("unknown parameter `colour`")));
        assert!(p.command("fly", &[]).is_err());
        assert!(p.command("empty_belt", &[]).is_ok());
        assert!(p.belt.is_empty());
    }
}
