//! The `anisomesh adapt` job: adapt a mesh to an implicit shape, to a P1 level set read from a
//! file, or to a given metric field, and write the mesh (`.mesh`, `.vtu`), a picture (`.png`,
//! triangles coloured by `Q_ani`) and `report.json`.
//!
//! The adaptation itself is the library's [`anisomesh::adapt::run`]; this module writes its
//! results.

use crate::app::plot::{mesh_png, Corner, Inset, MeshPlot, RGBColor};
use anisomesh::adapt::{AdaptTarget, RunOptions, RunReport};
use anisomesh::error::{Error, Result};
use anisomesh::geom::DVec2;
use anisomesh::io::{self, FieldRef};
use anisomesh::levelset::extract_zero_level;
use anisomesh::mesh::Mesh2;
use anisomesh::metric::{q_ani, Sym2};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Options of [`run`]: the library's options and where the files go.
#[derive(Debug, Clone)]
pub struct AdaptRunOptions {
    /// The adaptation (metric, limits).
    pub run: RunOptions,
    /// Output directory and base name of the files written there.
    pub out_dir: PathBuf,
    pub name: String,
    /// Whether to draw the PNG.
    pub picture: bool,
}

impl Default for AdaptRunOptions {
    fn default() -> Self {
        AdaptRunOptions {
            run: RunOptions::default(),
            out_dir: PathBuf::from("out"),
            name: "zalesak".into(),
            picture: true,
        }
    }
}

/// What [`run`] measured, written as `report.json`.
#[derive(Debug, Clone, Serialize)]
pub struct AdaptRunReport {
    #[serde(flatten)]
    pub run: RunReport,
    pub files: Vec<PathBuf>,
}

/// The default domain of a built-in shape: `[-2, 2]²` for the Zalesak disk (004 §5.1),
/// `[-1, 1]²` otherwise.
pub fn default_domain(shape_name: &str) -> (DVec2, DVec2) {
    if shape_name.eq_ignore_ascii_case("zalesak") {
        (DVec2::splat(-2.0), DVec2::splat(2.0))
    } else {
        (DVec2::splat(-1.0), DVec2::splat(1.0))
    }
}

/// Runs the job ([`anisomesh::adapt::run`]) and writes `<out_dir>/<name>.mesh`, `.vtu`, `.png`
/// and `<out_dir>/report.json`.
pub fn run(target: AdaptTarget, opts: &AdaptRunOptions) -> Result<AdaptRunReport> {
    let adapted = anisomesh::adapt::run(target, &opts.run)?;
    let run = adapted.report;
    let files = write_outputs(
        &adapted.mesh,
        &adapted.metric,
        adapted.level_set.as_deref(),
        opts,
    )?;
    let out = AdaptRunReport { run, files };
    let json = serde_json::to_string_pretty(&out)
        .map_err(|e| Error::InvalidInput(format!("report serialisation: {e}")))?;
    let path = opts.out_dir.join("report.json");
    io::atomic_write(&path, |w| w.write_all(json.as_bytes()))?;
    Ok(out)
}

/// Per-triangle `Q_ani` in the element metric (log-Euclidean mean of the vertex metrics).
fn triangle_quality(mesh: &Mesh2, metric: &[Sym2]) -> Vec<f64> {
    (0..mesh.n_tris())
        .map(|t| {
            let [a, b, c] = mesh.tris[t].map(|v| &metric[v as usize]);
            q_ani(
                mesh.tri_points(t),
                &anisomesh::metric::element_metric([a, b, c]),
            )
        })
        .collect()
}

fn write_outputs(
    mesh: &Mesh2,
    metric: &[Sym2],
    u: Option<&[f64]>,
    opts: &AdaptRunOptions,
) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(&opts.out_dir).map_err(|e| Error::io(&opts.out_dir, e))?;
    let path = |ext: &str| opts.out_dir.join(format!("{}.{ext}", opts.name));
    let quality = triangle_quality(mesh, metric);
    let mut files = Vec::new();
    io::write_mesh(&path("mesh"), mesh)?;
    files.push(path("mesh"));
    let mut point_fields = vec![("metric", FieldRef::TensorComponents(metric))];
    if let Some(u) = u {
        point_fields.push(("levelset", FieldRef::Scalar(u)));
    }
    io::write_vtu(&path("vtu"), mesh, &point_fields, &[("q_ani", &quality)])?;
    files.push(path("vtu"));
    if opts.picture {
        draw(&path("png"), mesh, u, quality, opts)?;
        files.push(path("png"));
    }
    Ok(files)
}

/// The mesh coloured by `Q_ani` with the interface drawn and a zoomed inset: at the upper right
/// corner of the slot for the Zalesak disk, else where the interface turns most sharply.
fn draw(
    path: &Path,
    mesh: &Mesh2,
    u: Option<&[f64]>,
    quality: Vec<f64>,
    opts: &AdaptRunOptions,
) -> Result<()> {
    let mut plot = MeshPlot {
        tri_colour: Some(quality),
        colour_range: Some((1.0, 2.0)),
        colour_label: "Q_ani (1 = ideal)".into(),
        title: format!("{}: {} vertices", opts.name, mesh.n_points()),
        ..MeshPlot::default()
    };
    if let Some(u) = u {
        if let Ok(lines) = extract_zero_level(mesh, u) {
            let focus = if opts.name.eq_ignore_ascii_case("zalesak") {
                Some(DVec2::new(0.06, 0.85))
            } else {
                sharpest_turn(&lines)
            };
            plot.polylines = lines
                .iter()
                .map(|l| (l.points.clone(), RGBColor(220, 30, 30), 1))
                .collect();
            if let Some(c) = focus {
                let half = DVec2::splat(0.02);
                plot.insets.push(Inset {
                    view: (c - half, c + half),
                    placement: Corner::TopRight,
                });
            }
        }
        // Show the shape, not the whole domain, when it is much smaller than the domain.
        if let Some((lo, hi)) = mesh.bounding_box() {
            let inside: Vec<DVec2> = mesh
                .points
                .iter()
                .zip(u)
                .filter(|(_, &v)| v <= 0.0)
                .map(|(p, _)| *p)
                .collect();
            if let Some(&first) = inside.first() {
                let (a, b) = inside
                    .iter()
                    .fold((first, first), |(a, b), &p| (a.min(p), b.max(p)));
                let margin = 0.25 * (b - a).max_element();
                plot.view = Some(((a - margin).max(lo), (b + margin).min(hi)));
            }
        }
    }
    mesh_png(path, mesh, &plot)
}

fn sharpest_turn(lines: &[anisomesh::levelset::Polyline]) -> Option<DVec2> {
    let mut best = (0.0, None);
    for l in lines {
        for w in l.points.windows(3) {
            let (d1, d2) = (
                (w[1] - w[0]).normalize_or_zero(),
                (w[2] - w[1]).normalize_or_zero(),
            );
            let turn = d1.perp_dot(d2).abs();
            if turn > best.0 {
                best = (turn, Some(w[1]));
            }
        }
    }
    best.1
}
