//! Wavefront OBJ surfaces through `tobj`: all objects of the file merged into one triangle
//! surface (polygons are fan-triangulated by `tobj`).

use crate::error::{Error, Result};
use crate::geom::DVec3;
use std::path::Path;

/// A triangulated surface in 3D (0-based indices).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SurfaceMesh {
    /// Vertex coordinates.
    pub points: Vec<DVec3>,
    /// Vertices of each triangle.
    pub tris: Vec<[u32; 3]>,
}

/// Parses OBJ text (`path` is used in messages). Materials are ignored.
pub fn parse_obj(path: &Path, bytes: &[u8]) -> Result<SurfaceMesh> {
    let opts = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let mut reader = std::io::BufReader::new(bytes);
    let (models, _) = tobj::load_obj_buf(&mut reader, &opts, |_| {
        Err(tobj::LoadError::MaterialParseError)
    })
    .map_err(|e| Error::parse(path, 0, format!("invalid OBJ file: {e}")))?;
    let mut out = SurfaceMesh::default();
    for m in &models {
        let mesh = &m.mesh;
        let base = out.points.len();
        if mesh.positions.len() % 3 != 0 || mesh.indices.len() % 3 != 0 {
            return Err(Error::parse(
                path,
                0,
                format!("object '{}': malformed data", m.name),
            ));
        }
        let n = mesh.positions.len() / 3;
        for c in mesh.positions.chunks_exact(3) {
            let p = DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64);
            if !p.is_finite() {
                return Err(Error::parse(
                    path,
                    0,
                    format!("object '{}': non-finite vertex coordinate", m.name),
                ));
            }
            out.points.push(p);
        }
        for t in mesh.indices.chunks_exact(3) {
            if t.iter().any(|&v| v as usize >= n) {
                return Err(Error::parse(
                    path,
                    0,
                    format!("object '{}': face refers to a missing vertex", m.name),
                ));
            }
            let tri = [t[0], t[1], t[2]].map(|v| (v as usize + base) as u32);
            out.tris.push(tri);
        }
    }
    if out.tris.is_empty() {
        return Err(Error::parse(
            path,
            0,
            "the OBJ file has no faces (no triangles)",
        ));
    }
    Ok(out)
}

/// Reads an OBJ file into a [`SurfaceMesh`]. Errors name the file: missing or unreadable file,
/// malformed content, no triangles.
pub fn read_obj(path: &Path) -> Result<SurfaceMesh> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    parse_obj(path, &bytes)
}
