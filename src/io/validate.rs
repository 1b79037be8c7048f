//! Turning the raw arrays read from a file into a validated [`Mesh2`], with errors that name the
//! file and the line of the offending entity.
//!
//! Documented repair: a mesh whose triangles are *all* clockwise (e.g. a Gmsh surface with its
//! normal along `-z`) is reoriented by swapping two vertices of every triangle. Mixed
//! orientation is an error naming the first triangle whose orientation differs from the
//! majority.

use crate::error::{Error, MeshDefect, Result};
use crate::geom::{orient2d, DVec2};
use crate::mesh::build::build_adjacency;
use crate::mesh::{next, prev, Mesh2, NONE};
use std::path::Path;

/// An edge label read from a file: 0-based vertices, label, source line.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RawEdge {
    pub v: [u32; 2],
    pub label: i32,
    pub line: usize,
}

/// The raw 2D mesh data of a file (0-based indices, each entity with its source line).
#[derive(Debug, Default)]
pub(crate) struct RawMesh2 {
    pub points: Vec<DVec2>,
    pub vert_ref: Vec<i32>,
    pub point_line: Vec<usize>,
    pub tris: Vec<[u32; 3]>,
    pub tri_ref: Vec<i32>,
    pub tri_line: Vec<usize>,
    pub edges: Vec<RawEdge>,
    /// Whether the file lists edges at all (then unlisted interior edges are unlabelled).
    pub has_edges: bool,
    pub corners: Vec<(u32, usize)>,
    pub required: Vec<(u32, usize)>,
    /// Line of the end of the file (for errors without a better place).
    pub last_line: usize,
}

/// Validates `raw` and builds the mesh: indices, finite coordinates, orientation (with the
/// all-clockwise repair), conformity and labels; see the module documentation.
pub(crate) fn build_mesh(path: &Path, raw: RawMesh2) -> Result<Mesh2> {
    build_mesh_with(path, raw, true)
}

/// [`build_mesh`] without its last step, the full [`Mesh2::check`] (`check = false`): indices,
/// orientation, elements, adjacency and labels are still validated. For callers that check a
/// mesh derived from this one instead and re-read the input when that check fails.
pub(crate) fn build_mesh_with(path: &Path, mut raw: RawMesh2, check: bool) -> Result<Mesh2> {
    let perr = |line: usize, msg: String| Error::parse(path, line, msg);
    let np = raw.points.len();
    if raw.tris.is_empty() {
        return Err(perr(raw.last_line, "the mesh has no triangles".into()));
    }
    for (v, p) in raw.points.iter().enumerate() {
        if !p.is_finite() {
            return Err(perr(
                raw.point_line[v],
                format!("vertex {} has a non-finite coordinate", v + 1),
            ));
        }
    }
    let check_index = |v: u32, line: usize, what: &dyn Fn() -> String| -> Result<()> {
        if v as usize >= np {
            Err(perr(
                line,
                format!(
                    "{} refers to vertex {} but there are {np} vertices (indices are 1-based)",
                    what(),
                    v as u64 + 1
                ),
            ))
        } else {
            Ok(())
        }
    };
    for (t, tri) in raw.tris.iter().enumerate() {
        for &v in tri {
            check_index(v, raw.tri_line[t], &|| format!("triangle {}", t + 1))?;
        }
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
            return Err(perr(
                raw.tri_line[t],
                format!("triangle {} repeats a vertex", t + 1),
            ));
        }
    }
    for e in &raw.edges {
        for &v in &e.v {
            check_index(v, e.line, &|| "edge".into())?;
        }
    }
    for &(v, line) in raw.corners.iter().chain(&raw.required) {
        check_index(v, line, &|| "corner/required vertex entry".into())?;
    }
    orient(path, &mut raw)?;
    let tri_line = std::mem::take(&mut raw.tri_line);
    let point_line = std::mem::take(&mut raw.point_line);
    let defect = |d: MeshDefect, tris: &[[u32; 3]]| -> Error {
        let line = defect_line(&d, &tri_line, &point_line, tris).unwrap_or(raw.last_line);
        Error::parse(path, line, format!("invalid mesh: {}", one_based(&d)))
    };
    let to_defect = |e: Error, tris: &[[u32; 3]]| match e {
        Error::InvalidMesh(d) => defect(d, tris),
        other => other,
    };
    // `validate_elements` has nothing left to find here: the coordinates are finite, the indices
    // in range and distinct, and `orient` left every triangle strictly counter-clockwise (by the
    // same exact predicate).
    let neighbours = build_adjacency(&raw.tris).map_err(|e| to_defect(e, &raw.tris))?;
    let mut mesh = Mesh2::assemble(raw.points, raw.tris, neighbours, raw.tri_ref);
    mesh.vert_ref = raw.vert_ref;
    apply_edges(path, &mut mesh, &raw.edges, raw.has_edges)?;
    for &(v, _) in &raw.corners {
        mesh.corner[v as usize] = true;
    }
    for &(v, _) in &raw.required {
        mesh.required[v as usize] = true;
    }
    if check {
        mesh.check().map_err(|e| to_defect(e, &mesh.tris))?;
    }
    Ok(mesh)
}

