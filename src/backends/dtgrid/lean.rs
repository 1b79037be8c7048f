//! Mean curvature motion on bands too large for assembled matrices (000 §2.4, §3): `Φ` in `f32`
//! on a DT-Grid, the system of 000 (2.5) applied matrix-free ([`super::matfree`]), CG with the
//! diagonal preconditioner, and the band rebuild with its signed distance extension
//! ([`super::distance::extend_distance`]) computed over windows of the band, so the memory is a
//! few vectors of the band plus one window, never a matrix or the whole grid.
//!
//! The windows: the new band is cut into ranges of its first coordinate holding about
//! [`LeanOptions::chunk_nodes`] nodes; each range is extended with a halo of `⌈d/h⌉ + 4` grid
//! planes on both sides (`d` the largest distance computed), the extension runs on the nodes of
//! the old and new bands inside, and the values of the range itself are kept. The extension only
//! propagates nearest triangles between `3³` neighbours for at most `⌈d/h⌉ + 1` passes, so the
//! halo covers everything a node's value can depend on and the windows give the values of one
//! extension over the whole band (tested).
//!
//! [`LeanState::step`] is [`super::mcf::McfState::step`] on this storage: Dirichlet values on
//! the boundary layer with the nested inner iteration (or natural conditions); transparent
//! conditions need the assembled boundary vector and are refused.

use super::band::Band;
use super::distance::{extend_distance, zero_level_integral, Keep};
use super::grid::DtGrid;
use super::lattice::{band_around, crosses, Lattice, NarrowBand, C3};
use super::matfree::MatFree;
use super::mcf::{cpu_seconds, McfOptions, McfState, StepReport};
use super::scheme::Bc;
use crate::error::{Error, Result};
use crate::geom::DVec3;
use rayon::prelude::*;
use std::collections::VecDeque;
use std::time::Instant;

/// Options of the windowed rebuild.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LeanOptions {
    /// The mean curvature options (band width, boundary condition, solves per step, `ε`, `δ`).
    pub mcf: McfOptions,
    /// About this many new band nodes per window of the rebuild.
    pub chunk_nodes: usize,
    /// CG stops when the residual has fallen by this factor.
    pub rtol: f64,
}

impl Default for LeanOptions {
    fn default() -> Self {
        LeanOptions {
            mcf: McfOptions::default(),
            chunk_nodes: 1 << 21,
            rtol: 1e-6,
        }
    }
}

/// A level set in `f32` on a DT-Grid band, moving by mean curvature.
#[derive(Debug, Clone)]
pub struct LeanState {
    /// The grid.
    pub lat: Lattice,
    /// The band around the current zero level.
    pub nb: NarrowBand<DtGrid<C3>>,
    /// `Φ` on the band nodes (a signed distance function after each step).
    pub phi: Vec<f32>,
}

/// Wall and processor seconds since `t`, `c`.
fn since(t: Instant, c: f64) -> (f64, f64) {
    (t.elapsed().as_secs_f64(), cpu_seconds() - c)
}

