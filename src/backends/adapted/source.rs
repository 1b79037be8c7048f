//! The metric source of a re-adaptation: new vertices get the exact signed distance to the zero
//! level the mesh had before it was adapted (004 §2.2's geometric distance, evaluated at the new
//! point), so remeshing does not move the interface by interpolation.

use crate::adapt::MetricSource;
use crate::error::Result;
use crate::geom::DVec2;
use crate::levelset::extract_zero_level;
use crate::mesh::{Location, Mesh2};
use crate::metric::Sym2;
use rstar::primitives::Line;
use rstar::{PointDistance, RTree};

/// Signed distance to the piecewise-linear zero level of a P1 field on a frozen copy of a mesh:
/// the magnitude is the distance to the nearest zero-level segment, the sign that of the P1
/// field at the point (the two agree exactly on the zero level, where the sign changes). The
/// metric is left to interpolation.
pub(crate) struct DistanceSource {
    mesh: Mesh2,
    u: Vec<f64>,
    segments: RTree<Line<[f64; 2]>>,
}

impl DistanceSource {
    /// The source for the zero level of `u` on `mesh`. Errors: `u` invalid, or no zero level
    /// ([`crate::Error::EmptyLevelSet`]).
    pub(crate) fn new(mesh: &Mesh2, u: &[f64]) -> Result<DistanceSource> {
        let lines: Vec<Line<[f64; 2]>> = extract_zero_level(mesh, u)?
            .iter()
            .flat_map(|pl| {
                pl.segments()
                    .map(|(a, b)| Line::new(a.to_array(), b.to_array()))
                    .collect::<Vec<_>>()
            })
            .collect();
        Ok(DistanceSource {
            mesh: mesh.clone(),
            u: u.to_vec(),
            segments: RTree::bulk_load(lines),
        })
    }

    /// The signed distance at `p`.
    pub(crate) fn distance(&self, p: DVec2) -> f64 {
        let q = p.to_array();
        let d = self
            .segments
            .nearest_neighbor(q)
            .map_or(f64::INFINITY, |l| l.distance_2(&q).sqrt());
        let start = self.mesh.live_tris().next().unwrap_or(0) as u32;
        let (Location::Inside { tri, bary } | Location::Outside { tri, bary }) =
            self.mesh.locate(p, start);
        let t = self.mesh.tris[tri as usize];
        let value: f64 = (0..3).map(|k| bary[k] * self.u[t[k] as usize]).sum();
        if value < 0.0 {
            -d
        } else {
            d
        }
    }
}

impl MetricSource for DistanceSource {
    fn metric_at(&self, _p: DVec2) -> Option<Sym2> {
        None
    }
    fn fields_at(&self, p: DVec2, out: &mut [f64]) -> bool {
        if out.len() == 1 {
            out[0] = self.distance(p);
            true
        } else {
            false
        }
    }
}
