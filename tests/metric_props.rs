//! Property tests of the metric mathematics (`anisomesh::metric`): intersection, log-Euclidean
//! interpolation, bounding, edge length and `Q_ani` (004 §3.3–3.5), and the 3D `Sym3`. 256 random
//! cases each.

use anisomesh::metric::{
    edge_length, interpolate_log, intersect, lerp_log, max_form_ratio, q_ani, Sym2, Sym3,
};
use anisomesh::DVec2;
use proptest::prelude::*;

/// A random SPD metric: sizes 10^[-4, 1] in a random orientation (eigenvalue ratios up to 1e10).
fn spd() -> impl Strategy<Value = Sym2> {
    (0.0..std::f64::consts::PI, -4.0..1.0f64, -4.0..1.0f64).prop_map(|(t, a, b)| {
        Sym2::from_sizes([10f64.powf(a), 10f64.powf(b)], DVec2::new(t.cos(), t.sin()))
    })
}

fn unit(t: f64) -> DVec2 {
    DVec2::new(t.cos(), t.sin())
}

fn rel_diff(a: &Sym2, b: &Sym2) -> f64 {
    a.sub(b).norm() / a.norm().max(b.norm())
}

/// Condition number `λ_max / λ_min`. Rounding the three stored entries moves `λ_min` by
/// `~ε ‖M‖`, so anything depending on `det M` or on the small size is known to a relative
/// `~ε κ` at best; tolerances below scale with it.
fn kappa(m: &Sym2) -> f64 {
    let (l, _) = m.eigen();
    l[1] / l[0]
}

fn cfg() -> ProptestConfig {
    ProptestConfig::with_cases(256)
}

