//! A linear drive with two end positions, shared by the models of
//! processes A7–A9 and the Festo station: a double-acting pneumatic
//! cylinder on a 5/3 closed-centre valve (two outputs, neither = stand
//! still, both = a fault that does not move), a swivel arm, a pivoting
//! mixer or a carriage.
//!
//! The position is kept as the stroke time already travelled, in whole
//! nanoseconds (0 = retracted, `stroke_ns` = extended), so end switches trip
//! at exactly the same step on every run and a stroke of `s` seconds takes
//! exactly `s` seconds of driving.

/// Conventional tolerance of an end switch: 1 % of the stroke (digest §0.2).
pub const END_TOLERANCE: f64 = 0.01;

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Drive {
    pos_ns: i64,
    stroke_ns: i64,
    /// The two valve coils (or motor directions) as last set.
    pub advance: bool,
    pub retract: bool,
    /// Time both coils were on together.
    pub conflict_ns: i64,
}

impl Drive {
    /// A retracted drive whose full stroke takes `stroke_s` seconds (at
    /// least 1 ms).
    pub fn new(stroke_s: f64) -> Drive {
        Drive {
            pos_ns: 0,
            stroke_ns: seconds_to_ns(stroke_s),
            advance: false,
            retract: false,
            conflict_ns: 0,
        }
    }

    /// Advances by `dt_ns`: extends while only `advance` is on, retracts
    /// while only `retract` is on, stops at the ends. Returns the signed
    /// travel in nanoseconds of stroke.
    pub fn step(&mut self, dt_ns: i64) -> i64 {
        let before = self.pos_ns;
        match (self.advance, self.retract) {
            (true, false) => self.pos_ns = self.pos_ns.saturating_add(dt_ns),
            (false, true) => self.pos_ns = self.pos_ns.saturating_sub(dt_ns),
            (true, true) => self.conflict_ns = self.conflict_ns.saturating_add(dt_ns),
            (false, false) => {}
        }
        self.pos_ns = self.pos_ns.clamp(0, self.stroke_ns);
        self.pos_ns - before
    }

    /// 0.0 retracted … 1.0 extended.
    pub fn fraction(&self) -> f64 {
        self.pos_ns as f64 / self.stroke_ns as f64
    }

    /// Within 1 % of the retracted end.
    pub fn retracted(&self) -> bool {
        i128::from(self.pos_ns) * 100 <= i128::from(self.stroke_ns)
    }

    /// Within 1 % of the extended end.
    pub fn extended(&self) -> bool {
        i128::from(self.pos_ns) * 100 >= i128::from(self.stroke_ns) * 99
    }

    /// Within `END_TOLERANCE` of `fraction` of the stroke (an intermediate
    /// position switch).
    pub fn near(&self, fraction: f64) -> bool {
        (self.fraction() - fraction).abs() <= END_TOLERANCE + 1e-12
    }

    /// The position on a stroke of `span` units (µm, say), rounded down.
    pub fn position(&self, span: i64) -> i64 {
        (i128::from(self.pos_ns) * i128::from(span) / i128::from(self.stroke_ns)) as i64
    }

    pub fn stroke_s(&self) -> f64 {
        self.stroke_ns as f64 / 1e9
    }

    /// A new stroke time keeping the fraction travelled.
    pub fn set_stroke(&mut self, stroke_s: f64) {
        let new = seconds_to_ns(stroke_s);
        self.pos_ns = (i128::from(self.pos_ns) * i128::from(new) / i128::from(self.stroke_ns))
            .clamp(0, i128::from(new)) as i64;
        self.stroke_ns = new;
    }

    /// Puts the drive at `fraction` of its stroke (clamped to 0..1).
    pub fn place(&mut self, fraction: f64) {
        let f = if fraction.is_finite() {
            fraction.clamp(0.0, 1.0)
        } else {
            0.0
        };
        self.pos_ns = (f * self.stroke_ns as f64).round() as i64;
    }
}

/// Seconds to whole nanoseconds, at least 1 ms and at most a day (so a
/// silly parameter cannot make a stroke of zero or overflow).
pub fn seconds_to_ns(s: f64) -> i64 {
    let s = if s.is_finite() {
        s.clamp(0.001, 86_400.0)
    } else {
        1.0
    };
    (s * 1e9).round() as i64
}

/// Checks a parameter: finite and strictly positive.
pub fn positive(model: &str, key: &str, v: f64) -> Result<f64, String> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(format!("{model}: `{key}` must be a number greater than 0"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strokes_in_exactly_the_stroke_time() {
        let mut d = Drive::new(0.5);
        assert!(d.retracted() && !d.extended());
        d.advance = true;
        for _ in 0..494 {
            d.step(1_000_000);
        }
        assert!(!d.extended());
        d.step(1_000_000);
        assert!(d.extended(), "{}", d.fraction());
        for _ in 0..100 {
            d.step(1_000_000);
        }
        assert_eq!(d.fraction(), 1.0);
        d.advance = false;
        d.step(1_000_000);
        assert_eq!(d.fraction(), 1.0);
        d.retract = true;
        assert_eq!(d.step(250_000_000), -250_000_000);
        assert_eq!(d.fraction(), 0.5);
        assert!(d.near(0.5) && !d.near(0.52));
    }

    #[test]
    fn both_coils_do_not_move_and_count() {
        let mut d = Drive::new(1.0);
        d.advance = true;
        d.retract = true;
        assert_eq!(d.step(7_000_000), 0);
        assert_eq!(d.conflict_ns, 7_000_000);
    }

    #[test]
    fn stroke_change_keeps_the_fraction_and_bad_values_are_clamped() {
        let mut d = Drive::new(1.0);
        d.place(0.25);
        d.set_stroke(2.0);
        assert_eq!(d.fraction(), 0.25);
        assert_eq!(seconds_to_ns(f64::NAN), 1_000_000_000);
        assert_eq!(seconds_to_ns(-3.0), 1_000_000);
        assert!(positive("m", "k", 0.0).is_err());
        assert_eq!(positive("m", "k", 2.0), Ok(2.0));
    }
}
