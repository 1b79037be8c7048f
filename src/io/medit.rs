//! Medit `.mesh` (ASCII, `MeshVersionFormatted` 1 to 4), as read and written by MMG and
//! FreeFem++.
//!
//! Dimension 2: `Vertices` (x y ref), `Triangles` (a b c ref), `Edges` (a b ref, mapped onto
//! `Mesh2::edge_ref` of the triangle edges), `Corners`, `RequiredVertices`, `End`. Dimension 3:
//! `Vertices`, `Tetrahedra`, `Triangles` into [`Medit3`], and `Edges`, `Corners`,
//! `RequiredVertices` into [`DeclaredFeatures3`] ([`parse_medit3_features`]); written with the
//! ridges and corners of a [`Features3`] ([`write_medit3_features`]). Indices in files are 1-based. Keywords
//! are case-insensitive, numbers may be split across lines, `#` starts a comment, and unknown
//! sections (`Normals`, `Ridges`, `RequiredEdges`, FreeFem++'s `Identifier "..."`,
//! `VertexOnGeometricEdge`, ...) are skipped.

use super::atomic::atomic_write;
use super::textout::Out;
use super::tokens::{read_text, shorten, Tokens};
use super::validate::{build_mesh_with, RawEdge, RawMesh2};
use crate::error::{Error, Result};
use crate::geom::{DVec2, DVec3};
use crate::mesh::{Mesh2, NONE};
use crate::mesh3::{DeclaredFeatures3, Features3};
use std::io::Write;
use std::path::Path;

/// A three-dimensional Medit mesh: tetrahedra and boundary triangles with labels (0-based
/// indices in memory).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Medit3 {
    /// Vertex coordinates.
    pub points: Vec<DVec3>,
    /// Vertex labels.
    pub point_ref: Vec<i32>,
    /// Vertices of each tetrahedron.
    pub tets: Vec<[u32; 4]>,
    /// Tetrahedron labels.
    pub tet_ref: Vec<i32>,
    /// Vertices of each (boundary or interface) triangle.
    pub tris: Vec<[u32; 3]>,
    /// Triangle labels.
    pub tri_ref: Vec<i32>,
}

/// Everything a Medit mesh file holds that we use, dimension-independent.
#[derive(Default)]
struct MeditData {
    dim: usize,
    /// The coordinates in dimension 3 (x y z per vertex).
    coords: Vec<f64>,
    /// The vertices in dimension 2.
    points2: Vec<DVec2>,
    point_ref: Vec<i32>,
    point_line: Vec<usize>,
    tris: Vec<[u32; 3]>,
    tri_ref: Vec<i32>,
    tri_line: Vec<usize>,
    tets: Vec<[u32; 4]>,
    tet_ref: Vec<i32>,
    tet_line: Vec<usize>,
    edges: Vec<RawEdge>,
    has_edges: bool,
    corners: Vec<(u32, usize)>,
    required: Vec<(u32, usize)>,
    has_vertices: bool,
    last_line: usize,
}

/// Whether `t` looks like a keyword (starts with a letter) rather than a number.
pub(crate) fn is_keyword(t: &str) -> bool {
    t.as_bytes()
        .first()
        .is_some_and(|c| c.is_ascii_alphabetic())
        && !matches!(t.to_ascii_lowercase().as_str(), "nan" | "inf" | "infinity")
}

/// Reads a 1-based vertex index and returns it 0-based.
fn vertex_index(tk: &mut Tokens, what: &dyn Fn() -> String) -> Result<u32> {
    let v: i64 = tk.int_with(what)?;
    if v < 1 || v > (NONE as i64) {
        return Err(tk.err(format!(
            "{}: vertex index {v} is out of range (indices are 1-based)",
            what()
        )));
    }
    Ok((v - 1) as u32)
}

/// Reads the header (`MeshVersionFormatted`, `Dimension`) keyword values; shared with `.sol`.
pub(crate) fn read_header_keyword(tk: &mut Tokens, kw: &str) -> Result<Option<usize>> {
    if kw.eq_ignore_ascii_case("MeshVersionFormatted") {
        let v: i64 = tk.int("MeshVersionFormatted")?;
        // 0 is written by FreeFem++'s BAMG writers.
        if !(0..=4).contains(&v) {
            return Err(tk.err(format!(
                "unsupported MeshVersionFormatted {v} (expected 0 to 4)"
            )));
        }
        return Ok(Some(0));
    }
    if kw.eq_ignore_ascii_case("Dimension") {
        let d: i64 = tk.int("Dimension")?;
        if d != 2 && d != 3 {
            return Err(tk.err(format!("unsupported Dimension {d} (expected 2 or 3)")));
        }
        return Ok(Some(d as usize));
    }
    Ok(None)
}

