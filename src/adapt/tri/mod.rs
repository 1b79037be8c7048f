//! The triangle operators (004 §3.5) on [`crate::mesh::Mesh2`]: the operator context and its
//! per-pass workspace, and one file per operator, each with a pure `check` that returns the
//! planned change from metric and quality and an `apply` that calls the topology edits of
//! [`crate::mesh`]:
//! - `topo.rs`: the operator context [`Ctx`] (mesh, metric, fields, source, parameters), its
//!   metric and quality queries and the vertex classes (free / on a labelled curve / fixed);
//!   `workspace.rs`: the per-pass workspace, which hears the mesh edits through
//!   [`crate::mesh::EditListener`]; `kernel.rs`: the metric quantities the checks evaluate.
//! - `split.rs` (split edge), `insert.rs` (fill a Delaunay cavity), `collapse.rs` (collapse
//!   edge), `flip.rs` (flip edge), `smooth.rs` (move vertex). `refine.rs` is the refinement
//!   operator that picks long edges and chooses between a split and an insertion.
//!
//! Refinement, collapse, flip and smoothing implement [`crate::adapt::pass::Operator`] for
//! [`Ctx`], and [`Ctx`] implements [`crate::adapt::cycle::Remesher`], so the shared pass
//! skeleton and adaptation cycle drive them.

pub(crate) mod kernel;
pub(crate) mod topo;
pub(crate) mod workspace;

pub(crate) mod collapse;
pub(crate) mod flip;
pub(crate) mod insert;
pub(crate) mod refine;
pub(crate) mod smooth;
pub(crate) mod split;

pub(crate) use topo::Ctx;

use super::cycle::Remesher;
use super::options::PassKind;
use crate::error::Result;
use crate::mesh::{Mesh2, NONE};
use crate::metric::Sym2;
use workspace::scatter;

impl Remesher for Ctx<'_> {
    fn n_vertices(&self) -> usize {
        self.mesh.n_points()
    }

    fn run_pass(&mut self, kind: PassKind) -> usize {
        match kind {
            PassKind::Split => refine::pass(self),
            PassKind::Collapse => collapse::pass(self),
            PassKind::Flip => flip::pass(self),
            PassKind::Smooth => smooth::pass(self),
        }
    }

    fn renumber(&mut self) {
        self.renumber_spatially();
    }

    fn grade(&mut self, beta: f64) -> Result<()> {
        grade_metric(self, beta)
    }

    fn smoothing_settled(&mut self) {
        Ctx::smoothing_settled(self);
    }

    fn check(&self) -> Result<()> {
        self.mesh.check()
    }
}

/// Grades the vertex metric over the current mesh ([`crate::metric::gradate`]) and marks the
/// triangles around every vertex whose metric changed as modified, so that the passes examine
/// them again (cached qualities forgotten, edges re-measured).
fn grade_metric(ctx: &mut Ctx, beta: f64) -> Result<()> {
    let before = ctx.metric.clone();
    if crate::metric::gradate(ctx.mesh, ctx.metric, beta)? == 0 {
        return Ok(());
    }
    let changed: Vec<bool> = before
        .iter()
        .zip(ctx.metric.iter())
        .map(|(a, b)| a != b)
        .collect();
    if !ctx.fast_q {
        for (v, &c) in changed.iter().enumerate() {
            if c {
                ctx.logm[v] = ctx.metric[v].log();
            }
        }
    }
    ctx.new_pass();
    for t in 0..ctx.mesh.n_tris() {
        let tri = ctx.mesh.tris[t];
        if tri[0] != NONE && tri.iter().any(|&v| changed[v as usize]) {
            ctx.touch(t as u32);
        }
    }
    Ok(())
}

/// `Mesh2::compact` plus the same renumbering of the metric and the fields.
pub(crate) fn compact_with_data(mesh: &mut Mesh2, metric: &mut Vec<Sym2>, fields: &mut [Vec<f64>]) {
    let vmap = mesh.compact();
    let n = mesh.n_points();
    *metric = scatter(metric, &vmap, n, Sym2::IDENTITY);
    for f in fields.iter_mut() {
        *f = scatter(f, &vmap, n, 0.0);
    }
}
