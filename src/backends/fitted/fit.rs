//! Interface fitting (001 §2, Fig. 2.2): the zero level of a P1 level set becomes a chain of mesh
//! edges. A vertex is added where the level set changes sign along an edge (linear
//! interpolation), and every cut triangle is split conformingly into triangles that lie on one
//! side of the zero level: with one lone vertex into a corner triangle and a quadrilateral cut
//! along its shorter diagonal (3 triangles), with a vertex on the zero level and the opposite
//! edge cut into 2 triangles.
//!
//! **Snapping.** One rule decides whether the zero level passes through a vertex: a value with
//! `|u - iso| <= snap · max |u - iso|` is set to zero, and every triangle reads the snapped values,
//! so two neighbours always agree on which edges are cut. An edge is cut exactly when its two
//! snapped values have strictly opposite signs, so the new vertex lies strictly inside it.
//!
//! **Labels** follow the convention of `mmg2d -ls`: triangles where the level set is negative
//! get [`REF_INSIDE`] (3), the others [`REF_OUTSIDE`] (2), edges between the two sides
//! [`REF_INTERFACE`] (10); boundary and interior edge labels of the base mesh are kept on the
//! pieces of those edges.
//!
//! **Back to the base mesh.** The base vertices keep their indices (the new vertices follow
//! them), and every fitted triangle records its base triangle, so a P1 field on the fitted mesh
//! restricts to the base mesh by truncation ([`FittedMesh::restrict_to_base`]) and a base field
//! extends to the fitted mesh by linear interpolation along the cut edges
//! ([`FittedMesh::extend_from_base`]).

use crate::error::{Error, Result};
use crate::geom::DVec2;
use crate::mesh::build::validate_elements;
use crate::mesh::{check_p1_field, next, prev, Mesh2, NONE};
use std::collections::HashMap;

/// Label of the triangles where the level set is negative (as `mmg2d -ls`).
pub const REF_INSIDE: i32 = 3;
/// Label of the triangles where the level set is positive (as `mmg2d -ls`).
pub const REF_OUTSIDE: i32 = 2;
/// Label of the edges on the zero level (as `mmg2d -ls`).
pub const REF_INTERFACE: i32 = 10;

/// Options of [`fit`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitOptions {
    /// The level to fit (the interface is `{u = iso}`); 0 by default.
    pub iso: f64,
    /// Relative snapping tolerance: values with `|u - iso| <= snap · max |u - iso|` are on the
    /// interface; `1e-12` by default.
    pub snap: f64,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            iso: 0.0,
            snap: 1e-12,
        }
    }
}

/// An interface-fitted mesh and its relation to the base mesh it was cut from.
#[derive(Debug, Clone)]
pub struct FittedMesh {
    /// The fitted mesh: labels [`REF_INSIDE`] / [`REF_OUTSIDE`], interface edges
    /// [`REF_INTERFACE`]; vertices `0..n_base_vertices` are the base vertices.
    pub mesh: Mesh2,
    /// The level set minus `iso` on the fitted mesh, snapped: exactly 0 at the new vertices
    /// and at snapped base vertices.
    pub u: Vec<f64>,
    /// Number of base vertices (the first vertices of `mesh`).
    pub n_base_vertices: usize,
    /// For every new vertex `n_base_vertices + k`: the base edge `[a, b]` it lies on and its
    /// position `s` on it (`p = (1 - s) p_a + s p_b`).
    pub cuts: Vec<([u32; 2], f64)>,
    /// For every fitted triangle, the base triangle it lies in.
    pub parent: Vec<u32>,
    /// Number of base vertices whose value was snapped to the interface.
    pub snapped: usize,
}

impl FittedMesh {
    /// Area of the inside (the triangles labelled [`REF_INSIDE`]).
    pub fn area_inside(&self) -> f64 {
        let m = &self.mesh;
        m.live_tris()
            .filter(|&t| m.tri_ref[t] == REF_INSIDE)
            .map(|t| m.tri_area(t))
            .sum()
    }

