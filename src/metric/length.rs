//! Lengths, element quality and mesh quality statistics in a metric (004 §3.3–3.4).
//!
//! **Edge length.** 004 §3.3 defines `|γ|_M = ∫_0^1 sqrt(γ'(t)^T M(γ(t)) γ'(t)) dt`. For a straight
//! edge `e = b - a` with metrics known only at its ends, the length density is interpolated
//! *geometrically*: `ℓ(t) = ℓ_a^{1-t} ℓ_b^t` with `ℓ_a = |e|_{M_a}`, `ℓ_b = |e|_{M_b}` (the size
//! varies geometrically along the edge, as gradation assumes), which integrates exactly to
//!
//! ```text
//! |e|_M = ∫_0^1 ℓ_a^{1-t} ℓ_b^t dt = (ℓ_a - ℓ_b) / ln(ℓ_a / ℓ_b),   = ℓ_a when ℓ_a = ℓ_b.
//! ```
//!
//! It lies between the geometric and the arithmetic mean of `ℓ_a`, `ℓ_b` (Alauzet & Frey,
//! "Anisotropic mesh adaptation for CFD computations", 2010).
//!
//! **Element quality.** 004 §3.4:
//!
//! ```text
//! Q_ani(K) = α_d (Σ_i e_i^T M_K e_i)^{d/2} / (|K| sqrt(det M_K)),   α_2 = sqrt(3) / 12,
//! ```
//!
//! so that `Q_ani = 1` for an equilateral triangle of unit edge length in `M_K` (`Σ = 3`,
//! `|K| sqrt(det M_K) = sqrt(3)/4`) and `Q_ani >= 1` otherwise. In 3D the sum runs over the six
//! edges and `α_3 = sqrt(3) / 216` (a regular tetrahedron of unit edges: `Σ = 6`,
//! `|K| = sqrt(2)/12`). `M_K` is the log-Euclidean mean of
//! the three vertex metrics ([`element_metric`]). `Q_ani` is invariant under any affine map `F`
//! that carries the metric along (`M' = A^{-T} M A^{-1}` for `F(x) = A x + c`, `det A > 0`).

use rayon::prelude::*;

use super::interpolate::interpolate_log;
use super::{Sym2, SymTensor};
use crate::geom::simplex::{self, simplex_edges};
#[cfg(test)]
use crate::geom::DVec2;
use crate::mesh::Mesh2;

/// `α_2 = sqrt(3) / 12`, the normalisation of [`q_ani`] (004 §3.4).
pub const ALPHA_2: f64 = 0.144_337_567_297_406_43;

/// `α_3 = sqrt(3) / 216`, the normalisation of [`q_ani`] on tetrahedra.
pub const ALPHA_3: f64 = 0.008_018_753_738_744_801;

/// Lower end of the unit-length interval `[1/sqrt(2), sqrt(2)]`.
pub const L_MIN: f64 = std::f64::consts::FRAC_1_SQRT_2;
/// Upper end of the unit-length interval `[1/sqrt(2), sqrt(2)]`.
pub const L_MAX: f64 = std::f64::consts::SQRT_2;

/// Length of the edge `[pa, pb]` in the metric field with end values `ma`, `mb`, with the length
/// density interpolated geometrically: `(ℓ_a - ℓ_b) / ln(ℓ_a / ℓ_b)` where `ℓ_a = |pb - pa|_{ma}`,
/// `ℓ_b = |pb - pa|_{mb}` (`ℓ_a` when they are equal; see the module documentation).
pub fn edge_length<const D: usize, S: SymTensor<D>>(pa: S::Vec, pb: S::Vec, ma: &S, mb: &S) -> f64 {
    let e = pb - pa;
    geometric_mean_length(ma.quad(e).sqrt(), mb.quad(e).sqrt())
}

