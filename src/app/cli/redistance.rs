//! `anisomesh redistance --input M.mesh (--sol U.sol | --expr E [--order 1|2]) [--method
//! geometric|ppr|fmm] [--band W] -o D.sol`: a signed distance to the zero level of `U` on a
//! triangle or tetrahedral mesh, sign kept, and how far the zero level moved. A vertex `.sol`
//! carries a P1 field; `--expr E --order 2` samples `E` at the P2 nodes (vertices and edge
//! midpoints) for PPR with `k = 2` (003 §6), whose output is written at the vertices.

use super::user_files::{read_scalar, read_user_mesh, UserMesh};
use anisomesh::fem::lagrange::P2Dofs;
use anisomesh::geom::Point;
use anisomesh::io::{self, Sol};
use anisomesh::levelset::enclosed_measure;
use anisomesh::levelset::redistance::{
    redistance_fmm_cells, redistance_geometric_cells, redistance_ppr, redistance_ppr_cells,
    PprOptions, ZeroLevelPieces,
};
use anisomesh::levelset::{Expr, Variables};
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
    #[arg(long, conflicts_with = "expr", required_unless_present = "expr")]
    pub sol: Option<PathBuf>,
    /// The level set as an expression in x, y (and z on a 3D mesh), sampled at the nodes.
    #[arg(long)]
    pub expr: Option<String>,
    /// Polynomial degree of the field sampled from --expr: 1 (vertices) or 2 (vertices and edge
    /// midpoints, for --method ppr: 003's k = 2).
    #[arg(long, default_value_t = 1, requires = "expr")]
    pub order: usize,
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

/// Redistances `u` on `cells` with `method`, and measures the move of the zero level. With
/// `p2` (the field at the P2 nodes, vertices first, numbered as `P2Dofs::for_mesh2` for a
/// `mesh2`, `P2Dofs::for_triangles`/`for_tets` otherwise; `u` its vertex values), PPR runs
/// with `k = 2`; the result is given at the vertices.
pub fn redistance<const D: usize, const N: usize, P: ZeroLevelPieces<D, N>>(
    points: &[P],
    cells: &[[u32; N]],
    u: &[f64],
    method: Method,
    mesh2: Option<&anisomesh::Mesh2>,
    p2: Option<&[f64]>,
) -> Result<(Vec<f64>, Moved)> {
    let exact = redistance_geometric_cells(points, cells, u)?;
    let (phi, degree) = match p2 {
        Some(f) => (f, 2),
        None => (u, 1),
    };
    let opts = PprOptions {
        degree,
        ..PprOptions::default()
    };
    let d = match method {
        Method::Geometric => exact.clone(),
        Method::Ppr => {
            let mut d = match mesh2 {
                Some(m) => redistance_ppr(m, phi, &opts)?.values,
                None => redistance_ppr_cells(points, cells, phi, &opts)?.values,
            };
            d.truncate(points.len());
            d
        }
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

/// A level set at the vertices (P1) or at the P2 nodes (vertices, then edge midpoints).
enum Field {
    P1(Vec<f64>),
    P2(Vec<f64>),
}

/// `e` at the vertices, and for `order` 2 at the edge midpoints too (numbered as the PPR call
/// of [`redistance`] expects); every value finite.
fn sample_expr(e: &str, mesh: &UserMesh, order: usize) -> Result<Field> {
    let f: Vec<f64> = match mesh {
        UserMesh::Tri { points, mesh, .. } => {
            let e = Expr::parse(e)?;
            let mut f: Vec<f64> = points.iter().map(|&p| e.eval(p)).collect();
            if order == 2 {
                let dofs = P2Dofs::for_mesh2(mesh);
                f.extend(
                    dofs.edges
                        .iter()
                        .map(|&[a, b]| e.eval(0.5 * (points[a as usize] + points[b as usize]))),
                );
            }
            f
        }
        UserMesh::Tet { points, cells } => {
            let e = Expr::parse_with(e, Variables::XYZ)?;
            let mut f: Vec<f64> = points.iter().map(|&p| e.eval3(p)).collect();
            if order == 2 {
                let dofs = P2Dofs::for_tets(cells, points.len());
                f.extend(
                    dofs.edges
                        .iter()
                        .map(|&[a, b]| e.eval3(0.5 * (points[a as usize] + points[b as usize]))),
                );
            }
            f
        }
    };
    if let Some(v) = f.iter().position(|x| !x.is_finite()) {
        return Err(Error::InvalidInput(format!(
            "--expr: non-finite value {} at node {}",
            f[v],
            v + 1
        )));
    }
    Ok(if order == 2 {
        Field::P2(f)
    } else {
        Field::P1(f)
    })
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
    if a.order != 1 && a.order != 2 {
        return Err(Error::InvalidInput(format!(
            "--order {}: expected 1 or 2",
            a.order
        )));
    }
    if a.order == 2 && method != Method::Ppr {
        return Err(Error::InvalidInput(
            "--order 2: a P2 field is redistanced by --method ppr only".into(),
        ));
    }
    let field = match (&a.sol, &a.expr) {
        (Some(p), _) => Field::P1(read_scalar(p, &mesh)?),
        (None, Some(e)) => sample_expr(e, &mesh, a.order)?,
        (None, None) => {
            return Err(Error::InvalidInput(
                "redistance: give the level set with --sol or --expr".into(),
            ))
        }
    };
    let (u, p2) = match &field {
        Field::P1(u) => (u.clone(), None),
        Field::P2(f) => (f[..mesh.n_points()].to_vec(), Some(f.as_slice())),
    };
    let t0 = Instant::now();
    let (mut d, moved, dim) = match &mesh {
        UserMesh::Tri {
            points,
            cells,
            mesh,
        } => {
            let (d, m) = redistance(points, cells, &u, method, Some(mesh), p2)?;
            (d, m, points_dim(points))
        }
        UserMesh::Tet { points, cells } => {
            let (d, m) = redistance(points, cells, &u, method, None, p2)?;
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
        "{}: {} ({:?}, P{} field, {seconds:.3} s)",
        a.input.display(),
        mesh.describe(),
        method,
        a.order
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
