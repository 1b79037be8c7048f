//! Conformity statistics of a tetrahedral mesh to a vertex metric, as the UGAWG study reports
//! them: edge lengths in the metric (the fraction in `[1/√2, √2]`) and the mean-ratio quality
//! of the tetrahedra (worst and mean; 1 = regular in the metric).

use serde::Serialize;

use super::mean_ratio;
use crate::mesh3::Mesh3;
use crate::metric::length::{L_MAX, L_MIN};
use crate::metric::Sym3;

/// Edge-length and quality statistics of a tetrahedral mesh in a metric.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TetStats {
    /// Number of edges.
    pub edges: usize,
    /// Fraction of edges with metric length in `[1/√2, √2]`.
    pub edge_length_in_range: f64,
    /// Shortest and longest metric edge length.
    pub length_min: f64,
    /// Longest metric edge length.
    pub length_max: f64,
    /// Worst mean-ratio quality (1 = regular tetrahedron of the metric).
    pub quality_min: f64,
    /// Mean of the mean-ratio quality.
    pub quality_mean: f64,
}

/// [`TetStats`] of `mesh` in the vertex metric `metric` (one tensor per vertex); edge lengths
/// with the geometric interpolation of the length density ([`crate::metric::edge_length`]),
/// quality in the arithmetic mean of the four vertex metrics.
pub fn tet_stats(mesh: &Mesh3, metric: &[Sym3]) -> TetStats {
    let (off, adj) = mesh.v2v();
    let (mut n, mut inr) = (0usize, 0usize);
    let (mut lmin, mut lmax) = (f64::INFINITY, 0.0f64);
    for a in 0..mesh.n_points() {
        for &b in &adj[off[a]..off[a + 1]] {
            if (b as usize) <= a {
                continue;
            }
            let l = crate::metric::edge_length(
                mesh.points[a],
                mesh.points[b as usize],
                &metric[a],
                &metric[b as usize],
            );
            n += 1;
            if (L_MIN..=L_MAX).contains(&l) {
                inr += 1;
            }
            lmin = lmin.min(l);
            lmax = lmax.max(l);
        }
    }
    let (mut qmin, mut qsum) = (f64::INFINITY, 0.0);
    for t in 0..mesh.n_tets() {
        let m = mesh.tets[t].map(|v| metric[v as usize]);
        let q = mean_ratio(mesh.tet_points(t), &m);
        qmin = qmin.min(q);
        qsum += q;
    }
    TetStats {
        edges: n,
        edge_length_in_range: inr as f64 / n.max(1) as f64,
        length_min: lmin,
        length_max: lmax,
        quality_min: qmin,
        quality_mean: qsum / mesh.n_tets().max(1) as f64,
    }
}