/// `∫_0^1 la^{1-t} lb^t dt = la (r - 1) / ln r` with `r = lb / la`, evaluated through `ln_1p` so
/// that it is accurate when `r` is close to one.
#[inline]
pub fn geometric_mean_length(la: f64, lb: f64) -> f64 {
    if la == lb {
        return la;
    }
    if la == 0.0 || lb == 0.0 {
        // The density la^{1-t} 0^t vanishes for t > 0.
        return 0.0;
    }
    let (lo, hi) = if la < lb { (la, lb) } else { (lb, la) };
    let x = hi / lo - 1.0;
    if x < 1.0 / 32.0 {
        // Near r = 1 (most edges) a polynomial is cheaper than `ln_1p` and a division.
        return lo * gregory(x);
    }
    lo * x / x.ln_1p()
}

/// `x / ln(1 + x)` for `0 <= x < 1/32` by its Taylor series (the Gregory coefficients
/// 1, 1/2, −1/12, 1/24, −19/720, 3/160, −863/60480, 275/24192, −33953/3628800, 8183/1036800),
/// truncated where the next term is below `1e-17` of the sum.
#[inline]
fn gregory(x: f64) -> f64 {
    const C: [f64; 10] = [
        1.0,
        1.0 / 2.0,
        -1.0 / 12.0,
        1.0 / 24.0,
        -19.0 / 720.0,
        3.0 / 160.0,
        -863.0 / 60480.0,
        275.0 / 24192.0,
        -33953.0 / 3628800.0,
        8183.0 / 1036800.0,
    ];
    C.iter().rev().fold(0.0, |acc, &c| acc * x + c)
}

/// The edge length of the UGAWG measures (the `MEASURES.md` of the UGAWG adapt-benchmarks, the
/// rule by which the UGAWG study rated every adaptor): the geometric-density length
/// [`geometric_mean_length`] when `|la - lb| > 1e-3`, the arithmetic mean of `la`, `lb`
/// otherwise (Omega_h's tolerance). Use it to compare a mesh with the study's published shares.
#[inline]
pub fn ugawg_length(la: f64, lb: f64) -> f64 {
    if (la - lb).abs() > UGAWG_LENGTH_EPS {
        geometric_mean_length(la, lb)
    } else {
        0.5 * (la + lb)
    }
}

/// The tolerance on `|la - lb|` below which [`ugawg_length`] takes the arithmetic mean.
pub const UGAWG_LENGTH_EPS: f64 = 1e-3;

/// `∫_0^1 dt / ((1-t)/la + t/lb) = la lb ln(la/lb) / (la - lb)`: the edge length when the size
/// along the edge, `1/ℓ(t)`, varies linearly between the ends (as mmg interpolates sizes between
/// vertices, and as eq. (6)'s sizes grow with the distance outside the band). Between the
/// harmonic and the geometric mean of `la`, `lb`; `la` when they are equal; evaluated through
/// `ln_1p`. The rule of [`crate::metric::conformity()`] (`docs/tools.md` compares the rules).
#[inline]
pub fn linear_size_length(la: f64, lb: f64) -> f64 {
    if la == lb {
        return la;
    }
    if la == 0.0 || lb == 0.0 {
        return 0.0;
    }
    let (lo, hi) = if la < lb { (la, lb) } else { (lb, la) };
    let x = hi / lo - 1.0;
    hi * x.ln_1p() / x
}

/// `Q_ani` of the simplex `p` (triangle or tetrahedron) in the metric `m` (004 §3.4):
/// `α_d (Σ_i e_i^T m e_i)^{d/2} / (|K| sqrt(det m))` over the edges `e_i`, with `α_2 = sqrt(3)/12`
/// and `α_3 = sqrt(3)/216`. Equals 1 for a regular simplex of unit edges in `m`, is larger
/// otherwise, and is `+inf` when the signed volume is not positive.
pub fn q_ani<const D: usize, const N: usize, S: SymTensor<D>>(p: [S::Vec; N], m: &S) -> f64 {
    let vol = simplex::volume(&p);
    if vol.is_nan() || vol <= 0.0 {
        return f64::INFINITY;
    }
    let edges = simplex_edges(N);
    let [a, b] = edges[0];
    let mut s = m.quad(p[b] - p[a]);
    for &[a, b] in &edges[1..] {
        s += m.quad(p[b] - p[a]);
    }
    if D == 2 {
        ALPHA_2 * s / (vol * m.det().sqrt())
    } else {
        ALPHA_3 * (s * s.sqrt()) / (vol * m.det().sqrt())
    }
}

