//! The zero level of a planar band field as polylines: marching squares on the band's cells
//! (a cell is cut where its corners change sign, `0` counting as positive; a saddle cell is
//! resolved by the sign of its bilinear centre value), with the crossing on each cut edge at the
//! root of the 1D cubic along the grid line and one point per cell on the bicubic zero level
//! between them ([`super::cubic`]). Polylines run counter-clockwise around the negative side,
//! as [`crate::levelset::Polyline`] documents; the enclosed area is the shoelace sum.

use super::cubic::{edge_root, Field, Patch};
use super::C2;
use crate::backends::dtgrid::band::Band;
use crate::geom::DVec2;
use crate::levelset::Polyline;
use std::collections::HashMap;

/// A cut edge: its lower node and its axis.
type EdgeKey = (C2, u8);

/// One piece of the zero level in one cell, oriented with the negative side on its left.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// The crossing where the piece enters the cell.
    pub a: DVec2,
    /// A point on the bicubic zero level between `a` and `b`.
    pub mid: DVec2,
    /// The crossing where it leaves.
    pub b: DVec2,
    /// The index of its cell in [`ZeroLevel::cells`].
    pub cell: u32,
    start: EdgeKey,
    end: EdgeKey,
}

/// The zero level of a band field.
#[derive(Debug, Clone, Default)]
pub struct ZeroLevel {
    /// The cut cells (lowest corners, sorted) with their reconstruction patches.
    pub cells: Vec<Patch>,
    /// The pieces, in cell order.
    pub segments: Vec<Segment>,
    /// The pieces chained into polylines.
    pub polylines: Vec<Polyline>,
}

/// The corners of a cell in counter-clockwise order (corner `k`: bit 0 along x, bit 1 along y).
const CCW: [usize; 4] = [0, 1, 3, 2];

/// The key of the counter-clockwise edge `i` of `cell` (edge `i` runs from `CCW[i]` to
/// `CCW[i + 1]`).
fn edge_key(cell: C2, i: usize) -> EdgeKey {
    match i {
        0 => (cell, 0),
        1 => ([cell[0] + 1, cell[1]], 1),
        2 => ([cell[0], cell[1] + 1], 0),
        _ => (cell, 1),
    }
}

/// The crossing point on edge `key` of the field (values at its ends of different signs).
fn crossing(f: &Field<'_>, key: EdgeKey, vlo: f64, vhi: f64) -> DVec2 {
    let (lo, axis) = key;
    let t = edge_root(f, lo, axis as usize, vlo, vhi);
    let mut p = f.plane.pos(lo);
    p[axis as usize] += t * f.plane.h;
    p
}

/// The pieces of the zero level in `cell` with corner values `v`, as (exit edge, entry edge)
/// pairs of counter-clockwise edge numbers.
fn cell_pieces(v: &[f64; 4]) -> Vec<(usize, usize)> {
    let neg = v.map(|x| x < 0.0);
    let (mut exits, mut entries) = (Vec::new(), Vec::new());
    for i in 0..4 {
        let (from, to) = (CCW[i], CCW[(i + 1) % 4]);
        if neg[from] && !neg[to] {
            exits.push(i);
        } else if !neg[from] && neg[to] {
            entries.push(i);
        }
    }
    if exits.len() == 1 {
        return vec![(exits[0], entries[0])];
    }
    if exits.is_empty() {
        return Vec::new();
    }
    // A saddle: the negative corners are joined through the centre when its bilinear value is
    // negative (each exit pairs with the next entry), else separated (the previous entry).
    let joined = v.iter().sum::<f64>() < 0.0;
    exits
        .iter()
        .map(|&e| {
            let pick = if joined { (e + 1) % 4 } else { (e + 3) % 4 };
            let entry = *entries.iter().find(|&&x| x == pick).unwrap_or(&entries[0]);
            (e, entry)
        })
        .collect()
}

/// The zero level of the band field `f` (see the module documentation).
pub fn zero_level(f: &Field<'_>) -> ZeroLevel {
    let mut z = ZeroLevel::default();
    for (cell, idx) in f.band.cells() {
        let v = idx.map(|i| f.u[i as usize]);
        let pieces = cell_pieces(&v);
        if pieces.is_empty() {
            continue;
        }
        let id = z.cells.len() as u32;
        let patch = Patch::of(f, cell).unwrap_or_else(|| Patch::linear(f.plane, cell, v));
        for (exit, entry) in pieces {
            let end_point = |i: usize| {
                let (from, to) = (CCW[i], CCW[(i + 1) % 4]);
                let key = edge_key(cell, i);
                // Ends in the key's order (lower node first).
                let (vlo, vhi) = if i < 2 {
                    (v[from], v[to])
                } else {
                    (v[to], v[from])
                };
                (key, crossing(f, key, vlo, vhi))
            };
            let (start, a) = end_point(exit);
            let (end, b) = end_point(entry);
            let mid = patch.project(0.5 * (a + b), 4);
            let mid = if (mid - 0.5 * (a + b)).length() <= f.plane.h {
                mid
            } else {
                0.5 * (a + b)
            };
            z.segments.push(Segment {
                a,
                mid,
                b,
                cell: id,
                start,
                end,
            });
        }
        z.cells.push(patch);
    }
    z.polylines = chain(&z.segments);
    z
}

