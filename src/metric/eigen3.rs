//! A closed-form eigen-decomposition of a symmetric 3×3 matrix, the fast path of
//! [`super::Sym3::eigen`].
//!
//! The trigonometric formula for the roots of the characteristic polynomial (Smith, "Eigenvalues
//! of a symmetric 3×3 matrix", CACM 4(4), 1961) gives the eigenvalues of `B = (A − qI)/p`,
//! `q = tr A / 3`, `p² = ‖A − qI‖²_F / 6`, as `2 cos(φ + 2πk/3)` with `φ = acos(det B / 2) / 3`.
//! Only the eigenvalue farthest from the other two is taken from the formula (when two
//! eigenvalues nearly coincide, `acos` near ±1 spoils those two, never the isolated one): its
//! eigenvector is the longest cross product of two rows of `A − λI`. The other two eigenvectors
//! come from one Jacobi rotation of the 2×2 restriction of `A − qI` to the orthogonal complement,
//! so the three vectors are orthonormal by construction. The eigenvalues returned are the
//! Rayleigh quotients `vᵀ A v`, the same first-order accuracy (`~ε ‖A‖` absolute) as an
//! iterative solver. This is the scheme of Eberly ("A robust eigensolver for 3×3 symmetric
//! matrices", Geometric Tools, 2014), written from its description.
//!
//! [`eigen_closed_form`] checks its own result: unless the residual `‖A V − V Λ‖_F` is within
//! `1e-13 ‖A‖_F` it returns `None`, and the caller falls back to the iterative solver.

use glam::DVec3;

use super::Sym3;

/// Relative residual `‖A V − V Λ‖_F / ‖A‖_F` above which the closed form is refused.
const RESIDUAL: f64 = 1e-13;

/// Eigenvalues ascending and orthonormal eigenvectors of the finite, non-zero `a` in closed form,
/// or `None` when the residual check fails (see the module documentation).
pub(crate) fn eigen_closed_form(a: &Sym3) -> Option<([f64; 3], [DVec3; 3])> {
    let s = [a.xx, a.xy, a.xz, a.yy, a.yz, a.zz]
        .iter()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    if s == 0.0 || !s.is_finite() {
        return None;
    }
    // Scaled and shifted: no overflow in the squares, and the shift is exact enough that the
    // eigenvectors see the spread of the eigenvalues rather than their mean.
    let b = a.scale(1.0 / s);
    let q = b.trace() / 3.0;
    let c = Sym3::new(b.xx - q, b.xy, b.xz, b.yy - q, b.yz, b.zz - q);
    let p2 =
        c.xx * c.xx + c.yy * c.yy + c.zz * c.zz + 2.0 * (c.xy * c.xy + c.xz * c.xz + c.yz * c.yz);
    if p2 == 0.0 {
        return None;
    }
    let p = (p2 / 6.0).sqrt();
    let half_det = (c.scale(1.0 / p).det() * 0.5).clamp(-1.0, 1.0);
    let phi = half_det.acos() / 3.0;
    // With det ≥ 0 the largest eigenvalue is the isolated one, otherwise the smallest.
    let beta = if half_det >= 0.0 {
        2.0 * phi.cos()
    } else {
        2.0 * (phi + 2.0 * std::f64::consts::FRAC_PI_3).cos()
    };
    let w = null_vector(&c, p * beta)?;
    let (u, v) = complement(w);
    // The 2×2 restriction of C to span(u, v), diagonalised by one Jacobi rotation.
    let (a00, a01, a11) = (c.quad(u), u.dot(c.mul_vec(v)), c.quad(v));
    let (e1, e2) = if a01 == 0.0 {
        (u, v)
    } else {
        let theta = (a11 - a00) / (2.0 * a01);
        let t = if theta.abs() > 1e150 {
            0.5 / theta
        } else {
            theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt())
        };
        let cs = 1.0 / (t * t + 1.0).sqrt();
        let sn = t * cs;
        (cs * u - sn * v, sn * u + cs * v)
    };
    let vecs = [w, e1, e2];
    // Rayleigh quotients and the residual check on the scaled `A / s` (no overflow).
    let vals = vecs.map(|x| b.quad(x));
    let mut res = 0.0;
    for k in 0..3 {
        res += (b.mul_vec(vecs[k]) - vals[k] * vecs[k]).length_squared();
    }
    if res.is_nan() || res.sqrt() > RESIDUAL * b.norm() {
        return None;
    }
    let mut idx = [0usize, 1, 2];
    idx.sort_by(|&i, &j| vals[i].total_cmp(&vals[j]));
    Some((idx.map(|k| vals[k] * s), idx.map(|k| vecs[k])))
}

