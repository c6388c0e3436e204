//! A10, the temperature loop of problem 10 of the textbook's chapter 5
//! (processes digest A10 and D1): the temperature of the heat-carrying
//! agent of a granulation plant, heated through a 4–20 mA gas valve.
//!
//! A first-order-plus-dead-time process, the usual model of such a loop:
//!   dT/dt = (T_amb + K · u(t − θ) − T) / τ
//! with u the valve opening in %, K = 1.5 °C/%, τ = 60 s, θ = 5 s and
//! T_amb = 20 °C (chosen: a heater that needs a minute to settle and
//! reaches 170 °C fully open, with the transport delay of a gas burner and
//! a steam line; the source gives no numbers). It is integrated exactly
//! over each 10 ms step (T approaches its target by 1 − e^(−dt/τ)), so the
//! step response does not depend on the step size.
//!
//! Signals: the transmitter `T_raw` (0…200 °C → 4…20 mA → 819…4095 raw,
//! the sources' analog scaling; rounded to the nearest count) and the valve
//! command `Ventil_raw` (819…4095 raw → 0…100 %, clamped; below 819 the
//! valve is closed).

use crate::{Dir, Kind, Plant, Quantity, Rng, Signal, Value};

const SIGNALS: &[Signal] = &[
    Signal {
        name: "T_raw",
        dir: Dir::Sensor,
        kind: Kind::Int,
        doc: "temperature transmitter, 0..200 °C as 4..20 mA = 819..4095",
    },
    Signal {
        name: "Ventil_raw",
        dir: Dir::Actuator,
        kind: Kind::Int,
        doc: "gas valve position, 4..20 mA = 819..4095 for 0..100 %",
    },
];

const QUANTITIES: &[Quantity] = &[
    Quantity {
        name: "temp",
        unit: "°C",
        doc: "temperature of the heat-carrying agent",
    },
    Quantity {
        name: "valve",
        unit: "%",
        doc: "valve opening commanded now",
    },
    Quantity {
        name: "heating",
        unit: "%",
        doc: "valve opening acting on the process now (after the dead time)",
    },
];

const RAW_MIN: i64 = 819;
const RAW_SPAN: i64 = 4095 - 819;
const STEP_NS: i64 = 10_000_000;
const RANGE_C: f64 = 200.0;

#[derive(Clone, Debug)]
pub struct PidTemperature {
    temp: f64,
    raw_out: i64,
    /// Valve openings of the last θ, one per step, oldest at `head`.
    delay: Vec<f64>,
    head: usize,
    gain: f64,
    tau_s: f64,
    ambient: f64,
}

impl Default for PidTemperature {
    fn default() -> Self {
        PidTemperature::new()
    }
}

/// Raw 819..4095 to a valve opening in %.
pub fn valve_percent(raw: i64) -> f64 {
    (raw - RAW_MIN).clamp(0, RAW_SPAN) as f64 * 100.0 / RAW_SPAN as f64
}

/// °C to the transmitter's raw value (0..200 °C → 819..4095).
pub fn transmitter_raw(temp: f64) -> i64 {
    let t = if temp.is_finite() {
        temp.clamp(0.0, RANGE_C)
    } else {
        0.0
    };
    RAW_MIN + (t / RANGE_C * RAW_SPAN as f64).round() as i64
}

impl PidTemperature {
    pub fn new() -> PidTemperature {
        let mut p = PidTemperature {
            temp: 20.0,
            raw_out: RAW_MIN,
            delay: Vec::new(),
            head: 0,
            gain: 1.5,
            tau_s: 60.0,
            ambient: 20.0,
        };
        p.set_dead_time(5.0);
        p
    }

    fn set_dead_time(&mut self, s: f64) {
        let steps = ((s.clamp(0.0, 600.0) * 1e9) / STEP_NS as f64).round() as usize;
        let now = self.delay.get(self.head).copied().unwrap_or(0.0);
        self.delay = vec![now; steps.max(1)];
        self.head = 0;
    }

    fn set_param(&mut self, key: &str, v: f64) -> Result<(), String> {
        if !v.is_finite() {
            return Err(format!("pid-temperature: `{key}` must be a finite number"));
        }
        match key {
            "temp" => self.temp = v.clamp(-50.0, 500.0),
            "ambient" => self.ambient = v.clamp(-50.0, 500.0),
            "gain" => self.gain = v.clamp(-100.0, 100.0),
            "tau" if v > 0.0 => self.tau_s = v.min(1e5),
            "dead_time" if v >= 0.0 => self.set_dead_time(v),
            "tau" | "dead_time" => {
                return Err(format!("pid-temperature: `{key}` must be greater than 0"))
            }
            _ => {
                return Err(format!(
                    "pid-temperature: unknown parameter `{key}` (known: temp, ambient (°C), gain (°C/%), tau, dead_time (s))"
                ))
            }
        }
        Ok(())
    }
}