/// Orientation: degenerate triangles are errors; all clockwise is repaired; mixed is an error.
fn orient(path: &Path, raw: &mut RawMesh2) -> Result<()> {
    let mut first_cw = None;
    let mut first_ccw = None;
    let (mut n_cw, mut n_ccw) = (0usize, 0usize);
    for (t, tri) in raw.tris.iter().enumerate() {
        let [a, b, c] = tri.map(|v| raw.points[v as usize]);
        let o = orient2d(a, b, c);
        if o == 0.0 {
            return Err(Error::parse(
                path,
                raw.tri_line[t],
                format!("triangle {} is degenerate (zero area)", t + 1),
            ));
        }
        if o < 0.0 {
            n_cw += 1;
            first_cw.get_or_insert(t);
        } else {
            n_ccw += 1;
            first_ccw.get_or_insert(t);
        }
    }
    if n_cw == 0 {
        return Ok(());
    }
    if n_ccw == 0 {
        for tri in &mut raw.tris {
            tri.swap(1, 2);
        }
        return Ok(());
    }
    let (t, what, n_bad, n_good) = if n_cw <= n_ccw {
        (first_cw.unwrap_or(0), "clockwise (inverted)", n_cw, n_ccw)
    } else {
        (first_ccw.unwrap_or(0), "counter-clockwise", n_ccw, n_cw)
    };
    Err(Error::parse(
        path,
        raw.tri_line[t],
        format!(
            "triangle {} is {what} while most triangles are not: mixed orientation \
             ({n_bad} against {n_good})",
            t + 1
        ),
    ))
}

/// Applies edge labels. With an edge list in the file, unlisted interior edges become 0 and
/// unlisted boundary edges keep the default label 1.
fn apply_edges(path: &Path, mesh: &mut Mesh2, edges: &[RawEdge], has_edges: bool) -> Result<()> {
    if !has_edges {
        return Ok(());
    }
    for t in 0..mesh.n_tris() {
        for i in 0..3 {
            if mesh.neighbours[t][i] != NONE {
                mesh.edge_ref[t][i] = 0;
            }
        }
    }
    for e in edges {
        let Some((t, i)) = find_edge(mesh, e.v[0], e.v[1]) else {
            return Err(Error::parse(
                path,
                e.line,
                format!(
                    "edge ({}, {}) is not an edge of any triangle of the mesh",
                    e.v[0] as u64 + 1,
                    e.v[1] as u64 + 1
                ),
            ));
        };
        mesh.edge_ref[t][i] = e.label;
        let nb = mesh.neighbours[t][i];
        if nb != NONE {
            if let Some(j) = mesh.mirror_edge(t, nb as usize) {
                mesh.edge_ref[nb as usize][j] = e.label;
            }
        }
    }
    Ok(())
}

