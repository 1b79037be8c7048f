//! The per-pass workspace of the operator context: pass stamps, the log of touched triangles,
//! cached qualities, and the [`EditListener`] through which the mesh edits keep them (and the
//! metric and fields) in step with the mesh; spatial renumbering carries them along.

use super::topo::{unknown_qualities, Ctx, Q_UNKNOWN};
use crate::mesh::{EditListener, Mesh2, NONE};
use crate::metric::Sym2;
use std::sync::atomic::AtomicU64;

impl Ctx<'_> {
    /// Starts a new pass: every stamp becomes stale.
    pub(crate) fn new_pass(&mut self) {
        // 2^32 passes never happen in practice; saturate rather than wrap.
        self.gen = self.gen.saturating_add(1);
    }

    /// Makes the next smoothing pass examine only the vertices whose ball changes after this
    /// call (by default a pass also re-examines the neighbours of the previous pass's moves).
    pub(crate) fn smoothing_settled(&mut self) {
        self.new_pass();
        self.last_smooth = self.gen;
    }

    /// Marks triangle `t` (with its current vertices) as modified in this pass.
    #[inline]
    pub(crate) fn touch(&mut self, t: u32) {
        let tri = self.mesh.tris[t as usize];
        self.edit(Sym2::IDENTITY).1.triangle_changed(t, tri);
    }

    /// The mesh, to call its edits, and the listener that keeps this workspace in step with
    /// them; `m` is the metric of a vertex the edit adds or moves (its field values are taken
    /// from `self.scratch_f`).
    #[inline]
    pub(crate) fn edit(&mut self, m: Sym2) -> (&mut Mesh2, Workspace<'_>) {
        let Ctx {
            mesh,
            metric,
            fields,
            tstamp,
            vstamp,
            vmod,
            log,
            tseen,
            tq,
            gen,
            logm,
            fast_q,
            scratch_f,
            ..
        } = self;
        let ws = Workspace {
            metric,
            fields,
            logm,
            scratch_f,
            fast_q: *fast_q,
            gen: *gen,
            m,
            tstamp,
            vstamp,
            vmod,
            log,
            tseen,
            tq,
        };
        (mesh, ws)
    }

    /// Drops deleted triangles and unused vertices and renumbers the rest along a space-filling
    /// curve ([`Mesh2::compact_spatial`]), carrying the metric, fields, stamps and cached
    /// qualities along: the operators' fan walks then touch memory that is close together.
    pub(crate) fn renumber_spatially(&mut self) {
        let (vmap, tmap) = self.mesh.compact_spatial();
        let nv = self.mesh.n_points();
        let nt = self.mesh.n_tris();
        *self.metric = scatter(self.metric, &vmap, nv, Sym2::IDENTITY);
        for f in self.fields.iter_mut() {
            *f = scatter(f, &vmap, nv, 0.0);
        }
        if !self.fast_q {
            self.logm = scatter(&self.logm, &vmap, nv, Sym2::IDENTITY);
        }
        self.vstamp = scatter(&self.vstamp, &vmap, nv, 0);
        self.vmod = scatter(&self.vmod, &vmap, nv, 0);
        self.tstamp = scatter(&self.tstamp, &tmap, nt, 0);
        self.tseen = vec![0; nt];
        // Known qualities stay known: the triangles are the same, only their indices change.
        let mut tq = unknown_qualities(nt);
        for (old, &new) in tmap.iter().enumerate() {
            if new != NONE {
                *tq[new as usize].get_mut() = *self.tq[old].get_mut();
            }
        }
        self.tq = tq;
        // Keep the log entries some pass has not consumed yet, renumbered.
        let lo = self.split_pos.min(self.flip_pos);
        let mut kept = Vec::with_capacity(self.log.len() - lo);
        let (mut sp, mut fp) = (0, 0);
        for k in lo..=self.log.len() {
            if k == self.split_pos {
                sp = kept.len();
            }
            if k == self.flip_pos {
                fp = kept.len();
            }
            if let Some(&t) = self.log.get(k) {
                let new = tmap[t as usize];
                if new != NONE {
                    kept.push(new);
                }
            }
        }
        self.log = kept;
        self.split_pos = sp;
        self.flip_pos = fp;
    }

    /// The live triangles logged since position `from`, each once, in index order (which the
    /// spatial renumbering makes a memory-friendly order).
    pub(crate) fn logged_since(&mut self, from: usize) -> Vec<u32> {
        let mut out = Vec::with_capacity(self.log.len().saturating_sub(from));
        for k in from..self.log.len() {
            let t = self.log[k];
            let tu = t as usize;
            if self.tseen[tu] != self.gen && !self.mesh.is_deleted(tu) {
                self.tseen[tu] = self.gen;
                out.push(t);
            }
        }
        if out.len() > self.tseen.len() / 16 {
            // Many: one sequential sweep of the marks is cheaper than sorting.
            out.clear();
            let gen = self.gen;
            out.extend((0..self.tseen.len() as u32).filter(|&t| self.tseen[t as usize] == gen));
        } else {
            out.sort_unstable();
        }
        out
    }
}

