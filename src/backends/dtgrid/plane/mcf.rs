//! Mean curvature motion of a planar level set on a narrow band (000 §2.2–§2.4 in two
//! dimensions): each step solves `(M[Φ^k] + τ L[Φ^k]) Φ^{k+1} = M[Φ^k] Φ^k` (000 (2.5)) on the
//! band, with Dirichlet values on its boundary layer (000 (2.12); the first solve's values the
//! distance moved by the predicted motion of the zero level), natural conditions, or
//! transparent ones (000 (2.11): the boundary flux of `Φ_approx = Φ^k` added, one solve). With
//! more than one solve per step (Dirichlet only) this is the nested inner iteration of 000 §2.4:
//! after each solve the band is rebuilt around the new zero level and the new iterate replaced
//! by its signed distance there ([`super::distance`]; the corners of the cut cells keep the
//! iterate, renormalised, so redistancing does not move the zero level), `Φ^k` is extended onto
//! the new band, and the step is solved again until the band stops changing and the boundary
//! data change by less than `δ h`. After each step `Φ^{k+1}` is a signed distance on the band
//! around its zero level.
//!
//! The options, phase times and step reports are the 3D band's ([`McfOptions`],
//! [`StepReport`]); the linear systems are [`crate::backends::dtgrid::scheme`]'s.

use super::cubic::{node_curvature, Field};
use super::distance::{extend_distance, Keep};
use super::fem::{assemble, elements, transparent_vector};
use super::lattice::{
    band_around, crossing_cells_of_band, crossing_cells_of_fn, neighbours, Plane, NONE,
};
use super::Grid2;
use crate::backends::dtgrid::band::Band;
use crate::backends::dtgrid::fem::Weight;
use crate::backends::dtgrid::lattice::NarrowBand;
use crate::backends::dtgrid::mcf::{McfOptions, StepReport};
use crate::backends::dtgrid::scheme::{solve_all, solve_dirichlet, system_matrix, Bc};
use crate::error::{Error, Result};
use crate::geom::DVec2;
use std::time::Instant;

/// A planar level set on a band (see the module documentation).
#[derive(Debug, Clone)]
pub struct PlaneMcf {
    /// The grid.
    pub plane: Plane,
    /// The band around the current zero level.
    pub nb: NarrowBand<Grid2>,
    /// `Φ` on the band nodes.
    pub phi: Vec<f64>,
}

/// How far the distance extension looks: `2j + 4` cells.
fn reach(plane: &Plane, j: usize) -> f64 {
    (2 * j + 4) as f64 * plane.h
}

/// The band of half-width `nb.j` around the zero level of `phi` on `nb` and the signed distance
/// to that zero level on it, keeping the values of `phi` where `keep` says.
/// Errors: [`Error::EmptyLevelSet`] when the zero level has vanished, [`Error::InvalidInput`]
/// when the band leaves the grid.
pub fn rebuild(
    plane: &Plane,
    nb: &NarrowBand<Grid2>,
    phi: &[f64],
    keep: Keep,
) -> Result<(NarrowBand<Grid2>, Vec<f64>)> {
    let cross: Vec<_> = crossing_cells_of_band(&nb.band, phi)
        .into_iter()
        .map(|(c, _)| c)
        .collect();
    let new = band_around(plane, &cross, nb.j).map_err(|e| match e {
        Error::EmptyLevelSet(_) => {
            Error::EmptyLevelSet("the zero level vanished (no band cell is crossed)".into())
        }
        e => e,
    })?;
    let d = extend_distance(plane, &nb.band, phi, &new.band, keep, reach(plane, nb.j));
    Ok((new, d))
}

/// The number of nodes in one of the sorted bands `a`, `b` and not the other.
fn band_difference(a: &Grid2, b: &Grid2) -> usize {
    let (mut x, mut y) = (a.coords().peekable(), b.coords().peekable());
    let mut diff = 0;
    loop {
        match (x.peek(), y.peek()) {
            (Some(p), Some(q)) if p == q => {
                x.next();
                y.next();
            }
            (Some(p), Some(q)) if p < q => {
                diff += 1;
                x.next();
            }
            (Some(_), Some(_)) => {
                diff += 1;
                y.next();
            }
            (Some(_), None) => {
                diff += 1;
                x.next();
            }
            (None, Some(_)) => {
                diff += 1;
                y.next();
            }
            (None, None) => return diff,
        }
    }
}

/// The first Dirichlet data of a step: the signed distance `φ` on `nb` moved by the motion of
/// its zero level, `φ + τ κ₀`, `κ₀` the curvature at the node's foot on the zero level from the
/// curvature `κ` of the level line through the node, `κ₀ = κ / (1 − φκ)` (parallel curves;
/// `κ` by central differences, [`node_curvature`], or a neighbour's `κ₀` near the band's edge).
/// The inner iteration of 000 §2.4 then starts `O(τ²)` from its fixed point instead of `O(τ)`,
/// so one solve per step usually meets its tolerance.
fn predicted(plane: &Plane, nb: &NarrowBand<Grid2>, phi: &[f64], tau: f64) -> Vec<f64> {
    let f = Field {
        plane,
        band: &nb.band,
        u: phi,
    };
    let coords: Vec<_> = nb.band.coords().collect();
    let foot: Vec<Option<f64>> = coords
        .iter()
        .zip(phi)
        .map(|(&c, &d)| {
            let k = node_curvature(&f, c)?;
            let den = 1.0 - d * k;
            (den > 0.25).then(|| k / den)
        })
        .collect();
    let nbrs = neighbours(&nb.band);
    (0..coords.len())
        .map(|i| {
            let k0 = foot[i].or_else(|| {
                let (mut s, mut m) = (0.0, 0);
                for &j in nbrs[i].iter().filter(|&&j| j != NONE) {
                    if let Some(k) = foot[j as usize] {
                        s += k;
                        m += 1;
                    }
                }
                (m > 0).then(|| s / m as f64)
            });
            phi[i] + tau * k0.unwrap_or(0.0)
        })
        .collect()
}

