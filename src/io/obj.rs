//! Wavefront OBJ surfaces through `tobj`: all objects of the file merged into one triangle
//! surface (polygons are fan-triangulated by `tobj`); [`write_obj`] writes one.

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

/// Writes `points` and `triangles` (0-based) as an OBJ file (`v x y z` lines with `decimals`
/// digits after the point, then `f a b c` lines, 1-based), atomically
/// ([`crate::io::atomic_write`]). `decimals` is capped at 17. Errors: a triangle referring to
/// a missing vertex, a non-finite coordinate, an I/O failure.
pub fn write_obj(
    path: &Path,
    points: &[DVec3],
    triangles: &[[u32; 3]],
    decimals: usize,
) -> Result<()> {
    if let Some(i) = points.iter().position(|p| !p.is_finite()) {
        return Err(Error::InvalidInput(format!(
            "{}: vertex {i} has a non-finite coordinate",
            path.display()
        )));
    }
    if let Some(t) = triangles
        .iter()
        .position(|t| t.iter().any(|&v| v as usize >= points.len()))
    {
        return Err(Error::InvalidInput(format!(
            "{}: triangle {t} refers to a missing vertex",
            path.display()
        )));
    }
    let dec = decimals.min(17);
    super::atomic_write(path, |w| {
        writeln!(
            w,
            "# {} vertices, {} triangles (anisomesh)",
            points.len(),
            triangles.len()
        )?;
        for p in points {
            writeln!(w, "v {:.dec$} {:.dec$} {:.dec$}", p.x, p.y, p.z)?;
        }
        for t in triangles {
            writeln!(w, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1)?;
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tetrahedron written and read back: same triangles, coordinates within the written
    /// precision (and `tobj`'s single precision).
    #[test]
    fn obj_round_trip() {
        let points = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(0.1234567, 0.25, 1.0 / 3.0),
        ];
        let tris = vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]];
        let dir = std::env::temp_dir().join(format!("anisomesh-obj-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("tet.obj");
        write_obj(&path, &points, &tris, 8).unwrap();
        let back = read_obj(&path).unwrap();
        // `tobj` renumbers vertices in order of first use: compare the triangles' corners.
        assert_eq!(back.tris.len(), tris.len());
        for (s, t) in back.tris.iter().zip(&tris) {
            for k in 0..3 {
                let (a, b) = (back.points[s[k] as usize], points[t[k] as usize]);
                assert!((a - b).length() < 1e-7, "{a} vs {b}");
            }
        }
        let bad = write_obj(&path, &points, &[[0, 1, 9]], 8);
        assert!(matches!(bad, Err(Error::InvalidInput(_))));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
