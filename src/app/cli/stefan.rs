//! `anisomesh stefan`: the Stefan problem on the interface-fitted mesh (001 §6).

use crate::app::repro::stefan::{frank, paper};
use anisomesh::backends::fitted::{
    Anisotropy, Coefficient, StefanAdvection, StefanCurvature, StefanFlux, VelocityExtension,
};
use anisomesh::error::{Error, Result};
use clap::Args;
use std::path::PathBuf;

/// Options of `anisomesh stefan`.
#[derive(Debug, Args)]
pub struct StefanArgs {
    /// The case: frank (Frank's expanding circle against the exact solution), pentagon
    /// (001 Figs. 6.1–6.3: n = 128, dt = 2.5e-4, t-end = 0.4) or star (001 Fig. 6.4: n = 128,
    /// dt = 1e-4, t-end = 0.04, eps-c = eps-v = 0.001, anisotropy cos4).
    #[arg(long, default_value = "frank", value_parser = ["frank", "pentagon", "star"])]
    case: String,
    /// One base mesh of n x n cells (frank: instead of the refinement table 32, 64, 128, 256).
    #[arg(long)]
    n: Option<usize>,
    /// End time (frank: from t0 = 0.25; default 0.5).
    #[arg(long)]
    t_end: Option<f64>,
    /// Time step (pentagon, star; frank uses 0.2 h).
    #[arg(long)]
    dt: Option<f64>,
    /// Mean surface tension coefficient eps_C of the Gibbs–Thomson relation (001 (6.2)).
    #[arg(long)]
    eps_c: Option<f64>,
    /// Mean kinetic coefficient eps_V of (6.2).
    #[arg(long)]
    eps_v: Option<f64>,
    /// Angular dependence of eps_C and eps_V: none, sin4 ((8/3) sin^4(2(theta - phase))) or
    /// cos4 (1 - cos 4(theta + phase)).
    #[arg(long, value_parser = ["none", "sin4", "cos4"])]
    anisotropy: Option<String>,
    /// Phase angle of the anisotropy in degrees (default 45 for sin4, 0 for cos4).
    #[arg(long)]
    phase: Option<f64>,
    /// Velocity extension: harmonic (001 §3, the default: stable in every case), ls (least
    /// squares with the gradient-jump rows, 001 §3: unstable without surface tension) or
    /// averaged (length-weighted mean over 3h).
    #[arg(long, default_value = "harmonic", value_parser = ["ls", "harmonic", "averaged"])]
    extension: String,
    /// One-sided gradients of the Stefan condition v_n = -[dT/dn] (001 (6.4)): quadratic
    /// (least-squares quadratic per side over two rings, second order; the default for frank) or
    /// p1 (area-weighted mean of the P1 gradients, first order; the default for pentagon, star).
    /// residual (the heat the heat step supplied at each interface vertex per unit length and
    /// time: the front's latent heat balances it, conserving the energy).
    #[arg(long, value_parser = ["p1", "quadratic", "residual"])]
    flux: Option<String>,
    /// Transfer of the temperature from the fitted mesh to the base mesh (pentagon, star):
    /// plain (the base vertices keep their values) or conservative (the heat of the kink
    /// across the interface, which the plain restriction cuts off, given back to the vertices of
    /// the cut triangles: the same heat content on both meshes).
    #[arg(long, default_value = "plain", value_parser = ["plain", "conservative"])]
    transfer: String,
    /// With --flux residual: passes of the conservative smoothing of the residuals along the
    /// interface.
    #[arg(long, default_value_t = 8)]
    smoothing_passes: usize,
    /// Curvature of the Gibbs–Thomson relation (pentagon, star): fit (least-squares parabola
    /// through the interface vertices within 3h along the interface, the default) or averaging
    /// (001 (5.2) at the base vertices interpolated onto the interface, as 001 §6).
    #[arg(long, default_value = "fit", value_parser = ["fit", "averaging"])]
    curvature: String,
    /// Redistancing after each step (pentagon, star): keep (the moved level set kept at the ends
    /// of the cut edges, only the other vertices redistanced, so the interface does not move; the
    /// default) or all (every vertex, which shrinks convex parts by O(h² κ) per step, a
    /// numerical surface tension).
    #[arg(long, default_value = "keep", value_parser = ["keep", "all"])]
    redistance: String,
    /// Level-set update (pentagon, star): levelset (phi -= dt v |grad phi|, the level-set
    /// equation of 001 (1.5)) or plain (phi -= dt v, exact for a signed distance).
    #[arg(long, default_value = "plain", value_parser = ["plain", "levelset"])]
    advection: String,
    /// The seed's size (pentagon: circumradius, default 0.1; star: mean radius, default 0.2).
    #[arg(long)]
    seed_radius: Option<f64>,
    /// With --redistance keep: every M-th step redistances every vertex (0: never).
    #[arg(long, default_value_t = 0)]
    full_redistance_every: usize,
    /// Output directory (stefan.json, stefan.csv, figures).
    #[arg(short, long, default_value = "out")]
    output: PathBuf,
}

