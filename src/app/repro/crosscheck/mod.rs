//! The cross-check: each problem through every back end that can take it, one table per problem
//! (back end, degrees of freedom, error, observed order, seconds), written as `crosscheck.json`,
//! `crosscheck.csv` and one log-log figure of error against degrees of freedom per problem.
//!
//! Problems ([`problems`]): the circle shrinking by curvature (`R(t) = √(R0² − 2t)`) through the
//! level-set back ends of [`level_set_backends`] and the parametric curves of 002; the sphere
//! shrinking by mean curvature (`R(t) = √(R0² − 4t)`) through the 3D level-set back ends of
//! [`level_set_backends_3d`] and parametric P1 and P2 surfaces; the
//! interface curvature of a circle and of an ellipse given by a non-distance implicit function;
//! Zalesak's slotted disk after one revolution (area and perimeter errors) through the level-set
//! back ends.
//! The order of a row is `log(e_prev / e) / log(h_prev / h)` against the previous row of the
//! same back end, `h` the resolution (the mesh size the back end was built with, the arc length
//! of a curve's element, `V^{-1/2}` on a surface).

mod problems;
pub mod table41;

use crate::app::plot::{loglog_png, LogLogPlot, Series};
use anisomesh::backends::adapted::AdaptedBackend3;
use anisomesh::backends::dtgrid::plane::{DtGrid2Backend, DtGrid2Options};
use anisomesh::backends::dtgrid::DtGridBackend;
use anisomesh::backends::fitted::FittedBackend;
use anisomesh::backends::{AdaptedBackend, BuildSpec, LevelSetBackend, D2, D3};
use anisomesh::error::{Error, Result};
use serde::Serialize;
use std::path::Path;

pub use problems::{circle_mcf, curvature, sphere_mcf, zalesak};

/// Builds a 2D level-set back end of one kind from a [`BuildSpec`].
pub type Build2 = Box<dyn Fn(&BuildSpec<'_, D2>) -> Result<Box<dyn LevelSetBackend<D2>>>>;

/// Builds a 3D level-set back end of one kind from a [`BuildSpec`].
pub type Build3 = Box<dyn Fn(&BuildSpec<'_, D3>) -> Result<Box<dyn LevelSetBackend<D3>>>>;

/// The 2D back end `B` with its default options, as a [`Build2`] entry.
pub fn entry2<B: LevelSetBackend<D2> + 'static>(name: &'static str) -> (&'static str, Build2) {
    (
        name,
        Box::new(|s| Ok(Box::new(B::build(s)?) as Box<dyn LevelSetBackend<D2>>)),
    )
}

/// The 3D back end `B` with its default options, as a [`Build3`] entry.
pub fn entry3<B: LevelSetBackend<D3> + 'static>(name: &'static str) -> (&'static str, Build3) {
    (
        name,
        Box::new(|s| Ok(Box::new(B::build(s)?) as Box<dyn LevelSetBackend<D3>>)),
    )
}

/// The 2D level-set back ends the cross-check runs (the circle, the curvatures, Zalesak):
/// adding one is one line here.
pub fn level_set_backends() -> Vec<(&'static str, Build2)> {
    vec![
        entry2::<AdaptedBackend>("adapted"),
        entry2::<FittedBackend>("fitted"),
        ("dtgrid", Box::new(dtgrid2)),
    ]
}

/// The planar DT-Grid band of the cross-check: the default band (`j = 2`, Dirichlet conditions,
/// up to 5 solves per step) with mean curvature sub-steps `τ ≤ (jh)²`, 000's second-order
/// regime.
fn dtgrid2(s: &BuildSpec<'_, D2>) -> Result<Box<dyn LevelSetBackend<D2>>> {
    let d = DtGrid2Options::default();
    let o = DtGrid2Options {
        tau_per_h2: (d.mcf.j * d.mcf.j) as f64,
        tau_per_h: f64::INFINITY,
        ..d
    };
    Ok(Box::new(DtGrid2Backend::new(s, o)?))
}

/// The coarsest resolution of a level-set back end on the shrinking circle, `h0`, halved per
/// level: the band takes `τ ≤ (jh)²`, `(0.4 h)/(jh)²` sub-steps per step of the others, so it
/// starts one level coarser than the meshes.
pub fn circle_h0(backend: &str) -> f64 {
    if backend == "dtgrid" {
        0.04
    } else {
        0.02
    }
}

