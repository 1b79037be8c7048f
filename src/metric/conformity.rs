//! How well a simplicial mesh (triangles or tetrahedra) conforms to a metric field: the
//! statistics used to compare meshes from different adaptors on equal terms (004 §3.3–3.4; the
//! UGAWG measures in 3D).
//!
//! - **Edge lengths** in the metric from the end metrics with the size varying linearly along
//!   the edge ([`linear_size_length`] of `ℓ_a = |e|_{M_a}`, `ℓ_b = |e|_{M_b}`; against an
//!   integration of the analytic metric it is the most faithful of the vertex rules compared in
//!   `tests/metric_length_rules.rs`) or, for an analytic metric, integrated along the edge
//!   ([`conformity_analytic`]), or by the rule of the UGAWG measures ([`conformity_ugawg`], to
//!   compare with the study's published shares): share in `[1/√2, √2]`, min, max, mean and a
//!   histogram with bounds [`LENGTH_BINS`] (powers of `√2`, so the unit interval is two bins).
//! - **`Q_ani`** (004 §3.4) of each cell in its log-Euclidean element metric ([`q_ani`] in
//!   [`element_metric`]): `1` for a regular simplex of unit edges, larger otherwise; mean, worst,
//!   histogram with bounds [`Q_ANI_BINS`].
//! - **Mean ratio** in `(0, 1]` as the UGAWG measures define it: in the vertex metric of largest
//!   determinant `M`, `(V sqrt(det M) / V_eq)^{2/d} / (Σ_e e^T M e / n_e)` with `V_eq` the volume
//!   of the regular simplex of unit edges and `n_e` the number of edges (3 or 6). In one metric it
//!   equals `Q_ani^{-2/d}`; with the largest vertex metric instead of the mean it is a second,
//!   slightly different rating. Minimum, mean, histogram with bounds [`MEAN_RATIO_BINS`].
//!
//! Cells with a non-positive signed volume count as inverted: `Q_ani = +inf`, mean ratio `0`.

use rayon::prelude::*;

use super::length::{element_metric, linear_size_length, q_ani, ugawg_length, Q_ANI_BINS};
use super::length::{L_MAX, L_MIN};
use super::SymTensor;
use crate::error::{Error, Result};
use crate::geom::simplex::{self, simplex_edges};

/// Upper bounds of the edge-length histogram: `2^{k/2}`, `k = -4..4`, then `+inf`.
pub const LENGTH_BINS: [f64; 10] = [
    0.25,
    0.353_553_390_593_273_8,
    0.5,
    std::f64::consts::FRAC_1_SQRT_2,
    1.0,
    std::f64::consts::SQRT_2,
    2.0,
    2.828_427_124_746_190_3,
    4.0,
    f64::INFINITY,
];

/// Upper bounds of the mean-ratio histogram: `0.1, 0.2, …, 1.0` (the last bin also holds values
/// a rounding error above 1).
pub const MEAN_RATIO_BINS: [f64; 10] = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, f64::INFINITY];

/// Statistics of a mesh in a metric field (see the module documentation).
#[derive(Debug, Clone, PartialEq, Default, serde::Serialize)]
pub struct Conformity {
    /// Number of distinct edges.
    pub edges: usize,
    /// Share of edges whose metric length is in `[1/√2, √2]`.
    pub edge_length_in_range: f64,
    /// Smallest metric edge length.
    pub edge_length_min: f64,
    /// Largest metric edge length.
    pub edge_length_max: f64,
    /// Mean metric edge length.
    pub edge_length_mean: f64,
    /// `(upper bound, count)` over [`LENGTH_BINS`]: edges with length in `(previous, bound]`
    /// (the first bin from 0).
    pub edge_length_histogram: Vec<(f64, usize)>,
    /// Number of cells.
    pub cells: usize,
    /// Cells with non-positive signed volume.
    pub inverted: usize,
    /// Mean `Q_ani` (`+inf` if a cell is inverted).
    pub q_ani_mean: f64,
    /// Largest `Q_ani`.
    pub q_ani_max: f64,
    /// Index of the cell with the largest `Q_ani` (the first one on ties).
    pub worst_cell: usize,
    /// `(upper bound, count)` over [`Q_ANI_BINS`].
    pub q_ani_histogram: Vec<(f64, usize)>,
    /// Smallest mean ratio.
    pub mean_ratio_min: f64,
    /// Mean of the mean ratio.
    pub mean_ratio_mean: f64,
    /// `(upper bound, count)` over [`MEAN_RATIO_BINS`].
    pub mean_ratio_histogram: Vec<(f64, usize)>,
}