/// The unit vector spanning the null space of `c − λI` (a simple eigenvalue `λ`): the longest
/// cross product of two of its rows.
fn null_vector(c: &Sym3, lambda: f64) -> Option<DVec3> {
    let r0 = DVec3::new(c.xx - lambda, c.xy, c.xz);
    let r1 = DVec3::new(c.xy, c.yy - lambda, c.yz);
    let r2 = DVec3::new(c.xz, c.yz, c.zz - lambda);
    let cands = [r0.cross(r1), r0.cross(r2), r1.cross(r2)];
    let mut best = cands[0];
    let mut len = best.length_squared();
    for x in &cands[1..] {
        let l = x.length_squared();
        if l > len {
            (best, len) = (*x, l);
        }
    }
    (len > 0.0 && len.is_finite()).then(|| best / len.sqrt())
}

/// Two unit vectors completing the unit `w` to a right-handed orthonormal basis.
fn complement(w: DVec3) -> (DVec3, DVec3) {
    let u = if w.x.abs() > w.y.abs() {
        DVec3::new(-w.z, 0.0, w.x) / (w.x * w.x + w.z * w.z).sqrt()
    } else {
        DVec3::new(0.0, w.z, -w.y) / (w.y * w.y + w.z * w.z).sqrt()
    };
    (u, w.cross(u))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A deterministic pseudo-random number in [0, 1) (splitmix64).
    fn rnd(state: &mut u64) -> f64 {
        *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = *state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        (z ^ (z >> 31)) as f64 / u64::MAX as f64
    }

    fn rotation(st: &mut u64) -> [DVec3; 3] {
        let tau = std::f64::consts::TAU;
        let m = glam::DMat3::from_euler(
            glam::EulerRot::ZYX,
            tau * rnd(st),
            tau * rnd(st),
            tau * rnd(st),
        );
        [m.x_axis, m.y_axis, m.z_axis]
    }

    /// Residual and orthogonality of a decomposition, relative to `‖A‖`.
    fn errors(a: &Sym3, (l, v): &([f64; 3], [DVec3; 3])) -> (f64, f64) {
        let mut res = 0.0f64;
        let mut orth = 0.0f64;
        for i in 0..3 {
            res += (a.mul_vec(v[i]) - l[i] * v[i]).length_squared();
            for j in 0..3 {
                let d = v[i].dot(v[j]) - if i == j { 1.0 } else { 0.0 };
                orth = orth.max(d.abs());
            }
        }
        (res.sqrt() / a.norm(), orth)
    }

    /// [`errors`] of the decomposition of `a / s` (with `‖a‖` beyond the largest float).
    fn errors_scaled(a: &Sym3, s: f64, (l, v): &([f64; 3], [DVec3; 3])) -> (f64, f64) {
        errors(&a.scale(1.0 / s), &(l.map(|x| x / s), *v))
    }

    #[test]
    fn closed_form_accuracy_random_and_anisotropic() {
        let mut st = 7u64;
        let (mut worst_res, mut worst_orth, mut worst_rel) = (0.0f64, 0.0f64, [0.0f64; 2]);
        let mut refused = 0;
        let n = 20_000;
        for i in 0..n {
            let r = rotation(&mut st);
            // Random spectra, huge ratios (1e6 and 1e12), nearly and exactly coincident pairs.
            let l = match i % 5 {
                0 => [rnd(&mut st) - 0.5, rnd(&mut st), 2.0 * rnd(&mut st)],
                1 => [1.0, 1e3 * (1.0 + rnd(&mut st)), 1e6],
                2 => [1.0, 1e6, 1e12 * (1.0 + rnd(&mut st))],
                3 => {
                    let x = 1.0 + rnd(&mut st);
                    [x, x * (1.0 + 1e-9 * rnd(&mut st)), 1e4]
                }
                _ => [25.0, 25.0, 25.0 + 1e-7 * rnd(&mut st)],
            };
            let a = Sym3::from_eigen(l, r);
            let Some(e) = eigen_closed_form(&a) else {
                refused += 1;
                continue;
            };
            let (res, orth) = errors(&a, &e);
            worst_res = worst_res.max(res);
            worst_orth = worst_orth.max(orth);
            assert!(e.0[0] <= e.0[1] && e.0[1] <= e.0[2]);
            let mut ls = l;
            ls.sort_by(f64::total_cmp);
            if i % 5 == 1 || i % 5 == 2 {
                let k = i % 5 - 1;
                for (x, y) in e.0.iter().zip(&ls) {
                    worst_rel[k] = worst_rel[k].max((x / y - 1.0).abs());
                }
            }
            // Same answer as the iterative solver to within its own accuracy.
            let (li, _) = a.eigen_iterative();
            for (x, y) in e.0.iter().zip(&li) {
                assert!((x - y).abs() <= 1e-12 * a.norm(), "{l:?}: {e:?} {li:?}");
            }
        }
        eprintln!(
            "closed-form Sym3 eigen: residual {worst_res:.1e}, orthogonality {worst_orth:.1e}, \
             eigenvalue rel. error ratio 1e6 {:.1e} / 1e12 {:.1e}, refused {refused} of {n}",
            worst_rel[0], worst_rel[1]
        );
        assert!(worst_res <= RESIDUAL && worst_orth < 1e-14);
        assert!(worst_rel[0] < 1e-9 && worst_rel[1] < 1e-3, "{worst_rel:?}");
        // The fallback is for rare cases only.
        assert!(refused * 100 < n, "{refused} refused");
        // Cost per call, printed only (never asserted: the machine may be loaded).
        let mats: Vec<Sym3> = (0..n)
            .map(|_| {
                let l = [rnd(&mut st), 1e3 * rnd(&mut st), 1e6 * rnd(&mut st)];
                Sym3::from_eigen(l, rotation(&mut st))
            })
            .collect();
        let time = |f: &dyn Fn(&Sym3) -> f64| {
            let t = std::time::Instant::now();
            let s: f64 = mats.iter().map(f).sum();
            (t.elapsed().as_secs_f64() * 1e9 / n as f64, s)
        };
        let (closed, _) = time(&|a| eigen_closed_form(a).map_or(0.0, |e| e.0[0]));
        let (iter, _) = time(&|a| a.eigen_iterative().0[0]);
        eprintln!("ns per call: closed form {closed:.0}, iterative {iter:.0}");
    }

    #[test]
    fn closed_form_edge_cases() {
        assert!(eigen_closed_form(&Sym3::default()).is_none());
        assert!(eigen_closed_form(&Sym3::scalar(3.0)).is_none());
        // Rank one, and a matrix with a zero diagonal.
        for a in [
            Sym3::outer(DVec3::new(1.0, -2.0, 0.5)),
            Sym3::new(0.0, 1.0, 1.0, 0.0, 1.0, 0.0),
            Sym3::new(1e300, 1e299, 0.0, 1e300, 0.0, 1e-300),
        ] {
            let e = eigen_closed_form(&a).expect("closed form");
            let (res, orth) = errors_scaled(&a, a.xx.abs().max(a.xy.abs()), &e);
            assert!(res <= RESIDUAL && orth < 1e-14, "{a:?}: {res:e} {orth:e}");
        }
    }
}
