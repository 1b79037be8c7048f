//! `anisomesh shape`: evaluate a level set (a named shape or a user expression) at the vertices
//! of a mesh and write it as a Medit `.sol` (scalar) or a `.vtu` with the field.

use anisomesh::io::{self, FieldRef, Sol};
use anisomesh::levelset::{nodal_distance, shape_by_name, Expr, Shape};
use anisomesh::{Error, Result};
use std::path::Path;

/// The level set chosen on the command line: `--name` or `--expr`, exactly one.
pub fn chosen_shape(name: Option<&str>, expr: Option<&str>) -> Result<Box<dyn Shape>> {
    match (name, expr) {
        (Some(n), None) => shape_by_name(n),
        (None, Some(e)) => Ok(Box::new(Expr::parse(e)?)),
        (None, None) => Err(Error::InvalidInput(
            "give a shape with --name NAME or --expr EXPRESSION".into(),
        )),
        (Some(_), Some(_)) => Err(Error::InvalidInput(
            "--name and --expr are exclusive: give one of them".into(),
        )),
    }
}

/// Evaluates the shape on `mesh_path`'s vertices and writes `output` (.sol or .vtu).
pub fn run(name: Option<&str>, expr: Option<&str>, mesh_path: &Path, output: &Path) -> Result<()> {
    let shape = chosen_shape(name, expr)?;
    let mesh = io::read_mesh(mesh_path)?;
    let u = nodal_distance(&mesh, shape.as_ref());
    if let Some(v) = u.iter().position(|x| !x.is_finite()) {
        return Err(Error::InvalidField {
            name: shape.name(),
            msg: format!(
                "the level set is not finite at vertex {v} ({})",
                mesh.points[v]
            ),
        });
    }
    let ext = output
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    match ext.as_str() {
        "sol" => io::write_sol(output, &Sol::scalar(u.clone()))?,
        "vtu" => io::write_vtu(output, &mesh, &[("levelset", FieldRef::Scalar(&u))], &[])?,
        _ => {
            return Err(Error::Unsupported(format!(
                "{}: write the level set as .sol or .vtu",
                output.display()
            )))
        }
    }
    let (lo, hi) = u
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    println!(
        "{} on {} ({} vertices): values in [{lo:.6}, {hi:.6}] -> {}",
        shape.name(),
        mesh_path.display(),
        mesh.n_points(),
        output.display()
    );
    Ok(())
}
