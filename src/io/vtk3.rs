//! `.vtu` output of tetrahedral meshes (ParaView's unstructured grid, ASCII), with point and
//! cell fields.

use std::path::Path;

use super::atomic_write;
use crate::error::{Error, Result};
use crate::mesh3::Mesh3;

/// Writes the tetrahedra of `mesh` (VTK cell type 10) with `point_fields` (one value per
/// vertex) and `cell_fields` (one per tetrahedron) to `path`, atomically. Wrong lengths,
/// non-finite values and unsafe names are [`Error::InvalidField`].
pub fn write_vtu3(
    path: &Path,
    mesh: &Mesh3,
    point_fields: &[(&str, &[f64])],
    cell_fields: &[(&str, &[f64])],
) -> Result<()> {
    for (fields, n, what) in [
        (point_fields, mesh.n_points(), "vertex"),
        (cell_fields, mesh.n_tets(), "tetrahedron"),
    ] {
        for (name, v) in fields {
            let bad = |msg: String| Error::InvalidField {
                name: name.to_string(),
                msg,
            };
            if name.is_empty() || name.contains(['"', '<', '>', '&']) {
                return Err(bad(
                    "field names must be non-empty and free of '\"<>&'".into()
                ));
            }
            if v.len() != n {
                return Err(bad(format!("{} values for {n} ({what})", v.len())));
            }
            if let Some(i) = v.iter().position(|x| !x.is_finite()) {
                return Err(bad(format!("non-finite value at {what} {i}")));
            }
        }
    }
    atomic_write(path, |w| {
        writeln!(w, "<?xml version=\"1.0\"?>")?;
        writeln!(
            w,
            "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">"
        )?;
        writeln!(w, "<UnstructuredGrid>")?;
        writeln!(
            w,
            "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">",
            mesh.n_points(),
            mesh.n_tets()
        )?;
        writeln!(
            w,
            "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">"
        )?;
        for p in &mesh.points {
            writeln!(w, "{:e} {:e} {:e}", p.x, p.y, p.z)?;
        }
        writeln!(w, "</DataArray></Points>")?;
        writeln!(
            w,
            "<Cells><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">"
        )?;
        for t in &mesh.tets {
            writeln!(w, "{} {} {} {}", t[0], t[1], t[2], t[3])?;
        }
        writeln!(
            w,
            "</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">"
        )?;
        for i in 1..=mesh.n_tets() {
            writeln!(w, "{}", 4 * i)?;
        }
        writeln!(
            w,
            "</DataArray><DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">"
        )?;
        for _ in 0..mesh.n_tets() {
            writeln!(w, "10")?;
        }
        writeln!(w, "</DataArray></Cells>")?;
        for (tag, fields) in [("PointData", point_fields), ("CellData", cell_fields)] {
            writeln!(w, "<{tag}>")?;
            for (name, v) in fields {
                writeln!(
                    w,
                    "<DataArray type=\"Float64\" Name=\"{name}\" format=\"ascii\">"
                )?;
                for x in v.iter() {
                    writeln!(w, "{x:e}")?;
                }
                writeln!(w, "</DataArray>")?;
            }
            writeln!(w, "</{tag}>")?;
        }
        writeln!(w, "</Piece></UnstructuredGrid></VTKFile>")
    })
}
