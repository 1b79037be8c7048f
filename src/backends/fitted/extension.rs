//! Extension of the normal velocity off the interface (001 §3): on the interface-fitted mesh,
//! `u = v_n` at the interface vertices (3.3), `Δu = 0` on both sides (3.1)–(3.2) with
//! `∂u/∂n = 0` on the outer boundary (3.5), and, for the least-squares extension, the jump of
//! the normal derivative across every interface edge set to zero (3.4).
//!
//! **Least squares** (001 (3.6)–(3.9)): the unknowns are the values at the vertices that are not
//! on the interface. Each unknown contributes its row of the P1 Galerkin system of its side
//! ((3.7) in `Ω−`, (3.8) in `Ω+`; the interface values move to the right-hand side, the natural
//! condition (3.5) is built in), and each interface edge `γ` contributes the row (3.9),
//! `∇u_h|T−·∇N⁻/|∇N⁻| + ∇u_h|T+·∇N⁺/|∇N⁺| = 0` with `T±` the triangles on the two sides of `γ`
//! and `N±` the hat functions of their vertices off `γ`. The overdetermined system `A U = F` is
//! solved through its normal equations `AᵀA U = AᵀF` by a sparse Cholesky factorisation (faer,
//! AMD ordering). The rows are not weighted, as in 001: a Galerkin row scales like 1, a jump row
//! like `1/h`.
//!
//! **Harmonic** (for comparison, 001's first system): the Galerkin rows alone, a square SPD
//! system. Its extension is continuous but kinked across `Γ`, so after unrefinement (the
//! interface vertices dropped, 001 Fig. 3.1) the interpolated velocity on `Γ` is off by `O(h)`;
//! the least-squares extension is smooth across `Γ` and keeps it to `O(h²)`.
//!
//! **Region.** The system is posed on the whole fitted mesh, or on the triangles within a band
//! `|u| <= w` of the interface (a vertex of such a triangle is in the band), with the natural
//! condition (3.5) on the band's edges; vertices outside get 0.

use super::fit::{FittedMesh, REF_INSIDE, REF_INTERFACE};
use crate::error::{Error, Result};
use crate::fem::solve::Cholesky;
use crate::fem::Csr;
use crate::geom::simplex::p1_gradients;
use crate::mesh::{check_p1_field, Mesh2, NONE};

/// Which extension of 001 §3.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ExtensionKind {
    /// Harmonic on each side (3.1)–(3.3), (3.5): continuous, kinked across the interface.
    Harmonic,
    /// Least squares of (3.1)–(3.5) with the gradient-jump rows (3.9): smooth across it.
    #[default]
    LeastSquares,
}

/// Options of [`extend_velocity`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ExtensionOptions {
    /// The system solved.
    pub kind: ExtensionKind,
    /// Pose the system on the triangles with a vertex within `|u| <= w` of the interface
    /// (`u` the fitted level set) instead of the whole mesh.
    pub band: Option<f64>,
}

/// The extended velocity and what the solve did.
#[derive(Debug, Clone)]
pub struct Extension {
    /// The extension at every fitted vertex (the given values at the known vertices, 0 outside
    /// the region).
    pub values: Vec<f64>,
    /// Vertices of the region the system was posed on.
    pub in_region: Vec<bool>,
    /// Number of unknowns.
    pub unknowns: usize,
    /// Number of gradient-jump rows (3.9) (0 for the harmonic extension).
    pub jump_rows: usize,
    /// Entries of the Cholesky factor.
    pub factor_nnz: usize,
}

/// The interface edges of `fm` with the triangles on their two sides: `(t_inside, i, t_outside)`
/// with `i` the local index of the edge in `t_inside`.
fn interface_edge_pairs(m: &Mesh2) -> Vec<(usize, usize, usize)> {
    let mut out = Vec::new();
    for t in m.live_tris() {
        if m.tri_ref[t] != REF_INSIDE {
            continue;
        }
        for i in 0..3 {
            let nb = m.neighbours[t][i];
            if m.edge_ref[t][i] == REF_INTERFACE && nb != NONE {
                out.push((t, i, nb as usize));
            }
        }
    }
    out
}

