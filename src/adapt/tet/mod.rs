//! The tetrahedral operators (004 §3.5 and §5) on [`crate::mesh3::EditMesh3`], driven by a vertex
//! metric field of [`Sym3`] tensors:
//! - this file: the operator context [`Ctx`] (mesh, metric, optional metric source, lengths and
//!   quality in the metric, pass stamps) and its [`Remesher`] implementation, so that the shared
//!   cycle ([`super::cycle::run_cycles`]) drives the tetrahedral operators as it drives the
//!   triangle ones;
//! - `split.rs` (split long edges at their metric midpoint), `collapse.rs` (collapse short
//!   edges), `swap.rs` (edge removal n → 2n − 4 and face 2-3 swaps, in the place of the 2D flips:
//!   a topology without a 2D analogue), `smooth.rs` (move vertices): each implements
//!   [`super::pass::Operator`] with a pure `check` (metric and quality on the current state) and
//!   an `apply` that calls the edits of [`crate::mesh3::EditMesh3`];
//! - `run.rs`: the fixed point in 3D ([`run3`]) and its report.
//!
//! The quality is the mean ratio in the metric, `12 (3 |K|_M)^{2/3} / Σ l_M(e)²` (1 for a
//! regular tetrahedron of the metric, 0 when flat), with `M` the arithmetic mean of the four
//! vertex metrics; it equals `Q_ani^{-2/3}` of 004 §3.4 for that `M`.

pub(crate) mod collapse;
pub(crate) mod conform;
pub(crate) mod improve;
pub(crate) mod merge;
pub mod run;
pub(crate) mod smooth;
pub(crate) mod split;
pub mod stats;
pub(crate) mod swap;
pub(crate) mod sweep;

use super::cycle::Remesher;
use super::options::PassKind;
use crate::error::{Error, Result};
use crate::geom::DVec3;
use crate::mesh3::{hilbert_order, EditMesh3};
use crate::metric::length::geometric_mean_length;
use crate::metric::{lerp_log, Sym3};

/// A metric given as a function of position (exact, re-evaluated at every new or moved vertex).
pub type MetricFn3<'a> = &'a (dyn Fn(DVec3) -> Sym3 + Sync);

/// The operator context: the mesh, its vertex metric, where new metrics come from, the length
/// bounds and the pass stamps that make each pass change an independent set.
pub(crate) struct Ctx<'a> {
    pub mesh: EditMesh3,
    pub metric: Vec<Sym3>,
    pub source: Option<MetricFn3<'a>>,
    pub l_min: f64,
    pub l_max: f64,
    /// Quality floor of collapses and moves (mean ratio): a change may not create a
    /// tetrahedron worse than this unless the ball was already worse.
    pub q_min: f64,
    /// Per vertex: the pass that last changed its ball (or moved a neighbour).
    pub stamp: Vec<u32>,
    pub pass: u32,
    /// Per operator ([`Op`]): the pass at which it last started; it examines only what changed
    /// since then.
    pub last: [u32; 5],
    /// Quality of every tetrahedron at the start of the current swap pass (survey only).
    pub tq: Vec<f64>,
    /// The insertion filter of the refinement passes: a split of an edge with an interior
    /// end is refused when its new point is closer than this (metric length) to a vertex
    /// inserted earlier in the same pass ([`split`]); 0 turns the filter off.
    pub split_filter: f64,
    /// The first vertex index created in the current split pass.
    pub first_new: u32,
}