/// Skips the data of an unknown section: every token up to the next keyword. A leading quoted
/// string (FreeFem++'s `Identifier "..."`, `Geometry "..."`) is skipped as a whole.
pub(crate) fn skip_section(tk: &mut Tokens) {
    if tk.peek().is_some_and(|t| t.starts_with('"')) {
        let _ = tk.quoted("quoted string");
    }
    while let Some(t) = tk.peek() {
        if is_keyword(t) {
            break;
        }
        tk.next_token();
    }
}

/// The Medit sections read (lower case); any other section is skipped.
const KNOWN: [&str; 6] = [
    "vertices",
    "triangles",
    "tetrahedra",
    "edges",
    "corners",
    "requiredvertices",
];

/// Reads the keywords and sections of a Medit mesh up to `End` or the end of the text.
fn parse(path: &Path, text: &str) -> Result<MeditData> {
    let mut tk = Tokens::new(path, text, Some(b'#'));
    let mut d = MeditData::default();
    let mut seen: Vec<String> = Vec::new();
    while let Some((kw, line)) = tk.next_token() {
        if !is_keyword(kw) {
            return Err(tk.err(format!(
                "unexpected '{}' where a keyword was expected (a count smaller than its data?)",
                shorten(kw)
            )));
        }
        let lower = kw.to_ascii_lowercase();
        if lower == "end" {
            break;
        }
        match read_header_keyword(&mut tk, kw)? {
            Some(0) => continue,
            Some(dim) => {
                d.dim = dim;
                continue;
            }
            None => {}
        }
        if KNOWN.contains(&lower.as_str()) {
            if seen.contains(&lower) {
                return Err(tk.err_at(line, format!("second {kw} section")));
            }
            seen.push(lower.clone());
        }
        d.read_section(&mut tk, kw, &lower, line)?;
    }
    d.last_line = tk.token_line();
    if !d.has_vertices {
        return Err(Error::parse(path, d.last_line, "no Vertices section"));
    }
    Ok(d)
}

impl MeditData {
    /// The data of section `kw` (`lower` in lower case), whose keyword is on `line`.
    fn read_section(&mut self, tk: &mut Tokens, kw: &str, lower: &str, line: usize) -> Result<()> {
        match lower {
            "vertices" => self.read_vertices(tk, line),
            "triangles" => self.read_triangles(tk),
            "tetrahedra" => self.read_tetrahedra(tk),
            "edges" => self.read_edges(tk),
            "corners" => {
                self.corners = read_vertex_list(tk, kw)?;
                Ok(())
            }
            "requiredvertices" => {
                self.required = read_vertex_list(tk, kw)?;
                Ok(())
            }
            "quadrilaterals" | "hexahedra" | "prisms" | "pyramids" => Err(tk.err_at(
                line,
                format!("{kw} are not supported (only triangles and tetrahedra)"),
            )),
            _ => {
                skip_section(tk);
                Ok(())
            }
        }
    }

    /// `Vertices`: count, then `dim` coordinates and a label per vertex (after `Dimension`).
    fn read_vertices(&mut self, tk: &mut Tokens, line: usize) -> Result<()> {
        if self.dim == 0 {
            return Err(tk.err_at(line, "Vertices section before Dimension"));
        }
        let n = tk.count("number of vertices")?;
        self.has_vertices = true;
        let cap = tk.capacity(n, 2 * self.dim + 2);
        if self.dim == 2 {
            self.points2.reserve(cap);
        } else {
            self.coords.reserve(cap * self.dim);
        }
        self.point_ref.reserve(cap);
        self.point_line.reserve(cap);
        for k in 0..n {
            let what = || format!("vertex {} of {n}", k + 1);
            if self.dim == 2 {
                let x = tk.real_with(&what)?;
                self.points2.push(DVec2::new(x, tk.real_with(&what)?));
            } else {
                for _ in 0..self.dim {
                    self.coords.push(tk.real_with(&what)?);
                }
            }
            self.point_ref.push(tk.int_with(&what)?);
            self.point_line.push(tk.token_line());
        }
        Ok(())
    }

    /// `Triangles`: count, then three vertex indices and a label per triangle.
    fn read_triangles(&mut self, tk: &mut Tokens) -> Result<()> {
        let n = tk.count("number of triangles")?;
        let cap = tk.capacity(n, 8);
        self.tris.reserve(cap);
        self.tri_ref.reserve(cap);
        self.tri_line.reserve(cap);
        for k in 0..n {
            let what = || format!("triangle {} of {n}", k + 1);
            let mut t = [0u32; 3];
            for v in &mut t {
                *v = vertex_index(tk, &what)?;
            }
            self.tris.push(t);
            self.tri_ref.push(tk.int_with(&what)?);
            self.tri_line.push(tk.token_line());
        }
        Ok(())
    }