proptest! {
    #![proptest_config(cfg())]

    /// The intersection is SPD and its unit ball lies inside both unit balls:
    /// `v^T (A∩B) v >= max(v^T A v, v^T B v)` for unit `v`, up to round-off of `‖A∩B‖`.
    #[test]
    fn intersection_is_spd_and_inside_both(a in spd(), b in spd(), ts in prop::collection::vec(0.0..6.3f64, 16)) {
        let r = intersect(&a, &b);
        prop_assert!(r.is_spd(), "{r:?}");
        for t in ts {
            let v = unit(t);
            let need = a.quad(v).max(b.quad(v));
            prop_assert!(r.quad(v) >= need * (1.0 - 1e-9) - 1e-14 * r.norm(),
                "v = {v}: {} < {need}", r.quad(v));
        }
        // Not too small either: in the reduction basis diag(max(1, μ)) <= diag(1 + μ), so
        // A∩B <= A + B.
        let s = a.add(&b);
        for k in 0..8 {
            let v = unit(k as f64 * 0.39);
            prop_assert!(r.quad(v) <= s.quad(v) * (1.0 + 1e-9) + 1e-14 * r.norm());
        }
    }

    /// `A ∩ A = A`, `A ∩ sA = max(1, s) A`, and the intersection is symmetric in its arguments.
    #[test]
    fn intersection_of_multiples(a in spd(), b in spd(), s in 0.05..20.0f64) {
        prop_assert!(rel_diff(&intersect(&a, &a), &a) < 1e-10);
        prop_assert!(rel_diff(&intersect(&a, &a.scale(s)), &a.scale(s.max(1.0))) < 1e-10);
        prop_assert!(rel_diff(&intersect(&a, &b), &intersect(&b, &a)) < 1e-8);
    }

    /// Nearly equal metrics (relative perturbation 1e-13 .. 1e-7): the intersection stays SPD,
    /// close to both, and inside both.
    #[test]
    fn intersection_of_nearly_equal_metrics(a in spd(), d in prop::array::uniform3(-1.0..1.0f64), e in -13.0..-7.0f64) {
        let eps = 10f64.powf(e) * a.norm();
        let b = a.add(&Sym2::new(d[0], d[1], d[2]).scale(eps));
        prop_assume!(b.is_spd());
        let r = intersect(&a, &b);
        prop_assert!(r.is_spd());
        // In the reduction basis of `a`, r has the eigenvalues max(1, μ_i) where μ_i are those of
        // b: so the largest generalised eigenvalue of r over a is max(1, that of b over a).
        let tol = 1e-12 + 1e-14 * kappa(&a);
        let (ra, ba) = (max_form_ratio(&a, &r), max_form_ratio(&a, &b));
        prop_assert!((ra - ba.max(1.0)).abs() < tol, "{ra} vs {ba}");
        prop_assert!(ra - 1.0 <= 3.0 * 10f64.powf(e) * kappa(&a) + tol);
        // max_form_ratio itself is accurate to ~ε κ (it reduces by `r`).
        let tol = 1e-12 + 1e-14 * kappa(&r);
        prop_assert!(max_form_ratio(&r, &a) <= 1.0 + tol, "{}", max_form_ratio(&r, &a));
        prop_assert!(max_form_ratio(&r, &b) <= 1.0 + tol, "{}", max_form_ratio(&r, &b));
    }

    /// Log-Euclidean mean of equal metrics is that metric; `lerp_log` hits its endpoints.
    #[test]
    fn interpolation_of_equal_metrics(a in spd(), b in spd(), w in prop::collection::vec(0.01..5.0f64, 1..6)) {
        let items: Vec<(f64, Sym2)> = w.iter().map(|&w| (w, a)).collect();
        prop_assert!(rel_diff(&interpolate_log(&items), &a) < 1e-10);
        prop_assert!(rel_diff(&lerp_log(&a, &b, 0.0), &a) < 1e-10);
        prop_assert!(rel_diff(&lerp_log(&a, &b, 1.0), &b) < 1e-10);
        let m = lerp_log(&a, &b, 0.5);
        prop_assert!(m.is_spd());
        let tol = 1e-12 + 1e-14 * (kappa(&a) + kappa(&b) + kappa(&m));
        prop_assert!((m.det() / (a.det() * b.det()).sqrt() - 1.0).abs() < tol);
    }

    /// Bounding gives sizes in `[hmin, hmax]` and a size ratio at most `max_aniso`.
    #[test]
    fn bound_respects_sizes_and_anisotropy(a in spd(), lhmin in -4.0..-1.0f64, span in 0.0..4.0f64, aniso in 1.0..1e3f64) {
        let (hmin, hmax) = (10f64.powf(lhmin), 10f64.powf(lhmin + span));
        let b = a.bound(hmin, hmax, aniso);
        prop_assert!(b.is_spd());
        let (h, _) = b.sizes();
        let tol = 1e-10;
        prop_assert!(h[1] >= hmin * (1.0 - tol) && h[0] <= hmax * (1.0 + tol), "{h:?}");
        prop_assert!(h[0] / h[1] <= aniso * (1.0 + tol), "{h:?}");
        // Already admissible metrics are kept.
        let bb = b.bound(hmin, hmax, aniso);
        prop_assert!(rel_diff(&bb, &b) < 1e-10);
    }

    /// Rotating the edge and the metrics together keeps the metric length.
    #[test]
    fn edge_length_is_rotation_invariant(ma in spd(), mb in spd(), t in 0.0..6.3f64, e in (-1.0..1.0f64, -1.0..1.0f64), p in (-5.0..5.0f64, -5.0..5.0f64)) {
        let (pa, pb) = (DVec2::new(p.0, p.1), DVec2::new(p.0 + e.0, p.1 + e.1));
        let l = edge_length(pa, pb, &ma, &mb);
        let (c, s) = (t.cos(), t.sin());
        let rot = |v: DVec2| DVec2::new(c * v.x - s * v.y, s * v.x + c * v.y);
        // M' = R M R^T is M pulled back by R^T, whose columns are the rows of R.
        let (c0, c1) = (DVec2::new(c, -s), DVec2::new(s, c));
        let (ra, rb) = (ma.congruence(c0, c1), mb.congruence(c0, c1));
        let l2 = edge_length(rot(pa), rot(pb), &ra, &rb);
        // Rounding in the rotated tensors grows with their conditioning (as in the Q_ani test).
        let tol = 1e-12 + 1e-14 * kappa(&ma).max(kappa(&mb));
        prop_assert!((l - l2).abs() <= tol * l.max(1e-300), "{l} vs {l2}");
        // The length lies between the two end lengths.
        let (la, lb) = (ma.quad(pb - pa).sqrt(), mb.quad(pb - pa).sqrt());
        prop_assert!(l >= la.min(lb) * (1.0 - 1e-12) && l <= la.max(lb) * (1.0 + 1e-12));
        prop_assert!((edge_length(pb, pa, &mb, &ma) - l).abs() <= 1e-12 * l);
    }

    /// `Q_ani = 1` for a unit equilateral triangle of the metric, whatever its anisotropy and
    /// orientation in physical space (equilateral in metric space, mapped by `M^{-1/2}`).
    #[test]
    fn q_ani_is_one_for_unit_equilateral(m in spd(), t in 0.0..6.3f64, c in (-3.0..3.0f64, -3.0..3.0f64)) {
        let r = m.powf(-0.5);
        let base = DVec2::new(c.0, c.1);
        let tri = [0.0, 2.0, 4.0].map(|k: f64| {
            let u = unit(t + k * std::f64::consts::PI / 3.0) / 3f64.sqrt();
            base + r.mul_vec(u)
        });
        let tol = 1e-12 + 1e-14 * kappa(&m);
        prop_assert!((q_ani(tri, &m) - 1.0).abs() < tol, "{}", q_ani(tri, &m));
    }

    /// `Q_ani >= 1` for any triangle, and it is invariant under an affine map `x -> A x + c` that
    /// carries the metric along (`M' = A^{-T} M A^{-1}`).
    #[test]
    fn q_ani_is_at_least_one_and_affine_invariant(
        m in spd(),
        p in prop::array::uniform6(-1.0..1.0f64),
        a in prop::array::uniform4(-2.0..2.0f64),
        c in (-3.0..3.0f64, -3.0..3.0f64),
    ) {
        let tri = [DVec2::new(p[0], p[1]), DVec2::new(p[2], p[3]), DVec2::new(p[4], p[5])];
        let area = anisomesh::geom::signed_area(tri[0], tri[1], tri[2]);
        prop_assume!(area > 1e-3);
        let q = q_ani(tri, &m);
        prop_assert!(q >= 1.0 - 1e-12 - 1e-14 * kappa(&m), "{q}");
        // A = [[a0, a1], [a2, a3]] with det A > 0 and a bounded condition number.
        let det = a[0] * a[3] - a[1] * a[2];
        prop_assume!(det > 0.1);
        let map = |x: DVec2| DVec2::new(a[0] * x.x + a[1] * x.y + c.0, a[2] * x.x + a[3] * x.y + c.1);
        // Columns of A^{-1} = [[a3, -a1], [-a2, a0]] / det.
        let (i0, i1) = (DVec2::new(a[3], -a[2]) / det, DVec2::new(-a[1], a[0]) / det);
        let m2 = m.congruence(i0, i1);
        let q2 = q_ani(tri.map(map), &m2);
        let tol = 1e-12 + 1e-14 * (kappa(&m) + kappa(&m2));
        prop_assert!((q - q2).abs() <= tol * q, "{q} vs {q2}");
    }
}