impl<'a> Ctx<'a> {
    pub fn new(mesh: EditMesh3, metric: Vec<Sym3>, source: Option<MetricFn3<'a>>) -> Ctx<'a> {
        let n = mesh.points.len();
        Ctx {
            mesh,
            metric,
            source,
            l_min: std::f64::consts::FRAC_1_SQRT_2,
            l_max: std::f64::consts::SQRT_2,
            q_min: 0.3,
            stamp: vec![0; n],
            pass: 0,
            last: [0; 5],
            tq: Vec::new(),
            split_filter: split::FILTER,
            first_new: 0,
        }
    }

    /// Starts a pass: a new stamp.
    pub fn next_pass(&mut self) -> u32 {
        self.pass += 1;
        self.mesh.now = self.pass;
        self.pass
    }

    /// Starts a pass of `op` and returns the pass at which `op` last started: the vertices
    /// with a stamp at least that have had their ball changed since `op` last looked at them.
    /// (The metric is exact, so an unchanged ball gives the same verdict as last time.)
    pub fn start(&mut self, op: Op) -> u32 {
        let since = self.last[op as usize];
        if self.stamp.len() < self.mesh.points.len() {
            self.stamp.resize(self.mesh.points.len(), 0);
        }
        self.last[op as usize] = self.next_pass();
        since
    }

    /// Starts a pass of `op` and lists the live vertices changed since its previous pass.
    pub fn changed_vertices(&mut self, op: Op) -> Vec<u32> {
        let since = self.start(op);
        (0..self.mesh.points.len() as u32)
            .filter(|&v| self.mesh.alive(v) && self.stamp[v as usize] >= since)
            .collect()
    }

    /// Marks the vertices of the ball of `v` (and `v`) as changed in this pass.
    pub fn touch_ball(&mut self, v: u32) {
        if self.stamp.len() < self.mesh.points.len() {
            self.stamp.resize(self.mesh.points.len(), 0);
        }
        for &t in &self.mesh.ball[v as usize] {
            for w in self.mesh.tets[t as usize] {
                self.stamp[w as usize] = self.pass;
            }
        }
        self.stamp[v as usize] = self.pass;
    }

    /// Metric length of the edge `(a, b)` (geometric interpolation of the length density,
    /// [`crate::metric::edge_length`]).
    #[inline]
    pub fn length(&self, a: u32, b: u32) -> f64 {
        let e = self.mesh.points[b as usize] - self.mesh.points[a as usize];
        geometric_mean_length(
            self.metric[a as usize].quad(e).sqrt(),
            self.metric[b as usize].quad(e).sqrt(),
        )
    }

    /// Metric length of the segment `pa`–`pb` with end metrics `ma`, `mb`.
    #[inline]
    pub fn length_at(pa: DVec3, pb: DVec3, ma: &Sym3, mb: &Sym3) -> f64 {
        let e = pb - pa;
        geometric_mean_length(ma.quad(e).sqrt(), mb.quad(e).sqrt())
    }

    /// The metric at a new point `p` on the edge `(a, b)` at parameter `t`: from the source, or
    /// log-Euclidean interpolation of the end metrics.
    pub fn metric_on_edge(&self, a: u32, b: u32, t: f64, p: DVec3) -> Sym3 {
        match self.source {
            Some(f) => f(p),
            None => lerp_log(&self.metric[a as usize], &self.metric[b as usize], t),
        }
    }

    /// Quality of the tetrahedron `t` given by vertex indices, with the metric of vertex
    /// `moved` taken as `m_moved` at `p_moved` when it is one of them.
    #[inline]
    pub fn quality_of(&self, t: [u32; 4], moved: Option<(u32, DVec3, &Sym3)>) -> f64 {
        let mut p = [DVec3::ZERO; 4];
        let mut m = [Sym3::default(); 4];
        for k in 0..4 {
            match moved {
                Some((v, pv, mv)) if v == t[k] => {
                    p[k] = pv;
                    m[k] = *mv;
                }
                _ => {
                    p[k] = self.mesh.points[t[k] as usize];
                    m[k] = self.metric[t[k] as usize];
                }
            }
        }
        mean_ratio(p, &m)
    }

    /// Caches in `tq` the quality of every live tetrahedron with a vertex changed since pass
    /// `since` (infinity for the others) and returns those below `q`. Qualities not yet known
    /// are computed (in parallel) and kept in the mesh's per-tetrahedron cache.
    pub fn bad_tets(&mut self, q: f64, since: u32) -> Vec<u32> {
        use rayon::prelude::*;
        let tq: Vec<f64> = (0..self.mesh.tets.len() as u32)
            .into_par_iter()
            .map(|t| {
                let tet = self.mesh.tets[t as usize];
                if tet[0] == crate::mesh::NONE
                    || tet.iter().all(|&v| self.stamp[v as usize] < since)
                {
                    f64::INFINITY
                } else {
                    self.tet_quality(t)
                }
            })
            .collect();
        for (t, &x) in tq.iter().enumerate() {
            if x.is_finite() {
                self.mesh.cache[t] = x;
            }
        }
        self.tq = tq;
        (0..self.tq.len() as u32)
            .filter(|&t| self.tq[t as usize] < q)
            .collect()
    }

    /// Quality of the live tetrahedron with index `t` (from the mesh's cache when known).
    #[inline]
    pub fn tet_quality(&self, t: u32) -> f64 {
        let c = self.mesh.cache[t as usize];
        if c.is_nan() {
            self.quality_of(self.mesh.tets[t as usize], None)
        } else {
            c
        }
    }

    /// Quality of the live tetrahedron with index `t`, kept in the mesh's cache.
    #[inline]
    pub fn cached_quality(&mut self, t: u32) -> f64 {
        let q = self.tet_quality(t);
        self.mesh.cache[t as usize] = q;
        q
    }

    /// The worst `rate` of the tetrahedra of the ball of `v`, or `None` as soon as one is at
    /// most `floor` (most trial positions fail early). The tetrahedron at `first` in the ball
    /// (the last one to fail, or the worst) is rated first, as it is the likeliest to fail
    /// again; `first` is left at the one that failed or the worst. The answer does not depend
    /// on `first`, only the time does.
    pub fn ball_min_above(
        &self,
        v: u32,
        floor: f64,
        first: &mut usize,
        rate: impl Fn([u32; 4]) -> f64,
    ) -> Option<f64> {
        let ball = &self.mesh.ball[v as usize];
        let n = ball.len();
        let (mut q, mut worst) = (f64::INFINITY, *first);
        for k in (0..n).map(|k| (k + *first) % n) {
            let x = rate(self.mesh.tets[ball[k] as usize]);
            if x <= floor {
                *first = k;
                return None;
            }
            if x < q {
                (q, worst) = (x, k);
            }
        }
        *first = worst;
        Some(q)
    }

    /// The worst quality in the ball of `v` and its place in the ball.
    pub fn ball_worst(&self, v: u32) -> (f64, usize) {
        let mut w = (f64::INFINITY, 0);
        for (k, &t) in self.mesh.ball[v as usize].iter().enumerate() {
            let q = self.tet_quality(t);
            if q < w.0 {
                w = (q, k);
            }
        }
        w
    }

    /// The worst quality in the ball of `v`.
    pub fn ball_quality(&self, v: u32) -> f64 {
        self.mesh.ball[v as usize]
            .iter()
            .map(|&t| self.tet_quality(t))
            .fold(f64::INFINITY, f64::min)
    }

    fn renumber_spatially(&mut self) {
        let order = hilbert_order(&self.mesh.points, |v| self.mesh.alive(v as u32));
        let old = self.mesh.compact(Some(&order));
        self.metric = old.iter().map(|&v| self.metric[v as usize]).collect();
        self.stamp
            .resize(self.metric.len().max(self.stamp.len()), 0);
        self.stamp = old.iter().map(|&v| self.stamp[v as usize]).collect();
    }
}

/// The operators, indexing [`Ctx::last`].
#[derive(Debug, Clone, Copy)]
pub(crate) enum Op {
    Split = 0,
    Collapse = 1,
    EdgeRemoval = 2,
    FaceSwap = 3,
    Smooth = 4,
}

/// `x^{-1/3}` for a positive normal `x`, to within a few units in the last place, without a
/// division: a bit-level first guess (within 3.5 %) and three second-order steps
/// `y ← y (1 + r/3 + 2r²/9)`, `r = 1 − x y³` (each cubes the relative error). Other inputs go
/// through `f64::cbrt`.
#[inline]
pub(crate) fn inv_cbrt_pos(x: f64) -> f64 {
    if !(f64::MIN_POSITIVE..=f64::MAX).contains(&x) {
        return 1.0 / x.cbrt();
    }
    // 0x553ef0f78b010000: the constant that makes `C − bits/3` a first guess within 3.5 %.
    let mut y = f64::from_bits(0x553e_f0f7_8b01_0000 - x.to_bits() / 3);
    for _ in 0..3 {
        let r = 1.0 - x * (y * y * y);
        y += y * r * (1.0 / 3.0 + r * (2.0 / 9.0));
    }
    y
}

/// Mean ratio of the tetrahedron `p` in the arithmetic mean of the vertex metrics `m`:
/// `12 (3 |K|_M)^{2/3} / Σ_e e^T M e`, in (0, 1], 1 for a regular tetrahedron of the metric;
/// 0 or negative when `p` is flat or inverted.
pub fn mean_ratio(p: [DVec3; 4], m: &[Sym3; 4]) -> f64 {
    let vol = crate::mesh3::signed_volume(p[0], p[1], p[2], p[3]);
    if vol <= 0.0 {
        return vol;
    }
    // With M4 = 4 M (the sum of the vertex metrics, exact powers of two throughout):
    // Σ_e eᵀ M e = Σ_i d_iᵀ M4 d_i with d_i = p_i − centroid (Σ_{i<j} (p_j − p_i)(p_j − p_i)ᵀ =
    // 4 Σ_i d_i d_iᵀ for four points), and |K|_M = |K| sqrt(det M4) / 8.
    let m4 = m[0].add(&m[1]).add(&m[2]).add(&m[3]);
    let c = (p[0] + p[1] + p[2] + p[3]) * 0.25;
    let s: f64 = p.iter().map(|&q| m4.quad(q - c)).sum();
    // (3 |K|_M)^{2/3} = x · x^{-1/3}.
    let x = 0.375 * vol * m4.det().max(0.0).sqrt();
    if x == 0.0 {
        return 0.0;
    }
    12.0 * x * inv_cbrt_pos(x) / s
}

impl Remesher for Ctx<'_> {
    fn n_vertices(&self) -> usize {
        self.mesh.points.len()
    }

