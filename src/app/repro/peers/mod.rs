//! Side-by-side comparison with the peer mesh adapters on the same problem, in the same run.
//!
//! The problem is the Zalesak slotted disk of 004 §5.1 (radius 0.5 centred at (0, 0.75), slot
//! `|x| ≤ 0.06` up to `y = 0.85`, in `[-2, 2]²`) and its geometric metric, 004 eq. (6),
//!
//! ```text
//! M = ∇u ∇uᵀ / hmin² + |D²u| / ε,   bounded by hmin = 0.001, hmax = 0.2,
//! ```
//!
//! with `u` the exact signed distance, applied in a band around the zero level and graded
//! outside it ([`LevelSetMetric`], the same target our own driver uses).
//!
//! Peers (external programs, found on `PATH`; a missing one gives
//! [`PeerResult::unavailable`], never a panic):
//! - [`PeerKind::Mmg2dMetric`]: `mmg2d_O3 -in bg.mesh -sol metric.sol -out out.mesh` (MMG 5.8).
//! - [`PeerKind::Mmg2dLevelSet`]: `mmg2d_O3 -in bg.mesh -ls -sol u.sol -hausd ε -hmin -hmax`
//!   (MMG's level-set discretisation mode: the zero level becomes mesh edges).
//! - [`PeerKind::BamgMetric`]: FreeFem++ `adaptmesh(Th, m11, m12, m22, IsMetric=1, ...)`.
//! - [`PeerKind::BamgLevelSet`]: FreeFem++ `adaptmesh(Th, u, err=ε, hmin, hmax)` (BAMG's own
//!   Hessian metric of the level set).
//! - [`PeerKind::Anisomesh`]: our [`anisomesh::adapt::adapt`] with the analytic source.
//!
//! A peer only sees the metric (or level set) at the vertices of the mesh it is given, so it is
//! run as a user would: the fixed point "evaluate at the current vertices → adapt → repeat"
//! ([`PeerOptions::iterations`] times) starting from a uniform background grid. Every result is
//! then measured the same way ([`measure`]): vertex count, edge lengths and `Q_ani` in the target
//! metric re-evaluated at the peer's vertices (004 §3.4), area and perimeter of the zero level of
//! the exact distance interpolated on the peer's mesh, the two-sided Hausdorff distance between
//! that zero level and the exact boundary, and the wall time of the peer's runs.

use anisomesh::adapt::sources::derivatives_at_scale;
use anisomesh::adapt::{adapt, AdaptOptions, AnalyticLevelSetSource, LevelSetMetric};
use anisomesh::error::{Error, Result};
use anisomesh::geom::DVec2;
use anisomesh::io::{self, Sol};
use anisomesh::levelset::interface::{
    enclosed_area, extract_zero_level, interface_distance, interface_length,
};
use anisomesh::levelset::shapes::{Shape, Zalesak};
use anisomesh::mesh::{GridPattern, Mesh2};
use anisomesh::metric::length::quality_stats;
use anisomesh::metric::Sym2;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

mod process;
mod speed_compare;
pub use process::{find_program, parse_bamg_seconds, parse_mmg_elapsed, run_with_timeout};
pub use speed_compare::speed_case;
use std::time::{Duration, Instant};

/// The FreeFem++ driver script, with `@IN@`, `@DATA@`, `@OUT@` and `@ADAPT@` placeholders.
pub const BAMG_SCRIPT: &str = include_str!("../../../../scripts/peers/bamg_adapt.edp");

/// The benchmark slotted disk (built once).
pub fn zalesak() -> &'static Zalesak {
    static SHAPE: OnceLock<Zalesak> = OnceLock::new();
    SHAPE.get_or_init(Zalesak::default)
}

/// The exact signed distance to the slotted disk (negative inside) and its gradient and Hessian
/// in closed form ([`Zalesak`]'s [`Shape`] implementation).
pub fn zalesak_exact(p: DVec2) -> (f64, DVec2, Sym2) {
    let s = zalesak();
    (s.distance(p), s.gradient(p), s.hessian(p))
}

