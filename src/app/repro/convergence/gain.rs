//! "Anisotropy pays" from the rows of a sweep: isotropic over anisotropic vertex counts at equal
//! error (interpolated log-log between sweep points, and from fitted power laws) and at equal `ε`.

use super::types::{AnisotropyGain, ConvergenceRow, Family, GainPoint};

/// The vertex count at which a family reaches the error `e`: the first crossing of `e` by the
/// piecewise log-log line through its `(vertices, error)` points sorted by vertices; `None`
/// when `e` is outside the range of the family's errors.
pub fn vertices_at_error(points: &[(f64, f64)], e: f64) -> Option<f64> {
    let mut p: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|(n, y)| *n > 0.0 && *y > 0.0 && n.is_finite() && y.is_finite())
        .collect();
    p.sort_by(|a, b| a.0.total_cmp(&b.0));
    let le = e.ln();
    for w in p.windows(2) {
        let (n0, e0) = (w[0].0.ln(), w[0].1.ln());
        let (n1, e1) = (w[1].0.ln(), w[1].1.ln());
        let (lo, hi) = (e0.min(e1), e0.max(e1));
        if le >= lo && le <= hi {
            if e1 == e0 {
                return Some(w[0].0);
            }
            let t = (le - e0) / (e1 - e0);
            return Some((n0 + t * (n1 - n0)).exp());
        }
    }
    None
}

/// Isotropic over anisotropic vertex counts at equal error, from `(vertices, error)` points of
/// each family: at every anisotropic error inside the isotropic range (the isotropic count
/// interpolated by [`vertices_at_error`]) and at every isotropic error inside the anisotropic
/// range; sorted by decreasing error.
pub fn equal_error_ratios(ani: &[(f64, f64)], iso: &[(f64, f64)]) -> Vec<GainPoint> {
    let point = |error: f64, anisotropic_vertices: f64, isotropic_vertices: f64| GainPoint {
        error,
        anisotropic_vertices,
        isotropic_vertices,
        ratio: isotropic_vertices / anisotropic_vertices,
    };
    let mut out: Vec<GainPoint> = ani
        .iter()
        .filter_map(|&(na, e)| vertices_at_error(iso, e).map(|ni| point(e, na, ni)))
        .chain(
            iso.iter()
                .filter_map(|&(ni, e)| vertices_at_error(ani, e).map(|na| point(e, na, ni))),
        )
        .collect();
    out.sort_by(|a, b| b.error.total_cmp(&a.error));
    out
}

/// The median ratio of `points` (the geometric mean of the middle two for an even count; `None`
/// for no point).
pub fn median_ratio(points: &[GainPoint]) -> Option<f64> {
    let mut r: Vec<f64> = points.iter().map(|g| g.ratio).collect();
    r.sort_by(f64::total_cmp);
    match r.len() {
        0 => None,
        n if n % 2 == 1 => Some(r[n / 2]),
        n => Some((r[n / 2 - 1] * r[n / 2]).sqrt()),
    }
}

/// The gain of anisotropy over the rows (see [`AnisotropyGain`]).
pub fn anisotropy_gain(rows: &[ConvergenceRow]) -> AnisotropyGain {
    let pts = |f: Family, err: fn(&ConvergenceRow) -> f64| -> Vec<(f64, f64)> {
        rows.iter()
            .filter(|r| r.family == f)
            .map(|r| (r.vertices as f64, err(r)))
            .collect()
    };
    let (ani, iso) = (
        pts(Family::Anisotropic, |r| r.hausdorff),
        pts(Family::Isotropic, |r| r.hausdorff),
    );
    let (ani_area, iso_area) = (
        pts(Family::Anisotropic, |r| r.area_rel_error),
        pts(Family::Isotropic, |r| r.area_rel_error),
    );
    let at_equal_area_error = equal_error_ratios(&ani_area, &iso_area)
        .into_iter()
        .map(|g| (g.error, g.ratio))
        .collect();
    let at_equal_error = equal_error_ratios(&ani, &iso);
    let median_at_equal_error = median_ratio(&at_equal_error);
    let at_equal_eps = rows
        .iter()
        .filter(|r| r.family == Family::Anisotropic)
        .filter_map(|a| {
            rows.iter()
                .find(|r| r.family == Family::Isotropic && r.parameter == a.parameter)
                .map(|i| (a.parameter, i.vertices as f64 / a.vertices as f64))
        })
        .collect();
    AnisotropyGain {
        at_equal_error,
        median_at_equal_error,
        at_equal_eps,
        fitted: fitted_gain(&ani, &iso, 4),
        at_equal_area_error,
    }
}

/// Least-squares line `log N = a + b log e` through `(N, e)` points; `None` with fewer than two
/// distinct errors.
fn fit_vertices_on_error(points: &[(f64, f64)]) -> Option<(f64, f64)> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(n, e)| *n > 0.0 && *e > 0.0 && n.is_finite() && e.is_finite())
        .map(|(n, e)| (e.ln(), n.ln()))
        .collect();
    let k = logs.len() as f64;
    if logs.len() < 2 {
        return None;
    }
    let mx = logs.iter().map(|p| p.0).sum::<f64>() / k;
    let my = logs.iter().map(|p| p.1).sum::<f64>() / k;
    let sxx: f64 = logs.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = logs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| (my - sxy / sxx * mx, sxy / sxx))
}

/// `count` errors log-spaced over the overlap of the two families' error ranges and the ratio
/// `N_iso(e) / N_ani(e)` of their fitted power laws there (empty when the ranges do not
/// overlap).
pub fn fitted_gain(ani: &[(f64, f64)], iso: &[(f64, f64)], count: usize) -> Vec<(f64, f64)> {
    let range = |p: &[(f64, f64)]| {
        p.iter()
            .map(|q| q.1)
            .filter(|e| *e > 0.0 && e.is_finite())
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), e| {
                (lo.min(e), hi.max(e))
            })
    };
    let ((alo, ahi), (ilo, ihi)) = (range(ani), range(iso));
    let (lo, hi) = (alo.max(ilo), ahi.min(ihi));
    let (Some((aa, ba)), Some((ai, bi))) = (fit_vertices_on_error(ani), fit_vertices_on_error(iso))
    else {
        return Vec::new();
    };
    if lo >= hi || lo.is_nan() || hi.is_nan() || count == 0 {
        return Vec::new();
    }
    (0..count)
        .map(|k| {
            let t = if count == 1 {
                0.5
            } else {
                k as f64 / (count - 1) as f64
            };
            let le = hi.ln() + t * (lo.ln() - hi.ln());
            (le.exp(), (ai - aa + (bi - ba) * le).exp())
        })
        .collect()
}
