//! The operator context: the mesh, its metric and P1 fields, an optional metric source, the
//! operator parameters and a per-pass workspace (scratch kept apart from the mesh data;
//! `workspace.rs`). Here: the metric and quality queries the operators' checks make, and the
//! vertex class (free, on a labelled curve, fixed).

use super::kernel;
use crate::adapt::params::{MetricInterpolation, OpParams};
use crate::adapt::sources::MetricSource;
use crate::geom::DVec2;
use crate::mesh::{next, prev, Mesh2, NONE};
use crate::metric::length::geometric_mean_length;
use crate::metric::Sym2;
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};

/// `tq` entry of a triangle whose quality is not known.
pub(super) const Q_UNKNOWN: u64 = 0x7ff8_0000_0000_0000; // f64::NAN

/// `n` cached qualities, none known.
pub(super) fn unknown_qualities(n: usize) -> Vec<AtomicU64> {
    (0..n).map(|_| AtomicU64::new(Q_UNKNOWN)).collect()
}

/// Where a vertex may go: anywhere (`Free`), along one labelled curve (`Curve`, with the label
/// and the two neighbours on the curve), or nowhere (`Fixed`: corner, required, junction).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum VClass {
    /// Interior vertex, no labelled edge: may move anywhere.
    Free,
    /// On one labelled curve (or the boundary) with label `label`, between its two curve
    /// neighbours `ends`.
    Curve { label: i32, ends: [u32; 2] },
    /// Corner, required vertex or junction of curves: never moved or removed.
    Fixed,
}

/// Operator context over borrowed mesh data: what the operators (`refine::pass`,
/// `collapse::pass`, ...) read and change. [`crate::adapt::adapt`] builds one per run.
pub(crate) struct Ctx<'a> {
    /// The mesh being adapted.
    pub mesh: &'a mut Mesh2,
    /// One metric tensor per vertex.
    pub metric: &'a mut Vec<Sym2>,
    /// P1 fields carried through the operations, one value per vertex each.
    pub fields: &'a mut [Vec<f64>],
    /// Where the metric and fields at new or moved vertices come from, when given.
    pub source: Option<&'a dyn MetricSource>,
    /// The operator parameters.
    pub params: OpParams,
    /// Per-triangle pass stamp (a triangle touched in the current pass has `tstamp == gen`).
    pub(crate) tstamp: Vec<u32>,
    /// Per-vertex pass stamp.
    pub(crate) vstamp: Vec<u32>,
    /// Per-vertex generation of the last change of its ball (a triangle holding it was touched):
    /// vertex passes skip vertices with `vmod < since` without walking their fans.
    pub(crate) vmod: Vec<u32>,
    /// Every triangle touched, in order (with repeats): the split and flip passes examine only
    /// the entries logged since their previous pass (`split_pos`, `flip_pos`), so a pass costs
    /// what changed, not the mesh size.
    pub(crate) log: Vec<u32>,
    /// Position in `log` up to which the refinement passes have examined it.
    pub(crate) split_pos: usize,
    /// Position in `log` up to which the flip passes have examined it.
    pub(crate) flip_pos: usize,
    /// Per-triangle visit mark of the current pass (deduplicates log entries).
    pub(crate) tseen: Vec<u32>,
    /// Cached `Q_ani` per triangle as `f64` bits (NaN: not known; `touch` forgets it). Most
    /// operator checks compare against the current quality of unchanged triangles. Atomic so
    /// that parallel checks may fill it (every writer stores the same value).
    pub(crate) tq: Vec<AtomicU64>,
    /// The generation of the current pass (see [`Ctx::new_pass`]).
    pub(crate) gen: u32,
    /// Logarithms of the vertex metrics (element metrics are `exp` of their mean).
    pub(crate) logm: Vec<Sym2>,
    /// Generation of the last smoothing / collapse pass: only vertices modified since are examined.
    pub(crate) last_smooth: u32,
    /// Generation of the last collapse pass.
    pub(crate) last_collapse: u32,
    /// Use the arithmetic-mean element metric in operator decisions (faster; the default). Set
    /// with `Ctx::exact_quality` (tests).
    pub(crate) fast_q: bool,
    /// The counter-clockwise fan of the vertex being examined ([`Ctx::load_fan`]).
    pub(crate) fan: Vec<u32>,
    /// The fan of the second vertex of a collapse check.
    pub(crate) fan2: Vec<u32>,
    /// The field values at a new or moved vertex, before the edit stores them.
    pub(crate) scratch_f: Vec<f64>,
}

