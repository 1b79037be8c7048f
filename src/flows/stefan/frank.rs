//! Frank's expanding circle: the self-similar solution of the two-dimensional Stefan problem
//! (001 eq. (6.1)–(6.4) with ε_C = ε_V = 0), the standard accuracy test of level-set Stefan
//! solvers (Chen, Merriman, Osher & Smereka 1997; Gibou & Fedkiw 2005).
//!
//! The solid disk `r < R(t) = S0 √t` is at the melting temperature 0; the undercooled liquid
//! outside has `T(r, t) = T∞ (1 − E1(r²/4t) / E1(S0²/4))`, which tends to `T∞ < 0` far away.
//! The Stefan condition `v_n = −[∂T/∂n]` fixes `T∞ = −(S0²/4) e^{S0²/4} E1(S0²/4)`.

use crate::error::{Error, Result};

/// The exponential integral `E1(x) = ∫_x^∞ e^{−s}/s ds` for `x > 0` (power series below 1,
/// continued fraction above; relative accuracy about 1e-15).
pub fn exp_integral_e1(x: f64) -> f64 {
    if x.is_nan() || x <= 0.0 {
        return f64::NAN;
    }
    if x <= 1.0 {
        // E1(x) = −γ − ln x − Σ_{k≥1} (−x)^k / (k k!)
        const EULER_GAMMA: f64 = 0.577_215_664_901_532_9;
        let mut sum = 0.0;
        let mut term = 1.0;
        for k in 1..60 {
            term *= -x / k as f64;
            let add = term / k as f64;
            sum += add;
            if add.abs() < 1e-17 * sum.abs().max(1e-300) {
                break;
            }
        }
        -EULER_GAMMA - x.ln() - sum
    } else {
        // Modified Lentz evaluation of e^{-x} / (x + 1 − 1/(x + 3 − 4/(x + 5 − ...))).
        let tiny = 1e-300;
        let mut b = x + 1.0;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..200 {
            let a = -((i * i) as f64);
            b += 2.0;
            d = 1.0 / (a * d + b);
            c = b + a / c;
            let delta = c * d;
            h *= delta;
            if (delta - 1.0).abs() < 1e-16 {
                break;
            }
        }
        h * (-x).exp()
    }
}

/// Frank's circle with growth constant `S0`: `R(t) = S0 √t`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrankCircle {
    /// The growth constant `S0` (`R(t) = S0 √t`).
    pub s0: f64,
}

impl FrankCircle {
    /// The common test case `S0 = 1.56` (Chen et al. 1997), for which `T∞ ≈ −0.5`.
    pub const STANDARD: FrankCircle = FrankCircle { s0: 1.56 };

    /// A circle with growth constant `s0 > 0`.
    pub fn new(s0: f64) -> Result<FrankCircle> {
        if s0.is_finite() && s0 > 0.0 {
            Ok(FrankCircle { s0 })
        } else {
            Err(Error::InvalidInput(format!(
                "Frank's circle: the growth constant S0 must be finite and positive (got {s0})"
            )))
        }
    }

    /// The radius `R(t) = S0 √t`.
    pub fn radius(&self, t: f64) -> f64 {
        self.s0 * t.sqrt()
    }

    /// The far-field undercooling `T∞ = −(S0²/4) e^{S0²/4} E1(S0²/4)`.
    pub fn undercooling(&self) -> f64 {
        let s = 0.25 * self.s0 * self.s0;
        -s * s.exp() * exp_integral_e1(s)
    }

    /// The temperature at distance `r` from the centre at time `t > 0`: 0 in the solid
    /// `r ≤ R(t)`, `T∞ (1 − E1(r²/4t)/E1(S0²/4))` in the liquid.
    pub fn temperature(&self, r: f64, t: f64) -> f64 {
        if r <= self.radius(t) {
            return 0.0;
        }
        let e0 = exp_integral_e1(0.25 * self.s0 * self.s0);
        self.undercooling() * (1.0 - exp_integral_e1(r * r / (4.0 * t)) / e0)
    }

    /// The radial derivative `∂T/∂r` in the liquid at distance `r > R(t)`.
    pub fn temperature_gradient(&self, r: f64, t: f64) -> f64 {
        let e0 = exp_integral_e1(0.25 * self.s0 * self.s0);
        // d/dr E1(r²/4t) = −e^{−r²/4t} · 2/r
        self.undercooling() * 2.0 * (-r * r / (4.0 * t)).exp() / (r * e0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exponential_integral_matches_tabulated_values() {
        // Abramowitz & Stegun, Table 5.1.
        for (x, e1) in [
            (0.1, 1.822_923_958_4),
            (0.5, 0.559_773_594_8),
            (1.0, 0.219_383_934_4),
            (2.0, 0.048_900_510_7),
            (5.0, 0.001_148_295_6),
        ] {
            let got = exp_integral_e1(x);
            assert!((got - e1).abs() < 1e-8 * e1, "E1({x}) = {got}, table {e1}");
        }
        // Continuity across the switch at x = 1.
        let (a, b) = (exp_integral_e1(1.0 - 1e-12), exp_integral_e1(1.0 + 1e-12));
        assert!((a - b).abs() < 1e-11);
    }

    #[test]
    fn frank_circle_satisfies_the_stefan_condition() {
        let f = FrankCircle::STANDARD;
        assert!(
            (f.undercooling() + 0.5).abs() < 0.01,
            "T∞ = {}",
            f.undercooling()
        );
        for t in [0.25, 1.0, 2.0] {
            let r = f.radius(t);
            // Interface at the melting temperature, continuous from outside.
            assert!(f.temperature(r * (1.0 + 1e-9), t).abs() < 1e-7);
            // v_n = dR/dt = S0 / (2 √t) = −∂T/∂r (the solid is isothermal).
            let vn = 0.5 * f.s0 / t.sqrt();
            assert!((vn + f.temperature_gradient(r, t)).abs() < 1e-12 * vn);
            // The heat equation in polar form, T_t = T_rr + T_r / r, by differences.
            let (rr, h, k) = (1.3 * r, 1e-4, 1e-5);
            let tt = (f.temperature(rr, t + k) - f.temperature(rr, t - k)) / (2.0 * k);
            let trr = (f.temperature(rr + h, t) - 2.0 * f.temperature(rr, t)
                + f.temperature(rr - h, t))
                / (h * h);
            let tr = f.temperature_gradient(rr, t);
            assert!((tt - trr - tr / rr).abs() < 1e-5, "heat equation residual");
        }
    }
}