/// The signed distance extension of `phi` on `from` to `to` (as
/// [`extend_distance`]) computed window by window (see the module documentation).
/// Error: [`Error::TooLarge`] from the window grids (not expected below `2^32` nodes).
pub fn extend_windowed(
    lat: &Lattice,
    from: &DtGrid<C3>,
    phi: &[f32],
    to: &DtGrid<C3>,
    keep: Keep,
    max_dist: f64,
    chunk_nodes: usize,
) -> Result<Vec<f32>> {
    let halo = (max_dist / lat.h).ceil() as i32 + 4;
    let mut per_x = vec![0usize; lat.n + 1];
    for c in to.coords() {
        per_x[c[0].clamp(0, lat.n as i32) as usize] += 1;
    }
    // Windows [a, b) of the first coordinate with about chunk_nodes nodes each.
    let mut windows = Vec::new();
    let (mut a, mut count) = (0usize, 0usize);
    for (x, &k) in per_x.iter().enumerate() {
        count += k;
        if count >= chunk_nodes.max(1) || x == lat.n {
            windows.push((a as i32, x as i32 + 1));
            a = x + 1;
            count = 0;
        }
    }
    let mut out: Vec<f32> = Vec::with_capacity(to.len());
    let mut fi = from.coords().zip(phi.iter().copied()).peekable();
    let mut ti = to.coords().peekable();
    let mut fw: VecDeque<(C3, f32)> = VecDeque::new();
    let mut tw: VecDeque<C3> = VecDeque::new();
    for (a, b) in windows {
        while let Some(p) = fi.next_if(|(c, _)| c[0] < b + halo) {
            fw.push_back(p);
        }
        while fw.front().is_some_and(|(c, _)| c[0] < a - halo) {
            fw.pop_front();
        }
        while let Some(c) = ti.next_if(|c| c[0] < b + halo) {
            tw.push_back(c);
        }
        while tw.front().is_some_and(|c| c[0] < a - halo) {
            tw.pop_front();
        }
        if !tw.iter().any(|c| (a..b).contains(&c[0])) {
            continue;
        }
        let fb: DtGrid<C3> = DtGrid::from_sorted(fw.iter().map(|p| p.0))?;
        let fv: Vec<f64> = fw.iter().map(|p| p.1 as f64).collect();
        let tb: DtGrid<C3> = DtGrid::from_sorted(tw.iter().copied())?;
        let d = extend_distance(lat, &fb, &fv, &tb, keep, max_dist);
        out.extend(
            tw.iter()
                .zip(&d)
                .filter(|(c, _)| (a..b).contains(&c[0]))
                .map(|(_, v)| *v as f32),
        );
    }
    Ok(out)
}

/// The cells of `band` whose corner values of `phi` change sign.
fn crossing_cells(band: &DtGrid<C3>, phi: &[f32]) -> Vec<C3> {
    band.cells()
        .filter(|(_, idx)| crosses(&idx.map(|i| phi[i as usize] as f64)))
        .map(|(c, _)| c)
        .collect()
}

/// The largest distance the extension computes for a band of half-width `j` (as in
/// [`super::mcf`]).
fn max_dist(lat: &Lattice, j: usize) -> f64 {
    (2 * j + 4) as f64 * lat.h
}

/// The band of half-width `j` around the zero level of `phi` on `band` and the values of the
/// windowed extension on it (`keep` as in [`extend_distance`]).
/// Errors: [`Error::EmptyLevelSet`] when no cell is crossed, [`Error::InvalidInput`] when the
/// band leaves the grid.
pub fn rebuild_windowed(
    lat: &Lattice,
    band: &DtGrid<C3>,
    phi: &[f32],
    j: usize,
    keep: Keep,
    chunk_nodes: usize,
) -> Result<(NarrowBand<DtGrid<C3>>, Vec<f32>)> {
    let cross = crossing_cells(band, phi);
    let new: NarrowBand<DtGrid<C3>> = band_around(lat, &cross, j).map_err(|e| match e {
        Error::EmptyLevelSet(_) => Error::EmptyLevelSet(
            "the zero level vanished during the motion (no band cell is crossed)".into(),
        ),
        e => e,
    })?;
    drop(cross);
    let d = extend_windowed(
        lat,
        band,
        phi,
        &new.band,
        keep,
        max_dist(lat, j),
        chunk_nodes,
    )?;
    Ok((new, d))
}