/// The distinct edges `[a, b]`, `a < b`, of the simplices `cells`, sorted.
pub fn cell_edges<const N: usize>(cells: &[[u32; N]]) -> Vec<[u32; 2]> {
    let local = simplex_edges(N);
    let mut edges: Vec<[u32; 2]> = Vec::with_capacity(cells.len() * local.len());
    for c in cells {
        for &[i, j] in local {
            let (a, b) = (c[i], c[j]);
            edges.push(if a < b { [a, b] } else { [b, a] });
        }
    }
    edges.par_sort_unstable();
    edges.dedup();
    edges
}

/// Mean ratio of the simplex `p` in the metric `m` (UGAWG form, see the module documentation):
/// `(V sqrt(det m) / V_eq)^{2/d} / mean_e(e^T m e)`; `0` for a non-positive signed volume.
pub fn mean_ratio<const D: usize, const N: usize, S: SymTensor<D>>(p: [S::Vec; N], m: &S) -> f64 {
    let vol = simplex::volume(&p);
    if vol.is_nan() || vol <= 0.0 {
        return 0.0;
    }
    let edges = simplex_edges(N);
    let msq = edges.iter().map(|&[a, b]| m.quad(p[b] - p[a])).sum::<f64>() / edges.len() as f64;
    let vm = vol * m.det().sqrt();
    if D == 2 {
        // V_eq = sqrt(3) / 4.
        (vm / 0.433_012_701_892_219_3) / msq
    } else {
        // V_eq = sqrt(2) / 12.
        (vm / 0.117_851_130_197_757_92).powf(2.0 / 3.0) / msq
    }
}

fn histogram(bins: &[f64], values: &[f64]) -> Vec<(f64, usize)> {
    let mut h: Vec<(f64, usize)> = bins.iter().map(|&b| (b, 0)).collect();
    for &v in values {
        let k = bins.iter().position(|&b| v <= b).unwrap_or(bins.len() - 1);
        h[k].1 += 1;
    }
    h
}

/// Checks that `metric` has one SPD entry per point and that the cells index existing points.
fn check_inputs<const D: usize, const N: usize, S: SymTensor<D>>(
    n_points: usize,
    cells: &[[u32; N]],
    metric: &[S],
) -> Result<()> {
    if metric.len() != n_points {
        return Err(Error::InvalidField {
            name: "metric".into(),
            msg: format!("{} tensors for {n_points} vertices", metric.len()),
        });
    }
    for (v, m) in metric.iter().enumerate() {
        m.validate(v)?;
    }
    if let Some(c) = cells
        .iter()
        .position(|c| c.iter().any(|&v| v as usize >= n_points))
    {
        return Err(Error::InvalidInput(format!(
            "cell {c} has a vertex index out of range (only {n_points} vertices)"
        )));
    }
    Ok(())
}

/// Edge-length, `Q_ani` and mean-ratio statistics of the simplices `cells` over `points`
/// (triangles over `DVec2` with `Sym2`, tetrahedra over `DVec3` with `Sym3`) in the vertex metric
/// field `metric`; edge lengths by [`linear_size_length`] from the end metrics. Runs in parallel; the
/// result does not depend on the thread count.
///
/// Errors: [`Error::InvalidField`] if `metric` does not have one tensor per point,
/// [`Error::InvalidMetric`] for a non-finite or non-SPD tensor, [`Error::InvalidInput`] for a cell
/// vertex out of range. An empty mesh gives zero counts.
pub fn conformity<const D: usize, const N: usize, S: SymTensor<D>>(
    points: &[S::Vec],
    cells: &[[u32; N]],
    metric: &[S],
) -> Result<Conformity> {
    from_end_lengths(points, cells, metric, linear_size_length)
}

/// [`conformity`] with the edge lengths of the UGAWG measures ([`ugawg_length`] of the end
/// metrics; the mean ratio is already theirs): the statistics by which the UGAWG study rated
/// every adaptor, for comparing a mesh with its published shares. For an analytic field, pass
/// the field evaluated at the vertices, as the study did.
///
/// Errors as [`conformity`].
pub fn conformity_ugawg<const D: usize, const N: usize, S: SymTensor<D>>(
    points: &[S::Vec],
    cells: &[[u32; N]],
    metric: &[S],
) -> Result<Conformity> {
    from_end_lengths(points, cells, metric, ugawg_length)
}

/// The statistics with each edge length given by `rule(ℓ_a, ℓ_b)` of its end lengths
/// `ℓ_a = |e|_{M_a}`, `ℓ_b = |e|_{M_b}`.
fn from_end_lengths<const D: usize, const N: usize, S: SymTensor<D>>(
    points: &[S::Vec],
    cells: &[[u32; N]],
    metric: &[S],
    rule: fn(f64, f64) -> f64,
) -> Result<Conformity> {
    check_inputs(points.len(), cells, metric)?;
    let edges = cell_edges(cells);
    let lengths: Vec<f64> = edges
        .par_iter()
        .map(|&[a, b]| {
            let (a, b) = (a as usize, b as usize);
            let e = points[b] - points[a];
            rule(metric[a].quad(e).sqrt(), metric[b].quad(e).sqrt())
        })
        .collect();
    Ok(summarise(points, cells, metric, &lengths))
}

