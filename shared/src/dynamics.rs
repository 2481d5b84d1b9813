//! Closed-form dynamics: the damped oscillator z'' + γ1·z' + γ0·z = 0 of the paper's synthetic sets.

/// The frame intervals `gen` renders and `estimate` accepts (s): from a million frames per
/// second to one frame a day. Outside them no camera filmed the clip, and single precision
/// loses the dynamics (dt² of 1e-300 is zero; 1e308 overflows).
pub const DT_RANGE: (f64, f64) = (1e-6, 86_400.0);

/// The under-damped oscillator z(t) = A·e^(−ζt)·cos(ωt + φ) (appendix A.3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DampedOscillator {
    /// Angular frequency ω (rad/s).
    pub omega: f64,
    /// Decay rate ζ (1/s).
    pub zeta: f64,
}

impl DampedOscillator {
    /// The paper's values: ω = 2, ζ = 0.04.
    pub const PAPER: DampedOscillator = DampedOscillator {
        omega: 2.0,
        zeta: 0.04,
    };

    /// γ0 = ω² + ζ².
    pub fn gamma0(&self) -> f64 {
        self.omega * self.omega + self.zeta * self.zeta
    }

    /// γ1 = 2ζ.
    pub fn gamma1(&self) -> f64 {
        2.0 * self.zeta
    }

    /// z(t) for amplitude `a` and phase `phi`.
    pub fn latent(&self, a: f64, phi: f64, t: f64) -> f64 {
        a * (-self.zeta * t).exp() * (self.omega * t + phi).cos()
    }

    /// Coefficients (a, b) of the exact two-step recurrence z[t+1] = a·z\[t\] + b·z[t−1] at step `dt`.
    pub fn recurrence(&self, dt: f64) -> (f64, f64) {
        two_step_coefficients(self.gamma0(), self.gamma1(), dt)
    }
}

/// Exact two-step propagator of z'' + γ1 z' + γ0 z = 0 at step `dt`, for any damping:
/// a = 2·e^(−γ1·dt/2)·C, b = −e^(−γ1·dt), where C = cos(ω_d·dt) with ω_d = √(γ0 − γ1²/4)
/// (under-damped), cosh(κ·dt) with κ = √(γ1²/4 − γ0) (over-damped), 1 when critical.
pub fn two_step_coefficients(gamma0: f64, gamma1: f64, dt: f64) -> (f64, f64) {
    let x = (gamma0 - gamma1 * gamma1 / 4.0) * dt * dt;
    let c = if x > 0.0 {
        x.sqrt().cos()
    } else {
        (-x).sqrt().cosh()
    };
    (2.0 * (-gamma1 * dt / 2.0).exp() * c, -(-gamma1 * dt).exp())
}

/// Inverts [`two_step_coefficients`] for an under-damped pair (a, b): returns (γ0, γ1), or
/// `None` when (a, b) is not the propagator of an under-damped, non-aliased oscillator.
pub fn gammas_from_recurrence(a: f64, b: f64, dt: f64) -> Option<(f64, f64)> {
    if b.is_nan() || b >= 0.0 {
        return None;
    }
    let decay = -b; // e^(−γ1·dt)
    let gamma1 = -decay.ln() / dt;
    let c = a / (2.0 * decay.sqrt());
    if !(-1.0..1.0).contains(&c) {
        return None;
    }
    let omega_d = c.acos() / dt;
    Some((omega_d * omega_d + gamma1 * gamma1 / 4.0, gamma1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_gammas() {
        let o = DampedOscillator::PAPER;
        assert!((o.gamma0() - 4.0016).abs() < 1e-12);
        assert!((o.gamma1() - 0.08).abs() < 1e-12);
    }

    #[test]
    fn closed_form_obeys_its_recurrence_and_inverts() {
        let o = DampedOscillator {
            omega: 3.1,
            zeta: 0.2,
        };
        let dt = 0.15;
        let (a, b) = o.recurrence(dt);
        for k in 1..30 {
            let t = k as f64 * dt;
            let z = |t| o.latent(0.7, 1.3, t);
            assert!((z(t + dt) - (a * z(t) + b * z(t - dt))).abs() < 1e-12);
        }
        let (g0, g1) = gammas_from_recurrence(a, b, dt).unwrap();
        assert!((g0 - o.gamma0()).abs() < 1e-9 && (g1 - o.gamma1()).abs() < 1e-9);
    }

    #[test]
    fn over_damped_propagator_is_exact() {
        // z = e^(−t) + e^(−3t) solves z'' + 4z' + 3z = 0.
        let z = |t: f64| (-t).exp() + (-3.0 * t).exp();
        let dt = 0.1;
        let (a, b) = two_step_coefficients(3.0, 4.0, dt);
        assert!((z(0.3) - (a * z(0.2) + b * z(0.1))).abs() < 1e-12);
        // Critically damped: z = (1 + t)e^(−2t) solves z'' + 4z' + 4z = 0.
        let z = |t: f64| (1.0 + t) * (-2.0 * t).exp();
        let (a, b) = two_step_coefficients(4.0, 4.0, dt);
        assert!((z(0.3) - (a * z(0.2) + b * z(0.1))).abs() < 1e-12);
    }
}
