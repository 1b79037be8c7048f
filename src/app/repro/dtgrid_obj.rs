//! Problems on a triangulated surface (OBJ) turned into a narrow band (000 §4): a Turing
//! reaction–diffusion texture on the fixed surface (000 §4.1, Fig. 4.1) and mean curvature
//! motion of the surface (000 §2.4, Fig. 2.5 and 4.4), with JSON reports, `.vtu` surfaces and
//! shaded PNG pictures.

use crate::app::plot::surface::{render_surfaces, SurfacePanel, View};
use anisomesh::backends::dtgrid::lattice::{Lattice, C3};
use anisomesh::backends::dtgrid::mcf::{McfOptions, McfState};
use anisomesh::backends::dtgrid::obj::{
    band_of_shape, interpolate, read_shape, welded_zero_level, Placement,
};
use anisomesh::backends::dtgrid::reaction::{Turing, TuringState};
use anisomesh::backends::dtgrid::scheme::Bc;
use anisomesh::backends::dtgrid::{Band, DtGrid};
use anisomesh::error::{Error, Result};
use anisomesh::levelset::triangulated::TriangulatedShape;
use anisomesh::levelset::TriangleSurface;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;

type B = DtGrid<C3>;

/// The surface as read and placed in the grid.
#[derive(Debug, Clone, Serialize)]
pub struct InputReport {
    /// The OBJ file.
    pub file: String,
    /// Its triangles.
    pub triangles: usize,
    /// Triangles whose orientation the validation reversed.
    pub flipped_triangles: usize,
    /// Connected components.
    pub components: usize,
    /// The placement `x ↦ (x − centre)·scale`.
    pub centre: [f64; 3],
    /// The placement's scale.
    pub scale: f64,
    /// The enclosed volume of the placed triangulation (compare with the zero level's).
    pub volume: f64,
    /// The area of the placed triangulation.
    pub area: f64,
}

fn load(obj: &Path, lat: &Lattice, j: usize) -> Result<(TriangulatedShape, InputReport)> {
    let raw = read_shape(obj)?;
    let place = Placement::fit(raw.surface(), lat, j)?;
    let shape = TriangulatedShape::new(
        place.surface(raw.surface()).points,
        raw.surface().triangles.clone(),
    )?;
    let c = place.centre;
    let rep = InputReport {
        file: obj.display().to_string(),
        triangles: raw.surface().triangles.len(),
        flipped_triangles: raw.flipped_triangles(),
        components: raw.components(),
        centre: [c.x, c.y, c.z],
        scale: place.scale,
        volume: shape.volume(),
        area: shape.area(),
    };
    Ok((shape, rep))
}

/// Options of [`texture`].
#[derive(Debug, Clone)]
pub struct TextureOptions {
    /// The closed surface (OBJ).
    pub obj: PathBuf,
    /// Grid nodes per side on `[−½, ½]³`.
    pub n: usize,
    /// Band half-width `j`.
    pub j: usize,
    /// Time steps.
    pub steps: usize,
    /// Time step.
    pub tau: f64,
    /// Natural or transparent conditions.
    pub bc: Bc,
    /// The Turing parameters.
    pub params: Turing,
    /// Output directory.
    pub output: PathBuf,
}

/// Min, max and mass-weighted mean of a species.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Stats {
    /// Smallest value on the drawn surface's vertices.
    pub min: f64,
    /// Largest value on the drawn surface's vertices.
    pub max: f64,
    /// Mass-weighted band mean `Σ Mᵢ uᵢ / Σ Mᵢ`.
    pub mean: f64,
    /// Mass-weighted band variance.
    pub variance: f64,
}

/// What [`texture`] did (written as `dtgrid_texture.json`).
#[derive(Debug, Clone, Serialize)]
pub struct TextureReport {
    /// The input surface and its placement.
    pub input: InputReport,
    /// Grid nodes per side.
    pub n: usize,
    /// Grid spacing.
    pub h: f64,
    /// Band half-width.
    pub band: usize,
    /// Boundary condition.
    pub bc: String,
    /// Band nodes.
    pub nodes: usize,
    /// Time steps.
    pub steps: usize,
    /// Time step.
    pub tau: f64,
    /// `c_s, c_a, c_b, α, β, β spread`.
    pub params: [f64; 6],
    /// Species `a` at the end.
    pub a: Stats,
    /// Species `b` at the end.
    pub b: Stats,
    /// Variance of `a` after each tenth of the steps (index 0: after the first step).
    pub a_variance_history: Vec<f64>,
    /// CG iterations over all steps.
    pub cg_iterations: usize,
    /// Triangles of the drawn zero level.
    pub surface_triangles: usize,
    /// Seconds building the band.
    pub seconds_band: f64,
    /// Seconds of the time steps.
    pub seconds_steps: f64,
    /// Seconds in all.
    pub seconds: f64,
}