/// Preconditioned CG for `(M + τ L) x = M Φ^k` with `x` fixed where `fixed` (Dirichlet) —
/// vectors in `f32`, products and dot products in `f64`; returns the iterations.
/// Errors: [`Error::NotConverged`], [`Error::InvalidField`] for a non-finite result.
fn solve(op: &MatFree, phik: &[f32], fixed: &[bool], x: &mut [f32], rtol: f64) -> Result<usize> {
    let n = x.len();
    let mut q = vec![0.0f64; n];
    op.apply(x, &mut q);
    let mut r: Vec<f32> = (0..n)
        .into_par_iter()
        .map(|i| {
            if fixed[i] {
                0.0
            } else {
                (op.mass[i] as f64 * phik[i] as f64 - q[i]) as f32
            }
        })
        .collect();
    let norm = |v: &[f32]| {
        v.par_iter()
            .map(|&a| a as f64 * a as f64)
            .sum::<f64>()
            .sqrt()
    };
    let r0 = norm(&r);
    let mut y = vec![0.0f32; n];
    let mut iters = 0;
    if r0 > 0.0 {
        let inv: &[f32] = &op.diag;
        let mut p: Vec<f32> = r.par_iter().zip(inv).map(|(r, d)| r / d).collect();
        let mut rz: f64 = r
            .par_iter()
            .zip(&p)
            .map(|(&a, &b)| a as f64 * b as f64)
            .sum();
        let mut done = false;
        for it in 1..=20_000 {
            iters = it;
            op.apply(&p, &mut q);
            let pq: f64 = q
                .par_iter_mut()
                .zip(&p)
                .zip(fixed)
                .map(|((q, &p), &f)| {
                    if f {
                        *q = 0.0;
                    }
                    *q * p as f64
                })
                .sum();
            if !(pq > 0.0 && rz.is_finite()) {
                break;
            }
            let alpha = rz / pq;
            y.par_iter_mut()
                .zip(&p)
                .for_each(|(y, &p)| *y = (*y as f64 + alpha * p as f64) as f32);
            r.par_iter_mut()
                .zip(&q)
                .for_each(|(r, &q)| *r = (*r as f64 - alpha * q) as f32);
            if norm(&r) <= rtol * r0 {
                done = true;
                break;
            }
            let rz_new: f64 = r
                .par_iter()
                .zip(inv)
                .map(|(&a, &d)| a as f64 * a as f64 / d as f64)
                .sum();
            let beta = rz_new / rz;
            rz = rz_new;
            p.par_iter_mut()
                .zip(r.par_iter().zip(inv))
                .for_each(|(p, (&r, &d))| *p = (r as f64 / d as f64 + beta * *p as f64) as f32);
        }
        if !done {
            return Err(Error::NotConverged(format!(
                "matrix-free band CG: residual {:.2e} of {r0:.2e} after {iters} iterations",
                norm(&r)
            )));
        }
    }
    x.par_iter_mut().zip(&y).for_each(|(x, y)| *x += y);
    if let Some(i) = x.iter().position(|v| !v.is_finite()) {
        return Err(Error::InvalidField {
            name: "band solution".into(),
            msg: format!("not finite at band node {i}"),
        });
    }
    Ok(iters)
}

/// The largest change from `(old, u)` to `(new, v)` over the boundary nodes of `new` that are
/// also nodes of `old` (one merge of the two sorted node lists).
fn boundary_change(
    old: &NarrowBand<DtGrid<C3>>,
    u: &[f32],
    new: &NarrowBand<DtGrid<C3>>,
    v: &[f32],
) -> f64 {
    let mut change = 0.0f64;
    let mut it = old.band.coords().zip(u).peekable();
    for ((cn, vn), int) in new.band.coords().zip(v).zip(&new.interior) {
        while it.next_if(|(co, _)| *co < cn).is_some() {}
        if let Some((_, vo)) = it.next_if(|(co, _)| *co == cn) {
            if !int {
                change = change.max((*vn as f64 - *vo as f64).abs());
            }
        }
    }
    change
}

impl LeanState {
    /// The level set of the `lipschitz`-Lipschitz function `f` (1 for a signed distance) on the
    /// band of half-width `j`, carrying the signed distance to its zero level: the band by block
    /// pruning ([`super::sparse_init`]), the distance by the windowed extension.
    /// Errors: as [`super::sparse_init::band_of_fn`] and [`rebuild_windowed`].
    pub fn new(
        lat: Lattice,
        j: usize,
        f: &(impl Fn(DVec3) -> f64 + Sync),
        lipschitz: f64,
        chunk_nodes: usize,
    ) -> Result<LeanState> {
        let (nb, v) = super::sparse_init::band_of_fn::<DtGrid<C3>>(&lat, j, f, Some(lipschitz))?;
        let v: Vec<f32> = v.into_iter().map(|x| x as f32).collect();
        let (nb, phi) = rebuild_windowed(&lat, &nb.band, &v, j, Keep::Nothing, chunk_nodes)?;
        Ok(LeanState { lat, nb, phi })
    }

    /// The state of an assembled-matrix level set, its values rounded to `f32`.
    pub fn from_state(s: &McfState<DtGrid<C3>>) -> LeanState {
        LeanState {
            lat: s.lat,
            nb: s.nb.clone(),
            phi: s.phi.iter().map(|&x| x as f32).collect(),
        }
    }

