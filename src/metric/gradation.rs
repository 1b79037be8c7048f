//! Size gradation: bounding how fast the prescribed sizes may grow along edges.
//!
//! Metric-space gradation (Alauzet, "Size gradation control of anisotropic meshes", FEAD 2010):
//! the metric `M_a` at vertex `a` is *spanned* to a neighbour `b` as
//!
//! ```text
//! M_{a→b} = η_ab^{-2} M_a,      η_ab = 1 + |e_ab|_{M_a} ln β,
//! ```
//!
//! i.e. every size of `M_a` grows by the factor `η_ab <= β^{|e_ab|_{M_a}}` over the edge, and `M_b`
//! is replaced by `M_b ∩ M_{a→b}` ([`super::intersect()`]). Sizes can only shrink, so the process is
//! monotone; it is iterated with a work list (a vertex whose metric changed is queued again) until
//! no metric changes by more than a relative `1e-6` in its quadratic form. The work list is a
//! priority queue on `sqrt(det M)`, smallest elements first, so most vertices receive their binding
//! constraint before they spread their own metric: on a 300x300 union-jack grid with a thin
//! anisotropic band (90,601 vertices) this took 96k vertex visits where a FIFO needed 1.05M (11x).
//!
//! **Property on return** (asserted by the tests): for every edge `(a, b)` and every direction `v`,
//!
//! ```text
//! v^T M_b v >= η_ab^{-2} v^T M_a v (1 - 1e-6),  i.e.  h_b(v) <= η_ab h_a(v) <= β^{|e|_{M_a}} h_a(v)
//! ```
//!
//! with `h_x(v) = 1/sqrt(v^T M_x v)` the size at `x` along the unit vector `v`.
//!
//! Note: per edge, `η h = h + |e| ln β` for an isotropic size `h`, so metric-space gradation lets
//! sizes grow *linearly* with distance, `h(x) <= h_0 + x ln β` (tested exactly on a strip), not
//! geometrically; `β` is the growth factor per unit metric length at the small end.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use super::intersect::intersect;
#[cfg(test)]
use super::intersect::max_form_ratio;
use super::{Sym2, Sym3, SymTensor};
use crate::error::{Error, Result};
use crate::geom::DVec3;
use crate::mesh::Mesh2;

/// Relative change of a quadratic form below which a metric counts as unchanged.
pub const GRADATION_TOL: f64 = 1e-6;

/// Bounds the size growth along every edge of `mesh` to the factor `1 + |e|_M ln beta` by
/// metric-space gradation (module documentation), modifying `metric` in place. Returns the number
/// of vertices whose metric was changed.
///
/// Errors: `beta <= 1` or not finite, a metric field whose length is not the vertex count, or a
/// tensor that is not SPD (the first bad vertex is named).
pub fn gradate(mesh: &Mesh2, metric: &mut [Sym2], beta: f64) -> Result<usize> {
    check_beta(beta)?;
    super::field::validate_field(metric, mesh.n_points())?;
    let (off, nbr) = mesh.v2v();
    Ok(gradate_graph(&mesh.points, &off, &nbr, metric, beta))
}

/// [`gradate`] on a tetrahedral mesh given by its vertices and tetrahedra (the edges are the
/// tetrahedra's): the same spanning, intersection and work list, over [`Sym3`].
///
/// Errors: `beta <= 1` or not finite, a field or cell list that does not fit the vertices, or a
/// tensor that is not SPD (the first bad vertex is named).
pub fn gradate_tets(
    points: &[DVec3],
    tets: &[[u32; 4]],
    metric: &mut [Sym3],
    beta: f64,
) -> Result<usize> {
    check_beta(beta)?;
    let n = points.len();
    if metric.len() != n {
        return Err(Error::InvalidField {
            name: "metric".into(),
            msg: format!(
                "{} tensors for {n} vertices (need one per vertex)",
                metric.len()
            ),
        });
    }
    for (v, m) in metric.iter().enumerate() {
        SymTensor::validate(m, v)?;
    }
    let mut nb: Vec<Vec<u32>> = vec![Vec::new(); n];
    for (t, tet) in tets.iter().enumerate() {
        if let Some(&v) = tet.iter().find(|&&v| v as usize >= n) {
            return Err(Error::InvalidInput(format!(
                "tetrahedron {} has vertex {} beyond the {n} vertices",
                t + 1,
                v + 1
            )));
        }
        for &a in tet {
            nb[a as usize].extend(tet.iter().filter(|&&b| b != a));
        }
    }
    let mut off = Vec::with_capacity(n + 1);
    let mut data = Vec::new();
    off.push(0);
    for mut l in nb {
        l.sort_unstable();
        l.dedup();
        data.extend_from_slice(&l);
        off.push(data.len());
    }
    Ok(gradate_graph(points, &off, &data, metric, beta))
}

