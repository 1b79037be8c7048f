//! `anisomesh advect --compare`: anisotropic, isotropic adapted and uniform meshes at several
//! accuracies on one case, the error at `t = T` (symmetric-difference area against the initial
//! shape) against the mean vertex count, and the isotropic / anisotropic vertex ratio at equal
//! error between the best meshes of each family (the Pareto fronts, interpolated log-log as
//! `convergence --best-vs-best` does); FreeFem++ (`convect` + `adaptmesh`) in the same run.

use super::cases::Case;
use super::freefem::{self, FreeFemRun};
use super::run::{run, AdvectReport, Family, RunSettings};
use crate::app::plot::{loglog_png, Series, SeriesStyle};
use crate::app::repro::convergence::gain::vertices_at_error;
use anisomesh::error::{Error, Result};
use anisomesh::io::atomic_write;
use serde::Serialize;
use std::path::Path;

/// The comparison: every run, the FreeFem++ run and the ratios at equal error.
#[derive(Debug, Clone, Serialize)]
pub struct Comparison {
    /// All runs (their series omitted in the summary).
    pub runs: Vec<AdvectReport>,
    /// The FreeFem++ run.
    pub freefem: FreeFemRun,
    /// Isotropic / anisotropic mean vertices at equal symmetric-difference error, at each
    /// anisotropic front point inside the isotropic front's error range.
    pub iso_over_aniso: Vec<(f64, f64)>,
    /// The same for uniform / anisotropic.
    pub uniform_over_aniso: Vec<(f64, f64)>,
}

/// The points `(vertices_mean, error)` of a family that no other point of it beats on both.
fn front(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut p: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|(n, e)| n.is_finite() && e.is_finite() && *e > 0.0)
        .collect();
    p.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut out: Vec<(f64, f64)> = Vec::new();
    for q in p {
        if out.last().map_or(true, |l| q.1 < l.1) {
            out.push(q);
        }
    }
    out
}

/// `(error, other / anisotropic vertices)` at each anisotropic front point inside the other
/// front's error range.
fn ratios(ani: &[(f64, f64)], other: &[(f64, f64)]) -> Vec<(f64, f64)> {
    ani.iter()
        .filter_map(|&(n, e)| vertices_at_error(other, e).map(|m| (e, m / n)))
        .collect()
}

/// Runs the comparison of `case` (default settings `base`) and writes `advect_compare.json`,
/// `advect_compare.csv` and `advect_compare.png` into `dir`.
pub fn compare(case: &Case, base: &RunSettings, dir: &Path, quick: bool) -> Result<Comparison> {
    let scale = |s: &RunSettings, f: f64| -> RunSettings {
        let mut r = s.clone();
        r.sizes = [s.sizes[0] * f, s.sizes[1], s.sizes[2] * f, s.sizes[3] * f];
        r.snapshot_times = Vec::new();
        r
    };
    let (ani_f, iso_f, uni_n): (&[f64], &[f64], &[usize]) = if quick {
        (&[8.0, 4.0], &[32.0, 16.0], &[32, 64])
    } else {
        (&[4.0, 2.0, 1.0], &[32.0, 16.0, 8.0, 4.0], &[64, 128, 256])
    };
    let mut runs = Vec::new();
    for &f in ani_f {
        runs.push(run(case, &scale(base, f))?.0);
    }
    for &f in iso_f {
        let mut s = scale(base, f);
        s.family = Family::Isotropic;
        runs.push(run(case, &s)?.0);
    }
    for &n in uni_n {
        let mut s = scale(base, 1.0);
        s.family = Family::Uniform { n };
        runs.push(run(case, &s)?.0);
    }
    let ff_sizes = [base.sizes[2] * 8.0, base.sizes[0] * 2.0, base.sizes[1]];
    let freefem = freefem::run(case, base.periods, ff_sizes, &dir.join("freefem"))?;
    let pts = |pick: fn(&Family) -> bool| -> Vec<(f64, f64)> {
        runs.iter()
            .filter(|r| pick(&r.family))
            .map(|r| (r.vertices_mean, r.symmetric_difference_relative()))
            .collect()
    };
    let ani = front(&pts(|f| *f == Family::Anisotropic));
    let iso = front(&pts(|f| *f == Family::Isotropic));
    let uni = front(&pts(|f| matches!(f, Family::Uniform { .. })));
    let cmp = Comparison {
        iso_over_aniso: ratios(&ani, &iso),
        uniform_over_aniso: ratios(&ani, &uni),
        runs,
        freefem,
    };
    write(dir, &cmp, [&ani, &iso, &uni])?;
    Ok(cmp)
}

