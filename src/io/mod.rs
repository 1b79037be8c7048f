//! Mesh and field file formats: Medit `.mesh`/`.sol` (MMG, FreeFem++), Gmsh `.msh` 4.1, VTK
//! `.vtu` (output), Wavefront `.obj` (surfaces). Every writer goes through [`atomic_write`].
//!
//! Readers return [`Error::Parse`] naming the file, the line and the problem; they never panic on
//! any input. A 2D mesh read from a file is validated like [`Mesh2::check`] (see `validate.rs`
//! for the one documented repair: a mesh whose triangles are *all* clockwise is reoriented).

mod atomic;
mod decimal;
mod gmsh;
mod medit;
mod obj;
mod sol;
mod textout;
mod tokens;
mod validate;
mod vtk;
mod vtk3;

pub use atomic::atomic_write;
pub use gmsh::{
    parse_msh, read_msh, read_msh_full, write_msh, write_msh_named, GmshMesh, PhysicalName,
};
pub use medit::{
    parse_medit3, parse_medit3_features, parse_mesh2, read_medit2, read_medit2_unchecked,
    read_medit3, read_medit3_features, write_medit2, write_medit2_to, write_medit3,
    write_medit3_features, Medit3,
};
pub use obj::{parse_obj, read_obj, write_obj, SurfaceMesh};
pub use sol::{
    parse_sol, read_sol, read_sol_for, sym3_from_file, sym3_to_file, write_sol, Sol, SolField,
};
pub use vtk::{write_vtu, FieldRef};
pub use vtk3::write_vtu3;

use crate::error::{Error, MeshDefect, Result};
use crate::mesh::Mesh2;
use std::path::Path;

/// The lower-case extension of `path`.
fn extension(path: &Path) -> String {
    path.extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default()
}

/// An [`Error::Io`] naming `path` when there is no such file (checked before the extension, so
/// that a mistyped path is reported as missing rather than as an unknown format).
fn existing(path: &Path) -> Result<()> {
    match std::fs::metadata(path) {
        Ok(_) => Ok(()),
        Err(e) => Err(Error::io(path, e)),
    }
}

/// Reads a 2D mesh, choosing the format by extension: `.mesh` (Medit) or `.msh` (Gmsh 4.1).
pub fn read_mesh(path: &Path) -> Result<Mesh2> {
    existing(path)?;
    match extension(path).as_str() {
        "mesh" => read_medit2(path),
        "msh" => read_msh(path),
        e => Err(Error::Unsupported(format!(
            "{}: cannot read meshes with extension '.{e}' (use .mesh or .msh)",
            path.display()
        ))),
    }
}

/// Array-length consistency of a mesh about to be written (writers index these arrays).
pub(crate) fn check_lengths(mesh: &Mesh2) -> Result<()> {
    let nt = mesh.tris.len();
    let np = mesh.points.len();
    if mesh.neighbours.len() != nt || mesh.tri_ref.len() != nt || mesh.edge_ref.len() != nt {
        return Err(MeshDefect::BadLabel {
            tri: nt,
            detail: "per-triangle arrays have different lengths",
        }
        .into());
    }
    if mesh.vert_ref.len() != np
        || mesh.corner.len() != np
        || mesh.required.len() != np
        || mesh.vert_tri.len() != np
    {
        return Err(MeshDefect::BadVertexData {
            vertex: np,
            detail: "per-vertex arrays have different lengths",
        }
        .into());
    }
    if let Some(v) = mesh
        .vert_tri
        .iter()
        .position(|&s| s != crate::mesh::NONE && s as usize >= nt)
    {
        return Err(MeshDefect::BadVertexData {
            vertex: v,
            detail: "the seed triangle is out of range",
        }
        .into());
    }
    for t in mesh.live_tris() {
        if mesh.tris[t].iter().any(|&v| v as usize >= np) {
            return Err(MeshDefect::IndexOutOfRange {
                tri: t,
                vertex: mesh.tris[t].iter().copied().max().unwrap_or(0) as u64,
                n_points: np,
            }
            .into());
        }
    }
    Ok(())
}

/// Writes a 2D mesh, choosing the format by extension: `.mesh`, `.msh` or `.vtu` (mesh and
/// `tri_ref` only; use [`write_vtu`] for fields). Tombstoned triangles are skipped.
pub fn write_mesh(path: &Path, mesh: &Mesh2) -> Result<()> {
    match extension(path).as_str() {
        "mesh" => write_medit2(path, mesh),
        "msh" => write_msh(path, mesh),
        "vtu" => write_vtu(path, mesh, &[], &[]),
        e => Err(Error::Unsupported(format!(
            "{}: cannot write meshes with extension '.{e}' (use .mesh, .msh or .vtu)",
            path.display()
        ))),
    }
}

/// Any file the library can read, as recognised by [`read_any`].
#[derive(Debug, Clone)]
pub enum AnyFile {
    /// A 2D triangle mesh (`.mesh` with Dimension 2, `.msh`).
    Mesh2(Mesh2),
    /// A 3D Medit mesh (`.mesh` with Dimension 3 and tetrahedra).
    Medit3(Medit3),
    /// A solution file (`.sol`).
    Sol(Sol),
    /// A triangulated surface (`.obj`).
    Surface(SurfaceMesh),
}

/// Reads any supported file by extension; a `.mesh` is read as 2D unless it is a volume mesh.
pub fn read_any(path: &Path) -> Result<AnyFile> {
    existing(path)?;
    match extension(path).as_str() {
        "sol" => Ok(AnyFile::Sol(read_sol(path)?)),
        "obj" => Ok(AnyFile::Surface(read_obj(path)?)),
        "msh" => Ok(AnyFile::Mesh2(read_msh(path)?)),
        "mesh" => {
            let text = tokens::read_text(path)?;
            match parse_mesh2(path, &text) {
                Ok(m) => Ok(AnyFile::Mesh2(m)),
                Err(e2) => match parse_medit3(path, &text) {
                    Ok(m3) if !m3.tets.is_empty() => Ok(AnyFile::Medit3(m3)),
                    // A 3D file's own defect rather than the 2D reader's refusal of it.
                    Err(Error::Parse { path, line, msg }) if !msg.starts_with(medit::NOT_3D) => {
                        Err(Error::Parse { path, line, msg })
                    }
                    _ => Err(e2),
                },
            }
        }
        e => Err(Error::Unsupported(format!(
            "{}: unknown file extension '.{e}' (known: .mesh, .msh, .sol, .obj)",
            path.display()
        ))),
    }
}
