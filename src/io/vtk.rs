//! VTK XML `.vtu` (UnstructuredGrid, ASCII) output for ParaView: points with `z = 0`, triangles
//! (VTK type 5), point fields (scalars, 2D vectors as 3 components, `Sym2` tensors as 9 or 3
//! components) and cell fields, plus `tri_ref` as an integer cell field.

use super::atomic::atomic_write;
use super::textout::fmt_f64;
use crate::error::{Error, Result};
use crate::geom::DVec2;
use crate::mesh::Mesh2;
use crate::metric::Sym2;
use std::io::Write;
use std::path::Path;

/// A point field to write, indexed by vertex.
#[derive(Debug, Clone, Copy)]
pub enum FieldRef<'a> {
    /// One value per vertex.
    Scalar(&'a [f64]),
    /// A 2D vector per vertex, written with 3 components (`z = 0`).
    Vector(&'a [DVec2]),
    /// A symmetric tensor per vertex, written as a full 3x3 tensor (9 components, `zz = 0`),
    /// which ParaView's tensor filters recognise.
    Tensor(&'a [Sym2]),
    /// A symmetric tensor per vertex written as its 3 components `xx, xy, yy`.
    TensorComponents(&'a [Sym2]),
}

impl FieldRef<'_> {
    fn len(&self) -> usize {
        match self {
            FieldRef::Scalar(v) => v.len(),
            FieldRef::Vector(v) => v.len(),
            FieldRef::Tensor(v) | FieldRef::TensorComponents(v) => v.len(),
        }
    }

    fn components(&self) -> usize {
        match self {
            FieldRef::Scalar(_) => 1,
            FieldRef::Vector(_) => 3,
            FieldRef::Tensor(_) => 9,
            FieldRef::TensorComponents(_) => 3,
        }
    }

    fn values(&self, v: usize) -> Vec<f64> {
        match self {
            FieldRef::Scalar(s) => vec![s[v]],
            FieldRef::Vector(x) => vec![x[v].x, x[v].y, 0.0],
            FieldRef::Tensor(m) => {
                let m = m[v];
                vec![m.xx, m.xy, 0.0, m.xy, m.yy, 0.0, 0.0, 0.0, 0.0]
            }
            FieldRef::TensorComponents(m) => vec![m[v].xx, m[v].xy, m[v].yy],
        }
    }
}

fn check_name(name: &str) -> Result<()> {
    if name.is_empty() || name.contains(['"', '<', '>', '&']) {
        return Err(Error::InvalidField {
            name: name.to_string(),
            msg: "field names must be non-empty and free of '\"', '<', '>', '&'".into(),
        });
    }
    Ok(())
}

/// Writes `mesh` and its fields to a `.vtu` file (atomically). Point fields must have one entry
/// per vertex, cell fields one per triangle slot (tombstones are skipped); non-finite values
/// are rejected with [`Error::InvalidField`].
pub fn write_vtu(
    path: &Path,
    mesh: &Mesh2,
    point_fields: &[(&str, FieldRef)],
    cell_fields: &[(&str, &[f64])],
) -> Result<()> {
    super::check_lengths(mesh)?;
    let live: Vec<usize> = mesh.live_tris().collect();
    check_point_fields(mesh, point_fields)?;
    check_cell_fields(mesh, &live, cell_fields)?;
    if let Some(v) = mesh.points.iter().position(|p| !p.is_finite()) {
        return Err(Error::InvalidField {
            name: "points".into(),
            msg: format!("non-finite coordinate at vertex {v}"),
        });
    }
    atomic_write(path, |w| {
        writeln!(w, "<?xml version=\"1.0\"?>")?;
        writeln!(
            w,
            "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" \
             header_type=\"UInt64\">"
        )?;
        writeln!(w, "<UnstructuredGrid>")?;
        writeln!(
            w,
            "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">",
            mesh.points.len(),
            live.len()
        )?;
        write_points(w, mesh)?;
        write_cells(w, mesh, &live)?;
        write_point_data(w, mesh, point_fields)?;
        write_cell_data(w, mesh, &live, cell_fields)?;
        writeln!(w, "</Piece>\n</UnstructuredGrid>\n</VTKFile>")
    })
}

/// Point fields: valid names, one value per vertex, finite.
fn check_point_fields(mesh: &Mesh2, point_fields: &[(&str, FieldRef)]) -> Result<()> {
    let np = mesh.points.len();
    for (name, f) in point_fields {
        check_name(name)?;
        if f.len() != np {
            return Err(Error::InvalidField {
                name: name.to_string(),
                msg: format!("{} values for {np} vertices", f.len()),
            });
        }
        if let Some(v) = (0..np).find(|&v| f.values(v).iter().any(|x| !x.is_finite())) {
            return Err(Error::InvalidField {
                name: name.to_string(),
                msg: format!("non-finite value at vertex {v}"),
            });
        }
    }
    Ok(())
}

/// Cell fields: valid names, one value per triangle slot, finite on the live triangles.
fn check_cell_fields(mesh: &Mesh2, live: &[usize], cell_fields: &[(&str, &[f64])]) -> Result<()> {
    for (name, f) in cell_fields {
        check_name(name)?;
        if f.len() != mesh.n_tris() {
            return Err(Error::InvalidField {
                name: name.to_string(),
                msg: format!("{} values for {} triangles", f.len(), mesh.n_tris()),
            });
        }
        if let Some(&t) = live.iter().find(|&&t| !f[t].is_finite()) {
            return Err(Error::InvalidField {
                name: name.to_string(),
                msg: format!("non-finite value at triangle {t}"),
            });
        }
    }
    Ok(())
}

/// `<Points>`: the vertices with `z = 0`.
fn write_points(w: &mut dyn Write, mesh: &Mesh2) -> std::io::Result<()> {
    writeln!(w, "<Points>")?;
    writeln!(
        w,
        "<DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">"
    )?;
    for p in &mesh.points {
        writeln!(w, "{} {} 0", fmt_f64(p.x), fmt_f64(p.y))?;
    }
    writeln!(w, "</DataArray>\n</Points>")
}

/// `<Cells>`: connectivity, offsets and types (5, triangle) of the live triangles.
fn write_cells(w: &mut dyn Write, mesh: &Mesh2, live: &[usize]) -> std::io::Result<()> {
    writeln!(w, "<Cells>")?;
    writeln!(
        w,
        "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">"
    )?;
    for &t in live {
        let [a, b, c] = mesh.tris[t];
        writeln!(w, "{a} {b} {c}")?;
    }
    writeln!(w, "</DataArray>")?;
    writeln!(
        w,
        "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">"
    )?;
    for k in 1..=live.len() {
        writeln!(w, "{}", 3 * k)?;
    }
    writeln!(w, "</DataArray>")?;
    writeln!(
        w,
        "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">"
    )?;
    for _ in live {
        writeln!(w, "5")?;
    }
    writeln!(w, "</DataArray>\n</Cells>")
}

/// `<PointData>`: one array per point field.
fn write_point_data(
    w: &mut dyn Write,
    mesh: &Mesh2,
    point_fields: &[(&str, FieldRef)],
) -> std::io::Result<()> {
    writeln!(w, "<PointData>")?;
    for (name, f) in point_fields {
        writeln!(
            w,
            "<DataArray type=\"Float64\" Name=\"{name}\" NumberOfComponents=\"{}\" format=\"ascii\">",
            f.components()
        )?;
        for v in 0..mesh.points.len() {
            let s: Vec<String> = f.values(v).into_iter().map(fmt_f64).collect();
            writeln!(w, "{}", s.join(" "))?;
        }
        writeln!(w, "</DataArray>")?;
    }
    writeln!(w, "</PointData>")
}

/// `<CellData>`: `tri_ref`, then one array per cell field, on the live triangles.
fn write_cell_data(
    w: &mut dyn Write,
    mesh: &Mesh2,
    live: &[usize],
    cell_fields: &[(&str, &[f64])],
) -> std::io::Result<()> {
    writeln!(w, "<CellData>")?;
    writeln!(
        w,
        "<DataArray type=\"Int32\" Name=\"tri_ref\" NumberOfComponents=\"1\" format=\"ascii\">"
    )?;
    for &t in live {
        writeln!(w, "{}", mesh.tri_ref[t])?;
    }
    writeln!(w, "</DataArray>")?;
    for (name, f) in cell_fields {
        writeln!(
            w,
            "<DataArray type=\"Float64\" Name=\"{name}\" NumberOfComponents=\"1\" format=\"ascii\">"
        )?;
        for &t in live {
            writeln!(w, "{}", fmt_f64(f[t]))?;
        }
        writeln!(w, "</DataArray>")?;
    }
    writeln!(w, "</CellData>")
}
