//! Validation and orientation repair of a closed triangulated surface.
//!
//! Rejected (with [`Error::InvalidInput`] naming the first offender and the counts): a
//! non-finite coordinate, a vertex index out of range, a degenerate triangle (a repeated vertex
//! or an area below `1e-14` times its longest edge squared), a hole (an edge used by one
//! triangle), a non-manifold edge (used by more than two) and a non-manifold vertex (its
//! triangles form several fans: two sheets touching at a point).
//!
//! Repaired: inconsistent orientation. Each connected component (triangles joined through
//! shared edges) is re-oriented by a breadth-first search from its lowest-numbered triangle, so
//! that the two triangles of every edge traverse it in opposite directions; then each component
//! whose enclosed volume (`Σ a · (b × c) / 6`) is negative is flipped as a whole, so that every
//! component is outward. A component that cannot be oriented (a Klein-bottle-like surface) is
//! rejected. Every component being outward is right for disjoint solids; a cavity (a
//! component nested inside another) comes out outward too, i.e. filled.

use crate::error::{Error, Result};
use crate::geom::DVec3;
use std::collections::{HashMap, VecDeque};

/// The outcome of [`orient`]: the triangles, consistently and outward oriented, and the repair.
pub struct Oriented {
    /// The triangles, outward oriented.
    pub triangles: Vec<[u32; 3]>,
    /// For each triangle and each local edge `i` (from local vertex `i` to `i + 1`), the
    /// triangle on the other side.
    pub neighbours: Vec<[u32; 3]>,
    /// The number of triangles whose orientation was reversed.
    pub flipped: usize,
    /// The number of connected components.
    pub components: usize,
}

/// Checks coordinates, indices and triangle shapes.
pub fn check_elements(points: &[DVec3], triangles: &[[u32; 3]]) -> Result<()> {
    if let Some(i) = points.iter().position(|p| !p.is_finite()) {
        let n = points.iter().filter(|p| !p.is_finite()).count();
        return Err(Error::InvalidInput(format!(
            "surface: vertex {i} has a non-finite coordinate ({n} such vertices)"
        )));
    }
    if triangles.is_empty() {
        return Err(Error::InvalidInput("surface: no triangles".into()));
    }
    let np = points.len();
    if let Some(t) = triangles
        .iter()
        .position(|t| t.iter().any(|&v| v as usize >= np))
    {
        return Err(Error::InvalidInput(format!(
            "surface: triangle {t} {:?} refers to a vertex beyond the {np} vertices",
            triangles[t]
        )));
    }
    let degenerate = |t: &[u32; 3]| {
        let [a, b, c] = t.map(|v| points[v as usize]);
        let longest = (b - a)
            .length_squared()
            .max((c - b).length_squared())
            .max((a - c).length_squared());
        let twice_area = (b - a).cross(c - a).length();
        t[0] == t[1]
            || t[1] == t[2]
            || t[0] == t[2]
            || twice_area.partial_cmp(&(2e-14 * longest)) != Some(std::cmp::Ordering::Greater)
    };
    if let Some(t) = triangles.iter().position(degenerate) {
        let n = triangles.iter().filter(|t| degenerate(t)).count();
        return Err(Error::InvalidInput(format!(
            "surface: triangle {t} {:?} is degenerate (zero area or a repeated vertex; \
             {n} degenerate triangles)",
            triangles[t]
        )));
    }
    Ok(())
}

