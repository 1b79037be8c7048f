//! Metric complexity and the vertex count it predicts (continuous-mesh model, Loseille & Alauzet
//! 2011; 004 §3.3).
//!
//! The complexity of a metric field on `Ω` is
//!
//! ```text
//! C(M) = ∫_Ω sqrt(det M(x)) dx,
//! ```
//!
//! the area of `Ω` measured in the metric. Here `sqrt(det M)` is interpolated P1 from the vertex
//! values and integrated exactly: `C = Σ_K |K| (d_a + d_b + d_c) / 3`, `d_v = sqrt(det M_v)`. (The
//! element-wise log-Euclidean mean would give the geometric mean `(d_a d_b d_c)^{1/3}` instead; the
//! two agree to second order for smooth fields. Both scale linearly, `C(s M) = s C(M)`, which is
//! what the normalisation of [`super::multiscale_lp`] relies on.)
//!
//! **Predicted vertex count.** 004 §3.3 asks every element to have unit volume in the metric, and
//! a unit mesh is made of equilateral triangles of unit edge length in `M_K`, whose metric area is
//! `|K| sqrt(det M_K) = sqrt(3)/4`. So a unit mesh has `N_T ≈ C / (sqrt(3)/4) = 4 C / sqrt(3)`
//! triangles, and since a planar triangulation has `N_T = 2 N_V - N_B - 2 ≈ 2 N_V` (Euler's
//! formula, `N_B` boundary vertices), `N_V ≈ 2 C / sqrt(3) ≈ 1.1547 C`.

use super::Sym2;
use crate::mesh::Mesh2;

/// `2 / sqrt(3)`: vertices per unit of complexity in a unit mesh (module documentation).
pub const VERTICES_PER_COMPLEXITY: f64 = 1.154_700_538_379_251_7;

/// `C(M) = ∫ sqrt(det M)` over the live triangles of `mesh`, with `sqrt(det M)` interpolated P1
/// from the vertex metrics. Triangles touching a vertex without a metric entry are skipped
/// (check the field with [`super::validate_field`] first).
pub fn complexity(mesh: &Mesh2, metric: &[Sym2]) -> f64 {
    let d: Vec<f64> = metric.iter().map(|m| m.det().max(0.0).sqrt()).collect();
    complexity_of_density(mesh, &d)
}

/// `Σ_K |K| (d_a + d_b + d_c) / 3`: the integral of a P1 field `d`.
pub(crate) fn complexity_of_density(mesh: &Mesh2, d: &[f64]) -> f64 {
    mesh.live_tris()
        .filter_map(|t| {
            let [a, b, c] = mesh.tris[t].map(|v| v as usize);
            if a.max(b).max(c) >= d.len() {
                return None;
            }
            Some(mesh.tri_area(t) * (d[a] + d[b] + d[c]) / 3.0)
        })
        .sum()
}

/// Vertex count of a unit mesh of complexity `c`: `2 c / sqrt(3)` (module documentation).
#[inline]
pub fn predicted_vertices(c: f64) -> f64 {
    VERTICES_PER_COMPLEXITY * c
}

/// Triangle count of a unit mesh of complexity `c`: `4 c / sqrt(3)`.
#[inline]
pub fn predicted_triangles(c: f64) -> f64 {
    2.0 * VERTICES_PER_COMPLEXITY * c
}

/// The complexity whose unit mesh has `n` vertices: `sqrt(3) n / 2`.
#[inline]
pub fn complexity_for_vertices(n: f64) -> f64 {
    n / VERTICES_PER_COMPLEXITY
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::DVec2;
    use crate::mesh::GridPattern;

    #[test]
    fn constant() {
        assert!((VERTICES_PER_COMPLEXITY - 2.0 / 3f64.sqrt()).abs() < 1e-15);
    }

    #[test]
    fn isotropic_complexity_is_area_over_h2() {
        let mesh = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 7, 5, GridPattern::UnionJack).unwrap();
        for h in [0.1, 0.02, 0.003] {
            let c = complexity(&mesh, &vec![Sym2::iso(h); mesh.n_points()]);
            assert!((c * h * h - 1.0).abs() < 1e-12, "h = {h}: C = {c}");
        }
        // A linear density is integrated exactly.
        let d: Vec<f64> = mesh.points.iter().map(|p| 1.0 + 2.0 * p.x + p.y).collect();
        assert!((complexity_of_density(&mesh, &d) - 2.5).abs() < 1e-12);
    }

    #[test]
    fn predicted_count_matches_a_unit_grid() {
        // The "Right" grid of spacing h is a unit mesh of M = [[1, -1/2], [-1/2, 1]] / h²
        // (|(h,0)| = |(0,h)| = |(h,h)| = 1); C = sqrt(3)/(2h²), predicted N = 1/h².
        for n in [10usize, 40, 100] {
            let h = 1.0 / n as f64;
            let mesh = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, n, n, GridPattern::Right).unwrap();
            let m = Sym2::new(1.0, -0.5, 1.0).scale(1.0 / (h * h));
            let c = complexity(&mesh, &vec![m; mesh.n_points()]);
            let pred = predicted_vertices(c);
            let actual = mesh.n_points() as f64;
            // Boundary vertices make up the difference: (n+1)² vs n².
            assert!(
                (pred / actual - 1.0).abs() < 2.5 / n as f64,
                "n = {n}: {pred} vs {actual}"
            );
            assert!((predicted_triangles(c) / mesh.n_tris() as f64 - 1.0).abs() < 1e-12);
        }
    }
}
