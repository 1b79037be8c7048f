//! `anisomesh bench`: the speed benchmarks, with the peers beside ours in the same run.

use crate::app::repro::peers::{self, PeerKind, PeerOptions, PeerResult};
use crate::app::repro::speed::{self, SpeedOptions, SpeedRow};
use anisomesh::levelset::redistance::redistance_geometric;
use anisomesh::{DVec2, GridPattern, Mesh2, Result};
use clap::{Args, Subcommand};
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// The benchmarks.
#[derive(Debug, Subcommand)]
pub enum Bench {
    /// Adaptation speed: a 100 x 100 grid of [-2, 2]^2 carrying the eq. (6) metric of the
    /// Zalesak disk with eps = hmin, adapted as `anisomesh adapt --input BG.mesh --sol M.sol`
    /// (one thread: RAYON_NUM_THREADS=1).
    Speed(SpeedArgs),
    /// anisomesh against mmg2d_O3 and FreeFem++ BAMG on the same problem, same run: the
    /// accuracy sweep (error against vertex count) and the speed case.
    Peers(PeersArgs),
    /// Geometric redistancing speed (004 §2.2): an n x n grid of [-1, 1]^2 and four circles.
    Redistance(RedistanceArgs),
    /// DT-Grid storage (000 §3): memory and build time of a sphere band, a streaming cell
    /// pass, and OpenVDB holding the same voxels in the same run.
    Band(crate::app::repro::band_memory::BandArgs),
    /// Exact signed distance to a triangulated surface: hierarchy build and query speed on an
    /// icosphere, checked against the sphere within the chord error.
    SurfaceDistance(crate::app::repro::surface_distance::SurfaceDistanceArgs),
    /// Tetrahedral adaptation speed: UGAWG cube-linear scaled to each requested vertex count,
    /// anisomesh and mmg3d_O3 on the same metric in the same run (CPU seconds, vertices per
    /// second, edges in range, worst mean ratio). One thread: RAYON_NUM_THREADS=1.
    Tet(TetArgs),
    /// Accuracy per vertex on the 004 star surface: `adapt --dim 3 --shape star` and mmg3d_O3
    /// `-ls -hausd` on Kuhn cubes in the same run, both measured against the exact surface
    /// (distances both ways, volume error). One thread: RAYON_NUM_THREADS=1.
    Star(StarArgs),
}

/// Options of `anisomesh bench star`.
#[derive(Debug, Args)]
pub struct StarArgs {
    /// Our eq. (6) setting (without --hmin: 5 eps, at most 0.01; without --band: hmin / 2).
    #[command(flatten)]
    metric: super::metric_args::MetricArgs,
    /// Cells per side of mmg3d's Kuhn input meshes of [-1, 1]^3 (comma-separated).
    #[arg(long, value_delimiter = ',', default_values_t = vec![64])]
    cubes: Vec<usize>,
    /// mmg3d's -hausd.
    #[arg(long, default_value_t = 1e-3)]
    hausd: f64,
    /// Without mmg3d.
    #[arg(long)]
    no_mmg3d: bool,
    /// Time limit of each mmg3d run, in seconds.
    #[arg(long, default_value_t = 3600)]
    timeout: u64,
    /// Output directory (the meshes, bench_star.json, bench_star.csv).
    #[arg(short, long, default_value = "out/bench_star")]
    output: PathBuf,
}

/// Options of `anisomesh bench tet`.
#[derive(Debug, Args)]
pub struct TetArgs {
    /// The vertex counts (comma-separated).
    #[arg(long, value_delimiter = ',', default_values_t = vec![1e4, 1e5])]
    vertices: Vec<f64>,
    /// Without mmg3d.
    #[arg(long)]
    no_mmg3d: bool,
    /// Time limit of each mmg3d run, in seconds.
    #[arg(long, default_value_t = 3600)]
    timeout: u64,
    /// Output directory (the inputs, both meshers' meshes).
    #[arg(short, long, default_value = "out/bench_tet")]
    output: PathBuf,
}

/// Options of `anisomesh bench speed`.
#[derive(Debug, Args)]
pub struct SpeedArgs {
    /// The accuracies (eps = hmin), comma-separated.
    #[arg(long, value_delimiter = ',', default_values_t = vec![1e-3, 1e-4, 3e-5, 1e-5])]
    eps: Vec<f64>,
    /// Grade the metric during the adaptation with this factor (as mmg2d's -hgrad).
    #[arg(long)]
    hgrad: Option<f64>,
    /// Log-Euclidean metric interpolation at new vertices instead of linear sizes.
    #[arg(long)]
    log_interp: bool,
}

