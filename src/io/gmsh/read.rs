//! Reading Gmsh 4.1 ASCII: one function per section (`$MeshFormat`, `$PhysicalNames`,
//! `$Entities`, `$Nodes`, `$Elements`; any other section is skipped), then the numbering of
//! nodes and triangles and the validation shared with the Medit reader.

use super::{GmshMesh, PhysicalName};
use crate::error::{Error, Result};
use crate::geom::DVec2;
use crate::io::tokens::{read_text, shorten, Tokens};
use crate::io::validate::{build_mesh, RawEdge, RawMesh2};
use crate::mesh::Mesh2;
use std::collections::HashMap;
use std::path::Path;

/// Parses a Gmsh 4.1 ASCII mesh from `text` (`path` is used in messages).
pub fn parse_msh(path: &Path, text: &str) -> Result<GmshMesh> {
    let mut tk = Tokens::new(path, text, None);
    read_mesh_format(&mut tk)?;
    let mut data = Sections::default();
    while let Some((sec, line)) = tk.next_token() {
        let Some(name) = sec.strip_prefix('$') else {
            return Err(tk.err(format!(
                "unexpected '{}' where a $Section was expected (a count smaller than its data?)",
                shorten(sec)
            )));
        };
        match name {
            "PhysicalNames" => data.read_physical_names(&mut tk)?,
            "Entities" => data.read_entities(&mut tk)?,
            "Nodes" => data.read_nodes(&mut tk, line)?,
            "Elements" => data.read_elements(&mut tk, line)?,
            _ => {
                skip_section(&mut tk, name)?;
                continue;
            }
        }
        expect_end(&mut tk, name)?;
    }
    let last_line = tk.token_line();
    data.into_mesh(path, last_line)
}

/// Reads a Gmsh 4.1 ASCII `.msh` file with its physical names.
pub fn read_msh_full(path: &Path) -> Result<GmshMesh> {
    parse_msh(path, &read_text(path)?)
}