/// The coefficients of `∇u_h|T · ∇N_o/|∇N_o|` in the three vertex values of triangle `t`, with
/// `o` the vertex opposite the local edge `edge_opp` (001 (3.9): the derivative along the unit
/// normal of the edge pointing into `t`).
fn normal_derivative_row(m: &Mesh2, t: usize, opposite: usize) -> [f64; 3] {
    let g = p1_gradients(&m.tri_points(t));
    let n = g[opposite] / g[opposite].length();
    [g[0].dot(n), g[1].dot(n), g[2].dot(n)]
}

/// The residuals of the discrete gradient-jump condition (3.9) of the P1 field `u` on the
/// fitted mesh, one per interface edge: `∂u/∂n` from `Ω+` minus `∂u/∂n` from `Ω−` (`n` the edge
/// normal out of `Ω−`). Errors on a field of the wrong size or with non-finite values.
pub fn normal_derivative_jumps(m: &Mesh2, u: &[f64]) -> Result<Vec<f64>> {
    check_p1_field(m.n_points(), u, "field")?;
    Ok(interface_edge_pairs(m)
        .into_iter()
        .map(|(tm, i, tp)| {
            let [a, b] = m.edge_vertices(tm, i);
            let j = (0..3)
                .find(|&j| m.tris[tp][j] != a && m.tris[tp][j] != b)
                .unwrap_or(0);
            let rm = normal_derivative_row(m, tm, i);
            let rp = normal_derivative_row(m, tp, j);
            let dm: f64 = (0..3).map(|k| rm[k] * u[m.tris[tm][k] as usize]).sum();
            let dp: f64 = (0..3).map(|k| rp[k] * u[m.tris[tp][k] as usize]).sum();
            // `dm` is the derivative into Ω− (along −n), `dp` into Ω+ (along n).
            dp + dm
        })
        .collect())
}

