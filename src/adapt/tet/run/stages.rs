//! The continuation of [`super::run3`]. For a shape target, the metric of 004 eq. (6) is reached
//! through a sequence of coarser metrics of the same interface, each stage starting from the
//! mesh of the previous one, so that every stage's start mesh is close to its metric (an edge
//! at most about twice too long) instead of the Kuhn start mesh being split toward a metric
//! many times finer in one go. Each stage is reported ([`Stage3`]) with its vertex count, the
//! largest count during its passes, the metric's complexity `∫ sqrt(det M)` on its mesh
//! (004 §3: the number of unit elements the metric asks for) and where its time went.

use serde::Serialize;

use crate::adapt::options::PassKind;
use crate::adapt::tet::Ctx;
use crate::adapt::{AdaptReport, LevelSetMetric};
use crate::mesh3::{signed_volume, EditMesh3};
use crate::metric::{Sym3, SymTensor};

/// How [`super::run3`] reaches a shape's metric from its start mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub enum Continuation3 {
    /// The target metric directly.
    Off,
    /// `hmin` and the band doubled per stage (ε kept): only the normal size is coarser, the
    /// tangential sizes `sqrt(ε/κ)` of every stage are the target's (above the stage's `hmin`).
    Normal,
    /// Every size doubled per stage: ε multiplied by 4, `hmin` and the band by 2 (`hmax`
    /// kept). A stage's metric is the target's with all sizes `2ᵏ` times larger, about `8ᵏ`
    /// times fewer vertices near the surface.
    #[default]
    Sizes,
}

/// One stage of the continuation.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Stage3 {
    /// The stage's sizes relative to the target's (`2ᵏ`; 1 for the target).
    pub scale: f64,
    /// The stage's ε (shape targets).
    pub eps: Option<f64>,
    /// The stage's `hmin` (shape targets) or size floor (metric targets: `2ᵏ` times the
    /// smallest size of the metric at the start vertices, that smallest size itself for the
    /// target stage).
    pub hmin: f64,
    /// The stage's band half-width (shape targets).
    pub band: Option<f64>,
    /// Vertices at the start of the stage.
    pub start_vertices: usize,
    /// Vertices at the end of the stage.
    pub vertices: usize,
    /// The largest vertex count after any of the stage's passes.
    pub peak_vertices: usize,
    /// `∫ sqrt(det M)` of the stage's metric over its final mesh (tetrahedron volume times the
    /// mean of its vertices' `sqrt(det M)`).
    pub complexity: f64,
    /// Passes run.
    pub passes: usize,
    /// Seconds in refinement, collapse, swap and smoothing passes.
    pub seconds: [f64; 4],
}

/// `lm` seen `s` times coarser by `c` (`s = 1`: `lm` itself).
pub(super) fn coarsened(lm: &LevelSetMetric, c: Continuation3, s: f64) -> LevelSetMetric {
    if s == 1.0 {
        return *lm;
    }
    match c {
        Continuation3::Off => *lm,
        Continuation3::Normal => LevelSetMetric {
            hmin: (lm.hmin * s).min(lm.hmax),
            band: lm.band * s,
            ..*lm
        },
        Continuation3::Sizes => LevelSetMetric {
            eps: lm.eps * s * s,
            hmin: (lm.hmin * s).min(lm.hmax),
            band: lm.band * s,
            ..*lm
        },
    }
}

/// The number of stages before the target metric: `hmin` doubled while it stays at most
/// `hmax / 2`, at most four times (`Normal`) or six (`Sizes`).
pub(super) fn stage_count(lm: &LevelSetMetric, c: Continuation3) -> u32 {
    let cap = match c {
        Continuation3::Off => 0,
        Continuation3::Normal => 4,
        Continuation3::Sizes => 6,
    };
    let mut k = 0;
    while k < cap && lm.hmin * f64::from(1u32 << (k + 1)) <= 0.5 * lm.hmax {
        k += 1;
    }
    k
}

/// The scale of the current stage, shared with the metric function (stored as the bits of an
/// `f64`).
#[derive(Debug)]
pub(super) struct Scale(std::sync::atomic::AtomicU64);

impl Default for Scale {
    fn default() -> Self {
        Scale::new(1.0)
    }
}

impl Scale {
    pub(super) fn new(s: f64) -> Scale {
        Scale(std::sync::atomic::AtomicU64::new(s.to_bits()))
    }
    pub(super) fn get(&self) -> f64 {
        f64::from_bits(self.0.load(std::sync::atomic::Ordering::Relaxed))
    }
    pub(super) fn set(&self, s: f64) {
        self.0
            .store(s.to_bits(), std::sync::atomic::Ordering::Relaxed)
    }
}

/// `m` with every size raised to at least `floor` ([`Sym3::bound`] with no upper size and no
/// anisotropy limit); `m` itself when `floor` is 0.
pub(super) fn floored(m: Sym3, floor: f64) -> Sym3 {
    if floor > 0.0 {
        m.bound(floor, f64::INFINITY, f64::INFINITY)
    } else {
        m
    }
}

