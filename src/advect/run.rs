//! A whole transport run: any initial level set in any velocity field `v(t, x)` on a rectangle,
//! over `[t_start, t_end]` in equal periods, on a fixed uniform mesh or with the transient
//! fixed-point adaptation of 004 §3.5 (level-set metric of 004 eq. (6) intersected over each
//! period, characteristics-Galerkin step of 004 eq. (2)), with the area, perimeter and mesh size
//! measured after every period.
//!
//! Input is checked: the initial level set must be finite and change sign in the domain, the
//! velocity must be finite at the vertices, and the interior `{u < 0}` must not reach the
//! domain boundary when it starts away from it (the shape would be carried out of the domain,
//! where the characteristics-Galerkin step has no data). Each violation is a one-line
//! [`Error::InvalidInput`].

use super::adapter::LevelSetAdapter;
use super::characteristics::Velocity;
use super::fixed_point::{advance_period, Adapter, FixedPointOptions};
use super::galerkin::advect;
use super::mass_correction::correct_mass;
use crate::adapt::{AdaptOptions, LevelSetMetric};
use crate::error::{Error, Result};
use crate::geom::DVec2;
use crate::levelset::interface::{enclosed_area, interface_length};
use crate::levelset::redistance::redistance_geometric;
use crate::mesh::{GridPattern, Mesh2};
use rayon::prelude::*;
use std::time::Instant;

/// The meshes that carry the level set.
#[derive(Debug, Clone)]
pub enum MeshFamily {
    /// A fixed `n x n` grid of the domain (union-jack diagonals).
    Uniform {
        /// Cells per side.
        n: usize,
    },
    /// Adapted meshes: the initial one adapted `initial_rounds` times to the exact initial
    /// level set from an `initial_n x initial_n` grid, then the fixed point of 004 §3.5.
    Adapted {
        /// The metric of one level set (its `isotropic` flag selects the isotropic variant).
        metric: LevelSetMetric,
        /// The remeshing options of every adaptation.
        adapt: AdaptOptions,
        /// Cells per side of the grid the initial adaptation starts from.
        initial_n: usize,
        /// Adaptations of the initial mesh to the exact initial level set.
        initial_rounds: usize,
    },
}

/// Options of [`run`].
#[derive(Debug, Clone)]
pub struct RunOptions {
    /// The domain `[lo, hi]`.
    pub domain: (DVec2, DVec2),
    /// Start and end times.
    pub t_start: f64,
    /// End time.
    pub t_end: f64,
    /// Number of equal periods (at least 1).
    pub periods: usize,
    /// The meshes.
    pub mesh: MeshFamily,
    /// The fixed point (adapted meshes) and the advection step (both families).
    pub fixed_point: FixedPointOptions,
    /// Geometric redistancing (004 §2.2) after each period: the level set becomes the exact
    /// distance to its P1 zero level again, so that the band and the sizes of the metric
    /// (004 eq. (6)) keep their meaning where the flow stretches or compresses the field.
    pub redistance: bool,
    /// Restore the initial enclosed area after each period (004 §5.1 "mass correction").
    pub mass_correction: bool,
    /// Times whose mesh and level set are kept ([`RunResult::snapshots`]): each is taken at the
    /// end of the first period ending at or after it.
    pub snapshot_times: Vec<f64>,
}

/// The measures after one period.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct StepStats {
    /// Period index (0 = the initial state).
    pub period: usize,
    /// Time at the end of the period.
    pub time: f64,
    /// Area of `{u < 0}`.
    pub area: f64,
    /// Length of the zero level.
    pub perimeter: f64,
    /// Vertices of the mesh.
    pub vertices: usize,
    /// Fixed-point iterations of the period (1 on a fixed mesh, 0 for the initial state).
    pub fixed_point_iterations: usize,
    /// Mean L1 change of `u^{n+1}` at the last fixed-point iteration (0 on a fixed mesh).
    pub l1_change: f64,
    /// Wall-clock seconds since the start of the run.
    pub seconds: f64,
}

/// A mesh and the level set on it at one time.
#[derive(Debug, Clone)]
pub struct Snapshot {
    /// The time.
    pub time: f64,
    /// The mesh.
    pub mesh: Mesh2,
    /// The level set (P1, one value per vertex).
    pub u: Vec<f64>,
}

