//! The solidification cases of 001 §6: a seed in an undercooled liquid, initial temperature 0
//! in the solid and −½ in the liquid (6.5)–(6.6), insulated walls (6.3), 128 × 128 cells
//! (129² base vertices).
//! - pentagon (001 Figs. 6.1–6.3): (−1.5, 1.5)², Δt = 2.5e-4 to t = 0.4, ε_V = 0 and ε_C = 0,
//!   0.001 or 0.001 (8/3) sin⁴(2(θ − 45°)). The seed's size is not given in 001; here it is the
//!   regular pentagon of circumradius 0.1 centred at the origin, a vertex on the positive y axis.
//! - star (001 Fig. 6.4): (−1, 1)², Δt = 1e-4, ε_C = ε_V = 0.001 [1 − cos 4(θ + θ₀)]. The
//!   eight-sided star is `r < 0.2 (1 + 0.25 cos 8θ)` (its size is not given in 001 either).

use crate::app::plot::{lines_png, LinesPlot, Series, SeriesStyle};
use anisomesh::backends::fitted::{
    fit, pentagon_seed, stefan_step, FitOptions, StefanAdvection, StefanBudget, StefanCurvature,
    StefanFlux, StefanOptions, StefanState, VelocityExtension,
};
use anisomesh::backends::fitted::{Anisotropy, Coefficient};
use anisomesh::error::{Error, Result};
use anisomesh::fem::p1::lumped_mass;
use anisomesh::geom::DVec2;
use anisomesh::io::atomic_write;
use anisomesh::levelset::redistance::redistance_geometric;
use anisomesh::mesh::{GridPattern, Mesh2};
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// Circumradius of the pentagon seed.
pub const SEED_RADIUS: f64 = 0.1;
/// Mean radius of the star seed.
pub const STAR_RADIUS: f64 = 0.2;
/// Relative amplitude of the star's eight arms.
pub const STAR_AMPLITUDE: f64 = 0.25;

/// The seed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Seed {
    /// Regular pentagon in (−1.5, 1.5)².
    Pentagon,
    /// Eight-armed star in (−1, 1)².
    Star,
}

/// A run of one case.
#[derive(Debug, Clone)]
pub struct Case {
    /// The seed (and domain).
    pub seed: Seed,
    /// Cells per side.
    pub n: usize,
    /// Time step.
    pub dt: f64,
    /// End time.
    pub t_end: f64,
    /// Surface tension `ε_C(θ)`.
    pub eps_c: Coefficient,
    /// Kinetic coefficient `ε_V(θ)`.
    pub eps_v: Coefficient,
    /// Velocity extension.
    pub extension: VelocityExtension,
    /// One-sided gradients of the Stefan condition.
    pub flux: StefanFlux,
    /// Curvature of the Gibbs–Thomson relation.
    pub curvature: StefanCurvature,
    /// Keep the level set at the ends of the cut edges when redistancing.
    pub keep_interface: bool,
    /// With `keep_interface`: every this many steps every vertex is redistanced (0: never).
    pub full_redistance_every: usize,
    /// The level-set update.
    pub advection: StefanAdvection,
    /// Restrict the temperature to the base mesh keeping its heat content.
    pub conservative_transfer: bool,
    /// The seed's size: the pentagon's circumradius, the star's mean radius.
    pub seed_radius: f64,
    /// Number of snapshot intervals.
    pub snapshots: usize,
}

/// A snapshot of the run.
#[derive(Debug, Clone, Serialize)]
pub struct Snapshot {
    /// Time.
    pub time: f64,
    /// Steps done.
    pub step: usize,
    /// Solid area.
    pub area: f64,
    /// Interface length.
    pub interface_length: f64,
    /// Heat content `∫ T` (lumped P1 on the base mesh).
    pub heat: f64,
    /// Energy balance `(∫ T − A) − (∫ T₀ − A₀)`: zero for the exact Stefan problem with
    /// insulated walls (latent heat 1: the solidified area warms the liquid by as much).
    pub energy_drift: f64,
    /// The terms of the energy balance summed from t = 0.
    pub budget: StefanBudget,
    /// Vertices of the fitted mesh.
    pub fitted_vertices: usize,
    /// Largest `|v_n|` of the last step.
    pub max_vn: f64,
    /// Largest `|T|` on the interface of the last step (Gibbs–Thomson).
    pub max_interface_temperature: f64,
    /// CG iterations of the last heat step.
    pub cg_iterations: usize,
    /// Unknowns of the last velocity extension.
    pub extension_unknowns: usize,
    /// Interface vertex positions.
    #[serde(skip)]
    pub interface: Vec<(f64, f64)>,
    /// Interface edges (end points).
    #[serde(skip)]
    pub edges: Vec<((f64, f64), (f64, f64))>,
}