/// The target metric of the comparison: 004 eq. (6) with hmin = 0.001, hmax = 0.2 and the given
/// `eps`, in the band `|u| < 4 hmin`, graded by 0.3 outside, anisotropy at most 1e4.
pub fn target_metric(eps: f64) -> LevelSetMetric {
    LevelSetMetric {
        eps,
        hmin: 1e-3,
        hmax: 0.2,
        max_aniso: 1e4,
        band: 4e-3,
        grade: 0.3,
        analytic: true,
        isotropic: false,
    }
}

/// The metric `m` and the exact signed distance at every vertex of `mesh`.
pub fn evaluate_target(mesh: &Mesh2, m: &LevelSetMetric) -> (Vec<Sym2>, Vec<f64>) {
    evaluate_target_with(mesh, m, None)
}

/// [`evaluate_target`] with the kinks of the distance resolved at the scale `k hmin` when
/// `kink_scale = Some(k)` ([`anisomesh::adapt::sources::derivatives_at_scale`]: the metric our
/// convergence sweep adapts to, so that the peers get the same target).
pub fn evaluate_target_with(
    mesh: &Mesh2,
    m: &LevelSetMetric,
    kink_scale: Option<f64>,
) -> (Vec<Sym2>, Vec<f64>) {
    match kink_scale {
        None => AnalyticLevelSetSource::new(zalesak_exact, *m).evaluate(mesh),
        Some(k) => {
            let delta = k * m.hmin;
            AnalyticLevelSetSource::new(|p| derivatives_at_scale(zalesak(), p, delta), *m)
                .evaluate(mesh)
        }
    }
}

/// The uniform background mesh: `n x n` vertices on `[-2, 2]²` (right diagonals).
pub fn background(n: usize) -> Result<Mesh2> {
    if n < 2 {
        return Err(Error::InvalidInput(format!(
            "peer background: need at least 2 x 2 vertices (got {n})"
        )));
    }
    Mesh2::rectangle(
        DVec2::splat(-2.0),
        DVec2::splat(2.0),
        n - 1,
        n - 1,
        GridPattern::Right,
    )
}

/// Which adapter a run uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum PeerKind {
    Mmg2dMetric,
    Mmg2dLevelSet,
    BamgMetric,
    BamgLevelSet,
    Anisomesh,
}

impl PeerKind {
    /// All kinds, peers first.
    pub const ALL: [PeerKind; 5] = [
        PeerKind::Mmg2dMetric,
        PeerKind::Mmg2dLevelSet,
        PeerKind::BamgMetric,
        PeerKind::BamgLevelSet,
        PeerKind::Anisomesh,
    ];

    /// A short name for file names and CSV rows.
    pub fn slug(self) -> &'static str {
        match self {
            PeerKind::Mmg2dMetric => "mmg2d-metric",
            PeerKind::Mmg2dLevelSet => "mmg2d-ls",
            PeerKind::BamgMetric => "bamg-metric",
            PeerKind::BamgLevelSet => "bamg-ls",
            PeerKind::Anisomesh => "anisomesh",
        }
    }

    /// The external program the kind runs (`None` for our own driver).
    pub fn program(self) -> Option<&'static str> {
        match self {
            PeerKind::Mmg2dMetric | PeerKind::Mmg2dLevelSet => Some("mmg2d_O3"),
            PeerKind::BamgMetric | PeerKind::BamgLevelSet => Some("FreeFem++"),
            PeerKind::Anisomesh => None,
        }
    }

    fn is_level_set(self) -> bool {
        matches!(self, PeerKind::Mmg2dLevelSet | PeerKind::BamgLevelSet)
    }
}

/// Outcome of a run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum PeerStatus {
    Ok,
    /// The program is not installed (not on `PATH`).
    Unavailable(String),
    /// The program ran but failed, timed out, or its output could not be read.
    Failed(String),
}

