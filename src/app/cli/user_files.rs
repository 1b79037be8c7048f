//! Reading a user's mesh and `.sol` files for `redistance`, `metric` and `measure`: a triangle or
//! tetrahedral mesh, and a scalar or metric field checked against it (length, kind, dimension,
//! finite values), each mismatch one typed error that names the file.

use anisomesh::io::{self, AnyFile, SolField};
use anisomesh::metric::{Sym2, Sym3, SymTensor};
use anisomesh::{DVec2, DVec3, Error, Result};
use std::path::Path;

/// A mesh read from a user's file: its vertices and simplices.
pub enum UserMesh {
    /// Triangles in the plane (live triangles of a `.mesh`/`.msh`).
    Tri {
        /// Vertices.
        points: Vec<DVec2>,
        /// Triangles.
        cells: Vec<[u32; 3]>,
        /// The mesh itself (for writing and 2D-only tools).
        mesh: Box<anisomesh::Mesh2>,
    },
    /// Tetrahedra (a `Dimension 3` Medit mesh).
    Tet {
        /// Vertices.
        points: Vec<DVec3>,
        /// Tetrahedra.
        cells: Vec<[u32; 4]>,
    },
}

impl UserMesh {
    /// Number of vertices.
    pub fn n_points(&self) -> usize {
        match self {
            UserMesh::Tri { points, .. } => points.len(),
            UserMesh::Tet { points, .. } => points.len(),
        }
    }

    /// Space dimension.
    pub fn dim(&self) -> usize {
        match self {
            UserMesh::Tri { .. } => 2,
            UserMesh::Tet { .. } => 3,
        }
    }

    /// "triangles" or "tetrahedra" with their count.
    pub fn describe(&self) -> String {
        match self {
            UserMesh::Tri { points, cells, .. } => {
                format!("{} vertices, {} triangles", points.len(), cells.len())
            }
            UserMesh::Tet { points, cells } => {
                format!("{} vertices, {} tetrahedra", points.len(), cells.len())
            }
        }
    }
}

/// Reads a 2D (`.mesh`, `.msh`) or 3D (`.mesh` with tetrahedra) mesh.
pub fn read_user_mesh(path: &Path) -> Result<UserMesh> {
    match io::read_any(path)? {
        AnyFile::Mesh2(mesh) => {
            mesh.check()?;
            let cells = mesh.live_tris().map(|t| mesh.tris[t]).collect();
            Ok(UserMesh::Tri {
                points: mesh.points.clone(),
                cells,
                mesh: Box::new(mesh),
            })
        }
        AnyFile::Medit3(m) => Ok(UserMesh::Tet {
            points: m.points,
            cells: m.tets,
        }),
        _ => Err(Error::InvalidInput(format!(
            "{}: not a triangle or tetrahedral mesh",
            path.display()
        ))),
    }
}

/// Reads the `.sol` at `path` for `mesh`: vertex count and dimension must match.
fn read_sol_for_mesh(path: &Path, mesh: &UserMesh) -> Result<io::Sol> {
    let sol = io::read_sol_for(path, mesh.n_points())?;
    if sol.dim != mesh.dim() {
        return Err(Error::InvalidInput(format!(
            "{}: a {}D solution for a {}D mesh",
            path.display(),
            sol.dim,
            mesh.dim()
        )));
    }
    Ok(sol)
}

fn bad_field(path: &Path, msg: String) -> Error {
    Error::InvalidField {
        name: path.display().to_string(),
        msg,
    }
}

/// The scalar field (first field of the file) of a `.sol` for `mesh`, all values finite.
pub fn read_scalar(path: &Path, mesh: &UserMesh) -> Result<Vec<f64>> {
    let sol = read_sol_for_mesh(path, mesh)?;
    match sol.fields.into_iter().next() {
        Some(SolField::Scalar(u)) => {
            if let Some(v) = u.iter().position(|x| !x.is_finite()) {
                return Err(bad_field(
                    path,
                    format!("non-finite value {} at vertex {}", u[v], v + 1),
                ));
            }
            Ok(u)
        }
        Some(SolField::Tensor2(_) | SolField::Tensor3(_)) => Err(Error::InvalidInput(format!(
            "{}: holds a metric (symmetric tensors); a scalar level set is needed here",
            path.display()
        ))),
        _ => Err(Error::InvalidInput(format!(
            "{}: the first field is not a scalar level set",
            path.display()
        ))),
    }
}

/// The metric field of a `.sol` for a 2D mesh (SPD at every vertex).
pub fn read_metric2(path: &Path, mesh: &UserMesh) -> Result<Vec<Sym2>> {
    let sol = read_sol_for_mesh(path, mesh)?;
    match sol.fields.into_iter().next() {
        Some(SolField::Tensor2(m)) => check_metric(path, m),
        _ => Err(not_a_metric(path)),
    }
}

/// The metric field of a `.sol` for a 3D mesh (SPD at every vertex).
pub fn read_metric3(path: &Path, mesh: &UserMesh) -> Result<Vec<Sym3>> {
    let sol = read_sol_for_mesh(path, mesh)?;
    match sol.fields.into_iter().next() {
        Some(SolField::Tensor3(m)) => {
            check_metric(path, m.iter().map(io::sym3_from_file).collect())
        }
        _ => Err(not_a_metric(path)),
    }
}

fn not_a_metric(path: &Path) -> Error {
    Error::InvalidInput(format!(
        "{}: holds no metric (a symmetric tensor field, Medit type 3) as its first field",
        path.display()
    ))
}

fn check_metric<const D: usize, S: SymTensor<D>>(path: &Path, m: Vec<S>) -> Result<Vec<S>> {
    for (v, t) in m.iter().enumerate() {
        if !(t.is_finite() && t.is_spd()) {
            return Err(bad_field(
                path,
                format!(
                    "the tensor at vertex {} is not a metric (finite SPD)",
                    v + 1
                ),
            ));
        }
    }
    Ok(m)
}
