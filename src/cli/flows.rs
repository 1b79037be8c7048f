//! The benchmark-flow commands: `zalesak` and `reinit` (thin wrappers over `anisomesh::bench`).

use anisomesh::bench::{convergence, couette, couette_sweep, reinit, zalesak};
use anisomesh::Result;
use clap::Args;
use std::path::PathBuf;

/// Options of `anisomesh zalesak` (defaults: 004 §5.1 and the tuned metric of
/// `bench::zalesak::ZalesakOptions::default`).
#[derive(Debug, Args)]
pub struct ZalesakArgs {
    /// Also run a uniform mesh and an isotropic adapted mesh of similar vertex count.
    #[arg(long)]
    compare: bool,
    /// Measure the error sources separately (representation, feet, transfer, redistancing).
    #[arg(long)]
    sources: bool,
    /// Restore the initial area after each period (004 §5.1 mass correction).
    #[arg(long)]
    mass_correction: bool,
    /// Geometric redistancing (004 §2.2) after each period.
    #[arg(long)]
    redistance: bool,
    /// Periods per revolution (16 = steps of pi/8).
    #[arg(long, default_value_t = 16)]
    periods: usize,
    /// Limit the L2-projected values to the range of the old field at the feet (on/off).
    #[arg(long)]
    limit: Option<bool>,
    /// Smallest mesh size.
    #[arg(long)]
    hmin: Option<f64>,
    /// hmax / hmin.
    #[arg(long)]
    stretching: Option<f64>,
    /// Interface error bound of 004 eq. (6).
    #[arg(long)]
    eps: Option<f64>,
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
    /// Fixed-point tolerance on the mean L1 change of u^{n+1}.
    #[arg(long)]
    fixed_point_tol: Option<f64>,
    /// Adaptations of the initial mesh.
    #[arg(long)]
    initial_rounds: Option<usize>,
    /// Split/collapse cycle cap of each adaptation.
    #[arg(long)]
    max_cycles: Option<usize>,
    /// Output directory (zalesak.json, zalesak.csv, figures).
    #[arg(short, long, default_value = "out")]
    output: PathBuf,
}

/// Runs the Zalesak rotation and prints its table.
pub fn zalesak(a: ZalesakArgs) -> Result<()> {
    let d = zalesak::ZalesakOptions::default();
    let (mut hmin, mut stretching) = match d.mesh {
        zalesak::ZalesakMesh::Adapted {
            hmin, stretching, ..
        } => (hmin, stretching),
        zalesak::ZalesakMesh::Uniform { .. } => (1e-3, 200.0),
    };
    hmin = a.hmin.unwrap_or(hmin);
    stretching = a.stretching.unwrap_or(stretching);
    let mut metric = d.metric;
    metric.eps = a.eps.unwrap_or(metric.eps);
    metric.band = a.band.unwrap_or(metric.band);
    metric.grade = a.grade.unwrap_or(metric.grade);
    let mut advect = d.advect.clone();
    advect.limit = a.limit.unwrap_or(advect.limit);
    let mut adapt = d.adapt.clone();
    adapt.max_cycles = a.max_cycles.unwrap_or(adapt.max_cycles);
    let opts = zalesak::ZalesakOptions {
        mesh: match a.uniform {
            Some(n) => zalesak::ZalesakMesh::Uniform { n },
            None => zalesak::ZalesakMesh::Adapted {
                hmin,
                stretching,
                isotropic: a.isotropic,
            },
        },
        metric,
        adapt,
        advect,
        initial_rounds: a.initial_rounds.unwrap_or(d.initial_rounds),
        fixed_point_iterations: a.fixed_point_iterations.unwrap_or(d.fixed_point_iterations),
        fixed_point_tol: a.fixed_point_tol.unwrap_or(d.fixed_point_tol),
        compare: a.compare,
        sources: a.sources,
        redistance: a.redistance,
        mass_correction: a.mass_correction,
        periods: a.periods,
        out_dir: Some(a.output.clone()),
        ..d
    };
    let r = zalesak::run(&opts)?;
    print!("{}", r.summary());
    println!(
        "fixed-point iterations per period: {:?}",
        r.fixed_point_iterations
    );
    println!("wrote {}", a.output.display());
    Ok(())
}

/// Options of `anisomesh reinit`.
#[derive(Debug, Args)]
pub struct ReinitArgs {
    /// Smaller levels (a run of seconds instead of minutes).
    #[arg(long)]
    quick: bool,
    /// Deepest torus level (003 Tables 8.1-8.3 use 3..=8; 7 needs ~2 GiB and minutes).
    #[arg(long, default_value_t = 5)]
    max_level_3d: u32,
    /// Values of alpha (1, 10 and the stress case 50).
    #[arg(long, value_delimiter = ',', default_values_t = vec![1u32, 10, 50])]
    alphas: Vec<u32>,
    /// Levels of the sphere volume-drift test (003 Fig. 8.4 uses 5 and 6); empty to skip.
    #[arg(long, value_delimiter = ',', default_values_t = vec![4u32])]
    drift_levels: Vec<u32>,
    /// Repeated redistancings of the drift test (003: 100).
    #[arg(long, default_value_t = 100)]
    reps: usize,
    /// Output directory (reinit.json and plots).
    #[arg(short, long, default_value = "out")]
    output: PathBuf,
}

