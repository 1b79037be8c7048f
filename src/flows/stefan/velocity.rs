//! The Stefan condition `v_n = −[∂T/∂n]` (001 (6.4)) at the interface vertices of a fitted mesh.

use crate::error::{Error, Result};
use crate::geom::{simplex, DVec2};
use crate::mesh::{check_p1_field, Mesh2};

/// The normal velocity `v_n = −(∂T/∂n|₊ − ∂T/∂n|₋)` at every interface vertex (0 elsewhere), with
/// `n = normals[v]` the unit normal pointing out of the solid (`Ω−`, the triangles labelled
/// `inside_label`) into the liquid (`Ω+`, every other label).
///
/// On each side the gradient at a vertex is the area-weighted mean of the P1 gradients of that
/// side's triangles around it, first-order accurate like the P1 gradient itself (001 §6). A
/// vertex with triangles on one side only (the interface meeting the outer boundary) takes the
/// missing side's gradient as zero (the insulated solid).
///
/// Errors: sizes that do not match the mesh, non-finite temperatures, a normal that is not unit
/// length at an interface vertex.
pub fn stefan_velocity(
    mesh: &Mesh2,
    inside_label: i32,
    on_interface: &[bool],
    normals: &[DVec2],
    temperature: &[f64],
) -> Result<Vec<f64>> {
    let n = mesh.n_points();
    check_velocity_inputs(n, on_interface, normals, temperature)?;
    // Per vertex and side: Σ area · ∇T and Σ area.
    let mut grad = vec![[DVec2::ZERO; 2]; n];
    let mut area = vec![[0.0f64; 2]; n];
    for t in mesh.live_tris() {
        let tri = mesh.tris[t];
        if !tri.iter().any(|&v| on_interface[v as usize]) {
            continue;
        }
        let p = mesh.tri_points(t);
        let f = tri.map(|v| temperature[v as usize]);
        let g = simplex::p1_gradient(&p, &f);
        let a = mesh.tri_area(t).abs();
        let side = usize::from(mesh.tri_ref[t] != inside_label);
        for &v in &tri {
            let v = v as usize;
            if on_interface[v] {
                grad[v][side] += a * g;
                area[v][side] += a;
            }
        }
    }
    Ok((0..n)
        .map(|v| {
            if !on_interface[v] {
                return 0.0;
            }
            let mean = |s: usize| {
                if area[v][s] > 0.0 {
                    grad[v][s] / area[v][s]
                } else {
                    DVec2::ZERO
                }
            };
            -(mean(1) - mean(0)).dot(normals[v])
        })
        .collect())
}

/// The checks shared by the Stefan velocity reconstructions: a temperature, an interface mask and
/// normals with one entry per vertex, finite temperatures, unit normals at interface vertices.
pub(crate) fn check_velocity_inputs(
    n: usize,
    on_interface: &[bool],
    normals: &[DVec2],
    temperature: &[f64],
) -> Result<()> {
    check_p1_field(n, temperature, "temperature")?;
    if on_interface.len() != n || normals.len() != n {
        return Err(Error::InvalidInput(format!(
            "Stefan velocity: the mesh has {n} vertices but the interface mask and normals have {} and {}",
            on_interface.len(),
            normals.len()
        )));
    }
    if let Some(v) = (0..n).find(|&v| {
        on_interface[v] && ((normals[v].length() - 1.0).abs() >= 1e-6 || normals[v].is_nan())
    }) {
        return Err(Error::InvalidInput(format!(
            "Stefan velocity: the normal at interface vertex {v} is not a unit vector ({})",
            normals[v]
        )));
    }
    Ok(())
}
