//! The benchmark-flow commands: `zalesak` and `reinit` (thin wrappers over `crate::app::repro`).

use super::metric_args::MetricArgs;
use super::progress::Spinner;
use crate::app::repro::{convergence, couette, couette_sweep, reinit, zalesak};
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
    /// Evaluation at the feet of the characteristics: l2 (L2 projection of the transported
    /// field, 004 eq. (2), the default) or nodal (values at the feet of the vertices).
    #[arg(long, value_parser = ["l2", "nodal"])]
    form: Option<String>,
    /// Interpolation at the feet: p1 or quadratic.
    #[arg(long, value_parser = ["p1", "quadratic"])]
    interp: Option<String>,
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
    match a.form.as_deref() {
        Some("nodal") => advect.form = anisomesh::advect::Form::Nodal,
        Some(_) => advect.form = anisomesh::advect::Form::L2Projection { subdivisions: 0 },
        None => {}
    }
    match a.interp.as_deref() {
        Some("quadratic") => advect.interp = anisomesh::advect::Interpolation::QUADRATIC,
        Some(_) => advect.interp = anisomesh::advect::Interpolation::P1,
        None => {}
    }
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
    let spinner = Spinner::start("rotating the slotted disk");
    let r = zalesak::run(&opts);
    spinner.finish();
    let r = r?;
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
    /// Do not run the installed peers (mmg2d, BAMG) on the Zalesak sweep's metrics.
    #[arg(long)]
    no_peers: bool,
    /// See the kinks of the distance at the scale K hmin in the metric of the adapted families.
    #[arg(long)]
    kink: Option<f64>,
    /// Apply eq. (6) within K hmin of the interface instead of 5 eps.
    #[arg(long)]
    band: Option<f64>,
    /// Growth rate of the sizes outside the band (default 1).
    #[arg(long)]
    grade: Option<f64>,
    /// Output directory (CSV and PNG).
    #[arg(short, long, default_value = "out")]
    output: PathBuf,
}

/// Interface error versus vertex count for anisotropic, isotropic-adapted and uniform meshes.
pub fn convergence(a: ConvergenceArgs) -> Result<()> {
    if a.paper_claim {
        use crate::app::repro::convergence::claim::{claim_table, paper_claim, CLAIM_SETTINGS};
        let (eps, settings) = if a.quick {
            (1e-2, &CLAIM_SETTINGS[..2])
        } else {
            (1e-4, &CLAIM_SETTINGS[..])
        };
        let spinner = Spinner::start("adapting both mesh families");
        let rows = paper_claim(&a.shape, eps, settings);
        spinner.finish();
        print!("{}", claim_table(&rows?));
        return Ok(());
    }
    if a.best_vs_best {
        use crate::app::repro::convergence::fronts::{run, FrontGrid};
        let grid = if a.quick {
            FrontGrid::quick()
        } else {
            FrontGrid::full()
        };
        let spinner = Spinner::start("sweeping both mesh families");
        let r = run(&a.shape, &grid, Some(&a.output));
        spinner.finish();
        let r = r?;
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
        peers: !a.no_peers,
        kink_scale: a.kink,
        band_hmin: a.band,
        grade: a.grade,
    };
    let r = convergence::run(&opts)?;
    print!("{}", r.table());
    for f in &r.files {
        println!("wrote {}", f.display());
    }
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
    /// With --sweep: two meshes per family, and no large fitted solve (seconds).
    #[arg(long)]
    quick: bool,
    /// The adapted mesh's metric [defaults: eps 1e-4, hmin 0.001, hmax 0.06, band 0.001,
    /// grade 0.3]; for --fitted, hmax bounds the element size away from the circle.
    #[command(flatten)]
    metric: MetricArgs,
    /// With --fitted: the edge length on the circle.
    #[arg(long)]
    h: Option<f64>,
    /// Output directory (couette.json, .vtu, PNGs).
    #[arg(short, long, default_value = "out")]
    output: PathBuf,
}

/// The two-phase Couette flow of 004 §5.1: angular velocity of the rigid inclusion.
pub fn couette(a: CouetteArgs) -> Result<()> {
    if a.sweep {
        return couette_sweep_tables(a.quick, &a.output);
    }
    let base = if a.fitted {
        couette_sweep::fitted_options(a.h.unwrap_or(5e-3))
    } else {
        couette::CouetteOptions::default()
    };
    let base = couette::CouetteOptions {
        metric: a.metric.apply(base.metric),
        ..base
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
    let spinner = Spinner::start("solving the two-phase flow");
    let r = couette::run(&opts);
    spinner.finish();
    let r = r?;
    println!(
        "Couette ({} mesh): omega {:.7} (exact -1, |omega+1| {:.1e}), rigidity {:.1e}, {} vertices, {} Uzawa iterations, {:.2} s",
        r.mesh, r.omega, r.omega_error, r.rigidity, r.vertices, r.uzawa_iterations, r.seconds
    );
    println!("wrote {}", a.output.display());
    Ok(())
}

/// The mesh-convergence table of omega, the figure, the interface-shift table and (without
/// `quick`) the timing of a 100,000-vertex fitted solve.
fn couette_sweep_tables(quick: bool, out: &std::path::Path) -> Result<()> {
    let (scales, hs, shifts): (Vec<f64>, Vec<f64>, Vec<f64>) = if quick {
        (vec![2.0, 1.0], vec![0.01, 0.005], vec![-1e-4, 0.0, 1e-4])
    } else {
        (
            vec![2.0, 1.4, 1.0, 0.7, 0.5, 0.35],
            vec![0.01, 0.005, 0.0025, 0.00125],
            (-4..=4).map(|k| k as f64 * 1e-4).collect(),
        )
    };
    let spinner = Spinner::start("solving on the mesh sequence");
    let rows = couette_sweep::sweep(&scales, &hs);
    spinner.finish();
    let rows = rows?;
    print!("{}", couette_sweep::sweep_table(&rows));
    std::fs::create_dir_all(out).map_err(|e| anisomesh::Error::io(out, e))?;
    let png = out.join("couette_convergence.png");
    couette_sweep::sweep_png(&png, &rows)?;
    println!("wrote {}", png.display());
    println!("\nDefault adapted mesh, disk radius 0.1 + shift (mesh unchanged), omega + 1:\n");
    println!("| shift | harmonic | quadrature |\n|---|---|---|");
    let sh = couette_sweep::interface_shift(&shifts)?;
    for (d, h, q) in &sh {
        println!("| {d:+.0e} | {h:+.1e} | {q:+.1e} |");
    }
    let spread = |v: Vec<f64>| {
        v.iter().cloned().fold(f64::MIN, f64::max) - v.iter().cloned().fold(f64::MAX, f64::min)
    };
    println!(
        "\nspread of omega: harmonic {:.1e}, quadrature {:.1e}",
        spread(sh.iter().map(|r| r.1).collect()),
        spread(sh.iter().map(|r| r.2).collect())
    );
    if !quick {
        let r = couette::run(&couette_sweep::fitted_options(0.0005))?;
        println!(
            "\nfitted h = 0.0005: {} vertices, omega {:.7}, {} Uzawa its; meshing {:.2} s, \
             assembly {:.2} s, factorisation {:.2} s (L: {} entries), Uzawa {:.2} s, solve \
             total {:.2} s",
            r.vertices,
            r.omega,
            r.uzawa_iterations,
            r.mesh_seconds,
            r.assembly_seconds,
            r.factor_seconds,
            r.factor_nnz,
            r.uzawa_seconds,
            r.solve_seconds
        );
    }
    Ok(())
}