/// The outcome of [`run`].
#[derive(Debug, Clone)]
pub struct RunResult {
    /// The initial mesh and level set.
    pub initial: Snapshot,
    /// The final mesh and level set.
    pub last: Snapshot,
    /// The measures: the initial state, then one row per period.
    pub steps: Vec<StepStats>,
    /// The states kept for [`RunOptions::snapshot_times`].
    pub snapshots: Vec<Snapshot>,
    /// Wall-clock seconds in total, in the adapter (initial mesh included) and in advection.
    pub seconds: f64,
    /// Seconds spent adapting.
    pub adapt_seconds: f64,
    /// Seconds spent in advection and transfer.
    pub advect_seconds: f64,
    /// Number of adaptations and their split/collapse cycles (0 on a uniform mesh).
    pub adaptations: usize,
    /// Split/collapse cycles of all adaptations.
    pub adapt_cycles: usize,
}

impl RunResult {
    /// Mean vertex count over the meshes of the run (initial included).
    pub fn vertices_mean(&self) -> f64 {
        let n = self.steps.len().max(1) as f64;
        self.steps.iter().map(|s| s.vertices as f64).sum::<f64>() / n
    }

    /// Largest vertex count over the meshes of the run.
    pub fn vertices_max(&self) -> usize {
        self.steps.iter().map(|s| s.vertices).max().unwrap_or(0)
    }
}

/// Transports the zero level of `phi0` by `v` as `opts` describes (see the module documentation).
pub fn run<F, V>(phi0: &F, v: &V, opts: &RunOptions) -> Result<RunResult>
where
    F: Fn(DVec2) -> f64 + Sync + ?Sized,
    V: Velocity + ?Sized,
{
    validate(opts)?;
    let start = Instant::now();
    let (lo, hi) = opts.domain;
    let mut adapter = match &opts.mesh {
        MeshFamily::Uniform { .. } => None,
        MeshFamily::Adapted { metric, adapt, .. } => {
            Some(LevelSetAdapter::new(*metric, adapt.clone())?)
        }
    };
    let mut mesh = match &opts.mesh {
        MeshFamily::Uniform { n } => Mesh2::rectangle(lo, hi, *n, *n, GridPattern::UnionJack)?,
        MeshFamily::Adapted {
            initial_n,
            initial_rounds,
            ..
        } => {
            let mut m = Mesh2::rectangle(lo, hi, *initial_n, *initial_n, GridPattern::UnionJack)?;
            if let Some(a) = adapter.as_mut() {
                for _ in 0..*initial_rounds {
                    let u = initial_values(&m, phi0)?;
                    m = a.adapt(&m, &[u])?;
                }
            }
            m
        }
    };
    let mut u = initial_values(&mesh, phi0)?;
    if !(u.iter().any(|&x| x < 0.0) && u.iter().any(|&x| x > 0.0)) {
        return Err(Error::InvalidInput(
            "advect: the initial level set has no zero level in the domain (it does not change sign at the vertices)".into(),
        ));
    }
    let guard_boundary = boundary_min(&mesh, &u) > 0.0;
    let mut adapt_seconds = start.elapsed().as_secs_f64();
    let mut advect_seconds = 0.0;
    let area0 = enclosed_area(&mesh, &u)?;
    let initial = Snapshot {
        time: opts.t_start,
        mesh: mesh.clone(),
        u: u.clone(),
    };
    let mut steps = vec![StepStats {
        period: 0,
        time: opts.t_start,
        area: area0,
        perimeter: interface_length(&mesh, &u)?,
        vertices: mesh.n_points(),
        fixed_point_iterations: 0,
        l1_change: 0.0,
        seconds: start.elapsed().as_secs_f64(),
    }];
    let mut snapshots = Vec::new();
    let mut pending: Vec<f64> = opts.snapshot_times.clone();
    pending.sort_by(f64::total_cmp);
    let dt = (opts.t_end - opts.t_start) / opts.periods as f64;
    for k in 0..opts.periods {
        let t0 = opts.t_start + k as f64 * dt;
        let t1 = if k + 1 == opts.periods {
            opts.t_end
        } else {
            t0 + dt
        };
        check_velocity(&mesh, v, t0, t1)?;
        let (iters, change) = match adapter.as_mut() {
            Some(a) => {
                let res = advance_period(&mesh, &u, v, t0, t1, a, &opts.fixed_point)?;
                adapt_seconds += res.adapt_seconds;
                advect_seconds += res.advect_seconds;
                mesh = res.mesh;
                u = res.u;
                (
                    res.iterations,
                    res.l1_changes.last().copied().unwrap_or(0.0),
                )
            }
            None => {
                let ta = Instant::now();
                u = advect(&mesh, &u, &mesh, v, t0, t1, &opts.fixed_point.advect)?;
                advect_seconds += ta.elapsed().as_secs_f64();
                (1, 0.0)
            }
        };
        if u.iter().any(|x| !x.is_finite()) {
            return Err(Error::InvalidInput(format!(
                "advect: the level set became non-finite in [{t0}, {t1}] (velocity not finite along the characteristics?)"
            )));
        }
        if guard_boundary && boundary_min(&mesh, &u) <= 0.0 {
            return Err(Error::InvalidInput(format!(
                "advect: the shape reaches the domain boundary in [{t0:.4}, {t1:.4}]: the velocity carries it out of the domain"
            )));
        }
        if opts.redistance {
            let ta = Instant::now();
            u = redistance_geometric(&mesh, &u)?;
            advect_seconds += ta.elapsed().as_secs_f64();
        }
        if opts.mass_correction {
            correct_mass(&mesh, &mut u, area0, 1e-13)?;
        }
        while pending.first().is_some_and(|&s| s <= t1 + 1e-12 * dt.abs()) {
            pending.remove(0);
            snapshots.push(Snapshot {
                time: t1,
                mesh: mesh.clone(),
                u: u.clone(),
            });
        }
        steps.push(StepStats {
            period: k + 1,
            time: t1,
            area: enclosed_area(&mesh, &u)?,
            perimeter: interface_length(&mesh, &u)?,
            vertices: mesh.n_points(),
            fixed_point_iterations: iters,
            l1_change: change,
            seconds: start.elapsed().as_secs_f64(),
        });
    }
    let (adaptations, adapt_cycles) = adapter.as_ref().map_or((0, 0), |a| {
        (a.reports.len(), a.reports.iter().map(|r| r.cycles).sum())
    });
    Ok(RunResult {
        initial,
        last: Snapshot {
            time: opts.t_end,
            mesh,
            u,
        },
        steps,
        snapshots,
        seconds: start.elapsed().as_secs_f64(),
        adapt_seconds,
        advect_seconds,
        adaptations,
        adapt_cycles,
    })
}

