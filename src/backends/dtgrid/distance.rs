//! The signed distance extension of 000 §2.4 computed in storage order: the distance of every
//! node of a new band to the zero level of a Q1 band field, by closest-triangle propagation
//! through the `3³` neighbourhoods of the band (no hashing, no random access).
//!
//! The zero level is cut into triangles by marching tetrahedra. The corners of the crossed cells
//! (`I¹`) take the nearest triangle of their own cells; then, layer by layer, every node takes the
//! nearest among the triangles its `26` neighbours found (a Jacobi pass over the band in storage
//! order, with one forward cursor per neighbouring grid column). The closest point on the triangle
//! is projected by Newton's method onto the zero level of the trilinear interpolant in the
//! triangle's cell, so the distance is measured to the zero level the finite elements see, not
//! to its chords (the chords of a convex surface lie inside it by `O(h²κ)`; measuring to them
//! shifts the zero level by that much at every redistancing).

use super::band::{Band, GridCoord};
use super::lattice::{Lattice, C3};
use super::nbhd::{neighbourhoods, Nbhd, SHARED_CELL, SLOT_SELF, WITHIN};
use super::surface::closest_on_triangle;
pub use super::zero_level::zero_level_integral;
pub(crate) use super::zero_level::{level, Level};
use crate::geom::DVec3;
use rayon::prelude::*;

const NONE: u32 = u32::MAX;

/// Seed flags (see [`propagate`]): the node's triangle is the nearest of a crossed cell it is a
/// corner of (the corner in the low three bits).
const FROM_CELL: u8 = 8;
/// Seed flags: every triangle of the node's crossed cells but its own is farther than its own by
/// more than the tie tolerance.
const CLEAR: u8 = 16;

/// Which values of the field are kept on the new band instead of the distance.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Keep {
    /// None: the signed distance everywhere (signs from the field where the node is in the old
    /// band).
    Nothing,
    /// The corners of the crossed cells (`I¹`): the zero level of the field is not moved.
    Crossing,
    /// Every node of the old band (the extension of `Φ^k` in 000 §2.4).
    OldBand,
}

/// The triangles of the zero level with cheap lower bounds of the distance to each: its plane
/// and the disc in it about the centroid that holds the triangle (one cache line per triangle,
/// apart from the corners, so that a rejected candidate costs one load).
struct Tris<'a> {
    corners: &'a [[DVec3; 3]],
    bounds: Vec<Bound>,
}

#[derive(Clone, Copy)]
#[repr(C, align(64))]
struct Bound {
    centre: DVec3,
    radius: f64,
    normal: DVec3,
    offset: f64,
}

impl Bound {
    fn new([a, b, c]: [DVec3; 3]) -> Bound {
        let centre = (a + b + c) / 3.0;
        let radius = [a, b, c]
            .iter()
            .map(|v| (*v - centre).length())
            .fold(0.0, f64::max);
        let n = (b - a).cross(c - a);
        let len = n.length();
        let normal = if len > 0.0 { n / len } else { DVec3::ZERO };
        // Rounding slack, so the bound never exceeds the distance computed from the vertices.
        Bound {
            centre,
            radius: radius * (1.0 + 1e-9),
            normal,
            offset: normal.dot(a),
        }
    }
}

