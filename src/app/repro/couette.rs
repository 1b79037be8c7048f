//! The two-phase Couette Stokes benchmark (004 §5.1, "A viscous flow example"): the unit square
//! with a disk of radius 0.1 at the centre, viscosity 1 inside and 1e-6 outside, the shear
//! `u = (2(y - 0.5), 0)` on the boundary. The disk should turn as a rigid body with `ω = -1`
//! ([`anisomesh::flows::couette`] explains why exactly -1); reported are the fitted `ω`, the
//! rigidity (relative deviation from the rigid motion inside the disk) and the cost.
//!
//! Default: the paper's setting — a mesh adapted anisotropically to the disk's level set with
//! the eq. (6) metric ([`adapt_to_shape`], the interface is *not* meshed), the viscosity from
//! the P1 level set, Uzawa. `fitted: true` gives the reference: a constrained Delaunay mesh
//! conforming to a polygon of the circle, viscosity per triangle from its sub-domain.
//! The paper (FreeFem++, adapted) reports ω = -0.99865 at 1,518 vertices and -1.00047 at 3,909.

use crate::app::plot::{mesh_png, Corner, Inset, MeshPlot, RGBColor};
use anisomesh::adapt::{adapt_to_shape, LevelSetMetric, ShapeAdaptOptions};
use anisomesh::error::{Error, Result};
use anisomesh::flows::{
    streamline, CouetteCase, InterfaceViscosity, StokesSolver, StreamlineOptions, Viscosity,
};
use anisomesh::geom::DVec2;
use anisomesh::levelset::Circle;
use anisomesh::mesh::{circle_points, Mesh2, PolygonDomain};
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;

/// The paper's adapted-mesh results (vertices, ω), 004 §5.1.
pub const PAPER: [(usize, f64); 2] = [(1518, -0.99865), (3909, -1.00047)];

/// Sub-domain label of the disk in the body-fitted mesh.
const DISK_REF: i32 = 2;

/// Options of [`run`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CouetteOptions {
    /// Where `couette.json`, `couette.vtu` and the figures go; `None` writes nothing.
    pub out_dir: Option<PathBuf>,
    /// Body-fitted reference mesh instead of the adapted one.
    pub fitted: bool,
    /// Adapted mesh: the metric of eq. (6) (ε, size bounds, band half-width, growth rate
    /// away from the band; the fitted mesh uses `hmax` only).
    /// The default growth 0.3
    /// (sizes `≈ 0.3 d` at distance `d` from the disk) resolves the flow around
    /// the disk; with `grade = 1` the sizes near the disk are as large as the distance and `ω`
    /// moved by up to 1.4e-3 when `hmax` or `eps` changed by 25% (measured, 2,200–3,200
    /// vertices), against at most 3.0e-4 with the defaults (3,060–4,160 vertices).
    pub metric: LevelSetMetric,
    /// Adapted mesh: viscosity of the triangles cut by the interface.
    pub interface: InterfaceViscosity,
    /// Adapted mesh, [`InterfaceViscosity::Quadrature`]: half-width of the smoothed Heaviside
    /// of the viscosity (0 = sharp).
    pub width: f64,
    /// Fitted mesh: edge length on the circle (the rest is graded by Delaunay refinement with a
    /// 25° angle bound and a maximal area `hmax² / 2`).
    pub h_interface: f64,
    /// Relative tolerance of the Uzawa (Schur-complement CG) iteration.
    pub rtol: f64,
    /// Write the PNG figures (mesh with insets, streamlines) when `out_dir` is set.
    pub figures: bool,
}

impl Default for CouetteOptions {
    fn default() -> Self {
        CouetteOptions {
            out_dir: None,
            fitted: false,
            metric: LevelSetMetric {
                eps: 1e-4,
                hmin: 1e-3,
                hmax: 0.06,
                band: 1e-3,
                grade: 0.3,
                ..LevelSetMetric::default()
            },
            interface: InterfaceViscosity::Harmonic,
            width: 0.0,
            h_interface: 5e-3,
            rtol: 1e-10,
            figures: true,
        }
    }
}

