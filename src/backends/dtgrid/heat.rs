//! The heat equation on a sphere solved on a narrow band (000 §2.1, Table 2.1): the second
//! spherical harmonic `Y = (z/|x|)² − 1/3` on the sphere of radius `R` decays as `e^{−6t/R²}`;
//! the band carries `Φ = |x| − R` and `U` extended constantly along the normals; each step
//! solves `(M[Φ] + τ L[Φ]) U^{k+1} = M[Φ] U^k (+ τ Γ[U^k])` (000 (2.10), transparent conditions
//! with `U_approx = U^k`). The error is `‖U − u‖_{L²(M_h)}` on the discrete surface `[Φ = 0]`.

use super::band::Band;
use super::fem::{assemble, elements, transparent_vector, Weight};
use super::lattice::{band_around, crossing_cells_of_fn, Lattice, NarrowBand, C3};
use super::scheme::{solve_all, system_matrix, Bc};
use super::surface::{surface_integral, zero_level};
use crate::error::{Error, Result};
use crate::geom::DVec3;

/// The options of one heat run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeatOptions {
    /// Grid nodes per side on `[−½, ½]³`.
    pub n: usize,
    /// The band half-width `j` in cells.
    pub j: usize,
    /// Natural or transparent conditions.
    pub bc: Bc,
    /// The time step (`None`: `h²`, rounded so that the steps end at `t_end`).
    pub tau: Option<f64>,
    /// The final time (000: 0.01).
    pub t_end: f64,
    /// The sphere radius (000: 1/3).
    pub radius: f64,
}

impl HeatOptions {
    /// The paper's problem (R = 1/3, t = 0.01) on `n³` nodes with half-width `j`.
    pub fn paper(n: usize, j: usize, bc: Bc) -> HeatOptions {
        HeatOptions {
            n,
            j,
            bc,
            tau: None,
            t_end: 0.01,
            radius: 1.0 / 3.0,
        }
    }
}

/// The outcome of one heat run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeatResult {
    /// `‖U − u‖_{L²(M_h)}` at `t_end`.
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

/// Runs the heat problem on a band stored as `B`.
/// Errors: [`Error::InvalidInput`] for Dirichlet conditions, a non-positive time or a band that
/// does not fit; solver errors from [`solve_all`].
pub fn sphere_heat<B: Band<Coord = C3>>(o: &HeatOptions) -> Result<HeatResult> {
    if o.bc == Bc::Dirichlet {
        return Err(Error::InvalidInput(
            "the heat problem takes natural or transparent conditions".into(),
        ));
    }
    if !(o.t_end.is_finite() && o.t_end > 0.0 && o.radius.is_finite() && o.radius > 0.0) {
        return Err(Error::InvalidInput(format!(
            "heat: t_end = {} and radius = {} must be positive",
            o.t_end, o.radius
        )));
    }
    let lat = Lattice::unit(o.n)?;
    let r = o.radius;
    let f = |p: DVec3| p.length() - r;
    let cross = crossing_cells_of_fn(&lat, &f)?;
    let nb: NarrowBand<B> = band_around(&lat, &cross, o.j)?;
    let n = nb.band.len();
    let phi: Vec<f64> = nb.band.coords().map(|c| f(lat.pos(c))).collect();
    let y = |p: DVec3| {
        let l = p.length().max(1e-300);
        (p.z / l).powi(2) - 1.0 / 3.0
    };
    let mut u: Vec<f64> = nb.band.coords().map(|c| y(lat.pos(c))).collect();
    let tau0 = o.tau.unwrap_or(lat.h * lat.h);
    if tau0.is_nan() || tau0 <= 0.0 {
        return Err(Error::InvalidInput(format!("heat: time step {tau0}")));
    }
    let steps = (o.t_end / tau0).ceil().max(1.0) as usize;
    let tau = o.t_end / steps as f64;
    let el = elements(&nb);
    let w = Weight::Heat;
    let m = assemble(&lat, &el, n, &phi, w)?;
    let a = system_matrix(&m, tau)?;
    let mut b = vec![0.0; n];
    for _ in 0..steps {
        b.iter_mut()
            .zip(&m.mass)
            .zip(&u)
            .for_each(|((b, m), u)| *b = m * u);
        if o.bc == Bc::Transparent {
            let g = transparent_vector(&lat, &el, n, &phi, &u, w);
            b.iter_mut().zip(&g).for_each(|(b, g)| *b += tau * g);
        }
        solve_all(&a, &b, &mut u)?;
    }
    let z = zero_level(&lat, &nb.band, &phi);
    let decay = (-6.0 * o.t_end / (r * r)).exp();
    let e2 = surface_integral(&lat, &nb.band, &z, &u, |x, ux| (ux - decay * y(x)).powi(2));
    Ok(HeatResult {
        error: e2.sqrt(),
        nodes: n,
        steps,
        tau,
        h: lat.h,
    })
}
