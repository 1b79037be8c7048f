//! PPR redistancing (003 §6.3): initialisation phase by oblique projection along the recovered
//! quasi-normal field on the cells cut by the zero level, then an extension phase by fast
//! marching to every node.
//!
//! Steps (003 §8, list after Table 8.4's description):
//! 1. the cut cells `T_{Γ_h}` are found from the nodal signs (a cell is cut when its nodal values
//!    take both signs or one is 0);
//! 2. the PPR recovered gradient `G_h φ_h` (`ppr.rs`) and `n_h = G_h φ_h / |G_h φ_h|` (6.6);
//! 3. for every node `v ∈ N(T_{Γ_h})`, `d_h(v)` by (6.10)–(6.11) (`oblique.rs`); with
//!    [`PprOptions::layers`] = 2 also for the nodes of the cells around the vertices of cut cells;
//! 4. nodal interpolation `I_h d_h` (6.7) — the values at those nodes;
//! 5. (extension) fast marching (`fmm.rs`) from the projected nodes to all others, on the P1
//!    sub-mesh of the nodes for P2; the sign of `φ_h` is kept outside the band.

use rayon::prelude::*;

use super::fmm::fast_marching;
use super::oblique::{project, ObliqueParams};
use super::ppr::Recovery;
use super::simplices::Simplices;
use crate::error::{Error, Result};
use crate::geom::{DVec3, Point};
use crate::mesh::Mesh2;

/// Options of [`redistance_ppr`] / [`redistance_ppr_cells`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PprOptions {
    /// Polynomial degree `k` of the field (1 = P1, 2 = P2).
    pub degree: usize,
    /// Relative tolerance (times the local mesh size) of the line search and of (6.11).
    pub tol: f64,
    /// Maximum number of oblique iterations (6.11) per node.
    pub max_outer: usize,
    /// Maximum number of Newton steps (6.10) per line search.
    pub max_newton: usize,
    /// Limit each Newton step to the local mesh size (the damped variant of 003 §6.3).
    pub damped: bool,
    /// Run the extension phase (fast marching); otherwise nodes off the band keep `φ_h`.
    pub extend: bool,
    /// Layers of cells whose nodes get the oblique projection: 1 = the nodes of the cut cells
    /// `N(T_{Γ_h})` only (003 §6.3, the tables); 2 also projects the nodes of every cell sharing a
    /// vertex with a cut cell, so that the PPR patches of the next redistancing see projected
    /// values rather than fast-marching ones (repeated redistancing, 003 Fig. 8.4).
    pub layers: usize,
}

impl Default for PprOptions {
    fn default() -> Self {
        PprOptions {
            degree: 1,
            tol: 1e-12,
            max_outer: 100,
            max_newton: 50,
            damped: true,
            extend: true,
            layers: 2,
        }
    }
}

/// Statistics of one redistancing.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PprReport {
    /// Cells of the mesh.
    pub cells: usize,
    /// Nodes of the field (vertices, plus edge nodes for P2).
    pub nodes: usize,
    /// Cells cut by the zero level, `T_{Γ_h}`.
    pub cut_cells: usize,
    /// Nodes of the cut cells, `N(T_{Γ_h})` (the initialisation band).
    pub band_nodes: usize,
    /// Largest number of oblique iterations (6.11) used by one node.
    pub max_outer_iterations: usize,
    /// Projected nodes (band, and second layer if any) where (6.10)–(6.11) did not reach the tolerance (they keep the last iterate, or
    /// `φ_h / |G_h φ_h|` when the projection failed outright).
    pub not_converged: usize,
    /// Line searches that needed the bracketing fallback.
    pub bracketed: usize,
    /// Vertex fits that needed the PPR fallback (second ring or lower degree).
    pub ppr_fallbacks: usize,
    /// `e^∇_∞ = max_{T ∈ T_{Γ_h}} | (|T|^{-1} ∫_T |∇ I_h d_h|²)^{1/2} - 1 |` (003 §8).
    pub e_grad: f64,
}

/// Result of a redistancing: values per node (vertices, then edge dofs for P2, numbered as
/// [`crate::fem::lagrange::P2Dofs`]), the band flags, and the report.
#[derive(Debug, Clone)]
pub struct PprOutput {
    /// The redistanced values, one per node.
    pub values: Vec<f64>,
    /// `band[n]` = node `n` belongs to a cut cell (its value comes from the oblique projection).
    pub band: Vec<bool>,
    /// Statistics of the run.
    pub report: PprReport,
}