/// A triangle and local edge joining `a` and `b`: searched in the fan of `a`, then (a vertex
/// whose triangles do not form one fan) among all triangles.
fn find_edge(mesh: &Mesh2, a: u32, b: u32) -> Option<(usize, usize)> {
    let on = |t: usize| {
        (0..3).find(|&i| {
            let [p, q] = mesh.edge_vertices(t, i);
            (p == a && q == b) || (p == b && q == a)
        })
    };
    let mut found = None;
    mesh.for_each_fan_triangle(a, |t| {
        if found.is_none() {
            found = on(t as usize).map(|i| (t as usize, i));
        }
    });
    found.or_else(|| (0..mesh.n_tris()).find_map(|t| on(t).map(|i| (t, i))))
}

/// The source line of the entity a defect names.
fn defect_line(
    d: &MeshDefect,
    tri_line: &[usize],
    point_line: &[usize],
    tris: &[[u32; 3]],
) -> Option<usize> {
    use MeshDefect::*;
    let tl = |t: usize| tri_line.get(t).copied();
    let pl = |v: usize| point_line.get(v).copied();
    match *d {
        IndexOutOfRange { tri, .. }
        | RepeatedVertex { tri }
        | DegenerateTriangle { tri }
        | InvertedTriangle { tri, .. }
        | BadAdjacency { tri, .. }
        | BadLabel { tri, .. } => tl(tri),
        DuplicateTriangle { second, .. } => tl(second),
        NonFiniteCoordinate { vertex }
        | OverlappingTriangles { vertex }
        | BadVertexData { vertex, .. }
        | HangingVertex { vertex, .. } => pl(vertex),
        DuplicateVertex { second, .. } => pl(second),
        NonManifoldEdge { a, b } => {
            // The last triangle that uses the edge (the one that made it non-manifold).
            let t = tris.iter().rposition(|tri| {
                (0..3).any(|i| {
                    let (p, q) = (tri[next(i)] as usize, tri[prev(i)] as usize);
                    (p == a && q == b) || (p == b && q == a)
                })
            })?;
            tl(t)
        }
    }
}

/// The defect message with indices converted to the 1-based numbering of the file.
fn one_based(d: &MeshDefect) -> String {
    use MeshDefect::*;
    let d1 = match d.clone() {
        IndexOutOfRange {
            tri,
            vertex,
            n_points,
        } => IndexOutOfRange {
            tri: tri + 1,
            vertex: vertex + 1,
            n_points,
        },
        RepeatedVertex { tri } => RepeatedVertex { tri: tri + 1 },
        NonFiniteCoordinate { vertex } => NonFiniteCoordinate { vertex: vertex + 1 },
        DegenerateTriangle { tri } => DegenerateTriangle { tri: tri + 1 },
        InvertedTriangle { tri, signed_area } => InvertedTriangle {
            tri: tri + 1,
            signed_area,
        },
        DuplicateTriangle { first, second } => DuplicateTriangle {
            first: first + 1,
            second: second + 1,
        },
        DuplicateVertex { first, second } => DuplicateVertex {
            first: first + 1,
            second: second + 1,
        },
        NonManifoldEdge { a, b } => NonManifoldEdge { a: a + 1, b: b + 1 },
        BadAdjacency { tri, edge, detail } => BadAdjacency {
            tri: tri + 1,
            edge,
            detail,
        },
        HangingVertex { vertex, a, b } => HangingVertex {
            vertex: vertex + 1,
            a: a + 1,
            b: b + 1,
        },
        OverlappingTriangles { vertex } => OverlappingTriangles { vertex: vertex + 1 },
        BadLabel { tri, detail } => BadLabel {
            tri: tri + 1,
            detail,
        },
        BadVertexData { vertex, detail } => BadVertexData {
            vertex: vertex + 1,
            detail,
        },
    };
    format!("{d1} (1-based numbering)")
}
