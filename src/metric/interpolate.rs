//! Log-Euclidean interpolation of metrics (Arsigny, Fillard, Pennec & Ayache 2006).
//!
//! Metrics are averaged through their logarithms:
//!
//! ```text
//! M = exp( Σ w_i ln M_i / Σ w_i ).
//! ```
//!
//! Unlike the entry-wise (Euclidean) mean, this mean of SPD tensors is SPD, commutes with
//! scaling (`mean(s M_i) = s mean(M_i)`), interpolates determinants geometrically
//! (`det M = Π det(M_i)^{w_i / Σ w}`), and does not swell the unit ball when the tensors rotate.
//! It is the interpolation used for element metrics (`M_K` of 004 §3.3–3.4) and for metric
//! transfer at new vertices.

use super::{Sym2, SymTensor};

/// The weighted log-Euclidean mean `exp(Σ w_i ln M_i / Σ w_i)` of the items `(w_i, M_i)`.
///
/// Weights are normalised by their sum. If the sum of weights is not positive and finite (all
/// zero, say), the unweighted mean is returned; an empty slice gives the identity. The tensors
/// must be SPD. Written once for [`Sym2`] and [`super::Sym3`].
pub fn interpolate_log<const D: usize, S: SymTensor<D>>(items: &[(f64, S)]) -> S {
    if items.is_empty() {
        return S::IDENTITY;
    }
    let total: f64 = items.iter().map(|(w, _)| *w).sum();
    let uniform = !(total.is_finite() && total > 0.0);
    let mut acc = S::default();
    for (w, m) in items {
        let w = if uniform {
            1.0 / items.len() as f64
        } else {
            *w / total
        };
        if w != 0.0 {
            acc = acc.add(&m.log().scale(w));
        }
    }
    acc.exp()
}

/// Geodesic interpolation `exp((1 - t) ln A + t ln B)` between two SPD metrics in the
/// log-Euclidean framework: `t = 0` gives `A`, `t = 1` gives `B` (and `t` outside `[0, 1]`
/// extrapolates).
pub fn lerp_log<const D: usize, S: SymTensor<D>>(a: &S, b: &S, t: f64) -> S {
    a.log().scale(1.0 - t).add(&b.log().scale(t)).exp()
}

/// Interpolation of two metrics with *sizes* varying linearly (MMG's `interpmet22` rule): in the
/// basis that reduces `a` and `b` simultaneously (`P^T a P = I`, `P^T b P = diag(c_i)`, from the
/// eigenvectors of `a^{-1/2} b a^{-1/2}`), the size along each basis vector goes linearly from 1
/// (that of `a`) to `1/sqrt(c_i)` (that of `b`): `h_i(t) = (1 - t) + t / sqrt(c_i)`, and the
/// result is `a^{1/2} Q diag(1/h_i²) Q^T a^{1/2}`. `t = 0` gives `a`, `t = 1` gives `b`.
///
/// Compared with [`lerp_log`] (sizes varying geometrically), a fine and a coarse metric give much
/// coarser intermediate metrics: halfway between sizes 1e-5 and 0.2 this gives 0.1, the
/// log-Euclidean mean 1.4e-3. Both inputs must be SPD.
pub fn lerp_sizes(a: &Sym2, b: &Sym2, t: f64) -> Sym2 {
    let (root, inv_root) = sqrt_and_inverse_sqrt(a);
    let (r0, r1) = (
        crate::geom::DVec2::new(inv_root.xx, inv_root.xy),
        crate::geom::DVec2::new(inv_root.xy, inv_root.yy),
    );
    let c = b.congruence(r0, r1);
    let d = c.map_eigen(|ci| {
        let h = (1.0 - t) + t / ci.sqrt();
        1.0 / (h * h)
    });
    let (q0, q1) = (
        crate::geom::DVec2::new(root.xx, root.xy),
        crate::geom::DVec2::new(root.xy, root.yy),
    );
    d.congruence(q0, q1)
}

