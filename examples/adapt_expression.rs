//! Adapt a mesh to an implicit function given as an expression.
//!
//! The zero level of `sqrt(x² + y²) - 0.5` (a circle, negative inside) is meshed on `[-1, 1]²`
//! with the geometric metric of Ducrot & Frey (004 eq. (6)): sizes `hmin` across the interface,
//! `sqrt(ε / κ)` along it, growing away from it. The piecewise-linear zero level of the result
//! is within about `ε` of the circle.
//!
//! `cargo run --release --example adapt_expression`

use anisomesh::prelude::*;

fn main() -> anisomesh::Result<()> {
    let circle = Expr::parse("sqrt(x^2 + y^2) - 0.5")?;
    let domain = (DVec2::splat(-1.0), DVec2::splat(1.0));
    let out = adapt::run(AdaptTarget::shape(circle, domain), &RunOptions::default())?;
    let r = &out.report;
    println!(
        "{} vertices, {:.1}% of edges of unit length in the metric, mean Q_ani {:.3}",
        r.mesh.vertices,
        100.0 * r.mesh.edge_length_in_range,
        r.mesh.q_ani_mean
    );
    let exact = std::f64::consts::PI * 0.25;
    println!(
        "enclosed area {:.8} (exact {exact:.8}, relative error {:.1e})",
        r.mesh.area,
        (r.mesh.area - exact).abs() / exact
    );
    out.mesh.check()?;
    io::write_mesh(&std::env::temp_dir().join("circle.mesh"), &out.mesh)?;
    Ok(())
}