/// Options of `anisomesh bench peers`.
#[derive(Debug, Args)]
pub struct PeersArgs {
    /// Only the accuracy sweep.
    #[arg(long, conflicts_with = "speed_only")]
    sweep_only: bool,
    /// Only the speed case.
    #[arg(long)]
    speed_only: bool,
    /// The accuracy of the speed case (eps = hmin).
    #[arg(long, default_value_t = 1e-5)]
    speed_eps: f64,
    /// A small sweep (two eps, coarse background, two iterations) and no speed case.
    #[arg(long)]
    quick: bool,
    /// Restrict to these adapters (comma-separated: mmg2d-metric, mmg2d-ls, bamg-metric,
    /// bamg-ls, anisomesh).
    #[arg(long, value_delimiter = ',')]
    kinds: Vec<String>,
    /// Time budget of our speed-case run, in seconds.
    #[arg(long, default_value_t = 1800)]
    budget: u64,
    /// Output directory (peers_sweep.csv, peers_speed.csv, the meshes).
    #[arg(short, long, default_value = "out/peers")]
    output: PathBuf,
}

/// Options of `anisomesh bench redistance`.
#[derive(Debug, Args)]
pub struct RedistanceArgs {
    /// Cells per side of the grid.
    #[arg(long, default_value_t = 1000)]
    n: usize,
}

/// Runs one benchmark.
pub fn run(b: Bench) -> Result<()> {
    match b {
        Bench::Speed(a) => speed(a),
        Bench::Peers(a) => peers(a),
        Bench::Redistance(a) => redistance(a),
        Bench::Band(a) => crate::app::repro::band_memory::run(a),
        Bench::SurfaceDistance(a) => crate::app::repro::surface_distance::run(a),
        Bench::Tet(a) => tet(a),
        Bench::Star(a) => star(a),
    }
}

fn tet(a: TetArgs) -> Result<()> {
    println!(
        "{:<10} {:>9} {:>9} {:>9} {:>9} {:>11} {:>9} {:>9} {:>9}",
        "mesher",
        "target",
        "vertices",
        "cpu_s",
        "wall_s",
        "vertices/s",
        "in_range",
        "ugawg",
        "q_min"
    );
    let timeout = Duration::from_secs(a.timeout);
    super::bench_tet::run(&a.vertices, !a.no_mmg3d, timeout, &a.output, |r| {
        println!(
            "{:<10} {:>9.0e} {:>9} {:>9.2} {:>9.2} {:>11.0} {:>8.2}% {:>8.2}% {:>9.3}",
            r.mesher,
            r.target,
            r.vertices,
            r.cpu,
            r.wall,
            r.vertices as f64 / r.cpu,
            100.0 * r.in_range,
            100.0 * r.in_range_ugawg,
            r.quality_min
        );
    })?;
    Ok(())
}

fn star(a: StarArgs) -> Result<()> {
    let b = super::bench_star::StarBench {
        metric: a
            .metric
            .apply_tet(anisomesh::adapt::Run3Options::default().metric),
        cubes: &a.cubes,
        hausd: a.hausd,
        with_mmg3d: !a.no_mmg3d,
        timeout: Duration::from_secs(a.timeout),
        dir: &a.output,
    };
    println!(
        "{:<10} {:<26} {:>9} {:>8} {:>8}  {:>29}  {:>29}  {:>10}",
        "mesher",
        "setting",
        "vertices",
        "cpu_s",
        "wall_s",
        "exact->discrete med/p99/max",
        "discrete->exact med/p99/max",
        "vol_error"
    );
    super::bench_star::run(&b, |r| {
        let c = &r.comparison;
        let (e, d) = (&c.exact_to_discrete, &c.discrete_to_exact);
        println!(
            "{:<10} {:<26} {:>9} {:>8.1} {:>8.1}  {:>9.2e} {:>9.2e} {:>9.2e}  {:>9.2e} {:>9.2e} {:>9.2e}  {:>+10.3e}",
            r.mesher, r.setting, r.vertices, r.cpu, r.wall, e.median, e.p99, e.max, d.median,
            d.p99, d.max, c.volume_error
        );
    })?;
    println!(
        "(exact volume 0.4805422178; files in {})",
        a.output.display()
    );
    Ok(())
}

fn speed(a: SpeedArgs) -> Result<()> {
    println!(
        "{:>8} {:>10} {:>10} {:>8} {:>12} {:>8} {:>8} {:>8}",
        "eps", "vertices", "triangles", "seconds", "vertices/s", "in_range", "q_mean", "q_max"
    );
    let opts = SpeedOptions {
        log_interp: a.log_interp,
        hgrad: a.hgrad,
    };
    speed::run(&a.eps, &opts, print_speed_row)?;
    Ok(())
}