/// A random SPD 3D metric: eigenvalues 10^[-2, 6] in a random rotation (ratios up to 1e8).
fn spd3() -> impl Strategy<Value = Sym3> {
    (
        prop::array::uniform3(-3.2..3.2f64),
        prop::array::uniform3(-2.0..6.0f64),
    )
        .prop_map(|(a, l)| {
            let r = glam::DMat3::from_euler(glam::EulerRot::ZYX, a[0], a[1], a[2]);
            Sym3::from_eigen(l.map(|x| 10f64.powf(x)), [r.x_axis, r.y_axis, r.z_axis])
        })
}

fn kappa3(m: &Sym3) -> f64 {
    let (l, _) = m.eigen();
    l[2] / l[0]
}

proptest! {
    #![proptest_config(cfg())]

    /// `Sym3`: the eigen-decomposition reconstructs, the intersection is SPD and inside both unit
    /// balls, `A ∩ A = A`, and `exp(log A) = A`.
    #[test]
    fn sym3_eigen_intersection_log(a in spd3(), b in spd3(), dirs in prop::collection::vec(prop::array::uniform3(-1.0..1.0f64), 16)) {
        let (l, v) = a.eigen();
        prop_assert!(l[0] <= l[1] && l[1] <= l[2]);
        prop_assert!(Sym3::from_eigen(l, v).sub(&a).norm() < 1e-14 * a.norm());
        let r = a.intersect(&b);
        prop_assert!(r.is_spd(), "{r:?}");
        for d in dirs {
            let u = glam::DVec3::from_array(d);
            prop_assume!(u.length() > 1e-3);
            let need = a.quad(u).max(b.quad(u));
            prop_assert!(r.quad(u) >= need * (1.0 - 1e-9) - 1e-14 * r.norm());
        }
        let tol = 1e-12 + 1e-14 * kappa3(&a);
        prop_assert!(a.intersect(&a).sub(&a).norm() < tol * a.norm());
        prop_assert!(a.log().exp().sub(&a).norm() < tol * a.norm());
    }
}
