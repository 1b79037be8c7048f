//! Metric intersection by simultaneous reduction of two quadratic forms (004 §3.5, after Frey &
//! George, reference 20 of 004).
//!
//! Given SPD `A` and `B`, the matrix `N = A^{-1} B` is diagonalisable with real positive
//! eigenvalues `μ_i` and eigenvectors `p_i` that are `A`- and `B`-orthogonal. In the basis
//! `P = [p_1, p_2]` normalised so that `P^T A P = I`, one has `P^T B P = diag(μ)`, and the
//! intersection is the metric whose quadratic form is the larger of the two along each `p_i`:
//!
//! ```text
//! A ∩ B = P^{-T} diag(max(1, μ_1), max(1, μ_2)) P^{-1}.
//! ```
//!
//! Its unit ball is the largest ellipse (in the sense of this construction) contained in both unit
//! balls: `v^T (A ∩ B) v >= max(v^T A v, v^T B v)` for every `v`, with equality along the `p_i`.
//!
//! Computation: with `A = V Λ V^T`, take `P_0 = V Λ^{-1/2}` (so `P_0^T A P_0 = I`), form the
//! *symmetric* matrix `C = P_0^T B P_0` (similar to `N`) and diagonalise it, `C = Q diag(μ) Q^T`;
//! then `P = P_0 Q` and `A ∩ B = Λ^{1/2}V^T`-pull-back of `Q diag(max(1, μ)) Q^T`. Working with
//! the symmetric `C` instead of the non-symmetric `N` keeps the result symmetric and SPD, and makes
//! `A ∩ A = A` (then `C = I` up to round-off) well conditioned: no eigenvector of a repeated
//! eigenvalue is ever needed. The less anisotropic of the two tensors is used as the base `A`,
//! which bounds the round-off by its condition number.

use super::SymTensor;
use crate::geom::Point;
#[cfg(test)]
use {super::Sym2, crate::geom::DVec2};

/// `A ∩ B`, the intersection of two SPD metrics by simultaneous reduction (004 §3.5). The result is
/// symmetric positive definite, satisfies `v^T (A∩B) v >= max(v^T A v, v^T B v)`, and
/// `intersect(a, a) == a`, `intersect(a, s a) == max(1, s) a` up to round-off.
///
/// Both inputs must be SPD (see [`SymTensor::validate`]); otherwise the result is meaningless
/// (NaN). Written once for [`super::Sym2`] and [`super::Sym3`].
pub fn intersect<const D: usize, S: SymTensor<D>>(a: &S, b: &S) -> S {
    let (la, va) = a.eigen();
    let (lb, vb) = b.eigen();
    // The base of the reduction is the better-conditioned tensor.
    let (base_l, base_v, other) = if la[D - 1] * lb[0] <= lb[D - 1] * la[0] {
        (la, va, b)
    } else {
        (lb, vb, a)
    };
    let s = base_l.map(f64::sqrt);
    // C = P0^T B P0 with P0 = V Λ^{-1/2}, columns v_i / sqrt(λ_i).
    let c = other.congruence(std::array::from_fn(|i| base_v[i] / s[i]));
    let (mu, q) = c.eigen();
    let d = S::from_eigen(mu.map(|m| m.max(1.0)), q);
    // A ∩ B = (P0^{-1})^T D P0^{-1}, with P0^{-1} = Λ^{1/2} V^T: its column j is
    // (sqrt(λ_i) v_i[j])_i.
    let col = |j: usize| S::Vec::from_array(std::array::from_fn(|i| s[i] * base_v[i][j]));
    d.congruence(std::array::from_fn(col))
}