fn extension(a: &StefanArgs, h: f64) -> VelocityExtension {
    match a.extension.as_str() {
        "averaged" => VelocityExtension::Averaged { smoothing: 3.0 * h },
        "ls" => VelocityExtension::LeastSquares,
        _ => VelocityExtension::Harmonic,
    }
}

fn flux(a: &StefanArgs) -> StefanFlux {
    match a.flux.as_deref() {
        Some("quadratic") => StefanFlux::Quadratic,
        Some("residual") => StefanFlux::Residual {
            smoothing_passes: a.smoothing_passes,
        },
        Some(_) => StefanFlux::P1Mean,
        None if a.case == "frank" => StefanFlux::Quadratic,
        None => StefanFlux::P1Mean,
    }
}

/// Runs the case, prints its table and writes the report.
pub fn run(a: StefanArgs) -> Result<()> {
    if a.case != "frank" {
        return paper_case(&a);
    }
    let t_end = a.t_end.unwrap_or(0.5);
    let ns = match a.n {
        Some(n) => vec![n],
        None => vec![32, 64, 128, 256],
    };
    // The averaging length is 3 h of each mesh (h = 4/n); the variant carries it per run.
    let mut rows = Vec::new();
    for &n in &ns {
        let ext = extension(&a, 4.0 / n as f64);
        let mut row = frank::run(&[n], t_end, ext, flux(&a))?.remove(0);
        if let Some(prev) = rows.last() {
            let prev: &frank::FrankRow = prev;
            row.order =
                (prev.radius_error / row.radius_error).ln() / (n as f64 / prev.n as f64).ln();
        }
        rows.push(row);
    }
    println!(
        "Frank's circle, S0 = {}, t {} -> {}, (-2, 2)^2, dt ~ 0.2 h, extension {}, flux {:?}",
        frank::S0,
        frank::T0,
        t_end,
        a.extension,
        flux(&a)
    );
    println!(
        "{:>5} {:>9} {:>6} {:>11} {:>11} {:>11} {:>6} {:>8} {:>6} {:>8}",
        "n", "dt", "steps", "mean |r-R|", "max |r-R|", "|RA - R|", "order", "fitted", "CG", "s"
    );
    for r in &rows {
        println!(
            "{:>5} {:>9.3e} {:>6} {:>11.3e} {:>11.3e} {:>11.3e} {:>6} {:>8} {:>6.1} {:>8.2}",
            r.n,
            r.dt,
            r.steps,
            r.radius_error,
            r.radius_error_max,
            r.area_radius_error,
            if r.order.is_finite() {
                format!("{:.2}", r.order)
            } else {
                "–".to_string()
            },
            r.fitted_vertices,
            r.cg_iterations,
            r.seconds
        );
    }
    frank::write(&a.output, &rows, t_end)?;
    println!("wrote {}", a.output.join("stefan.json").display());
    Ok(())
}

