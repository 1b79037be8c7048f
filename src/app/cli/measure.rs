//! `anisomesh measure MESH [--metric METRIC.sol | --ugawg CASE] [--json]`: how well a triangle or
//! tetrahedral mesh conforms to a metric — edge lengths in the metric, `Q_ani` and the mean
//! ratio ([`anisomesh::metric::conformity`]); without a metric, in the Euclidean metric. With
//! `--against REF.mesh --sol U.sol`, the distance between the zero levels and the area (volume)
//! error ([`anisomesh::levelset::compare`], [`anisomesh::levelset::compare3`]).

use super::user_files::{read_metric2, read_metric3, read_scalar, read_user_mesh, UserMesh};
use anisomesh::levelset::compare::{compare_zero_levels, interpolate_p1, ZeroLevelComparison};
use anisomesh::levelset::compare3::{compare_zero_levels3, interpolate_p1_tets};
use anisomesh::metric::interpolate_log;
use anisomesh::metric::ugawg::UgawgCase;
use anisomesh::metric::{
    conformity, conformity_analytic, conformity_ugawg, Conformity, Sym2, Sym3,
};
use anisomesh::{DVec2, Error, Location, Mesh2, Result};
use clap::Args;
use std::path::PathBuf;

/// Options of `anisomesh measure`.
#[derive(Debug, Args)]
pub struct MeasureArgs {
    /// The mesh (.mesh 2D or 3D, .msh).
    pub mesh: PathBuf,
    /// A metric on the mesh's vertices (.sol, symmetric tensors), or on the vertices of
    /// --metric-mesh.
    #[arg(long, conflicts_with = "ugawg")]
    pub metric: Option<PathBuf>,
    /// The 2D mesh the --metric file lives on (e.g. the input of an adaptation): the metric is
    /// interpolated log-Euclidean at the measured vertices, so that meshes from different
    /// adaptors are rated in the same metric field.
    #[arg(long, requires = "metric")]
    pub metric_mesh: Option<PathBuf>,
    /// A UGAWG analytic metric (3D): cube-linear or cube-polar-1; edge lengths are integrated
    /// along the edges in it.
    #[arg(long)]
    pub ugawg: Option<String>,
    /// A reference mesh (2D or 3D, as the measured one) with its level set (--sol): compare
    /// the zero levels (sampled Hausdorff distance, enclosed area or volume).
    #[arg(long, requires = "sol")]
    pub against: Option<PathBuf>,
    /// The reference level set on --against's vertices (.sol, scalar).
    #[arg(long, requires = "against")]
    pub sol: Option<PathBuf>,
    /// The measured mesh's own level set (.sol, scalar); default: the reference's interpolated
    /// at its vertices (with --against) or the shape's level set at the vertices (--shape).
    #[arg(long)]
    pub level_set: Option<PathBuf>,
    /// Compare the tetrahedral mesh's zero level with an exact surface centred at the origin:
    /// star (004 §5, r = 0.45 + 0.3 cos 6θ cos² 3φ) or sphere (radius 0.5); distances both
    /// ways (median, 99th percentile, max) and the volume error.
    #[arg(long, conflicts_with_all = ["against", "metric", "ugawg"])]
    pub shape: Option<String>,
    /// With --shape: the discrete surface is the interface between the tetrahedra labelled IN
    /// and OUT, as "IN,OUT" (mmg3d -ls output: 3,2, the default when the mesh has both labels
    /// and no --level-set is given).
    #[arg(long, requires = "shape")]
    pub regions: Option<String>,
    /// With --shape: the exact surface is sampled on the icosahedron refined this many times
    /// (20 * 4^level triangles).
    #[arg(long, default_value_t = 7, requires = "shape")]
    pub sampling_level: u32,
    /// Print the statistics as JSON.
    #[arg(long)]
    pub json: bool,
}