/// One run of one adapter at one accuracy, measured by [`measure`].
#[derive(Debug, Clone, Serialize)]
pub struct PeerResult {
    pub peer: PeerKind,
    pub status: PeerStatus,
    pub eps: f64,
    /// Fixed-point iterations run (adapter calls).
    pub iterations: usize,
    pub vertices: usize,
    pub triangles: usize,
    /// Whether the mesh passes [`Mesh2::check`] (conforming, counter-clockwise, consistent).
    pub valid: bool,
    /// Share of edges with metric length in `[1/sqrt(2), sqrt(2)]` (target metric).
    pub edge_length_in_range: f64,
    pub q_ani_mean: f64,
    pub q_ani_max: f64,
    /// Area of `{u_h < 0}` and its relative error against the exact 0.7135424760.
    pub area: f64,
    pub area_rel_error: f64,
    /// Length of `{u_h = 0}` and its relative error against the exact 4.3340766629.
    pub perimeter: f64,
    pub perimeter_rel_error: f64,
    /// Two-sided Hausdorff distance between `{u_h = 0}` and the exact boundary.
    pub hausdorff: f64,
    /// Wall time of the adapter calls (all iterations; the external process included).
    pub seconds: f64,
    /// Wall time of the last call alone.
    pub seconds_last: f64,
    /// Time the peer reports itself for the last call (MMG's "ELAPSED TIME", BAMG's CPU time of
    /// `adaptmesh`), when it prints one.
    pub self_seconds_last: Option<f64>,
}

impl PeerResult {
    fn empty(peer: PeerKind, eps: f64, status: PeerStatus) -> PeerResult {
        PeerResult {
            peer,
            status,
            eps,
            iterations: 0,
            vertices: 0,
            triangles: 0,
            valid: false,
            edge_length_in_range: f64::NAN,
            q_ani_mean: f64::NAN,
            q_ani_max: f64::NAN,
            area: f64::NAN,
            area_rel_error: f64::NAN,
            perimeter: f64::NAN,
            perimeter_rel_error: f64::NAN,
            hausdorff: f64::NAN,
            seconds: f64::NAN,
            seconds_last: f64::NAN,
            self_seconds_last: None,
        }
    }

    /// A result for a peer that is not installed (every measure NaN).
    pub fn unavailable(peer: PeerKind, eps: f64, reason: impl Into<String>) -> PeerResult {
        PeerResult::empty(peer, eps, PeerStatus::Unavailable(reason.into()))
    }

    /// A result for a peer that failed (every measure NaN).
    pub fn failed(peer: PeerKind, eps: f64, reason: impl Into<String>) -> PeerResult {
        PeerResult::empty(peer, eps, PeerStatus::Failed(reason.into()))
    }

    /// Whether the run produced a measured mesh.
    pub fn is_ok(&self) -> bool {
        self.status == PeerStatus::Ok
    }

    /// The CSV header matching [`PeerResult::csv_row`].
    pub const CSV_HEADER: &'static str = "peer,status,eps,iterations,vertices,triangles,valid,\
edge_length_in_range,q_ani_mean,q_ani_max,area,area_rel_error,perimeter,perimeter_rel_error,\
hausdorff,seconds,seconds_last,self_seconds_last";

    /// One CSV line (no newline); the status is `ok`, `unavailable` or `failed`.
    pub fn csv_row(&self) -> String {
        let status = match self.status {
            PeerStatus::Ok => "ok",
            PeerStatus::Unavailable(_) => "unavailable",
            PeerStatus::Failed(_) => "failed",
        };
        format!(
            "{},{},{:e},{},{},{},{},{:.6},{:.6},{:.6},{:.10},{:.6e},{:.10},{:.6e},{:.6e},{:.4},{:.4},{}",
            self.peer.slug(),
            status,
            self.eps,
            self.iterations,
            self.vertices,
            self.triangles,
            self.valid,
            self.edge_length_in_range,
            self.q_ani_mean,
            self.q_ani_max,
            self.area,
            self.area_rel_error,
            self.perimeter,
            self.perimeter_rel_error,
            self.hausdorff,
            self.seconds,
            self.seconds_last,
            self.self_seconds_last
                .map(|s| format!("{s:.4}"))
                .unwrap_or_default()
        )
    }
}