    fn run_pass(&mut self, kind: PassKind) -> usize {
        match kind {
            PassKind::Split => split::pass(self),
            PassKind::Collapse => collapse::pass(self),
            PassKind::Flip => swap::pass(self),
            PassKind::Smooth => smooth::pass(self),
        }
    }

    fn renumber(&mut self) {
        self.renumber_spatially();
    }

    fn grade(&mut self, _beta: f64) -> Result<()> {
        Err(Error::InvalidInput(
            "metric gradation during the adaptation is not available on tetrahedra".into(),
        ))
    }

    fn smoothing_settled(&mut self) {}

    fn check(&self) -> Result<()> {
        self.mesh.check()?;
        if self.metric.len() != self.mesh.points.len() {
            return Err(Error::InvalidInput(format!(
                "{} vertex metrics for {} vertices",
                self.metric.len(),
                self.mesh.points.len()
            )));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::{inv_cbrt_pos, mean_ratio};
    use crate::geom::DVec3;
    use crate::metric::Sym3;

    #[test]
    fn mean_ratio_matches_the_measure_in_one_metric() {
        // In one metric the quality is the UGAWG mean ratio of `anisomesh measure`; a regular
        // tetrahedron of the metric rates 1, an inverted one at most 0.
        let mut worst = 0.0f64;
        for k in 0..200 {
            let t = k as f64;
            let p = [
                DVec3::new(0.1 * t.sin(), 0.0, 0.3),
                DVec3::new(1.0, 0.2 * t.cos(), 0.0),
                DVec3::new(0.3, 1.0 + 0.1 * (2.0 * t).sin(), 0.1),
                DVec3::new(0.2, 0.3, 1.0),
            ]
            .map(|q| 1e-3 * q + DVec3::splat(0.7));
            let m = Sym3::new(1e6, 2e5 * t.cos(), 1e4, 5e5, -1e3 * t, 3e4 + 1e3 * t);
            if !m.is_spd() {
                continue;
            }
            let q = mean_ratio(p, &[m; 4]);
            let r = crate::metric::conformity::mean_ratio(p, &m);
            worst = worst.max((q / r - 1.0).abs());
        }
        assert!(worst < 1e-12, "{worst:e}");
        let s = 2f64.sqrt();
        let reg = [
            DVec3::new(1.0, 0.0, -1.0 / s),
            DVec3::new(-1.0, 0.0, -1.0 / s),
            DVec3::new(0.0, 1.0, 1.0 / s),
            DVec3::new(0.0, -1.0, 1.0 / s),
        ];
        let q = mean_ratio(reg, &[Sym3::IDENTITY; 4]);
        let q = if q < 0.0 {
            mean_ratio([reg[1], reg[0], reg[2], reg[3]], &[Sym3::IDENTITY; 4])
        } else {
            q
        };
        assert!((q - 1.0).abs() < 1e-14, "{q}");
        let flat = [reg[0], reg[1], reg[2], (reg[0] + reg[1]) * 0.5];
        assert!(mean_ratio(flat, &[Sym3::IDENTITY; 4]) <= 0.0);
    }

    #[test]
    fn inverse_cube_root_to_the_last_bits() {
        let mut x = 1e-300;
        let mut worst = 0.0f64;
        while x < 1e300 {
            for y in [x, 1.7 * x, 3.3 * x, 7.9 * x] {
                let c = inv_cbrt_pos(y);
                worst = worst.max((c * y.cbrt() - 1.0).abs());
            }
            x *= 10.0;
        }
        eprintln!("inverse cube root: relative error {worst:.1e}");
        assert!(worst <= 4.0 * f64::EPSILON, "{worst:e}");
        assert_eq!(inv_cbrt_pos(0.0), f64::INFINITY);
        assert!((inv_cbrt_pos(1e-310) * 1e-310f64.cbrt() - 1.0).abs() < 1e-15);
        assert!((inv_cbrt_pos(8.0) - 0.5).abs() <= f64::EPSILON);
    }
}
