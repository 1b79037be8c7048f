//! Comparing the P1 zero levels of two level sets on two triangle meshes: the yardstick of
//! `anisomesh measure --against`, for an adapted mesh against the reference it was adapted to.
//!
//! The measured level set is the reference's P1 field interpolated at the measured mesh's
//! vertices (or a field the caller gives), so that the comparison is the interpolation error
//! of the measured mesh. The distance between the two zero levels is sampled: `k` points per
//! segment (ends included) of each polyline, each at its exact distance to the other polyline
//! (an R-tree of segments); the enclosed areas are exact ([`super::enclosed_area`]).

use super::interface::{enclosed_area, extract_zero_level, Polyline};
use crate::error::{Error, Result};
use crate::geom::{point_segment_distance, DVec2};
use crate::mesh::{Location, Mesh2};
use rstar::primitives::Line;
use rstar::RTree;

/// Samples per segment of [`compare_zero_levels`].
pub const SAMPLES_PER_SEGMENT: usize = 8;

/// The result of [`compare_zero_levels`].
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ZeroLevelComparison {
    /// Largest distance from a sample of the measured zero level to the reference one.
    pub to_reference_max: f64,
    /// Largest distance from a sample of the reference zero level to the measured one.
    pub from_reference_max: f64,
    /// `max` of the two: the sampled Hausdorff distance.
    pub hausdorff: f64,
    /// Area of `{v < 0}` on the measured mesh (volume in 3D, [`super::compare3`]).
    pub area: f64,
    /// Area of `{u < 0}` on the reference mesh (volume in 3D).
    pub reference_area: f64,
    /// `|area - reference_area| / reference_area`.
    pub relative_area_error: f64,
}

/// The P1 interpolant of `u` (on `reference`) at `points`; a point outside the reference mesh
/// takes the nearest triangle along the walk with its barycentric weights clipped at 0.
pub fn interpolate_p1(reference: &Mesh2, u: &[f64], points: &[DVec2]) -> Result<Vec<f64>> {
    crate::mesh::check_p1_field(reference.n_points(), u, "u")?;
    if reference.n_live_tris() == 0 {
        return Err(Error::InvalidInput(
            "the reference mesh has no triangles".into(),
        ));
    }
    let mut start = 0u32;
    Ok(points
        .iter()
        .map(|&p| {
            let (t, bary) = match reference.locate(p, start) {
                Location::Inside { tri, bary } | Location::Outside { tri, bary } => (tri, bary),
            };
            start = t;
            let w = bary.map(|b| b.max(0.0));
            let s: f64 = w.iter().sum();
            let v = reference.tris[t as usize];
            (0..3).map(|k| w[k] / s * u[v[k] as usize]).sum()
        })
        .collect())
}

fn segments(lines: &[Polyline]) -> Vec<(DVec2, DVec2)> {
    lines.iter().flat_map(|l| l.segments()).collect()
}

/// Largest distance from the samples of `from` to the segments of `to`.
fn one_side(from: &[(DVec2, DVec2)], to: &[(DVec2, DVec2)]) -> f64 {
    let tree = RTree::bulk_load(
        to.iter()
            .map(|(a, b)| Line::new(a.to_array(), b.to_array()))
            .collect(),
    );
    let k = SAMPLES_PER_SEGMENT;
    let mut worst: f64 = 0.0;
    for &(a, b) in from {
        for i in 0..k {
            let q = a + (b - a) * (i as f64 / (k - 1) as f64);
            let d = tree
                .nearest_neighbor(q.to_array())
                .map_or(f64::INFINITY, |l| {
                    point_segment_distance(q, DVec2::from_array(l.from), DVec2::from_array(l.to)).0
                });
            worst = worst.max(d);
        }
    }
    worst
}

/// Compares the zero level of `v` on `mesh` with that of `u` on `reference` (module
/// documentation). Errors: invalid fields, or an empty zero level on either side.
pub fn compare_zero_levels(
    mesh: &Mesh2,
    v: &[f64],
    reference: &Mesh2,
    u: &[f64],
) -> Result<ZeroLevelComparison> {
    let ours = segments(&extract_zero_level(mesh, v)?);
    let theirs = segments(&extract_zero_level(reference, u)?);
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
    let to_reference_max = one_side(&ours, &theirs);
    let from_reference_max = one_side(&theirs, &ours);
    let area = enclosed_area(mesh, v)?;
    let reference_area = enclosed_area(reference, u)?;
    Ok(ZeroLevelComparison {
        to_reference_max,
        from_reference_max,
        hausdorff: to_reference_max.max(from_reference_max),
        area,
        reference_area,
        relative_area_error: (area - reference_area).abs() / reference_area.abs(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::GridPattern;

    #[test]
    fn a_mesh_against_itself_and_a_shifted_line() {
        let mesh = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 10, 10, GridPattern::Right).unwrap();
        let u: Vec<f64> = mesh.points.iter().map(|p| p.x - 0.43).collect();
        let c = compare_zero_levels(&mesh, &u, &mesh, &u).unwrap();
        assert!(
            c.hausdorff < 1e-14 && c.relative_area_error < 1e-14,
            "{c:?}"
        );
        let fine = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 17, 13, GridPattern::Right).unwrap();
        let v = interpolate_p1(&mesh, &u, &fine.points).unwrap();
        let c = compare_zero_levels(&fine, &v, &mesh, &u).unwrap();
        // A linear field is interpolated exactly: the same line.
        assert!(c.hausdorff < 1e-12, "{c:?}");
        let w: Vec<f64> = fine.points.iter().map(|p| p.x - 0.45).collect();
        let c = compare_zero_levels(&fine, &w, &mesh, &u).unwrap();
        assert!((c.hausdorff - 0.02).abs() < 1e-12, "{c:?}");
        assert!((c.relative_area_error - 0.02 / 0.43).abs() < 1e-12, "{c:?}");
    }
}
