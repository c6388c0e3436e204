//! Part B, the Festo MPS distribution station (the Romanian lab manual,
//! lab 1; processes digest Part B).
//!
//! A stack magazine holds workpieces; a single-acting ejecting cylinder
//! (`EjectOut`, spring return; `CylBack`/`CylFront`) pushes the bottom one
//! out to the pick-up point; a swivel arm on a double-solenoid rotary drive
//! (`ArmToMag`/`ArmToNxt`; `ArmMag`/`ArmNext`) with a vacuum cup (`VacOn`,
//! blow-off `VacOff`, vacuum switch `Vacuum`) carries it to the next
//! station. `PartAv` sees a workpiece in the bottom slot of the magazine
//! (TRUE = present, the digest's simulator convention).
//!
//! Times, as the digest suggests: cylinder stroke 0.5 s, swivel 1.0 s,
//! vacuum build-up 0.3 s. The vacuum builds only when the cup sits on a
//! workpiece (arm at the magazine and a workpiece at the pick-up point, or
//! one already held); without `VacOn` it decays in 0.3 s, ten times faster
//! with the blow-off `VacOff`. The cup holds its workpiece while the vacuum
//! is above a third of full; losing it puts the workpiece down where the
//! arm is: at the next station it is delivered, at the magazine it is back
//! at the pick-up point, in between it is dropped. The magazine starts with
//! 4 workpieces (`set stack=N`): one falls into the slot whenever the
//! cylinder is back and the slot is empty. Pushing a workpiece onto an
//! occupied pick-up point is a jam (the cylinder stops, counted once).
//!
//! The operator signals keep what was set: `STOP_N` is normally closed, so
//! the model starts with it TRUE (not pressed).

use super::pneumatic::{positive, Drive};
use super::{q, sig};
use crate::{Dir, Plant, Quantity, Rng, Signal, Value};

const SIGNALS: &[Signal] = &[
    sig("CylBack", Dir::Sensor, "ejecting cylinder retracted (I0.1)"),
    sig("CylFront", Dir::Sensor, "ejecting cylinder extended (I0.2)"),
    sig(
        "Vacuum",
        Dir::Sensor,
        "vacuum switch: workpiece held (I0.3)",
    ),
    sig("ArmMag", Dir::Sensor, "swivel arm at the magazine (I0.4)"),
    sig(
        "ArmNext",
        Dir::Sensor,
        "swivel arm at the downstream station (I0.5)",
    ),
    sig(
        "PartAv",
        Dir::Sensor,
        "workpiece in the magazine's bottom slot (I0.6)",
    ),
    sig("START", Dir::Operator, "start button (I1.0)"),
    sig(
        "STOP_N",
        Dir::Operator,
        "stop button, normally closed: FALSE when pressed (I1.1)",
    ),
    sig("ResetBtn", Dir::Operator, "reset button (I1.3)"),
    sig(
        "EjectOut",
        Dir::Actuator,
        "extend the ejecting cylinder (O0.0)",
    ),
    sig("VacOn", Dir::Actuator, "vacuum on (O0.1)"),
    sig("VacOff", Dir::Actuator, "blow-off pulse (O0.2)"),
    sig(
        "ArmToMag",
        Dir::Actuator,
        "swivel the arm to the magazine (O0.3)",
    ),
    sig(
        "ArmToNxt",
        Dir::Actuator,
        "swivel the arm to the downstream station (O0.4)",
    ),
];

const QUANTITIES: &[Quantity] = &[
    q("stack", "", "workpieces in the magazine above the slot"),
    q(
        "delivered",
        "",
        "workpieces put down at the downstream station",
    ),
    q("dropped", "", "workpieces lost by the arm between its ends"),
    q("arm", "", "swivel position, 0 downstream .. 1 magazine"),
    q("vacuum", "", "vacuum level, 0 .. 1 (the switch is on at 1)"),
    q(
        "jams",
        "",
        "workpieces pushed onto an occupied pick-up point",
    ),
    q(
        "conflicts",
        "ms",
        "time both coils of the arm, or VacOn and VacOff, were on",
    ),
];

const START: usize = 6;
const EJECT_OUT: usize = 9;
const VAC_ON: usize = 10;
const VAC_OFF: usize = 11;
const ARM_TO_MAG: usize = 12;
const ARM_TO_NXT: usize = 13;
const VACUUM_FULL_NS: i64 = 300_000_000;

#[derive(Clone, Debug)]
pub struct Festo {
    /// START, STOP_N, ResetBtn.
    operator: [bool; 3],
    cyl: Drive,
    /// Swivel: 0 = at the downstream station, 1 = at the magazine.
    arm: Drive,
    vac_on: bool,
    vac_off: bool,
    vacuum_ns: i64,
    stack: u32,
    slot: bool,
    /// A workpiece travelling on the slider out of the slot.
    pushing: bool,
    pickup: bool,
    held: bool,
    delivered: u32,
    dropped: u32,
    jams: u32,
    jammed: bool,
    conflict_ns: i64,
}

impl Default for Festo {
    fn default() -> Self {
        Festo::new()
    }
}

impl Festo {
    pub fn new() -> Festo {
        let mut f = Festo {
            operator: [false, true, false],
            cyl: Drive::new(0.5),
            arm: Drive::new(1.0),
            vac_on: false,
            vac_off: false,
            vacuum_ns: 0,
            stack: 3,
            slot: true,
            pushing: false,
            pickup: false,
            held: false,
            delivered: 0,
            dropped: 0,
            jams: 0,
            jammed: false,
            conflict_ns: 0,
        };
        f.cyl.retract = true;
        f
    }

