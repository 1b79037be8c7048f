//! Adapt a mesh to a metric field read from a file, as `mmg2d -in M.mesh -sol S.sol` does.
//!
//! `meshes/square.mesh` carries, in `meshes/square_metric.sol`, one symmetric tensor per vertex
//! (Medit type 3). The adapted mesh has edges of unit length in that metric (between `1/√2` and
//! `√2`) and elements of `Q_ani` close to 1 (004 §3.4); sizes between the given vertices vary
//! linearly, as in MMG.
//!
//! `cargo run --release --example adapt_metric_file`

use anisomesh::io::{self, SolField};
use anisomesh::prelude::*;
use std::path::Path;

fn main() -> anisomesh::Result<()> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("meshes");
    let mesh = io::read_mesh(&dir.join("square.mesh"))?;
    let sol = io::read_sol_for(&dir.join("square_metric.sol"), mesh.n_points())?;
    let Some(SolField::Tensor2(metric)) = sol.fields.into_iter().next() else {
        return Err(Error::InvalidInput("expected a metric field".into()));
    };
    println!("input: {} vertices", mesh.n_points());
    let out = adapt::run(AdaptTarget::Metric { mesh, metric }, &RunOptions::default())?;
    let r = &out.report;
    println!(
        "adapted: {} vertices (estimated {:.0}), {:.1}% of edges in [1/√2, √2], Q_ani mean {:.3} \
         max {:.2}, converged {}",
        r.mesh.vertices,
        r.estimated_vertices,
        100.0 * r.mesh.edge_length_in_range,
        r.mesh.q_ani_mean,
        r.mesh.q_ani_max,
        r.converged
    );
    out.mesh.check()?;
    Ok(())
}
