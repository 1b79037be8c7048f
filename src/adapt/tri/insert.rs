//! Anisotropic Delaunay insertion (004 §3.5, "a modification of the Delaunay kernel to account
//! for anisotropic elements"): a new point `p` is inserted by removing the *cavity* — the
//! triangles whose circumcircle, measured in the metric `M_p` of the new point, contains `p` —
//! and re-triangulating it as the star of `p`. Used instead of a plain split on unlabelled
//! interior edges: it also reconnects the neighbourhood toward the metric.
//!
//! The cavity starts from the two triangles sharing the split edge and grows across unlabelled
//! interior edges only (curves are never crossed). It is then shrunk until it is star-shaped
//! from `p` (exact `orient2d` on each boundary edge), and the insertion is rejected (the caller
//! falls back to a split) if it is not a topological disc without interior vertices, or if the
//! star's worst `Q_ani` is above the floor and worse than the cavity's.

use super::split::SplitPlan;
use super::topo::Ctx;
use crate::geom::{incircle, orient2d, DVec2};
use crate::mesh::{next, prev, CavityEdge, NONE};
use crate::metric::Sym2;

/// Maximal cavity size (triangles).
const MAX_CAVITY: usize = 32;

/// A planned insertion: the point, its metric, the cavity triangles and its boundary edges in
/// the order of the cavity's triangles.
#[derive(Debug, Clone, PartialEq)]
pub struct InsertPlan {
    /// The new point (metric midpoint of the split edge).
    pub p: DVec2,
    /// The metric at the new point.
    pub m: Sym2,
    /// Parameter of `p` along the split edge `ends[0] -> ends[1]`.
    pub s: f64,
    /// The ends of the split edge.
    pub ends: [u32; 2],
    /// The triangles removed (the two holding the split edge first).
    pub cavity: Vec<u32>,
    /// The boundary edges of the cavity, each to be joined to the new point.
    pub boundary: Vec<CavityEdge>,
    /// `Q_ani` of the star triangle on each boundary edge in the arithmetic-mean element metric
    /// (the operators' default quality, so `apply` caches it; set only by `check`).
    pub(crate) q_star: Vec<f64>,
}

/// Upper-triangular `L` with `M = Lᵀ L`: `x -> L x` maps to the metric-space coordinates.
#[derive(Clone, Copy)]
struct MetricSpace {
    a: f64,
    b: f64,
    c: f64,
}

impl MetricSpace {
    #[inline]
    fn new(m: &Sym2) -> MetricSpace {
        let a = m.xx.sqrt();
        MetricSpace {
            a,
            b: m.xy / a,
            c: (m.det() / m.xx).sqrt(),
        }
    }

    #[inline]
    fn map(&self, x: DVec2) -> DVec2 {
        DVec2::new(self.a * x.x + self.b * x.y, self.c * x.y)
    }
}

/// Pure check: the insertion of the metric midpoint of the unlabelled interior edge planned by
/// `split` (metric re-evaluated by the source when it has one, else interpolated).
pub fn check(ctx: &mut Ctx, split: &SplitPlan) -> Option<InsertPlan> {
    let (t, i) = (split.t as usize, split.i as usize);
    let t2 = ctx.mesh.neighbours[t][i];
    if t2 == NONE || ctx.mesh.edge_ref[t][i] != 0 {
        return None;
    }
    let tri = ctx.mesh.tris[t];
    let (a, b) = (tri[next(i)], tri[prev(i)]);
    let m = match ctx.source.and_then(|s| s.metric_at(split.p)) {
        Some(m) => m,
        None => ctx.interpolate_metric(&[a, b], &[1.0 - split.s, split.s]),
    };
    let p = split.p;
    let space = MetricSpace::new(&m);
    let pm = space.map(p);
    let mesh = &*ctx.mesh;
    let mut cavity: Vec<u32> = vec![t as u32, t2];
    let mut k = 0;
    while k < cavity.len() && cavity.len() < MAX_CAVITY {
        let c = cavity[k] as usize;
        for e in 0..3 {
            let nb = mesh.neighbours[c][e];
            if nb == NONE || mesh.edge_ref[c][e] != 0 || cavity.contains(&nb) {
                continue;
            }
            let q = mesh.tris[nb as usize].map(|v| space.map(mesh.points[v as usize]));
            if incircle(q[0], q[1], q[2], pm) > 0.0 {
                cavity.push(nb);
            }
        }
        k += 1;
    }
    // Shrink to a star-shaped cavity (the two seeds always are).
    loop {
        let mut removed = false;
        let mut idx = 2;
        while idx < cavity.len() {
            let c = cavity[idx] as usize;
            let mut bad = false;
            for e in 0..3 {
                let nb = mesh.neighbours[c][e];
                if nb != NONE && cavity.contains(&nb) {
                    continue;
                }
                let [u, w] = mesh.edge_vertices(c, e);
                if orient2d(mesh.points[u as usize], mesh.points[w as usize], p) <= 0.0 {
                    bad = true;
                }
            }
            if bad {
                cavity.swap_remove(idx);
                removed = true;
            } else {
                idx += 1;
            }
        }
        if !removed {
            break;
        }
    }
    // Boundary edges; seeds' edges must also see p on their left.
    let boundary = mesh.cavity_boundary(&cavity)?;
    for e in &boundary {
        if orient2d(mesh.points[e.u as usize], mesh.points[e.w as usize], p) <= 0.0 {
            return None;
        }
    }
    // A disc without interior vertices: k triangles, k + 2 boundary edges, distinct starts.
    if boundary.len() != cavity.len() + 2 {
        return None;
    }
    for x in 0..boundary.len() {
        for y in x + 1..boundary.len() {
            if boundary[x].u == boundary[y].u {
                return None;
            }
        }
    }
    // Quality: the star must not be worse than the cavity beyond the floor.
    let q_old = cavity.iter().map(|&c| ctx.q_tri(c)).fold(1.0, f64::max);
    let q_star: Vec<f64> = boundary
        .iter()
        .map(|&CavityEdge { u, w, .. }| {
            let pts = [p, mesh.points[u as usize], mesh.points[w as usize]];
            super::kernel::q_ani_mean(pts, [&m, ctx.m(u), ctx.m(w)])
        })
        .collect();
    let q_new = q_star.iter().fold(1.0, |q, &x| f64::max(q, x));
    if !(q_new <= ctx.params.q_max || q_new <= q_old) {
        return None;
    }
    Some(InsertPlan {
        p,
        m,
        s: split.s,
        ends: [a, b],
        cavity,
        boundary,
        q_star,
    })
}

/// Applies an insertion ([`crate::mesh::TriMesh::fill_cavity`]): the cavity slots are reused
/// for the star and two triangles appended. Returns the new vertex.
pub fn apply(ctx: &mut Ctx, plan: &InsertPlan) -> u32 {
    let [a, b] = plan.ends;
    // Fields at the new vertex: from the source, else interpolated along the edge.
    let filled = ctx
        .source
        .is_some_and(|s| s.fields_at(plan.p, &mut ctx.scratch_f));
    if !filled {
        for (k, f) in ctx.fields.iter().enumerate() {
            ctx.scratch_f[k] = (1.0 - plan.s) * f[a as usize] + plan.s * f[b as usize];
        }
    }
    let (mesh, mut ws) = ctx.edit(plan.m);
    let v = mesh.add_vertex(plan.p, 0, &mut ws);
    let star = mesh.fill_cavity(v, &plan.cavity, &plan.boundary, &mut ws);
    for (&t, &q) in star.iter().zip(&plan.q_star) {
        ctx.set_fast_q(t, q);
    }
    v
}