    /// `Tetrahedra`: count, then four vertex indices and a label per tetrahedron.
    fn read_tetrahedra(&mut self, tk: &mut Tokens) -> Result<()> {
        let n = tk.count("number of tetrahedra")?;
        self.tets.reserve(tk.capacity(n, 10));
        for k in 0..n {
            let what = || format!("tetrahedron {} of {n}", k + 1);
            let mut t = [0u32; 4];
            for v in &mut t {
                *v = vertex_index(tk, &what)?;
            }
            self.tets.push(t);
            self.tet_ref.push(tk.int_with(&what)?);
            self.tet_line.push(tk.token_line());
        }
        Ok(())
    }

    /// `Edges`: count, then two vertex indices and a label per edge.
    fn read_edges(&mut self, tk: &mut Tokens) -> Result<()> {
        let n = tk.count("number of edges")?;
        self.has_edges = true;
        self.edges.reserve(tk.capacity(n, 6));
        for k in 0..n {
            let what = || format!("edge {} of {n}", k + 1);
            let a = vertex_index(tk, &what)?;
            let b = vertex_index(tk, &what)?;
            let label = tk.int_with(&what)?;
            self.edges.push(RawEdge {
                v: [a, b],
                label,
                line: tk.token_line(),
            });
        }
        Ok(())
    }
}

/// `Corners` or `RequiredVertices` (`kw`): count, then one vertex index per entry, each with
/// its line.
fn read_vertex_list(tk: &mut Tokens, kw: &str) -> Result<Vec<(u32, usize)>> {
    let n = tk.count(kw)?;
    let mut list = Vec::with_capacity(tk.capacity(n, 2));
    for k in 0..n {
        let v = vertex_index(tk, &|| format!("{kw} entry {} of {n}", k + 1))?;
        list.push((v, tk.token_line()));
    }
    Ok(list)
}

/// Parses a two-dimensional Medit mesh from `text` (`path` is used in messages). A
/// `Dimension 3` file without tetrahedra whose vertices all have `z = 0` is accepted as 2D.
pub fn parse_mesh2(path: &Path, text: &str) -> Result<Mesh2> {
    parse_mesh2_with(path, text, true)
}

/// [`parse_mesh2`]; with `check = false` the final [`Mesh2::check`] is left out.
fn parse_mesh2_with(path: &Path, text: &str, check: bool) -> Result<Mesh2> {
    let mut d = parse(path, text)?;
    let n = d.point_ref.len();
    let points: Vec<DVec2> = match d.dim {
        2 => std::mem::take(&mut d.points2),
        _ => {
            if !d.tets.is_empty() {
                return Err(Error::parse(
                    path,
                    d.tet_line[0],
                    "this is a volume mesh (Dimension 3 with Tetrahedra); read it with read_medit3",
                ));
            }
            if let Some(v) = (0..n).find(|&v| d.coords[3 * v + 2] != 0.0) {
                return Err(Error::parse(
                    path,
                    d.point_line[v],
                    format!(
                        "Dimension 3 mesh with vertex {} off the plane z = 0: not a 2D mesh",
                        v + 1
                    ),
                ));
            }
            (0..n)
                .map(|v| DVec2::new(d.coords[3 * v], d.coords[3 * v + 1]))
                .collect()
        }
    };
    let raw = RawMesh2 {
        points,
        vert_ref: d.point_ref,
        point_line: d.point_line,
        tris: d.tris,
        tri_ref: d.tri_ref,
        tri_line: d.tri_line,
        edges: d.edges,
        has_edges: d.has_edges,
        corners: d.corners,
        required: d.required,
        last_line: d.last_line,
    };
    build_mesh_with(path, raw, check)
}

/// Reads a two-dimensional Medit `.mesh` file; see [`parse_mesh2`].
pub fn read_medit2(path: &Path) -> Result<Mesh2> {
    parse_mesh2(path, &read_text(path)?)
}

/// The start of [`parse_medit3`]'s refusal of a file of another dimension.
pub(crate) const NOT_3D: &str = "expected a Dimension 3 mesh";

/// [`read_medit2`] without the final [`Mesh2::check`] (indices, orientation, elements,
/// adjacency and labels are still validated): for a caller that checks a mesh derived from
/// this one and calls [`read_medit2`] for its message when that check fails (`anisomesh fit`).
pub fn read_medit2_unchecked(path: &Path) -> Result<Mesh2> {
    parse_mesh2_with(path, &read_text(path)?, false)
}

