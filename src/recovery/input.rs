//! Input validation shared by every recovery: the field (length, finiteness) and the mesh
//! (array lengths, index ranges, at least [`MIN_COMPONENT_VERTICES`] vertices per connected
//! component, so that a quadratic fit is possible somewhere in each component).

use crate::error::{Error, MeshDefect, Result};
use crate::mesh::{Mesh2, NONE};

/// The smallest connected component a recovery accepts: a full quadratic in 2D has 6
/// coefficients (004 §4.3: `d(d+1)/2` Hessian coefficients plus value and gradient).
pub const MIN_COMPONENT_VERTICES: usize = 6;

/// Array lengths and triangle indices are consistent (what the ring walks index with), and every
/// connected component of the live triangles has at least [`MIN_COMPONENT_VERTICES`] vertices.
/// The error names the smallest vertex of the first (by vertex index) undersized component.
pub(crate) fn check_mesh(mesh: &Mesh2) -> Result<()> {
    let n = mesh.n_points();
    if mesh.vert_tri.len() != n {
        return Err(MeshDefect::BadVertexData {
            vertex: mesh.vert_tri.len().min(n),
            detail: "vert_tri has a different length than points",
        }
        .into());
    }
    if mesh.neighbours.len() != mesh.tris.len() {
        return Err(MeshDefect::BadAdjacency {
            tri: mesh.neighbours.len().min(mesh.tris.len()),
            edge: 0,
            detail: "neighbours has a different length than tris",
        }
        .into());
    }
    // Union-find over the vertices of live triangles (path halving, union by size).
    let mut parent: Vec<u32> = (0..n as u32).collect();
    let mut size = vec![1u32; n];
    fn find(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            let gp = parent[parent[x as usize] as usize];
            parent[x as usize] = gp;
            x = gp;
        }
        x
    }
    for t in mesh.live_tris() {
        let tri = mesh.tris[t];
        for &v in &tri {
            if v as usize >= n {
                return Err(MeshDefect::IndexOutOfRange {
                    tri: t,
                    vertex: v as u64,
                    n_points: n,
                }
                .into());
            }
        }
        for (a, b) in [(tri[0], tri[1]), (tri[1], tri[2])] {
            let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
            if ra != rb {
                let (big, small) = if size[ra as usize] >= size[rb as usize] {
                    (ra, rb)
                } else {
                    (rb, ra)
                };
                parent[small as usize] = big;
                size[big as usize] += size[small as usize];
            }
        }
        for i in 0..3 {
            let nb = mesh.neighbours[t][i];
            if nb != NONE && nb as usize >= mesh.tris.len() {
                return Err(MeshDefect::BadAdjacency {
                    tri: t,
                    edge: i,
                    detail: "neighbour index out of range",
                }
                .into());
            }
        }
    }
    for v in 0..n {
        let seed = mesh.vert_tri[v];
        if seed == NONE {
            continue; // unreferenced vertex: not part of the triangulation
        }
        if seed as usize >= mesh.tris.len() {
            return Err(MeshDefect::BadVertexData {
                vertex: v,
                detail: "seed triangle index out of range",
            }
            .into());
        }
        let r = find(&mut parent, v as u32) as usize;
        if (size[r] as usize) < MIN_COMPONENT_VERTICES {
            return Err(Error::InvalidInput(format!(
                "vertex {v} lies in a connected component of {} vertices; derivative recovery \
                 needs at least {MIN_COMPONENT_VERTICES}",
                size[r]
            )));
        }
    }
    Ok(())
}