fn validate(opts: &RunOptions) -> Result<()> {
    let (lo, hi) = opts.domain;
    if !(lo.is_finite() && hi.is_finite() && hi.x > lo.x && hi.y > lo.y) {
        return Err(Error::InvalidInput(format!(
            "advect: the domain [{lo}, {hi}] needs finite corners with hi > lo"
        )));
    }
    if !(opts.t_start.is_finite() && opts.t_end.is_finite() && opts.t_end > opts.t_start) {
        return Err(Error::InvalidInput(format!(
            "advect: need finite times with t_end > t_start (got {}, {})",
            opts.t_start, opts.t_end
        )));
    }
    if opts.periods == 0 || opts.periods > 1_000_000 {
        return Err(Error::InvalidInput(format!(
            "advect: periods must be in 1..=1e6 (got {})",
            opts.periods
        )));
    }
    match &opts.mesh {
        MeshFamily::Uniform { n } if *n < 2 || *n > 20_000 => Err(Error::InvalidInput(format!(
            "advect: a uniform mesh needs 2..=20000 cells per side (got {n})"
        ))),
        MeshFamily::Adapted { initial_n, .. } if *initial_n < 2 || *initial_n > 20_000 => {
            Err(Error::InvalidInput(format!(
                "advect: the initial grid needs 2..=20000 cells per side (got {initial_n})"
            )))
        }
        _ => Ok(()),
    }
}

/// The initial level set at the vertices, which must be finite.
fn initial_values<F: Fn(DVec2) -> f64 + Sync + ?Sized>(mesh: &Mesh2, phi0: &F) -> Result<Vec<f64>> {
    let u: Vec<f64> = mesh.points.par_iter().map(|&p| phi0(p)).collect();
    if let Some(i) = u.iter().position(|x| !x.is_finite()) {
        let p = mesh.points[i];
        return Err(Error::InvalidInput(format!(
            "advect: the initial level set is not finite at ({}, {})",
            p.x, p.y
        )));
    }
    Ok(u)
}

/// The velocity must be finite at the vertices at the start, middle and end of a period.
fn check_velocity<V: Velocity + ?Sized>(mesh: &Mesh2, v: &V, t0: f64, t1: f64) -> Result<()> {
    for t in [t0, 0.5 * (t0 + t1), t1] {
        let bad = mesh
            .points
            .par_iter()
            .position_any(|&p| !v.at(t, p).is_finite());
        if let Some(i) = bad {
            let p = mesh.points[i];
            return Err(Error::InvalidInput(format!(
                "advect: the velocity is not finite at ({}, {}), t = {t}",
                p.x, p.y
            )));
        }
    }
    Ok(())
}

/// Smallest level-set value on the boundary vertices (`+inf` when there is none).
fn boundary_min(mesh: &Mesh2, u: &[f64]) -> f64 {
    mesh.boundary_vertex_flags()
        .iter()
        .zip(u)
        .filter(|(b, _)| **b)
        .map(|(_, &x)| x)
        .fold(f64::INFINITY, f64::min)
}
