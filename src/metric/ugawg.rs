//! The analytic metric fields of the UGAWG adaptation benchmarks on the unit cube `[0,1]³`
//! (UGAWG adapt-benchmarks, `cube/README.md` and `cube-cylinder/README.md`; Park, Loseille,
//! Krakos, Michal 2015, eq. (18)), with `h0 = 0.001`:
//!
//! - **cube-linear**: `M = diag(h_x^{-2}, h_y^{-2}, h_z^{-2})`, `h_x = h_y = 0.1`,
//!   `h_z = h0 + 2 (0.1 - h0) |z - 0.5|` — a layer of thickness `h0` at the plane `z = 0.5`.
//! - **cube-polar-1**: with `r = sqrt(x² + y²)`, `θ = atan2(y, x)`, radial unit vector
//!   `e_r = (cos θ, sin θ, 0)` and `e_θ = (-sin θ, cos θ, 0)`:
//!   `M = h_r^{-2} e_r e_rᵀ + h_θ^{-2} e_θ e_θᵀ + h_z^{-2} e_z e_zᵀ`, `h_θ = h_z = 0.1`,
//!   `h_r = h0 + 2 (0.1 - h0) |r - 0.5|` — a layer at the cylinder `r = 0.5`.

use super::Sym3;
use crate::error::{Error, Result};
use crate::geom::DVec3;

/// The smallest size `h0` of both fields.
pub const H0: f64 = 0.001;
/// The size away from the layer.
pub const H_FAR: f64 = 0.1;

/// One of the UGAWG analytic metric fields (module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UgawgCase {
    /// `cube-linear`: a planar layer at `z = 0.5`.
    CubeLinear,
    /// `cube-polar-1`: a cylindrical layer at `r = 0.5`.
    CubePolar1,
}

/// The size `h0 + 2 (0.1 - h0) |s - 0.5|` across a layer at `s = 0.5`.
#[inline]
fn layer_size(s: f64) -> f64 {
    H0 + 2.0 * (H_FAR - H0) * (s - 0.5).abs()
}

impl UgawgCase {
    /// Parses `cube-linear` or `cube-polar-1`.
    pub fn parse(s: &str) -> Result<UgawgCase> {
        match s {
            "cube-linear" | "linear" => Ok(UgawgCase::CubeLinear),
            "cube-polar-1" | "polar-1" => Ok(UgawgCase::CubePolar1),
            _ => Err(Error::InvalidInput(format!(
                "unknown UGAWG case '{s}' (expected cube-linear or cube-polar-1)"
            ))),
        }
    }

    /// The case's name, as UGAWG spells it.
    pub fn name(self) -> &'static str {
        match self {
            UgawgCase::CubeLinear => "cube-linear",
            UgawgCase::CubePolar1 => "cube-polar-1",
        }
    }

    /// The metric at `p`.
    pub fn metric(self, p: DVec3) -> Sym3 {
        match self {
            UgawgCase::CubeLinear => {
                let hz = layer_size(p.z);
                let far = 1.0 / (H_FAR * H_FAR);
                Sym3::new(far, 0.0, 0.0, far, 0.0, 1.0 / (hz * hz))
            }
            UgawgCase::CubePolar1 => {
                let r = (p.x * p.x + p.y * p.y).sqrt();
                let t = p.y.atan2(p.x);
                let (s, c) = t.sin_cos();
                let hr = layer_size(r);
                let (lr, lt) = (1.0 / (hr * hr), 1.0 / (H_FAR * H_FAR));
                Sym3::new(
                    lr * c * c + lt * s * s,
                    (lr - lt) * c * s,
                    0.0,
                    lr * s * s + lt * c * c,
                    0.0,
                    lt,
                )
            }
        }
    }

    /// The metric at each point.
    pub fn field(self, points: &[DVec3]) -> Vec<Sym3> {
        points.iter().map(|&p| self.metric(p)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metric::SymTensor;

    #[test]
    fn sizes_match_the_definitions() {
        let m = UgawgCase::CubeLinear.metric(DVec3::new(0.3, 0.7, 0.5));
        let (h, _) = m.sizes();
        let mut h = h.to_vec();
        h.sort_by(f64::total_cmp);
        assert!((h[0] - H0).abs() < 1e-15 && (h[2] - 0.1).abs() < 1e-14);
        let p = DVec3::new(0.6, 0.8, 0.2); // r = 1, θ with cos 0.6, sin 0.8
        let m = UgawgCase::CubePolar1.metric(p);
        let hr = H0 + 2.0 * (0.1 - H0) * 0.5;
        let er = DVec3::new(0.6, 0.8, 0.0);
        let et = DVec3::new(-0.8, 0.6, 0.0);
        assert!((m.quad(er) - 1.0 / (hr * hr)).abs() < 1e-10);
        assert!((m.quad(et) - 100.0).abs() < 1e-10);
        assert!(m.quad(er + et).abs() > 0.0 && m.mul_vec(er).dot(et).abs() < 1e-10);
        assert!(UgawgCase::parse("cube-round").is_err());
    }
}