fn paper_case(a: &StefanArgs) -> Result<()> {
    let star = a.case == "star";
    let seed = if star {
        paper::Seed::Star
    } else {
        paper::Seed::Pentagon
    };
    let n = a.n.unwrap_or(128);
    let dt = a.dt.unwrap_or(if star { 1e-4 } else { 2.5e-4 });
    let t_end = a.t_end.unwrap_or(if star { 0.04 } else { 0.4 });
    let default_eps = if star { 0.001 } else { 0.0 };
    let shape = a
        .anisotropy
        .as_deref()
        .unwrap_or(if star { "cos4" } else { "none" });
    let anisotropy = match shape {
        "sin4" => Anisotropy::Sin4 {
            phase: a.phase.unwrap_or(45.0).to_radians(),
        },
        "cos4" => Anisotropy::Cos4 {
            phase: a.phase.unwrap_or(0.0).to_radians(),
        },
        _ => Anisotropy::Isotropic,
    };
    if let Some(p) = a.phase {
        if !p.is_finite() {
            return Err(Error::InvalidInput(format!(
                "stefan: --phase must be finite (got {p})"
            )));
        }
    }
    let coef = |mean: f64, what: &str| -> Result<Coefficient> {
        if mean.is_finite() && mean >= 0.0 {
            Ok(Coefficient { mean, anisotropy })
        } else {
            Err(Error::InvalidInput(format!(
                "stefan: --{what} must be finite and non-negative (got {mean})"
            )))
        }
    };
    let eps_c = coef(a.eps_c.unwrap_or(default_eps), "eps-c")?;
    let h = if star { 2.0 } else { 3.0 } / n.max(1) as f64;
    let ext = extension(a, h);
    let curvature = if a.curvature == "averaging" {
        StefanCurvature::LocalAveraging
    } else {
        StefanCurvature::InterfaceFit {
            half_width: 3.0 * h,
        }
    };
    let case = paper::Case {
        seed,
        n,
        dt,
        t_end,
        eps_c,
        eps_v: coef(a.eps_v.unwrap_or(default_eps), "eps-v")?,
        extension: ext,
        flux: flux(a),
        curvature,
        keep_interface: a.redistance == "keep",
        full_redistance_every: a.full_redistance_every,
        conservative_transfer: a.transfer == "conservative",
        advection: if a.advection == "levelset" {
            StefanAdvection::LevelSet
        } else {
            StefanAdvection::Plain
        },
        seed_radius: a.seed_radius.unwrap_or(if star {
            paper::STAR_RADIUS
        } else {
            paper::SEED_RADIUS
        }),
        snapshots: if star { 4 } else { 8 },
    };
    let rep = paper::run(&case)?;
    println!(
        "{} seed, {n} x {n} cells, dt = {dt}, {} steps, eps_C = {}, eps_V = {}, extension {}, \
         flux {}, curvature {}, redistance {}",
        a.case,
        rep.steps,
        rep.eps_c,
        rep.eps_v,
        rep.extension,
        rep.flux,
        rep.curvature,
        a.redistance
    );
    println!(
        "{:>7} {:>6} {:>10} {:>8} {:>9} {:>8} {:>8} {:>8} {:>6} {:>4}",
        "t", "step", "area", "length", "energy", "fitted", "max vn", "max |T|", "ext", "CG"
    );
    for s in &rep.snapshots {
        println!(
            "{:>7.4} {:>6} {:>10.4e} {:>8.3} {:>9.2e} {:>8} {:>8.3} {:>8.2e} {:>6} {:>4}",
            s.time,
            s.step,
            s.area,
            s.interface_length,
            s.energy_drift,
            s.fitted_vertices,
            s.max_vn,
            s.max_interface_temperature,
            s.extension_unknowns,
            s.cg_iterations
        );
    }
    println!(
        "energy balance from t = 0: heat in transfer to the fitted mesh, at the interface \
         (of it by the interface values), in transfer back; the front's latent heat; area by \
         snapping, advection, redistancing"
    );
    println!(
        "{:>7} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}",
        "t", "in", "iface", "assign", "out", "front", "snap", "advect", "redist"
    );
    for s in &rep.snapshots {
        let b = &s.budget;
        println!(
            "{:>7.4} {:>9.2e} {:>9.2e} {:>9.2e} {:>9.2e} {:>9.2e} {:>9.2e} {:>9.2e} {:>9.2e}",
            s.time,
            b.transfer_in,
            b.interface_heat,
            b.assignment_heat,
            b.transfer_out,
            b.front_heat,
            b.area_snap,
            b.area_advection,
            b.area_redistance
        );
    }
    println!("{:.1} s", rep.seconds);
    paper::write(&a.output, &a.case, &rep)?;
    println!(
        "wrote {} and {}",
        a.output.join("stefan.json").display(),
        a.output
            .join("figures")
            .join(format!("{}.png", a.case))
            .display()
    );
    Ok(())
}