/// Measures an adapted mesh against the Zalesak problem (see the module documentation): the
/// target metric `m` and the exact distance are evaluated at the mesh's vertices; the zero level
/// of the P1 interpolant is compared with the exact area, perimeter and boundary
/// ([`anisomesh::levelset::interface`], 4 samples per segment for the Hausdorff distance). A mesh
/// whose zero level is empty gets infinite interface errors.
pub fn measure(peer: PeerKind, mesh: &Mesh2, m: &LevelSetMetric) -> PeerResult {
    let shape = zalesak();
    let (metric, u) = evaluate_target(mesh, m);
    let q = quality_stats(mesh, &metric);
    let exact_area = shape.exact_area().unwrap_or(f64::NAN);
    let exact_perimeter = shape.exact_perimeter().unwrap_or(f64::NAN);
    let area = enclosed_area(mesh, &u).unwrap_or(f64::NAN);
    let perimeter = interface_length(mesh, &u).unwrap_or(f64::NAN);
    let hausdorff = extract_zero_level(mesh, &u)
        .map(|pl| interface_distance(&pl, shape, 4).hausdorff)
        .unwrap_or(f64::INFINITY);
    PeerResult {
        vertices: mesh.n_points(),
        triangles: mesh.n_live_tris(),
        valid: mesh.check().is_ok(),
        edge_length_in_range: q.edge_length_in_range,
        q_ani_mean: q.q_ani_mean,
        q_ani_max: q.q_ani_max,
        area,
        area_rel_error: (area - exact_area) / exact_area,
        perimeter,
        perimeter_rel_error: (perimeter - exact_perimeter) / exact_perimeter,
        hausdorff,
        ..PeerResult::empty(peer, m.eps, PeerStatus::Ok)
    }
}

/// Options of a peer run.
#[derive(Debug, Clone)]
pub struct PeerOptions {
    /// Background grid: `n x n` vertices on `[-2, 2]²`.
    pub background: usize,
    /// Fixed-point iterations (adapter calls) for the external peers.
    pub iterations: usize,
    /// Time limit of one external call.
    pub timeout: Duration,
    /// Where inputs, outputs and logs go (one sub-directory per peer and `eps`).
    pub work_dir: PathBuf,
    /// BAMG's `nbvx` (maximal vertex count; FreeFem's default 9000 is too small here).
    pub bamg_max_vertices: usize,
    /// Kinks of the distance resolved at this multiple of `hmin` in the metric given to the
    /// peers ([`evaluate_target_with`]); `None` (default): the plain eq. (6) metric.
    pub kink_scale: Option<f64>,
}

impl Default for PeerOptions {
    fn default() -> Self {
        PeerOptions {
            background: 50,
            iterations: 3,
            timeout: Duration::from_secs(600),
            work_dir: std::env::temp_dir().join("anisomesh-peers"),
            bamg_max_vertices: 5_000_000,
            kink_scale: None,
        }
    }
}

/// Writes `mesh` as `<stem>.mesh` and the metric `metric` as the tensor `<stem>.sol` (MMG's
/// layout) in `dir`; returns both paths.
pub fn write_metric_input(
    dir: &Path,
    stem: &str,
    mesh: &Mesh2,
    metric: &[Sym2],
) -> Result<(PathBuf, PathBuf)> {
    let (mp, sp) = (
        dir.join(format!("{stem}.mesh")),
        dir.join(format!("{stem}.sol")),
    );
    io::write_medit2(&mp, mesh)?;
    io::write_sol(&sp, &Sol::metric(metric.to_vec()))?;
    Ok((mp, sp))
}

/// Writes `mesh` as `<stem>.mesh` and the scalar level set `u` as `<stem>.sol` in `dir`.
pub fn write_levelset_input(
    dir: &Path,
    stem: &str,
    mesh: &Mesh2,
    u: &[f64],
) -> Result<(PathBuf, PathBuf)> {
    let (mp, sp) = (
        dir.join(format!("{stem}.mesh")),
        dir.join(format!("{stem}.sol")),
    );
    io::write_medit2(&mp, mesh)?;
    io::write_sol(&sp, &Sol::scalar(u.to_vec()))?;
    Ok((mp, sp))
}

/// The FreeFem++ data file of [`BAMG_SCRIPT`]: the count, then three numbers per vertex.
pub fn write_bamg_data(path: &Path, rows: &[[f64; 3]]) -> Result<()> {
    io::atomic_write(path, |w| {
        writeln!(w, "{}", rows.len())?;
        for r in rows {
            writeln!(w, "{:.17e} {:.17e} {:.17e}", r[0], r[1], r[2])?;
        }
        Ok(())
    })
}

/// The BAMG driver script for one call: `adapt` is the `adaptmesh(...)` expression.
pub fn bamg_script(mesh_in: &Path, data: &Path, mesh_out: &Path, adapt: &str) -> String {
    BAMG_SCRIPT
        .replace("@IN@", &mesh_in.display().to_string())
        .replace("@DATA@", &data.display().to_string())
        .replace("@OUT@", &mesh_out.display().to_string())
        .replace("@ADAPT@", adapt)
}