/// `(a^{1/2}, a^{-1/2})` of a 2x2 SPD tensor in closed form, without an eigen-decomposition: with
/// `s = sqrt(det a)` and `r = sqrt(tr a + 2 s)`, `a^{1/2} = (a + s I) / r` (Cayley–Hamilton) and
/// its inverse is the adjugate of `a + s I` divided by `r s`. The sums add positive terms; the
/// accuracy is that of `det a`, whose cancellation gives a relative error of about `1e-16 κ` for
/// an eigenvalue ratio `κ` (1e-9 at `κ` = 4e8) — the same as the eigen-decomposition, which
/// takes the small eigenvalue as `det / λ_max`.
#[inline]
fn sqrt_and_inverse_sqrt(a: &Sym2) -> (Sym2, Sym2) {
    let s = a.det().sqrt();
    let r = (a.xx + a.yy + 2.0 * s).sqrt();
    let root = Sym2::new((a.xx + s) / r, a.xy / r, (a.yy + s) / r);
    let rs = r * s;
    let inv_root = Sym2::new((a.yy + s) / rs, -a.xy / rs, (a.xx + s) / rs);
    (root, inv_root)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::DVec2;

    fn rel_diff(a: &Sym2, b: &Sym2) -> f64 {
        a.sub(b).norm() / a.norm().max(b.norm())
    }

    #[test]
    fn closed_form_roots_match_the_eigen_roots() {
        for (h, dir) in [
            ([0.2, 1e-5], DVec2::new(0.3, 1.0)),
            ([1.0, 1.0], DVec2::X),
            ([0.1, 1e-3], DVec2::new(1.0, 1.0)),
            ([1e-2, 3.0], DVec2::new(-2.0, 0.5)),
        ] {
            let a = Sym2::from_sizes(h, dir);
            let (root, inv_root) = sqrt_and_inverse_sqrt(&a);
            assert!(rel_diff(&root, &a.sqrt()) < 1e-10, "{a:?}");
            assert!(rel_diff(&inv_root, &a.powf(-0.5)) < 1e-10, "{a:?}");
            // The square of the root is `a`; the root times its inverse is the identity.
            let (r0, r1) = (DVec2::new(root.xx, root.xy), DVec2::new(root.xy, root.yy));
            assert!(rel_diff(&Sym2::IDENTITY.congruence(r0, r1), &a) < 1e-10);
            let prod = [
                r0.dot(DVec2::new(inv_root.xx, inv_root.xy)),
                r0.dot(DVec2::new(inv_root.xy, inv_root.yy)),
                r1.dot(DVec2::new(inv_root.xy, inv_root.yy)),
            ];
            assert!(
                (prod[0] - 1.0).abs() < 1e-10 && prod[1].abs() < 1e-10,
                "{prod:?}"
            );
            assert!((prod[2] - 1.0).abs() < 1e-10, "{prod:?}");
        }
    }

    #[test]
    fn mean_of_equal_metrics_and_endpoints() {
        let a = Sym2::from_sizes([0.1, 1e-3], DVec2::new(1.0, 1.0));
        let b = Sym2::from_sizes([1.0, 0.5], DVec2::new(-1.0, 3.0));
        assert!(rel_diff(&interpolate_log(&[(0.2, a), (0.5, a), (3.0, a)]), &a) < 1e-12);
        assert!(rel_diff(&lerp_log(&a, &b, 0.0), &a) < 1e-12);
        assert!(rel_diff(&lerp_log(&a, &b, 1.0), &b) < 1e-12);
        // Weights are normalised.
        let m1 = interpolate_log(&[(1.0, a), (3.0, b)]);
        let m2 = interpolate_log(&[(0.25, a), (0.75, b)]);
        assert!(rel_diff(&m1, &m2) < 1e-14);
        assert!(rel_diff(&m1, &lerp_log(&a, &b, 0.75)) < 1e-12);
    }

    #[test]
    fn determinant_is_interpolated_geometrically() {
        let a = Sym2::from_sizes([0.1, 1e-3], DVec2::new(1.0, 1.0));
        let b = Sym2::from_sizes([1.0, 0.5], DVec2::new(-1.0, 3.0));
        let t = 0.3;
        let m = lerp_log(&a, &b, t);
        let expect = a.det().powf(1.0 - t) * b.det().powf(t);
        assert!((m.det() / expect - 1.0).abs() < 1e-12);
        // Two crossed tensors of the same shape: the mean is isotropic, not swollen.
        let x = Sym2::from_sizes([1.0, 0.01], DVec2::X);
        let y = Sym2::from_sizes([1.0, 0.01], DVec2::Y);
        let m = lerp_log(&x, &y, 0.5);
        assert!(rel_diff(&m, &Sym2::iso(0.1)) < 1e-13, "{m:?}");
    }

    #[test]
    fn degenerate_weights_fall_back_to_uniform() {
        let a = Sym2::iso(1.0);
        let b = Sym2::iso(0.01);
        assert!(rel_diff(&interpolate_log(&[(0.0, a), (0.0, b)]), &Sym2::iso(0.1)) < 1e-13);
        assert_eq!(interpolate_log::<2, Sym2>(&[]), Sym2::IDENTITY);
    }

    #[test]
    fn lerp_sizes_interpolates_sizes_linearly_and_keeps_the_ends() {
        use crate::geom::DVec2;
        let dir = DVec2::new(0.6, 0.8);
        let a = Sym2::from_sizes([0.2, 1e-5], dir);
        let b = Sym2::from_sizes([0.4, 0.2], DVec2::new(-0.3, 0.9));
        for (t, m) in [(0.0, a), (1.0, b)] {
            let r = lerp_sizes(&a, &b, t);
            // `a` has condition number 4e8: round-off of order 4e8 * 1e-16 relative.
            assert!(
                r.sub(&m).norm() <= 1e-6 * m.norm(),
                "t = {t}: {r:?} vs {m:?}"
            );
        }
        // Homothetic metrics: sizes along every direction go linearly.
        let c = Sym2::from_sizes([0.3, 1e-3], dir);
        let d = c.scale(1.0 / 400.0); // sizes x 20
        for t in [0.25, 0.5, 0.75] {
            let r = lerp_sizes(&c, &d, t);
            let (h, _) = r.sizes();
            let k = (1.0 - t) + 20.0 * t;
            assert!((h[0] / (0.3 * k) - 1.0).abs() < 1e-9, "{h:?}");
            assert!((h[1] / (1e-3 * k) - 1.0).abs() < 1e-9, "{h:?}");
        }
        // The fine/coarse example of the doc comment: halfway size 0.1 (log-Euclidean 1.4e-3).
        let fine = Sym2::from_sizes([1e-5, 1e-5], dir);
        let coarse = Sym2::from_sizes([0.2, 0.2], dir);
        let (h, _) = lerp_sizes(&fine, &coarse, 0.5).sizes();
        assert!(
            (h[0] - 0.100005).abs() < 1e-9 && (h[1] - 0.100005).abs() < 1e-9,
            "{h:?}"
        );
        let (hl, _) = lerp_log(&fine, &coarse, 0.5).sizes();
        assert!((hl[0] - (1e-5f64 * 0.2).sqrt()).abs() < 1e-9, "{hl:?}");
    }
}