/// The element metric `M_K` (004 §3.3): log-Euclidean mean of the vertex metrics of a simplex.
pub fn element_metric<const D: usize, const N: usize, S: SymTensor<D>>(m: [&S; N]) -> S {
    interpolate_log(&m.map(|x| (1.0, *x)))
}

/// Upper bounds of the bins of [`QualityStats::q_ani_histogram`].
pub const Q_ANI_BINS: [f64; 9] = [1.05, 1.1, 1.25, 1.5, 2.0, 3.0, 5.0, 10.0, f64::INFINITY];

/// How well a mesh matches a metric field: edge lengths and `Q_ani` (004 §3.4–3.5).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct QualityStats {
    /// Number of edges measured.
    pub edges: usize,
    /// Share of edges whose metric length is in `[1/sqrt(2), sqrt(2)]`.
    pub edge_length_in_range: f64,
    /// Smallest metric edge length.
    pub edge_length_min: f64,
    /// Largest metric edge length.
    pub edge_length_max: f64,
    /// Number of triangles measured.
    pub tris: usize,
    /// Mean of `Q_ani` over the triangles (`+inf` if any triangle is inverted).
    pub q_ani_mean: f64,
    /// Largest `Q_ani` (the worst triangle).
    pub q_ani_max: f64,
    /// Index of the triangle with the largest `Q_ani` (the first one on ties).
    pub worst_tri: usize,
    /// `(upper bound, count)`: triangles with `Q_ani` in `(previous bound, bound]`
    /// (bounds [`Q_ANI_BINS`]).
    pub q_ani_histogram: Vec<(f64, usize)>,
}

/// Work below which the statistics are computed sequentially.
const PAR_MIN: usize = 4096;

