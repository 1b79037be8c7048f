//! Gmsh `.msh` version 4.1 ASCII for 2D triangle meshes.
//!
//! Reading: `$MeshFormat` (4.1, ASCII), `$PhysicalNames`, `$Entities`, `$Nodes` (entity blocks,
//! parametric or not), `$Elements` of type 2 (triangles), 1 (lines) and 15 (points); other
//! sections are skipped. The first physical tag of a surface becomes `tri_ref`, of a curve the
//! `edge_ref` of its lines, of a point the `vert_ref` of its node (which is also flagged corner
//! and required); an entity without a physical group gives label 0. Nodes are numbered in
//! increasing tag order and triangles in increasing element-tag order; `z` must be 0.
//!
//! Writing: one point entity per corner, one curve entity per edge label (every boundary edge and
//! every labelled interior edge), one surface entity per `tri_ref`; non-zero labels become
//! physical tags, physical names are optional.

use super::atomic::atomic_write;
use super::tokens::{fmt_f64, read_text, shorten, Tokens};
use super::validate::{build_mesh, RawEdge, RawMesh2};
use crate::error::{Error, Result};
use crate::geom::DVec2;
use crate::mesh::{Mesh2, NONE};
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

/// A physical group name: dimension, physical tag, name.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PhysicalName {
    pub dim: u8,
    pub tag: i32,
    pub name: String,
}

/// A mesh read from a `.msh` file with its physical names.
#[derive(Debug, Clone)]
pub struct GmshMesh {
    pub mesh: Mesh2,
    pub physical_names: Vec<PhysicalName>,
}

/// Reads the end marker of section `name`.
fn expect_end(tk: &mut Tokens, name: &str) -> Result<()> {
    let end = format!("$End{name}");
    let t = tk.expect(&end)?;
    if t != end {
        return Err(tk.err(format!(
            "expected {end}, found '{}' (a count smaller than its data?)",
            shorten(t)
        )));
    }
    Ok(())
}