/// Panels of the composite Gauss–Legendre rule of [`conformity_analytic`].
pub const ANALYTIC_PANELS: usize = 32;

/// `∫_0^1 sqrt(e^T M(a + t e) e) dt` (004 §3.3) by [`ANALYTIC_PANELS`] panels of 2-point
/// Gauss–Legendre: exact to round-off for a constant metric, second order in the panel width
/// across a kink of the metric, fourth order where it is smooth.
pub fn integrated_length<const D: usize, S: SymTensor<D>>(
    a: S::Vec,
    b: S::Vec,
    metric: &(impl Fn(S::Vec) -> S + ?Sized),
) -> f64 {
    let e = b - a;
    let h = 1.0 / ANALYTIC_PANELS as f64;
    let g = 0.5 * h / 3f64.sqrt();
    let mut s = 0.0;
    for k in 0..ANALYTIC_PANELS {
        let c = (k as f64 + 0.5) * h;
        s += metric(a + e * (c - g)).quad(e).sqrt() + metric(a + e * (c + g)).quad(e).sqrt();
    }
    0.5 * h * s
}

/// [`conformity`] in an analytic metric field `metric(x)`: edge lengths integrated along each
/// edge ([`integrated_length`]), element statistics in the metric at the vertices. Use it when
/// the metric is known everywhere: a rule from the end metrics ([`conformity`]) cannot see a
/// metric's variation between the vertices (a layer, a kink of the distance), which misjudges
/// edges there (see `docs/tools.md`).
///
/// Errors as [`conformity`] (for the metric at the vertices).
pub fn conformity_analytic<const D: usize, const N: usize, S: SymTensor<D>>(
    points: &[S::Vec],
    cells: &[[u32; N]],
    metric: &(impl Fn(S::Vec) -> S + Sync),
) -> Result<Conformity> {
    let at_vertices: Vec<S> = points.par_iter().map(|&p| metric(p)).collect();
    check_inputs(points.len(), cells, &at_vertices)?;
    let edges = cell_edges(cells);
    let lengths: Vec<f64> = edges
        .par_iter()
        .map(|&[a, b]| integrated_length(points[a as usize], points[b as usize], metric))
        .collect();
    Ok(summarise(points, cells, &at_vertices, &lengths))
}