impl PlaneMcf {
    /// The level set `f` (negative inside, local coordinates) on `plane`: the band of
    /// half-width `j` around its zero level carrying the signed distance to that zero level.
    /// Errors: [`Error::EmptyLevelSet`], [`Error::InvalidInput`] (the shape does not fit),
    /// [`Error::InvalidField`] (NaN in `f`).
    pub fn new(plane: Plane, j: usize, f: &(impl Fn(DVec2) -> f64 + Sync)) -> Result<PlaneMcf> {
        let cross = crossing_cells_of_fn(&plane, f)?;
        let nb = band_around(&plane, &cross, j)?;
        let v: Vec<f64> = nb.band.coords().map(|c| f(plane.pos(c))).collect();
        if let Some(i) = v.iter().position(|x| !x.is_finite()) {
            return Err(Error::InvalidField {
                name: "level-set function".into(),
                msg: format!("{} at band node {:?}", v[i], nb.band.coords().nth(i)),
            });
        }
        let (nb, phi) = rebuild(&plane, &nb, &v, Keep::Nothing)?;
        Ok(PlaneMcf { plane, nb, phi })
    }

    /// One time step of length `tau` under `o` (Dirichlet, natural or transparent conditions).
    /// Errors: [`Error::InvalidInput`] for a bad `tau`, no solve per step, or a band that leaves
    /// the grid;
    /// [`Error::EmptyLevelSet`] when the zero level vanishes; solver errors.
    pub fn step(&mut self, tau: f64, o: &McfOptions) -> Result<StepReport> {
        if !(tau.is_finite() && tau > 0.0) || o.inner == 0 {
            return Err(Error::InvalidInput(format!(
                "planar mean curvature step: tau = {tau}, solves per step = {} (both positive)",
                o.inner,
            )));
        }
        let plane = self.plane;
        let mut rep = StepReport::default();
        let mut nb = self.nb.clone();
        let mut phik = self.phi.clone();
        let mut approx = if o.bc == Bc::Dirichlet {
            predicted(&plane, &nb, &self.phi, tau)
        } else {
            self.phi.clone()
        };
        let solves = if o.bc == Bc::Dirichlet { o.inner } else { 1 };
        for m in 1..=solves {
            let t = Instant::now();
            let n = nb.band.len();
            let w = Weight::Mcf { eps: o.eps };
            let el = elements(&nb);
            let mats = assemble(&plane, &el, n, &phik, w)?;
            let a = system_matrix(&mats, tau)?;
            let mut b: Vec<f64> = mats.mass.iter().zip(&phik).map(|(m, p)| m * p).collect();
            rep.times.assembly += t.elapsed().as_secs_f64();
            let t = Instant::now();
            let mut x = approx.clone();
            rep.cg_iterations +=
                match o.bc {
                    Bc::Dirichlet => {
                        let fixed: Vec<bool> = nb.interior.iter().map(|i| !i).collect();
                        solve_dirichlet(&a, &b, &fixed, &mut x)?
                    }
                    Bc::Natural => solve_all(&a, &b, &mut x)?,
                    Bc::Extrapolated => return Err(Error::InvalidInput(
                        "mean curvature motion takes natural, transparent or Dirichlet conditions"
                            .into(),
                    )),
                    Bc::Transparent => {
                        let g = transparent_vector(&plane, &el, n, &phik, &approx, w);
                        b.iter_mut().zip(&g).for_each(|(b, g)| *b += tau * g);
                        solve_all(&a, &b, &mut x)?
                    }
                };
            rep.solves += 1;
            rep.times.solve += t.elapsed().as_secs_f64();
            let t = Instant::now();
            let (new_nb, new_approx) = rebuild(&plane, &nb, &x, Keep::Crossing)?;
            let same = band_difference(&nb.band, &new_nb.band) as f64 <= o.delta * n as f64;
            let (sum, count) = new_nb
                .band
                .coords()
                .zip(&new_approx)
                .zip(&new_nb.interior)
                .filter(|(_, &int)| !int)
                .filter_map(|((c, v), _)| nb.band.index(c).map(|k| (v - approx[k]).abs()))
                .fold((0.0, 0usize), |(s, m), d| (s + d, m + 1));
            let change = if count > 0 {
                sum / count as f64
            } else {
                f64::INFINITY
            };
            if m < solves {
                phik = extend_distance(
                    &plane,
                    &self.nb.band,
                    &self.phi,
                    &new_nb.band,
                    Keep::OldBand,
                    reach(&plane, nb.j),
                );
            }
            nb = new_nb;
            approx = new_approx;
            rep.times.rebuild += t.elapsed().as_secs_f64();
            if same && change < o.delta * plane.h {
                break;
            }
        }
        self.nb = nb;
        self.phi = approx;
        Ok(rep)
    }
}