/// Checks the options.
fn validate_options(opts: &PprOptions) -> Result<()> {
    if opts.degree != 1 && opts.degree != 2 {
        return Err(Error::InvalidInput(format!(
            "PPR redistancing: degree must be 1 or 2 (got {})",
            opts.degree
        )));
    }
    if opts.tol.is_nan()
        || opts.tol <= 0.0
        || opts.max_outer == 0
        || opts.max_newton == 0
        || !(1..=2).contains(&opts.layers)
    {
        return Err(Error::InvalidInput(format!(
            "PPR redistancing: tol, max_outer and max_newton must be positive and layers 1 or 2 \
             (got tol {}, max_outer {}, max_newton {}, layers {})",
            opts.tol, opts.max_outer, opts.max_newton, opts.layers
        )));
    }
    Ok(())
}

/// The view of the simplices `cells` over `points` for a field of degree `opts.degree`, after
/// checking the options and that `phi` holds one finite value per node.
fn view<const D: usize, const N: usize, P: Point<D>>(
    points: &[P],
    cells: impl Iterator<Item = [u32; N]>,
    phi: &[f64],
    opts: &PprOptions,
) -> Result<Simplices> {
    validate_options(opts)?;
    let pts = points.iter().map(|p| p.to_xyz()).collect();
    let sx = Simplices::new(D, pts, cells.flatten().collect(), opts.degree)?;
    crate::mesh::check_p1_field(sx.n_nodes(), phi, "phi")?;
    Ok(sx)
}

/// PPR redistancing of a P1 or P2 field on a triangle mesh (003 §6): [`redistance_ppr_cells`]
/// on the live triangles of `mesh`, except that the P1 recovered gradient is the recovery
/// module's ([`crate::recovery::gradient_ppr`], the same fit of 003 §6.2 on the mesh's vertex
/// patches). For `degree = 2`, `phi` is indexed by [`P2Dofs::for_mesh2`](crate::fem::lagrange::P2Dofs::for_mesh2). Errors:
/// [`Error::InvalidField`] (length, NaN), [`Error::EmptyLevelSet`] (no cut cell),
/// [`Error::InvalidInput`] (options).
pub fn redistance_ppr(mesh: &Mesh2, phi: &[f64], opts: &PprOptions) -> Result<PprOutput> {
    let sx = view(
        &mesh.points,
        mesh.live_tris().map(|t| mesh.tris[t]),
        phi,
        opts,
    )?;
    if opts.degree == 1 {
        let g: Vec<DVec3> = crate::recovery::gradient_ppr(mesh, phi)?
            .iter()
            .map(|g| g.extend(0.0))
            .collect();
        return run(&sx, phi, opts, Recovery::with_node_grads(&sx, phi, &g));
    }
    run(&sx, phi, opts, Recovery::new(&sx, phi))
}

/// PPR redistancing (003 §6) of a P1 or P2 field on the simplices `cells` over `points`
/// (triangles over `DVec2`, tetrahedra over `DVec3`); `phi` is indexed by vertex, then for P2 by
/// the edge dofs of [`P2Dofs::for_triangles`](crate::fem::lagrange::P2Dofs::for_triangles) / [`P2Dofs::for_tets`](crate::fem::lagrange::P2Dofs::for_tets). The recovered gradient is
/// the PPR fit of 003 §6.2 on the cell patches of each vertex. Errors as [`redistance_ppr`].
pub fn redistance_ppr_cells<const D: usize, const N: usize, P: Point<D>>(
    points: &[P],
    cells: &[[u32; N]],
    phi: &[f64],
    opts: &PprOptions,
) -> Result<PprOutput> {
    let sx = view(points, cells.iter().copied(), phi, opts)?;
    run(&sx, phi, opts, Recovery::new(&sx, phi))
}

/// Whether a cell with these nodal values is cut by the zero level.
fn is_cut(vals: impl Iterator<Item = f64>) -> bool {
    let (mut neg, mut pos, mut zero) = (false, false, false);
    for v in vals {
        neg |= v < 0.0;
        pos |= v > 0.0;
        zero |= v == 0.0;
    }
    (neg && pos) || zero
}