fn check_beta(beta: f64) -> Result<()> {
    if !(beta > 1.0 && beta.is_finite()) {
        return Err(Error::InvalidInput(format!(
            "gradation factor beta = {beta} must be finite and > 1"
        )));
    }
    Ok(())
}

/// The gradation of the module documentation over any dimension: `points`, the neighbours of
/// `v` in `nbr[off[v]..off[v + 1]]`, a valid SPD field `metric` (one per point) and `beta > 1`.
/// Returns the number of vertices whose metric changed.
pub fn gradate_graph<const D: usize, S: SymTensor<D>>(
    points: &[S::Vec],
    off: &[usize],
    nbr: &[u32],
    metric: &mut [S],
    beta: f64,
) -> usize {
    let n = points.len();
    let ln_beta = beta.ln();
    // Max-heap on (sqrt det M, vertex): the smallest elements spread first, so that most
    // vertices are reached by their binding constraint before they are spread themselves. An
    // entry whose key is stale (the metric changed after it was pushed) is skipped.
    let key = |m: &S| m.det().max(0.0).sqrt();
    let mut queue: BinaryHeap<(Key, usize)> = (0..n)
        .filter(|&v| off[v + 1] > off[v])
        .map(|v| (Key(key(&metric[v])), v))
        .collect();
    let mut modified = vec![false; n];
    // Safety net only: each update grows a quadratic form by at least GRADATION_TOL, and forms are
    // bounded by the largest initial metric, so the loop ends long before this.
    let mut budget = 1000usize.saturating_mul(n).saturating_add(1000);
    while let Some((Key(k), a)) = queue.pop() {
        if k != key(&metric[a]) {
            continue;
        }
        if budget == 0 {
            break;
        }
        budget -= 1;
        let ma = metric[a];
        let pa = points[a];
        for &b in &nbr[off[a]..off[a + 1]] {
            let b = b as usize;
            let la = ma.quad(points[b] - pa).sqrt();
            let eta = 1.0 + la * ln_beta;
            let spanned = ma.scale(1.0 / (eta * eta));
            let mb = metric[b];
            if !exceeds(&mb, &spanned) {
                continue;
            }
            let r = intersect(&mb, &spanned);
            // Changes below round-off (possible only at anisotropy ~1e9) are not propagated.
            if r.sub(&mb).norm() <= 1e-13 * mb.norm() {
                continue;
            }
            metric[b] = r;
            modified[b] = true;
            queue.push((Key(key(&r)), b));
        }
    }
    modified.iter().filter(|&&m| m).count()
}

/// A totally ordered `f64` heap key (`total_cmp`).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Key(f64);

impl Eq for Key {}

impl PartialOrd for Key {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for Key {
    fn cmp(&self, o: &Self) -> Ordering {
        self.0.total_cmp(&o.0)
    }
}

/// Whether `s` is *not* below `(1 + GRADATION_TOL) m` in the SPD order, i.e. whether
/// `max_v (v^T s v) / (v^T m v) > 1 + GRADATION_TOL` ([`max_form_ratio`]), tested without an
/// eigen-decomposition: `(1 + tol) m - s` is positive semi-definite iff its diagonal and its
/// determinant are non-negative (in 3D: its principal minors, [`SymTensor::is_psd`]).
#[inline]
fn exceeds<const D: usize, S: SymTensor<D>>(m: &S, s: &S) -> bool {
    !m.scale(1.0 + GRADATION_TOL).sub(s).is_psd()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::DVec2;
    use crate::mesh::GridPattern;

    #[test]
    fn rejects_bad_input() {
        let mesh = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 2, 2, GridPattern::Right).unwrap();
        let mut m = vec![Sym2::IDENTITY; mesh.n_points()];
        assert!(gradate(&mesh, &mut m, 1.0).is_err());
        assert!(gradate(&mesh, &mut m, f64::NAN).is_err());
        assert!(gradate(&mesh, &mut m[..3], 1.5).is_err());
        m[4] = Sym2::new(-1.0, 0.0, 1.0);
        assert!(matches!(
            gradate(&mesh, &mut m, 1.5),
            Err(Error::InvalidMetric { vertex: 4, .. })
        ));
    }