fn write(dir: &Path, cmp: &Comparison, fronts: [&Vec<(f64, f64)>; 3]) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let json = serde_json::to_vec_pretty(cmp)
        .map_err(|e| Error::InvalidInput(format!("advect comparison serialisation: {e}")))?;
    atomic_write(&dir.join("advect_compare.json"), |w| w.write_all(&json))?;
    let mut csv = String::from(
        "family,vertices_mean,vertices_max,area_error,symmetric_difference_relative,hausdorff,seconds\n",
    );
    for r in &cmp.runs {
        csv.push_str(&format!(
            "{},{:.1},{},{:.4e},{:.4e},{:.4e},{:.2}\n",
            r.label(),
            r.vertices_mean,
            r.vertices_max,
            r.area_error(),
            r.symmetric_difference_relative(),
            r.hausdorff.unwrap_or(f64::NAN),
            r.seconds
        ));
    }
    let f = &cmp.freefem;
    if f.status == "ok" {
        csv.push_str(&format!(
            "freefem err {:.1e},{:.1},{},{:.4e},{:.4e},{:.4e},{:.2}\n",
            f.err,
            f.vertices_mean,
            f.vertices_max,
            (f.area_final - f.area_initial) / f.area_initial,
            f.area_symmetric_difference / f.area_initial,
            f.hausdorff,
            f.seconds
        ));
    }
    atomic_write(&dir.join("advect_compare.csv"), |w| {
        w.write_all(csv.as_bytes())
    })?;
    let names = ["anisotropic", "isotropic adapted", "uniform"];
    let mut series: Vec<Series> = names
        .iter()
        .zip(fronts)
        .map(|(n, p)| Series {
            name: n.to_string(),
            points: p.clone(),
            show_fit_slope: false,
            style: SeriesStyle::default(),
        })
        .collect();
    if f.status == "ok" {
        series.push(Series {
            name: "FreeFem++ convect + adaptmesh".into(),
            points: vec![(
                f.vertices_mean,
                f.area_symmetric_difference / f.area_initial,
            )],
            show_fit_slope: false,
            style: SeriesStyle::default(),
        });
    }
    let plot = crate::app::plot::LogLogPlot {
        title: format!(
            "{} at t = T: symmetric difference / area vs mean vertices",
            cmp.runs.first().map_or("", |r| r.case.as_str())
        ),
        x_label: "mean vertices per mesh".into(),
        y_label: "|A(T) Δ A(0)| / |A(0)|".into(),
        series,
        ..Default::default()
    };
    loglog_png(&dir.join("advect_compare.png"), &plot)
}

impl Comparison {
    /// The table of runs and the ratios.
    pub fn summary(&self) -> String {
        let mut s = format!(
            "{:<28} {:>9} {:>9} {:>11} {:>11} {:>10} {:>8}\n",
            "run", "verts", "max", "area", "symdiff", "hausdorff", "seconds"
        );
        for r in &self.runs {
            s.push_str(&format!(
                "{:<28} {:>9.0} {:>9} {:>+11.3e} {:>11.3e} {:>10.2e} {:>8.1}\n",
                r.label(),
                r.vertices_mean,
                r.vertices_max,
                r.area_error(),
                r.symmetric_difference_relative(),
                r.hausdorff.unwrap_or(f64::NAN),
                r.seconds
            ));
        }
        let f = &self.freefem;
        if f.status == "ok" {
            s.push_str(&format!(
                "{:<28} {:>9.0} {:>9} {:>+11.3e} {:>11.3e} {:>10.2e} {:>8.1}\n",
                format!("FreeFem++ err {:.1e}", f.err),
                f.vertices_mean,
                f.vertices_max,
                (f.area_final - f.area_initial) / f.area_initial,
                f.area_symmetric_difference / f.area_initial,
                f.hausdorff,
                f.seconds
            ));
        } else {
            s.push_str(&format!("FreeFem++: {}\n", f.status));
        }
        for (name, r) in [
            ("isotropic", &self.iso_over_aniso),
            ("uniform", &self.uniform_over_aniso),
        ] {
            if r.is_empty() {
                s.push_str(&format!(
                    "{name} / anisotropic vertices at equal error: the fronts' errors do not overlap\n"
                ));
            }
            for (e, q) in r {
                s.push_str(&format!(
                    "{name} / anisotropic vertices at symmetric difference {e:.2e}: {q:.2}\n"
                ));
            }
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fronts_and_ratios_at_equal_error() {
        // (vertices, error): the third point is beaten by the second.
        let a = front(&[(100.0, 1e-2), (400.0, 2.5e-3), (800.0, 3e-3)]);
        assert_eq!(a, vec![(100.0, 1e-2), (400.0, 2.5e-3)]);
        // Isotropic needs four times the vertices for the same error (slope -1).
        let i = front(&[(400.0, 1e-2), (1600.0, 2.5e-3)]);
        let r = ratios(&a, &i);
        assert_eq!(r.len(), 2);
        assert!(r.iter().all(|(_, q)| (q - 4.0).abs() < 1e-9), "{r:?}");
        assert!(ratios(&a, &front(&[(10.0, 1.0)])).is_empty());
    }
}