fn stats(surface_vals: &[f64], st: &TuringState, band_vals: &[f64]) -> Stats {
    Stats {
        min: surface_vals.iter().copied().fold(f64::INFINITY, f64::min),
        max: surface_vals
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max),
        mean: st.op.mean(band_vals),
        variance: st.op.variance(band_vals),
    }
}

fn io_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))
}

/// Turing's system on the surface of `o.obj`: writes `dtgrid_texture.json`, `.vtu` (the zero
/// level with `a` and `b`) and `.png` (the shaded surface coloured by `a`) into `o.output`.
pub fn texture(o: &TextureOptions) -> Result<TextureReport> {
    let t0 = Instant::now();
    let lat = Lattice::unit(o.n)?;
    let (shape, input) = load(&o.obj, &lat, o.j)?;
    let s: McfState<B> = band_of_shape(lat, o.j, &shape)?;
    let mut st = TuringState::new(lat, &s.nb, &s.phi, o.params, o.tau, o.bc)?;
    let seconds_band = t0.elapsed().as_secs_f64();
    let t1 = Instant::now();
    let mut cg = 0;
    let mut hist = Vec::new();
    let every = (o.steps / 10).max(1);
    for k in 0..o.steps {
        cg += st.step()?;
        if k == 0 || (k + 1) % every == 0 {
            hist.push(st.op.variance(&st.a));
        }
    }
    let seconds_steps = t1.elapsed().as_secs_f64();
    let surf = welded_zero_level(&lat, &s.nb.band, &s.phi);
    let at = |u: &[f64]| -> Result<Vec<f64>> {
        surf.points
            .iter()
            .map(|&p| {
                interpolate(&lat, &s.nb.band, u, p).ok_or_else(|| {
                    Error::InvalidInput(format!("surface point {p} outside the band's cells"))
                })
            })
            .collect()
    };
    let (va, vb) = (at(&st.a)?, at(&st.b)?);
    io_dir(&o.output)?;
    super::surface_mcf::write_surface_fields(
        &o.output.join("dtgrid_texture.vtu"),
        &surf,
        &[("a", &va), ("b", &vb)],
    )?;
    let view = View {
        colour_label: "a".into(),
        ..View::default()
    };
    render_surfaces(
        &o.output.join("dtgrid_texture.png"),
        &[SurfacePanel {
            surface: &surf,
            scalars: Some(&va),
            title: format!(
                "Turing texture, {} steps, {}³ grid, {} band nodes",
                o.steps,
                o.n,
                s.nb.band.len()
            ),
        }],
        &view,
    )?;
    let p = o.params;
    let rep = TextureReport {
        input,
        n: o.n,
        h: lat.h,
        band: o.j,
        bc: o.bc.name().into(),
        nodes: s.nb.band.len(),
        steps: o.steps,
        tau: o.tau,
        params: [p.cs, p.ca, p.cb, p.alpha, p.beta, p.beta_spread],
        a: stats(&va, &st, &st.a),
        b: stats(&vb, &st, &st.b),
        a_variance_history: hist,
        cg_iterations: cg,
        surface_triangles: surf.triangles.len(),
        seconds_band,
        seconds_steps,
        seconds: t0.elapsed().as_secs_f64(),
    };
    write_json(&o.output.join("dtgrid_texture.json"), &rep)?;
    Ok(rep)
}

/// Options of [`obj_mcf`].
#[derive(Debug, Clone)]
pub struct ObjMcfOptions {
    /// The closed surface (OBJ).
    pub obj: PathBuf,
    /// Grid nodes per side.
    pub n: usize,
    /// The mean curvature scheme (band, conditions, inner iterations).
    pub mcf: McfOptions,
    /// Time step (`None`: `h²`).
    pub tau: Option<f64>,
    /// Final time (in the placed coordinates).
    pub t_end: f64,
    /// Frames drawn (at least 2: the first and the last).
    pub frames: usize,
    /// Output directory.
    pub output: PathBuf,
}

/// One time of the motion.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct McfSample {
    /// Time (placed coordinates).
    pub t: f64,
    /// Enclosed volume of the zero level (placed coordinates).
    pub volume: f64,
    /// Area of the zero level (placed coordinates).
    pub area: f64,
    /// Band nodes.
    pub nodes: usize,
}

