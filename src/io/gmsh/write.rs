//! Writing Gmsh 4.1 ASCII: the entity layout of the mesh (one point entity per corner, one
//! curve entity per edge label, one surface entity per `tri_ref`, every node classified on the
//! lowest-dimensional entity it lies on), then one function per section (`$MeshFormat`,
//! `$PhysicalNames`, `$Entities`, `$Nodes`, `$Elements`).

use super::PhysicalName;
use crate::error::Result;
use crate::geom::DVec2;
use crate::io::atomic::atomic_write;
use crate::io::textout::fmt_f64;
use crate::mesh::{Mesh2, NONE};
use std::collections::BTreeMap;
use std::io::Write;
use std::path::Path;

/// Writes a 2D mesh as Gmsh 4.1 ASCII (atomically), without physical names.
pub fn write_msh(path: &Path, mesh: &Mesh2) -> Result<()> {
    write_msh_named(path, mesh, &[])
}

/// Writes a 2D mesh as Gmsh 4.1 ASCII (atomically) with the given physical names.
pub fn write_msh_named(path: &Path, mesh: &Mesh2, names: &[PhysicalName]) -> Result<()> {
    crate::io::check_lengths(mesh)?;
    let layout = Layout::new(mesh);
    atomic_write(path, |w| {
        writeln!(w, "$MeshFormat\n4.1 0 8\n$EndMeshFormat")?;
        write_physical_names(w, names)?;
        layout.write_entities(w)?;
        layout.write_nodes(w)?;
        layout.write_elements(w)
    })
}

/// `$PhysicalNames`, omitted when there are none (double quotes in a name become `'`).
fn write_physical_names(w: &mut dyn Write, names: &[PhysicalName]) -> std::io::Result<()> {
    if names.is_empty() {
        return Ok(());
    }
    writeln!(w, "$PhysicalNames\n{}", names.len())?;
    for n in names {
        writeln!(w, "{} {} \"{}\"", n.dim, n.tag, n.name.replace('"', "'"))?;
    }
    writeln!(w, "$EndPhysicalNames")
}

/// An entity to write: its tag, physical tag (0 = none) and node bounding box.
struct Entity {
    tag: usize,
    phys: i32,
    lo: DVec2,
    hi: DVec2,
}

impl Entity {
    fn new(tag: usize, phys: i32) -> Self {
        Entity {
            tag,
            phys,
            lo: DVec2::splat(f64::INFINITY),
            hi: DVec2::splat(f64::NEG_INFINITY),
        }
    }

    fn grow(&mut self, p: DVec2) {
        self.lo = self.lo.min(p);
        self.hi = self.hi.max(p);
    }

    /// The bounding box, `(0, 0)`–`(0, 0)` for an entity without nodes.
    fn bbox(&self) -> (DVec2, DVec2) {
        if self.lo.x <= self.hi.x {
            (self.lo, self.hi)
        } else {
            (DVec2::ZERO, DVec2::ZERO)
        }
    }

    /// The physical-tag list: `1 tag`, or `0` for none.
    fn phys_tags(&self) -> String {
        if self.phys != 0 {
            format!("1 {}", self.phys)
        } else {
            "0".to_string()
        }
    }
}

/// An edge written as a line element: the index of its curve entity and its vertices.
type Line = (usize, [u32; 2]);

/// How a mesh is laid out in entities.
struct Layout<'m> {
    mesh: &'m Mesh2,
    /// The corner vertices, one point entity each.
    corners: Vec<usize>,
    /// The edges written as line elements (every boundary edge and every labelled interior
    /// edge) with the index of their curve entity.
    lines: Vec<Line>,
    /// Surface entity index of each `tri_ref`.
    surf_of: BTreeMap<i32, usize>,
    /// Point, curve and surface entities.
    points: Vec<Entity>,
    curves: Vec<Entity>,
    surfs: Vec<Entity>,
    /// The entity `(dim, index)` each node is classified on.
    class: Vec<(u8, usize)>,
}

