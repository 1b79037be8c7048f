//! `anisomesh dtgrid texture` and `anisomesh dtgrid obj-mcf`: a Turing reaction–diffusion
//! texture on a triangulated surface (000 §4.1) and mean curvature motion of that surface
//! (000 §2.4), both on a narrow band built from the surface's exact signed distance.

use crate::app::repro::dtgrid_obj as repro;
use anisomesh::backends::dtgrid::mcf::McfOptions;
use anisomesh::backends::dtgrid::reaction::Turing;
use anisomesh::backends::dtgrid::scheme::Bc;
use anisomesh::Result;
use clap::Args;
use std::path::PathBuf;

/// Options of `dtgrid texture`.
#[derive(Debug, Args)]
pub struct TextureArgs {
    /// A closed triangulated surface (OBJ); placed in (−½, ½)³.
    #[arg(long, default_value = "meshes/star.obj")]
    obj: PathBuf,
    /// Grid nodes per side.
    #[arg(long, default_value_t = 129)]
    n: usize,
    /// Band half-width j in cells.
    #[arg(long, default_value_t = 1)]
    band: usize,
    /// Time steps.
    #[arg(long, default_value_t = 300)]
    steps: usize,
    /// Time step (the reaction is explicit: c_s·τ well below 1).
    #[arg(long, default_value_t = 1.0)]
    tau: f64,
    /// natural or transparent (000 §4.1 uses transparent; with the explicit boundary flux it
    /// diverges in long runs, see docs/dtgrid_surfaces.md).
    #[arg(long, default_value = "natural")]
    bc: String,
    /// Diffusion coefficient of a (default: 000 Fig. 4.1's 2.5e-7 scaled by (h/0.00102)²).
    #[arg(long)]
    ca: Option<f64>,
    /// Diffusion coefficient of b (default: 000 Fig. 4.1's 6.3e-8 scaled by (h/0.00102)²).
    #[arg(long)]
    cb: Option<f64>,
    /// Reaction rate c_s.
    #[arg(long, default_value_t = 0.05)]
    cs: f64,
    /// Seed of the random β = 12 ± 0.4.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Output directory.
    #[arg(short, long, default_value = "out/dtgrid")]
    output: PathBuf,
}

/// Options of `dtgrid obj-mcf`.
#[derive(Debug, Args)]
pub struct ObjMcfArgs {
    /// A closed triangulated surface (OBJ); placed in (−½, ½)³.
    #[arg(long, default_value = "meshes/star.obj")]
    obj: PathBuf,
    /// Grid nodes per side.
    #[arg(long, default_value_t = 65)]
    n: usize,
    /// Band half-width j in cells.
    #[arg(long, default_value_t = 1)]
    band: usize,
    /// Most solves per step (1: no inner iteration).
    #[arg(long, default_value_t = 5)]
    inner: usize,
    /// Time step (default h²).
    #[arg(long)]
    tau: Option<f64>,
    /// Final time (in the placed coordinates).
    #[arg(long, default_value_t = 0.005)]
    t_end: f64,
    /// Frames drawn (first and last included).
    #[arg(long, default_value_t = 5)]
    frames: usize,
    /// Output directory.
    #[arg(short, long, default_value = "out/dtgrid")]
    output: PathBuf,
}

/// Runs `dtgrid texture`.
pub fn texture(a: TextureArgs) -> Result<()> {
    let lat = anisomesh::backends::dtgrid::lattice::Lattice::unit(a.n)?;
    let base = Turing::paper_at(lat.h);
    let params = Turing {
        cs: a.cs,
        ca: a.ca.unwrap_or(base.ca),
        cb: a.cb.unwrap_or(base.cb),
        seed: a.seed,
        ..base
    };
    let r = repro::texture(&repro::TextureOptions {
        obj: a.obj,
        n: a.n,
        j: a.band,
        steps: a.steps,
        tau: a.tau,
        bc: Bc::parse(&a.bc)?,
        params,
        output: a.output.clone(),
    })?;
    let c = r.input.centre;
    println!(
        "{}: {} triangles ({} reoriented), placed by x -> (x - ({:.4}, {:.4}, {:.4})) * {:.5}",
        r.input.file, r.input.triangles, r.input.flipped_triangles, c[0], c[1], c[2], r.input.scale
    );
    println!(
        "{}³ grid, j = {}, {} band nodes; c_s = {}, c_a = {:.3e}, c_b = {:.3e}, α = {}, β = {} ± {}",
        r.n, r.band, r.nodes, params.cs, params.ca, params.cb, params.alpha, params.beta,
        params.beta_spread
    );
    println!(
        "{} steps of τ = {} ({} conditions, {} CG iterations): a in [{:.4}, {:.4}], mean {:.4}, \
         variance {:.4e}; band {:.2} s, steps {:.2} s",
        r.steps,
        r.tau,
        r.bc,
        r.cg_iterations,
        r.a.min,
        r.a.max,
        r.a.mean,
        r.a.variance,
        r.seconds_band,
        r.seconds_steps
    );
    println!(
        "wrote {}/dtgrid_texture.{{json,vtu,png}}",
        a.output.display()
    );
    Ok(())
}

/// Runs `dtgrid obj-mcf`.
pub fn obj_mcf(a: ObjMcfArgs) -> Result<()> {
    let r = repro::obj_mcf(&repro::ObjMcfOptions {
        obj: a.obj,
        n: a.n,
        mcf: McfOptions {
            j: a.band,
            inner: a.inner,
            ..McfOptions::default()
        },
        tau: a.tau,
        t_end: a.t_end,
        frames: a.frames,
        output: a.output.clone(),
    })?;
    let c = r.input.centre;
    println!(
        "{}: {} triangles ({} reoriented), placed by x -> (x - ({:.4}, {:.4}, {:.4})) * {:.5}",
        r.input.file, r.input.triangles, r.input.flipped_triangles, c[0], c[1], c[2], r.input.scale
    );
    println!(
        "placed triangulation: volume {:.6}, area {:.6}",
        r.input.volume, r.input.area
    );
    println!(
        "mean curvature motion, {}³ grid, j = {}, {} conditions, τ = {:.3e}, {} steps, {:.2} \
         solves per step, {:.1} s",
        r.n, r.band, r.bc, r.tau, r.steps, r.mean_solves, r.seconds
    );
    println!("{:>9} {:>10} {:>10} {:>8}", "t", "volume", "area", "nodes");
    for s in r.samples.iter().filter(|s| r.frame_times.contains(&s.t)) {
        println!(
            "{:>9.5} {:>10.6} {:>10.6} {:>8}",
            s.t, s.volume, s.area, s.nodes
        );
    }
    println!(
        "wrote {}/dtgrid_obj_mcf.{{json,png}} and {} frames",
        a.output.display(),
        r.frame_times.len()
    );
    Ok(())
}
