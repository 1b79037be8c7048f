//! The cross-check: each problem through every back end that can take it, one table per problem
//! (back end, degrees of freedom, error, observed order, seconds), written as `crosscheck.json`,
//! `crosscheck.csv` and one log-log figure of error against degrees of freedom per problem.
//!
//! Problems ([`problems`]): the circle shrinking by curvature (`R(t) = √(R0² − 2t)`) through the
//! level-set back ends of [`level_set_backends`] and the parametric curves of 002; the sphere
//! shrinking by mean curvature (`R(t) = √(R0² − 4t)`) with parametric P1 and P2 surfaces; the
//! interface curvature of a circle and of an ellipse given by a non-distance implicit function;
//! Zalesak's slotted disk after one revolution (area and perimeter errors) through the level-set
//! back ends.
//! The order of a row is `log(e_prev / e) / log(h_prev / h)` against the previous row of the
//! same back end, `h` the resolution (the mesh size the back end was built with, the arc length
//! of a curve's element, `V^{-1/2}` on a surface).

mod problems;

use crate::app::plot::{loglog_png, LogLogPlot, Series};
use anisomesh::backends::{AdaptedBackend, BuildSpec, LevelSetBackend, D2};
use anisomesh::error::{Error, Result};
use serde::Serialize;
use std::path::Path;

pub use problems::{circle_mcf, curvature, sphere_mcf, zalesak};

/// Builds a 2D level-set back end of one kind from a [`BuildSpec`].
pub type Build2 = Box<dyn Fn(&BuildSpec<'_, D2>) -> Result<Box<dyn LevelSetBackend<D2>>>>;

/// The 2D level-set back ends the cross-check runs: adding one is one line here.
pub fn level_set_backends() -> Vec<(&'static str, Build2)> {
    vec![(
        "adapted",
        Box::new(|s| Ok(Box::new(AdaptedBackend::build(s)?) as Box<dyn LevelSetBackend<D2>>)),
    )]
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

/// Runs every problem; `progress` hears a line per finished run.
pub fn run(res: Resolution, progress: &mut dyn FnMut(&str)) -> Result<CrossReport> {
    let backends = level_set_backends();
    let mut problems = vec![
        circle_mcf(res, &backends, progress)?,
        sphere_mcf(res, progress)?,
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
        writeln!(w, "problem,backend,resolution,dof,error,order,seconds")?;
        for p in &report.problems {
            for r in &p.rows {
                let o = r.order.map_or(String::new(), |o| format!("{o}"));
                writeln!(
                    w,
                    "{},{},{},{},{},{},{}",
                    p.name, r.backend, r.resolution, r.dof, r.error, o, r.seconds
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