/// One external adapter call on `mesh`, returning the adapted mesh, the wall time and the
/// self-reported time.
fn call_peer(
    kind: PeerKind,
    exe: &Path,
    mesh: &Mesh2,
    m: &LevelSetMetric,
    opts: &PeerOptions,
    dir: &Path,
    k: usize,
) -> Result<(Mesh2, f64, Option<f64>)> {
    let (metric, u) = evaluate_target_with(mesh, m, opts.kink_scale);
    let stem = format!("in{k}");
    let out = dir.join(format!("out{k}.mesh"));
    let _ = std::fs::remove_file(&out);
    let mut cmd = Command::new(exe);
    match kind {
        PeerKind::Mmg2dMetric | PeerKind::Mmg2dLevelSet => {
            let (mp, sp) = if kind.is_level_set() {
                write_levelset_input(dir, &stem, mesh, &u)?
            } else {
                write_metric_input(dir, &stem, mesh, &metric)?
            };
            cmd.arg("-v").arg("1").arg("-in").arg(&mp);
            if kind.is_level_set() {
                cmd.arg("-ls").arg("-hausd").arg(format!("{:e}", m.eps));
                cmd.arg("-hmin").arg(format!("{:e}", m.hmin));
                cmd.arg("-hmax").arg(format!("{:e}", m.hmax));
            }
            cmd.arg("-sol").arg(&sp).arg("-out").arg(&out);
        }
        PeerKind::BamgMetric | PeerKind::BamgLevelSet => {
            let mp = dir.join(format!("{stem}.mesh"));
            io::write_medit2(&mp, mesh)?;
            let data = dir.join(format!("{stem}.txt"));
            let (rows, adapt): (Vec<[f64; 3]>, String) = if kind.is_level_set() {
                (
                    u.iter().map(|&v| [v, 0.0, 0.0]).collect(),
                    format!(
                        "adaptmesh(Th, a, err={:e}, hmin={:e}, hmax={:e}, nbvx={})",
                        m.eps, m.hmin, m.hmax, opts.bamg_max_vertices
                    ),
                )
            } else {
                (
                    metric.iter().map(|s| [s.xx, s.xy, s.yy]).collect(),
                    format!(
                        "adaptmesh(Th, a, b, c, IsMetric=1, hmin={:e}, hmax={:e}, nbvx={})",
                        m.hmin, m.hmax, opts.bamg_max_vertices
                    ),
                )
            };
            write_bamg_data(&data, &rows)?;
            let edp = dir.join(format!("adapt{k}.edp"));
            let text = bamg_script(&mp, &data, &out, &adapt);
            io::atomic_write(&edp, |w| w.write_all(text.as_bytes()))?;
            cmd.arg("-nw").arg("-v").arg("0").arg(&edp);
        }
        PeerKind::Anisomesh => {
            return Err(Error::InvalidInput(
                "anisomesh is not an external peer".into(),
            ))
        }
    }
    let tag = format!("call{k}");
    let run = run_with_timeout(&mut cmd, opts.timeout, dir, &tag)?;
    let what = format!("{} call {k} in {}", kind.slug(), dir.display());
    if run.timed_out {
        return Err(Error::NotConverged(format!(
            "{what}: timed out after {:.0} s",
            run.seconds
        )));
    }
    if !run.success || !out.is_file() {
        let tail: String = run
            .stdout
            .lines()
            .rev()
            .take(5)
            .collect::<Vec<_>>()
            .join(" | ");
        return Err(Error::InvalidInput(format!(
            "{what}: failed (no output mesh); last lines: {tail} {}",
            run.stderr.trim()
        )));
    }
    let own = match kind {
        PeerKind::BamgMetric | PeerKind::BamgLevelSet => parse_bamg_seconds(&run.stdout),
        _ => parse_mmg_elapsed(&run.stdout),
    };
    Ok((io::read_medit2(&out)?, run.seconds, own))
}