/// The statistics from the edge lengths and the cells in the vertex metric.
fn summarise<const D: usize, const N: usize, S: SymTensor<D>>(
    points: &[S::Vec],
    cells: &[[u32; N]],
    metric: &[S],
    lengths: &[f64],
) -> Conformity {
    let per_cell: Vec<(f64, f64)> = cells
        .par_iter()
        .map(|c| {
            let p = c.map(|v| points[v as usize]);
            let ms = c.map(|v| &metric[v as usize]);
            let q = q_ani(p, &element_metric(ms));
            let mut big = ms[0];
            for m in &ms[1..] {
                if m.det() > big.det() {
                    big = m;
                }
            }
            (q, mean_ratio(p, big))
        })
        .collect();
    let (q, mr): (Vec<f64>, Vec<f64>) = per_cell.into_iter().unzip();

    let mut s = Conformity {
        edges: lengths.len(),
        cells: q.len(),
        edge_length_histogram: histogram(&LENGTH_BINS, lengths),
        q_ani_histogram: histogram(&Q_ANI_BINS, &q),
        mean_ratio_histogram: histogram(&MEAN_RATIO_BINS, &mr),
        inverted: q.iter().filter(|x| x.is_infinite()).count(),
        ..Conformity::default()
    };
    if !lengths.is_empty() {
        let n = lengths.len() as f64;
        let in_range = lengths
            .iter()
            .filter(|&&l| (L_MIN..=L_MAX).contains(&l))
            .count();
        s.edge_length_in_range = in_range as f64 / n;
        s.edge_length_min = lengths.iter().copied().fold(f64::INFINITY, f64::min);
        s.edge_length_max = lengths.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        s.edge_length_mean = lengths.iter().sum::<f64>() / n;
    }
    if !q.is_empty() {
        let n = q.len() as f64;
        s.q_ani_mean = q.iter().sum::<f64>() / n;
        let (mut worst, mut qmax) = (0, f64::NEG_INFINITY);
        for (i, &qi) in q.iter().enumerate() {
            if qi > qmax {
                worst = i;
                qmax = qi;
            }
        }
        s.q_ani_max = qmax;
        s.worst_cell = worst;
        s.mean_ratio_min = mr.iter().copied().fold(f64::INFINITY, f64::min);
        s.mean_ratio_mean = mr.iter().sum::<f64>() / n;
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{DVec2, DVec3};
    use crate::metric::{Sym2, Sym3};

    #[test]
    fn regular_simplices_rate_one() {
        let tri = [
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(0.5, 3f64.sqrt() / 2.0),
        ];
        assert!((mean_ratio(tri, &Sym2::IDENTITY) - 1.0).abs() < 1e-14);
        let s = 1.0 / 2f64.sqrt();
        let tet = [
            DVec3::new(1.0, 0.0, -s),
            DVec3::new(-1.0, 0.0, -s),
            DVec3::new(0.0, 1.0, s),
            DVec3::new(0.0, -1.0, s),
        ];
        // Edge length 2: unit edges in the metric I / 4.
        let m = Sym3::scalar(0.25);
        let p = if simplex::volume(&tet) > 0.0 {
            tet
        } else {
            [tet[1], tet[0], tet[2], tet[3]]
        };
        assert!((mean_ratio(p, &m) - 1.0).abs() < 1e-14);
        assert!((q_ani(p, &m) - 1.0).abs() < 1e-14);
        let c = conformity(&p, &[[0, 1, 2, 3]], &[m; 4]).unwrap();
        assert_eq!((c.edges, c.cells, c.inverted), (6, 1, 0));
        assert!((c.edge_length_in_range - 1.0).abs() < 1e-15);
        assert!((c.edge_length_mean - 1.0).abs() < 1e-14);
    }

    #[test]
    fn mean_ratio_is_q_ani_power_in_one_metric() {
        let p = [
            DVec2::new(0.0, 0.0),
            DVec2::new(2.0, 0.1),
            DVec2::new(0.3, 0.7),
        ];
        let m = Sym2::new(3.0, 0.4, 1.5);
        assert!((mean_ratio(p, &m) - 1.0 / q_ani(p, &m)).abs() < 1e-14);
    }

    #[test]
    fn bad_inputs_are_errors() {
        let p = [DVec2::ZERO, DVec2::X, DVec2::Y];
        assert!(conformity(&p, &[[0, 1, 2]], &[Sym2::IDENTITY; 2]).is_err());
        assert!(conformity(&p, &[[0, 1, 3]], &[Sym2::IDENTITY; 3]).is_err());
        let mut m = [Sym2::IDENTITY; 3];
        m[1].xx = f64::NAN;
        assert!(conformity(&p, &[[0, 1, 2]], &m).is_err());
        let inv = conformity(&p, &[[0, 2, 1]], &[Sym2::IDENTITY; 3]).unwrap();
        assert_eq!(inv.inverted, 1);
        assert_eq!(inv.mean_ratio_min, 0.0);
    }

    #[test]
    fn ugawg_rule_is_the_log_mean_away_from_equal_ends() {
        use crate::metric::length::{geometric_mean_length, ugawg_length};
        // Ends far apart: (la - lb) / ln(la / lb).
        let (la, lb) = (0.5f64, 2.0f64);
        let want = (la - lb) / (la / lb).ln();
        assert!((ugawg_length(la, lb) - want).abs() < 1e-15);
        assert_eq!(ugawg_length(la, lb), geometric_mean_length(la, lb));
        // Within Omega_h's tolerance: the arithmetic mean.
        let (near_a, near_b) = (1.0f64, 1.0005f64);
        assert_eq!(ugawg_length(near_a, near_b), 0.5 * (near_a + near_b));
        assert_ne!(
            ugawg_length(near_a, near_b),
            geometric_mean_length(near_a, near_b)
        );
        // Graded edges: the log mean is longer than the linear-size rule of `conformity`.
        let p = [
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(0.0, 1.0),
        ];
        let m = [Sym2::IDENTITY, Sym2::scalar(16.0), Sym2::IDENTITY];
        let u = conformity_ugawg(&p, &[[0, 1, 2]], &m).unwrap();
        let l = conformity(&p, &[[0, 1, 2]], &m).unwrap();
        // The longest edge, 1-2: la = 4√2, lb = √2, log mean 3√2 / ln 4 = 3.06, linear size
        // 8 ln 4 / (3√2) = 2.61.
        let r2 = 2f64.sqrt();
        assert!((u.edge_length_max - 3.0 * r2 / 4f64.ln()).abs() < 1e-12);
        assert!((l.edge_length_max - 8.0 * 4f64.ln() / (3.0 * r2)).abs() < 1e-12);
        assert_eq!(u.mean_ratio_min, l.mean_ratio_min);
    }
}