/// Reads a Gmsh 4.1 ASCII `.msh` file.
pub fn read_msh(path: &Path) -> Result<Mesh2> {
    Ok(read_msh_full(path)?.mesh)
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

/// `$MeshFormat`: version 4.1, ASCII, up to `$EndMeshFormat`.
fn read_mesh_format(tk: &mut Tokens) -> Result<()> {
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
    expect_end(tk, "MeshFormat")
}

/// An unknown section: skipped up to its end marker.
fn skip_section(tk: &mut Tokens, name: &str) -> Result<()> {
    let end = format!("$End{name}");
    loop {
        match tk.next_token() {
            Some((t, _)) if t == end => return Ok(()),
            Some(_) => {}
            None => return Err(tk.err(format!("section ${name} has no {end}"))),
        }
    }
}

/// What the sections of a file hold, in file order, before nodes and triangles are numbered.
#[derive(Default)]
struct Sections {
    names: Vec<PhysicalName>,
    /// Physical tag of each entity `(dim, tag)`; absent = no physical group.
    phys: HashMap<(u8, i32), i32>,
    has_nodes: bool,
    node_tags: Vec<u64>,
    coords: Vec<DVec2>,
    node_lines: Vec<usize>,
    has_elements: bool,
    /// Triangles: node tags, element tag, label, line.
    tri_nodes: Vec<[u64; 3]>,
    tri_tags: Vec<u64>,
    tri_ref: Vec<i32>,
    tri_line: Vec<usize>,
    /// Lines: node tags, label, line.
    edge_nodes: Vec<([u64; 2], i32, usize)>,
    /// Points: node tag, label, line.
    point_nodes: Vec<(u64, i32, usize)>,
}

impl Sections {
    /// `$PhysicalNames`: count, then `dim tag "name"` per group.
    fn read_physical_names(&mut self, tk: &mut Tokens) -> Result<()> {
        let n = tk.count("number of physical names")?;
        for _ in 0..n {
            let dim: u8 = tk.int("physical name dimension")?;
            let tag: i32 = tk.int("physical tag")?;
            let name = tk.quoted("physical name")?.to_string();
            self.names.push(PhysicalName { dim, tag, name });
        }
        Ok(())
    }

    /// `$Entities`: the first physical tag of every point, curve and surface (volumes are
    /// read and ignored).
    fn read_entities(&mut self, tk: &mut Tokens) -> Result<()> {
        let mut counts = [0usize; 4];
        for (d, c) in counts.iter_mut().enumerate() {
            *c = tk.count(&format!("number of dimension-{d} entities"))?;
        }
        for (d, &c) in counts.iter().enumerate() {
            for k in 0..c {
                let what = format!("dimension-{d} entity {} of {c}", k + 1);
                self.read_entity(tk, d, &what)?;
            }
        }
        Ok(())
    }

    /// One entity of dimension `d`: tag, bounding box (a point for `d = 0`), physical tags,
    /// and for `d > 0` the bounding entities.
    fn read_entity(&mut self, tk: &mut Tokens, d: usize, what: &str) -> Result<()> {
        let tag: i32 = tk.int(what)?;
        for _ in 0..if d == 0 { 3 } else { 6 } {
            tk.real(what)?;
        }
        let np = tk.count(what)?;
        for j in 0..np {
            let p: i32 = tk.int(what)?;
            if j == 0 {
                self.phys.insert((d as u8, tag), p);
            }
        }
        if d > 0 {
            let nb = tk.count(what)?;
            for _ in 0..nb {
                let _: i64 = tk.int(what)?;
            }
        }
        Ok(())
    }

    /// `$Nodes` (at most one, starting on `line`): header, then entity blocks of node tags and
    /// coordinates (`z = 0`; parametric coordinates skipped).
    fn read_nodes(&mut self, tk: &mut Tokens, line: usize) -> Result<()> {
        if self.has_nodes {
            return Err(tk.err_at(line, "second $Nodes section"));
        }
        self.has_nodes = true;
        let nblocks = tk.count("number of node blocks")?;
        let total = tk.count("number of nodes")?;
        let _: u64 = tk.int("minimum node tag")?;
        let _: u64 = tk.int("maximum node tag")?;
        self.node_tags.reserve(tk.capacity(total, 8));
        for b in 0..nblocks {
            self.read_node_block(tk, &format!("node block {} of {nblocks}", b + 1))?;
        }
        if self.node_tags.len() != total {
            return Err(tk.err(format!(
                "$Nodes announces {total} nodes but its blocks hold {}",
                self.node_tags.len()
            )));
        }
        Ok(())
    }

    /// One node block: entity dimension and tag, parametric flag, count, tags, coordinates.
    fn read_node_block(&mut self, tk: &mut Tokens, what: &str) -> Result<()> {
        let dim = tk.count(what)?;
        let _: i32 = tk.int(what)?;
        let parametric = tk.count(what)?;
        let n = tk.count(what)?;
        if dim > 3 || parametric > 1 {
            return Err(tk.err(format!("{what}: bad entity dimension or parametric flag")));
        }
        let start = self.node_tags.len();
        for k in 0..n {
            self.node_tags
                .push(tk.int(&format!("{what}, node tag {}", k + 1))?);
        }
        for k in 0..n {
            let tag = self.node_tags[start + k];
            let w = format!("coordinates of node {tag}");
            let x = tk.real(&w)?;
            let y = tk.real(&w)?;
            let z = tk.real(&w)?;
            if z != 0.0 {
                return Err(tk.err(format!(
                    "node {tag} has z = {z}: only planar meshes with z = 0 are supported"
                )));
            }
            for _ in 0..parametric * dim.min(2) {
                tk.real(&w)?;
            }
            self.coords.push(DVec2::new(x, y));
            self.node_lines.push(tk.token_line());
        }
        Ok(())
    }

    /// `$Elements` (at most one, starting on `line`): header, then entity blocks of points,
    /// lines or triangles.
    fn read_elements(&mut self, tk: &mut Tokens, line: usize) -> Result<()> {
        if self.has_elements {
            return Err(tk.err_at(line, "second $Elements section"));
        }
        self.has_elements = true;
        let nblocks = tk.count("number of element blocks")?;
        let _total = tk.count("number of elements")?;
        let _: u64 = tk.int("minimum element tag")?;
        let _: u64 = tk.int("maximum element tag")?;
        for b in 0..nblocks {
            self.read_element_block(tk, &format!("element block {} of {nblocks}", b + 1))?;
        }
        Ok(())
    }

    /// One element block: entity dimension and tag (whose physical tag labels the elements),
    /// element type (2 triangles, 1 lines, 15 points), count, then tag and nodes per element.
    fn read_element_block(&mut self, tk: &mut Tokens, what: &str) -> Result<()> {
        let dim = tk.count(what)?;
        let etag: i32 = tk.int(what)?;
        let etype: i64 = tk.int(what)?;
        let n = tk.count(what)?;
        let bline = tk.token_line();
        let label = self
            .phys
            .get(&(dim.min(255) as u8, etag))
            .copied()
            .unwrap_or(0);
        let nn = match etype {
            2 => 3,
            1 => 2,
            15 => 1,
            _ => {
                return Err(tk.err_at(
                    bline,
                    format!(
                        "{what}: element type {etype} is not supported (only 2 triangles, 1 \
                         lines and 15 points in a 2D mesh)"
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
                    self.tri_nodes.push(v);
                    self.tri_tags.push(el_tag);
                    self.tri_ref.push(label);
                    self.tri_line.push(l);
                }
                1 => self.edge_nodes.push(([v[0], v[1]], label, l)),
                _ => self.point_nodes.push((v[0], label, l)),
            }
        }
        Ok(())
    }

    /// Numbers nodes by increasing tag and triangles by increasing element tag, resolves the
    /// node tags of every element, and validates the mesh (`last_line`: the end of the file).
    fn into_mesh(self, path: &Path, last_line: usize) -> Result<GmshMesh> {
        if !self.has_nodes {
            return Err(Error::parse(path, last_line, "no $Nodes section"));
        }
        let (order, index) = self.number_nodes(path)?;
        let lookup = |tag: u64, line: usize| -> Result<u32> {
            index.get(&tag).copied().ok_or_else(|| {
                Error::parse(
                    path,
                    line,
                    format!("element refers to unknown node tag {tag}"),
                )
            })
        };
        let mut raw = RawMesh2 {
            points: order.iter().map(|&k| self.coords[k]).collect(),
            point_line: order.iter().map(|&k| self.node_lines[k]).collect(),
            vert_ref: vec![0; order.len()],
            last_line,
            ..RawMesh2::default()
        };
        let mut torder: Vec<usize> = (0..self.tri_nodes.len()).collect();
        torder.sort_by_key(|&k| self.tri_tags[k]);
        raw.tri_ref = torder.iter().map(|&k| self.tri_ref[k]).collect();
        raw.tri_line = torder.iter().map(|&k| self.tri_line[k]).collect();
        for (&o, &l) in torder.iter().zip(&raw.tri_line) {
            let t = self.tri_nodes[o];
            raw.tris
                .push([lookup(t[0], l)?, lookup(t[1], l)?, lookup(t[2], l)?]);
        }
        raw.has_edges = !self.edge_nodes.is_empty();
        for &(e, label, line) in &self.edge_nodes {
            raw.edges.push(RawEdge {
                v: [lookup(e[0], line)?, lookup(e[1], line)?],
                label,
                line,
            });
        }
        for &(p, label, line) in &self.point_nodes {
            let v = lookup(p, line)?;
            raw.vert_ref[v as usize] = label;
            raw.corners.push((v, line));
            raw.required.push((v, line));
        }
        Ok(GmshMesh {
            mesh: build_mesh(path, raw)?,
            physical_names: self.names,
        })
    }

    /// The nodes in increasing tag order and the index of each tag; errors on a repeated tag.
    fn number_nodes(&self, path: &Path) -> Result<(Vec<usize>, HashMap<u64, u32>)> {
        let mut order: Vec<usize> = (0..self.node_tags.len()).collect();
        order.sort_unstable_by_key(|&k| self.node_tags[k]);
        let mut index: HashMap<u64, u32> = HashMap::with_capacity(order.len());
        for (new, &k) in order.iter().enumerate() {
            if index.insert(self.node_tags[k], new as u32).is_some() {
                return Err(Error::parse(
                    path,
                    self.node_lines[k],
                    format!("node tag {} appears twice", self.node_tags[k]),
                ));
            }
        }
        Ok((order, index))
    }
}
