//! Reading a user's mesh and `.sol` files for `redistance`, `metric` and `measure`: a triangle or
//! tetrahedral mesh, and a scalar or metric field checked against it (length, kind, dimension,
//! finite values), each mismatch one typed error that names the file.

use anisomesh::io::{self, AnyFile, SolField};
use anisomesh::mesh3::Mesh3;
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
    read_sol_checked(path, mesh.n_points(), mesh.dim())
}

/// Reads the `.sol` at `path` for a mesh of `n` vertices in dimension `dim`: vertex count and
/// dimension must match.
pub fn read_sol_checked(path: &Path, n: usize, dim: usize) -> Result<io::Sol> {
    let sol = io::read_sol_for(path, n)?;
    if sol.dim != dim {
        return Err(Error::InvalidInput(format!(
            "{}: a {}D solution for a {dim}D mesh",
            path.display(),
            sol.dim,
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

/// An error naming the first vertex (1-based, as in the file) whose tensor is not a finite SPD
/// metric.
pub fn check_metric<const D: usize, S: SymTensor<D>>(path: &Path, m: Vec<S>) -> Result<Vec<S>> {
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

/// A mesh given to `adapt --input`: triangles or tetrahedra.
pub enum InputMesh {
    /// A planar triangle mesh.
    Tri(Box<anisomesh::Mesh2>),
    /// A tetrahedral mesh, checked ([`mesh3_from_medit`]).
    Tet(Box<Mesh3>),
}

/// Reads the mesh of `adapt --input`: a 2D mesh as it is, a 3D one checked by
/// [`mesh3_from_medit`], with the ridges and corners of its boundary found with the ridge angle
/// `ridge_angle` (degrees) and those the file declares ([`Mesh3::detect_features`]). A
/// `Dimension 3` file with triangles and no tetrahedra (a surface mesh) is refused with its own
/// error.
pub fn read_input_mesh(path: &Path, ridge_angle: f64) -> Result<InputMesh> {
    match io::read_any(path) {
        Ok(AnyFile::Mesh2(m)) => Ok(InputMesh::Tri(Box::new(m))),
        Ok(AnyFile::Medit3(_)) => {
            let (m, declared) = io::read_medit3_features(path)?;
            let mut mesh = mesh3_from_medit(path, m)?;
            mesh.features = mesh
                .detect_features(ridge_angle, &declared)
                .map_err(|e| Error::InvalidInput(format!("{}: {e}", path.display())))?;
            Ok(InputMesh::Tet(Box::new(mesh)))
        }
        Ok(_) => Err(Error::InvalidInput(format!(
            "{}: not a triangle or tetrahedral mesh",
            path.display()
        ))),
        Err(e) => match io::read_medit3(path) {
            Ok(m) if m.tets.is_empty() => Err(Error::InvalidInput(format!(
                "{}: a surface mesh ({} triangles, no tetrahedra); adapting in 3D needs a \
                 volume mesh",
                path.display(),
                m.tris.len()
            ))),
            _ => Err(e),
        },
    }
}

/// The tetrahedral mesh of a Medit file, checked: every tetrahedron positively oriented (as
/// Medit and mmg3d orient them; a non-positive volume is refused, naming the tetrahedron), a
/// conforming mesh ([`Mesh3::check`]); the boundary faces carry the labels of the file's
/// triangles (1 where the file has none).
pub fn mesh3_from_medit(path: &Path, m: io::Medit3) -> Result<Mesh3> {
    for (t, tet) in m.tets.iter().enumerate() {
        let p = tet.map(|v| m.points[v as usize]);
        let vol = anisomesh::mesh3::signed_volume(p[0], p[1], p[2], p[3]);
        if vol <= 0.0 || vol.is_nan() {
            return Err(Error::InvalidInput(format!(
                "{}: tetrahedron {} (vertices {} {} {} {}) is {} (signed volume {vol:.3e}); \
                 tetrahedra must be positively oriented",
                path.display(),
                t + 1,
                tet[0] + 1,
                tet[1] + 1,
                tet[2] + 1,
                tet[3] + 1,
                if vol < 0.0 { "inverted" } else { "flat" }
            )));
        }
    }
    let labels: std::collections::HashMap<[u32; 3], i32> = m
        .tris
        .iter()
        .zip(&m.tri_ref)
        .map(|(t, &r)| {
            let mut k = *t;
            k.sort_unstable();
            (k, r)
        })
        .collect();
    let mut mesh = Mesh3::from_parts(m.points, m.tets, m.tet_ref);
    mesh.label_boundary(|_, f| {
        let mut k = f;
        k.sort_unstable();
        labels.get(&k).copied().unwrap_or(1)
    });
    mesh.check().map_err(|e| {
        Error::InvalidInput(format!(
            "{}: not a valid tetrahedral mesh: {e}",
            path.display()
        ))
    })?;
    Ok(mesh)
}

/// The sizes of a scalar `.sol` for a 3D or 2D mesh of `n` vertices (`h > 0`, finite, at
/// every vertex; as mmg reads a scalar solution without `-ls`).
pub fn check_sizes(path: &Path, h: &[f64]) -> Result<()> {
    if let Some(v) = h.iter().position(|x| !(x.is_finite() && *x > 0.0)) {
        return Err(bad_field(
            path,
            format!(
                "the size at vertex {} is {} (sizes must be positive and finite)",
                v + 1,
                h[v]
            ),
        ));
    }
    Ok(())
}
