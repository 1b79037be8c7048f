//! One characteristics-Galerkin step of a level set (004 eq. (2)).
//!
//! A circle of radius 0.3 centred at (0.5, 0) is rotated by a quarter turn about the origin,
//! `v = (-y, x)`: the new values are the old ones at the feet of the characteristics, traced
//! back with a second-order scheme and L2-projected onto the mesh. The enclosed area and the
//! position of the centre are compared with the exact ones.
//!
//! `cargo run --release --example advection_step`

use anisomesh::advect::{self, AdvectOptions, Rotation};
use anisomesh::levelset::enclosed_area;
use anisomesh::prelude::*;
use std::f64::consts::FRAC_PI_2;

fn main() -> anisomesh::Result<()> {
    let mesh = Mesh2::rectangle(
        DVec2::splat(-1.0),
        DVec2::splat(1.0),
        200,
        200,
        GridPattern::UnionJack,
    )?;
    let centre = DVec2::new(0.5, 0.0);
    let u0: Vec<f64> = mesh
        .points
        .iter()
        .map(|&p| (p - centre).length() - 0.3)
        .collect();
    let rotation = Rotation { omega: 1.0 };
    let opts = AdvectOptions::default();
    let u1 = advect::advect(&mesh, &u0, &mesh, &rotation, 0.0, FRAC_PI_2, &opts)?;
    let exact = std::f64::consts::PI * 0.09;
    let (a0, a1) = (enclosed_area(&mesh, &u0)?, enclosed_area(&mesh, &u1)?);
    // The new centre: the vertex of smallest value (the circle's centre after the turn).
    let (i, _) = u1.iter().enumerate().fold(
        (0, f64::INFINITY),
        |b, (i, &v)| if v < b.1 { (i, v) } else { b },
    );
    println!(
        "area {a0:.6} -> {a1:.6} (exact {exact:.6}); centre now near ({:.3}, {:.3}), exact (0, 0.5)",
        mesh.points[i].x, mesh.points[i].y
    );
    Ok(())
}
