//! The zero level of a Q1 band field as marching-tetrahedra triangles (the six Kuhn
//! tetrahedra of every crossed cell), each with its cell's corner values, so that a point on a
//! triangle can be moved onto the zero level of the trilinear interpolant (000 §2.4, the closest
//! points of the signed distance extension; the surface integrals of §4).

use super::band::Band;
use super::lattice::{crosses, Lattice, C3};
use super::surface::KUHN;
use crate::geom::DVec3;

/// The triangles of the zero level with the corner values of their cells.
pub(crate) struct Level {
    /// The triangles' corners, oriented with the negative side behind them.
    pub(super) tris: Vec<[DVec3; 3]>,
    /// Per triangle: its cell.
    pub(super) tri_cell: Vec<u32>,
    /// Per crossed cell: lowest corner, corner values.
    pub(super) cells: Vec<(C3, [f64; 8])>,
}

/// Appends the zero level of the linear interpolant of `values` on the tetrahedron `points` to
/// `out`, oriented with the negative side behind (the triangles of
/// [`TriangleSurface::add_tet_zero_level`], without allocating).
///
/// [`TriangleSurface::add_tet_zero_level`]: crate::levelset::TriangleSurface::add_tet_zero_level
fn tet_zero_level(points: [DVec3; 4], values: [f64; 4], out: &mut Vec<[DVec3; 3]>) {
    let (mut inside, mut outside) = ([0usize; 4], [0usize; 4]);
    let (mut ni, mut no) = (0, 0);
    for (i, v) in values.iter().enumerate() {
        if *v < 0.0 {
            inside[ni] = i;
            ni += 1;
        } else {
            outside[no] = i;
            no += 1;
        }
    }
    let cut = |a: usize, b: usize| {
        let (ua, ub) = (values[a], values[b]);
        let s = ua / (ua - ub);
        points[a] + s * (points[b] - points[a])
    };
    let mut poly = [DVec3::ZERO; 4];
    let np = match (ni, no) {
        (1, 3) => {
            for (q, &o) in poly.iter_mut().zip(&outside[..3]) {
                *q = cut(inside[0], o);
            }
            3
        }
        (3, 1) => {
            for (q, &i) in poly.iter_mut().zip(&inside[..3]) {
                *q = cut(i, outside[0]);
            }
            3
        }
        (2, 2) => {
            poly = [
                cut(inside[0], outside[0]),
                cut(inside[0], outside[1]),
                cut(inside[1], outside[1]),
                cut(inside[1], outside[0]),
            ];
            4
        }
        _ => return,
    };
    let centre =
        |idx: &[usize]| idx.iter().fold(DVec3::ZERO, |s, &i| s + points[i]) / idx.len() as f64;
    let (centre_in, centre_out) = (centre(&inside[..ni]), centre(&outside[..no]));
    let n = (poly[1] - poly[0]).cross(poly[2] - poly[0])
        + if np == 4 {
            (poly[2] - poly[0]).cross(poly[3] - poly[0])
        } else {
            DVec3::ZERO
        };
    let flip = n.dot(centre_out - centre_in) < 0.0;
    let mut push = |a: usize, b: usize, c: usize| {
        out.push(if flip {
            [poly[a], poly[c], poly[b]]
        } else {
            [poly[a], poly[b], poly[c]]
        });
    };
    push(0, 1, 2);
    if np == 4 {
        push(0, 2, 3);
    }
}