impl<'a> Ctx<'a> {
    /// A context; the caller guarantees `metric.len() == mesh.n_points()` and the same for each
    /// field (the driver validates this).
    pub(crate) fn new(
        mesh: &'a mut Mesh2,
        metric: &'a mut Vec<Sym2>,
        fields: &'a mut [Vec<f64>],
        source: Option<&'a dyn MetricSource>,
        params: OpParams,
    ) -> Ctx<'a> {
        let (nt, nv) = (mesh.n_tris(), mesh.n_points());
        let nf = fields.len();
        // Log-metrics are only kept for the exact (log-Euclidean) element metric; see `fast_q`.
        let logm = Vec::new();
        let _ = &metric;
        Ctx {
            mesh,
            metric,
            fields,
            source,
            params,
            tstamp: vec![0; nt],
            vstamp: vec![0; nv],
            vmod: vec![0; nv],
            log: (0..nt as u32).collect(),
            split_pos: 0,
            flip_pos: 0,
            tseen: vec![0; nt],
            tq: unknown_qualities(nt),
            gen: 1,
            logm,
            last_smooth: 0,
            last_collapse: 0,
            fast_q: true,
            fan: Vec::with_capacity(16),
            fan2: Vec::with_capacity(16),
            scratch_f: vec![0.0; nf],
        }
    }

    /// Makes the operators judge quality with the log-Euclidean element metric
    /// ([`crate::metric::element_metric`]) instead of the arithmetic mean (slower).
    #[cfg(test)]
    pub(crate) fn exact_quality(mut self) -> Self {
        use rayon::prelude::*;
        self.logm = self.metric.par_iter().map(|m| m.log()).collect();
        self.fast_q = false;
        self
    }

    /// The position of vertex `v`.
    #[inline]
    pub(crate) fn p(&self, v: u32) -> DVec2 {
        self.mesh.points[v as usize]
    }

    /// The metric of vertex `v`.
    #[inline]
    pub(crate) fn m(&self, v: u32) -> &Sym2 {
        &self.metric[v as usize]
    }

    /// The lengths of the edge vector `b - a` in the metrics of `a` and of `b`.
    #[inline]
    pub(crate) fn end_lengths(&self, a: u32, b: u32) -> (f64, f64) {
        let e = self.p(b) - self.p(a);
        (self.m(a).quad(e).sqrt(), self.m(b).quad(e).sqrt())
    }

    /// The metric length of `(a, b)` (004 §3.3, [`crate::metric::edge_length`]) if it exceeds
    /// `l`, else `None`. The length is the
    /// logarithmic mean of the end lengths, which lies between their geometric and arithmetic
    /// means: most edges are decided by those bounds without the logarithm.
    #[inline]
    pub(crate) fn len_if_above(&self, a: u32, b: u32, l: f64) -> Option<f64> {
        let (la, lb) = self.end_lengths(a, b);
        if 0.5 * (la + lb) < l * (1.0 - 1e-12) {
            return None;
        }
        let len = geometric_mean_length(la, lb);
        (len > l).then_some(len)
    }

    /// The metric length of `(a, b)` if it is below `l`, else `None` (see [`Ctx::len_if_above`]).
    #[inline]
    pub(crate) fn len_if_below(&self, a: u32, b: u32, l: f64) -> Option<f64> {
        let (la, lb) = self.end_lengths(a, b);
        if (la * lb).sqrt() > l * (1.0 + 1e-12) {
            return None;
        }
        let len = geometric_mean_length(la, lb);
        (len < l).then_some(len)
    }

    /// `Q_ani` of the triangle `(a, b, c)` at its current positions.
    #[inline]
    pub(crate) fn q(&self, tri: [u32; 3]) -> f64 {
        if self.fast_q {
            kernel::q_ani_mean(tri.map(|v| self.p(v)), tri.map(|v| self.m(v)))
        } else {
            kernel::q_ani_log(tri.map(|v| self.p(v)), tri.map(|v| &self.logm[v as usize]))
        }
    }

    /// `Q_ani` of the live triangle `t` as it is now (cached until the triangle is touched).
    #[inline]
    pub(crate) fn q_tri(&self, t: u32) -> f64 {
        let c = &self.tq[t as usize];
        let q = f64::from_bits(c.load(Relaxed));
        if !q.is_nan() {
            return q;
        }
        let q = self.q(self.mesh.tris[t as usize]);
        c.store(q.to_bits(), Relaxed);
        q
    }

    /// Caches `q`, the arithmetic-mean `Q_ani` ([`kernel::q_ani_mean`]) of the live triangle `t`
    /// as it is now, when that is the quality the operators use (no effect under
    /// `Ctx::exact_quality` (tests)).
    #[inline]
    pub(crate) fn set_fast_q(&mut self, t: u32, q: f64) {
        if self.fast_q {
            self.set_q(t, q);
        }
    }

    /// Caches `q`, which must be [`Ctx::q`] of the live triangle `t` as it is now (checked in
    /// debug builds; `cached_qualities_are_exact` checks it in release).
    #[inline]
    pub(crate) fn set_q(&mut self, t: u32, q: f64) {
        debug_assert_eq!(q.to_bits(), self.q(self.mesh.tris[t as usize]).to_bits());
        *self.tq[t as usize].get_mut() = q.to_bits();
    }

    /// `Q_ani` of the triangle `(a, b, c)` where vertex `v` is put at `pv` with log-metric `lv`.
    #[inline]
    pub(crate) fn q_moved(&self, tri: [u32; 3], v: u32, pv: DVec2, mv: &Sym2, lv: &Sym2) -> f64 {
        let p = tri.map(|w| if w == v { pv } else { self.p(w) });
        if self.fast_q {
            let m = tri.map(|w| if w == v { mv } else { self.m(w) });
            return kernel::q_ani_mean(p, m);
        }
        let l = tri.map(|w| if w == v { lv } else { &self.logm[w as usize] });
        kernel::q_ani_log(p, l)
    }

    /// Fills `self.fan` with the counter-clockwise fan of `v`.
    pub(crate) fn load_fan(&mut self, v: u32) {
        let mut fan = std::mem::take(&mut self.fan);
        fan.clear();
        self.mesh.for_each_fan_triangle(v, |t| fan.push(t));
        self.fan = fan;
    }

    /// The class of `v` (its fan must be loaded in `self.fan`).
    pub(crate) fn vclass(&self, v: u32) -> VClass {
        self.vclass_in(v, &self.fan)
    }

    /// The class of `v` whose fan is `fan`.
    pub(crate) fn vclass_in(&self, v: u32, fan: &[u32]) -> VClass {
        let vu = v as usize;
        if self.mesh.corner[vu] || self.mesh.required[vu] {
            return VClass::Fixed;
        }
        let mut n = 0;
        let mut ends = [NONE; 2];
        let mut labels = [0i32; 2];
        for &t in fan {
            let t = t as usize;
            let tri = self.mesh.tris[t];
            let i = local(tri, v);
            // Edge v -> tri[next(i)] is local prev(i); edge v -> tri[prev(i)] is local next(i).
            for (e, w) in [(prev(i), tri[next(i)]), (next(i), tri[prev(i)])] {
                let nb = self.mesh.neighbours[t][e];
                let lab = self.mesh.edge_ref[t][e];
                // An interior labelled edge is seen from both sides; count it once.
                let counted = nb == NONE || (lab != 0 && e == prev(i));
                if counted {
                    if n < 2 {
                        ends[n] = w;
                        labels[n] = lab;
                    }
                    n += 1;
                }
            }
        }
        match n {
            0 => VClass::Free,
            2 if labels[0] == labels[1] => VClass::Curve {
                label: labels[0],
                ends,
            },
            _ => VClass::Fixed,
        }
    }

    /// Metric and field values at `p` from the source, or interpolated with `weights` over
    /// `verts` (metric by `params.interpolation`, fields linear). Field values go to `self.scratch_f`.
    pub(crate) fn sample(&mut self, p: DVec2, verts: &[u32], weights: &[f64]) -> Sym2 {
        let (m, fields_done) = match self.source {
            Some(s) => (s.metric_at(p), s.fields_at(p, &mut self.scratch_f)),
            None => (None, false),
        };
        if !fields_done {
            for (k, f) in self.fields.iter().enumerate() {
                self.scratch_f[k] = verts
                    .iter()
                    .zip(weights)
                    .map(|(&v, &w)| w * f[v as usize])
                    .sum();
            }
        }
        match m {
            Some(m) => m,
            None => self.interpolate_metric(verts, weights),
        }
    }

    /// The metric interpolated with `weights` over `verts` (at most three) by the rule of
    /// `params.interpolation`: log-Euclidean, or linear sizes applied pairwise `((v0, v1), v2)`.
    pub(crate) fn interpolate_metric(&self, verts: &[u32], weights: &[f64]) -> Sym2 {
        let m = |k: usize| &self.metric[verts[k] as usize];
        match (self.params.interpolation, verts.len()) {
            (_, 0) => Sym2::IDENTITY,
            (_, 1) => *m(0),
            (MetricInterpolation::LinearSizes, n) => {
                let (w0, w1) = (weights[0], weights[1]);
                let s01 = if w0 + w1 > 0.0 { w1 / (w0 + w1) } else { 0.5 };
                let m01 = crate::metric::lerp_sizes(m(0), m(1), s01);
                if n == 2 {
                    m01
                } else {
                    crate::metric::lerp_sizes(&m01, m(2), weights[2])
                }
            }
            (MetricInterpolation::LogEuclidean, n) => {
                let mut w: [(f64, &Sym2); 3] = [(0.0, &self.metric[0]); 3];
                for (k, (&v, &wt)) in verts.iter().zip(weights).take(3).enumerate() {
                    w[k] = (wt, &self.metric[v as usize]);
                }
                kernel::interpolate(&w[..n.min(3)])
            }
        }
    }
}

/// Local index of `v` in `tri` (the caller knows it is there).
pub(crate) use crate::mesh::local_index_of as local;
