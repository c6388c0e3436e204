//! A6, liquid temperature control (problem 6 of the textbook's chapter 5;
//! processes digest A6).
//!
//! Tank 1 holds the liquid, a heating resistor (`rezistenta`), an air
//! blower that cools it (`racire`, "răcire") and the temperature
//! transducer (`temp_citita`). Valve 1 lets make-up liquid into tank 1;
//! valve 2 with the pump (`pompa`) transfers liquid to tank 2, which drains
//! continuously to a consumer and has two level switches (`senzor_plin`
//! high, `senzor_gol` low). The valve commands are inverted as in the
//! source: `valva_1`/`valva_2` TRUE = valve CLOSED.
//!
//! Parameters (the digest gives none; chosen so the heater brings the
//! liquid into the 60–65 °C band in minutes and tank 2 fills in about two):
//! - tank 1: 50 L of water (4186 J/(kg·K), 1 kg/L), at most 60 L (an
//!   overflow spills the rest); 20 °C ambient, losses 10 W/K;
//! - heater 9 kW (+0.043 K/s at 50 L); blower 200 W/K more towards ambient
//!   (−0.045 K/s at 67 °C);
//! - valve 1: 0.1 L/s of make-up at 15 °C (−0.094 K/s at 62 °C and 50 L);
//! - pump: 0.1 L/s into tank 2 while `pompa` runs with valve 2 open and
//!   tank 1 holds more than 5 L; tank 2: 10 L, drains 0.04 L/s; `senzor_plin`
//!   on from 8 L, `senzor_gol` on up to 2 L, so it fills from empty to full
//!   in 133 s and drains from full to empty-switch in 150 s;
//! - transducer: 0–100 °C as 4–20 mA on a 12-bit 0–20 mA card, so raw =
//!   819 + T·32.76, rounded, held at 819..4095 outside the range.
//!
//! The liquid is perfectly mixed (one temperature) and the transducer has no
//! lag, so an out-of-band temperature is seen in the next scan. Heater and
//! blower on together count as `conflicts`. A tank that runs over (tank 1
//! above 60 L, tank 2 above 10 L) counts one of `overflows` each time it
//! starts, and what ran over is `spilled` (L): a right program keeps both 0.

use super::pneumatic::positive;
use crate::{Dir, Kind, Plant, Quantity, Rng, Signal, Value};

const SIGNALS: &[Signal] = &[
    sig("senzor_plin", Dir::Sensor, Kind::Bool, "tank 2 full"),
    sig("senzor_gol", Dir::Sensor, Kind::Bool, "tank 2 empty"),
    sig(
        "temp_citita",
        Dir::Sensor,
        Kind::Int,
        "temperature transducer, raw 819..4095 (0..100 °C)",
    ),
    sig(
        "valva_1",
        Dir::Actuator,
        Kind::Bool,
        "inlet valve 1, TRUE = closed",
    ),
    sig(
        "valva_2",
        Dir::Actuator,
        Kind::Bool,
        "transfer valve 2, TRUE = closed",
    ),
    sig("rezistenta", Dir::Actuator, Kind::Bool, "heating resistor"),
    sig(
        "racire",
        Dir::Actuator,
        Kind::Bool,
        "air blower, cooling (răcire)",
    ),
    sig("pompa", Dir::Actuator, Kind::Bool, "transfer pump"),
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
    Quantity {
        name: "temp",
        unit: "°C",
        doc: "liquid temperature in tank 1",
    },
    Quantity {
        name: "level1",
        unit: "L",
        doc: "liquid in tank 1",
    },
    Quantity {
        name: "level2",
        unit: "L",
        doc: "liquid in tank 2",
    },
    Quantity {
        name: "conflicts",
        unit: "ms",
        doc: "time heater and blower were on together",
    },
    Quantity {
        name: "overflows",
        unit: "",
        doc: "times tank 1 or tank 2 ran over",
    },
    Quantity {
        name: "spilled",
        unit: "L",
        doc: "liquid that ran over the rims",
    },
];

