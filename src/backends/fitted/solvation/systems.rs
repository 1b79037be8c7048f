//! The artificial systems of 001 §7 and their initial surfaces ("wraps") in the unit square.
//!
//! - **three**: particles at (0.3, 0.35) and (0.6, 0.65) with `ε = 0.005`, `σ = 0.15`, and at
//!   (0.5, 0.2) with `ε = 0.003`, `σ = 0.1`; `γ = 0.0001`, `ρ_w = 0.5` (001 §7, Figs. 7.3–7.4).
//! - **ring**: 8 particles evenly on a circle (001 Figs. 7.5–7.6). 001 gives no parameters for
//!   it; here the circle has radius [`RING_RADIUS`] about the centre of the box, and the
//!   particles and the model take the two-rod values below.
//! - **rods**: 9 particles evenly on each of two parallel lines a distance `d` apart
//!   (001 Figs. 7.7–7.8), `γ = 0.00035`, `ρ_w = 0.5`, `ε = 0.0062`, `σ = 0.1`. 001 does not give
//!   the spacing along a rod; by default it is [`ROD_SPACING`]` σ = 0.05` (the rods vertical
//!   and centred in the box, from y = 0.3 to 0.7, on the 0.05 grid of 001's other particle
//!   positions), [`SystemKind::Rods`] takes any spacing. The spacing sets the van der Waals
//!   pull per unit length of a rod, and with it the upper end of the range of `d` in which the
//!   two wraps end in different minima (docs/solvation.md).
//!
//! **Wraps** (001 §7): a loose wrap is a large surface around all particles — here the convex
//! hull of the discs of radius `1.5 σ_i` about the particles ("at least 1.5σ from the i-th
//! particle", 001), which is the large circle of 001 Fig. 7.5 for the ring. A tight wrap is
//! `φ = min_i (|x − x_i| − σ̂_i)` with `σ̂_i = 0.4 σ_i < σ_i/2` (001 §7); for the ring it is
//! the annulus between two circles (001 Fig. 7.6), `||x − c| − R| − 0.4σ`.

use super::model::{Parameters, Particle, System};
use crate::error::{Error, Result};
use crate::geom::DVec2;

/// Radius of the ring of 8 particles.
pub const RING_RADIUS: f64 = 0.25;
/// Default spacing of the particles along a rod, in units of `σ` (001 does not give it).
pub const ROD_SPACING: f64 = 0.5;
/// Particles per rod.
pub const ROD_PARTICLES: usize = 9;
/// Distance of a loose wrap from the particles, in units of each particle's `σ`.
pub const LOOSE_MARGIN: f64 = 1.5;
/// Radius of a tight wrap about each particle, in units of its `σ`.
pub const TIGHT_RADIUS: f64 = 0.4;

/// The initial surface of a relaxation (001 §7).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Wrap {
    /// A large surface around all particles.
    Loose,
    /// A small surface tightly around the particles.
    Tight,
}

/// The systems of 001 §7.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SystemKind {
    /// Three particles (001 Figs. 7.3–7.4).
    Three,
    /// A ring of 8 particles (001 Figs. 7.5–7.6).
    Ring,
    /// Two rods of 9 particles, `d` apart (in units of `σ`; 001 Figs. 7.7–7.8).
    Rods {
        /// Distance between the rods in units of `σ = 0.1`.
        d: f64,
        /// Spacing of the particles along a rod in units of `σ` ([`ROD_SPACING`] by default).
        spacing: f64,
    },
}

const ROD_SIGMA: f64 = 0.1;
const ROD_EPSILON: f64 = 0.0062;

fn unit_box() -> (DVec2, DVec2) {
    (DVec2::ZERO, DVec2::ONE)
}

impl SystemKind {
    /// The two rods `d σ` apart with the default spacing [`ROD_SPACING`].
    pub fn rods(d: f64) -> Self {
        SystemKind::Rods {
            d,
            spacing: ROD_SPACING,
        }
    }