/// The statistics of `mesh` in the chosen metric, and a one-line name of that metric.
pub fn measure(a: &MeasureArgs, mesh: &UserMesh) -> Result<(Conformity, String)> {
    match mesh {
        UserMesh::Tri { points, cells, .. } => {
            if a.ugawg.is_some() {
                return Err(Error::InvalidInput(
                    "--ugawg: the UGAWG metrics are 3D; this mesh is 2D".into(),
                ));
            }
            let (m, name) = match (&a.metric, &a.metric_mesh) {
                (Some(p), Some(r)) => {
                    let reference = read_user_mesh(r)?;
                    let on_ref = read_metric2(p, &reference)?;
                    let UserMesh::Tri { mesh: rm, .. } = &reference else {
                        return Err(Error::InvalidInput(format!(
                            "--metric-mesh {}: a 2D mesh is needed",
                            r.display()
                        )));
                    };
                    if rm.n_live_tris() == 0 {
                        return Err(Error::InvalidInput(format!(
                            "--metric-mesh {}: no triangles",
                            r.display()
                        )));
                    }
                    (
                        transfer(rm, &on_ref, points),
                        format!("{} on {} (interpolated)", p.display(), r.display()),
                    )
                }
                (Some(p), None) => (read_metric2(p, mesh)?, p.display().to_string()),
                (None, _) => (vec![Sym2::IDENTITY; points.len()], "Euclidean".into()),
            };
            Ok((conformity(points, cells, &m)?, name))
        }
        UserMesh::Tet { points, cells } => {
            if a.metric_mesh.is_some() {
                return Err(Error::Unsupported(
                    "--metric-mesh: interpolation between meshes is 2D only".into(),
                ));
            }
            let (m, name) = match (&a.metric, &a.ugawg) {
                (Some(p), _) => (read_metric3(p, mesh)?, p.display().to_string()),
                (None, Some(c)) => {
                    // Known everywhere: lengths integrated along the edges.
                    let case = UgawgCase::parse(c)?;
                    let metric = move |p| case.metric(p);
                    let name = format!("UGAWG {} (lengths integrated along edges)", case.name());
                    return Ok((conformity_analytic(points, cells, &metric)?, name));
                }
                (None, None) => (vec![Sym3::IDENTITY; points.len()], "Euclidean".into()),
            };
            Ok((conformity(points, cells, &m)?, name))
        }
    }
}

/// The metric `on_ref` of the mesh `reference` at `points`: log-Euclidean mean of the three
/// vertex metrics of the containing triangle with the barycentric weights (a point outside the
/// reference mesh takes the nearest triangle along the walk, weights clipped at 0).
fn transfer(reference: &Mesh2, on_ref: &[Sym2], points: &[DVec2]) -> Vec<Sym2> {
    let mut start = 0u32;
    points
        .iter()
        .map(|&p| {
            let loc = reference.locate(p, start);
            let (t, bary) = match loc {
                Location::Inside { tri, bary } | Location::Outside { tri, bary } => (tri, bary),
            };
            start = t;
            let w = bary.map(|b| b.max(0.0));
            let sum: f64 = w.iter().sum();
            let v = reference.tris[t as usize];
            let items: Vec<(f64, Sym2)> = (0..3)
                .map(|k| (w[k] / sum, on_ref[v[k] as usize]))
                .collect();
            interpolate_log(&items)
        })
        .collect()
}

/// Prints the share of edges in range and the worst mean ratio by the UGAWG measures
/// ([`anisomesh::metric::conformity_ugawg`]), the line to compare with the UGAWG study.
pub fn print_ugawg_line(c: &Conformity) {
    println!(
        "  UGAWG measures (end-point lengths, as the UGAWG study rates meshes): in [1/sqrt2, sqrt2] {:.2}%  mean ratio min {:.4}",
        100.0 * c.edge_length_in_range,
        c.mean_ratio_min
    );
}

/// Prints the statistics in the text layout of `measure`.
pub fn print_conformity(title: &str, c: &Conformity) {
    println!("{title}");
    println!(
        "  edges {}  in [1/sqrt2, sqrt2] {:.2}%  length min {:.4} mean {:.4} max {:.4}",
        c.edges,
        100.0 * c.edge_length_in_range,
        c.edge_length_min,
        c.edge_length_mean,
        c.edge_length_max
    );
    println!("  {}", histogram_line("length", &c.edge_length_histogram));
    println!(
        "  cells {}  inverted {}  Q_ani mean {:.4} worst {:.4} (cell {})",
        c.cells, c.inverted, c.q_ani_mean, c.q_ani_max, c.worst_cell
    );
    println!("  {}", histogram_line("Q_ani", &c.q_ani_histogram));
    println!(
        "  mean ratio min {:.4} mean {:.4}",
        c.mean_ratio_min, c.mean_ratio_mean
    );
    println!(
        "  {}",
        histogram_line("mean ratio", &c.mean_ratio_histogram)
    );
}

