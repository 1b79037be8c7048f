//! Anisotropic mesh adaptation: metric-driven split, collapse, flip, smoothing and Delaunay
//! insertion on [`crate::mesh::Mesh2`] (004 §3.5), the driver that alternates them, metric
//! sources (004 eq. (6), multiscale Lp) and the shape-capturing loop.
//!
//! Layout (one concept per file, MMG/Omega_h style):
//! - `topo.rs`: the operator context (mesh, metric, fields, source, parameters), its metric and
//!   quality queries and the vertex classes (free / on a labelled curve / fixed);
//!   `workspace.rs`: the per-pass workspace, which hears the mesh edits through
//!   [`crate::mesh::EditListener`].
//! - `kernel.rs`: the metric quantities the operators evaluate (edge length, `Q_ani`), thin
//!   wrappers over [`crate::metric`].
//! - `split.rs`, `insert.rs`, `collapse.rs`, `flip.rs`, `smooth.rs`: one operator each, with a
//!   pure `check` that returns the planned change from metric and quality, and an `apply` that
//!   calls the topology edits of [`crate::mesh`] (split edge, fill cavity, collapse edge, flip
//!   edge, move vertex). `refine.rs` is the pass that picks long edges and chooses between a
//!   split and an insertion; collapse, flip and smooth have their own `pass`. Each pass returns
//!   a count.
//! - `driver.rs`: [`adapt`], [`AdaptOptions`], [`AdaptReport`].
//! - `sources.rs`: [`MetricSource`] implementations and metric fields from level sets/Hessians.
//! - `shape.rs`: [`adapt_to_shape`]; `report.rs`: [`MeshReport`].
//!
//! Entry points (for the CLI):
//! - `anisomesh adapt` on a given mesh + metric (`.sol`): [`adapt`]`(&mut mesh, &mut metric,
//!   &mut fields, None, &AdaptOptions::default())`, then [`mesh_report`] (or
//!   `metric::quality_stats`) for the numbers; [`AdaptReport`] is `Serialize`.
//! - a metric from a P1 level set: [`LevelSetMetric::field_from_p1`]; from any P1 field with a
//!   target vertex count: [`HessianMetric::field`].
//! - an exact shape: [`adapt_to_shape`]`(&shape, (lo, hi), &ShapeAdaptOptions::default())`
//!   returns `(mesh, level set, report)`; then [`mesh_report`]`(&mesh, &metric, &u,
//!   Some(&shape))` with the metric from [`AnalyticLevelSetSource::evaluate`] (graded like the
//!   run) gives vertices, quality, area, perimeter and Hausdorff distance.
//!
//! Invariants kept by every operator: counter-clockwise triangles (exact `orient2d`), symmetric
//! `neighbours`, `edge_ref`, `vert_tri`, `corner`, `required`, `vert_ref`, `tri_ref`. Deleted
//! triangles are tombstones until [`crate::mesh::TriMesh::compact`] (the driver compacts at the
//! end, remapping the metric and the fields).

mod kernel;
mod topo;
mod workspace;

mod cycle;
mod pass;

mod collapse;
mod flip;
mod insert;
mod refine;
mod smooth;
mod split;

mod driver;
pub mod estimate;
pub mod features;
mod report;
mod run;
mod shape;
pub mod sources;

pub use driver::{
    adapt, validate_inputs, AdaptOptions, AdaptReport, CycleSmoothing, PassKind, PassReport,
};
pub use report::{mesh_report, MeshReport};
pub use run::{
    metric_file_options, run, AdaptTarget, Adapted, RunOptions, RunReport, DEFAULT_MAX_VERTICES,
};
pub use shape::{adapt_to_shape, ShapeAdaptOptions};
pub use sources::{AnalyticLevelSetSource, HessianMetric, LevelSetMetric, MetricSource, NoSource};
pub use topo::MetricInterpolation;

#[cfg(test)]
mod tests;