/// Result of [`run`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CouetteReport {
    /// "adapted" or "fitted".
    pub mesh: String,
    /// Fitted angular velocity of the disk (exact: -1).
    pub omega: f64,
    /// `|ω + 1|`.
    pub omega_error: f64,
    /// `max |u - rigid| / max |u|` over the vertices inside the disk.
    pub rigidity: f64,
    pub vertices: usize,
    pub triangles: usize,
    /// Vertices inside the disk used by the fit.
    pub fit_vertices: usize,
    pub uzawa_iterations: usize,
    pub residual: f64,
    pub converged: bool,
    /// Meshing (adaptation or CDT), solve, and total wall-clock seconds (figures excluded).
    pub mesh_seconds: f64,
    pub solve_seconds: f64,
    /// Parts of `solve_seconds`: block assembly, Cholesky factorisations, Uzawa iteration.
    pub assembly_seconds: f64,
    pub factor_seconds: f64,
    pub uzawa_seconds: f64,
    /// Entries of the Cholesky factor of the velocity block.
    pub factor_nnz: usize,
    pub seconds: f64,
    pub options: CouetteOptions,
}

/// The mesh of the run: adapted to the disk's level set, or body-fitted. Returns the mesh and
/// the viscosity field to use.
pub fn build_mesh(opts: &CouetteOptions) -> Result<(Mesh2, Viscosity)> {
    let case = CouetteCase::default();
    if opts.fitted {
        let h = opts.h_interface;
        if !(h > 0.0 && opts.metric.hmax > 0.0) {
            return Err(Error::InvalidInput(format!(
                "couette: h_interface {h} and hmax {} must be positive",
                opts.metric.hmax
            )));
        }
        let n = ((std::f64::consts::TAU * case.radius / h).ceil() as usize).max(8);
        let square = vec![
            DVec2::ZERO,
            DVec2::new(1.0, 0.0),
            DVec2::ONE,
            DVec2::new(0.0, 1.0),
        ];
        let mesh = PolygonDomain::new(square, 1)
            .with_size(opts.metric.hmax)
            .interface(circle_points(case.centre, case.radius, n), 5, DISK_REF)
            .with_size(h)
            .with_max_area(0.5 * opts.metric.hmax * opts.metric.hmax)
            .with_min_angle(25.0)
            .mesh()?;
        let mu: Vec<f64> = mesh
            .tri_ref
            .iter()
            .map(|&r| {
                if r == DISK_REF {
                    case.mu_in
                } else {
                    case.mu_out
                }
            })
            .collect();
        return Ok((mesh, Viscosity::PerElement(mu)));
    }
    let shape = Circle {
        centre: case.centre,
        radius: case.radius,
    };
    let metric = opts.metric;
    let sopts = ShapeAdaptOptions {
        metric,
        ..ShapeAdaptOptions::default()
    };
    let (mesh, phi, _) = adapt_to_shape(&shape, (DVec2::ZERO, DVec2::ONE), &sopts)?;
    let case = CouetteCase {
        interface: opts.interface,
        width: opts.width,
        ..case
    };
    Ok((mesh, case.viscosity(phi)))
}