/// Runs the redistancing experiments of 003 §8 and prints the tables beside the paper's.
pub fn reinit(a: ReinitArgs) -> Result<()> {
    let mut opts = reinit::ReinitOptions {
        out_dir: Some(a.output.clone()),
        levels_3d: (3..=a.max_level_3d).collect(),
        alphas: a.alphas,
        volume_levels: a.drift_levels,
        volume_reps: a.reps,
        ..reinit::ReinitOptions::default()
    };
    if a.quick {
        opts.levels_3d = vec![3];
        opts.levels_2d = (3..=6).collect();
        opts.alphas = vec![1, 10];
        opts.volume_levels = vec![3];
        opts.volume_reps = 10;
    }
    reinit::run(&opts)?;
    println!("wrote {}", a.output.join("reinit.json").display());
    Ok(())
}

/// Options of `anisomesh convergence`.
#[derive(Debug, Args)]
pub struct ConvergenceArgs {
    /// The shape: zalesak, circle or flower.
    #[arg(long, default_value = "zalesak")]
    shape: String,
    /// Sweep points per family (anisotropic, isotropic adapted, uniform).
    #[arg(long, default_value_t = 5)]
    points: usize,
    /// A tiny sweep (seconds).
    #[arg(long)]
    quick: bool,
    /// Instead of the sweep, the comparison of 004 §5.1 as the paper states it: the anisotropic
    /// mesh against the isotropic graded mesh with the same smallest size (hmin 0.001, eps
    /// 1e-4, several bands and gradations; about 30 s; with --quick eps 1e-2, two settings).
    #[arg(long)]
    paper_claim: bool,
    /// Instead of the sweep, anisotropy at equal interface error best against best: both
    /// families swept over their free parameters (eps, normal size and band; isotropic size and
    /// band), the Pareto front of each, and their vertex ratio at equal error; writes
    /// fronts_<shape>.csv and .png (48 meshes, about 10 s on zalesak; with --quick 8 meshes).
    #[arg(long, conflicts_with_all = ["paper_claim", "points"])]
    best_vs_best: bool,
    /// Output directory (CSV and PNG).
    #[arg(short, long, default_value = "out")]
    output: PathBuf,
}

/// Interface error versus vertex count for anisotropic, isotropic-adapted and uniform meshes.
pub fn convergence(a: ConvergenceArgs) -> Result<()> {
    if a.paper_claim {
        use anisomesh::bench::convergence_claim::{claim_table, paper_claim, CLAIM_SETTINGS};
        let (eps, settings) = if a.quick {
            (1e-2, &CLAIM_SETTINGS[..2])
        } else {
            (1e-4, &CLAIM_SETTINGS[..])
        };
        print!("{}", claim_table(&paper_claim(&a.shape, eps, settings)?));
        return Ok(());
    }
    if a.best_vs_best {
        use anisomesh::bench::convergence_fronts::{run, FrontGrid};
        let grid = if a.quick {
            FrontGrid::quick()
        } else {
            FrontGrid::full()
        };
        let r = run(&a.shape, &grid, Some(&a.output))?;
        print!("{}", r.table());
        for f in &r.files {
            println!("wrote {}", f.display());
        }
        return Ok(());
    }
    let opts = convergence::ConvergenceOptions {
        shape: a.shape,
        points: a.points,
        quick: a.quick,
        out_dir: Some(a.output),
        ..Default::default()
    };
    let r = convergence::run(&opts)?;
    print!("{}", r.table());
    Ok(())
}

/// Options of `anisomesh couette`.
#[derive(Debug, Args)]
pub struct CouetteArgs {
    /// Use a body-fitted mesh (constrained Delaunay conforming to the circle) instead of the
    /// anisotropic mesh adapted to the level set.
    #[arg(long)]
    fitted: bool,
    /// Viscosity of the cut triangles: the sign of the level set at the quadrature points
    /// instead of the harmonic mean over the exact cut areas (the default).
    #[arg(long)]
    quadrature: bool,
    /// Print the mesh-convergence table of omega (adapted meshes with both cut-element rules,
    /// fitted meshes) instead of one run.
    #[arg(long)]
    sweep: bool,
    /// With --sweep: two meshes per family (seconds).
    #[arg(long)]
    quick: bool,
    /// Output directory (couette.json, .vtu, PNGs).
    #[arg(short, long, default_value = "out")]
    output: PathBuf,
}

/// The two-phase Couette flow of 004 §5.1: angular velocity of the rigid inclusion.
pub fn couette(a: CouetteArgs) -> Result<()> {
    if a.sweep {
        let (scales, hs) = if a.quick {
            (vec![2.0, 1.0], vec![0.01, 0.005])
        } else {
            (
                vec![2.0, 1.4, 1.0, 0.7, 0.5, 0.35],
                vec![0.01, 0.005, 0.0025, 0.00125],
            )
        };
        let rows = couette_sweep::sweep(&scales, &hs)?;
        print!("{}", couette_sweep::sweep_table(&rows));
        return Ok(());
    }
    let base = if a.fitted {
        couette_sweep::fitted_options(5e-3)
    } else {
        couette::CouetteOptions::default()
    };
    let opts = couette::CouetteOptions {
        figures: true,
        interface: if a.quadrature {
            anisomesh::flows::InterfaceViscosity::Quadrature
        } else {
            anisomesh::flows::InterfaceViscosity::Harmonic
        },
        out_dir: Some(a.output.clone()),
        ..base
    };
    let r = couette::run(&opts)?;
    println!(
        "Couette ({} mesh): omega {:.7} (exact -1, |omega+1| {:.1e}), rigidity {:.1e}, {} vertices, {} Uzawa iterations, {:.2} s",
        r.mesh, r.omega, r.omega_error, r.rigidity, r.vertices, r.uzawa_iterations, r.seconds
    );
    println!("wrote {}", a.output.display());
    Ok(())
}
