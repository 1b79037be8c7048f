//! The sweep of the three families on one shape ([`run`]): the adapted families at decreasing `ε`,
//! the uniform grids, the fitted slopes, the anisotropy gain, the installed peers on the Zalesak
//! disk, and the CSV and figure.

use std::path::{Path, PathBuf};
use std::time::Instant;

use super::figure::{figure, write_csv};
use super::gain::anisotropy_gain;
use super::measure::{adapted_row, corners_of, domain_of, metric_with, row};
use super::types::{ConvergenceOptions, ConvergenceReport, ConvergenceRow, Family, FamilyFit};
use crate::app::plot::fit_loglog_slope;
use crate::app::repro::peers::{find_program, run_peer_with, PeerKind, PeerOptions, PeerResult};
use anisomesh::error::{Error, Result};
use anisomesh::geom::DVec2;
use anisomesh::levelset::{shape_by_name, Shape};
use anisomesh::mesh::{GridPattern, Mesh2};

/// The sweep: `ε` values of the adapted families and cells per side of the uniform grids.
///
/// Full: `points` values of `ε` log-spaced from `1e-2` to `1e-4` (the last one gives the paper's
/// `h_min = 0.001`); grids halving from 800 cells per side on Zalesak (641,601 vertices, the
/// uniform mesh of [`super::figure::REPORTED`]) and from 512 on the circle and the flower.
/// Quick: `min(points, 3)` values from `1e-2` in steps of `10^{-1/2}`, and three grids of 32 to
/// 128 cells (Zalesak 64 to 256).
pub fn sweep(shape: &str, points: usize, quick: bool) -> Result<(Vec<f64>, Vec<usize>)> {
    if points < 2 {
        return Err(Error::InvalidInput(format!(
            "convergence: need at least 2 sweep points per family (got {points})"
        )));
    }
    let zalesak = shape.trim().eq_ignore_ascii_case("zalesak");
    let eps_max: f64 = 1e-2;
    let (eps_min, n_max): (f64, usize) = if quick {
        let n = points.min(3);
        (eps_max * 10f64.powf(-0.5 * (n - 1) as f64), n)
    } else {
        (eps_max * 1e-2, points)
    };
    // Powers of ten computed as such, so that the last full point is exactly `1e-4` (the default
    // `anisomesh adapt` setting; the corner errors react to the last bit of `h_min`).
    let eps = (0..n_max)
        .map(|k| {
            let t = k as f64 / (n_max - 1) as f64;
            10f64.powf(eps_max.log10() + t * (eps_min.log10() - eps_max.log10()))
        })
        .collect();
    let top: usize = match (quick, zalesak) {
        (true, true) => 256,
        (true, false) => 128,
        (false, true) => 800,
        (false, false) => 512,
    };
    let n_grids = if quick { 3 } else { points };
    let mut cells: Vec<usize> = (0..n_grids).map(|k| top >> k).filter(|&c| c >= 4).collect();
    cells.reverse();
    Ok((eps, cells))
}

/// The peers run beside the sweep on the Zalesak disk: mmg2d and BAMG given the anisotropic
/// family's metric at the vertices of their meshes, and BAMG with its own Hessian metric of the
/// level set (`adaptmesh(Th, u, err = ε)`).
pub const PEER_KINDS: [PeerKind; 3] = [
    PeerKind::Mmg2dMetric,
    PeerKind::BamgMetric,
    PeerKind::BamgLevelSet,
];

/// The peers' fixed point (as [`crate::app::repro::peers`]): from a 50 x 50 grid, six adapter calls
/// (the reported mmg2d point is after six passes); quick: a 30 x 30 grid and two calls.
fn peer_options(opts: &ConvergenceOptions) -> PeerOptions {
    let d = PeerOptions::default();
    PeerOptions {
        background: if opts.quick { 30 } else { 50 },
        iterations: if opts.quick { 2 } else { 6 },
        timeout: std::time::Duration::from_secs(if opts.quick { 60 } else { 600 }),
        work_dir: d
            .work_dir
            .join(format!("convergence-{}", std::process::id())),
        kink_scale: opts.kink_scale,
        ..d
    }
}