/// The number of circle levels of a level-set back end: [`Resolution::levels`], but at most 2
/// for the fitted mesh below [`Resolution::Full`] (its third level, 160,801 vertices, took
/// about 60 s of the default run's 100; its two levels still bracket the common error of the
/// circle, so its dof for that error are interpolated between them).
pub fn circle_levels(res: Resolution, backend: &str) -> usize {
    if backend == "fitted" && res != Resolution::Full {
        res.levels().min(2)
    } else {
        res.levels()
    }
}

/// The 3D level-set back ends the cross-check runs on the shrinking sphere, beside the
/// parametric surfaces: adding one is one line here.
pub fn level_set_backends_3d() -> Vec<(&'static str, Build3)> {
    vec![
        entry3::<AdaptedBackend3>("adapted"),
        entry3::<DtGridBackend>("dtgrid"),
    ]
}

/// The resolutions of a 3D level-set back end on the sphere: the band at `h = 0.2 / 2^k`
/// ([`Resolution::levels_3d`] levels; a level costs about 8× the one before), the adapted
/// tetrahedral mesh at `h = 0.2 / √2^k` ([`Resolution::levels`] levels: its vertices grow
/// about like `1/h`, and each level is one tetrahedral adaptation).
pub fn sphere_resolutions(res: Resolution, backend: &str) -> Vec<f64> {
    if backend == "adapted" {
        (0..res.levels())
            .map(|k| 0.2 / 2f64.sqrt().powi(k as i32))
            .collect()
    } else {
        (0..res.levels_3d())
            .map(|k| 0.2 / 2f64.powi(k as i32))
            .collect()
    }
}

/// The time step of a 3D level-set back end on the sphere at resolution `h`: `h²` for the band
/// (000's second-order regime), `h²/4` for the adapted mesh, whose semi-implicit Euler step is
/// first order in time (at `τ = h²` its time error, 1.1e-2 at h = 0.2, exceeds its spatial
/// error).
pub fn sphere_tau(backend: &str, h: f64) -> f64 {
    if backend == "adapted" {
        0.25 * h * h
    } else {
        h * h
    }
}

/// How much to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Resolution {
    /// A few seconds: two coarse levels (the tests).
    Tiny,
    /// The default: three levels, under two minutes.
    Quick,
    /// One more level everywhere (a benchmark).
    Full,
}

impl Resolution {
    /// The number of levels of each back end.
    pub fn levels(self) -> usize {
        match self {
            Resolution::Tiny => 2,
            Resolution::Quick => 3,
            Resolution::Full => 4,
        }
    }

    /// The number of levels of the DT-Grid band on the sphere: two, three for
    /// [`Resolution::Full`] (the third level, `h = 0.05`, takes minutes).
    pub fn levels_3d(self) -> usize {
        match self {
            Resolution::Full => 3,
            _ => 2,
        }
    }
}

/// One row of a problem's table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// The back end (`adapted`, `parametric P1`, ...).
    pub backend: String,
    /// The resolution it was run at.
    pub resolution: f64,
    /// Degrees of freedom at the end of the run.
    pub dof: usize,
    /// The problem's error measure.
    pub error: f64,
    /// The computed quantity whose error is measured, where it is one number (the final
    /// radius of the flows), for comparing back ends with each other.
    pub value: Option<f64>,
    /// Observed order against the previous row of the same back end.
    pub order: Option<f64>,
    /// Wall-clock seconds.
    pub seconds: f64,
}

/// One problem and its rows.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Problem {
    /// A short name (`circle_mcf`, `sphere_mcf`, `curvature_circle`, `curvature_ellipse`).
    pub name: String,
    /// What is measured.
    pub error_measure: String,
    /// The rows, by back end then resolution.
    pub rows: Vec<Row>,
}

impl Problem {
    /// Fills [`Row::order`] from consecutive rows of the same back end.
    pub(crate) fn fill_orders(&mut self) {
        for i in 1..self.rows.len() {
            let (a, b) = (&self.rows[i - 1], &self.rows[i]);
            if a.backend == b.backend && a.error > 0.0 && b.error > 0.0 {
                let o = (a.error / b.error).ln() / (a.resolution / b.resolution).ln();
                self.rows[i].order = Some(o);
            }
        }
    }