/// The report of [`run`].
#[derive(Debug, Clone, Serialize)]
pub struct PaperReport {
    /// The seed.
    pub case: Seed,
    /// Cells per side.
    pub n: usize,
    /// Time step.
    pub dt: f64,
    /// End time.
    pub t_end: f64,
    /// Steps.
    pub steps: usize,
    /// `ε_C` as text.
    pub eps_c: String,
    /// `ε_V` as text.
    pub eps_v: String,
    /// The velocity extension.
    pub extension: String,
    /// The one-sided gradients of the Stefan condition.
    pub flux: String,
    /// The curvature of the Gibbs–Thomson relation.
    pub curvature: String,
    /// Whether redistancing kept the level set at the ends of the cut edges.
    pub keep_interface: bool,
    /// The level-set update.
    pub advection: String,
    /// Whether the temperature was restricted to the base mesh keeping its heat content.
    pub conservative_transfer: bool,
    /// The seed's size.
    pub seed_radius: f64,
    /// With `keep_interface`: every this many steps every vertex was redistanced (0: never).
    pub full_redistance_every: usize,
    /// Wall time of the loop, seconds.
    pub seconds: f64,
    /// Snapshots at t = 0 and at equal intervals.
    pub snapshots: Vec<Snapshot>,
}

/// `ε` as text.
pub fn describe(c: &Coefficient) -> String {
    match c.anisotropy {
        Anisotropy::Isotropic => format!("{}", c.mean),
        Anisotropy::Sin4 { phase } => {
            format!("{} (8/3) sin^4(2(theta - {}°))", c.mean, phase.to_degrees())
        }
        Anisotropy::Cos4 { phase } => {
            format!("{} [1 - cos 4(theta + {}°)]", c.mean, phase.to_degrees())
        }
    }
}

fn snapshot(
    base: &Mesh2,
    st: &StefanState,
    step: usize,
    last: Option<&anisomesh::backends::fitted::StefanStepReport>,
    budget: StefanBudget,
) -> Result<Snapshot> {
    let fm = fit(base, &st.phi, &FitOptions::default())?;
    let heat: f64 = lumped_mass(base)?
        .iter()
        .zip(&st.temperature)
        .map(|(m, t)| m * t)
        .sum();
    let xy = |v: u32| {
        let p = fm.mesh.points[v as usize];
        (p.x, p.y)
    };
    let edges: Vec<_> = fm
        .interface_edges()
        .into_iter()
        .map(|[a, b]| (xy(a), xy(b)))
        .collect();
    let interface = edges.iter().map(|e| e.0).collect();
    Ok(Snapshot {
        time: st.time,
        step,
        area: fm.area_inside(),
        interface_length: fm.interface_length(),
        heat,
        energy_drift: 0.0,
        budget,
        fitted_vertices: last.map_or(fm.mesh.n_points(), |r| r.fitted_vertices),
        max_vn: last.map_or(0.0, |r| r.max_vn),
        max_interface_temperature: last.map_or(0.0, |r| r.max_interface_temperature),
        cg_iterations: last.map_or(0, |r| r.cg_iterations),
        extension_unknowns: last.map_or(0, |r| r.extension_unknowns),
        interface,
        edges,
    })
}

/// The base mesh and initial level set (signed distance, negative in the seed) of `seed`.
pub fn initial(seed: Seed, n: usize, radius: f64) -> Result<(Mesh2, Vec<f64>)> {
    let half = match seed {
        Seed::Pentagon => 1.5,
        Seed::Star => 1.0,
    };
    let base = Mesh2::rectangle(
        DVec2::new(-half, -half),
        DVec2::new(half, half),
        n,
        n,
        GridPattern::UnionJack,
    )?;
    let phi = match seed {
        Seed::Pentagon => pentagon_seed(&base, radius)?,
        Seed::Star => {
            let phi0: Vec<f64> = base
                .points
                .iter()
                .map(|p| {
                    let th = p.y.atan2(p.x);
                    p.length() - radius * (1.0 + STAR_AMPLITUDE * (8.0 * th).cos())
                })
                .collect();
            redistance_geometric(&base, &phi0)?
        }
    };
    Ok((base, phi))
}