/// Extends the values `v` given at the `known` vertices of the fitted mesh (at least every
/// vertex of the interface; further known vertices, e.g. Dirichlet values on the outer boundary,
/// are allowed) to the other vertices by the harmonic or the least-squares extension of 001 §3
/// (see the module documentation). `v` is read only where `known`.
///
/// Errors: sizes that do not match the mesh, a non-finite known value, an interface vertex not
/// marked known, a non-positive band, a singular system (a region with no known vertex).
pub fn extend_velocity(
    fm: &FittedMesh,
    v: &[f64],
    known: &[bool],
    opts: &ExtensionOptions,
) -> Result<Extension> {
    let m = &fm.mesh;
    let n = m.n_points();
    if v.len() != n || known.len() != n {
        return Err(Error::InvalidInput(format!(
            "velocity extension: the fitted mesh has {n} vertices but the values and the known \
             mask have {} and {}",
            v.len(),
            known.len()
        )));
    }
    if let Some(k) = (0..n).find(|&k| known[k] && !v[k].is_finite()) {
        return Err(Error::InvalidInput(format!(
            "velocity extension: the value at vertex {k} is not finite ({})",
            v[k]
        )));
    }
    if let Some(w) = opts.band {
        if !(w.is_finite() && w > 0.0) {
            return Err(Error::InvalidInput(format!(
                "velocity extension: the band must be finite and positive (got {w})"
            )));
        }
    }
    let pairs = interface_edge_pairs(m);
    for &(t, i, _) in &pairs {
        for a in m.edge_vertices(t, i) {
            if !known[a as usize] {
                return Err(Error::InvalidInput(format!(
                    "velocity extension: interface vertex {a} has no given value"
                )));
            }
        }
    }
    // The region: triangles with a vertex within the band.
    let tris: Vec<usize> = m
        .live_tris()
        .filter(|&t| match opts.band {
            None => true,
            Some(w) => m.tris[t].iter().any(|&a| fm.u[a as usize].abs() <= w),
        })
        .collect();
    let mut in_region = vec![false; n];
    for &t in &tris {
        for &a in &m.tris[t] {
            in_region[a as usize] = true;
        }
    }
    let mut index = vec![u32::MAX; n];
    let mut unknowns = 0usize;
    for k in 0..n {
        if in_region[k] && !known[k] {
            index[k] = unknowns as u32;
            unknowns += 1;
        }
    }
    let mut values: Vec<f64> = (0..n).map(|k| if known[k] { v[k] } else { 0.0 }).collect();
    if unknowns == 0 {
        return Ok(Extension {
            values,
            in_region,
            unknowns,
            jump_rows: 0,
            factor_nnz: 0,
        });
    }
    // Galerkin rows (3.7)–(3.8): K_UU U = −K_UΓ V.
    let mut kt: Vec<(u32, u32, f64)> = Vec::with_capacity(9 * tris.len());
    let mut f = vec![0.0; unknowns];
    for &t in &tris {
        let tri = m.tris[t];
        let g = p1_gradients(&m.tri_points(t));
        let area = m.tri_area(t).abs();
        for i in 0..3 {
            let r = index[tri[i] as usize];
            if r == u32::MAX {
                continue;
            }
            for j in 0..3 {
                let kij = area * g[i].dot(g[j]);
                let c = index[tri[j] as usize];
                if c == u32::MAX {
                    f[r as usize] -= kij * values[tri[j] as usize];
                } else {
                    kt.push((r, c, kij));
                }
            }
        }
    }
    let k = Csr::from_triplets(unknowns, &kt)?;
    let (matrix, mut rhs, jump_rows) = match opts.kind {
        ExtensionKind::Harmonic => (k, f, 0),
        ExtensionKind::LeastSquares => {
            // KᵀK (K is symmetric) and Kᵀf.
            let mut t2: Vec<(u32, u32, f64)> = Vec::new();
            let mut rhs = vec![0.0; unknowns];
            for (r, &fr) in f.iter().enumerate() {
                let span = k.row_ptr[r]..k.row_ptr[r + 1];
                for a in span.clone() {
                    let ca = k.col[a];
                    rhs[ca as usize] += k.val[a] * fr;
                    for b in span.clone() {
                        t2.push((ca, k.col[b], k.val[a] * k.val[b]));
                    }
                }
            }
            // Jump rows (3.9), one per interface edge inside the region.
            let mut rows = 0;
            for &(tm, i, tp) in &pairs {
                let [a, b] = m.edge_vertices(tm, i);
                let Some(j) = (0..3).find(|&j| m.tris[tp][j] != a && m.tris[tp][j] != b) else {
                    continue;
                };
                let mut entries: Vec<(u32, f64)> = Vec::with_capacity(2);
                let mut g = 0.0;
                for (t, opp) in [(tm, i), (tp, j)] {
                    let row = normal_derivative_row(m, t, opp);
                    for (q, &c) in row.iter().enumerate() {
                        let vtx = m.tris[t][q] as usize;
                        if index[vtx] == u32::MAX {
                            g -= c * values[vtx];
                        } else {
                            entries.push((index[vtx], c));
                        }
                    }
                }
                if entries.is_empty() {
                    continue;
                }
                rows += 1;
                for &(ra, ca) in &entries {
                    rhs[ra as usize] += ca * g;
                    for &(rb, cb) in &entries {
                        t2.push((ra, rb, ca * cb));
                    }
                }
            }
            (Csr::from_triplets(unknowns, &t2)?, rhs, rows)
        }
    };
    let chol = Cholesky::new(&matrix).map_err(|e| {
        Error::InvalidInput(format!(
            "velocity extension: the system is singular (a region without a known vertex?): {e}"
        ))
    })?;
    chol.solve_in_place(&mut rhs);
    for kx in 0..n {
        if index[kx] != u32::MAX {
            values[kx] = rhs[index[kx] as usize];
        }
    }
    Ok(Extension {
        values,
        in_region,
        unknowns,
        jump_rows,
        factor_nnz: chol.factor_nnz(),
    })
}
