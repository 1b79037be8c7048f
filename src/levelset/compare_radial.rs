//! Measuring a discrete surface (the P1 zero level of a tetrahedral mesh, or the labelled
//! interface between two regions of it) against an exact star-shaped surface
//! `{c + ρ(d) d : |d| = 1}` — the yardstick of the 004 §5 star (`ρ = 0.45 + 0.3 cos 6θ cos² 3φ`)
//! and of the sphere.
//!
//! - **Exact → discrete**: the exact surface is sampled at the vertices and at the radially
//!   projected triangle centroids of the refined icosahedron of `level`
//!   ([`super::radial_surface`]; every sample lies exactly on the surface); each sample's
//!   distance to the discrete triangles is exact (an R-tree of triangles, exact point–triangle
//!   distance).
//! - **Discrete → exact**: every discrete triangle is sampled at the 15 points of its
//!   barycentric grid of step 1/4; the distance of a sample `q` to the exact surface is
//!   `min_d |q − c − ρ(d) d|`, found by Gauss–Newton on the direction `d` (two tangent
//!   coordinates, ρ differentiated by central differences), started from the closest point of
//!   the icosahedral triangulation (its direction through the centre), each step halved until
//!   the distance does not grow; the result is the distance to a point of the exact surface.
//! - **Volume**: the volume inside the discrete surface (of the P1 level set or of the inside
//!   region) against the exact volume.
//!
//! Each direction is summarised by its median, 99th percentile and maximum.

use super::compare3::Facet;
use super::redistance::ZeroLevelPieces;
use super::triangulated::closest::closest_point;
use super::{enclosed_measure, radial_surface};
use crate::error::{Error, Result};
use crate::geom::DVec3;
use rayon::prelude::*;
use rstar::RTree;
use serde::Serialize;
use std::collections::HashMap;

/// An exact star-shaped surface `{centre + ρ(d) d : |d| = 1}`.
pub struct RadialSurface<'a> {
    /// The centre.
    pub centre: DVec3,
    /// The radius in the direction of a unit vector (positive).
    pub rho: &'a (dyn Fn(DVec3) -> f64 + Sync),
    /// The exact enclosed volume.
    pub volume: f64,
}

/// Median, 99th percentile and maximum of a set of distances.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct DistanceStats {
    /// Number of samples.
    pub samples: usize,
    /// Median.
    pub median: f64,
    /// 99th percentile (nearest rank).
    pub p99: f64,
    /// Maximum.
    pub max: f64,
}

impl DistanceStats {
    /// The statistics of `d` (sorted in place).
    pub fn of(d: &mut [f64]) -> DistanceStats {
        if d.is_empty() {
            return DistanceStats::default();
        }
        d.sort_by(f64::total_cmp);
        let rank = |q: f64| d[((q * d.len() as f64).ceil() as usize).clamp(1, d.len()) - 1];
        DistanceStats {
            samples: d.len(),
            median: rank(0.5),
            p99: rank(0.99),
            max: d[d.len() - 1],
        }
    }
}

/// What [`compare_to_radial`] measured.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct RadialComparison {
    /// Discrete triangles measured.
    pub triangles: usize,
    /// Distances from samples of the exact surface to the discrete surface.
    pub exact_to_discrete: DistanceStats,
    /// Distances from samples of the discrete surface to the exact surface.
    pub discrete_to_exact: DistanceStats,
    /// Volume inside the discrete surface.
    pub volume: f64,
    /// The exact volume.
    pub exact_volume: f64,
    /// `volume − exact_volume`.
    pub volume_error: f64,
}

/// Samples per side of a discrete triangle's barycentric grid.
const GRID_STEPS: usize = 4;

/// The triangles of the P1 zero level of `u` on the tetrahedra `tets`, and the volume of
/// `{u < 0}`. Errors: an invalid field or cells.
pub fn zero_level_triangles(
    points: &[DVec3],
    tets: &[[u32; 4]],
    u: &[f64],
) -> Result<(Vec<[DVec3; 3]>, f64)> {
    let volume = enclosed_measure(points, tets, u)?;
    let mut out = Vec::new();
    for t in tets {
        DVec3::zero_pieces(t, u, |v| points[v as usize], &mut out);
    }
    Ok((out, volume))
}

