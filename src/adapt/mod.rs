//! Anisotropic mesh adaptation: metric-driven split, collapse, flip, smoothing and Delaunay
//! insertion on [`crate::mesh::Mesh2`] (004 §3.5), the driver that alternates them, metric
//! sources (004 eq. (6), multiscale Lp) and the shape-capturing loop.
//!
//! Layout (one concept per file, MMG/Omega_h style), dimension-free first:
//! - `pass.rs`: the pass skeleton every operator shares (sites, survey on the state at the
//!   start of the pass, in parallel when worth it, order, visit: independent set, re-check where
//!   the surroundings changed, apply, count) and the `Operator` trait an operator implements.
//! - `cycle.rs`: the adaptation cycle (refine and flip until no split, collapse, flip, smooth,
//!   convergence test, final sweeps, renumbering, gradation), written against the `Remesher`
//!   trait a mesh context of any dimension implements; `params.rs`: the operator parameters.
//! - `tri/`: the triangle operators on [`crate::mesh::Mesh2`]: the context and its workspace
//!   (`topo.rs`, `workspace.rs`, `kernel.rs`) and one file per operator (`split.rs`,
//!   `insert.rs`, `refine.rs`, `collapse.rs`, `flip.rs`, `smooth.rs`), each with a pure
//!   `check` that returns the planned change from metric and quality and an `apply` that calls
//!   the topology edits of [`crate::mesh`].
//! - `tet/`: the tetrahedral operators on [`crate::mesh3::EditMesh3`] (split, collapse, edge
//!   removal and face swaps, smoothing) with their context implementing the same `Remesher`,
//!   and the 3D fixed point [`run3`] with [`tet_stats`].
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

mod cycle;
mod params;
mod pass;
mod tet;
mod tri;

mod discrete;
mod driver;
pub mod estimate;
pub mod features;
mod files3;
mod options;
mod report;
mod run;
mod shape;
pub mod sources;

pub use driver::{
    adapt, validate_inputs, AdaptOptions, AdaptReport, CycleSmoothing, PassKind, PassReport,
};
pub use files3::{
    run3_graded, run3_to_field, shape_metric3, DiscreteLevelSet3, FieldInterpolation3,
    MetricField3, GRADED_ROUNDS,
};
pub use params::MetricInterpolation;
pub use report::{mesh_report, MeshReport};
pub use run::{
    final_metric, level_set_metric, metric_file_options, run, AdaptTarget, Adapted, RunOptions,
    RunReport, DEFAULT_MAX_VERTICES,
};
pub use shape::{adapt_mesh_to_shape, adapt_to_shape, ShapeAdaptOptions};
pub use sources::{AnalyticLevelSetSource, HessianMetric, LevelSetMetric, MetricSource, NoSource};
pub use tet::run::{
    level_set_metric3, run3, Adapted3, Continuation3, Report3, Run3Options, Stage3, Target3,
};
pub use tet::stats::{tet_stats, TetStats};
pub use tet::{mean_ratio, MetricFn3};

#[cfg(test)]
mod tests;