/// Parses a three-dimensional Medit mesh (vertices, tetrahedra, triangles). Indices are checked;
/// element orientation and conformity are left to the 3D mesh module.
pub fn parse_medit3(path: &Path, text: &str) -> Result<Medit3> {
    Ok(parse_medit3_features(path, text)?.0)
}

/// Parses a three-dimensional Medit mesh as [`parse_medit3`] does, with the features it
/// declares: its `Edges` (ridges, required or plain: all kept as features), `Corners` and
/// `RequiredVertices`. Indices are checked.
pub fn parse_medit3_features(path: &Path, text: &str) -> Result<(Medit3, DeclaredFeatures3)> {
    let d = parse(path, text)?;
    if d.dim != 3 {
        return Err(Error::parse(
            path,
            d.point_line.first().copied().unwrap_or(d.last_line),
            format!("{NOT_3D}, found Dimension {}", d.dim),
        ));
    }
    let n = d.point_ref.len();
    let bad = |line: usize, what: String| {
        Error::parse(
            path,
            line,
            format!("{what} refers to a vertex beyond the {n} vertices"),
        )
    };
    for (k, t) in d.tets.iter().enumerate() {
        if t.iter().any(|&v| v as usize >= n) {
            return Err(bad(d.tet_line[k], format!("tetrahedron {}", k + 1)));
        }
    }
    for (k, t) in d.tris.iter().enumerate() {
        if t.iter().any(|&v| v as usize >= n) {
            return Err(bad(d.tri_line[k], format!("triangle {}", k + 1)));
        }
    }
    for (k, e) in d.edges.iter().enumerate() {
        if e.v.iter().any(|&v| v as usize >= n) {
            return Err(bad(e.line, format!("edge {}", k + 1)));
        }
    }
    for (list, kw) in [(&d.corners, "Corners"), (&d.required, "RequiredVertices")] {
        if let Some(k) = list.iter().position(|&(v, _)| v as usize >= n) {
            return Err(bad(list[k].1, format!("{kw} entry {}", k + 1)));
        }
    }
    let declared = DeclaredFeatures3 {
        edges: d.edges.iter().map(|e| e.v).collect(),
        corners: d.corners.iter().map(|&(v, _)| v).collect(),
        required: d.required.iter().map(|&(v, _)| v).collect(),
    };
    let m = Medit3 {
        points: (0..n)
            .map(|v| DVec3::new(d.coords[3 * v], d.coords[3 * v + 1], d.coords[3 * v + 2]))
            .collect(),
        point_ref: d.point_ref,
        tets: d.tets,
        tet_ref: d.tet_ref,
        tris: d.tris,
        tri_ref: d.tri_ref,
    };
    Ok((m, declared))
}

/// Reads a three-dimensional Medit `.mesh` file; see [`parse_medit3`].
pub fn read_medit3(path: &Path) -> Result<Medit3> {
    parse_medit3(path, &read_text(path)?)
}

/// Reads a three-dimensional Medit `.mesh` file with its declared features; see
/// [`parse_medit3_features`].
pub fn read_medit3_features(path: &Path) -> Result<(Medit3, DeclaredFeatures3)> {
    parse_medit3_features(path, &read_text(path)?)
}