    /// Length of the interface: the edges labelled [`REF_INTERFACE`], each counted once.
    pub fn interface_length(&self) -> f64 {
        let m = &self.mesh;
        let mut len = 0.0;
        for t in m.live_tris() {
            for i in 0..3 {
                let nb = m.neighbours[t][i];
                if m.edge_ref[t][i] == REF_INTERFACE && (nb == NONE || (nb as usize) > t) {
                    let [a, b] = m.edge_vertices(t, i);
                    len += (m.points[a as usize] - m.points[b as usize]).length();
                }
            }
        }
        len
    }

    /// The interface edges `[a, b]` (fitted vertex indices), each once, oriented with the
    /// inside on the left.
    pub fn interface_edges(&self) -> Vec<[u32; 2]> {
        let m = &self.mesh;
        let mut out = Vec::new();
        for t in m.live_tris() {
            if m.tri_ref[t] != REF_INSIDE {
                continue;
            }
            for i in 0..3 {
                if m.edge_ref[t][i] == REF_INTERFACE {
                    out.push(m.edge_vertices(t, i));
                }
            }
        }
        out
    }

    /// A P1 field on the fitted mesh restricted to the base mesh (its first values).
    pub fn restrict_to_base(&self, f: &[f64]) -> Result<Vec<f64>> {
        check_p1_field(self.mesh.n_points(), f, "fitted field")?;
        Ok(f[..self.n_base_vertices].to_vec())
    }

    /// A P1 field on the base mesh extended to the fitted mesh: at a new vertex, the linear
    /// interpolation along its base edge (the fitted field is the same P1 function).
    pub fn extend_from_base(&self, f: &[f64]) -> Result<Vec<f64>> {
        check_p1_field(self.n_base_vertices, f, "base field")?;
        let mut out = Vec::with_capacity(self.mesh.n_points());
        out.extend_from_slice(f);
        out.extend(
            self.cuts
                .iter()
                .map(|&([a, b], s)| (1.0 - s) * f[a as usize] + s * f[b as usize]),
        );
        Ok(out)
    }
}

/// The snapped values `u - iso` (see the module documentation) and the number of snapped
/// vertices: the single place that decides whether a vertex is on the interface.
pub fn snapped_values(u: &[f64], opts: &FitOptions) -> (Vec<f64>, usize) {
    let scale = u.iter().fold(0.0f64, |m, &x| m.max((x - opts.iso).abs()));
    let tol = opts.snap * scale;
    let mut snapped = 0;
    let v = u
        .iter()
        .map(|&x| {
            let d = x - opts.iso;
            if d.abs() <= tol {
                snapped += usize::from(d != 0.0);
                0.0
            } else {
                d
            }
        })
        .collect();
    (v, snapped)
}

fn sign(x: f64) -> i8 {
    if x < 0.0 {
        -1
    } else if x > 0.0 {
        1
    } else {
        0
    }
}

