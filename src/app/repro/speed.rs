//! The adaptation speed case: a `100 x 100`-vertex grid of `[-2, 2]²` carrying the geometric
//! metric of 004 eq. (6) of the Zalesak disk with `eps = hmin` (the files that `anisomesh adapt
//! --input BG.mesh --sol M.sol` reads, and that mmg2d is given in the peer comparison), adapted
//! with the metric interpolated at new vertices with sizes varying linearly, as mmg2d does.

use super::peers::{background, evaluate_target};
use anisomesh::adapt::{
    adapt, metric_file_options, AdaptReport, LevelSetMetric, MetricInterpolation,
};
use anisomesh::error::{Error, Result};
use anisomesh::io::{self, Sol};
use anisomesh::mesh::Mesh2;
use anisomesh::metric::{quality_stats, QualityStats, Sym2};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// One adaptation of the speed case.
pub struct SpeedRow {
    /// The metric's eps (= hmin).
    pub eps: f64,
    /// Output vertices and triangles.
    pub vertices: usize,
    pub triangles: usize,
    /// Wall time of the adaptation.
    pub seconds: f64,
    /// Edge lengths and `Q_ani` in the metric.
    pub quality: QualityStats,
    /// The driver's report (cycles, passes, times).
    pub report: AdaptReport,
    /// A hash of the vertex coordinates and triangles: equal runs give equal fingerprints.
    pub fingerprint: u64,
}

/// Options of [`run`].
#[derive(Debug, Clone, Default)]
pub struct SpeedOptions {
    /// Log-Euclidean metric interpolation instead of linear sizes (many more vertices).
    pub log_interp: bool,
    /// Grade the metric during the adaptation (as mmg2d's `-hgrad`).
    pub hgrad: Option<f64>,
}

/// Adapts the speed case once per `eps`, calling `each` with every row as it is measured.
pub fn run(
    eps: &[f64],
    opts: &SpeedOptions,
    mut each: impl FnMut(&SpeedRow),
) -> Result<Vec<SpeedRow>> {
    let dir = std::env::temp_dir().join(format!("anisomesh_speed_{}", std::process::id()));
    let mut rows = Vec::new();
    for &e in eps {
        let (bg, sol) = write_speed_case(&dir, 100, e)?;
        let (mut mesh, mut metric) = read_mesh_and_metric(&bg, &sol)?;
        let t0 = Instant::now();
        let interp = if opts.log_interp {
            MetricInterpolation::LogEuclidean
        } else {
            MetricInterpolation::LinearSizes
        };
        let options = metric_file_options()
            .interpolation(interp)
            .gradation(opts.hgrad);
        let report = adapt(&mut mesh, &mut metric, &mut [], None, &options)?;
        let seconds = t0.elapsed().as_secs_f64();
        let row = SpeedRow {
            eps: e,
            vertices: mesh.n_points(),
            triangles: mesh.n_tris(),
            seconds,
            quality: quality_stats(&mesh, &metric),
            report,
            fingerprint: fingerprint(&mesh),
        };
        each(&row);
        rows.push(row);
    }
    let _ = std::fs::remove_dir_all(&dir);
    Ok(rows)
}

/// FNV-1a over the coordinate bits and the triangle vertices.
pub fn fingerprint(mesh: &Mesh2) -> u64 {
    let mut h: u64 = 0xcbf29ce484222325;
    for p in &mesh.points {
        for x in [p.x.to_bits(), p.y.to_bits()] {
            h = (h ^ x).wrapping_mul(0x100000001b3);
        }
    }
    for t in &mesh.tris {
        for &v in t {
            h = (h ^ u64::from(v)).wrapping_mul(0x100000001b3);
        }
    }
    h
}

/// The speed case: the background is the `n x n` grid and the metric is eq. (6)
/// with `eps = hmin` (1e-5 for a mesh of about a million vertices), hmax = 0.2, evaluated at the grid vertices in a band
/// of one background cell (so the grid sees the interface) — written as `<dir>/BG.mesh` and
/// `<dir>/M.sol`. Returns the two paths.
pub fn write_speed_case(dir: &Path, n: usize, eps: f64) -> Result<(PathBuf, PathBuf)> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let mesh = background(n)?;
    let m = speed_case_metric(n, eps);
    let (metric, _) = evaluate_target(&mesh, &m);
    let (mp, sp) = (dir.join("BG.mesh"), dir.join("M.sol"));
    io::write_medit2(&mp, &mesh)?;
    io::write_sol(&sp, &Sol::metric(metric))?;
    Ok((mp, sp))
}

/// Reads a mesh and the metric given at its vertices (the files of [`write_speed_case`], or any
/// `--input`/`--sol` pair holding a 2D metric). Errors: unreadable files, a `.sol` whose first
/// field is not a symmetric 2x2 tensor field (named).
pub fn read_mesh_and_metric(mesh: &Path, sol: &Path) -> Result<(Mesh2, Vec<Sym2>)> {
    let mesh_data = io::read_mesh(mesh)?;
    match io::read_sol_for(sol, mesh_data.n_points())?
        .fields
        .into_iter()
        .next()
    {
        Some(io::SolField::Tensor2(metric)) => Ok((mesh_data, metric)),
        _ => Err(Error::InvalidInput(format!(
            "{}: expected a 2D metric (symmetric tensor) field",
            sol.display()
        ))),
    }
}

/// The metric parameters of [`write_speed_case`].
pub fn speed_case_metric(n: usize, eps: f64) -> LevelSetMetric {
    LevelSetMetric {
        eps,
        hmin: eps,
        hmax: 0.2,
        max_aniso: f64::INFINITY,
        band: 4.0 / (n.max(2) - 1) as f64,
        grade: 0.3,
        analytic: true,
        isotropic: false,
    }
}
