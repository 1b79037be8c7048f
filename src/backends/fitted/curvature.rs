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

use super::fit::FittedMesh;
use crate::error::Result;
use crate::geom::simplex::{p1_gradient, p1_gradients};
use crate::geom::DVec2;
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

/// The outward unit normals `∇u/|∇u|` of the fitted level set at the vertices flagged `on`
/// (zero elsewhere): the area-weighted mean of the P1 gradients of the triangles around each
/// vertex; where they cancel (a symmetric pinch), `(1, 0)`.
pub(crate) fn vertex_normals(fm: &FittedMesh, on: &[bool]) -> Vec<DVec2> {
    let m = &fm.mesh;
    let mut g = vec![DVec2::ZERO; m.n_points()];
    for t in m.live_tris() {
        let tri = m.tris[t];
        if !tri.iter().any(|&v| on[v as usize]) {
            continue;
        }
        let p = m.tri_points(t);
        let f = tri.map(|v| fm.u[v as usize]);
        let gt = p1_gradient(&p, &f) * m.tri_area(t).abs();
        for &v in &tri {
            if on[v as usize] {
                g[v as usize] += gt;
            }
        }
    }
    g.into_iter()
        .map(|x| {
            let n = x / x.length();
            if n.is_finite() && (n.length() - 1.0).abs() < 1e-9 {
                n
            } else {
                DVec2::new(1.0, 0.0)
            }
        })
        .collect()
}

/// Curvature of the fitted interface itself, for every vertex of `fm.mesh` on it (0 at the
/// other vertices): at an interface vertex `p₀` with outward normal `n` (the area-weighted
/// mean of the P1 gradients of `fm.u` around it) and tangent `t`, the interface vertices reachable from `p₀` along the interface polyline within
/// the arc length `half_width` are written as `(x, y) = ((p − p₀)·t, (p − p₀)·n)`, the
/// parabola `y = a + b x + c x²` is fitted to them by least squares (weights `1 − s/half_width`
/// by arc length `s`, `p₀` weight 1) and `κ = −2c / (1 + b²)^{3/2}` (positive where the
/// inside is convex, the sign of 001 (5.2)). With fewer than four points or a degenerate fit,
/// the vertex gets 0.
///
/// Unlike the local-averaging curvature 001 (5.2) interpolated onto the cut points, this does
/// not differentiate the level set twice across one cell: a fit over a few cells averages out
/// the grid-scale scatter of the P1 zero level (cut points of a redistanced level set, whose
/// second differences divided by `h²` give the scatter of (5.2)). On a smooth curve the fit's
/// error is `O(half_width²)`: with `half_width` a fixed multiple of `h`, second order.
///
/// Errors: `half_width` not finite and positive ([`crate::Error::InvalidInput`]).
pub fn interface_fit_curvature(fm: &FittedMesh, half_width: f64) -> Result<Vec<f64>> {
    if !(half_width.is_finite() && half_width > 0.0) {
        return Err(crate::Error::InvalidInput(format!(
            "interface curvature: the fitting half-width must be finite and positive (got \
             {half_width})"
        )));
    }
    let m = &fm.mesh;
    let n = m.n_points();
    let mut adj: Vec<Vec<u32>> = vec![Vec::new(); n];
    for [a, b] in fm.interface_edges() {
        adj[a as usize].push(b);
        adj[b as usize].push(a);
    }
    let on: Vec<bool> = adj.iter().map(|a| !a.is_empty()).collect();
    let normals = vertex_normals(fm, &on);
    let mut kappa = vec![0.0; n];
    // Reused per vertex: (vertex, arc length) of the reached vertices.
    let mut reached: Vec<(usize, f64)> = Vec::new();
    for v in 0..n {
        if !on[v] {
            continue;
        }
        // Walk along the polyline (a breadth-first search by arc length; a vertex is kept at its
        // first, shortest, arrival since the polyline has no short cycles within half_width).
        reached.clear();
        reached.push((v, 0.0));
        let mut head = 0;
        while head < reached.len() {
            let (w, s) = reached[head];
            head += 1;
            for &x in &adj[w] {
                let x = x as usize;
                let s2 = s + (m.points[x] - m.points[w]).length();
                if s2 <= half_width && !reached.iter().any(|&(r, _)| r == x) {
                    reached.push((x, s2));
                }
            }
        }
        if reached.len() < 4 {
            continue;
        }
        let nv = normals[v];
        let tv = DVec2::new(-nv.y, nv.x);
        let p0 = m.points[v];
        // Normal equations of the weighted fit of (1, x, x²) to y.
        let mut a = [[0.0f64; 3]; 3];
        let mut r = [0.0f64; 3];
        for &(w, s) in &reached {
            let d = m.points[w] - p0;
            let (x, y) = (d.dot(tv), d.dot(nv));
            let wt = if w == v { 1.0 } else { 1.0 - s / half_width };
            let phi = [1.0, x, x * x];
            for i in 0..3 {
                r[i] += wt * phi[i] * y;
                for j in 0..3 {
                    a[i][j] += wt * phi[i] * phi[j];
                }
            }
        }
        if let Some([_, b, c]) = solve3(a, r) {
            let k = -2.0 * c / (1.0 + b * b).powf(1.5);
            if k.is_finite() {
                kappa[v] = k;
            }
        }
    }
    Ok(kappa)
}

/// Solves a symmetric 3×3 system by Cramer's rule; `None` if it is (nearly) singular.
fn solve3(a: [[f64; 3]; 3], r: [f64; 3]) -> Option<[f64; 3]> {
    let det = |m: &[[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(&a);
    let scale = a[0][0] * a[1][1] * a[2][2];
    if d.is_nan() || d.abs() <= 1e-12 * scale.abs() {
        return None;
    }
    let mut out = [0.0; 3];
    for (k, o) in out.iter_mut().enumerate() {
        let mut ak = a;
        for i in 0..3 {
            ak[i][k] = r[i];
        }
        *o = det(&ak) / d;
    }
    Some(out)
}
