//! A velocity field given as two expressions in `x`, `y`, `t` (and `pi`), for example the single
//! vortex `-sin(pi*x)^2*sin(2*pi*y)*cos(pi*t/8); sin(pi*y)^2*sin(2*pi*x)*cos(pi*t/8)`.

use super::characteristics::Velocity;
use crate::error::{Error, Result};
use crate::geom::DVec2;
use crate::levelset::expr::{Expr, Variables};

/// `v(t, x) = (U(x, y, t), V(x, y, t))` from two compiled expressions.
#[derive(Debug, Clone)]
pub struct ExprVelocity {
    /// The first component `U`.
    pub u: Expr,
    /// The second component `V`.
    pub v: Expr,
}

impl ExprVelocity {
    /// Parses `"U; V"`: two expressions in `x`, `y`, `t` separated by one `;`. Errors
    /// ([`Error::InvalidInput`]) for a missing or extra component and for a malformed or empty
    /// expression (naming the component).
    pub fn parse(source: &str) -> Result<ExprVelocity> {
        let parts: Vec<&str> = source.split(';').collect();
        if parts.len() != 2 {
            return Err(Error::InvalidInput(format!(
                "velocity: expected two expressions \"U; V\" separated by one ';' (got {} part{})",
                parts.len(),
                if parts.len() == 1 { "" } else { "s" }
            )));
        }
        let comp = |name: &str, s: &str| {
            Expr::parse_with(s.trim(), Variables::XYT)
                .map_err(|e| Error::InvalidInput(format!("velocity component {name}: {e}")))
        };
        Ok(ExprVelocity {
            u: comp("U", parts[0])?,
            v: comp("V", parts[1])?,
        })
    }
}

impl Velocity for ExprVelocity {
    #[inline]
    fn at(&self, t: f64, x: DVec2) -> DVec2 {
        DVec2::new(self.u.eval_t(x, t), self.v.eval_t(x, t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_evaluates_the_single_vortex() {
        let f = ExprVelocity::parse(
            "-sin(pi*x)^2*sin(2*pi*y)*cos(pi*t/8); sin(pi*y)^2*sin(2*pi*x)*cos(pi*t/8)",
        )
        .unwrap();
        let pi = std::f64::consts::PI;
        let (x, y, t) = (0.3, 0.6, 1.7);
        let w = f.at(t, DVec2::new(x, y));
        let c = (pi * t / 8.0).cos();
        assert!((w.x + (pi * x).sin().powi(2) * (2.0 * pi * y).sin() * c).abs() < 1e-14);
        assert!((w.y - (pi * y).sin().powi(2) * (2.0 * pi * x).sin() * c).abs() < 1e-14);
    }

    #[test]
    fn malformed_velocities_are_one_line_errors() {
        for bad in ["", "x", "x; y; t", "x +; y", "x; ", "x; z", "(x; y"] {
            let e = ExprVelocity::parse(bad).unwrap_err().to_string();
            assert!(!e.contains('\n') && !e.is_empty(), "{bad:?}: {e}");
        }
    }
}