/// Writes the Medit text of a 2D mesh: live triangles, every boundary edge and every labelled
/// interior edge in `Edges`, `Corners` and `RequiredVertices`.
pub fn write_medit2_to(w: &mut dyn Write, mesh: &Mesh2) -> std::io::Result<()> {
    let mut o = Out::new(w);
    o.text("MeshVersionFormatted 2\n\nDimension 2\n\nVertices\n");
    o.int(mesh.points.len());
    o.text("\n");
    for (v, p) in mesh.points.iter().enumerate() {
        o.real(p.x);
        o.text(" ");
        o.real(p.y);
        o.text(" ");
        o.int(mesh.vert_ref.get(v).copied().unwrap_or(0));
        o.line()?;
    }
    o.text("\nTriangles\n");
    o.int(mesh.live_tris().count());
    o.text("\n");
    for t in mesh.live_tris() {
        let [a, b, c] = mesh.tris[t];
        o.ints(&[
            a as i64 + 1,
            b as i64 + 1,
            c as i64 + 1,
            mesh.tri_ref[t] as i64,
        ]);
        o.line()?;
    }
    // The edges written, in the order of TriMesh::edges (each interior edge from the triangle
    // with the smaller index), without collecting every edge of the mesh.
    let written = |t: usize, i: usize| {
        let nb = mesh.neighbours[t][i];
        nb == NONE || (nb as usize > t && mesh.edge_ref[t][i] != 0)
    };
    let n_edges = mesh
        .live_tris()
        .map(|t| (0..3).filter(|&i| written(t, i)).count())
        .sum::<usize>();
    o.text("\nEdges\n");
    o.int(n_edges);
    o.text("\n");
    for t in mesh.live_tris() {
        for i in 0..3 {
            if written(t, i) {
                let [a, b] = mesh.edge_vertices(t, i);
                o.ints(&[a as i64 + 1, b as i64 + 1, mesh.edge_ref[t][i] as i64]);
                o.line()?;
            }
        }
    }
    for (name, flags) in [
        ("Corners", &mesh.corner),
        ("RequiredVertices", &mesh.required),
    ] {
        let list: Vec<usize> = (0..flags.len()).filter(|&v| flags[v]).collect();
        if !list.is_empty() {
            o.text("\n");
            o.text(name);
            o.text("\n");
            o.int(list.len());
            o.text("\n");
            for v in list {
                o.int(v + 1);
                o.line()?;
            }
        }
    }
    o.text("\nEnd\n");
    o.finish()
}

/// Writes a 2D mesh as Medit `.mesh` (atomically).
pub fn write_medit2(path: &Path, mesh: &Mesh2) -> Result<()> {
    super::check_lengths(mesh)?;
    atomic_write(path, |w| write_medit2_to(w, mesh))
}

/// Writes a 3D Medit mesh (atomically).
pub fn write_medit3(path: &Path, m: &Medit3) -> Result<()> {
    write_medit3_features(path, m, &Features3::default())
}

/// Writes a 3D Medit mesh (atomically) with the ridges of `f` as `Edges` (label 0), all listed
/// in `Ridges`, and its corners as `Corners` (sections written only when not empty), as mmg3d
/// reads them.
pub fn write_medit3_features(path: &Path, m: &Medit3, f: &Features3) -> Result<()> {
    let n = m.points.len();
    if f.ridges
        .iter()
        .flatten()
        .chain(&f.corners)
        .any(|&v| v as usize >= n)
    {
        return Err(Error::InvalidInput(format!(
            "cannot write '{}': a ridge or corner refers to a vertex beyond the {n} vertices",
            path.display()
        )));
    }
    if m.point_ref.len() != m.points.len()
        || m.tet_ref.len() != m.tets.len()
        || m.tri_ref.len() != m.tris.len()
    {
        return Err(Error::InvalidInput(format!(
            "cannot write '{}': a label array has the wrong length",
            path.display()
        )));
    }
    atomic_write(path, |w| {
        let mut o = Out::new(w);
        o.text("MeshVersionFormatted 2\n\nDimension 3\n\nVertices\n");
        o.int(m.points.len());
        o.text("\n");
        for (p, &r) in m.points.iter().zip(&m.point_ref) {
            for x in [p.x, p.y, p.z] {
                o.real(x);
                o.text(" ");
            }
            o.int(r);
            o.line()?;
        }
        o.text("\nTetrahedra\n");
        o.int(m.tets.len());
        o.text("\n");
        for (t, &r) in m.tets.iter().zip(&m.tet_ref) {
            let [a, b, c, d] = t.map(|v| v as i64 + 1);
            o.ints(&[a, b, c, d, r as i64]);
            o.line()?;
        }
        if !m.tris.is_empty() {
            o.text("\nTriangles\n");
            o.int(m.tris.len());
            o.text("\n");
            for (t, &r) in m.tris.iter().zip(&m.tri_ref) {
                let [a, b, c] = t.map(|v| v as i64 + 1);
                o.ints(&[a, b, c, r as i64]);
                o.line()?;
            }
        }
        if !f.ridges.is_empty() {
            o.text("\nEdges\n");
            o.int(f.ridges.len());
            o.text("\n");
            for e in &f.ridges {
                o.ints(&[e[0] as i64 + 1, e[1] as i64 + 1, 0]);
                o.line()?;
            }
            o.text("\nRidges\n");
            o.int(f.ridges.len());
            o.text("\n");
            for k in 1..=f.ridges.len() {
                o.int(k);
                o.line()?;
            }
        }
        if !f.corners.is_empty() {
            o.text("\nCorners\n");
            o.int(f.corners.len());
            o.text("\n");
            for &v in &f.corners {
                o.int(v as usize + 1);
                o.line()?;
            }
        }
        o.text("\nEnd\n");
        o.finish()
    })
}