// Signal indices, in the order of SIGNALS.
const PLIN: usize = 0;
const GOL: usize = 1;
const TEMP_CITITA: usize = 2;
const VALVA_1: usize = 3;
const POMPA: usize = 7;

/// J/(L·K): water at 1 kg/L.
const HEAT_CAPACITY: f64 = 4186.0;

/// Raw reading of a 4–20 mA transducer over 0..`span` on a 12-bit 0–20 mA
/// card: 4 mA = 819, 20 mA = 4095, saturated outside the range.
pub fn raw_4_20(value: f64, span: f64) -> i64 {
    let raw = 819.0 + value / span * 3276.0;
    if raw.is_nan() {
        return 819;
    }
    raw.round().clamp(819.0, 4095.0) as i64
}

/// The two tanks.
#[derive(Clone, Debug)]
pub struct TankTemperature {
    temp: f64,
    level1: f64,
    level2: f64,
    /// valva_1, valva_2, rezistenta, racire, pompa as last set.
    out: [bool; 5],
    conflict_ns: i64,
    overflows: u64,
    spilled: f64,
    /// Tank 1, tank 2 running over in the last step.
    over: [bool; 2],
    // parameters
    ambient: f64,
    inlet_temp: f64,
    heater_w: f64,
    loss_w_per_k: f64,
    blower_w_per_k: f64,
    inflow: f64,
    pump_flow: f64,
    drain: f64,
    max1: f64,
    min1: f64,
    max2: f64,
    full2: f64,
    empty2: f64,
}

impl Default for TankTemperature {
    fn default() -> Self {
        TankTemperature::new()
    }
}

impl TankTemperature {
    /// 50 L at 20 °C in tank 1, tank 2 empty, everything off (valves open).
    pub fn new() -> TankTemperature {
        TankTemperature {
            temp: 20.0,
            level1: 50.0,
            level2: 0.0,
            out: [false; 5],
            conflict_ns: 0,
            overflows: 0,
            spilled: 0.0,
            over: [false; 2],
            ambient: 20.0,
            inlet_temp: 15.0,
            heater_w: 9000.0,
            loss_w_per_k: 10.0,
            blower_w_per_k: 200.0,
            inflow: 0.1,
            pump_flow: 0.1,
            drain: 0.04,
            max1: 60.0,
            min1: 5.0,
            max2: 10.0,
            full2: 8.0,
            empty2: 2.0,
        }
    }

    fn valve_1_open(&self) -> bool {
        !self.out[0]
    }
    fn valve_2_open(&self) -> bool {
        !self.out[1]
    }

    fn set_param(&mut self, key: &str, v: f64) -> Result<(), String> {
        if !v.is_finite() {
            return Err(format!("tank-temperature: `{key}` must be a finite number"));
        }
        let nonneg = |v: f64| -> Result<f64, String> {
            if v >= 0.0 {
                Ok(v)
            } else {
                Err(format!("tank-temperature: `{key}` must be >= 0"))
            }
        };
        match key {
            "temp" => self.temp = v.clamp(-50.0, 200.0),
            "ambient" => self.ambient = v.clamp(-50.0, 200.0),
            "inlet_temp" => self.inlet_temp = v.clamp(-50.0, 200.0),
            "level1" => self.level1 = nonneg(v)?.min(self.max1),
            "level2" => self.level2 = nonneg(v)?.min(self.max2),
            "heater" => self.heater_w = nonneg(v)?,
            "losses" => self.loss_w_per_k = nonneg(v)?,
            "blower" => self.blower_w_per_k = nonneg(v)?,
            "inflow" => self.inflow = nonneg(v)?,
            "pump_flow" => self.pump_flow = nonneg(v)?,
            "drain" => self.drain = nonneg(v)?,
            "capacity2" => {
                // the switches keep their fractions of the tank
                let c = positive("tank-temperature", key, v)?;
                let k = c / self.max2;
                (self.max2, self.full2, self.empty2) = (c, self.full2 * k, self.empty2 * k);
                self.level2 = self.level2.min(c);
            }
            _ => {
                return Err(format!(
                    "tank-temperature: unknown parameter `{key}` (known: temp, ambient, \
                     inlet_temp, level1, level2, heater, losses, blower, inflow, pump_flow, \
                     drain, capacity2)"
                ))
            }
        }
        Ok(())
    }
}