fn run(sx: &Simplices, phi: &[f64], opts: &PprOptions, rec: Recovery) -> Result<PprOutput> {
    let nn = sx.n_nodes();
    let cut: Vec<u32> = (0..sx.n_cells() as u32)
        .filter(|&c| is_cut(sx.nodes(c as usize).iter().map(|&n| phi[n as usize])))
        .collect();
    if cut.is_empty() {
        return Err(Error::EmptyLevelSet(format!(
            "the field has no zero crossing on the {} cells of the mesh",
            sx.n_cells()
        )));
    }
    // Band nodes with the smallest cut cell around each (its size scales the tolerances).
    let mut h = vec![f64::INFINITY; nn];
    let mut home = vec![u32::MAX; nn];
    for &c in &cut {
        let d = sx.diameter(c as usize);
        for &n in sx.nodes(c as usize) {
            if d < h[n as usize] {
                h[n as usize] = d;
                home[n as usize] = c;
            }
        }
    }
    let mut band = vec![false; nn];
    for n in 0..nn {
        band[n] = home[n] != u32::MAX;
    }
    if opts.layers == 2 {
        // Second layer: nodes of cells sharing a vertex with a cut cell; such a node is within
        // two cell diameters of Γ_h.
        let mut seen = vec![false; sx.n_cells()];
        for &c in &cut {
            for &v in &sx.nodes(c as usize)[..sx.nv] {
                for &c2 in sx.cells_of(v) {
                    if std::mem::replace(&mut seen[c2 as usize], true) {
                        continue;
                    }
                    let d = 2.0 * sx.diameter(c2 as usize);
                    for &n in sx.nodes(c2 as usize) {
                        let i = n as usize;
                        if !band[i] && d < h[i] {
                            h[i] = d;
                            home[i] = c2;
                        }
                    }
                }
            }
        }
    }
    let band_nodes: Vec<u32> = (0..nn as u32)
        .filter(|&n| home[n as usize] != u32::MAX)
        .collect();
    let params = ObliqueParams {
        tol: opts.tol,
        max_outer: opts.max_outer,
        max_newton: opts.max_newton,
        damped: opts.damped,
    };
    let proj: Vec<_> = band_nodes
        .par_iter()
        .map(|&n| {
            let i = n as usize;
            project(
                sx,
                phi,
                &rec,
                &sx.node_points[i],
                phi[i],
                home[i],
                h[i],
                &params,
            )
        })
        .collect();
    let mut report = PprReport {
        cells: sx.n_cells(),
        nodes: nn,
        cut_cells: cut.len(),
        band_nodes: band.iter().filter(|&&b| b).count(),
        ..PprReport::default()
    };
    let mut values = phi.to_vec();
    let mut projected = vec![false; nn];
    for (&n, p) in band_nodes.iter().zip(&proj) {
        values[n as usize] = p.d;
        projected[n as usize] = true;
        report.max_outer_iterations = report.max_outer_iterations.max(p.outer_iterations);
        report.not_converged += usize::from(!p.converged);
        report.bracketed += usize::from(p.bracketed);
    }
    report.ppr_fallbacks = rec.fallbacks.load(std::sync::atomic::Ordering::Relaxed);
    report.e_grad = cut
        .iter()
        .map(|&c| (mean_grad_norm(sx, c as usize, &values) - 1.0).abs())
        .fold(0.0, f64::max);
    if opts.extend {
        let known: Vec<Option<f64>> = (0..nn)
            .map(|n| projected[n].then(|| values[n].abs()))
            .collect();
        let dist = fast_marching(&sx.node_points, &sx.node_cells(), sx.nv, &known);
        for n in 0..nn {
            if !projected[n] && dist[n].is_finite() {
                values[n] = dist[n].copysign(phi[n]);
            }
        }
    }
    Ok(PprOutput {
        values,
        band,
        report,
    })
}

/// `(|T|^{-1} ∫_T |∇f|²)^{1/2}` on cell `c`, exact for P1 and P2 (degree-2 quadrature).
pub(crate) fn mean_grad_norm(sx: &Simplices, c: usize, f: &[f64]) -> f64 {
    if sx.degree == 1 {
        return sx.grad_in(c, &[0.25; 4], f).length();
    }
    let pts: Vec<[f64; 4]> = if sx.dim == 2 {
        vec![
            [0.5, 0.5, 0.0, 0.0],
            [0.0, 0.5, 0.5, 0.0],
            [0.5, 0.0, 0.5, 0.0],
        ]
    } else {
        let (a, b) = (0.585_410_196_624_968_5, 0.138_196_601_125_010_5);
        vec![[a, b, b, b], [b, a, b, b], [b, b, a, b], [b, b, b, a]]
    };
    let w = 1.0 / pts.len() as f64;
    pts.iter()
        .map(|l| {
            let g = sx.grad_in(c, l, f);
            w * g.length_squared()
        })
        .sum::<f64>()
        .sqrt()
}