fn histogram_line(name: &str, h: &[(f64, usize)]) -> String {
    let total: usize = h.iter().map(|b| b.1).sum();
    let mut line = format!("{name} histogram:");
    for (upper, count) in h {
        if *count > 0 {
            line += &format!(
                " <={upper:.3}: {:.1}%",
                100.0 * *count as f64 / total.max(1) as f64
            );
        }
    }
    line
}

/// The zero-level comparison of `--against`, if asked (2D: [`compare_zero_levels`], 3D:
/// [`compare_zero_levels3`]).
fn against(a: &MeasureArgs, mesh: &UserMesh) -> Result<Option<ZeroLevelComparison>> {
    let (Some(r), Some(u_path)) = (&a.against, &a.sol) else {
        return Ok(None);
    };
    let reference = read_user_mesh(r)?;
    let u = read_scalar(u_path, &reference)?;
    let own = match &a.level_set {
        Some(p) => Some(read_scalar(p, mesh)?),
        None => None,
    };
    match (mesh, &reference) {
        (UserMesh::Tri { mesh: m, .. }, UserMesh::Tri { mesh: rm, .. }) => {
            let v = match own {
                Some(v) => v,
                None => interpolate_p1(rm, &u, &m.points)?,
            };
            Ok(Some(compare_zero_levels(m, &v, rm, &u)?))
        }
        (
            UserMesh::Tet { points, cells },
            UserMesh::Tet {
                points: rp,
                cells: rc,
            },
        ) => {
            let v = match own {
                Some(v) => v,
                None => interpolate_p1_tets(rp, rc, &u, points)?,
            };
            Ok(Some(compare_zero_levels3(points, cells, &v, rp, rc, &u)?))
        }
        _ => Err(Error::InvalidInput(format!(
            "--against {}: a {}D mesh, the measured mesh is {}D",
            r.display(),
            reference.dim(),
            mesh.dim()
        ))),
    }
}

/// With `--ugawg CASE` on a tetrahedral mesh: the statistics by the UGAWG measures (the field
/// at the vertices, the study's end-point length rule), beside the integrated ones.
fn ugawg_measures(a: &MeasureArgs, mesh: &UserMesh) -> Result<Option<Conformity>> {
    match (&a.ugawg, mesh) {
        (Some(c), UserMesh::Tet { points, cells }) => {
            let at_vertices = UgawgCase::parse(c)?.field(points);
            Ok(Some(conformity_ugawg(points, cells, &at_vertices)?))
        }
        _ => Ok(None),
    }
}

/// Runs `anisomesh measure`.
pub fn run(a: MeasureArgs) -> Result<()> {
    if let Some(shape) = &a.shape {
        return super::measure_shape::run(&super::measure_shape::ShapeMeasure {
            mesh: &a.mesh,
            shape,
            level_set: a.level_set.as_deref(),
            regions: a.regions.as_deref(),
            level: a.sampling_level,
            json: a.json,
        });
    }
    if a.level_set.is_some() && a.against.is_none() {
        return Err(Error::InvalidInput(
            "--level-set goes with --against or --shape".into(),
        ));
    }
    let mesh = read_user_mesh(&a.mesh)?;
    let (c, name) = measure(&a, &mesh)?;
    let by_ugawg = ugawg_measures(&a, &mesh)?;
    let cmp = against(&a, &mesh)?;
    if a.json {
        let v = serde_json::json!({
            "mesh": a.mesh.display().to_string(),
            "dimension": mesh.dim(),
            "metric": name,
            "conformity": c,
            "ugawg_measures": by_ugawg,
            "against": cmp,
        });
        println!(
            "{}",
            serde_json::to_string_pretty(&v)
                .map_err(|e| Error::InvalidInput(format!("JSON output: {e}")))?
        );
    } else {
        print_conformity(
            &format!(
                "{}: {} in the metric {name}",
                a.mesh.display(),
                mesh.describe()
            ),
            &c,
        );
        if let Some(u) = &by_ugawg {
            print_ugawg_line(u);
        }
        if let Some(z) = cmp {
            println!(
                "zero level against {}: Hausdorff {:.3e} (to {:.3e}, from {:.3e}); {} {:.10} vs \
                 {:.10} (relative error {:.2e})",
                a.against
                    .as_deref()
                    .unwrap_or(std::path::Path::new(""))
                    .display(),
                z.hausdorff,
                z.to_reference_max,
                z.from_reference_max,
                if mesh.dim() == 2 { "area" } else { "volume" },
                z.area,
                z.reference_area,
                z.relative_area_error
            );
        }
    }
    Ok(())
}
