//! `Bounds`: the interval a learnable parameter lives in, and the map from the unconstrained
//! variable the optimiser moves (its "raw" value) to the parameter: the identity when free,
//! lo + e^r above a lower bound (log p for a positive one), hi − e^r below an upper one, and
//! lo + (hi − lo)·σ(r) between two.

use tch::Tensor;

/// Lower and upper bounds, excluded (±∞ when absent).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    pub lo: f64,
    pub hi: f64,
}

impl Bounds {
    pub const FREE: Bounds = Bounds {
        lo: f64::NEG_INFINITY,
        hi: f64::INFINITY,
    };
    pub const POSITIVE: Bounds = Bounds {
        lo: 0.0,
        hi: f64::INFINITY,
    };

    /// From optional bounds.
    pub fn new(lo: Option<f64>, hi: Option<f64>) -> Bounds {
        Bounds {
            lo: lo.unwrap_or(f64::NEG_INFINITY),
            hi: hi.unwrap_or(f64::INFINITY),
        }
    }

    /// Whether it is the positive half-line, learned as a logarithm.
    pub fn is_positive(&self) -> bool {
        *self == Bounds::POSITIVE
    }

    /// Whether `v` lies strictly inside.
    pub fn contains(&self, v: f64) -> bool {
        v > self.lo && v < self.hi
    }

    /// The prefix of the variable's name (`log_` for a positive parameter).
    pub fn prefix(&self) -> &'static str {
        match (self.lo.is_finite(), self.hi.is_finite()) {
            (false, false) => "",
            _ if self.is_positive() => "log_",
            _ => "raw_",
        }
    }

    /// The raw value of parameter value `v` (inside the bounds).
    pub fn raw(&self, v: f64) -> f64 {
        match (self.lo.is_finite(), self.hi.is_finite()) {
            (false, false) => v,
            (true, false) => (v - self.lo).ln(),
            (false, true) => (self.hi - v).ln(),
            (true, true) => {
                let u = (v - self.lo) / (self.hi - self.lo);
                (u / (1.0 - u)).ln()
            }
        }
    }

    /// The parameter as a differentiable function of its raw tensor.
    pub fn value(&self, r: &Tensor) -> Tensor {
        match (self.lo.is_finite(), self.hi.is_finite()) {
            (false, false) => r.shallow_clone(),
            (true, false) if self.lo == 0.0 => r.exp(),
            (true, false) => r.exp() + self.lo,
            (false, true) => r.exp().neg() + self.hi,
            (true, true) => r.sigmoid() * (self.hi - self.lo) + self.lo,
        }
    }

    /// d(value)/d(raw) at value `v`.
    pub fn slope(&self, v: f64) -> f64 {
        match (self.lo.is_finite(), self.hi.is_finite()) {
            (false, false) => 1.0,
            (true, false) => v - self.lo,
            (false, true) => v - self.hi,
            (true, true) => (v - self.lo) * (self.hi - v) / (self.hi - self.lo),
        }
    }

    /// The value after a step `s` of the raw variable from value `v` (steps of bounded
    /// parameters limited to ±0.5, a factor e^0.5 of the distance to the bound).
    pub fn step(&self, v: f64, s: f64) -> f64 {
        if !self.lo.is_finite() && !self.hi.is_finite() {
            return v + s;
        }
        let r = self.raw(v) + s.clamp(-0.5, 0.5);
        self.value_f64(r)
    }

    fn value_f64(&self, r: f64) -> f64 {
        match (self.lo.is_finite(), self.hi.is_finite()) {
            (false, false) => r,
            (true, false) => self.lo + r.exp(),
            (false, true) => self.hi - r.exp(),
            (true, true) => self.lo + (self.hi - self.lo) / (1.0 + (-r).exp()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn raw_values_round_trip_and_slopes_match() {
        let cases = [
            (Bounds::FREE, -3.0),
            (Bounds::POSITIVE, 0.2),
            (Bounds::new(Some(1.0), None), 1.5),
            (Bounds::new(None, Some(2.0)), -1.0),
            (Bounds::new(Some(0.0), Some(2.0)), 0.3),
        ];
        for (b, v) in cases {
            let r = b.raw(v);
            let t = b.value(&Tensor::from(r)).double_value(&[]);
            assert!((t - v).abs() < 1e-6, "{b:?}");
            let h = 1e-6;
            let fd = (b.value_f64(r + h) - b.value_f64(r - h)) / (2.0 * h);
            assert!((fd - b.slope(v)).abs() < 1e-6, "{b:?}");
            assert!(
                b.contains(b.step(v, 100.0)) && b.contains(b.step(v, -100.0)) || b == Bounds::FREE
            );
        }
    }
}