    #[test]
    fn one_dimensional_growth_is_geometric_with_unit_steps() {
        // A strip of n cells along x, size h0 at x = 0 and huge elsewhere. With isotropic metrics
        // the spanned size is h η = h (1 + (Δx / h) ln β) = h + Δx ln β: metric-space gradation
        // grows sizes *linearly*, h(x) = h0 + x ln β, along the chain of bottom edges.
        let n = 40;
        let mesh = Mesh2::rectangle(
            DVec2::ZERO,
            DVec2::new(1.0, 0.025),
            n,
            1,
            GridPattern::Right,
        )
        .unwrap();
        let h0 = 1e-3;
        let mut m: Vec<Sym2> = mesh
            .points
            .iter()
            .map(|p| {
                if p.x == 0.0 {
                    Sym2::iso(h0)
                } else {
                    Sym2::iso(10.0)
                }
            })
            .collect();
        let changed = gradate(&mesh, &mut m, 1.3).unwrap();
        assert_eq!(changed, mesh.n_points() - 2);
        // Bound on every edge.
        for ([a, b], _, _) in mesh.edges() {
            let (a, b) = (a as usize, b as usize);
            for (x, y) in [(a, b), (b, a)] {
                let l = m[x].quad(mesh.points[y] - mesh.points[x]).sqrt();
                let eta = 1.0 + l * 1.3f64.ln();
                assert!(max_form_ratio(&m[y], &m[x].scale(1.0 / (eta * eta))) <= 1.0 + 2e-6);
            }
        }
        // Sizes grow monotonically with x along the bottom row, by at most β per unit length.
        let row: Vec<f64> = (0..=n).map(|i| m[i].sizes().0[1]).collect();
        for i in 0..n {
            assert!(row[i + 1] >= row[i] * (1.0 - 1e-9));
            let unit_len = 0.025 / row[i];
            assert!(row[i + 1] <= row[i] * 1.3f64.powf(unit_len) * (1.0 + 1e-6));
        }
        for (i, &h) in row.iter().enumerate() {
            let x = mesh.points[i].x;
            let expect = h0 + x * 1.3f64.ln();
            assert!(
                (h / expect - 1.0).abs() < 1e-5,
                "x = {x}: h = {h}, expected {expect}"
            );
        }
    }

    #[test]
    fn tetrahedral_gradation_grows_sizes_linearly_from_a_plane() {
        // Size h0 on the plane x = 0 of a Kuhn box, huge elsewhere: every path from the plane
        // is at least as long as its x extent, and the x-parallel edges give exactly that, so
        // the graded isotropic size is h0 + x ln β at every vertex; the bound holds on every
        // edge of every tetrahedron, along every direction.
        let mesh = crate::mesh3::Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [8, 5, 4]).unwrap();
        let h0 = 2e-3;
        let beta = 1.4f64;
        let mut m: Vec<Sym3> = mesh
            .points
            .iter()
            .map(|p| Sym3::iso(if p.x == 0.0 { h0 } else { 50.0 }))
            .collect();
        let changed = gradate_tets(&mesh.points, &mesh.tets, &mut m, beta).unwrap();
        assert_eq!(changed, 9 * 6 * 5 - 6 * 5);
        for (p, mm) in mesh.points.iter().zip(&m) {
            let expect = h0 + p.x * beta.ln();
            let (h, _) = SymTensor::sizes(mm);
            for hi in h {
                assert!((hi / expect - 1.0).abs() < 1e-5, "{p}: {hi} vs {expect}");
            }
        }
        for t in &mesh.tets {
            for &a in t {
                for &b in t {
                    let (a, b) = (a as usize, b as usize);
                    let l = m[a].quad(mesh.points[b] - mesh.points[a]).sqrt();
                    let eta = 1.0 + l * beta.ln();
                    assert!(max_form_ratio(&m[b], &m[a].scale(1.0 / (eta * eta))) <= 1.0 + 2e-6);
                }
            }
        }
        // An anisotropic field: the bound on every edge after grading.
        let mut m: Vec<Sym3> = mesh
            .points
            .iter()
            .map(|p| {
                let d = DVec3::new(1.0, p.y, 0.3).normalize();
                let h = 1e-3 + p.distance(DVec3::splat(0.5));
                Sym3::outer(d).scale(1.0 / (h * h)).add(&Sym3::scalar(1.0))
            })
            .collect();
        gradate_tets(&mesh.points, &mesh.tets, &mut m, 1.3).unwrap();
        for t in &mesh.tets {
            for &a in t {
                for &b in t {
                    let (a, b) = (a as usize, b as usize);
                    let l = m[a].quad(mesh.points[b] - mesh.points[a]).sqrt();
                    let eta = 1.0 + l * 1.3f64.ln();
                    assert!(max_form_ratio(&m[b], &m[a].scale(1.0 / (eta * eta))) <= 1.0 + 2e-6);
                }
            }
        }
        let mut bad = m.clone();
        bad[7] = Sym3::new(1.0, 2.0, 0.0, 1.0, 0.0, 1.0);
        assert!(matches!(
            gradate_tets(&mesh.points, &mesh.tets, &mut bad, 1.3),
            Err(Error::InvalidMetric { vertex: 7, .. })
        ));
        assert!(gradate_tets(&mesh.points, &mesh.tets, &mut m[..5], 1.3).is_err());
    }
}