/// Fits the level `opts.iso` of the P1 field `u` into the conforming mesh `base` (see the module
/// documentation). The base mesh must have no deleted triangles (as read from a file or after
/// [`crate::mesh::TriMesh::compact`]).
///
/// Errors: a field of the wrong length or with non-finite values ([`Error::InvalidField`]), a
/// level that does not cross the mesh ([`Error::EmptyLevelSet`]: every value on one side),
/// a base mesh with deleted triangles ([`Error::InvalidInput`]).
pub fn fit(base: &Mesh2, u: &[f64], opts: &FitOptions) -> Result<FittedMesh> {
    check_p1_field(base.n_points(), u, "level set")?;
    if base.live_tris().count() != base.n_tris() {
        return Err(Error::InvalidInput(
            "interface fitting needs a mesh without deleted triangles (compact it first)".into(),
        ));
    }
    let (v, snapped) = snapped_values(u, opts);
    let has_neg = v.iter().any(|&x| x < 0.0);
    let has_pos = v.iter().any(|&x| x > 0.0);
    if !(has_neg && has_pos) {
        let side = if has_neg {
            "below it"
        } else if has_pos {
            "above it"
        } else {
            "on it"
        };
        let zeros: Vec<usize> = (0..v.len()).filter(|&i| v[i] == 0.0).collect();
        let touch = match (zeros.first(), has_neg || has_pos) {
            (Some(&z), true) => format!(
                " or on it at {} vertices only (e.g. vertex {z} at {}), which bound no region",
                zeros.len(),
                base.points[z]
            ),
            _ => String::new(),
        };
        return Err(Error::EmptyLevelSet(format!(
            "the level {} does not cross the mesh: every vertex value is {side}{touch} \
             (mesh unchanged)",
            opts.iso
        )));
    }
    let nb = base.n_points();
    // Room for the new vertices (about one per cut edge) without regrowing.
    let extra = base.n_tris() / 8 + 16;
    let mut points = Vec::with_capacity(nb + extra);
    points.extend_from_slice(&base.points);
    let mut values = Vec::with_capacity(nb + extra);
    values.extend_from_slice(&v);
    let mut cuts: Vec<([u32; 2], f64)> = Vec::new();
    // The new vertex of each cut edge by its vertices (smaller first), so each edge is cut once,
    // in the order the triangles meet it (a map: few edges are cut).
    let mut cut_of: HashMap<[u32; 2], u32> = HashMap::new();
    let mut cut = |t: usize, k: usize, points: &mut Vec<DVec2>, values: &mut Vec<f64>| -> u32 {
        let [a, b] = base.edge_vertices(t, k);
        let (lo, hi) = (a.min(b), a.max(b));
        if let Some(&m) = cut_of.get(&[lo, hi]) {
            return m;
        }
        let (ul, uh) = (v[lo as usize], v[hi as usize]);
        let s = ul / (ul - uh);
        let (pl, ph) = (base.points[lo as usize], base.points[hi as usize]);
        points.push(pl + (ph - pl) * s);
        values.push(0.0);
        cuts.push(([lo, hi], s));
        let m = (points.len() - 1) as u32;
        cut_of.insert([lo, hi], m);
        m
    };
    let mut tris: Vec<[u32; 3]> = Vec::with_capacity(base.n_tris() + base.n_tris() / 4);
    let mut tri_ref: Vec<i32> = Vec::with_capacity(tris.capacity());
    let mut parent: Vec<u32> = Vec::with_capacity(tris.capacity());
    let label = |s: i8| if s < 0 { REF_INSIDE } else { REF_OUTSIDE };
    for t in 0..base.n_tris() {
        let tri = base.tris[t];
        let s = tri.map(|x| sign(v[x as usize]));
        let is_cut = |i: usize| s[next(i)] * s[prev(i)] < 0;
        let n_cut = (0..3).filter(|&i| is_cut(i)).count();
        let mut push = |tr: [u32; 3], r: i32| {
            tris.push(tr);
            tri_ref.push(r);
            parent.push(t as u32);
        };
        match n_cut {
            0 => push(tri, label(s.into_iter().min().unwrap_or(0))),
            1 => {
                // A vertex on the level (s = 0) and the opposite edge cut.
                let i = (0..3).find(|&i| is_cut(i)).unwrap_or(0);
                let (z, a, b) = (tri[i], tri[next(i)], tri[prev(i)]);
                let m = cut(t, i, &mut points, &mut values);
                push([z, a, m], label(s[next(i)]));
                push([z, m, b], label(s[prev(i)]));
            }
            _ => {
                // The lone vertex i is opposite the uncut edge.
                let i = (0..3).find(|&i| !is_cut(i)).unwrap_or(0);
                let (a, b, c) = (tri[i], tri[next(i)], tri[prev(i)]);
                let p = cut(t, prev(i), &mut points, &mut values);
                let q = cut(t, next(i), &mut points, &mut values);
                push([a, p, q], label(s[i]));
                let other = label(s[next(i)]);
                let d = |x: u32, y: u32| (points[x as usize] - points[y as usize]).length_squared();
                if d(p, c) <= d(b, q) {
                    push([p, b, c], other);
                    push([p, c, q], other);
                } else {
                    push([p, b, q], other);
                    push([b, c, q], other);
                }
            }
        }
    }
    validate_elements(&points, &tris)?;
    // The pieces of a base triangle are consecutive: `first[t]..first[t + 1]`.
    let mut first = Vec::with_capacity(base.n_tris() + 1);
    first.push(0u32);
    for (k, w) in parent.windows(2).enumerate() {
        if w[0] != w[1] {
            first.push(k as u32 + 1);
        }
    }
    first.push(tris.len() as u32);
    let on_base_edge = |x: u32, a: u32, b: u32| {
        x == a
            || x == b
            || (x as usize >= nb && {
                let [ca, cb] = cuts[x as usize - nb].0;
                (ca == a && cb == b) || (ca == b && cb == a)
            })
    };
    // The piece of the base triangles `range` with the directed edge (x, y).
    let find_edge = |range: std::ops::Range<usize>, x: u32, y: u32| -> Option<(usize, usize)> {
        range.into_iter().find_map(|u| {
            let tr = tris[u];
            (0..3)
                .find(|&i| tr[next(i)] == x && tr[prev(i)] == y)
                .map(|i| (u, i))
        })
    };
    // Adjacency from the base mesh's: an edge of a piece is shared with another piece of the
    // same base triangle, or lies on a base edge and is shared with a piece of the base
    // neighbour across it (which cut that edge at the same new vertex), or is on the boundary.
    let mut neighbours = vec![[NONE; 3]; tris.len()];
    let mut edge_ref = vec![[0i32; 3]; tris.len()];
    let not_shared = |pt: usize, n: usize, [a, b]: [u32; 2]| {
        Error::InvalidInput(format!(
            "interface fitting: the base triangles {pt} and {n} do not share the edge of \
             vertices {a} and {b} (not a conforming mesh)"
        ))
    };
    for (t, &pt) in parent.iter().enumerate() {
        let pt = pt as usize;
        let own = first[pt] as usize..first[pt + 1] as usize;
        let tr = tris[t];
        if own.len() == 1 {
            // An uncut base triangle is its one piece, with the same corners in the same order:
            // its edge j is the base edge j, shared with a piece of the base neighbour across it.
            for j in 0..3 {
                let (x, y) = (tr[next(j)], tr[prev(j)]);
                let mut r = base.edge_ref[pt][j];
                let n = base.neighbours[pt][j];
                if n != NONE {
                    let n = n as usize;
                    let Some((u, _)) = find_edge(first[n] as usize..first[n + 1] as usize, y, x)
                    else {
                        return Err(not_shared(pt, n, [x, y]));
                    };
                    neighbours[t][j] = u as u32;
                    if tri_ref[u] != tri_ref[t] {
                        r = REF_INTERFACE;
                    }
                }
                edge_ref[t][j] = r;
            }
            continue;
        }
        for j in 0..3 {
            let (x, y) = (tr[next(j)], tr[prev(j)]);
            let mut r = 0;
            let mut nbr = find_edge(own.clone(), y, x);
            if nbr.is_none() {
                for k in 0..3 {
                    let [a, b] = base.edge_vertices(pt, k);
                    if on_base_edge(x, a, b) && on_base_edge(y, a, b) {
                        r = base.edge_ref[pt][k];
                        let n = base.neighbours[pt][k];
                        if n != NONE {
                            let n = n as usize;
                            nbr = find_edge(first[n] as usize..first[n + 1] as usize, y, x);
                            if nbr.is_none() {
                                return Err(not_shared(pt, n, [a, b]));
                            }
                        }
                        break;
                    }
                }
            }
            if let Some((u, _)) = nbr {
                neighbours[t][j] = u as u32;
                if tri_ref[u] != tri_ref[t] {
                    r = REF_INTERFACE;
                }
            }
            edge_ref[t][j] = r;
        }
    }
    let mut mesh = Mesh2::assemble(points, tris, neighbours, tri_ref);
    mesh.edge_ref = edge_ref;
    mesh.vert_ref[..nb].copy_from_slice(&base.vert_ref);
    mesh.corner[..nb].copy_from_slice(&base.corner);
    mesh.required[..nb].copy_from_slice(&base.required);
    Ok(FittedMesh {
        mesh,
        u: values,
        n_base_vertices: nb,
        cuts,
        parent,
        snapped,
    })
}