/// Builds the edge adjacency (rejecting holes and non-manifold edges) and orients every
/// component consistently and outward (see the module documentation).
pub fn orient(points: &[DVec3], triangles: &[[u32; 3]]) -> Result<Oriented> {
    // Undirected edge -> the (triangle, local edge) that use it, in triangle order.
    let mut uses: HashMap<(u32, u32), Vec<(u32, u8)>> =
        HashMap::with_capacity(3 * triangles.len() / 2);
    for (t, tri) in triangles.iter().enumerate() {
        for i in 0..3 {
            let (a, b) = (tri[i], tri[(i + 1) % 3]);
            uses.entry((a.min(b), a.max(b)))
                .or_default()
                .push((t as u32, i as u8));
        }
    }
    let mut holes: Vec<(u32, u32, u32)> = Vec::new();
    let mut non_manifold: Vec<(u32, u32, u32, usize)> = Vec::new();
    for (&(a, b), u) in &uses {
        match u.len() {
            1 => holes.push((u[0].0, a, b)),
            2 => {}
            m => non_manifold.push((u[0].0, a, b, m)),
        }
    }
    if !holes.is_empty() {
        holes.sort_unstable();
        let (t, a, b) = holes[0];
        return Err(Error::InvalidInput(format!(
            "surface is not closed: edge ({a}, {b}) of triangle {t} is used by one triangle only \
             ({} boundary edges)",
            holes.len()
        )));
    }
    if !non_manifold.is_empty() {
        non_manifold.sort_unstable();
        let (t, a, b, m) = non_manifold[0];
        return Err(Error::InvalidInput(format!(
            "surface is not a manifold: edge ({a}, {b}) of triangle {t} is used by {m} triangles \
             ({} non-manifold edges)",
            non_manifold.len()
        )));
    }
    let mut neighbours = vec![[u32::MAX; 3]; triangles.len()];
    for u in uses.values() {
        let ((t0, i0), (t1, i1)) = (u[0], u[1]);
        neighbours[t0 as usize][i0 as usize] = t1;
        neighbours[t1 as usize][i1 as usize] = t0;
    }
    // BFS: flip[t] says whether triangle t is reversed relative to the input.
    let n = triangles.len();
    let mut flip: Vec<Option<bool>> = vec![None; n];
    let mut components = 0;
    let mut queue = VecDeque::new();
    let directed = |t: usize, f: bool, i: usize| {
        let tri = triangles[t];
        let (a, b) = (tri[i], tri[(i + 1) % 3]);
        if f {
            (b, a)
        } else {
            (a, b)
        }
    };
    for seed in 0..n {
        if flip[seed].is_some() {
            continue;
        }
        components += 1;
        flip[seed] = Some(false);
        queue.push_back(seed);
        let mut members = vec![seed];
        while let Some(t) = queue.pop_front() {
            let ft = flip[t].unwrap_or(false);
            for (i, &s) in neighbours[t].iter().enumerate() {
                let s = s as usize;
                let (a, b) = directed(t, ft, i);
                // The neighbour must traverse the edge as (b, a).
                let tri = triangles[s];
                let j = (0..3)
                    .find(|&j| {
                        let (x, y) = (tri[j], tri[(j + 1) % 3]);
                        (x.min(y), x.max(y)) == (a.min(b), a.max(b))
                    })
                    .unwrap_or(0);
                let same_as_input = (tri[j], tri[(j + 1) % 3]) == (b, a);
                let needed = !same_as_input;
                match flip[s] {
                    None => {
                        flip[s] = Some(needed);
                        members.push(s);
                        queue.push_back(s);
                    }
                    Some(f) if f != needed => {
                        return Err(Error::InvalidInput(format!(
                            "surface is not orientable: triangles {t} and {s} cannot be \
                             oriented consistently across edge ({a}, {b})"
                        )));
                    }
                    Some(_) => {}
                }
            }
        }
        // Outward: positive enclosed volume (relative to the component's first vertex, to
        // limit cancellation).
        let origin = points[triangles[seed][0] as usize];
        let volume: f64 = members
            .iter()
            .map(|&t| {
                let [a, b, c] = triangles[t].map(|v| points[v as usize] - origin);
                let v = a.dot(b.cross(c));
                if flip[t] == Some(true) {
                    -v
                } else {
                    v
                }
            })
            .sum();
        if volume < 0.0 {
            for &t in &members {
                flip[t] = flip[t].map(|f| !f);
            }
        }
    }
    let mut flipped = 0;
    let mut out = Vec::with_capacity(n);
    let mut out_nb = Vec::with_capacity(n);
    for t in 0..n {
        let [a, b, c] = triangles[t];
        let nb = neighbours[t];
        if flip[t] == Some(true) {
            flipped += 1;
            // [a, c, b]: edges (a, c), (c, b), (b, a) = old edges 2, 1, 0.
            out.push([a, c, b]);
            out_nb.push([nb[2], nb[1], nb[0]]);
        } else {
            out.push([a, b, c]);
            out_nb.push(nb);
        }
    }
    check_vertex_fans(points.len(), &out, &out_nb)?;
    Ok(Oriented {
        triangles: out,
        neighbours: out_nb,
        flipped,
        components,
    })
}

/// Rejects a vertex whose triangles form more than one fan (two sheets touching at a point):
/// walking around the vertex across the (consistently oriented) edges that start at it must
/// visit all of its triangles.
fn check_vertex_fans(
    n_points: usize,
    triangles: &[[u32; 3]],
    neighbours: &[[u32; 3]],
) -> Result<()> {
    let mut incident = vec![0usize; n_points];
    let mut first = vec![u32::MAX; n_points];
    for (t, tri) in triangles.iter().enumerate() {
        for &v in tri {
            incident[v as usize] += 1;
            if first[v as usize] == u32::MAX {
                first[v as usize] = t as u32;
            }
        }
    }
    let mut bad: Option<(usize, usize, usize)> = None;
    let mut count = 0;
    for v in 0..n_points {
        if incident[v] == 0 {
            continue;
        }
        let start = first[v] as usize;
        let (mut t, mut fan) = (start, 0);
        loop {
            fan += 1;
            let i = (0..3).find(|&i| triangles[t][i] as usize == v).unwrap_or(0);
            // After crossing the edge (v, w) the neighbour holds (w, v); its next edge from v
            // is the one to cross next.
            t = neighbours[t][i] as usize;
            if t == start || fan > incident[v] {
                break;
            }
        }
        if fan != incident[v] {
            count += 1;
            bad.get_or_insert((v, incident[v], fan));
        }
    }
    if let Some((v, n, fan)) = bad {
        return Err(Error::InvalidInput(format!(
            "surface is not a manifold at vertex {v}: a fan of {fan} of its {n} triangles \
             closes without the others ({count} such vertices)"
        )));
    }
    Ok(())
}