/// Runs the installed peers of [`PEER_KINDS`] at every `ε` (quick: the first only); a peer not
/// on `PATH` is skipped with a printed note (and listed once in the result with its status).
fn run_peers(eps_list: &[f64], opts: &ConvergenceOptions) -> Vec<PeerResult> {
    let popts = peer_options(opts);
    let mut out = Vec::new();
    for kind in PEER_KINDS {
        let Some(program) = kind.program() else {
            continue;
        };
        if find_program(program).is_none() {
            println!(
                "note: {program} not found on PATH: the measured {} series is skipped",
                kind.slug()
            );
            out.push(PeerResult::unavailable(
                kind,
                f64::NAN,
                format!("{program} not on PATH"),
            ));
            continue;
        }
        for &eps in eps_list
            .iter()
            .take(if opts.quick { 1 } else { usize::MAX })
        {
            let m = metric_with(eps, false, opts.band_hmin, opts.grade);
            let r = run_peer_with(kind, &m, &popts);
            if !r.is_ok() {
                println!("note: {} at eps {eps:.1e}: {:?}", kind.slug(), r.status);
            }
            out.push(r);
        }
    }
    let _ = std::fs::remove_dir_all(&popts.work_dir);
    out
}

/// Runs the sweep of the three families on `opts.shape`, fits the slopes, computes the
/// anisotropy gain, runs the installed peers (Zalesak, `opts.peers`) and, with `out_dir`, writes
/// `convergence_<shape>.csv` and the three-panel figure `convergence_<shape>.png`
/// ([`super::figure`]).
///
/// Errors: an unknown shape, fewer than 2 points, adaptation or I/O failures (never a missing
/// peer).
pub fn run(opts: &ConvergenceOptions) -> Result<ConvergenceReport> {
    let shape = shape_by_name(&opts.shape)?;
    let name = opts.shape.trim().to_ascii_lowercase();
    let domain = domain_of(&name)?;
    let corners = corners_of(&name);
    let (eps_list, cells) = sweep(&name, opts.points, opts.quick)?;
    let mut rows = Vec::new();
    for &eps in &eps_list {
        for (family, iso) in [(Family::Anisotropic, false), (Family::Isotropic, true)] {
            let lm = metric_with(eps, iso, opts.band_hmin, opts.grade);
            rows.push(adapted_row(
                family,
                eps,
                lm,
                shape.as_ref(),
                domain,
                &corners,
                opts.kink_scale,
                None,
            )?);
        }
    }
    for &n in &cells {
        rows.push(uniform_row(n, domain, shape.as_ref(), &corners)?);
    }
    let fits = family_fits(&rows);
    let gain = anisotropy_gain(&rows);
    let peers = if opts.peers && name == "zalesak" {
        run_peers(&eps_list, opts)
    } else {
        Vec::new()
    };
    let mut report = ConvergenceReport {
        shape: name.clone(),
        domain: [domain.0.x, domain.0.y, domain.1.x, domain.1.y],
        rows,
        fits,
        gain,
        peers,
        files: Vec::new(),
    };
    if let Some(dir) = &opts.out_dir {
        report.files = write_files(dir, &name, &report)?;
    }
    Ok(report)
}

/// The uniform union-jack grid of `domain` with `n` cells per side, measured as a row
/// (`seconds` is the grid construction time).
fn uniform_row(
    n: usize,
    domain: (DVec2, DVec2),
    shape: &dyn Shape,
    corners: &[DVec2],
) -> Result<ConvergenceRow> {
    let t = Instant::now();
    let mesh = Mesh2::rectangle(domain.0, domain.1, n, n, GridPattern::UnionJack)?;
    let secs = t.elapsed().as_secs_f64();
    let h = (domain.1.x - domain.0.x) / n as f64;
    row(
        Family::Uniform,
        n as f64,
        h,
        &mesh,
        shape,
        corners,
        secs,
        true,
    )
}

/// The least-squares log-log slopes of the Hausdorff and area errors against the vertex count,
/// per family.
fn family_fits(rows: &[ConvergenceRow]) -> Vec<FamilyFit> {
    [Family::Anisotropic, Family::Isotropic, Family::Uniform]
        .into_iter()
        .map(|f| {
            let pts = |g: fn(&ConvergenceRow) -> f64| -> Vec<(f64, f64)> {
                rows.iter()
                    .filter(|r| r.family == f)
                    .map(|r| (r.vertices as f64, g(r)))
                    .collect()
            };
            FamilyFit {
                family: f,
                hausdorff_slope: fit_loglog_slope(&pts(|r| r.hausdorff)),
                area_slope: fit_loglog_slope(&pts(|r| r.area_rel_error)),
            }
        })
        .collect()
}

/// Writes `convergence_<name>.csv` and `convergence_<name>.png` into `dir` (created if
/// missing); returns their paths.
fn write_files(dir: &Path, name: &str, report: &ConvergenceReport) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let csv = dir.join(format!("convergence_{name}.csv"));
    write_csv(&csv, report)?;
    let png = dir.join(format!("convergence_{name}.png"));
    figure(report)?.save_png(&png)?;
    Ok(vec![csv, png])
}
