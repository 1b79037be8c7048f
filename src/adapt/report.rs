//! The report of an adapted level-set mesh (serde `Serialize`, for the CLI and the benches):
//! size, metric conformity (edge lengths, `Q_ani`, 004 §3.4), the discrete interface's area,
//! perimeter and two-sided distance to the exact shape, and timings.

use crate::error::Result;
use crate::levelset::interface::{
    enclosed_area, extract_zero_level, interface_distance, interface_length,
};
use crate::levelset::shapes::Shape;
use crate::mesh::Mesh2;
use crate::metric::{quality_stats, Sym2};
use serde::Serialize;

/// Measures of an adapted mesh and its level set.
#[derive(Debug, Clone, Default, Serialize)]
pub struct MeshReport {
    /// Number of vertices.
    pub vertices: usize,
    /// Number of triangles.
    pub triangles: usize,
    /// Share of edges with metric length in `[1/sqrt 2, sqrt 2]`.
    pub edge_length_in_range: f64,
    /// Mean `Q_ani` of the triangles (004 §3.4; 1 is ideal).
    pub q_ani_mean: f64,
    /// Worst `Q_ani` of the triangles.
    pub q_ani_max: f64,
    /// Area enclosed by the zero level of the P1 level set (`u < 0`).
    pub area: f64,
    /// Length of the zero level.
    pub perimeter: f64,
    /// Exact area and perimeter of the shape, when there is one and they are known.
    pub exact_area: Option<f64>,
    /// Exact perimeter of the shape, when known.
    pub exact_perimeter: Option<f64>,
    /// `|area - exact| / exact`.
    pub area_rel_error: Option<f64>,
    /// Two-sided sampled Hausdorff distance between the zero level and the exact interface.
    pub hausdorff: Option<f64>,
    /// Total seconds, and seconds per phase (`(name, seconds)`).
    pub seconds: f64,
    /// Seconds per phase, `(name, seconds)`.
    pub phases: Vec<(String, f64)>,
}

/// Measures `mesh` with its metric and level set `u` (and the exact `shape` when given).
pub fn mesh_report(
    mesh: &Mesh2,
    metric: &[Sym2],
    u: &[f64],
    shape: Option<&dyn Shape>,
) -> Result<MeshReport> {
    let q = quality_stats(mesh, metric);
    let area = enclosed_area(mesh, u)?;
    let perimeter = interface_length(mesh, u)?;
    let (mut exact_area, mut exact_perimeter, mut hausdorff) = (None, None, None);
    if let Some(s) = shape {
        exact_area = s.exact_area();
        exact_perimeter = s.exact_perimeter();
        let lines = extract_zero_level(mesh, u)?;
        hausdorff = Some(interface_distance(&lines, s, 8).hausdorff);
    }
    Ok(MeshReport {
        vertices: mesh.n_points(),
        triangles: mesh.n_live_tris(),
        edge_length_in_range: q.edge_length_in_range,
        q_ani_mean: q.q_ani_mean,
        q_ani_max: q.q_ani_max,
        area,
        perimeter,
        exact_area,
        exact_perimeter,
        area_rel_error: exact_area.map(|a| (area - a).abs() / a),
        hausdorff,
        seconds: 0.0,
        phases: Vec::new(),
    })
}