impl<'m> Layout<'m> {
    fn new(mesh: &'m Mesh2) -> Self {
        let corners: Vec<usize> = (0..mesh.points.len()).filter(|&v| mesh.corner[v]).collect();
        let (curve_of, lines) = curve_lines(mesh);
        let mut surf_of: BTreeMap<i32, usize> = BTreeMap::new();
        for t in mesh.live_tris() {
            let n = surf_of.len();
            surf_of.entry(mesh.tri_ref[t]).or_insert(n);
        }
        let points = corners
            .iter()
            .enumerate()
            .map(|(k, &v)| Entity::new(k + 1, mesh.vert_ref[v]))
            .collect();
        let mut surfs = entities(&surf_of);
        if surfs.is_empty() {
            surfs.push(Entity::new(1, 0));
        }
        let mut layout = Layout {
            mesh,
            corners,
            lines,
            points,
            curves: entities(&curve_of),
            surfs,
            class: Vec::new(),
            surf_of,
        };
        layout.classify_nodes();
        layout.grow_boxes();
        layout
    }

    /// Classifies every node: on its seed triangle's surface, then on the curve of a line
    /// through it, then on its point entity if it is a corner (the last assignment wins).
    fn classify_nodes(&mut self) {
        let mesh = self.mesh;
        let mut class: Vec<(u8, usize)> = vec![(2, 0); mesh.points.len()];
        for (c, &t) in class.iter_mut().zip(&mesh.vert_tri) {
            if let Some(&s) = (t != NONE)
                .then(|| self.surf_of.get(&mesh.tri_ref[t as usize]))
                .flatten()
            {
                *c = (2, s);
            }
        }
        for &(c, [a, b]) in &self.lines {
            class[a as usize] = (1, c);
            class[b as usize] = (1, c);
        }
        for (k, &v) in self.corners.iter().enumerate() {
            class[v] = (0, k);
        }
        self.class = class;
    }

    /// Bounding boxes: the nodes classified on each entity, the end points of each curve's
    /// lines and the corners of each surface's triangles.
    fn grow_boxes(&mut self) {
        let mesh = self.mesh;
        for (v, &(d, e)) in self.class.iter().enumerate() {
            let p = mesh.points[v];
            match d {
                0 => self.points[e].grow(p),
                1 => self.curves[e].grow(p),
                _ => self.surfs[e].grow(p),
            }
        }
        for &(c, [a, b]) in &self.lines {
            self.curves[c].grow(mesh.points[a as usize]);
            self.curves[c].grow(mesh.points[b as usize]);
        }
        for t in mesh.live_tris() {
            let s = self.surf_of[&mesh.tri_ref[t]];
            for p in mesh.tri_points(t) {
                self.surfs[s].grow(p);
            }
        }
    }

    /// `$Entities`: points with their coordinates, curves and surfaces with their boxes.
    fn write_entities(&self, w: &mut dyn Write) -> std::io::Result<()> {
        let (np, nc, ns) = (self.points.len(), self.curves.len(), self.surfs.len());
        writeln!(w, "$Entities\n{np} {nc} {ns} 0")?;
        for e in &self.points {
            let (p, _) = e.bbox();
            writeln!(
                w,
                "{} {} {} 0 {}",
                e.tag,
                fmt_f64(p.x),
                fmt_f64(p.y),
                e.phys_tags()
            )?;
        }
        for e in self.curves.iter().chain(&self.surfs) {
            let (lo, hi) = e.bbox();
            writeln!(
                w,
                "{} {} {} 0 {} {} 0 {} 0",
                e.tag,
                fmt_f64(lo.x),
                fmt_f64(lo.y),
                fmt_f64(hi.x),
                fmt_f64(hi.y),
                e.phys_tags()
            )?;
        }
        writeln!(w, "$EndEntities")
    }

    /// `$Nodes`: one block per non-empty entity (points, curves, surfaces), node tag `v + 1`.
    fn write_nodes(&self, w: &mut dyn Write) -> std::io::Result<()> {
        let ents = [&self.points, &self.curves, &self.surfs];
        let mut blocks: Vec<Vec<Vec<usize>>> = ents.iter().map(|e| vec![vec![]; e.len()]).collect();
        for (v, &(d, e)) in self.class.iter().enumerate() {
            blocks[d as usize][e].push(v);
        }
        let np = self.mesh.points.len();
        let nblocks = blocks.iter().flatten().filter(|b| !b.is_empty()).count();
        writeln!(w, "$Nodes\n{nblocks} {np} {} {np}", np.min(1))?;
        for (d, per) in blocks.iter().enumerate() {
            for (e, nodes) in per.iter().enumerate().filter(|(_, n)| !n.is_empty()) {
                writeln!(w, "{d} {} 0 {}", ents[d][e].tag, nodes.len())?;
                for &v in nodes {
                    writeln!(w, "{}", v + 1)?;
                }
                for &v in nodes {
                    let p = self.mesh.points[v];
                    writeln!(w, "{} {} 0", fmt_f64(p.x), fmt_f64(p.y))?;
                }
            }
        }
        writeln!(w, "$EndNodes")
    }

