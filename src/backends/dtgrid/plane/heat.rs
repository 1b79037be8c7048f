//! The heat equation on a circle solved on a planar narrow band (000 §2.1 and Table 2.1 in two
//! dimensions): the eigenfunction `cos 2θ` on the circle of radius `R` decays as `e^{−4t/R²}`;
//! the band carries `Φ = |x − c| − R` and `U` extended constantly along the normals; each step
//! solves `(M[Φ] + τ L[Φ]) U^{k+1} = M[Φ] U^k (+ τ Γ[U^k])` (000 (2.10): natural conditions, or
//! transparent Neumann conditions (2.9) with `U_approx = U^k`). The error is
//! `‖U − u‖_{L²(Γ_h)}` on the discrete zero level `Γ_h = [Φ = 0]` (two Gauss points on each
//! chord of its pieces, `U` the Q1 interpolant).

use super::cubic::{Field, Patch};
use super::fem::{assemble, elements, transparent_vector};
use super::lattice::{band_around, crossing_cells_of_fn, Plane};
use super::level::zero_level;
use crate::backends::dtgrid::band::{Band, GridCoord};
use crate::backends::dtgrid::fem::Weight;
use crate::backends::dtgrid::scheme::{solve_all, system_matrix, Bc};
use crate::error::{Error, Result};
use crate::geom::DVec2;

/// The options of one heat run on `[−½, ½]²`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CircleHeatOptions {
    /// Grid nodes per side.
    pub n: usize,
    /// The band half-width `j` in cells.
    pub j: usize,
    /// Natural or transparent conditions.
    pub bc: Bc,
    /// The time step (`None`: `h²`, rounded so that the steps end at `t_end`).
    pub tau: Option<f64>,
    /// The final time.
    pub t_end: f64,
    /// The circle's radius.
    pub radius: f64,
    /// The circle's centre.
    pub centre: DVec2,
}

impl CircleHeatOptions {
    /// The planar analogue of 000's Table 2.1: `R = 1/3` about the origin, `t = 0.01`, on `n²`
    /// nodes with half-width `j`.
    pub fn table(n: usize, j: usize, bc: Bc) -> CircleHeatOptions {
        CircleHeatOptions {
            n,
            j,
            bc,
            tau: None,
            t_end: 0.01,
            radius: 1.0 / 3.0,
            centre: DVec2::ZERO,
        }
    }
}

/// The outcome of one heat run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CircleHeatResult {
    /// `‖U − u‖_{L²(Γ_h)}` at `t_end`.
    pub error: f64,
    /// Band nodes.
    pub nodes: usize,
    /// Time steps taken.
    pub steps: usize,
    /// The time step used.
    pub tau: f64,
    /// The grid spacing.
    pub h: f64,
}

/// Runs the heat problem of `o`.
/// Errors: [`Error::InvalidInput`] for Dirichlet or extrapolated conditions, a non-positive time, radius or
/// time step, or a circle whose band does not fit in `[−½, ½]²`; [`Error::EmptyLevelSet`];
/// solver errors.
pub fn circle_heat(o: &CircleHeatOptions) -> Result<CircleHeatResult> {
    if matches!(o.bc, Bc::Dirichlet | Bc::Extrapolated) {
        return Err(Error::InvalidInput(
            "the planar heat problem takes natural or transparent conditions".into(),
        ));
    }
    let ok = |x: f64| x.is_finite() && x > 0.0;
    if !(ok(o.t_end) && ok(o.radius) && o.centre.is_finite() && o.tau.map_or(true, ok)) {
        return Err(Error::InvalidInput(format!(
            "circle heat: t_end = {}, radius = {}, centre {:?} and tau {:?} must be finite, the \
             times and the radius positive",
            o.t_end, o.radius, o.centre, o.tau
        )));
    }
    let plane = Plane::new(o.n, 1.0 / (o.n.max(2) - 1) as f64)?;
    let h = plane.h;
    // Local coordinates: the domain's corner (−½, −½) is the grid's origin.
    let c = o.centre + DVec2::splat(0.5);
    let r = o.radius;
    let f = |p: DVec2| (p - c).length() - r;
    let nb = band_around(&plane, &crossing_cells_of_fn(&plane, &f)?, o.j)?;
    let n = nb.band.len();
    let phi: Vec<f64> = nb.band.coords().map(|q| f(plane.pos(q))).collect();
    let cos2 = |p: DVec2| {
        let d = p - c;
        let l2 = d.length_squared().max(1e-300);
        (d.x * d.x - d.y * d.y) / l2
    };
    let mut u: Vec<f64> = nb.band.coords().map(|q| cos2(plane.pos(q))).collect();
    let steps = (o.t_end / o.tau.unwrap_or(h * h) - 1e-9).ceil().max(1.0) as usize;
    let tau = o.t_end / steps as f64;
    let el = elements(&nb);
    let w = Weight::Heat;
    let m = assemble(&plane, &el, n, &phi, w)?;
    let a = system_matrix(&m, tau)?;
    let mut b = vec![0.0; n];
    for _ in 0..steps {
        b.iter_mut()
            .zip(&m.mass)
            .zip(&u)
            .for_each(|((b, m), u)| *b = m * u);
        if o.bc == Bc::Transparent {
            let g = transparent_vector(&plane, &el, n, &phi, &u, w);
            b.iter_mut().zip(&g).for_each(|(b, g)| *b += tau * g);
        }
        solve_all(&a, &b, &mut u)?;
    }
    let z = zero_level(&Field {
        plane: &plane,
        band: &nb.band,
        u: &phi,
    });
    if z.is_empty() {
        return Err(Error::EmptyLevelSet("circle heat: no zero level".into()));
    }
    let uf = Field {
        plane: &plane,
        band: &nb.band,
        u: &u,
    };
    let decay = (-4.0 * o.t_end / (r * r)).exp();
    let g = 0.5 / 3f64.sqrt();
    let mut e2 = 0.0;
    for s in &z.segments {
        let cell = z.cells[s.cell as usize].cell;
        let mut corners = [0.0; 4];
        for (k, ck) in corners.iter_mut().enumerate() {
            *ck = uf.at(cell.corner(k)).ok_or_else(|| {
                Error::InvalidInput("circle heat: a cut cell's corner is not a band node".into())
            })?;
        }
        let q1 = Patch::linear(&plane, cell, corners);
        for (p, q) in [(s.a, s.mid), (s.mid, s.b)] {
            let len = (q - p).length();
            for t in [0.5 - g, 0.5 + g] {
                let x = p + t * (q - p);
                let d = q1.jet(x).value - decay * cos2(x);
                e2 += 0.5 * len * d * d;
            }
        }
    }
    Ok(CircleHeatResult {
        error: e2.sqrt(),
        nodes: n,
        steps,
        tau,
        h,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_input_is_a_typed_error() {
        let o = CircleHeatOptions::table(33, 2, Bc::Dirichlet);
        assert!(matches!(circle_heat(&o), Err(Error::InvalidInput(_))));
        let o = CircleHeatOptions {
            tau: Some(-1.0),
            ..CircleHeatOptions::table(33, 2, Bc::Natural)
        };
        assert!(matches!(circle_heat(&o), Err(Error::InvalidInput(_))));
        let o = CircleHeatOptions {
            radius: 0.49,
            ..CircleHeatOptions::table(33, 2, Bc::Natural)
        };
        assert!(matches!(circle_heat(&o), Err(Error::InvalidInput(_))));
    }
}
