//! A small dense least-squares solver for the patch fits: Householder QR of a column-equilibrated
//! `m x n` system (`n <= 6`), in caller-owned buffers, so the hot loop does not allocate.
//!
//! QR works on the scaled system itself, so its accuracy degrades with `cond(A)`, not with
//! `cond(A)^2` as the normal equations `A^T A y = A^T b` of 004 §4.3 would.

/// Most unknowns of a fit: value, gradient (2) and Hessian (3).
pub(crate) const MAX_UNKNOWNS: usize = 6;

/// Solves `min |A x - b|` for the column-major `m x n` matrix `a` (overwritten) and `b`
/// (overwritten), writing the solution into `x[..n]`.
///
/// Columns are first scaled to unit Euclidean norm. Returns the smallest `|R_kk|` of the scaled
/// system's QR factor (at most 1; a cheap inverse-condition indicator: it is the distance of a
/// unit column from the span of the previous ones), or `None` when `m < n`, a column is zero or
/// `R` is singular.
pub(crate) fn solve(
    a: &mut [f64],
    m: usize,
    n: usize,
    b: &mut [f64],
    x: &mut [f64],
) -> Option<f64> {
    debug_assert!(n <= MAX_UNKNOWNS && a.len() >= m * n && b.len() >= m && x.len() >= n);
    if m < n || n == 0 {
        return None;
    }
    let mut scale = [0.0; MAX_UNKNOWNS];
    for (j, s) in scale.iter_mut().enumerate().take(n) {
        let col = &mut a[j * m..(j + 1) * m];
        let norm = col.iter().map(|c| c * c).sum::<f64>().sqrt();
        if !(norm > 0.0 && norm.is_finite()) {
            return None;
        }
        col.iter_mut().for_each(|c| *c /= norm);
        *s = norm;
    }
    let mut rdiag = [0.0; MAX_UNKNOWNS];
    for k in 0..n {
        let (head, tail) = a.split_at_mut((k + 1) * m);
        let v = &mut head[k * m + k..k * m + m];
        let norm = v.iter().map(|c| c * c).sum::<f64>().sqrt();
        if norm == 0.0 {
            return None;
        }
        let alpha = if v[0] > 0.0 { -norm } else { norm };
        // |x - alpha e1|^2 = |x|^2 - 2 alpha x_0 + alpha^2 = 2 (alpha^2 - alpha x_0).
        let vnorm2 = 2.0 * (alpha * alpha - alpha * v[0]);
        v[0] -= alpha;
        rdiag[k] = alpha;
        if vnorm2 == 0.0 {
            continue; // the column is already a multiple of e_k
        }
        let f = 2.0 / vnorm2;
        for j in k + 1..n {
            let col = &mut tail[(j - k - 1) * m + k..(j - k) * m];
            let s = f * dot(v, col);
            col.iter_mut()
                .zip(v.iter())
                .for_each(|(c, vi)| *c -= s * vi);
        }
        let rhs = &mut b[k..m];
        let s = f * dot(v, rhs);
        rhs.iter_mut()
            .zip(v.iter())
            .for_each(|(c, vi)| *c -= s * vi);
    }
    let min_r = rdiag[..n]
        .iter()
        .fold(f64::INFINITY, |acc, r| acc.min(r.abs()));
    if !(min_r > 0.0 && min_r.is_finite()) {
        return None;
    }
    for k in (0..n).rev() {
        let mut s = b[k];
        for (j, xj) in x.iter().enumerate().take(n).skip(k + 1) {
            s -= a[j * m + k] * xj;
        }
        x[k] = s / rdiag[k];
    }
    for k in 0..n {
        x[k] /= scale[k];
    }
    Some(min_r)
}

#[inline]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_overdetermined_consistent_system_exactly() {
        // rows (1, t, t^2) at t = 0..5, x = (2, -1, 0.5): consistent, so residual 0.
        let m = 6;
        let ts: Vec<f64> = (0..m).map(|i| i as f64).collect();
        let mut a = Vec::new();
        for p in 0..3 {
            a.extend(ts.iter().map(|t| t.powi(p)));
        }
        let mut b: Vec<f64> = ts.iter().map(|t| 2.0 - t + 0.5 * t * t).collect();
        let mut x = [0.0; 3];
        let r = solve(&mut a, m, 3, &mut b, &mut x).unwrap();
        assert!(r > 1e-3);
        for (xi, ei) in x.iter().zip([2.0, -1.0, 0.5]) {
            assert!((xi - ei).abs() < 1e-13, "{x:?}");
        }
    }

    #[test]
    fn least_squares_line_fit() {
        // Fit c to (1, 2, 6): the mean 3.
        let mut a = vec![1.0; 3];
        let mut b = vec![1.0, 2.0, 6.0];
        let mut x = [0.0];
        solve(&mut a, 3, 1, &mut b, &mut x).unwrap();
        assert!((x[0] - 3.0).abs() < 1e-14);
    }

    #[test]
    fn rank_deficiency_is_reported() {
        // Two identical columns.
        let mut a = vec![1.0, 2.0, 3.0, 1.0, 2.0, 3.0];
        let mut b = vec![1.0, 1.0, 1.0];
        let mut x = [0.0; 2];
        let r = solve(&mut a, 3, 2, &mut b, &mut x);
        assert!(r.map_or(true, |r| r < 1e-14), "{r:?}");
        let mut a = vec![1.0, 2.0];
        assert!(solve(&mut a, 1, 2, &mut [1.0], &mut x).is_none());
    }
}
