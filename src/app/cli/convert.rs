//! `anisomesh convert IN OUT`: mesh format conversion, formats chosen by extension.

use anisomesh::{io, Result};
use std::path::Path;

/// Reads `input` (.mesh, .msh) and writes `output` (.mesh, .msh, .vtu), validating on the way.
pub fn run(input: &Path, output: &Path) -> Result<()> {
    let mesh = io::read_mesh(input)?;
    mesh.check()?;
    io::write_mesh(output, &mesh)?;
    println!(
        "{} -> {}: {} vertices, {} triangles",
        input.display(),
        output.display(),
        mesh.n_points(),
        mesh.n_live_tris()
    );
    Ok(())
}