impl Plant for PidTemperature {
    fn name(&self) -> &'static str {
        "pid-temperature"
    }
    fn signals(&self) -> &'static [Signal] {
        SIGNALS
    }
    fn quantities(&self) -> &'static [Quantity] {
        QUANTITIES
    }
    fn step_ns(&self) -> i64 {
        STEP_NS
    }

    fn set(&mut self, signal: usize, value: Value) {
        if signal == 1 {
            self.raw_out = match value {
                Value::Int(i) => i,
                Value::Real(r) if r.is_finite() => r.round().clamp(-1e9, 1e9) as i64,
                _ => 0,
            };
        }
    }

    fn get(&self, signal: usize) -> Value {
        match signal {
            0 => Value::Int(transmitter_raw(self.temp)),
            1 => Value::Int(self.raw_out),
            _ => Value::Bool(false),
        }
    }

    fn quantity(&self, index: usize) -> f64 {
        match index {
            0 => self.temp,
            1 => valve_percent(self.raw_out),
            2 => self.delay.get(self.head).copied().unwrap_or(0.0),
            _ => 0.0,
        }
    }

    fn step(&mut self, dt_ns: i64, _rng: &mut Rng) {
        // the opening that entered the line θ ago acts now; today's enters
        let acting = self.delay.get(self.head).copied().unwrap_or(0.0);
        if let Some(slot) = self.delay.get_mut(self.head) {
            *slot = valve_percent(self.raw_out);
        }
        self.head = (self.head + 1) % self.delay.len().max(1);
        let target = self.ambient + self.gain * acting;
        let k = 1.0 - (-(dt_ns as f64 / 1e9) / self.tau_s).exp();
        self.temp += (target - self.temp) * k;
    }

    fn command(&mut self, name: &str, args: &[(&str, f64)]) -> Result<(), String> {
        match name {
            "set" => args.iter().try_for_each(|(k, v)| self.set_param(k, *v)),
            _ => Err(format!(
                "the pid-temperature model has no command `{name}` (known: set)"
            )),
        }
    }

    fn commands(&self) -> &'static [(&'static str, &'static str)] {
        &[(
            "set",
            "parameters: temp, ambient (°C), gain (°C per % of valve), tau, dead_time (s)",
        )]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(p: &mut PidTemperature, s: i64) {
        let mut rng = Rng::new(1);
        for _ in 0..s * 100 {
            p.step(STEP_NS, &mut rng);
        }
    }

    #[test]
    fn analog_scaling() {
        assert_eq!(transmitter_raw(0.0), 819);
        assert_eq!(transmitter_raw(100.0), 2457);
        assert_eq!(transmitter_raw(200.0), 4095);
        assert_eq!(transmitter_raw(250.0), 4095);
        assert_eq!(transmitter_raw(f64::NAN), 819);
        assert_eq!(valve_percent(819), 0.0);
        assert_eq!(valve_percent(2457), 50.0);
        assert_eq!(valve_percent(4095), 100.0);
        assert_eq!(valve_percent(0), 0.0);
        assert_eq!(valve_percent(9999), 100.0);
        let p = PidTemperature::new();
        assert_eq!(p.get(0), Value::Int(transmitter_raw(20.0)));
        assert_eq!(p.get(0), Value::Int(1147));
    }

    #[test]
    fn dead_time_then_first_order_response() {
        let mut p = PidTemperature::new();
        p.set(1, Value::Int(2457)); // 50 %
        run(&mut p, 5);
        // nothing yet: the dead time is 5 s
        assert_eq!(p.quantity(0), 20.0);
        assert_eq!(p.quantity(2), 50.0);
        run(&mut p, 60);
        // one time constant after the dead time: 63.2 % of the 75 °C step
        let expect = 20.0 + 75.0 * (1.0 - (-1.0f64).exp());
        assert!((p.quantity(0) - expect).abs() < 1e-9, "{}", p.quantity(0));
        run(&mut p, 600);
        assert!((p.quantity(0) - 95.0).abs() < 0.01);
        assert_eq!(p.get(0), Value::Int(transmitter_raw(95.0)));
    }

    #[test]
    fn cools_back_to_ambient() {
        let mut p = PidTemperature::new();
        assert!(p.command("set", &[("temp", 80.0)]).is_ok());
        run(&mut p, 60);
        let expect = 20.0 + 60.0 * (-1.0f64).exp();
        assert!((p.quantity(0) - expect).abs() < 1e-9);
    }

    #[test]
    fn parameters() {
        let mut p = PidTemperature::new();
        assert!(p.command("set", &[("dead_time", 0.0)]).is_ok());
        p.set(1, Value::Int(4095));
        run(&mut p, 1);
        assert!(p.quantity(0) > 20.0);
        assert!(p.command("set", &[("tau", 0.0)]).is_err());
        assert!(p.command("set", &[("pressure", 1.0)]).is_err());
        assert!(p.command("heat", &[]).is_err());
    }
}
