//! Comparing the P1 zero levels of two level sets on two tetrahedral meshes: the 3D yardstick of
//! `anisomesh measure --against` ([`super::compare`] in 2D).
//!
//! - **Point location** ([`TetLocator`]): an R-tree of the tetrahedra's bounding boxes; a point
//!   takes the candidate tetrahedron whose smallest barycentric coordinate is largest (inside
//!   when it is `>= -1e-12`); a point outside the mesh takes, among the 16 tetrahedra whose boxes
//!   are nearest, the one with the largest smallest coordinate, with the weights clipped at 0.
//! - **Interface distance**: the zero levels are the triangle soups of
//!   [`super::redistance::ZeroLevelPieces`]; every triangle of one is sampled at the 15 points
//!   of its barycentric grid of step 1/4 (corners, edges, interior), each at its exact distance
//!   to the other soup (an R-tree of triangles, exact point–triangle distance); both directions
//!   and their maximum (the sampled Hausdorff distance).
//! - **Volume error**: the volumes of `{v < 0}` and `{u < 0}`, exact up to round-off
//!   ([`super::enclosed_measure`]).

use super::compare::ZeroLevelComparison;
use super::enclosed_measure;
use super::redistance::ZeroLevelPieces;
use crate::error::{Error, Result};
use crate::fem::lagrange::bary_tet;
use crate::geom::simplex::facet_distance;
use crate::geom::DVec3;
use rayon::prelude::*;
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{PointDistance, RTree, RTreeObject, AABB};

/// Samples per side of a zero-level triangle's barycentric grid.
pub const GRID_STEPS: usize = 4;

/// Candidates examined for a point outside the mesh.
const OUTSIDE_CANDIDATES: usize = 16;

type TetBox = GeomWithData<Rectangle<[f64; 3]>, u32>;

/// Point location in a tetrahedral mesh (module documentation).
pub struct TetLocator<'a> {
    points: &'a [DVec3],
    tets: &'a [[u32; 4]],
    tree: RTree<TetBox>,
}

impl<'a> TetLocator<'a> {
    /// The locator of `tets` over `points`. Errors: no tetrahedra, a vertex index out of range.
    pub fn new(points: &'a [DVec3], tets: &'a [[u32; 4]]) -> Result<Self> {
        if tets.is_empty() {
            return Err(Error::InvalidInput(
                "the reference mesh has no tetrahedra".into(),
            ));
        }
        if let Some(t) = tets
            .iter()
            .position(|t| t.iter().any(|&v| v as usize >= points.len()))
        {
            return Err(Error::InvalidInput(format!(
                "tetrahedron {} has a vertex out of range ({} vertices)",
                t + 1,
                points.len()
            )));
        }
        let boxes = tets
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let p = t.map(|v| points[v as usize]);
                let lo = p[0].min(p[1]).min(p[2]).min(p[3]);
                let hi = p[0].max(p[1]).max(p[2]).max(p[3]);
                GeomWithData::new(
                    Rectangle::from_corners(lo.to_array(), hi.to_array()),
                    i as u32,
                )
            })
            .collect();
        Ok(TetLocator {
            points,
            tets,
            tree: RTree::bulk_load(boxes),
        })
    }

    fn bary(&self, t: u32, x: DVec3) -> [f64; 4] {
        bary_tet(self.tets[t as usize].map(|v| self.points[v as usize]), x)
    }

    /// The tetrahedron containing `x` (or the nearest candidate) and the barycentric weights,
    /// clipped at 0 and summing to 1.
    pub fn locate(&self, x: DVec3) -> (u32, [f64; 4]) {
        let q = x.to_array();
        let min = |b: &[f64; 4]| b.iter().copied().fold(f64::INFINITY, f64::min);
        let mut best: Option<(u32, [f64; 4])> = None;
        for c in self.tree.locate_all_at_point(q) {
            let b = self.bary(c.data, x);
            if best.map_or(true, |(_, bb)| min(&b) > min(&bb)) {
                best = Some((c.data, b));
            }
        }
        if best.map_or(true, |(_, b)| min(&b) < -1e-12) {
            for c in self.tree.nearest_neighbor_iter(q).take(OUTSIDE_CANDIDATES) {
                let b = self.bary(c.data, x);
                if best.map_or(true, |(_, bb)| min(&b) > min(&bb)) {
                    best = Some((c.data, b));
                }
            }
        }
        let (t, b) = best.expect("a non-empty tree has a nearest box");
        let w = b.map(|v| v.max(0.0));
        let s: f64 = w.iter().sum();
        (t, w.map(|v| v / s))
    }

    /// The P1 interpolant of `u` (one value per vertex) at `x`.
    pub fn interpolate(&self, u: &[f64], x: DVec3) -> f64 {
        let (t, w) = self.locate(x);
        let v = self.tets[t as usize];
        (0..4).map(|k| w[k] * u[v[k] as usize]).sum()
    }
}

/// The P1 interpolant of `u` on the tetrahedra `tets` over `points` at the points `at`
/// ([`TetLocator`]). Errors: a field without one finite value per vertex, no tetrahedra.
pub fn interpolate_p1_tets(
    points: &[DVec3],
    tets: &[[u32; 4]],
    u: &[f64],
    at: &[DVec3],
) -> Result<Vec<f64>> {
    crate::mesh::check_p1_field(points.len(), u, "u")?;
    let loc = TetLocator::new(points, tets)?;
    Ok(at.par_iter().map(|&x| loc.interpolate(u, x)).collect())
}

/// A zero-level triangle in the R-tree.
pub(crate) struct Facet(pub(crate) [DVec3; 3]);