    /// One time step of length `tau` (see the module documentation).
    /// Errors: [`Error::InvalidInput`] for a bad `tau`, no solves, transparent or extrapolated conditions;
    /// [`Error::EmptyLevelSet`], [`Error::NotConverged`] as [`McfState::step`].
    pub fn step(&mut self, tau: f64, o: &LeanOptions) -> Result<StepReport> {
        let m = &o.mcf;
        if tau.is_nan()
            || tau <= 0.0
            || m.inner == 0
            || matches!(m.bc, Bc::Transparent | Bc::Extrapolated)
        {
            return Err(Error::InvalidInput(format!(
                "matrix-free mean curvature step: tau = {tau}, solves per step = {}, \
                 conditions {} (tau and solves positive; dirichlet or natural)",
                m.inner,
                m.bc.name()
            )));
        }
        let lat = self.lat;
        let mut rep = StepReport::default();
        let mut nb = self.nb.clone();
        let mut phik = self.phi.clone();
        let mut approx = self.phi.clone();
        let solves = if m.bc == Bc::Dirichlet { m.inner } else { 1 };
        for s in 1..=solves {
            let (t, c) = (Instant::now(), cpu_seconds());
            let op = MatFree::new(&lat, &nb, &phik, m.eps, tau)?;
            let (w, p) = since(t, c);
            rep.times.assembly += w;
            rep.times.assembly_cpu += p;
            let (t, c) = (Instant::now(), cpu_seconds());
            let fixed: Vec<bool> = match m.bc {
                Bc::Dirichlet => nb.interior.iter().map(|i| !i).collect(),
                _ => vec![false; nb.interior.len()],
            };
            let mut x = approx.clone();
            rep.cg_iterations += solve(&op, &phik, &fixed, &mut x, o.rtol)?;
            drop((op, fixed));
            rep.solves += 1;
            let (w, p) = since(t, c);
            rep.times.solve += w;
            rep.times.solve_cpu += p;
            let (t, c) = (Instant::now(), cpu_seconds());
            let (new_nb, new_approx) =
                rebuild_windowed(&lat, &nb.band, &x, nb.j, Keep::Crossing, o.chunk_nodes)?;
            drop(x);
            let same = new_nb.band == nb.band;
            // The largest change of the boundary data on nodes of both bands (merge of the
            // two sorted node lists).
            let change = boundary_change(&nb, &approx, &new_nb, &new_approx);
            let done = same && change < m.delta * lat.h;
            if s < solves && !done && !same {
                phik = extend_windowed(
                    &lat,
                    &self.nb.band,
                    &self.phi,
                    &new_nb.band,
                    Keep::OldBand,
                    max_dist(&lat, nb.j),
                    o.chunk_nodes,
                )?;
            }
            nb = new_nb;
            approx = new_approx;
            let (w, p) = since(t, c);
            rep.times.rebuild += w;
            rep.times.rebuild_cpu += p;
            if done {
                break;
            }
        }
        self.nb = nb;
        self.phi = approx;
        Ok(rep)
    }

    /// The area-weighted mean of `g(x)` over the zero level (as
    /// [`McfState::surface_mean`]), summed window by window over planes of cells.
    /// Error: [`Error::EmptyLevelSet`] when the zero level is empty.
    pub fn surface_mean(&self, g: impl Fn(DVec3) -> f64 + Sync, planes: i32) -> Result<f64> {
        let planes = planes.max(1);
        let (mut area, mut total) = (0.0, 0.0);
        let mut it = self
            .nb
            .band
            .coords()
            .zip(self.phi.iter().copied())
            .peekable();
        let mut win: VecDeque<(C3, f32)> = VecDeque::new();
        let mut a = 0;
        while a < self.lat.n as i32 {
            let b = a + planes;
            // The window's nodes lie in the planes [a, b]: its cells are exactly those with
            // lowest corner in [a, b), so the windows split the cells.
            while let Some(p) = it.next_if(|(c, _)| c[0] <= b) {
                win.push_back(p);
            }
            while win.front().is_some_and(|(c, _)| c[0] < a) {
                win.pop_front();
            }
            let band: DtGrid<C3> = DtGrid::from_sorted(win.iter().map(|p| p.0))?;
            let v: Vec<f64> = win.iter().map(|p| p.1 as f64).collect();
            let (ar, s) = zero_level_integral(&self.lat, &band, &v, &g);
            area += ar;
            total += s;
            a = b;
        }
        if area.is_nan() || area <= 0.0 {
            return Err(Error::EmptyLevelSet("the zero level has no area".into()));
        }
        Ok(total / area)
    }
}