    /// `$Elements`: one point block per corner, one line block per curve, one triangle block
    /// per surface. Triangle element tags follow the triangle order (so that reading keeps it).
    fn write_elements(&self, w: &mut dyn Write) -> std::io::Result<()> {
        let mesh = self.mesh;
        let mut lines_of: Vec<Vec<[u32; 2]>> = vec![vec![]; self.curves.len()];
        for &(c, e) in &self.lines {
            lines_of[c].push(e);
        }
        let mut tris_of: Vec<Vec<usize>> = vec![vec![]; self.surfs.len()];
        for t in mesh.live_tris() {
            tris_of[self.surf_of[&mesh.tri_ref[t]]].push(t);
        }
        let n_el = self.corners.len() + self.lines.len() + mesh.n_live_tris();
        let nblocks = self.corners.len()
            + lines_of.iter().filter(|l| !l.is_empty()).count()
            + tris_of.iter().filter(|l| !l.is_empty()).count();
        writeln!(w, "$Elements\n{nblocks} {n_el} {} {n_el}", n_el.min(1))?;
        let mut tag = 0usize;
        for (k, &v) in self.corners.iter().enumerate() {
            tag += 1;
            writeln!(w, "0 {} 15 1\n{tag} {}", self.points[k].tag, v + 1)?;
        }
        for (c, ls) in lines_of.iter().enumerate().filter(|(_, l)| !l.is_empty()) {
            writeln!(w, "1 {} 1 {}", self.curves[c].tag, ls.len())?;
            for [a, b] in ls {
                tag += 1;
                writeln!(w, "{tag} {} {}", a + 1, b + 1)?;
            }
        }
        self.write_triangle_blocks(w, &tris_of)?;
        writeln!(w, "$EndElements")
    }

    /// The triangle blocks of `$Elements`, element tags after the points and lines in the order
    /// of the live triangles.
    fn write_triangle_blocks(
        &self,
        w: &mut dyn Write,
        tris_of: &[Vec<usize>],
    ) -> std::io::Result<()> {
        let mesh = self.mesh;
        let base = self.corners.len() + self.lines.len();
        let mut rank = vec![0usize; mesh.n_tris()];
        for (k, t) in mesh.live_tris().enumerate() {
            rank[t] = k;
        }
        for (s, ts) in tris_of.iter().enumerate().filter(|(_, t)| !t.is_empty()) {
            writeln!(w, "2 {} 2 {}", self.surfs[s].tag, ts.len())?;
            for &t in ts {
                let [a, b, c] = mesh.tris[t];
                writeln!(w, "{} {} {} {}", base + rank[t] + 1, a + 1, b + 1, c + 1)?;
            }
        }
        Ok(())
    }
}

/// One curve entity per edge label, numbered in order of first appearance over
/// [`Mesh2::edges`], and the edges written as lines (boundary or labelled) with their curve.
fn curve_lines(mesh: &Mesh2) -> (BTreeMap<i32, usize>, Vec<Line>) {
    let mut curve_of: BTreeMap<i32, usize> = BTreeMap::new();
    let mut lines = Vec::new();
    for (_, t, i) in mesh.edges() {
        let (t, i) = (t as usize, i as usize);
        let label = mesh.edge_ref[t][i];
        if mesh.neighbours[t][i] == NONE || label != 0 {
            let n = curve_of.len();
            let c = *curve_of.entry(label).or_insert(n);
            lines.push((c, mesh.edge_vertices(t, i)));
        }
    }
    (curve_of, lines)
}

/// The entities of a label map (label -> index), ordered by index, with tag `index + 1` and the
/// label as physical tag.
fn entities(index_of: &BTreeMap<i32, usize>) -> Vec<Entity> {
    let mut ents: Vec<Entity> = index_of
        .iter()
        .map(|(&label, &k)| Entity::new(k + 1, label))
        .collect();
    ents.sort_by_key(|e| e.tag);
    ents
}