    fn step_cylinder(&mut self, dt_ns: i64) {
        let extending = self.cyl.advance;
        if extending && self.cyl.retracted() && self.slot && !self.pushing {
            self.slot = false;
            self.pushing = true;
        }
        // A workpiece on the slider that meets one at the pick-up point jams.
        if self.pushing && self.pickup && extending && self.cyl.fraction() >= 0.5 {
            if !self.jammed {
                self.jams += 1;
            }
            self.jammed = true;
            return;
        }
        self.jammed = false;
        self.cyl.step(dt_ns);
        if self.pushing && self.cyl.extended() {
            self.pushing = false;
            self.pickup = true;
        }
        if self.pushing && self.cyl.retracted() && !extending {
            // pulled back before reaching the front: it falls back in the slot
            self.pushing = false;
            self.slot = true;
        }
        if self.cyl.retracted() && !self.slot && !self.pushing && self.stack > 0 {
            self.stack -= 1;
            self.slot = true;
        }
    }

    fn step_vacuum(&mut self, dt_ns: i64) {
        if self.vac_on && self.vac_off {
            self.conflict_ns = self.conflict_ns.saturating_add(dt_ns);
        }
        let on_piece = self.held || (self.pickup && self.arm.extended());
        if self.vac_on && !self.vac_off && on_piece {
            self.vacuum_ns = (self.vacuum_ns + dt_ns).min(VACUUM_FULL_NS);
        } else if !self.vac_on || self.vac_off {
            let rate = if self.vac_off { 10 } else { 1 };
            self.vacuum_ns = (self.vacuum_ns - dt_ns * rate).max(0);
        }
        let holding = self.vacuum_ns * 3 > VACUUM_FULL_NS;
        if holding && !self.held && self.pickup && self.arm.extended() {
            self.held = true;
            self.pickup = false;
        } else if !holding && self.held {
            self.held = false;
            if self.arm.retracted() {
                self.delivered += 1;
            } else if self.arm.extended() && !self.pickup {
                self.pickup = true;
            } else {
                self.dropped += 1;
            }
        }
    }

    fn set_param(&mut self, key: &str, v: f64) -> Result<(), String> {
        match key {
            "stack" if v.is_finite() && v >= 0.0 => self.stack = v.min(1e6) as u32,
            "stack" => return Err("festo: `stack` must be a number of workpieces >= 0".into()),
            "stroke_time" => self.cyl.set_stroke(positive("festo", key, v)?),
            "swivel_time" => self.arm.set_stroke(positive("festo", key, v)?),
            _ => {
                return Err(format!(
                    "festo: unknown parameter `{key}` (known: stack, stroke_time, swivel_time)"
                ))
            }
        }
        Ok(())
    }
}

impl Plant for Festo {
    fn name(&self) -> &'static str {
        "festo"
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
            START..=8 => {
                if let Some(o) = self.operator.get_mut(signal - START) {
                    *o = on;
                }
            }
            EJECT_OUT => {
                self.cyl.advance = on;
                self.cyl.retract = !on;
            }
            VAC_ON => self.vac_on = on,
            VAC_OFF => self.vac_off = on,
            ARM_TO_MAG => self.arm.advance = on,
            ARM_TO_NXT => self.arm.retract = on,
            _ => {}
        }
    }

    fn get(&self, signal: usize) -> Value {
        Value::Bool(match signal {
            0 => self.cyl.retracted(),
            1 => self.cyl.extended(),
            2 => self.vacuum_ns >= VACUUM_FULL_NS,
            3 => self.arm.extended(),
            4 => self.arm.retracted(),
            5 => self.slot,
            START..=8 => self.operator.get(signal - START).copied().unwrap_or(false),
            EJECT_OUT => self.cyl.advance,
            VAC_ON => self.vac_on,
            VAC_OFF => self.vac_off,
            ARM_TO_MAG => self.arm.advance,
            ARM_TO_NXT => self.arm.retract,
            _ => false,
        })
    }

    fn quantity(&self, index: usize) -> f64 {
        match index {
            0 => f64::from(self.stack),
            1 => f64::from(self.delivered),
            2 => f64::from(self.dropped),
            3 => self.arm.fraction(),
            4 => self.vacuum_ns as f64 / VACUUM_FULL_NS as f64,
            5 => f64::from(self.jams),
            6 => (self.conflict_ns.saturating_add(self.arm.conflict_ns)) as f64 / 1e6,
            _ => 0.0,
        }
    }

    fn step(&mut self, dt_ns: i64, _rng: &mut Rng) {
        self.step_cylinder(dt_ns);
        self.arm.step(dt_ns);
        self.step_vacuum(dt_ns);
    }

    fn command(&mut self, name: &str, args: &[(&str, f64)]) -> Result<(), String> {
        match name {
            "set" => args.iter().try_for_each(|(k, v)| self.set_param(k, *v)),
            _ => Err(format!(
                "the festo model has no command `{name}` (known: set)"
            )),
        }
    }

    fn commands(&self) -> &'static [(&'static str, &'static str)] {
        &[(
            "set",
            "parameters: stack (workpieces in the magazine above the slot), stroke_time, swivel_time (s)",
        )]
    }
}

#[cfg(test)]
#[path = "festo_tests.rs"]
mod tests;