/// What [`obj_mcf`] did (written as `dtgrid_obj_mcf.json`).
#[derive(Debug, Clone, Serialize)]
pub struct ObjMcfReport {
    /// The input surface and its placement.
    pub input: InputReport,
    /// Grid nodes per side.
    pub n: usize,
    /// Grid spacing.
    pub h: f64,
    /// Band half-width.
    pub band: usize,
    /// Boundary condition.
    pub bc: String,
    /// Most solves per step.
    pub inner: usize,
    /// Time step.
    pub tau: f64,
    /// Steps taken.
    pub steps: usize,
    /// Volume and area after every step (first entry: the initial surface).
    pub samples: Vec<McfSample>,
    /// The times of the drawn frames.
    pub frame_times: Vec<f64>,
    /// Mean solves per step.
    pub mean_solves: f64,
    /// Seconds in all.
    pub seconds: f64,
}

/// Mean curvature motion of the surface of `o.obj`: writes `dtgrid_obj_mcf.json`, a `.vtu`
/// and a PNG per frame (`dtgrid_obj_mcf_frame_K`) and the montage `dtgrid_obj_mcf.png`.
/// A zero level that vanishes before `t_end` stops the run with [`Error::EmptyLevelSet`].
pub fn obj_mcf(o: &ObjMcfOptions) -> Result<ObjMcfReport> {
    let t0 = Instant::now();
    let lat = Lattice::unit(o.n)?;
    let (shape, input) = load(&o.obj, &lat, o.mcf.j)?;
    let mut s: McfState<B> = band_of_shape(lat, o.mcf.j, &shape)?;
    let tau0 = o.tau.unwrap_or(lat.h * lat.h);
    if !(tau0.is_finite() && tau0 > 0.0 && o.t_end.is_finite() && o.t_end > 0.0) {
        return Err(Error::InvalidInput(format!(
            "tau = {tau0}, t_end = {} (both positive)",
            o.t_end
        )));
    }
    let steps = (o.t_end / tau0 - 1e-9).ceil().max(1.0) as usize;
    let tau = o.t_end / steps as f64;
    let frames = o.frames.max(2);
    let frame_steps: Vec<usize> = (0..frames).map(|k| k * steps / (frames - 1)).collect();
    io_dir(&o.output)?;
    let sample = |s: &McfState<B>, t: f64| {
        let z = welded_zero_level(&s.lat, &s.nb.band, &s.phi);
        (
            McfSample {
                t,
                volume: z.enclosed_volume(),
                area: z.area(),
                nodes: s.nb.band.len(),
            },
            z,
        )
    };
    let mut samples = Vec::with_capacity(steps + 1);
    let mut shots: Vec<(f64, TriangleSurface)> = Vec::new();
    let mut solves = 0;
    for k in 0..=steps {
        if k > 0 {
            solves += s.step(tau, &o.mcf)?.solves;
        }
        let t = k as f64 * tau;
        let (smp, z) = sample(&s, t);
        samples.push(smp);
        if frame_steps.contains(&k) && !shots.iter().any(|(ts, _)| *ts == t) {
            let i = shots.len();
            crate::app::repro::surface_mcf::write_surface_vtu(
                &o.output.join(format!("dtgrid_obj_mcf_frame_{i}.vtu")),
                &z,
            )?;
            shots.push((t, z));
        }
    }
    let panels: Vec<SurfacePanel> = shots
        .iter()
        .map(|(t, z)| SurfacePanel {
            surface: z,
            scalars: None,
            title: format!("t = {t:.4}"),
        })
        .collect();
    let small = View {
        size: 500,
        ..View::default()
    };
    for (i, p) in panels.iter().enumerate() {
        render_surfaces(
            &o.output.join(format!("dtgrid_obj_mcf_frame_{i}.png")),
            std::slice::from_ref(p),
            &small,
        )?;
    }
    render_surfaces(&o.output.join("dtgrid_obj_mcf.png"), &panels, &small)?;
    let rep = ObjMcfReport {
        input,
        n: o.n,
        h: lat.h,
        band: o.mcf.j,
        bc: o.mcf.bc.name().into(),
        inner: o.mcf.inner,
        tau,
        steps,
        samples,
        frame_times: shots.iter().map(|(t, _)| *t).collect(),
        mean_solves: solves as f64 / steps as f64,
        seconds: t0.elapsed().as_secs_f64(),
    };
    write_json(&o.output.join("dtgrid_obj_mcf.json"), &rep)?;
    Ok(rep)
}

fn write_json(path: &Path, v: &impl Serialize) -> Result<()> {
    let json = serde_json::to_string_pretty(v).map_err(|e| Error::InvalidInput(e.to_string()))?;
    anisomesh::io::atomic_write(path, |w| w.write_all(json.as_bytes()))
}