/// Runs the benchmark (see the module documentation) and writes its outputs to `out_dir`:
/// `couette.json` (the report), `couette.vtu` (velocity, pressure, level set),
/// `couette_mesh.png` (the mesh with zooms on the disk and its interface) and
/// `couette_streamlines.png` (streamlines over the mesh, as 004 Fig. 4).
pub fn run(opts: &CouetteOptions) -> Result<CouetteReport> {
    let t0 = Instant::now();
    let (mesh, viscosity) = build_mesh(opts)?;
    let mesh_seconds = t0.elapsed().as_secs_f64();
    let case = CouetteCase::default();
    let solver = StokesSolver::Uzawa {
        rtol: opts.rtol,
        max_iter: 2000,
    };
    let res = case.solve_with(&mesh, viscosity, solver)?;
    let seconds = t0.elapsed().as_secs_f64();
    let report = CouetteReport {
        mesh: if opts.fitted { "fitted" } else { "adapted" }.into(),
        omega: res.fit.omega,
        omega_error: (res.fit.omega + 1.0).abs(),
        rigidity: res.fit.max_deviation_rel,
        vertices: mesh.n_points(),
        triangles: mesh.n_live_tris(),
        fit_vertices: res.fit.vertices,
        uzawa_iterations: res.report.uzawa_iterations,
        residual: res.report.residual,
        converged: res.report.converged,
        mesh_seconds,
        solve_seconds: seconds - mesh_seconds,
        assembly_seconds: res.report.assembly_seconds,
        factor_seconds: res.report.factor_seconds,
        uzawa_seconds: res.report.uzawa_seconds,
        factor_nnz: res.report.factor_nnz,
        seconds,
        options: opts.clone(),
    };
    if let Some(dir) = &opts.out_dir {
        write_outputs(dir, opts, &case, &mesh, &res.solution, &report)?;
    }
    Ok(report)
}

fn write_outputs(
    dir: &std::path::Path,
    opts: &CouetteOptions,
    case: &CouetteCase,
    mesh: &Mesh2,
    sol: &anisomesh::flows::StokesSolution,
    report: &CouetteReport,
) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    anisomesh::io::atomic_write(&dir.join("couette.json"), |w| {
        serde_json::to_writer_pretty(&mut *w, report).map_err(std::io::Error::from)?;
        writeln!(w)
    })?;
    let phi = case.level_set(mesh);
    anisomesh::io::write_vtu(
        &dir.join("couette.vtu"),
        mesh,
        &[
            ("velocity", anisomesh::io::FieldRef::Vector(&sol.velocity)),
            ("pressure", anisomesh::io::FieldRef::Scalar(&sol.pressure)),
            ("phi", anisomesh::io::FieldRef::Scalar(&phi)),
        ],
        &[],
    )?;
    if !opts.figures {
        return Ok(());
    }
    let circle = {
        let mut c = circle_points(case.centre, case.radius, 400);
        c.push(c[0]);
        c
    };
    let red = RGBColor(214, 39, 40);
    let kind = &report.mesh;
    let disk = (DVec2::splat(0.37), DVec2::splat(0.63));
    let edge = (DVec2::new(0.592, 0.488), DVec2::new(0.608, 0.512));
    mesh_png(
        &dir.join("couette_mesh.png"),
        mesh,
        &MeshPlot {
            insets: vec![
                Inset {
                    view: disk,
                    placement: Corner::TopRight,
                },
                Inset {
                    view: edge,
                    placement: Corner::BottomRight,
                },
            ],
            title: format!(
                "Couette, {kind} mesh: {} vertices, omega = {:.6}",
                report.vertices, report.omega
            ),
            ..MeshPlot::default()
        },
    )?;
    let sopts = StreamlineOptions::default();
    let mut lines: Vec<(Vec<DVec2>, RGBColor, u32)> = Vec::new();
    let blue = RGBColor(31, 119, 180);
    for k in 0..40 {
        let y = (k as f64 + 0.5) / 40.0;
        let line = streamline(mesh, &sol.velocity, DVec2::new(0.5, y), &sopts);
        if line.len() > 1 {
            lines.push((line, blue, 1));
        }
    }
    lines.push((circle, red, 2));
    mesh_png(
        &dir.join("couette_streamlines.png"),
        mesh,
        &MeshPlot {
            polylines: lines,
            title: format!("Couette streamlines, {kind} mesh (004 Fig. 4)"),
            ..MeshPlot::default()
        },
    )?;
    Ok(())
}
