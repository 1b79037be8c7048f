//! `anisomesh redistance --input M.mesh --sol U.sol [--method geometric|ppr|fmm] [--band W]
//! -o D.sol`: a signed distance to the P1 zero level of `U` on a triangle or tetrahedral mesh,
//! sign kept, and how far the zero level moved.

use super::user_files::{read_scalar, read_user_mesh, UserMesh};
use anisomesh::geom::Point;
use anisomesh::io::{self, Sol};
use anisomesh::levelset::enclosed_measure;
use anisomesh::levelset::redistance::{
    redistance_fmm_cells, redistance_geometric_cells, redistance_ppr, redistance_ppr_cells,
    PprOptions, ZeroLevelPieces,
};
use anisomesh::{Error, Result};
use clap::Args;
use std::path::PathBuf;
use std::time::Instant;

/// Options of `anisomesh redistance`.
#[derive(Debug, Args)]
pub struct RedistanceArgs {
    /// The mesh (.mesh 2D or 3D, .msh).
    #[arg(long)]
    pub input: PathBuf,
    /// The level set on the mesh's vertices (.sol, one scalar per vertex).
    #[arg(long)]
    pub sol: PathBuf,
    /// geometric: exact distance to the P1 zero level (004 §2.2); ppr: PPR gradient recovery and
    /// oblique projection (003 §6), fast marching beyond; fmm: first-order fast marching.
    #[arg(long, default_value = "geometric")]
    pub method: String,
    /// Clip the distance to [-W, W] (a narrow band).
    #[arg(long)]
    pub band: Option<f64>,
    /// Output .sol.
    #[arg(short, long)]
    pub output: PathBuf,
}

/// The redistancing method.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Method {
    /// Exact distance to the P1 zero level.
    Geometric,
    /// PPR with oblique projection (P1).
    Ppr,
    /// First-order fast marching.
    Fmm,
}

fn parse_method(s: &str) -> Result<Method> {
    match s {
        "geometric" => Ok(Method::Geometric),
        "ppr" => Ok(Method::Ppr),
        "fmm" => Ok(Method::Fmm),
        _ => Err(Error::InvalidInput(format!(
            "--method '{s}': expected geometric, ppr or fmm"
        ))),
    }
}

/// What a redistancing did to the zero level.
#[derive(Debug, Clone, Copy)]
pub struct Moved {
    /// Enclosed area (2D) or volume (3D) of `{u < 0}` before.
    pub before: f64,
    /// The same of `{d < 0}` after.
    pub after: f64,
    /// `max |d - dist(Γ_h)|` over the vertices of the cells cut by the input's zero level
    /// `Γ_h` (0 for the geometric method): how far the zero level moved, to first order.
    pub band_deviation: f64,
    /// Vertices of the cut cells.
    pub band_vertices: usize,
}

/// Redistances `u` on `cells` with `method`, and measures the move of the zero level.
pub fn redistance<const D: usize, const N: usize, P: ZeroLevelPieces<D, N>>(
    points: &[P],
    cells: &[[u32; N]],
    u: &[f64],
    method: Method,
    mesh2: Option<&anisomesh::Mesh2>,
) -> Result<(Vec<f64>, Moved)> {
    let exact = redistance_geometric_cells(points, cells, u)?;
    let d = match method {
        Method::Geometric => exact.clone(),
        Method::Ppr => match mesh2 {
            Some(m) => redistance_ppr(m, u, &PprOptions::default())?.values,
            None => redistance_ppr_cells(points, cells, u, &PprOptions::default())?.values,
        },
        Method::Fmm => redistance_fmm_cells(points, cells, u)?,
    };
    let mut in_band = vec![false; points.len()];
    for c in cells {
        let s = c.map(|v| u[v as usize]);
        if s.iter().any(|&x| x <= 0.0) && s.iter().any(|&x| x >= 0.0) {
            for &v in c {
                in_band[v as usize] = true;
            }
        }
    }
    let band_deviation = (0..points.len())
        .filter(|&v| in_band[v])
        .map(|v| (d[v] - exact[v]).abs())
        .fold(0.0, f64::max);
    let moved = Moved {
        before: enclosed_measure(points, cells, u)?,
        after: enclosed_measure(points, cells, &d)?,
        band_deviation,
        band_vertices: in_band.iter().filter(|&&b| b).count(),
    };
    Ok((d, moved))
}

fn points_dim<const D: usize, P: Point<D>>(_: &[P]) -> usize {
    D
}

/// Runs `anisomesh redistance`.
pub fn run(a: RedistanceArgs) -> Result<()> {
    let method = parse_method(&a.method)?;
    if let Some(w) = a.band {
        if w.is_nan() || w <= 0.0 {
            return Err(Error::InvalidInput(format!("--band {w}: must be > 0")));
        }
    }
    let mesh = read_user_mesh(&a.input)?;
    let u = read_scalar(&a.sol, &mesh)?;
    let t0 = Instant::now();
    let (mut d, moved, dim) = match &mesh {
        UserMesh::Tri {
            points,
            cells,
            mesh,
        } => {
            let (d, m) = redistance(points, cells, &u, method, Some(mesh))?;
            (d, m, points_dim(points))
        }
        UserMesh::Tet { points, cells } => {
            let (d, m) = redistance(points, cells, &u, method, None)?;
            (d, m, points_dim(points))
        }
    };
    let seconds = t0.elapsed().as_secs_f64();
    if let Some(w) = a.band {
        for x in &mut d {
            *x = x.clamp(-w, w);
        }
    }
    io::write_sol(&a.output, &Sol::scalar_dim(dim, d))?;
    let what = if dim == 2 { "area" } else { "volume" };
    println!(
        "{}: {} ({:?}, {seconds:.3} s)",
        a.input.display(),
        mesh.describe(),
        method
    );
    println!(
        "enclosed {what} {:.12} before, {:.12} after (relative change {:.2e})",
        moved.before,
        moved.after,
        (moved.after - moved.before).abs() / moved.before.abs().max(f64::MIN_POSITIVE)
    );
    println!(
        "max |d - distance to the input's zero level| on the {} vertices of the cut cells: {:.3e}",
        moved.band_vertices, moved.band_deviation
    );
    println!("wrote {}", a.output.display());
    Ok(())
}