    /// The rows of one back end.
    pub fn rows_of<'a>(&'a self, backend: &'a str) -> impl Iterator<Item = &'a Row> + 'a {
        self.rows.iter().filter(move |r| r.backend == backend)
    }

    /// The back ends in order of first appearance.
    pub fn backends(&self) -> Vec<&str> {
        let mut names: Vec<&str> = Vec::new();
        for r in &self.rows {
            if !names.contains(&r.backend.as_str()) {
                names.push(&r.backend);
            }
        }
        names
    }

    /// For each back end, the degrees of freedom and seconds it needs for the error `target`:
    /// log-log interpolation between its two rows around `target`, `None` when its rows do not
    /// reach `target` or do not bracket it.
    pub fn cost_at_error(&self, target: f64) -> Vec<(String, Option<(f64, f64)>)> {
        self.backends()
            .into_iter()
            .map(|b| {
                let rows: Vec<&Row> = self.rows_of(b).collect();
                let hit = rows.windows(2).find_map(|w| {
                    let (a, c) = (w[0], w[1]);
                    if !(a.error >= target && c.error <= target && a.error > c.error) {
                        return None;
                    }
                    let s = (a.error / target).ln() / (a.error / c.error).ln();
                    let lerp = |x: f64, y: f64| {
                        (x.max(1e-9).ln() * (1.0 - s) + y.max(1e-9).ln() * s).exp()
                    };
                    Some((lerp(a.dof as f64, c.dof as f64), lerp(a.seconds, c.seconds)))
                });
                (b.to_string(), hit)
            })
            .collect()
    }
}

/// The whole cross-check (`crosscheck.json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CrossReport {
    /// How much was run.
    pub resolution: Resolution,
    /// The problems.
    pub problems: Vec<Problem>,
}

/// The number of runs [`run`] reports to its `progress` (one per back end, level and problem;
/// a Zalesak run fills two problems).
pub fn planned_runs(res: Resolution) -> usize {
    let l = res.levels();
    let two = level_set_backends();
    let circle: usize = two.iter().map(|(name, _)| circle_levels(res, name)).sum();
    let sphere: usize = level_set_backends_3d()
        .iter()
        .map(|(name, _)| sphere_resolutions(res, name).len())
        .sum();
    let zalesak: usize = two.iter().map(|(name, _)| zalesak_levels(res, name)).sum();
    // Circle (+ 2 parametric), sphere (+ 2 parametric), two curvatures (+ 2 parametric each).
    circle + 2 * l + sphere + 2 * l + 2 * l * (two.len() + 2) + zalesak
}

/// The number of Zalesak levels of a level-set back end: at most 3 (a revolution is the
/// costliest run), at most 2 for the band (its third level, h = 0.005, took 8× its second:
/// 250 advection sub-steps of 2 cells, each rebuilding the band and its distance).
pub fn zalesak_levels(res: Resolution, backend: &str) -> usize {
    let cap = if backend == "dtgrid" { 2 } else { 3 };
    res.levels().min(cap)
}

/// For each pair of back ends in `p` with at least two rows carrying a value: whether their
/// finest values agree within the sum of their error estimates, each estimate the change of the
/// value between its last two rows (an upper bound of the finest error when the order is at
/// least 1). Returns `(a, b, |v_a − v_b|, est_a + est_b)`.
pub fn agreement(p: &Problem) -> Vec<(String, String, f64, f64)> {
    let est: Vec<(String, f64, f64)> = p
        .backends()
        .into_iter()
        .filter_map(|b| {
            let v: Vec<f64> = p.rows_of(b).filter_map(|r| r.value).collect();
            (v.len() >= 2).then(|| {
                let (a, c) = (v[v.len() - 2], v[v.len() - 1]);
                (b.to_string(), c, (c - a).abs())
            })
        })
        .collect();
    let mut out = Vec::new();
    for i in 0..est.len() {
        for j in i + 1..est.len() {
            let (a, b) = (&est[i], &est[j]);
            out.push((a.0.clone(), b.0.clone(), (a.1 - b.1).abs(), a.2 + b.2));
        }
    }
    out
}