/// The largest generalised eigenvalue `max_v (v^T B v) / (v^T A v)` of two SPD tensors: how far
/// the quadratic form of `b` exceeds that of `a` (`<= 1` exactly when `b <= a`, i.e. the unit ball
/// of `a` lies inside that of `b`). Computed as the largest eigenvalue of
/// `Λ_a^{-1/2} V_a^T B V_a Λ_a^{-1/2}`.
pub fn max_form_ratio<const D: usize, S: SymTensor<D>>(a: &S, b: &S) -> f64 {
    let (la, va) = a.eigen();
    let c = b.congruence(std::array::from_fn(|i| va[i] / la[i].sqrt()));
    c.eigen().0[D - 1]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel_diff(a: &Sym2, b: &Sym2) -> f64 {
        a.sub(b).norm() / a.norm().max(b.norm())
    }

    #[test]
    fn intersect_of_itself_and_of_multiples() {
        let a = Sym2::from_sizes([0.2, 1e-4], DVec2::new(0.3, 0.9));
        assert!(rel_diff(&intersect(&a, &a), &a) < 1e-13);
        assert!(rel_diff(&intersect(&a, &a.scale(4.0)), &a.scale(4.0)) < 1e-13);
        assert!(rel_diff(&intersect(&a.scale(4.0), &a), &a.scale(4.0)) < 1e-13);
        assert!(rel_diff(&intersect(&a, &a.scale(0.25)), &a) < 1e-13);
        let r3 = max_form_ratio(&a, &a.scale(3.0));
        // Anisotropy 4e6: the small eigenvalue of `a` is known to ~ε·4e6 relative.
        assert!((r3 - 3.0).abs() < 1e-9, "{r3}");
        let b = Sym2::from_sizes([0.2, 1e-4], DVec2::new(0.9, -0.3));
        let r = intersect(&a, &b);
        assert!(max_form_ratio(&r, &a) <= 1.0 + 1e-12 && max_form_ratio(&r, &b) <= 1.0 + 1e-12);
    }

    #[test]
    fn crossed_anisotropic_metrics_give_the_small_sizes() {
        // Thin along x intersected with thin along y: size 0.01 in both directions.
        let a = Sym2::from_sizes([1.0, 0.01], DVec2::X);
        let b = Sym2::from_sizes([1.0, 0.01], DVec2::Y);
        let r = intersect(&a, &b);
        assert!(rel_diff(&r, &Sym2::iso(0.01)) < 1e-14, "{r:?}");
        // Coaxial tensors: entry-wise max of eigenvalues.
        let a = Sym2::new(4.0, 0.0, 1.0);
        let b = Sym2::new(1.0, 0.0, 9.0);
        assert!(rel_diff(&intersect(&a, &b), &Sym2::new(4.0, 0.0, 9.0)) < 1e-15);
    }

    /// The textbook construction: eigenvectors `p_i` of the non-symmetric `N = A^{-1} B`, then
    /// `P^{-T} diag(max(p_i^T A p_i, p_i^T B p_i)) P^{-1}`. Same result as the symmetric route.
    #[test]
    fn agrees_with_the_eigenvectors_of_a_inverse_b() {
        let a = Sym2::from_sizes([0.3, 0.02], DVec2::new(1.0, 0.4));
        let b = Sym2::from_sizes([0.05, 0.5], DVec2::new(-0.2, 1.0));
        let ai = a.inverse();
        // N = A^{-1} B (general 2x2).
        let n = [
            [ai.xx * b.xx + ai.xy * b.xy, ai.xx * b.xy + ai.xy * b.yy],
            [ai.xy * b.xx + ai.yy * b.xy, ai.xy * b.xy + ai.yy * b.yy],
        ];
        let tr = n[0][0] + n[1][1];
        let det = n[0][0] * n[1][1] - n[0][1] * n[1][0];
        let disc = (0.25 * tr * tr - det).sqrt();
        let p: Vec<DVec2> = [0.5 * tr - disc, 0.5 * tr + disc]
            .iter()
            .map(|&mu| DVec2::new(n[0][1], mu - n[0][0]).normalize())
            .collect();
        let d = [0, 1].map(|i| a.quad(p[i]).max(b.quad(p[i])));
        // R = P^{-T} diag(d) P^{-1}: with Q = P^{-1} (rows q_i), R = Σ d_i q_i q_i^T.
        let pdet = p[0].x * p[1].y - p[1].x * p[0].y;
        let q0 = DVec2::new(p[1].y, -p[1].x) / pdet;
        let q1 = DVec2::new(-p[0].y, p[0].x) / pdet;
        let r = Sym2::outer(q0)
            .scale(d[0])
            .add(&Sym2::outer(q1).scale(d[1]));
        assert!(
            rel_diff(&intersect(&a, &b), &r) < 1e-12,
            "{:?} vs {r:?}",
            intersect(&a, &b)
        );
    }

    #[test]
    fn nearly_equal_metrics_stay_symmetric_and_close() {
        let a = Sym2::from_sizes([0.5, 0.001], DVec2::new(1.0, 2.0));
        let b = a.add(&Sym2::new(1e-9, -1e-9, 2e-9).scale(a.norm()));
        let r = intersect(&a, &b);
        assert!(r.is_spd());
        assert!(rel_diff(&r, &a) < 1e-8 && rel_diff(&r, &b) < 1e-8);
        for k in 0..64 {
            let t = k as f64 * std::f64::consts::PI / 64.0;
            let v = DVec2::new(t.cos(), t.sin());
            assert!(r.quad(v) >= a.quad(v).max(b.quad(v)) * (1.0 - 1e-10));
        }
    }
}