/// The segments chained through their shared edges: open chains first (from a segment no other
/// one ends at), then closed loops.
fn chain(segs: &[Segment]) -> Vec<Polyline> {
    let by_start: HashMap<EdgeKey, usize> =
        segs.iter().enumerate().map(|(i, s)| (s.start, i)).collect();
    let ends: std::collections::HashSet<EdgeKey> = segs.iter().map(|s| s.end).collect();
    let mut used = vec![false; segs.len()];
    let mut out = Vec::new();
    let heads: Vec<usize> = (0..segs.len())
        .filter(|&i| !ends.contains(&segs[i].start))
        .chain(0..segs.len())
        .collect();
    for first in heads {
        if used[first] {
            continue;
        }
        let mut points = Vec::new();
        let mut s = first;
        let closed = loop {
            used[s] = true;
            points.push(segs[s].a);
            points.push(segs[s].mid);
            match by_start.get(&segs[s].end) {
                Some(&n) if n == first => break true,
                Some(&n) if !used[n] => s = n,
                _ => {
                    points.push(segs[s].b);
                    break false;
                }
            }
        };
        out.push(Polyline { points, closed });
    }
    out
}

impl ZeroLevel {
    /// Whether the zero level has no piece.
    pub fn is_empty(&self) -> bool {
        self.segments.is_empty()
    }

    /// The area of the negative side: the shoelace sum over the polylines (an open polyline is
    /// closed by its chord) plus, per piece, the area between its two chords and the parabola
    /// through its three points (Simpson's rule: a third of the triangle they span), so the
    /// chords' `O(h²κ)` defect does not bias the area.
    pub fn enclosed_area(&self) -> f64 {
        let polygon: f64 = self
            .polylines
            .iter()
            .map(|l| {
                let n = l.points.len();
                (0..n)
                    .map(|i| l.points[i].perp_dot(l.points[(i + 1) % n]))
                    .sum::<f64>()
                    * 0.5
            })
            .sum();
        let bulge: f64 = self
            .segments
            .iter()
            .map(|s| 0.5 * (s.mid - s.a).perp_dot(s.b - s.a))
            .sum();
        polygon + bulge / 3.0
    }

    /// The length of the zero level.
    pub fn length(&self) -> f64 {
        self.polylines.iter().map(Polyline::length).sum()
    }

    /// The polylines moved by `shift` (local to world coordinates).
    pub fn shifted(&self, shift: DVec2) -> Vec<Polyline> {
        self.polylines
            .iter()
            .map(|l| Polyline {
                points: l.points.iter().map(|&p| p + shift).collect(),
                closed: l.closed,
            })
            .collect()
    }
}

impl ZeroLevel {
    /// The range of [`ZeroLevel::segments`] in each cut cell (segments are stored in cell order).
    pub fn cell_segments(&self) -> Vec<std::ops::Range<usize>> {
        let mut out = vec![0..0; self.cells.len()];
        for (i, s) in self.segments.iter().enumerate() {
            let r = &mut out[s.cell as usize];
            if r.start == r.end {
                *r = i..i + 1;
            } else {
                r.end = i + 1;
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backends::dtgrid::plane::lattice::{band_around, crossing_cells_of_fn};
    use crate::backends::dtgrid::plane::Plane;
    use std::f64::consts::PI;

    #[test]
    fn circle_and_slotted_shapes_area_and_length() {
        let centre = DVec2::new(0.51, 0.49);
        let mut errs = Vec::new();
        for n in [33, 65] {
            let plane = Plane::new(n, 1.0 / (n - 1) as f64).unwrap();
            let r = 0.3;
            let f = |p: DVec2| (p - centre).length() - r;
            let nb = band_around(&plane, &crossing_cells_of_fn(&plane, &f).unwrap(), 2).unwrap();
            let u: Vec<f64> = nb.band.coords().map(|c| f(plane.pos(c))).collect();
            let field = Field {
                plane: &plane,
                band: &nb.band,
                u: &u,
            };
            let z = zero_level(&field);
            assert_eq!(z.polylines.len(), 1);
            assert!(z.polylines[0].closed);
            let a = z.enclosed_area();
            errs.push((a / (PI * r * r) - 1.0).abs());
            assert!((z.length() / (2.0 * PI * r) - 1.0).abs() < 2e-3);
            for l in &z.polylines {
                for p in &l.points {
                    assert!(((*p - centre).length() - r).abs() < 1e-4);
                }
            }
        }
        assert!(errs[1] < 1e-4 && errs[1] < errs[0] / 3.0, "{errs:?}");
        // A hole: the negative side of −(|x − c| − r) is the outside, area negative.
        let plane = Plane::new(33, 1.0 / 32.0).unwrap();
        let f = |p: DVec2| 0.25 - (p - centre).length();
        let nb = band_around(&plane, &crossing_cells_of_fn(&plane, &f).unwrap(), 1).unwrap();
        let u: Vec<f64> = nb.band.coords().map(|c| f(plane.pos(c))).collect();
        let z = zero_level(&Field {
            plane: &plane,
            band: &nb.band,
            u: &u,
        });
        assert!((z.enclosed_area() + PI * 0.0625).abs() < 1e-3);
        // A saddle cell.
        assert_eq!(cell_pieces(&[-1.0, 1.0, 1.0, -1.0]).len(), 2);
        assert_eq!(cell_pieces(&[-1.0, 1.0, 1.0, -3.0]), vec![(0, 1), (2, 3)]);
    }
}
