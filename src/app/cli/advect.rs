//! `anisomesh advect`: any shape in any velocity field, or a built-in case (single vortex,
//! deformation, Zalesak), through `anisomesh::advect::run`.

use super::progress::Spinner;
use crate::app::repro::advect::{self as adv, Family, RunSettings};
use anisomesh::error::{Error, Result};
use anisomesh::geom::DVec2;
use clap::Args;
use std::path::PathBuf;

/// Options of `anisomesh advect`.
#[derive(Debug, Args)]
pub struct AdvectArgs {
    /// A built-in case: vortex (single vortex, T = 8), deformation (four vortices, T = 2) or
    /// zalesak (rigid rotation of the slotted disk).
    #[arg(long, conflicts_with_all = ["expr", "velocity"])]
    case: Option<String>,
    /// The initial shape: a level-set expression in x, y (negative inside).
    #[arg(long, requires = "velocity")]
    expr: Option<String>,
    /// The velocity "U(x,y,t); V(x,y,t)".
    #[arg(long, requires = "expr")]
    velocity: Option<String>,
    /// Final time (for vortex and deformation: the reversal period T).
    #[arg(long)]
    t_end: Option<f64>,
    /// The domain X0,Y0,X1,Y1 (custom shapes; default the unit square).
    #[arg(long, value_delimiter = ',', num_args = 4)]
    domain: Option<Vec<f64>>,
    /// The custom flow brings the shape back at t-end (time-reversed): measure the symmetric
    /// difference and the Hausdorff distance to the initial shape.
    #[arg(long)]
    reversed: bool,
    /// Number of periods (time steps of the transient fixed point).
    #[arg(long)]
    periods: Option<usize>,
    /// Interface error bound of 004 eq. (6).
    #[arg(long)]
    eps: Option<f64>,
    /// Smallest mesh size.
    #[arg(long)]
    hmin: Option<f64>,
    /// Largest mesh size.
    #[arg(long)]
    hmax: Option<f64>,
    /// Half-width of the band where eq. (6) applies.
    #[arg(long)]
    band: Option<f64>,
    /// Growth rate of the sizes outside the band.
    #[arg(long)]
    grade: Option<f64>,
    /// Isotropic adaptation instead of anisotropic.
    #[arg(long)]
    isotropic: bool,
    /// A fixed uniform n x n mesh instead of adaptation.
    #[arg(long)]
    uniform: Option<usize>,
    /// Maximal fixed-point iterations per period.
    #[arg(long)]
    fixed_point_iterations: Option<usize>,
    /// Restore the initial area after each period.
    #[arg(long)]
    mass_correction: bool,
    /// Geometric redistancing after each period (on/off).
    #[arg(long)]
    redistance: Option<bool>,
    /// Limited quadratic interpolation at the feet instead of P1.
    #[arg(long)]
    quadratic: bool,
    /// RK4 sub-steps of the feet per period.
    #[arg(long)]
    substeps: Option<usize>,
    /// Split/collapse cycle cap of each adaptation.
    #[arg(long)]
    max_cycles: Option<usize>,
    /// Compare anisotropic, isotropic adapted and uniform meshes at several accuracies (and
    /// FreeFem++ where installed) at equal error.
    #[arg(long)]
    compare: bool,
    /// A small comparison (coarse meshes, seconds to minutes).
    #[arg(long, requires = "compare")]
    quick: bool,
    /// Output directory (advect.json, advect.csv, advect_final.mesh/.sol/.vtu, PNG frames).
    #[arg(short, long, default_value = "out")]
    output: PathBuf,
}

/// Runs the transport and prints its summary.
pub fn run(a: AdvectArgs) -> Result<()> {
    let case = match (&a.case, &a.expr, &a.velocity) {
        (Some(name), None, None) => adv::builtin(name, a.t_end)?,
        (None, Some(e), Some(v)) => {
            let d = a.domain.clone().unwrap_or_else(|| vec![0.0, 0.0, 1.0, 1.0]);
            let t = a.t_end.ok_or_else(|| {
                Error::InvalidInput("advect: --t-end is needed with --expr".into())
            })?;
            adv::custom(
                e,
                v,
                (DVec2::new(d[0], d[1]), DVec2::new(d[2], d[3])),
                t,
                a.reversed,
            )?
        }
        (None, None, None) => adv::builtin("vortex", a.t_end)?,
        _ => {
            return Err(Error::InvalidInput(
                "advect: give either --case or both --expr and --velocity".into(),
            ))
        }
    };
    let mut s = RunSettings::for_case(&case);
    s.family = match (a.uniform, a.isotropic) {
        (Some(n), _) => Family::Uniform { n },
        (None, true) => Family::Isotropic,
        (None, false) => Family::Anisotropic,
    };
    for (slot, v) in s.sizes.iter_mut().zip([a.hmin, a.hmax, a.eps, a.band]) {
        *slot = v.unwrap_or(*slot);
    }
    s.grade = a.grade.unwrap_or(s.grade);
    s.periods = a.periods.unwrap_or(s.periods);
    s.fixed_point_iterations = a.fixed_point_iterations.unwrap_or(s.fixed_point_iterations);
    s.mass_correction = a.mass_correction;
    s.redistance = a.redistance.unwrap_or(s.redistance);
    s.quadratic = a.quadratic;
    s.substeps = a.substeps.unwrap_or(s.substeps);
    s.max_cycles = a.max_cycles.unwrap_or(s.max_cycles);
    if a.compare {
        let spinner = Spinner::start("comparing mesh families");
        let c = adv::compare::compare(&case, &s, &a.output, a.quick);
        spinner.finish();
        print!("{}", c?.summary());
        println!("wrote {}", a.output.display());
        return Ok(());
    }
    s.snapshot_times = (1..4).map(|k| case.t_end * k as f64 / 4.0).collect();
    let spinner = Spinner::start("advecting");
    let r = adv::run(&case, &s);
    spinner.finish();
    let (report, result) = r?;
    print!("{}", report.summary());
    adv::output::write_all(&a.output, &report, &result)?;
    println!("wrote {}", a.output.display());
    Ok(())
}