/// Parses a Gmsh 4.1 ASCII mesh from `text` (`path` is used in messages).
pub fn parse_msh(path: &Path, text: &str) -> Result<GmshMesh> {
    let mut tk = Tokens::new(path, text, None);
    let first = tk.expect("$MeshFormat")?;
    if first != "$MeshFormat" {
        return Err(tk.err(format!(
            "not a Gmsh file: expected $MeshFormat, found '{}'",
            shorten(first)
        )));
    }
    let version = tk.expect("format version")?;
    if version != "4.1" {
        return Err(tk.err(format!(
            "unsupported Gmsh format version {} (only 4.1 is supported; convert with \
             `gmsh file -save -format msh41`)",
            shorten(version)
        )));
    }
    let file_type: i64 = tk.int("file type")?;
    if file_type != 0 {
        return Err(tk.err("binary .msh files are not supported (only ASCII)"));
    }
    let _data_size: i64 = tk.int("data size")?;
    expect_end(&mut tk, "MeshFormat")?;

    let mut names = Vec::new();
    // Physical tag of each entity (dim, tag); absent = no physical group.
    let mut phys: HashMap<(u8, i32), i32> = HashMap::new();
    let mut node_tags: Vec<u64> = Vec::new();
    let mut coords: Vec<DVec2> = Vec::new();
    let mut node_lines: Vec<usize> = Vec::new();
    let mut raw = RawMesh2::default();
    let mut tri_nodes: Vec<[u64; 3]> = Vec::new();
    let mut tri_tags: Vec<u64> = Vec::new();
    let mut edge_nodes: Vec<([u64; 2], i32, usize)> = Vec::new();
    let mut point_nodes: Vec<(u64, i32, usize)> = Vec::new();
    let (mut has_nodes, mut has_elements) = (false, false);

    while let Some((sec, line)) = tk.next_token() {
        let Some(name) = sec.strip_prefix('$') else {
            return Err(tk.err(format!(
                "unexpected '{}' where a $Section was expected (a count smaller than its data?)",
                shorten(sec)
            )));
        };
        match name {
            "PhysicalNames" => {
                let n = tk.count("number of physical names")?;
                for _ in 0..n {
                    let dim: u8 = tk.int("physical name dimension")?;
                    let tag: i32 = tk.int("physical tag")?;
                    let name = tk.quoted("physical name")?.to_string();
                    names.push(PhysicalName { dim, tag, name });
                }
            }
            "Entities" => {
                let mut counts = [0usize; 4];
                for (d, c) in counts.iter_mut().enumerate() {
                    *c = tk.count(&format!("number of dimension-{d} entities"))?;
                }
                for (d, &c) in counts.iter().enumerate() {
                    for k in 0..c {
                        let what = format!("dimension-{d} entity {} of {c}", k + 1);
                        let tag: i32 = tk.int(&what)?;
                        for _ in 0..if d == 0 { 3 } else { 6 } {
                            tk.real(&what)?;
                        }
                        let np = tk.count(&what)?;
                        for j in 0..np {
                            let p: i32 = tk.int(&what)?;
                            if j == 0 {
                                phys.insert((d as u8, tag), p);
                            }
                        }
                        if d > 0 {
                            let nb = tk.count(&what)?;
                            for _ in 0..nb {
                                let _: i64 = tk.int(&what)?;
                            }
                        }
                    }
                }
            }
            "Nodes" => {
                if has_nodes {
                    return Err(tk.err_at(line, "second $Nodes section"));
                }
                has_nodes = true;
                let nblocks = tk.count("number of node blocks")?;
                let total = tk.count("number of nodes")?;
                let _: u64 = tk.int("minimum node tag")?;
                let _: u64 = tk.int("maximum node tag")?;
                node_tags.reserve(tk.capacity(total, 8));
                for b in 0..nblocks {
                    let what = format!("node block {} of {nblocks}", b + 1);
                    let dim = tk.count(&what)?;
                    let _: i32 = tk.int(&what)?;
                    let parametric = tk.count(&what)?;
                    let n = tk.count(&what)?;
                    if dim > 3 || parametric > 1 {
                        return Err(
                            tk.err(format!("{what}: bad entity dimension or parametric flag"))
                        );
                    }
                    let start = node_tags.len();
                    for k in 0..n {
                        node_tags.push(tk.int(&format!("{what}, node tag {}", k + 1))?);
                    }
                    for k in 0..n {
                        let w = format!("coordinates of node {}", node_tags[start + k]);
                        let x = tk.real(&w)?;
                        let y = tk.real(&w)?;
                        let z = tk.real(&w)?;
                        if z != 0.0 {
                            return Err(tk.err(format!(
                                "node {} has z = {z}: only planar meshes with z = 0 are supported",
                                node_tags[start + k]
                            )));
                        }
                        for _ in 0..parametric * dim.min(2) {
                            tk.real(&w)?;
                        }
                        coords.push(DVec2::new(x, y));
                        node_lines.push(tk.token_line());
                    }
                }
                if node_tags.len() != total {
                    return Err(tk.err(format!(
                        "$Nodes announces {total} nodes but its blocks hold {}",
                        node_tags.len()
                    )));
                }
            }
            "Elements" => {
                if has_elements {
                    return Err(tk.err_at(line, "second $Elements section"));
                }
                has_elements = true;
                let nblocks = tk.count("number of element blocks")?;
                let _total = tk.count("number of elements")?;
                let _: u64 = tk.int("minimum element tag")?;
                let _: u64 = tk.int("maximum element tag")?;
                for b in 0..nblocks {
                    let what = format!("element block {} of {nblocks}", b + 1);
                    let dim = tk.count(&what)?;
                    let etag: i32 = tk.int(&what)?;
                    let etype: i64 = tk.int(&what)?;
                    let n = tk.count(&what)?;
                    let bline = tk.token_line();
                    let label = phys.get(&(dim.min(255) as u8, etag)).copied().unwrap_or(0);
                    let nn = match etype {
                        2 => 3,
                        1 => 2,
                        15 => 1,
                        _ => {
                            return Err(tk.err_at(
                                bline,
                                format!(
                                    "{what}: element type {etype} is not supported (only 2 \
                                     triangles, 1 lines and 15 points in a 2D mesh)"
                                ),
                            ))
                        }
                    };
                    for k in 0..n {
                        let w = format!("{what}, element {} of {n}", k + 1);
                        let el_tag: u64 = tk.int(&w)?;
                        let mut v = [0u64; 3];
                        for x in v.iter_mut().take(nn) {
                            *x = tk.int(&w)?;
                        }
                        let l = tk.token_line();
                        match etype {
                            2 => {
                                tri_nodes.push(v);
                                tri_tags.push(el_tag);
                                raw.tri_ref.push(label);
                                raw.tri_line.push(l);
                            }
                            1 => edge_nodes.push(([v[0], v[1]], label, l)),
                            _ => point_nodes.push((v[0], label, l)),
                        }
                    }
                }
            }
            _ => {
                // Unknown section: skip to its end marker.
                let end = format!("$End{name}");
                loop {
                    match tk.next_token() {
                        Some((t, _)) if t == end => break,
                        Some(_) => {}
                        None => {
                            return Err(tk.err(format!("section ${name} has no {end}")));
                        }
                    }
                }
                continue;
            }
        }
        expect_end(&mut tk, name)?;
    }
    raw.last_line = tk.token_line();
    if !has_nodes {
        return Err(Error::parse(path, raw.last_line, "no $Nodes section"));
    }
    // Number nodes by increasing tag.
    let mut order: Vec<usize> = (0..node_tags.len()).collect();
    order.sort_unstable_by_key(|&k| node_tags[k]);
    let mut index: HashMap<u64, u32> = HashMap::with_capacity(order.len());
    for (new, &k) in order.iter().enumerate() {
        if index.insert(node_tags[k], new as u32).is_some() {
            return Err(Error::parse(
                path,
                node_lines[k],
                format!("node tag {} appears twice", node_tags[k]),
            ));
        }
    }
    raw.points = order.iter().map(|&k| coords[k]).collect();
    raw.point_line = order.iter().map(|&k| node_lines[k]).collect();
    raw.vert_ref = vec![0; raw.points.len()];
    let lookup = |tag: u64, line: usize| -> Result<u32> {
        index.get(&tag).copied().ok_or_else(|| {
            Error::parse(
                path,
                line,
                format!("element refers to unknown node tag {tag}"),
            )
        })
    };
    // Triangles in increasing element-tag order.
    let mut torder: Vec<usize> = (0..tri_nodes.len()).collect();
    torder.sort_by_key(|&k| tri_tags[k]);
    raw.tri_ref = torder.iter().map(|&k| raw.tri_ref[k]).collect();
    raw.tri_line = torder.iter().map(|&k| raw.tri_line[k]).collect();
    for (k, &o) in torder.iter().enumerate() {
        let (t, l) = (tri_nodes[o], raw.tri_line[k]);
        raw.tris
            .push([lookup(t[0], l)?, lookup(t[1], l)?, lookup(t[2], l)?]);
    }
    raw.has_edges = !edge_nodes.is_empty();
    for &(e, label, line) in &edge_nodes {
        raw.edges.push(RawEdge {
            v: [lookup(e[0], line)?, lookup(e[1], line)?],
            label,
            line,
        });
    }
    for &(p, label, line) in &point_nodes {
        let v = lookup(p, line)?;
        raw.vert_ref[v as usize] = label;
        raw.corners.push((v, line));
        raw.required.push((v, line));
    }
    let mesh = build_mesh(path, raw)?;
    Ok(GmshMesh {
        mesh,
        physical_names: names,
    })
}