/// Runs one external peer at accuracy `eps` (the metric [`target_metric`]): the fixed point from
/// the background grid, then [`measure`]. Never fails: a missing program or a failed call is in
/// the result's status.
pub fn run_peer(kind: PeerKind, eps: f64, opts: &PeerOptions) -> PeerResult {
    if kind == PeerKind::Anisomesh {
        return run_anisomesh(eps, opts);
    }
    run_peer_with(kind, &target_metric(eps), opts)
}

/// Runs one external peer with the level-set metric `m` (any `eps`, bounds, band): the fixed
/// point "evaluate at the current vertices → adapt" ([`PeerOptions::iterations`] calls) from the
/// background grid, then [`measure`] against `m`. Never fails: a missing program or a failed call
/// is in the result's status; [`PeerKind::Anisomesh`] is not external and gives a failed result.
pub fn run_peer_with(kind: PeerKind, m: &LevelSetMetric, opts: &PeerOptions) -> PeerResult {
    let eps = m.eps;
    let Some(name) = kind.program() else {
        return PeerResult::failed(kind, eps, "not an external peer");
    };
    let Some(exe) = find_program(name) else {
        return PeerResult::unavailable(kind, eps, format!("{name} not found on PATH"));
    };
    let m = *m;
    let dir = opts.work_dir.join(format!("{}_eps{eps:e}", kind.slug()));
    let go = || -> Result<PeerResult> {
        std::fs::create_dir_all(&dir).map_err(|e| Error::io(&dir, e))?;
        let mut mesh = background(opts.background)?;
        let (mut total, mut last, mut own) = (0.0, 0.0, None);
        for k in 0..opts.iterations.max(1) {
            let (next, s, o) = call_peer(kind, &exe, &mesh, &m, opts, &dir, k)?;
            mesh = next;
            total += s;
            last = s;
            own = o;
        }
        let mut r = measure(kind, &mesh, &m);
        r.iterations = opts.iterations.max(1);
        r.seconds = total;
        r.seconds_last = last;
        r.self_seconds_last = own;
        Ok(r)
    };
    go().unwrap_or_else(|e| PeerResult::failed(kind, eps, e.to_string()))
}

/// Our own driver on the same problem: [`anisomesh::adapt::adapt`] from the background grid with the
/// analytic eq. (6) source (it re-evaluates the exact metric at new vertices, so one call).
pub fn run_anisomesh(eps: f64, opts: &PeerOptions) -> PeerResult {
    let m = target_metric(eps);
    let go = || -> Result<PeerResult> {
        let mut mesh = background(opts.background)?;
        let source = AnalyticLevelSetSource::new(zalesak_exact, m);
        let (mut metric, u) = source.evaluate(&mesh);
        let mut fields = vec![u];
        let t0 = Instant::now();
        adapt(
            &mut mesh,
            &mut metric,
            &mut fields,
            Some(&source),
            &AdaptOptions::default(),
        )?;
        let s = t0.elapsed().as_secs_f64();
        let mut r = measure(PeerKind::Anisomesh, &mesh, &m);
        r.iterations = 1;
        r.seconds = s;
        r.seconds_last = s;
        Ok(r)
    };
    go().unwrap_or_else(|e| PeerResult::failed(PeerKind::Anisomesh, eps, e.to_string()))
}

/// The accuracy sweep: every kind at every `eps`, written as `peers_sweep.csv` in `out_dir` (the
/// points of the error-versus-vertex-count figure). Unavailable peers appear as such in the CSV.
pub fn sweep(
    kinds: &[PeerKind],
    eps: &[f64],
    opts: &PeerOptions,
    out_dir: &Path,
) -> Result<Vec<PeerResult>> {
    let mut all = Vec::new();
    for &e in eps {
        for &k in kinds {
            all.push(run_peer(k, e, opts));
        }
    }
    write_csv(&out_dir.join("peers_sweep.csv"), &all)?;
    Ok(all)
}

/// Writes results as CSV ([`PeerResult::CSV_HEADER`]), creating the directory.
pub fn write_csv(path: &Path, results: &[PeerResult]) -> Result<()> {
    if let Some(d) = path.parent() {
        std::fs::create_dir_all(d).map_err(|e| Error::io(d, e))?;
    }
    io::atomic_write(path, |w| {
        writeln!(w, "{}", PeerResult::CSV_HEADER)?;
        for r in results {
            writeln!(w, "{}", r.csv_row())?;
        }
        Ok(())
    })
}