/// The per-vertex and per-triangle data of a [`Ctx`], borrowed while the mesh is edited: as an
/// [`EditListener`] it grows with the mesh (a new vertex gets the metric `m` and the field
/// values of `scratch_f`) and marks every changed triangle and its vertices as modified in the
/// current pass (logged for the next split and flip passes, cached quality forgotten).
pub(crate) struct Workspace<'c> {
    metric: &'c mut Vec<Sym2>,
    fields: &'c mut [Vec<f64>],
    logm: &'c mut Vec<Sym2>,
    scratch_f: &'c [f64],
    fast_q: bool,
    gen: u32,
    m: Sym2,
    tstamp: &'c mut Vec<u32>,
    vstamp: &'c mut Vec<u32>,
    vmod: &'c mut Vec<u32>,
    log: &'c mut Vec<u32>,
    tseen: &'c mut Vec<u32>,
    tq: &'c mut Vec<AtomicU64>,
}

impl EditListener for Workspace<'_> {
    fn vertex_added(&mut self, _v: u32) {
        self.metric.push(self.m);
        if !self.fast_q {
            self.logm.push(self.m.log());
        }
        for (f, &x) in self.fields.iter_mut().zip(self.scratch_f) {
            f.push(x);
        }
        self.vstamp.push(self.gen);
        self.vmod.push(self.gen);
    }

    fn vertex_moved(&mut self, v: u32) {
        let vu = v as usize;
        self.metric[vu] = self.m;
        if !self.fast_q {
            self.logm[vu] = self.m.log();
        }
        for (f, &x) in self.fields.iter_mut().zip(self.scratch_f) {
            f[vu] = x;
        }
    }

    #[inline]
    fn triangle_added(&mut self, t: u32, tri: [u32; 3]) {
        self.tstamp.push(self.gen);
        self.tseen.push(0);
        self.tq.push(AtomicU64::new(Q_UNKNOWN));
        self.log.push(t);
        for v in tri {
            self.vmod[v as usize] = self.gen;
        }
    }

    #[inline]
    fn triangle_changed(&mut self, t: u32, tri: [u32; 3]) {
        let tu = t as usize;
        if self.tstamp[tu] != self.gen {
            self.log.push(t);
        }
        self.tstamp[tu] = self.gen;
        *self.tq[tu].get_mut() = Q_UNKNOWN;
        for v in tri {
            if v != NONE {
                self.vmod[v as usize] = self.gen;
            }
        }
    }

    #[inline]
    fn triangle_removed(&mut self, t: u32) {
        self.triangle_changed(t, [NONE; 3]);
    }
}

/// `src` renumbered by `map` (old index -> new index, `NONE` for dropped entries) into a vector
/// of length `n`; entries no old index maps to get `fill`.
pub(crate) fn scatter<T: Copy>(src: &[T], map: &[u32], n: usize, fill: T) -> Vec<T> {
    let mut out = vec![fill; n];
    for (old, &new) in map.iter().enumerate() {
        if new != NONE {
            out[new as usize] = src[old];
        }
    }
    out
}