impl<'a> Tris<'a> {
    fn new(corners: &'a [[DVec3; 3]]) -> Tris<'a> {
        let bounds = corners.par_iter().map(|&t| Bound::new(t)).collect();
        Tris { corners, bounds }
    }

    /// Whether a lower bound of the distance of `p` to triangle `t` exceeds `lim`.
    #[inline]
    fn beyond(&self, t: u32, p: DVec3, lim: f64) -> bool {
        let b = &self.bounds[t as usize];
        // The triangle lies in its plane within the disc of its radius about the centroid, so
        // the squared distance is at least the plane's squared distance plus the squared
        // distance from the foot of `p` to that disc.
        let s = b.normal.dot(p) - b.offset;
        let lim2 = lim * lim;
        // The plane alone decides most rejections, before the square root of the disc term.
        if s * s * (1.0 - 1e-9) > lim2 {
            return true;
        }
        let foot = (p - s * b.normal - b.centre).length();
        let out = (foot - b.radius).max(0.0);
        (s * s + out * out) * (1.0 - 1e-9) > lim2
    }

    /// The closest point of triangle `t` to `p`.
    #[inline]
    fn closest(&self, t: u32, p: DVec3) -> DVec3 {
        let [a, b, c] = self.corners[t as usize];
        closest_on_triangle(p, a, b, c)
    }

    /// The distance of `p` to triangle `t`.
    #[inline]
    fn distance(&self, t: u32, p: DVec3) -> f64 {
        (p - self.closest(t, p)).length()
    }

    /// `|cos|` of the angle between the offset of `p` from triangle `t` and its normal.
    fn cos(&self, t: u32, p: DVec3) -> f64 {
        let d = p - self.closest(t, p);
        let len = d.length();
        let normal = self.bounds[t as usize].normal;
        if len > 0.0 && normal != DVec3::ZERO {
            (d.dot(normal) / len).abs()
        } else {
            0.0
        }
    }
}

/// The nearest to `p` of the current best `(bd, bt)` and the triangles `cands` (repeats and
/// `NONE` skipped): ties within `tie` go to the triangle facing `p` most, then the lowest index.
/// Each candidate comes with a tag (the slot of the neighbour proposing it), returned with the
/// winner (`tag` for the current best).
fn nearest(
    tris: &Tris,
    p: DVec3,
    (mut bd, mut bt, mut btag): (f64, u32, u32),
    tie: f64,
    cands: impl Iterator<Item = (u32, u32)>,
) -> (f64, u32, u32) {
    // `|cos|` of the best triangle, computed when a tie needs it.
    let mut bcos = f64::NAN;
    // The candidates seen, with a one-word filter (bit `t mod 64`) in front of the list; the
    // neighbours mostly propose the same triangle, so a repeat of the last one is skipped first.
    let (mut seen, mut ns, mut filter) = ([NONE; 27], 0, 0u64);
    let mut last = NONE;
    for (tag, t) in cands {
        if t == NONE || t == last || t == bt {
            continue;
        }
        last = t;
        let bit = 1u64 << (t % 64);
        if filter & bit != 0 && seen[..ns].contains(&t) {
            continue;
        }
        filter |= bit;
        seen[ns] = t;
        ns += 1;
        if tris.beyond(t, p, bd + tie) {
            continue;
        }
        let d = tris.distance(t, p);
        if d < bd - tie {
            (bd, bt, btag, bcos) = (d, t, tag, f64::NAN);
        } else if (d - bd).abs() <= tie {
            if bcos.is_nan() {
                bcos = tris.cos(bt, p);
            }
            let cos = tris.cos(t, p);
            if cos > bcos || (cos == bcos && t < bt) {
                (bd, bt, btag, bcos) = (d, t, tag, cos);
            }
        }
    }
    (bd, bt, btag)
}

/// Up to `layers` Jacobi passes in which every node (position `pos`) takes the nearest of its
/// own triangle and its neighbours' (`nbr`), starting from the seeds' `best` and `dist`.
///
/// Only nodes with a neighbour that changed in the last pass are visited again (a list built
/// from the changes, not a test of 27 flags per node), and only the triangles of those
/// neighbours are candidates: a neighbour's triangle from an earlier pass was measured when that
/// neighbour changed (or in the first pass) and lost, and the best distance only falls, so it
/// cannot win now. Nor is a changed neighbour's triangle a candidate when the neighbour took it
/// from a node that is itself in this node's neighbourhood (each node keeps the slot of the
/// neighbour its triangle came from): that node held it a pass earlier, so it was measured here
/// then (or, by the same rule, before). In the first pass a seed flagged [`CLEAR`] skips the
/// triangles its neighbours took from a crossed cell ([`FROM_CELL`], `seeds`) that it is a corner
/// of too: it measured them when it was seeded, and they lost by more than the tie tolerance.
/// The states after every pass are those of full passes. A candidate is measured only when its
/// lower bound can beat the best so far (the node's own triangle, whose distance is known, bounds
/// the search from the start).
#[allow(clippy::too_many_arguments)]
fn propagate(
    tris: &Tris,
    nbr: &[Nbhd],
    pos: &(impl Fn(usize) -> DVec3 + Sync),
    layers: usize,
    tie: f64,
    seeds: &[u8],
    best: &mut [u32],
    dist: &mut [f64],
) {
    let mut visit: Vec<u32> = (0..nbr.len() as u32).collect();
    let mut mark = vec![false; nbr.len()];
    // The pass in which a node's triangle last changed (0: a seed's, or none).
    let mut stamp = vec![0u32; nbr.len()];
    // The slot, in a node's neighbourhood, of the neighbour its triangle came from.
    let mut from = vec![SLOT_SELF as u8; nbr.len()];
    // Per visited node its nearest triangle this pass (one buffer for all passes).
    let mut found: Vec<(f64, u32, u32)> = Vec::new();
    for pass in 1..=layers as u32 {
        let (b, s, f, dd) = (&*best, &stamp, &from, &*dist);
        visit
            .par_iter()
            .map(|&i| {
                let i = i as usize;
                let clear = seeds[i] & CLEAR != 0;
                let fresh = nbr[i]
                    .slots()
                    .filter(|&(slot, j)| {
                        let j = j as usize;
                        if pass == 1 {
                            let sj = seeds[j];
                            !(clear
                                && sj & FROM_CELL != 0
                                && SHARED_CELL[slot as usize] >> (sj & 7) & 1 != 0)
                        } else {
                            s[j] == pass - 1 && WITHIN[slot as usize] >> f[j] & 1 == 0
                        }
                    })
                    .map(|(slot, j)| (slot, b[j as usize]));
                nearest(tris, pos(i), (dd[i], b[i], SLOT_SELF), tie, fresh)
            })
            .collect_into_vec(&mut found);
        let mut changed = false;
        for (&i, &(d, t, slot)) in visit.iter().zip(&found) {
            let i = i as usize;
            if t == best[i] {
                continue;
            }
            changed = true;
            best[i] = t;
            dist[i] = d;
            stamp[i] = pass;
            from[i] = slot as u8;
            for j in nbr[i].iter() {
                mark[j as usize] = true;
            }
        }
        if !changed {
            break;
        }
        visit.clear();
        for (i, m) in mark.iter_mut().enumerate() {
            if std::mem::take(m) {
                visit.push(i as u32);
            }
        }
    }
}

/// The seeds of the propagation: per node of `coords` that is a corner of a crossed cell of
/// `l`, the nearest triangle of its crossed cells and its distance (`NONE` and infinity
/// elsewhere), whether it is such a corner, and its flags for [`propagate`].
fn seeds(
    lat: &Lattice,
    l: &Level,
    tris: &Tris,
    coords: &[C3],
    tie: f64,
) -> (Vec<u32>, Vec<f64>, Vec<bool>, Vec<u8>) {
    let mut best = vec![NONE; coords.len()];
    let mut dist = vec![f64::INFINITY; coords.len()];
    let mut seed = vec![false; coords.len()];
    // Per seed: the corner of the cell of its triangle, and whether a tie came near (see
    // `propagate`).
    let mut flags = vec![0u8; coords.len()];
    let mut tied = vec![false; coords.len()];
    // One forward cursor per corner: the corners `c + offset` of the sorted crossed cells are
    // sorted too, so they are found by merging, not by search.
    let mut cur = [0usize; 8];
    let mut tri = 0usize;
    for (id, (c, _)) in l.cells.iter().enumerate() {
        let start = tri;
        while tri < l.tri_cell.len() && l.tri_cell[tri] == id as u32 {
            tri += 1;
        }
        for (corner, cur) in cur.iter_mut().enumerate() {
            let q = GridCoord::corner(*c, corner);
            while *cur < coords.len() && coords[*cur] < q {
                *cur += 1;
            }
            if *cur == coords.len() || coords[*cur] != q {
                continue;
            }
            let i = *cur;
            seed[i] = true;
            let p = lat.pos(q);
            for t in start as u32..tri as u32 {
                if tris.beyond(t, p, dist[i] + tie) {
                    continue;
                }
                let d = tris.distance(t, p);
                if d < dist[i] {
                    tied[i] |= d >= dist[i] - tie;
                    dist[i] = d;
                    best[i] = t;
                    flags[i] = FROM_CELL | corner as u8;
                } else {
                    tied[i] |= d <= dist[i] + tie;
                }
            }
        }
    }
    for (f, (&s, &t)) in flags.iter_mut().zip(seed.iter().zip(&tied)) {
        if s && !t {
            *f |= CLEAR;
        }
    }
    (best, dist, seed, flags)
}

/// The values on `to` of the band field `phi` on `from`: the signed distance to the zero level of
/// `phi` (the trilinear zero level in the cells it crosses), except where `keep` keeps `phi`.
/// Signs come from `phi` where the node is in `from`, else from the side of the nearest
/// triangle. Nodes farther than `max_dist` (or not reached) get `±max_dist`.
pub fn extend_distance<B: Band<Coord = C3>>(
    lat: &Lattice,
    from: &B,
    phi: &[f64],
    to: &B,
    keep: Keep,
    max_dist: f64,
) -> Vec<f64> {
    extend_from_level(lat, &level(lat, from, phi), from, phi, to, keep, max_dist)
}

/// [`extend_distance`] with the zero level `l` of `phi` on `from` already cut.
pub(crate) fn extend_from_level<B: Band<Coord = C3>>(
    lat: &Lattice,
    l: &Level,
    from: &B,
    phi: &[f64],
    to: &B,
    keep: Keep,
    max_dist: f64,
) -> Vec<f64> {
    let coords: Vec<C3> = to.coords().collect();
    let old_coords: Vec<C3> = from.coords().collect();
    // The old value of every new node, by one merge of the two sorted lists.
    let mut old: Vec<Option<f64>> = vec![None; coords.len()];
    let mut k = 0;
    for (i, c) in coords.iter().enumerate() {
        while k < old_coords.len() && old_coords[k] < *c {
            k += 1;
        }
        if k < old_coords.len() && old_coords[k] == *c {
            old[i] = Some(phi[k]);
        }
    }
    // Seeds: the corners of the crossed cells take the nearest triangle of their cells.
    let tris = Tris::new(&l.tris);
    let tie = 1e-12 * lat.h;
    let (mut best, mut dist, seed, flags) = seeds(lat, l, &tris, &coords, tie);
    // Layers: every node takes the nearest of its neighbours' triangles (Jacobi passes).
    let nbr = neighbourhoods(&coords);
    let layers = (max_dist / lat.h).ceil() as usize + 1;
    propagate(
        &tris,
        &nbr,
        &|i| lat.pos(coords[i]),
        layers,
        tie,
        &flags,
        &mut best,
        &mut dist,
    );
    // The distance to the trilinear zero level from the nearest triangle, and the side of it
    // (needed only where the old field gives no sign).
    let (dist, side): (Vec<f64>, Vec<f64>) = (0..coords.len())
        .into_par_iter()
        .map(|i| match best[i] {
            NONE => (f64::INFINITY, 1.0),
            t => {
                let p = lat.pos(coords[i]);
                let q = tris.closest(t, p);
                let d = (p - l.project(lat, t, q)).length();
                if old[i].is_some() {
                    return (d, 1.0);
                }
                let [a, b, c] = l.tris[t as usize];
                let s = (p - q).dot((b - a).cross(c - a));
                (d, if s < 0.0 { -1.0 } else { 1.0 })
            }
        })
        .unzip();
    // The crossing corners: the field times the slope of the least-squares line `d ≈ s x + b`
    // through (field, signed distance) over the crossing corners of the 3³ neighbourhood (the
    // zero level stays put to within the variation of the factor; the gradient is renormalised).
    // The intercept `b` absorbs the offset between the trilinear zero level and the zero of the
    // smooth function the field samples (`O(h²κ)`, inward on convex parts): a line through the
    // origin would fold it into the slope by `b Σx / Σx²` — a factor wrong by `O(hκ)` that
    // changes from node to node and moved a shrinking sphere inward at every step (000 Table 2.2,
    // j = 4, τ = h²: 1.22e-3 → 7.07e-4 on 65³, see docs/dtgrid.md).
    let scale: Vec<f64> = if keep == Keep::Crossing {
        (0..coords.len())
            .into_par_iter()
            .map(|i| {
                if !seed[i] {
                    return 1.0;
                }
                let (mut n, mut sx, mut sd, mut sxx, mut sxd) = (0.0f64, 0.0, 0.0, 0.0, 0.0);
                for k in nbr[i].iter() {
                    if !seed[k as usize] {
                        continue;
                    }
                    if let Some(x) = old[k as usize] {
                        let d = dist[k as usize].min(max_dist);
                        let d = if x < 0.0 { -d } else { d };
                        n += 1.0;
                        sx += x;
                        sd += d;
                        sxx += x * x;
                        sxd += x * d;
                    }
                }
                if n < 2.0 {
                    return 1.0;
                }
                let var = sxx - sx * sx / n;
                let cov = sxd - sx * sd / n;
                if var > 0.0 && cov > 0.0 {
                    cov / var
                } else {
                    1.0
                }
            })
            .collect()
    } else {
        vec![1.0; coords.len()]
    };
    (0..coords.len())
        .map(|i| {
            let kept = match keep {
                Keep::Nothing => None,
                Keep::Crossing => seed[i].then(|| old[i].map(|x| x * scale[i])).flatten(),
                Keep::OldBand => old[i],
            };
            if let Some(v) = kept {
                return v;
            }
            let s = match old[i] {
                Some(v) if v < 0.0 => -1.0,
                Some(_) => 1.0,
                None => side[i],
            };
            s * dist[i].min(max_dist)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backends::dtgrid::lattice::{band_around, crossing_cells_of_fn, NarrowBand};
    use crate::backends::dtgrid::DtGrid;

    #[test]
    fn passes_over_changed_neighbours_equal_full_passes() {
        // Arbitrary seeds (every fifth node, a scattered triangle), then the propagation against
        // full Jacobi passes that measure every neighbour's triangle at every node.
        let lat = Lattice::unit(29).unwrap();
        let f = |p: DVec3| (p.x / 0.3).powi(2) + (p.y / 0.25).powi(2) + (p.z / 0.2).powi(2) - 1.0;
        let cross = crossing_cells_of_fn(&lat, &f).unwrap();
        let nb: NarrowBand<DtGrid<C3>> = band_around(&lat, &cross, 2).unwrap();
        let phi: Vec<f64> = nb.band.coords().map(|c| f(lat.pos(c))).collect();
        let l = level(&lat, &nb.band, &phi);
        let tris = Tris::new(&l.tris);
        let coords: Vec<C3> = nb.band.coords().collect();
        let nbr = neighbourhoods(&coords);
        let pos = |i: usize| lat.pos(coords[i]);
        let tie = 1e-12 * lat.h;
        let n = coords.len();
        let no_flags = vec![0u8; n];
        for layers in [1, 2, 8] {
            let mut best = vec![NONE; n];
            let mut dist = vec![f64::INFINITY; n];
            for i in (0..n).step_by(5) {
                best[i] = ((i * 7919) % l.tris.len()) as u32;
                dist[i] = tris.distance(best[i], pos(i));
            }
            let (mut rb, mut rd) = (best.clone(), dist.clone());
            propagate(
                &tris, &nbr, &pos, layers, tie, &no_flags, &mut best, &mut dist,
            );
            for _ in 0..layers {
                let new: Vec<(f64, u32)> = (0..n)
                    .map(|i| {
                        let all = nbr[i].slots().map(|(s, j)| (s, rb[j as usize]));
                        let (d, t, _) = nearest(&tris, pos(i), (rd[i], rb[i], SLOT_SELF), tie, all);
                        (d, t)
                    })
                    .collect();
                (rd, rb) = new.into_iter().unzip();
            }
            let moved = best.iter().zip(&rb).filter(|(a, b)| a != b).count();
            assert_eq!(moved, 0, "{layers} passes: {moved} of {n} nodes differ");
            assert!(dist
                .iter()
                .zip(&rd)
                .all(|(a, b)| a.to_bits() == b.to_bits()));
            assert!(rb.iter().filter(|&&t| t != NONE).count() > n / 2);
        }
    }

    #[test]
    fn triangle_bounds_never_exceed_the_distance() {
        // The plane-and-disc bound of every triangle of a wavy sphere's zero level against the
        // measured distance, from nodes around it and points on and just off the triangles:
        // it never rejects a triangle at its distance plus the search's tie tolerance, and it
        // rejects most triangles at half their distance. Triangles of (nearly) zero area are
        // left out: where the zero level passes exactly through a node, marching tetrahedra
        // cut slivers whose computed normal is rounding noise, and the plane part of the bound
        // (this one's and the plane-or-ball bound's before it) is then no bound.
        let lat = Lattice::unit(41).unwrap();
        let f = |p: DVec3| p.length() - 0.3 - 0.02 * (7.0 * p.x).sin() * (5.0 * p.y).cos();
        let cross = crossing_cells_of_fn(&lat, &f).unwrap();
        let nb: NarrowBand<DtGrid<C3>> = band_around(&lat, &cross, 2).unwrap();
        let phi: Vec<f64> = nb.band.coords().map(|c| f(lat.pos(c))).collect();
        let l = level(&lat, &nb.band, &phi);
        let tris = Tris::new(&l.tris);
        let mut points: Vec<DVec3> = nb.band.coords().step_by(7).map(|c| lat.pos(c)).collect();
        points.extend(l.tris.iter().step_by(5).flat_map(|[a, b, c]| {
            let m = (*a + *b + *c) / 3.0;
            [m, m + 1e-9 * lat.h * (*b - *a), *a + 1e-13 * (*c - *a)]
        }));
        let tie = 1e-12 * lat.h;
        let (mut tested, mut rejected) = (0usize, 0usize);
        for (k, p) in points.iter().enumerate() {
            for t in (k % 3..l.tris.len()).step_by(3) {
                let [a, b, c] = l.tris[t];
                let area = (b - a).cross(c - a).length();
                if area < 1e-8 * (b - a).length() * (c - a).length() {
                    continue;
                }
                let d = tris.distance(t as u32, *p);
                if d > 4.0 * lat.h {
                    continue;
                }
                assert!(!tris.beyond(t as u32, *p, d + tie), "{p:?} {t} {d}");
                tested += 1;
                rejected += tris.beyond(t as u32, *p, 0.5 * d) as usize;
            }
        }
        println!("{rejected} of {tested} rejected at half the distance");
        assert!(tested > 100_000, "{tested}");
        assert!(2 * rejected > tested, "{rejected} of {tested}");
    }

    #[test]
    fn seeds_skip_only_triangles_that_lose() {
        // The first pass skips the triangles a seed measured in its own cells: the result is
        // that of passes without the seed flags, on an ellipsoid and a wavy sphere.
        let shapes: [(usize, &(dyn Fn(DVec3) -> f64 + Sync)); 2] = [
            (29, &|p: DVec3| {
                (p.x / 0.3).powi(2) + (p.y / 0.25).powi(2) + (p.z / 0.2).powi(2) - 1.0
            }),
            (41, &|p: DVec3| {
                p.length() - 0.3 - 0.02 * (7.0 * p.x).sin() * (5.0 * p.y).cos()
            }),
        ];
        for (n, f) in shapes {
            let lat = Lattice::unit(n).unwrap();
            let cross = crossing_cells_of_fn(&lat, &f).unwrap();
            let nb: NarrowBand<DtGrid<C3>> = band_around(&lat, &cross, 2).unwrap();
            let phi: Vec<f64> = nb.band.coords().map(|c| f(lat.pos(c))).collect();
            let l = level(&lat, &nb.band, &phi);
            let tris = Tris::new(&l.tris);
            let coords: Vec<C3> = nb.band.coords().collect();
            let nbr = neighbourhoods(&coords);
            let pos = |i: usize| lat.pos(coords[i]);
            let tie = 1e-12 * lat.h;
            let (best, dist, seed, flags) = seeds(&lat, &l, &tris, &coords, tie);
            let clear = flags.iter().filter(|&&f| f & CLEAR != 0).count();
            let seeded = seed.iter().filter(|&&s| s).count();
            assert!(2 * clear > seeded, "{clear} of {seeded} seeds skip");
            let no_flags = vec![0u8; coords.len()];
            for layers in [1, 3, 8] {
                let (mut b1, mut d1) = (best.clone(), dist.clone());
                propagate(&tris, &nbr, &pos, layers, tie, &flags, &mut b1, &mut d1);
                let (mut b2, mut d2) = (best.clone(), dist.clone());
                propagate(&tris, &nbr, &pos, layers, tie, &no_flags, &mut b2, &mut d2);
                assert_eq!(b1, b2, "{n}³, {layers} passes");
                assert!(d1.iter().zip(&d2).all(|(a, b)| a.to_bits() == b.to_bits()));
            }
        }
    }

    #[test]
    fn sphere_distance_and_kept_zero_level() {
        let lat = Lattice::unit(33).unwrap();
        let r = 0.27;
        let f = |p: DVec3| p.length() - r;
        let cross = crossing_cells_of_fn(&lat, &f).unwrap();
        let nb: NarrowBand<DtGrid<C3>> = band_around(&lat, &cross, 2).unwrap();
        // A field that is not a distance (gradient 2|x|).
        let phi: Vec<f64> = nb
            .band
            .coords()
            .map(|c| lat.pos(c).length_squared() - r * r)
            .collect();
        let d = extend_distance(&lat, &nb.band, &phi, &nb.band, Keep::Nothing, 8.0 * lat.h);
        for (c, di) in nb.band.coords().zip(&d) {
            let e = f(lat.pos(c));
            // The trilinear zero level lies within 3h²/(8r) of the sphere.
            assert!((di - e).abs() < lat.h * lat.h / r, "{c:?} {di} {e}");
        }
        // Keeping the crossing corners keeps every sign, so the zero level does not move.
        let k = extend_distance(&lat, &nb.band, &phi, &nb.band, Keep::Crossing, 8.0 * lat.h);
        for ((a, b), e) in phi.iter().zip(&k).zip(&d) {
            assert_eq!(*a < 0.0, *b < 0.0);
            assert!((b - e).abs() < 0.6 * lat.h, "{b} {e}");
        }
        let (area, _) = zero_level_integral(&lat, &nb.band, &k, |_| 1.0);
        let exact = 4.0 * std::f64::consts::PI * r * r;
        assert!((area / exact - 1.0).abs() < 0.01);
    }
}