/// Runs every problem; `progress` hears a line per finished run.
pub fn run(res: Resolution, progress: &mut dyn FnMut(&str)) -> Result<CrossReport> {
    let backends = level_set_backends();
    let backends_3d = level_set_backends_3d();
    let mut problems = vec![
        circle_mcf(res, &backends, progress)?,
        sphere_mcf(res, &backends_3d, progress)?,
        curvature(res, false, &backends, progress)?,
        curvature(res, true, &backends, progress)?,
    ];
    problems.extend(zalesak(res, &backends, progress)?);
    Ok(CrossReport {
        resolution: res,
        problems,
    })
}

/// The tables of `report`, as text.
pub fn tables(report: &CrossReport) -> String {
    let mut s = String::new();
    for p in &report.problems {
        s += &format!("\n{} ({})\n", p.name, p.error_measure);
        s += &format!(
            "{:<16} {:>10} {:>8} {:>10} {:>6} {:>8}\n",
            "backend", "resolution", "dof", "error", "order", "seconds"
        );
        for r in &p.rows {
            let o = r.order.map_or("-".into(), |o| format!("{o:.2}"));
            s += &format!(
                "{:<16} {:>10.3e} {:>8} {:>10.3e} {:>6} {:>8.2}\n",
                r.backend, r.resolution, r.dof, r.error, o, r.seconds
            );
        }
        // The cost of one error for all: the largest finest error of the back ends that
        // converge (positive order at their finest row).
        let target = p
            .backends()
            .iter()
            .filter_map(|b| p.rows_of(b).last())
            .filter(|r| r.order.is_some_and(|o| o > 0.0))
            .map(|r| r.error)
            .fold(0.0, f64::max);
        for (a, b, diff, est) in agreement(p) {
            let verdict = if diff <= est { "agree" } else { "DISAGREE" };
            s += &format!(
                "{a} vs {b}: final values differ by {diff:.2e}, error estimates sum to {est:.2e}: \
                 {verdict}\n"
            );
        }
        if target <= 0.0 {
            continue;
        }
        s += &format!("dof and seconds for the error {target:.2e}:");
        for (b, hit) in p.cost_at_error(target) {
            match hit {
                Some((dof, sec)) => s += &format!("  {b} {dof:.0} dof {sec:.3} s;"),
                None => s += &format!("  {b} -;"),
            }
        }
        s += "\n";
    }
    s
}

/// Writes `crosscheck.json`, `crosscheck.csv` and `crosscheck_<problem>.png` into `dir`.
pub fn write_outputs(dir: &Path, report: &CrossReport) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    anisomesh::io::atomic_write(&dir.join("crosscheck.json"), |w| {
        serde_json::to_writer_pretty(&mut *w, report).map_err(std::io::Error::from)?;
        writeln!(w)
    })?;
    anisomesh::io::atomic_write(&dir.join("crosscheck.csv"), |w| {
        writeln!(
            w,
            "problem,backend,resolution,dof,error,order,seconds,value"
        )?;
        for p in &report.problems {
            for r in &p.rows {
                let o = r.order.map_or(String::new(), |o| format!("{o}"));
                let v = r.value.map_or(String::new(), |v| format!("{v}"));
                writeln!(
                    w,
                    "{},{},{},{},{},{},{},{}",
                    p.name, r.backend, r.resolution, r.dof, r.error, o, r.seconds, v
                )?;
            }
        }
        Ok(())
    })?;
    for p in &report.problems {
        let series = p
            .backends()
            .iter()
            .map(|n| Series {
                name: n.to_string(),
                points: p.rows_of(n).map(|r| (r.dof as f64, r.error)).collect(),
                show_fit_slope: true,
                ..Series::default()
            })
            .collect();
        let plot = LogLogPlot {
            title: format!("{}: {}", p.name, p.error_measure),
            x_label: "degrees of freedom".into(),
            y_label: "error".into(),
            series,
            ..LogLogPlot::default()
        };
        loglog_png(&dir.join(format!("crosscheck_{}.png", p.name)), &plot)?;
    }
    Ok(())
}