    /// The particles and parameters. Errors: a rod distance that is not finite and positive,
    /// or rods that do not fit in the box.
    pub fn system(&self) -> Result<System> {
        let rod_params = Parameters {
            gamma: 0.00035,
            rho_w: 0.5,
            pressure: 0.0,
            tolman: 0.0,
        };
        let particle = |x: f64, y: f64, sigma: f64, epsilon: f64| Particle {
            x: DVec2::new(x, y),
            sigma,
            epsilon,
        };
        let sys = match *self {
            SystemKind::Three => System {
                particles: vec![
                    particle(0.3, 0.35, 0.15, 0.005),
                    particle(0.6, 0.65, 0.15, 0.005),
                    particle(0.5, 0.2, 0.1, 0.003),
                ],
                params: Parameters {
                    gamma: 0.0001,
                    rho_w: 0.5,
                    pressure: 0.0,
                    tolman: 0.0,
                },
                domain: unit_box(),
            },
            SystemKind::Ring => System {
                particles: (0..8)
                    .map(|k| {
                        let a = std::f64::consts::FRAC_PI_4 * k as f64;
                        particle(
                            0.5 + RING_RADIUS * a.cos(),
                            0.5 + RING_RADIUS * a.sin(),
                            ROD_SIGMA,
                            ROD_EPSILON,
                        )
                    })
                    .collect(),
                params: rod_params,
                domain: unit_box(),
            },
            SystemKind::Rods { d, spacing } => {
                if !(d.is_finite() && d > 0.0) {
                    return Err(Error::InvalidInput(format!(
                        "solvation: the rod distance d must be finite and positive (got {d})"
                    )));
                }
                if !(spacing.is_finite() && spacing > 0.0) {
                    return Err(Error::InvalidInput(format!(
                        "solvation: the spacing along a rod must be finite and positive (got \
                         {spacing})"
                    )));
                }
                let half = 0.5 * d * ROD_SIGMA;
                let mut particles = Vec::with_capacity(2 * ROD_PARTICLES);
                for x in [0.5 - half, 0.5 + half] {
                    for k in 0..ROD_PARTICLES {
                        let y = 0.5 + (k as f64 - 4.0) * spacing * ROD_SIGMA;
                        particles.push(particle(x, y, ROD_SIGMA, ROD_EPSILON));
                    }
                }
                System {
                    particles,
                    params: rod_params,
                    domain: unit_box(),
                }
            }
        };
        sys.check()?;
        Ok(sys)
    }

    /// A short name ("three", "ring", "rods").
    pub fn name(&self) -> &'static str {
        match self {
            SystemKind::Three => "three",
            SystemKind::Ring => "ring",
            SystemKind::Rods { .. } => "rods",
        }
    }
}

/// The initial level set of `wrap` about `sys` at `points` (negative in the solute; a signed
/// distance for the loose wrap and the ring's annulus, a minimum of distances otherwise).
/// `ring` selects the annulus for the tight wrap (001 Fig. 7.6).
pub fn initial_level_set(sys: &System, wrap: Wrap, ring: bool, points: &[DVec2]) -> Vec<f64> {
    match wrap {
        Wrap::Loose => {
            let hull = disc_hull(&sys.particles, LOOSE_MARGIN);
            points.iter().map(|&p| convex_distance(&hull, p)).collect()
        }
        Wrap::Tight if ring => {
            let n = sys.particles.len() as f64;
            let c = sys.particles.iter().map(|p| p.x).sum::<DVec2>() / n;
            let r = sys
                .particles
                .iter()
                .map(|p| (p.x - c).length())
                .sum::<f64>()
                / n;
            let w = TIGHT_RADIUS * sys.particles.iter().map(|p| p.sigma).fold(0.0, f64::max);
            points
                .iter()
                .map(|&p| ((p - c).length() - r).abs() - w)
                .collect()
        }
        Wrap::Tight => points
            .iter()
            .map(|&p| {
                sys.particles
                    .iter()
                    .map(|q| (p - q.x).length() - TIGHT_RADIUS * q.sigma)
                    .fold(f64::INFINITY, f64::min)
            })
            .collect(),
    }
}

/// The convex hull (counter-clockwise) of the discs of radius `margin σ_i` about the particles,
/// from 256 points on each circle (Andrew's monotone chain).
fn disc_hull(particles: &[Particle], margin: f64) -> Vec<DVec2> {
    let mut pts: Vec<DVec2> = Vec::new();
    for p in particles {
        for k in 0..256 {
            let a = std::f64::consts::TAU * k as f64 / 256.0;
            pts.push(p.x + DVec2::new(a.cos(), a.sin()) * (margin * p.sigma));
        }
    }
    pts.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    let cross = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut lower: Vec<DVec2> = Vec::new();
    for &p in &pts {
        while lower.len() >= 2 && cross(lower[lower.len() - 2], lower[lower.len() - 1], p) <= 0.0 {
            lower.pop();
        }
        lower.push(p);
    }
    let mut upper: Vec<DVec2> = Vec::new();
    for &p in pts.iter().rev() {
        while upper.len() >= 2 && cross(upper[upper.len() - 2], upper[upper.len() - 1], p) <= 0.0 {
            upper.pop();
        }
        upper.push(p);
    }
    lower.pop();
    upper.pop();
    lower.extend(upper);
    lower
}

/// Signed distance from `p` to the counter-clockwise convex polygon `poly` (negative inside).
fn convex_distance(poly: &[DVec2], p: DVec2) -> f64 {
    let n = poly.len();
    let mut dist = f64::INFINITY;
    let mut inside = true;
    for k in 0..n {
        let (a, b) = (poly[k], poly[(k + 1) % n]);
        dist = dist.min(super::model::segment_distance(p, a, b));
        if (b - a).perp_dot(p - a) < 0.0 {
            inside = false;
        }
    }
    if inside {
        -dist
    } else {
        dist
    }
}