impl RTreeObject for Facet {
    type Envelope = AABB<[f64; 3]>;
    fn envelope(&self) -> Self::Envelope {
        let [a, b, c] = self.0;
        AABB::from_corners(a.min(b).min(c).to_array(), a.max(b).max(c).to_array())
    }
}

impl PointDistance for Facet {
    fn distance_2(&self, q: &[f64; 3]) -> f64 {
        let d = facet_distance(DVec3::from_array(*q), &self.0);
        d * d
    }
}

fn pieces(points: &[DVec3], tets: &[[u32; 4]], u: &[f64]) -> Vec<[DVec3; 3]> {
    let mut out = Vec::new();
    for t in tets {
        DVec3::zero_pieces(t, u, |v| points[v as usize], &mut out);
    }
    out
}

/// Largest distance from the grid samples of the triangles `from` to the soup `to`.
fn one_side(from: &[[DVec3; 3]], to: &RTree<Facet>) -> f64 {
    let k = GRID_STEPS;
    from.par_iter()
        .map(|&[a, b, c]| {
            let mut worst: f64 = 0.0;
            for i in 0..=k {
                for j in 0..=k - i {
                    let (s, t) = (i as f64 / k as f64, j as f64 / k as f64);
                    let q = a + (b - a) * s + (c - a) * t;
                    let d = to
                        .nearest_neighbor(q.to_array())
                        .map_or(f64::INFINITY, |f| facet_distance(q, &f.0));
                    worst = worst.max(d);
                }
            }
            worst
        })
        .reduce(|| 0.0, f64::max)
}

/// Compares the zero level of `v` on the tetrahedra `tets` over `points` with that of `u` on
/// `ref_tets` over `ref_points` (module documentation); the `area` fields of the result hold
/// volumes. Errors: invalid fields or cells, an empty zero level on either side.
pub fn compare_zero_levels3(
    points: &[DVec3],
    tets: &[[u32; 4]],
    v: &[f64],
    ref_points: &[DVec3],
    ref_tets: &[[u32; 4]],
    u: &[f64],
) -> Result<ZeroLevelComparison> {
    let volume = enclosed_measure(points, tets, v)?;
    let reference_volume = enclosed_measure(ref_points, ref_tets, u)?;
    let ours = pieces(points, tets, v);
    let theirs = pieces(ref_points, ref_tets, u);
    if ours.is_empty() || theirs.is_empty() {
        return Err(Error::EmptyLevelSet(format!(
            "no zero level on the {} mesh",
            if ours.is_empty() {
                "measured"
            } else {
                "reference"
            }
        )));
    }
    let tree = |f: &[[DVec3; 3]]| RTree::bulk_load(f.iter().map(|&t| Facet(t)).collect());
    let to_reference_max = one_side(&ours, &tree(&theirs));
    let from_reference_max = one_side(&theirs, &tree(&ours));
    Ok(ZeroLevelComparison {
        to_reference_max,
        from_reference_max,
        hausdorff: to_reference_max.max(from_reference_max),
        area: volume,
        reference_area: reference_volume,
        relative_area_error: (volume - reference_volume).abs() / reference_volume.abs(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh3::Mesh3;

    #[test]
    fn planes_are_compared_exactly_and_linear_fields_interpolated_exactly() {
        let coarse = Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [5, 4, 3]).unwrap();
        let fine = Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [7, 6, 9]).unwrap();
        let f = |p: DVec3| p.x - 0.43 + 0.1 * p.y - 0.05 * p.z;
        let u: Vec<f64> = coarse.points.iter().map(|&p| f(p)).collect();
        let v = interpolate_p1_tets(&coarse.points, &coarse.tets, &u, &fine.points).unwrap();
        for (p, x) in fine.points.iter().zip(&v) {
            assert!((x - f(*p)).abs() < 1e-13, "{p} {x}");
        }
        // Just outside the mesh (round-off in a user's file): the nearest tetrahedron, clipped
        // weights.
        let x = DVec3::new(0.37, 0.52, 1.0 + 1e-9);
        let out = interpolate_p1_tets(&coarse.points, &coarse.tets, &u, &[x]).unwrap();
        assert!((out[0] - f(x)).abs() < 1e-8, "{out:?}");
        let c = compare_zero_levels3(
            &fine.points,
            &fine.tets,
            &v,
            &coarse.points,
            &coarse.tets,
            &u,
        )
        .unwrap();
        assert!(
            c.hausdorff < 1e-12 && c.relative_area_error < 1e-12,
            "{c:?}"
        );
        // A plane x = 0.45 against x = 0.43: distance 0.02 both ways, volume error 0.02 / 0.43.
        let a: Vec<f64> = coarse.points.iter().map(|p| p.x - 0.43).collect();
        let b: Vec<f64> = fine.points.iter().map(|p| p.x - 0.45).collect();
        let c = compare_zero_levels3(
            &fine.points,
            &fine.tets,
            &b,
            &coarse.points,
            &coarse.tets,
            &a,
        )
        .unwrap();
        assert!((c.to_reference_max - 0.02).abs() < 1e-12, "{c:?}");
        assert!((c.from_reference_max - 0.02).abs() < 1e-12, "{c:?}");
        assert!((c.relative_area_error - 0.02 / 0.43).abs() < 1e-12, "{c:?}");
        let none = vec![1.0; fine.points.len()];
        assert!(matches!(
            compare_zero_levels3(
                &fine.points,
                &fine.tets,
                &none,
                &coarse.points,
                &coarse.tets,
                &a
            ),
            Err(Error::EmptyLevelSet(_))
        ));
    }
}
