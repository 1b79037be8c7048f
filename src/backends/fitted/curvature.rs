//! Curvature of the level sets of a P1 function by local averaging (001 (5.2)): at a vertex `v`
//! with patch `ω` (its triangles) and hat function `N_v`,
//! `κ_h(v) = -∫_ω (∇φ_h/|∇φ_h|)·∇N_v dx / ∫_ω N_v dx`, which on a uniform right-triangle grid is
//! `-(1/h²) ∫_ω (∇φ_h/|∇φ_h|)·∇N_v dx` and second-order accurate (001 §5). Only the unit normal
//! enters, so the result does not depend on the level set's normalisation.
//!
//! The formula is bounded: `|κ_h(v)| <= ∫_ω |∇N_v| / ∫_ω N_v` (001 §5 bounds it by `3√2/h` on
//! the uniform grid; it is `(2 + √2)/h` on the right-diagonal grid), reached when every
//! triangle's normal is parallel to `∇N_v`. Values within 1e-9 of the bound are counted as "at
//! the limit": there the grid cannot resolve the curvature.
//! Boundary vertices (where the patch is not closed and the formula misses its boundary term)
//! get no value.

use crate::error::Result;
use crate::geom::simplex::p1_gradients;
use crate::mesh::{check_p1_field, Mesh2, NONE};

/// Vertex curvatures of the level sets of a P1 function.
#[derive(Debug, Clone)]
pub struct VertexCurvature {
    /// `κ_h` per vertex (001 (5.2)); `None` on the boundary, at isolated vertices and where the
    /// gradient vanishes on the whole patch.
    pub kappa: Vec<Option<f64>>,
    /// The bound `∫_ω |∇N_v| / ∫_ω N_v` per vertex (0 where there is no value).
    pub limit: Vec<f64>,
    /// Number of vertices whose `|κ_h|` reaches the bound (within 1e-9 relative).
    pub at_limit: usize,
}

/// The local-averaging curvature 001 (5.2) at every interior vertex of `mesh` for the P1
/// function `phi`. Errors on a field of the wrong length or with non-finite values.
pub fn vertex_curvature(mesh: &Mesh2, phi: &[f64]) -> Result<VertexCurvature> {
    check_p1_field(mesh.n_points(), phi, "level set")?;
    let n = mesh.n_points();
    let mut num = vec![0.0; n];
    let mut mass = vec![0.0; n];
    let mut lim = vec![0.0; n];
    let mut boundary = vec![false; n];
    let mut flat = vec![true; n];
    for t in mesh.live_tris() {
        let tri = mesh.tris[t];
        let p = mesh.tri_points(t);
        let g = p1_gradients(&p);
        let f = tri.map(|v| phi[v as usize]);
        let grad = g[0] * f[0] + g[1] * f[1] + g[2] * f[2];
        let len = grad.length();
        let area = mesh.tri_area(t);
        for i in 0..3 {
            let v = tri[i] as usize;
            mass[v] += area / 3.0;
            lim[v] += area * g[i].length();
            if len > 0.0 {
                num[v] -= area * (grad / len).dot(g[i]);
                flat[v] = false;
            }
            let [a, b] = mesh.edge_vertices(t, i);
            if mesh.neighbours[t][i] == NONE {
                boundary[a as usize] = true;
                boundary[b as usize] = true;
            }
        }
    }
    let mut at_limit = 0;
    let mut kappa = vec![None; n];
    for v in 0..n {
        if boundary[v] || flat[v] || mass[v] == 0.0 {
            lim[v] = 0.0;
            continue;
        }
        let k = num[v] / mass[v];
        lim[v] /= mass[v];
        if k.abs() >= lim[v] * (1.0 - 1e-9) {
            at_limit += 1;
        }
        kappa[v] = Some(k);
    }
    Ok(VertexCurvature {
        kappa,
        limit: lim,
        at_limit,
    })
}

/// The curvature on the zero level of `phi` as 001 §5 measures it: the vertex curvatures of
/// [`vertex_curvature`] interpolated linearly onto the nodes of the fitted interface (the
/// points where the zero level crosses the edges of `mesh`, and the vertices it passes
/// through). Returns the nodes, their curvatures and the number of base vertices used there
/// (the ends of the cut edges and the vertices on the level) whose `|κ_h|` reaches the bound
/// `∫_ω |∇N_v| / ∫_ω N_v` (001 §5: `3√2/h` on the uniform grid): the curvature of the zero
/// level is then not resolved by the grid and the samples are capped.
///
/// Errors: those of [`vertex_curvature`] and [`super::fit`]; an interface that reaches the
/// boundary, where vertex curvatures are not defined ([`crate::Error::InvalidInput`]).
pub fn interface_curvature(
    mesh: &Mesh2,
    phi: &[f64],
) -> Result<(Vec<crate::geom::DVec2>, Vec<f64>, usize)> {
    let k = vertex_curvature(mesh, phi)?;
    let fitted = super::fit(mesh, phi, &super::FitOptions::default())?;
    let value = |v: usize| -> Result<f64> {
        let at = |b: usize| {
            k.kappa[b].ok_or_else(|| {
                crate::Error::InvalidInput(format!(
                    "interface curvature: the zero level reaches the boundary vertex {b}, where \
                     001 (5.2) has no value"
                ))
            })
        };
        if v < fitted.n_base_vertices {
            at(v)
        } else {
            let ([a, b], s) = fitted.cuts[v - fitted.n_base_vertices];
            Ok((1.0 - s) * at(a as usize)? + s * at(b as usize)?)
        }
    };
    let mut nodes: Vec<u32> = fitted.interface_edges().into_iter().flatten().collect();
    nodes.sort_unstable();
    nodes.dedup();
    let points = nodes
        .iter()
        .map(|&v| fitted.mesh.points[v as usize])
        .collect();
    let values = nodes
        .iter()
        .map(|&v| value(v as usize))
        .collect::<Result<Vec<f64>>>()?;
    let mut used: Vec<usize> = nodes
        .iter()
        .flat_map(|&v| {
            let v = v as usize;
            if v < fitted.n_base_vertices {
                [v, v]
            } else {
                fitted.cuts[v - fitted.n_base_vertices]
                    .0
                    .map(|x| x as usize)
            }
        })
        .collect();
    used.sort_unstable();
    used.dedup();
    let at_limit = used
        .iter()
        .filter(|&&v| k.kappa[v].is_some_and(|kv| kv.abs() >= k.limit[v] * (1.0 - 1e-9)))
        .count();
    Ok((points, values, at_limit))
}