/// The continuation of a metric target: stages whose metric is the target's with every size
/// raised to at least a floor, `2ᵏ` times the smallest size at the start mesh's vertices,
/// `k = count, …, 1`, before the target itself, where `2^count` is about half the longest
/// metric edge of the start mesh (no stage for a start mesh whose edges are at most 2 long).
/// Each stage only has to halve the smallest sizes of the previous one, so its refinement
/// follows the anisotropy the previous stage made, instead of the start mesh being split
/// almost isotropically down to the smallest size and collapsed back. Measured on UGAWG
/// cube-linear from its 10³-cube Kuhn mesh, scaled to 2·10⁴ vertices (one thread): without
/// the stages 90,732 splits, 74,238 collapses and 478,944 swaps in 44 CPU s; with them 30,785,
/// 14,364 and 42,629 in 6 s (at 10⁵ vertices: 1,440 s against 35 s).
#[derive(Debug, Clone, Copy)]
pub(super) struct SizeFloors {
    /// The smallest size of the metric at the start mesh's vertices.
    pub(super) smallest: f64,
    /// Stages before the target.
    pub(super) count: u32,
}

/// At most this many stages before a metric target.
const MAX_METRIC_STAGES: u32 = 8;

impl SizeFloors {
    /// The floors for the start mesh `mesh` with the target metric `metric` at its vertices
    /// (lengths as the operators measure them, [`Ctx::length_at`]).
    pub(super) fn new(mesh: &crate::mesh3::Mesh3, metric: &[Sym3]) -> SizeFloors {
        let smallest = metric
            .iter()
            .map(|m| SymTensor::sizes(m).0[2])
            .fold(f64::INFINITY, f64::min);
        let mut longest = 0.0f64;
        for t in &mesh.tets {
            for (i, j) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
                let (a, b) = (t[i] as usize, t[j] as usize);
                let (pa, pb) = (mesh.points[a], mesh.points[b]);
                longest = longest.max(Ctx::length_at(pa, pb, &metric[a], &metric[b]));
            }
        }
        let mut count = 0;
        while count < MAX_METRIC_STAGES && f64::from(1u32 << (count + 1)) < longest {
            count += 1;
        }
        SizeFloors { smallest, count }
    }

    /// The size floor of stage `k` (`k ≥ 1`).
    pub(super) fn floor(&self, k: u32) -> f64 {
        if k == 0 {
            0.0
        } else {
            self.smallest * f64::from(1u32 << k)
        }
    }
}

/// `∫ sqrt(det M)` over the live tetrahedra of `mesh` with the vertex metric `metric`.
pub(crate) fn complexity(mesh: &EditMesh3, metric: &[Sym3]) -> f64 {
    use rayon::prelude::*;
    mesh.tets
        .par_iter()
        .filter(|t| t[0] != crate::mesh::NONE)
        .map(|t| {
            let p = t.map(|v| mesh.points[v as usize]);
            let vol = signed_volume(p[0], p[1], p[2], p[3]).abs();
            let d: f64 = t
                .iter()
                .map(|&v| metric[v as usize].det().max(0.0).sqrt())
                .sum();
            vol * 0.25 * d
        })
        .sum()
}

/// The largest vertex count after any pass of `rep` from `start` vertices (refinement adds
/// one vertex per operation, a collapse removes one).
pub(super) fn peak(start: usize, rep: &AdaptReport) -> usize {
    let mut n = start as i64;
    let mut top = n;
    for p in &rep.passes {
        match p.kind {
            PassKind::Split => n += p.count as i64,
            PassKind::Collapse => n -= p.count as i64,
            _ => {}
        }
        top = top.max(n);
    }
    top.max(0) as usize
}

/// Seconds of `rep` by pass kind: refinement, collapse, swap, smoothing.
pub(super) fn seconds_by_kind(rep: &AdaptReport) -> [f64; 4] {
    [
        PassKind::Split,
        PassKind::Collapse,
        PassKind::Flip,
        PassKind::Smooth,
    ]
    .map(|k| rep.pass_totals(k).2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::DVec3;

    #[test]
    fn complexity_of_a_constant_metric_is_volume_over_size_cubed() {
        let m = crate::mesh3::Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [3, 3, 3]).unwrap();
        let e = EditMesh3::from_mesh(&m).unwrap();
        let h = 0.1;
        let c = complexity(&e, &vec![Sym3::iso(h); m.n_points()]);
        assert!((c - 1.0 / (h * h * h)).abs() < 1e-9 * c, "{c}");
    }

    #[test]
    fn stages_scale_every_size() {
        let lm = LevelSetMetric {
            eps: 1e-3,
            hmin: 1e-2,
            hmax: 0.2,
            max_aniso: 1e3,
            band: 5e-3,
            grade: 1.0,
            analytic: true,
            isotropic: false,
        };
        assert_eq!(stage_count(&lm, Continuation3::Sizes), 3);
        assert_eq!(stage_count(&lm, Continuation3::Off), 0);
        let c = coarsened(&lm, Continuation3::Sizes, 4.0);
        assert!((c.eps - 1.6e-2).abs() < 1e-15 && (c.hmin - 4e-2).abs() < 1e-15);
        assert!((c.band - 2e-2).abs() < 1e-15 && c.hmax == lm.hmax);
        let n = coarsened(&lm, Continuation3::Normal, 4.0);
        assert!(n.eps == lm.eps && (n.hmin - 4e-2).abs() < 1e-15);
    }
}