/// Reads a Gmsh 4.1 ASCII `.msh` file with its physical names.
pub fn read_msh_full(path: &Path) -> Result<GmshMesh> {
    parse_msh(path, &read_text(path)?)
}

/// Reads a Gmsh 4.1 ASCII `.msh` file.
pub fn read_msh(path: &Path) -> Result<Mesh2> {
    Ok(read_msh_full(path)?.mesh)
}

/// Writes a 2D mesh as Gmsh 4.1 ASCII (atomically), without physical names.
pub fn write_msh(path: &Path, mesh: &Mesh2) -> Result<()> {
    write_msh_named(path, mesh, &[])
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
}

/// Writes a 2D mesh as Gmsh 4.1 ASCII (atomically) with the given physical names.
pub fn write_msh_named(path: &Path, mesh: &Mesh2, names: &[PhysicalName]) -> Result<()> {
    super::check_lengths(mesh)?;
    let np = mesh.points.len();
    // Point entities: one per corner.
    let corners: Vec<usize> = (0..np).filter(|&v| mesh.corner[v]).collect();
    // Curve entities: one per edge label; edges written = boundary + labelled interior.
    let mut curve_of: BTreeMap<i32, usize> = BTreeMap::new();
    let mut lines: Vec<(usize, [u32; 2])> = Vec::new();
    for (_, t, i) in mesh.edges() {
        let (t, i) = (t as usize, i as usize);
        let label = mesh.edge_ref[t][i];
        if mesh.neighbours[t][i] == NONE || label != 0 {
            let n = curve_of.len();
            let c = *curve_of.entry(label).or_insert(n);
            lines.push((c, mesh.edge_vertices(t, i)));
        }
    }
    let mut surf_of: BTreeMap<i32, usize> = BTreeMap::new();
    for t in mesh.live_tris() {
        let n = surf_of.len();
        surf_of.entry(mesh.tri_ref[t]).or_insert(n);
    }
    let mut points: Vec<Entity> = corners
        .iter()
        .enumerate()
        .map(|(k, &v)| Entity::new(k + 1, mesh.vert_ref[v]))
        .collect();
    let mut curves: Vec<Entity> = vec![];
    for (&label, &c) in &curve_of {
        curves.push(Entity::new(c + 1, label));
    }
    curves.sort_by_key(|e| e.tag);
    let mut surfs: Vec<Entity> = vec![];
    for (&r, &s) in &surf_of {
        surfs.push(Entity::new(s + 1, r));
    }
    surfs.sort_by_key(|e| e.tag);
    if surfs.is_empty() {
        surfs.push(Entity::new(1, 0));
    }
    // Node classification: (dim, entity index).
    let mut class: Vec<(u8, usize)> = vec![(2, 0); np];
    for (c, &t) in class.iter_mut().zip(&mesh.vert_tri) {
        if let Some(&s) = (t != NONE)
            .then(|| surf_of.get(&mesh.tri_ref[t as usize]))
            .flatten()
        {
            *c = (2, s);
        }
    }
    for &(c, [a, b]) in &lines {
        class[a as usize] = (1, c);
        class[b as usize] = (1, c);
    }
    for (k, &v) in corners.iter().enumerate() {
        class[v] = (0, k);
    }
    for (v, &(d, e)) in class.iter().enumerate() {
        let p = mesh.points[v];
        match d {
            0 => points[e].grow(p),
            1 => curves[e].grow(p),
            _ => surfs[e].grow(p),
        }
    }
    for &(c, [a, b]) in &lines {
        curves[c].grow(mesh.points[a as usize]);
        curves[c].grow(mesh.points[b as usize]);
    }
    for t in mesh.live_tris() {
        let s = surf_of[&mesh.tri_ref[t]];
        for p in mesh.tri_points(t) {
            surfs[s].grow(p);
        }
    }
    let mut blocks: Vec<Vec<Vec<usize>>> = vec![
        vec![vec![]; points.len()],
        vec![vec![]; curves.len()],
        vec![vec![]; surfs.len()],
    ];
    for (v, &(d, e)) in class.iter().enumerate() {
        blocks[d as usize][e].push(v);
    }
    let ents = [&points, &curves, &surfs];
    atomic_write(path, |w| {
        writeln!(w, "$MeshFormat\n4.1 0 8\n$EndMeshFormat")?;
        if !names.is_empty() {
            writeln!(w, "$PhysicalNames\n{}", names.len())?;
            for n in names {
                writeln!(w, "{} {} \"{}\"", n.dim, n.tag, n.name.replace('"', "'"))?;
            }
            writeln!(w, "$EndPhysicalNames")?;
        }
        writeln!(
            w,
            "$Entities\n{} {} {} 0",
            points.len(),
            curves.len(),
            surfs.len()
        )?;
        let bbox = |e: &Entity| {
            let (lo, hi) = if e.lo.x <= e.hi.x {
                (e.lo, e.hi)
            } else {
                (DVec2::ZERO, DVec2::ZERO)
            };
            (lo, hi)
        };
        let phys = |e: &Entity| {
            if e.phys != 0 {
                format!("1 {}", e.phys)
            } else {
                "0".to_string()
            }
        };
        for e in &points {
            let (p, _) = bbox(e);
            writeln!(
                w,
                "{} {} {} 0 {}",
                e.tag,
                fmt_f64(p.x),
                fmt_f64(p.y),
                phys(e)
            )?;
        }
        for e in curves.iter().chain(&surfs) {
            let (lo, hi) = bbox(e);
            writeln!(
                w,
                "{} {} {} 0 {} {} 0 {} 0",
                e.tag,
                fmt_f64(lo.x),
                fmt_f64(lo.y),
                fmt_f64(hi.x),
                fmt_f64(hi.y),
                phys(e)
            )?;
        }
        writeln!(w, "$EndEntities")?;
        let nblocks = blocks.iter().flatten().filter(|b| !b.is_empty()).count();
        writeln!(w, "$Nodes\n{nblocks} {np} {} {np}", np.min(1))?;
        for (d, per) in blocks.iter().enumerate() {
            for (e, nodes) in per.iter().enumerate() {
                if nodes.is_empty() {
                    continue;
                }
                writeln!(w, "{d} {} 0 {}", ents[d][e].tag, nodes.len())?;
                for &v in nodes {
                    writeln!(w, "{}", v + 1)?;
                }
                for &v in nodes {
                    let p = mesh.points[v];
                    writeln!(w, "{} {} 0", fmt_f64(p.x), fmt_f64(p.y))?;
                }
            }
        }
        writeln!(w, "$EndNodes")?;
        let mut lines_of: Vec<Vec<[u32; 2]>> = vec![vec![]; curves.len()];
        for &(c, e) in &lines {
            lines_of[c].push(e);
        }
        // Triangle element tags follow the triangle order (so that reading keeps it).
        let base = corners.len() + lines.len();
        let mut tris_of: Vec<Vec<usize>> = vec![vec![]; surfs.len()];
        for t in mesh.live_tris() {
            tris_of[surf_of[&mesh.tri_ref[t]]].push(t);
        }
        let n_el = corners.len() + lines.len() + mesh.n_live_tris();
        let mut rank = vec![0usize; mesh.n_tris()];
        for (k, t) in mesh.live_tris().enumerate() {
            rank[t] = k;
        }
        let nblocks = corners.len()
            + lines_of.iter().filter(|l| !l.is_empty()).count()
            + tris_of.iter().filter(|l| !l.is_empty()).count();
        writeln!(w, "$Elements\n{nblocks} {n_el} {} {n_el}", n_el.min(1))?;
        let mut tag = 0usize;
        for (k, &v) in corners.iter().enumerate() {
            tag += 1;
            writeln!(w, "0 {} 15 1\n{tag} {}", points[k].tag, v + 1)?;
        }
        for (c, ls) in lines_of.iter().enumerate() {
            if ls.is_empty() {
                continue;
            }
            writeln!(w, "1 {} 1 {}", curves[c].tag, ls.len())?;
            for [a, b] in ls {
                tag += 1;
                writeln!(w, "{tag} {} {}", a + 1, b + 1)?;
            }
        }
        for (s, ts) in tris_of.iter().enumerate() {
            if ts.is_empty() {
                continue;
            }
            writeln!(w, "2 {} 2 {}", surfs[s].tag, ts.len())?;
            for &t in ts {
                let [a, b, c] = mesh.tris[t];
                writeln!(w, "{} {} {} {}", base + rank[t] + 1, a + 1, b + 1, c + 1)?;
            }
        }
        writeln!(w, "$EndElements")
    })
}