impl Plant for TankTemperature {
    fn name(&self) -> &'static str {
        "tank-temperature"
    }
    fn mimic(&self) -> Option<&'static str> {
        Some("tank-temperature")
    }
    fn signals(&self) -> &'static [Signal] {
        SIGNALS
    }
    fn quantities(&self) -> &'static [Quantity] {
        QUANTITIES
    }
    /// Thermal and level dynamics are slow: one step per 10 ms scan.
    fn step_ns(&self) -> i64 {
        10_000_000
    }

    fn set(&mut self, signal: usize, value: Value) {
        if (VALVA_1..=POMPA).contains(&signal) {
            if let Some(o) = self.out.get_mut(signal - VALVA_1) {
                *o = value.as_bool();
            }
        }
    }

    fn get(&self, signal: usize) -> Value {
        match signal {
            PLIN => Value::Bool(self.level2 >= self.full2),
            GOL => Value::Bool(self.level2 <= self.empty2),
            TEMP_CITITA => Value::Int(raw_4_20(self.temp, 100.0)),
            i if (VALVA_1..=POMPA).contains(&i) => {
                Value::Bool(self.out.get(i - VALVA_1).copied().unwrap_or(false))
            }
            _ => Value::Bool(false),
        }
    }

    fn quantity(&self, index: usize) -> f64 {
        match index {
            0 => self.temp,
            1 => self.level1,
            2 => self.level2,
            3 => self.conflict_ns as f64 / 1e6,
            4 => self.overflows as f64,
            5 => self.spilled,
            _ => 0.0,
        }
    }

    fn step(&mut self, dt_ns: i64, _rng: &mut Rng) {
        let dt = dt_ns as f64 / 1e9;
        let [_, _, heater, blower, pump] = self.out;
        if heater && blower {
            self.conflict_ns = self.conflict_ns.saturating_add(dt_ns);
        }
        // heat balance of tank 1 (W), then the make-up liquid mixing in
        let mut power = -self.loss_w_per_k * (self.temp - self.ambient);
        if heater {
            power += self.heater_w;
        }
        if blower {
            power -= self.blower_w_per_k * (self.temp - self.ambient);
        }
        let inflow = if self.valve_1_open() {
            self.inflow * dt
        } else {
            0.0
        };
        let mass = self.level1.max(1.0);
        self.temp += power * dt / (HEAT_CAPACITY * mass)
            + inflow * (self.inlet_temp - self.temp) / (mass + inflow);
        self.level1 += inflow;
        let spill1 = (self.level1 - self.max1).max(0.0);
        self.level1 -= spill1;
        // transfer, then the consumer
        if pump && self.valve_2_open() && self.level1 > self.min1 {
            let q = (self.pump_flow * dt).min(self.level1 - self.min1);
            self.level1 -= q;
            self.level2 += q;
        }
        self.level2 = (self.level2 - self.drain * dt).max(0.0);
        let spill2 = (self.level2 - self.max2).max(0.0);
        self.level2 -= spill2;
        let over = [spill1 > 0.0, spill2 > 0.0];
        for (now, was) in over.iter().zip(&self.over) {
            if *now && !*was {
                self.overflows += 1;
            }
        }
        self.over = over;
        self.spilled += spill1 + spill2;
    }

    fn command(&mut self, name: &str, args: &[(&str, f64)]) -> Result<(), String> {
        match name {
            "set" => args.iter().try_for_each(|(k, v)| self.set_param(k, *v)),
            _ => Err(format!(
                "the tank-temperature model has no command `{name}` (known: set)"
            )),
        }
    }

    fn commands(&self) -> &'static [(&'static str, &'static str)] {
        &[(
            "set",
            "temp, ambient, inlet_temp (°C), level1, level2 (L), heater (W), losses, blower \
             (W/K), inflow, pump_flow, drain (L/s), capacity2 (L)",
        )]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const VALVA_2: usize = 4;
    const REZISTENTA: usize = 5;
    const RACIRE: usize = 6;

    fn run(t: &mut TankTemperature, ms: i64) {
        let mut rng = Rng::new(1);
        for _ in 0..ms / 10 {
            t.step(10_000_000, &mut rng);
        }
    }

    fn on(t: &mut TankTemperature, signal: usize, v: bool) {
        t.set(signal, Value::Bool(v));
    }

    /// Valves closed, nothing on: nothing changes at ambient.
    fn closed() -> TankTemperature {
        let mut t = TankTemperature::new();
        on(&mut t, VALVA_1, true);
        on(&mut t, VALVA_2, true);
        assert_eq!(t.command("set", &[("drain", 0.0)]), Ok(()));
        t
    }

    #[test]
    fn each_overflow_of_either_tank_counts_and_spills() {
        // valve 1 open: 0.1 L/s into 50 L; the rim at 60 L after 100 s
        let mut t = closed();
        on(&mut t, VALVA_1, false);
        run(&mut t, 99_990);
        assert_eq!((t.quantity(4), t.quantity(5)), (0.0, 0.0));
        run(&mut t, 1_010);
        assert_eq!(t.quantity(1), 60.0);
        assert_eq!(t.quantity(4), 1.0);
        assert!((t.quantity(5) - 0.1).abs() < 0.002, "{}", t.quantity(5));
        // closed and opened again at the rim: a second overflow
        on(&mut t, VALVA_1, true);
        run(&mut t, 1_000);
        on(&mut t, VALVA_1, false);
        run(&mut t, 10);
        assert_eq!(t.quantity(4), 2.0);
        // tank 2: 0.1 L/s pumped, 0.04 L/s drained: 10 L after 166.7 s
        let mut t = closed();
        assert_eq!(t.command("set", &[("drain", 0.04)]), Ok(()));
        on(&mut t, VALVA_2, false);
        on(&mut t, POMPA, true);
        run(&mut t, 166_000);
        assert_eq!(t.quantity(4), 0.0);
        run(&mut t, 1_000);
        assert_eq!(t.quantity(2), 10.0);
        assert_eq!(t.quantity(4), 1.0);
    }

    #[test]
    fn transducer_scaling_4_to_20_ma() {
        assert_eq!(raw_4_20(0.0, 100.0), 819);
        assert_eq!(raw_4_20(100.0, 100.0), 4095);
        assert_eq!(raw_4_20(60.0, 100.0), 2785); // 2784.6
        assert_eq!(raw_4_20(65.0, 100.0), 2948); // 2948.4
        assert_eq!(raw_4_20(-10.0, 100.0), 819);
        assert_eq!(raw_4_20(150.0, 100.0), 4095);
        assert_eq!(raw_4_20(f64::NAN, 100.0), 819);
        let mut t = TankTemperature::new();
        assert_eq!(t.command("set", &[("temp", 62.0)]), Ok(()));
        assert_eq!(t.get(TEMP_CITITA), Value::Int(2850)); // 2850.12
    }

    #[test]
    fn the_heater_warms_50_litres_at_43_millikelvin_per_second() {
        let mut t = closed();
        assert_eq!(t.command("set", &[("losses", 0.0)]), Ok(()));
        on(&mut t, REZISTENTA, true);
        run(&mut t, 100_000);
        let expected = 20.0 + 9000.0 * 100.0 / (4186.0 * 50.0);
        assert!((t.quantity(0) - expected).abs() < 1e-9, "{}", t.quantity(0));
        assert_eq!(t.quantity(1), 50.0);
    }

    #[test]
    fn the_blower_cools_faster_than_the_losses_alone() {
        let mut a = closed();
        let mut b = closed();
        for t in [&mut a, &mut b] {
            assert_eq!(t.command("set", &[("temp", 67.0)]), Ok(()));
        }
        on(&mut b, RACIRE, true);
        run(&mut a, 10_000);
        run(&mut b, 10_000);
        // first step: 10 W/K vs 210 W/K over 47 K
        assert!(
            a.quantity(0) > 66.9 && a.quantity(0) < 67.0,
            "{}",
            a.quantity(0)
        );
        assert!(
            b.quantity(0) < 66.6 && b.quantity(0) > 66.4,
            "{}",
            b.quantity(0)
        );
    }

    #[test]
    fn make_up_liquid_cools_and_fills_tank_1_up_to_the_overflow() {
        let mut t = closed();
        assert_eq!(t.command("set", &[("temp", 62.0), ("losses", 0.0)]), Ok(()));
        on(&mut t, VALVA_1, false);
        run(&mut t, 10);
        // 1 mL at 15 °C into 50 L at 62 °C
        let expected = 62.0 + 0.001 * (15.0 - 62.0) / 50.001;
        assert!((t.quantity(0) - expected).abs() < 1e-12);
        run(&mut t, 200_000);
        assert_eq!(t.quantity(1), 60.0);
    }

    #[test]
    fn tank_2_fills_through_valve_2_and_the_pump_and_switches_at_8_and_2_litres() {
        let mut t = TankTemperature::new();
        on(&mut t, VALVA_1, true);
        on(&mut t, POMPA, true);
        assert!(t.get(GOL).as_bool());
        // net 0.06 L/s: 2 L after 33.3 s, 8 L after 133.3 s
        run(&mut t, 33_320);
        assert!(t.get(GOL).as_bool());
        run(&mut t, 20);
        assert!(!t.get(GOL).as_bool());
        run(&mut t, 133_320 - 33_340);
        assert!(!t.get(PLIN).as_bool());
        run(&mut t, 20);
        assert!(t.get(PLIN).as_bool(), "{}", t.quantity(2));
        // valve 2 closed: the pump moves nothing, tank 2 drains
        on(&mut t, VALVA_2, true);
        let l1 = t.quantity(1);
        run(&mut t, 1000);
        assert_eq!(t.quantity(1), l1);
        assert!((t.quantity(2) - (8.0 - 0.04)).abs() < 0.002);
    }

    #[test]
    fn the_pump_leaves_5_litres_in_tank_1() {
        let mut t = TankTemperature::new();
        on(&mut t, VALVA_1, true);
        on(&mut t, POMPA, true);
        assert_eq!(t.command("set", &[("level1", 6.0), ("drain", 0.0)]), Ok(()));
        run(&mut t, 60_000);
        assert_eq!(t.quantity(1), 5.0);
        assert!((t.quantity(2) - 1.0).abs() < 1e-9);
    }

    #[test]
    fn heater_and_blower_together_count_as_conflict() {
        let mut t = closed();
        on(&mut t, REZISTENTA, true);
        on(&mut t, RACIRE, true);
        run(&mut t, 250);
        assert_eq!(t.quantity(3), 250.0);
    }

    #[test]
    fn parameters_and_errors() {
        let mut t = TankTemperature::new();
        assert_eq!(
            t.command("set", &[("capacity2", 20.0), ("level2", 15.0)]),
            Ok(())
        );
        assert!(!t.get(PLIN).as_bool());
        assert_eq!(t.command("set", &[("level2", 16.0)]), Ok(()));
        assert!(t.get(PLIN).as_bool());
        assert!(t
            .command("set", &[("level1", -1.0)])
            .is_err_and(|e| e.contains(">= 0")));
        assert!(t
            .command("set", &[("temp", f64::INFINITY)])
            .is_err_and(|e| e.contains("finite")));
        assert!(t
            .command("set", &[("pressure", 1.0)])
            .is_err_and(|e| e.contains("unknown parameter `pressure`")));
        assert!(t
            .command("heat", &[])
            .is_err_and(|e| e.contains("no command `heat`")));
    }
}
