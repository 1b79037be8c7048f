//! Frank's expanding circle (S0 = 1.56) in (−2, 2)² from t0 = 0.25 (R = S0 √t0 = 0.78) to t1:
//! the Stefan loop of [`anisomesh::backends::fitted::stefan_step`] on uniform n × n base meshes
//! with Δt ≈ 0.2 h (a chosen velocity extension and one-sided gradient of the Stefan condition), the temperature initialised from the exact solution and held at the exact
//! value on the outer boundary (Dirichlet). Reported per mesh: the mean and largest
//! `||p| − R(t)|` over the interface vertices and `|√(A/π) − R(t)|` at t1, with the observed order
//! between successive meshes; the radius against time for the figure.

use crate::app::plot::{lines_png, LinesPlot, Series, SeriesStyle};
use anisomesh::backends::fitted::{
    circle_deviation, stefan_step, StefanFlux, StefanOptions, StefanState, VelocityExtension,
};
use anisomesh::error::{Error, Result};
use anisomesh::flows::stefan::FrankCircle;
use anisomesh::geom::DVec2;
use anisomesh::io::atomic_write;
use anisomesh::mesh::{GridPattern, Mesh2};
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// The growth constant of the run.
pub const S0: f64 = 1.56;
/// Start time.
pub const T0: f64 = 0.25;

/// One mesh of the refinement table.
#[derive(Debug, Clone, Serialize)]
pub struct FrankRow {
    /// Cells per side of the base mesh.
    pub n: usize,
    /// Time step.
    pub dt: f64,
    /// Steps taken.
    pub steps: usize,
    /// Mean `||p| − R(t1)|` over the interface vertices.
    pub radius_error: f64,
    /// Largest `||p| − R(t1)|`.
    pub radius_error_max: f64,
    /// `|√(A/π) − R(t1)|`.
    pub area_radius_error: f64,
    /// Observed order of `radius_error` against the previous row (NaN on the first).
    pub order: f64,
    /// Largest fitted-mesh vertex count over the steps.
    pub fitted_vertices: usize,
    /// Largest `|v_n|` at the last step.
    pub max_vn: f64,
    /// Mean CG iterations per heat step.
    pub cg_iterations: f64,
    /// Wall time of the run, seconds.
    pub seconds: f64,
    /// (t, √(A/π)) after each step.
    pub history: Vec<(f64, f64)>,
}

/// Runs one mesh.
pub fn run_one(
    n: usize,
    t1: f64,
    extension: VelocityExtension,
    flux: StefanFlux,
) -> Result<FrankRow> {
    if n < 4 || !(t1.is_finite() && t1 > T0) {
        return Err(Error::InvalidInput(format!(
            "Frank's circle: need n >= 4 and a finite end time above {T0} (got n = {n}, t1 = {t1})"
        )));
    }
    let base = Mesh2::rectangle(
        DVec2::new(-2.0, -2.0),
        DVec2::new(2.0, 2.0),
        n,
        n,
        GridPattern::UnionJack,
    )?;
    let fc = FrankCircle::new(S0)?;
    let h = 4.0 / n as f64;
    let steps = ((t1 - T0) / (0.2 * h)).ceil() as usize;
    let dt = (t1 - T0) / steps as f64;
    let r0 = fc.radius(T0);
    let mut state = StefanState::new(
        base.points.iter().map(|p| p.length() - r0).collect(),
        base.points
            .iter()
            .map(|p| fc.temperature(p.length(), T0))
            .collect(),
        T0,
    );
    let bc = |p: DVec2, t: f64| fc.temperature(p.length(), t);
    let mut opts = StefanOptions::new(dt, h);
    opts.extension = extension;
    opts.flux = flux;
    opts.boundary = Some(&bc);
    let start = Instant::now();
    let (mut fitted, mut cg, mut max_vn) = (0usize, 0usize, 0.0);
    let mut history = vec![(T0, circle_deviation(&base, &state.phi, r0)?.2)];
    for _ in 0..steps {
        let rep = stefan_step(&base, &mut state, &opts)?;
        fitted = fitted.max(rep.fitted_vertices);
        cg += rep.cg_iterations;
        max_vn = rep.max_vn;
        let r = fc.radius(state.time);
        history.push((state.time, circle_deviation(&base, &state.phi, r)?.2));
    }
    let r = fc.radius(state.time);
    let (mean, max, ra) = circle_deviation(&base, &state.phi, r)?;
    Ok(FrankRow {
        n,
        dt,
        steps,
        radius_error: mean,
        radius_error_max: max,
        area_radius_error: (ra - r).abs(),
        order: f64::NAN,
        fitted_vertices: fitted,
        max_vn,
        cg_iterations: cg as f64 / steps as f64,
        seconds: start.elapsed().as_secs_f64(),
        history,
    })
}

/// Runs the refinement table; fills the observed orders.
pub fn run(
    ns: &[usize],
    t1: f64,
    extension: VelocityExtension,
    flux: StefanFlux,
) -> Result<Vec<FrankRow>> {
    let mut rows: Vec<FrankRow> = Vec::new();
    for &n in ns {
        let mut row = run_one(n, t1, extension, flux)?;
        if let Some(prev) = rows.last() {
            row.order =
                (prev.radius_error / row.radius_error).ln() / (n as f64 / prev.n as f64).ln();
        }
        rows.push(row);
    }
    Ok(rows)
}

/// Writes `stefan.json` (`rows`), `stefan.csv` and `frank_radius.png` (radius against time,
/// exact and computed) into `dir`.
pub fn write(dir: &Path, rows: &[FrankRow], t1: f64) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::Io {
        path: dir.to_path_buf(),
        source: e,
    })?;
    #[derive(Serialize)]
    struct Report<'a> {
        case: &'static str,
        s0: f64,
        t0: f64,
        t1: f64,
        rows: &'a [FrankRow],
    }
    let report = Report {
        case: "frank",
        s0: S0,
        t0: T0,
        t1,
        rows,
    };
    atomic_write(&dir.join("stefan.json"), |w| {
        serde_json::to_writer_pretty(&mut *w, &report).map_err(std::io::Error::other)
    })?;
    atomic_write(&dir.join("stefan.csv"), |w| {
        writeln!(w, "n,dt,steps,radius_error,radius_error_max,area_radius_error,order,fitted_vertices,cg_iterations,seconds")?;
        for r in rows {
            writeln!(
                w,
                "{},{},{},{},{},{},{},{},{},{}",
                r.n,
                r.dt,
                r.steps,
                r.radius_error,
                r.radius_error_max,
                r.area_radius_error,
                r.order,
                r.fitted_vertices,
                r.cg_iterations,
                r.seconds
            )?;
        }
        Ok(())
    })?;
    let fc = FrankCircle::new(S0)?;
    let exact: Vec<(f64, f64)> = (0..=100)
        .map(|k| {
            let t = T0 + (t1 - T0) * k as f64 / 100.0;
            (t, fc.radius(t))
        })
        .collect();
    let mut series = vec![Series {
        name: "exact S0 sqrt(t)".into(),
        points: exact,
        show_fit_slope: false,
        style: SeriesStyle::Line,
    }];
    for r in rows {
        series.push(Series {
            name: format!("n = {}", r.n),
            points: r.history.clone(),
            show_fit_slope: false,
            style: SeriesStyle::Line,
        });
    }
    lines_png(
        &dir.join("frank_radius.png"),
        &LinesPlot {
            title: "Frank's circle: radius sqrt(A/pi) against time".into(),
            x_label: "t".into(),
            y_label: "R".into(),
            series,
            ..LinesPlot::default()
        },
    )
}