/// The faces shared by a tetrahedron labelled `inside` and one labelled `outside` (the
/// interface `mmg3d -ls` writes between its regions 3 and 2), and the volume of the `inside`
/// tetrahedra. Errors: no such face.
pub fn interface_triangles(
    points: &[DVec3],
    tets: &[[u32; 4]],
    tet_ref: &[i32],
    inside: i32,
    outside: i32,
) -> Result<(Vec<[DVec3; 3]>, f64)> {
    let mut faces: HashMap<[u32; 3], i32> = HashMap::new();
    let mut out = Vec::new();
    let mut volume = 0.0;
    for (t, r) in tets.iter().zip(tet_ref) {
        if *r != inside && *r != outside {
            continue;
        }
        let p = t.map(|v| points[v as usize]);
        if *r == inside {
            volume += (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0])).abs() / 6.0;
        }
        for skip in 0..4 {
            let mut f = [0u32; 3];
            let mut k = 0;
            for (i, &v) in t.iter().enumerate() {
                if i != skip {
                    f[k] = v;
                    k += 1;
                }
            }
            f.sort_unstable();
            match faces.remove(&f) {
                Some(other) if other != *r => out.push(f.map(|v| points[v as usize])),
                Some(_) => {}
                None => {
                    faces.insert(f, *r);
                }
            }
        }
    }
    if out.is_empty() {
        return Err(Error::EmptyLevelSet(format!(
            "no face between a tetrahedron labelled {inside} and one labelled {outside}"
        )));
    }
    Ok((out, volume))
}

/// The reference triangulation of the exact surface and the Gauss–Newton projection.
struct Exact<'a> {
    s: &'a RadialSurface<'a>,
    tris: Vec<[DVec3; 3]>,
    tree: RTree<Facet>,
}

impl Exact<'_> {
    fn point(&self, d: DVec3) -> DVec3 {
        self.s.centre + (self.s.rho)(d) * d
    }

    /// `min_d |q − X(d)|` (module documentation).
    fn distance(&self, q: DVec3) -> f64 {
        let Some(f) = self.tree.nearest_neighbor(q.to_array()) else {
            return f64::INFINITY;
        };
        let [a, b, c] = f.0;
        let (y, _) = closest_point(q, a, b, c);
        let Some(mut d) = (y - self.s.centre).try_normalize() else {
            return (q - a).length();
        };
        let mut cur = (q - self.point(d)).length();
        for _ in 0..40 {
            let e1 = d.any_orthonormal_vector();
            let e2 = d.cross(e1);
            let h = 1e-6;
            let x = |s: f64, t: f64| self.point((d + s * e1 + t * e2).normalize());
            let x0 = self.point(d);
            let j1 = (x(h, 0.0) - x(-h, 0.0)) / (2.0 * h);
            let j2 = (x(0.0, h) - x(0.0, -h)) / (2.0 * h);
            let r = q - x0;
            // Normal equations of min |r − J δ|².
            let (a11, a12, a22) = (j1.dot(j1), j1.dot(j2), j2.dot(j2));
            let (b1, b2) = (j1.dot(r), j2.dot(r));
            let det = a11 * a22 - a12 * a12;
            if det.abs() <= 1e-300 || det.is_nan() {
                break;
            }
            let (mut s, mut t) = ((a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det);
            // Damped: halve the step until the distance does not grow.
            let mut accepted = false;
            for _ in 0..20 {
                let nd = (d + s * e1 + t * e2).normalize();
                let v = (q - self.point(nd)).length();
                if v <= cur {
                    let step = (nd - d).length();
                    d = nd;
                    cur = v;
                    accepted = step > 1e-14;
                    break;
                }
                s *= 0.5;
                t *= 0.5;
            }
            if !accepted {
                break;
            }
        }
        cur
    }
}