fn print_speed_row(r: &SpeedRow) {
    println!(
        "{:>8.0e} {:>10} {:>10} {:>8.2} {:>12.0} {:>8.4} {:>8.3} {:>8.2}",
        r.eps,
        r.vertices,
        r.triangles,
        r.seconds,
        r.vertices as f64 / r.seconds,
        r.quality.edge_length_in_range,
        r.quality.q_ani_mean,
        r.quality.q_ani_max
    );
    println!(
        "    cycles {} converged {} gradation {:.2} s fingerprint {:016x}",
        r.report.cycles, r.report.converged, r.report.gradation_seconds, r.fingerprint
    );
    for kind in [
        anisomesh::adapt::PassKind::Split,
        anisomesh::adapt::PassKind::Collapse,
        anisomesh::adapt::PassKind::Flip,
        anisomesh::adapt::PassKind::Smooth,
    ] {
        let (passes, n, s) = r.report.pass_totals(kind);
        println!("    {kind:?}: {passes} passes, {n} ops, {s:.3} s");
    }
}

fn print_peer(r: &PeerResult) {
    if r.is_ok() {
        println!(
            "{:<13} eps {:>7.1e}  nv {:>8}  in-range {:>5.1}%  Qmean {:>6.3}  Qmax {:>9.2}  \
             area {:>+9.2e}  perim {:>+9.2e}  haus {:>8.2e}  t {:>7.2} s (last {:.2} s, self {})",
            r.peer.slug(),
            r.eps,
            r.vertices,
            100.0 * r.edge_length_in_range,
            r.q_ani_mean,
            r.q_ani_max,
            r.area_rel_error,
            r.perimeter_rel_error,
            r.hausdorff,
            r.seconds,
            r.seconds_last,
            r.self_seconds_last
                .map(|s| format!("{s:.2} s"))
                .unwrap_or_else(|| "-".into())
        );
    } else {
        println!("{:<13} eps {:>7.1e}  {:?}", r.peer.slug(), r.eps, r.status);
    }
}

fn peers(a: PeersArgs) -> Result<()> {
    let out = a.output;
    let wanted = |k: PeerKind| a.kinds.is_empty() || a.kinds.iter().any(|s| s == k.slug());
    if !a.speed_only {
        let base = PeerOptions {
            work_dir: out.join("work"),
            ..PeerOptions::default()
        };
        let (eps, opts): (&[f64], PeerOptions) = if a.quick {
            let o = PeerOptions {
                background: 30,
                iterations: 2,
                timeout: Duration::from_secs(120),
                ..base
            };
            (&[1e-2, 4e-3], o)
        } else {
            (&[1e-2, 3e-3, 1e-3, 3e-4, 1e-4], base)
        };
        println!(
            "sweep: background {0}x{0}, {1} fixed-point iterations per peer",
            opts.background, opts.iterations
        );
        let kinds: Vec<PeerKind> = PeerKind::ALL.into_iter().filter(|&k| wanted(k)).collect();
        for r in &peers::sweep(&kinds, eps, &opts, &out)? {
            print_peer(r);
        }
        println!("wrote {}", out.join("peers_sweep.csv").display());
    }
    if !a.quick && !a.sweep_only {
        let with_mmg = wanted(PeerKind::Mmg2dMetric);
        let budget = Duration::from_secs(a.budget);
        peers::speed_case(&out, a.speed_eps, with_mmg, budget, print_peer)?;
        println!("wrote {}", out.join("peers_speed.csv").display());
    }
    Ok(())
}

fn redistance(a: RedistanceArgs) -> Result<()> {
    let n = a.n;
    let mesh = Mesh2::rectangle(
        DVec2::splat(-1.0),
        DVec2::splat(1.0),
        n,
        n,
        GridPattern::Right,
    )?;
    // Four circles of radius 0.37 centred at (±0.5, ±0.5): about 10,000 cut triangles at n = 1000.
    let r = 0.37;
    let exact = |p: &DVec2| DVec2::new(p.x.abs() - 0.5, p.y.abs() - 0.5).length() - r;
    let u: Vec<f64> = mesh.points.iter().map(exact).collect();
    let cut = mesh
        .tris
        .iter()
        .filter(|t| {
            let s = t.map(|v| u[v as usize]);
            s.iter().any(|&x| x < 0.0) && s.iter().any(|&x| x > 0.0)
        })
        .count();
    let mut best = f64::INFINITY;
    let mut d = Vec::new();
    for _ in 0..3 {
        let t0 = Instant::now();
        d = redistance_geometric(&mesh, &u)?;
        best = best.min(t0.elapsed().as_secs_f64());
    }
    let err = d
        .iter()
        .zip(&mesh.points)
        .map(|(d, p)| (d - exact(p)).abs())
        .fold(0.0, f64::max);
    println!(
        "{} vertices, {} cut triangles, {} threads: best of 3 = {:.3} s (max |d - d_exact| = {:.2e})",
        mesh.n_points(),
        cut,
        rayon::current_num_threads(),
        best,
        err
    );
    Ok(())
}