/// Edge-length and `Q_ani` statistics of the live triangles of `mesh` in the vertex metric field
/// `metric` (edges with [`edge_length`], elements with [`q_ani`] in [`element_metric`]).
///
/// `metric` should hold one SPD tensor per vertex (check with [`super::validate_field`]); edges and
/// triangles that touch a vertex without an entry are skipped (and so not counted). Runs in
/// parallel on large meshes; the result does not depend on the thread count. An empty mesh gives
/// zero counts and zero values.
pub fn quality_stats(mesh: &Mesh2, metric: &[Sym2]) -> QualityStats {
    let n = metric.len();
    let edges: Vec<[u32; 2]> = mesh
        .edges()
        .into_iter()
        .map(|(e, _, _)| e)
        .filter(|e| (e[1] as usize) < n)
        .collect();
    let len = |e: &[u32; 2]| {
        let (a, b) = (e[0] as usize, e[1] as usize);
        edge_length(mesh.points[a], mesh.points[b], &metric[a], &metric[b])
    };
    let lengths: Vec<f64> = if edges.len() >= PAR_MIN {
        edges.par_iter().map(len).collect()
    } else {
        edges.iter().map(len).collect()
    };
    let tris: Vec<usize> = mesh
        .live_tris()
        .filter(|&t| mesh.tris[t].iter().all(|&v| (v as usize) < n))
        .collect();
    let qual = |&t: &usize| {
        let [a, b, c] = mesh.tris[t].map(|v| v as usize);
        q_ani(
            mesh.tri_points(t),
            &element_metric([&metric[a], &metric[b], &metric[c]]),
        )
    };
    let q: Vec<f64> = if tris.len() >= PAR_MIN {
        tris.par_iter().map(qual).collect()
    } else {
        tris.iter().map(qual).collect()
    };

    let mut s = QualityStats {
        edges: lengths.len(),
        tris: q.len(),
        q_ani_histogram: Q_ANI_BINS.iter().map(|&b| (b, 0)).collect(),
        ..QualityStats::default()
    };
    if !lengths.is_empty() {
        let in_range = lengths
            .iter()
            .filter(|&&l| (L_MIN..=L_MAX).contains(&l))
            .count();
        s.edge_length_in_range = in_range as f64 / lengths.len() as f64;
        s.edge_length_min = lengths.iter().copied().fold(f64::INFINITY, f64::min);
        s.edge_length_max = lengths.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    }
    if !q.is_empty() {
        s.q_ani_mean = q.iter().sum::<f64>() / q.len() as f64;
        let (mut worst, mut qmax) = (0, f64::NEG_INFINITY);
        for (i, &qi) in q.iter().enumerate() {
            if qi > qmax || (qi.is_nan() && !qmax.is_nan()) {
                worst = i;
                qmax = qi;
            }
            let bin = Q_ANI_BINS
                .iter()
                .position(|&b| qi <= b)
                .unwrap_or(Q_ANI_BINS.len() - 1);
            s.q_ani_histogram[bin].1 += 1;
        }
        s.q_ani_max = qmax;
        s.worst_tri = tris[worst];
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gregory_series_matches_the_logarithm() {
        // Both forms of x / ln(1 + x) on [0, 1/32]: the series to the last bits.
        let mut worst = 0.0f64;
        for k in 1..=4000 {
            let x = k as f64 / 4000.0 / 32.0;
            let exact = x / x.ln_1p();
            worst = worst.max((gregory(x) / exact - 1.0).abs());
        }
        eprintln!("x / ln(1 + x) series: relative difference {worst:.1e}");
        assert!(worst < 4.0 * f64::EPSILON, "{worst:e}");
        // Continuous across the switch at r = 1 + 1/32.
        let r = 1.0 + 1.0 / 32.0;
        let (below, above) = (
            geometric_mean_length(1.0, r * (1.0 - 1e-15)),
            geometric_mean_length(1.0, r * (1.0 + 1e-15)),
        );
        assert!((above - below).abs() < 1e-14, "{below} {above}");
    }

    #[test]
    fn alpha_2_value() {
        assert!((ALPHA_2 - 3f64.sqrt() / 12.0).abs() < 1e-17);
        assert!((ALPHA_3 - 3f64.sqrt() / 216.0).abs() < 1e-18);
    }

    #[test]
    fn q_ani_of_tetrahedra() {
        use crate::geom::DVec3;
        use crate::metric::Sym3;
        // Regular tetrahedron of edge h: Q_ani = 1 in the isotropic metric of any size.
        let h = 0.3;
        let p = [
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(1.0, -1.0, -1.0),
            DVec3::new(-1.0, 1.0, -1.0),
            DVec3::new(-1.0, -1.0, 1.0),
        ]
        .map(|x| x * (h / 8f64.sqrt()));
        let p = [p[0], p[1], p[3], p[2]];
        assert!(simplex::volume(&p) > 0.0);
        for size in [h, 5.0] {
            assert!((q_ani(p, &Sym3::iso(size)) - 1.0).abs() < 1e-13);
        }
        // The unit right tetrahedron: Σ = 3 + 3·2 = 9, |K| = 1/6 → α_3 27 · 6.
        let r = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        assert!((q_ani(r, &Sym3::IDENTITY) - ALPHA_3 * 27.0 * 6.0).abs() < 1e-13);
        assert_eq!(
            q_ani([r[1], r[0], r[2], r[3]], &Sym3::IDENTITY),
            f64::INFINITY
        );
    }

    #[test]
    fn edge_length_formula() {
        let m = Sym2::iso(0.1);
        let (a, b) = (DVec2::ZERO, DVec2::new(0.3, 0.4));
        assert!((edge_length(a, b, &m, &m) - 5.0).abs() < 1e-14);
        // Sizes 0.1 and 0.4 at the ends: ℓ_a = 5, ℓ_b = 1.25; (5 - 1.25) / ln 4.
        let l = edge_length(a, b, &m, &Sym2::iso(0.4));
        assert!((l - 3.75 / 4f64.ln()).abs() < 1e-14);
        assert!((edge_length(b, a, &Sym2::iso(0.4), &m) - l).abs() < 1e-15);
        // Nearly equal ends: continuous (no 0/0).
        let l = geometric_mean_length(2.0, 2.0 * (1.0 + 1e-13));
        assert!((l - 2.0 * (1.0 + 0.5e-13)).abs() < 1e-15);
        // Exact against a fine quadrature of ℓ_a^{1-t} ℓ_b^t.
        let (la, lb) = (0.3_f64, 7.0_f64);
        let n = 20000;
        let quad: f64 = (0..n)
            .map(|k| {
                let t = (k as f64 + 0.5) / n as f64;
                la.powf(1.0 - t) * lb.powf(t)
            })
            .sum::<f64>()
            / n as f64;
        assert!((geometric_mean_length(la, lb) - quad).abs() < 1e-7);
    }

    #[test]
    fn q_ani_equilateral_and_degenerate() {
        let h = 0.01;
        let p = [
            DVec2::ZERO,
            DVec2::new(h, 0.0),
            DVec2::new(0.5 * h, 0.5 * 3f64.sqrt() * h),
        ];
        assert!((q_ani(p, &Sym2::iso(h)) - 1.0).abs() < 1e-13);
        // Same triangle, any isotropic scaling: still 1 (scale invariance).
        assert!((q_ani(p, &Sym2::iso(7.0)) - 1.0).abs() < 1e-13);
        // Right isosceles triangle: Σ = 4 h², |K| = h²/2 → 8 α_2 = 2/sqrt(3).
        let r = [DVec2::ZERO, DVec2::new(h, 0.0), DVec2::new(0.0, h)];
        assert!((q_ani(r, &Sym2::iso(h)) - 2.0 / 3f64.sqrt()).abs() < 1e-13);
        assert_eq!(q_ani([p[0], p[2], p[1]], &Sym2::iso(h)), f64::INFINITY);
        assert_eq!(q_ani([p[0], p[1], p[1]], &Sym2::iso(h)), f64::INFINITY);
    }

    #[test]
    fn stats_on_a_grid() {
        use crate::mesh::GridPattern;
        let mesh = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 4, 4, GridPattern::Right).unwrap();
        // The metric that makes the "Right" grid a unit mesh: |(h,0)| = |(0,h)| = |(h,h)| = 1.
        let h = 0.25;
        let m = Sym2::new(1.0, -0.5, 1.0).scale(1.0 / (h * h));
        let metric = vec![m; mesh.n_points()];
        let s = quality_stats(&mesh, &metric);
        assert_eq!(s.edges, 3 * 16 + 8);
        assert_eq!(s.tris, 32);
        assert!((s.edge_length_min - 1.0).abs() < 1e-12 && (s.edge_length_max - 1.0).abs() < 1e-12);
        assert_eq!(s.edge_length_in_range, 1.0);
        assert!((s.q_ani_max - 1.0).abs() < 1e-12 && (s.q_ani_mean - 1.0).abs() < 1e-12);
        assert_eq!(s.q_ani_histogram[0].1, 32);
        // Isotropic metric: edges of length 1 and sqrt(2), Q_ani = 2/sqrt(3) everywhere.
        let s = quality_stats(&mesh, &vec![Sym2::iso(h); mesh.n_points()]);
        assert!((s.edge_length_max - 2f64.sqrt()).abs() < 1e-12);
        assert!((s.q_ani_mean - 2.0 / 3f64.sqrt()).abs() < 1e-12);
        // Missing metric entries: those edges are skipped.
        let s = quality_stats(&mesh, &metric[..5]);
        assert_eq!((s.edges, s.tris), (4, 0));
    }
}