/// Compares the discrete surface `triangles` (enclosing `volume`) with the exact surface
/// `exact` (module documentation), sampling the exact surface on the icosahedron of `level`
/// (`20 · 4^level` triangles; 7 gives about 490,000 samples). Errors: no triangles, a level
/// above 9.
pub fn compare_to_radial(
    triangles: &[[DVec3; 3]],
    volume: f64,
    exact: &RadialSurface<'_>,
    level: u32,
) -> Result<RadialComparison> {
    if triangles.is_empty() {
        return Err(Error::EmptyLevelSet(
            "the discrete surface has no triangles".into(),
        ));
    }
    if level > 9 {
        return Err(Error::InvalidInput(format!(
            "sampling level {level}: at most 9 (5 million triangles)"
        )));
    }
    let reference = radial_surface(exact.centre, exact.rho, level);
    let tris: Vec<[DVec3; 3]> = reference
        .triangles
        .iter()
        .map(|t| t.map(|v| reference.points[v as usize]))
        .collect();
    let ex = Exact {
        s: exact,
        tree: RTree::bulk_load(tris.iter().map(|&t| Facet(t)).collect()),
        tris,
    };
    // Exact samples: the vertices and the projected centroids.
    let mut samples = reference.points.clone();
    samples.extend(ex.tris.iter().filter_map(|[a, b, c]| {
        let d = ((*a + *b + *c) / 3.0 - exact.centre).try_normalize()?;
        Some(ex.point(d))
    }));
    let discrete = RTree::bulk_load(triangles.iter().map(|&t| Facet(t)).collect::<Vec<_>>());
    let mut to_discrete: Vec<f64> = samples
        .par_iter()
        .map(|&q| {
            discrete
                .nearest_neighbor(q.to_array())
                .map_or(f64::INFINITY, |f| {
                    let [a, b, c] = f.0;
                    (q - closest_point(q, a, b, c).0).length()
                })
        })
        .collect();
    let k = GRID_STEPS;
    let mut to_exact: Vec<f64> = triangles
        .par_iter()
        .flat_map_iter(|&[a, b, c]| {
            let ex = &ex;
            (0..=k).flat_map(move |i| {
                (0..=k - i).map(move |j| {
                    let (s, t) = (i as f64 / k as f64, j as f64 / k as f64);
                    ex.distance(a + (b - a) * s + (c - a) * t)
                })
            })
        })
        .collect();
    Ok(RadialComparison {
        triangles: triangles.len(),
        exact_to_discrete: DistanceStats::of(&mut to_discrete),
        discrete_to_exact: DistanceStats::of(&mut to_exact),
        volume,
        exact_volume: exact.volume,
        volume_error: volume - exact.volume,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::levelset::StarSurface;

    #[test]
    fn projection_onto_the_star_recovers_normal_offsets() {
        // Points moved by t along the exact normal of the star are at distance |t|.
        let star = StarSurface::PAPER;
        let rho = |d: DVec3| star.radius_towards(d);
        let s = RadialSurface {
            centre: DVec3::ZERO,
            rho: &rho,
            volume: 0.0,
        };
        let reference = radial_surface(DVec3::ZERO, rho, 5);
        let tris = reference
            .triangles
            .iter()
            .map(|t| t.map(|v| reference.points[v as usize]))
            .collect::<Vec<_>>();
        let ex = Exact {
            s: &s,
            tree: RTree::bulk_load(tris.iter().map(|&t| Facet(t)).collect()),
            tris,
        };
        use crate::levelset::Shape;
        let mut worst: f64 = 0.0;
        for i in 0..200 {
            let th = 0.1 + 0.031 * i as f64;
            let ph = -1.4 + 0.014 * i as f64;
            let d = DVec3::new(ph.cos() * th.cos(), ph.cos() * th.sin(), ph.sin());
            let x = ex.point(d);
            let n = star.gradient(x).normalize();
            for t in [-3e-3, -1e-4, 2e-5, 1e-3] {
                let got = ex.distance(x + t * n);
                worst = worst.max((got - t.abs()).abs() / t.abs());
            }
        }
        assert!(worst < 1e-4, "relative error {worst}");
    }
}