/// Runs a case.
pub fn run(c: &Case) -> Result<PaperReport> {
    let (n, dt, t_end) = (c.n, c.dt, c.t_end);
    if n < 8 || !(dt.is_finite() && dt > 0.0) || !(t_end.is_finite() && t_end > 0.0) {
        return Err(Error::InvalidInput(format!(
            "stefan: need n >= 8, dt > 0 and t_end > 0, finite (got {n}, {dt}, {t_end})"
        )));
    }
    let half = match c.seed {
        Seed::Pentagon => 1.5,
        Seed::Star => 1.0,
    };
    if !(c.seed_radius.is_finite() && c.seed_radius > 0.0 && c.seed_radius < 0.75 * half) {
        return Err(Error::InvalidInput(format!(
            "stefan: the seed radius must be positive and below {} (got {})",
            0.75 * half,
            c.seed_radius
        )));
    }
    let (base, phi) = initial(c.seed, n, c.seed_radius)?;
    let temperature = phi
        .iter()
        .map(|&f| if f < 0.0 { 0.0 } else { -0.5 })
        .collect();
    let mut st = StefanState::new(phi, temperature, 0.0);
    let width = match c.seed {
        Seed::Pentagon => 3.0,
        Seed::Star => 2.0,
    };
    let h = width / n as f64;
    let mut opts = StefanOptions::new(dt, h);
    opts.extension = c.extension;
    opts.flux = c.flux;
    opts.curvature = c.curvature;
    opts.keep_interface = c.keep_interface;
    opts.advection = c.advection;
    opts.conservative_transfer = c.conservative_transfer;
    opts.eps_c = c.eps_c;
    opts.eps_v = c.eps_v;
    let steps = (t_end / dt).round().max(1.0) as usize;
    let every = (steps / c.snapshots.max(1)).max(1);
    let start = Instant::now();
    let mut budget = StefanBudget::default();
    let mut snaps = vec![snapshot(&base, &st, 0, None, budget)?];
    for k in 1..=steps {
        opts.keep_interface =
            c.keep_interface && !(c.full_redistance_every > 0 && k % c.full_redistance_every == 0);
        let rep = stefan_step(&base, &mut st, &opts)?;
        budget = budget.add(&rep.budget);
        if k % every == 0 || k == steps {
            snaps.push(snapshot(&base, &st, k, Some(&rep), budget)?);
        }
    }
    let e0 = snaps[0].heat - snaps[0].area;
    for s in &mut snaps {
        s.energy_drift = s.heat - s.area - e0;
    }
    Ok(PaperReport {
        case: c.seed,
        n,
        dt,
        t_end,
        steps,
        eps_c: describe(&c.eps_c),
        eps_v: describe(&c.eps_v),
        extension: format!("{:?}", c.extension),
        flux: format!("{:?}", c.flux),
        curvature: format!("{:?}", c.curvature),
        keep_interface: c.keep_interface,
        advection: format!("{:?}", c.advection),
        conservative_transfer: c.conservative_transfer,
        seed_radius: c.seed_radius,
        full_redistance_every: c.full_redistance_every,
        seconds: start.elapsed().as_secs_f64(),
        snapshots: snaps,
    })
}

/// Writes `stefan.json` and `figures/<name>.png` (the interface at the snapshot times).
pub fn write(dir: &Path, name: &str, rep: &PaperReport) -> Result<()> {
    let figs = dir.join("figures");
    std::fs::create_dir_all(&figs).map_err(|e| Error::Io {
        path: figs.clone(),
        source: e,
    })?;
    atomic_write(&dir.join("stefan.json"), |w| {
        serde_json::to_writer_pretty(&mut *w, rep).map_err(std::io::Error::other)
    })?;
    atomic_write(&dir.join("interface.csv"), |w| {
        writeln!(w, "time,x0,y0,x1,y1")?;
        for s in &rep.snapshots {
            for (a, b) in &s.edges {
                writeln!(w, "{},{},{},{},{}", s.time, a.0, a.1, b.0, b.1)?;
            }
        }
        Ok(())
    })?;
    let series = rep
        .snapshots
        .iter()
        .map(|s| Series {
            name: format!("t = {:.3}", s.time),
            points: s.interface.clone(),
            show_fit_slope: false,
            style: SeriesStyle::Markers,
        })
        .collect();
    lines_png(
        &figs.join(format!("{name}.png")),
        &LinesPlot {
            title: format!(
                "{:?} seed, eps_C = {}, eps_V = {}: interface at several times",
                rep.case, rep.eps_c, rep.eps_v
            ),
            x_label: "x".into(),
            y_label: "y".into(),
            series,
            width: 800,
            height: 800,
        },
    )
}