/// The zero level of the band field `phi` on `band`: its crossed cells, in storage order (those
/// of [`crossing_cells_of_band`](super::lattice::crossing_cells_of_band)), and their triangles.
pub(crate) fn level<B: Band<Coord = C3>>(lat: &Lattice, band: &B, phi: &[f64]) -> Level {
    let mut l = Level {
        tris: Vec::new(),
        tri_cell: Vec::new(),
        cells: Vec::new(),
    };
    for (c, idx) in band.cells() {
        let v: [f64; 8] = std::array::from_fn(|k| phi[idx[k] as usize]);
        if !crosses(&v) {
            continue;
        }
        let p0 = lat.pos(c);
        let before = l.tris.len();
        for t in KUHN {
            let pts = t.map(|k| p0 + lat.h * corner_offset(k));
            tet_zero_level(pts, t.map(|k| v[k]), &mut l.tris);
        }
        let id = l.cells.len() as u32;
        l.tri_cell
            .extend(std::iter::repeat(id).take(l.tris.len() - before));
        l.cells.push((c, v));
    }
    l
}

impl Level {
    /// The crossed cells' lowest corners, in storage order.
    pub(crate) fn crossing_cells(&self) -> Vec<C3> {
        self.cells.iter().map(|(c, _)| *c).collect()
    }

    /// `q` moved by two Newton steps onto the trilinear zero level of the cell of triangle `t`.
    pub(super) fn project(&self, lat: &Lattice, t: u32, mut q: DVec3) -> DVec3 {
        let (c0, v) = &self.cells[self.tri_cell[t as usize] as usize];
        let p0 = lat.pos(*c0);
        for _ in 0..2 {
            let (f, g) = trilinear(v, p0, lat.h, q);
            let g2 = g.length_squared();
            if g2 <= 1e-300 {
                break;
            }
            let step = g * (f / g2);
            if step.length() > 0.5 * lat.h {
                break;
            }
            q -= step;
        }
        q
    }
}

/// The area of the zero level of the band field `phi` and the integral of `g` over it: the
/// marching-tetrahedra triangles with a three-point rule whose points are projected onto the
/// trilinear zero level of their cells (the chords of a curved zero level lie `O(h²κ)` off it,
/// which would bias a radius measured on them).
pub fn zero_level_integral<B: Band<Coord = C3>>(
    lat: &Lattice,
    band: &B,
    phi: &[f64],
    g: impl Fn(DVec3) -> f64,
) -> (f64, f64) {
    let l = level(lat, band, phi);
    let (mut area, mut total) = (0.0, 0.0);
    for (t, &[a, b, c]) in l.tris.iter().enumerate() {
        let ar = 0.5 * (b - a).cross(c - a).length();
        area += ar;
        for (wa, wb, wc) in [(4.0, 1.0, 1.0), (1.0, 4.0, 1.0), (1.0, 1.0, 4.0)] {
            let x = l.project(lat, t as u32, (wa * a + wb * b + wc * c) / 6.0);
            total += ar / 3.0 * g(x);
        }
    }
    (area, total)
}

fn corner_offset(k: usize) -> DVec3 {
    DVec3::new((k & 1) as f64, ((k >> 1) & 1) as f64, (k >> 2) as f64)
}

/// The trilinear interpolant of the corner values `v` of the cell at `p0` and its gradient at `q`.
fn trilinear(v: &[f64; 8], p0: DVec3, h: f64, q: DVec3) -> (f64, DVec3) {
    let xi = (q - p0) / h;
    let (x, y, z) = (xi.x, xi.y, xi.z);
    let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
    // Along x on the four x-edges, then y, then z.
    let e = [(0, 1), (2, 3), (4, 5), (6, 7)].map(|(a, b)| (lerp(v[a], v[b], x), v[b] - v[a]));
    let f0 = (
        lerp(e[0].0, e[1].0, y),
        lerp(e[0].1, e[1].1, y),
        e[1].0 - e[0].0,
    );
    let f1 = (
        lerp(e[2].0, e[3].0, y),
        lerp(e[2].1, e[3].1, y),
        e[3].0 - e[2].0,
    );
    let val = lerp(f0.0, f1.0, z);
    let g = DVec3::new(lerp(f0.1, f1.1, z), lerp(f0.2, f1.2, z), f1.0 - f0.0) / h;
    (val, g)
}
