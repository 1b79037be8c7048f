//! `anisomesh adapt --dim 3`: adapt the Kuhn mesh of `[−1, 1]³` to an implicit surface (the 004
//! star, a sphere, a torus or an expression in x, y, z) with the geometric metric of 004 eq. (6),
//! optionally graded (`--hgrad`); and `adapt --input M.mesh --sol S.sol` on a tetrahedral mesh
//! with a metric, sizes or a level set at its vertices. Both write the mesh (`.mesh`), a `.vtu`
//! with the level set and the quality, `report.json` and a PNG (the zero level shaded, the cut
//! through the middle of the mesh in y by mean ratio).

use anisomesh::adapt::{
    run3, run3_graded, run3_to_field, tet_stats, Adapted3, Continuation3, DiscreteLevelSet3,
    LevelSetMetric, Run3Options, Target3,
};
use anisomesh::geom::DVec3;
use anisomesh::io::{self, atomic_write, Medit3};
use anisomesh::levelset::{Expr, Shape, Sphere, StarSurface, Torus, Variables};
use anisomesh::mesh3::Mesh3;
use anisomesh::metric::Sym3;
use anisomesh::{Error, Result};
use std::path::Path;

/// A level-set expression in x, y, z as a 3D shape (derivatives by differences; not a
/// distance, so the adaptation sees it through `u/|∇u|`).
struct ExprShape3(Expr);

impl Shape<DVec3> for ExprShape3 {
    fn distance(&self, p: DVec3) -> f64 {
        self.0.eval3(p)
    }
    fn is_distance(&self) -> bool {
        false
    }
    fn name(&self) -> String {
        "expr".into()
    }
}

/// The 3D shape chosen on the command line (default: the 004 star).
pub(crate) fn shape3(
    name: Option<&str>,
    expr: Option<&str>,
) -> Result<(String, Box<dyn Shape<DVec3>>)> {
    Ok(match (name, expr) {
        (_, Some(e)) => (
            "expr".into(),
            Box::new(ExprShape3(Expr::parse_with(e, Variables::XYZ)?)),
        ),
        (None | Some("star"), None) => ("star".into(), Box::new(StarSurface::PAPER)),
        (Some("sphere"), None) => (
            "sphere".into(),
            Box::new(Sphere {
                centre: DVec3::ZERO,
                radius: 0.5,
            }),
        ),
        (Some("torus"), None) => ("torus".into(), Box::new(Torus::PAPER)),
        (Some(n), None) => {
            return Err(Error::InvalidInput(format!(
                "unknown 3D shape '{n}': expected star, sphere or torus (or --expr)"
            )))
        }
    })
}

/// Runs the 3D adaptation with `opts` ([`options`]) and prints its numbers; `hgrad` grades
/// the metric ([`anisomesh::adapt::run3_graded`]).
pub fn run(
    name: Option<&str>,
    expr: Option<&str>,
    opts: &Run3Options,
    hgrad: Option<f64>,
    out_dir: &Path,
) -> Result<()> {
    let (name, shape) = shape3(name, expr)?;
    let a = match hgrad {
        Some(beta) => run3_graded(shape.as_ref(), None, opts, beta)?,
        None => run3(Target3::Shape(shape.as_ref()), None, opts)?,
    };
    print_and_write(&a, &format!("{name}3d"), None, out_dir)
}

/// The `--continuation` flag ([`Continuation3`]; default: sizes).
fn parse_continuation(continuation: Option<&str>) -> Result<Continuation3> {
    match continuation {
        None | Some("sizes") => Ok(Continuation3::Sizes),
        Some("normal") => Ok(Continuation3::Normal),
        Some("off") => Ok(Continuation3::Off),
        Some(c) => Err(Error::InvalidInput(format!(
            "--continuation '{c}': expected sizes, normal or off"
        ))),
    }
}

/// [`Run3Options`] with the command line's metric setting (`metric`: the eq. (6) setting
/// after the flags), `--continuation` and vertex limit.
pub fn options(
    metric: impl Fn(LevelSetMetric) -> LevelSetMetric,
    continuation: Option<&str>,
    max_vertices: f64,
) -> Result<Run3Options> {
    let base = Run3Options::default();
    let mut opts = Run3Options {
        metric: metric(base.metric),
        ..base
    };
    opts.adapt = opts
        .adapt
        .max_vertices(Some(max_vertices.min(1e9) as usize));
    opts.continuation = parse_continuation(continuation)?;
    Ok(opts)
}

/// What a 3D `.sol` given with `adapt --input` holds.
pub enum Sol3 {
    /// A metric tensor per vertex.
    Metric(Vec<Sym3>),
    /// An isotropic size per vertex.
    Sizes(Vec<f64>),
    /// A level set per vertex (adapt to its zero level).
    LevelSet(Vec<f64>),
}

/// `adapt --input M.mesh --sol S.sol` on a tetrahedral mesh: conform to the metric (or sizes)
/// given at its vertices, interpolated log-Euclidean in the input mesh at new vertices
/// ([`run3_to_field`]), or adapt to the zero level of a level set ([`DiscreteLevelSet3`], 004
/// eq. (6) with the flags' setting). Writes `<stem>_adapted.{mesh,vtu,png}`, the level set on
/// the adapted mesh as `<stem>_adapted.sol` (level-set input) and `report.json`.
pub fn run_files(
    mesh: &Mesh3,
    stem: &str,
    sol: Sol3,
    opts: &Run3Options,
    hgrad: Option<f64>,
    out_dir: &Path,
) -> Result<()> {
    let name = format!("{stem}_adapted");
    match sol {
        Sol3::Metric(m) => {
            let a = run3_to_field(mesh, m, opts, hgrad)?;
            print_and_write(&a, &name, Some("metric read from file"), out_dir)
        }
        Sol3::Sizes(h) => {
            let m = h.iter().map(|&h| Sym3::iso(h)).collect();
            let a = run3_to_field(mesh, m, opts, hgrad)?;
            print_and_write(&a, &name, Some("sizes read from file"), out_dir)
        }
        Sol3::LevelSet(u) => {
            let shape = DiscreteLevelSet3::new(&mesh.points, &mesh.tets, &u)?;
            let a = match hgrad {
                Some(beta) => run3_graded(&shape, Some(mesh), opts, beta)?,
                None => run3(Target3::Shape(&shape), Some(mesh), opts)?,
            };
            print_and_write(
                &a,
                &name,
                Some("geometric metric 004 eq. (6) of the distance to the input's zero level"),
                out_dir,
            )
        }
    }
}

/// Prints the numbers of `a` and writes `<name>.mesh`, `<name>.vtu`, `<name>.png`, the level set
/// as `<name>.sol` when there is one and `report.json`.
fn print_and_write(a: &Adapted3, name: &str, source: Option<&str>, out_dir: &Path) -> Result<()> {
    let r = &a.report;
    std::fs::create_dir_all(out_dir).map_err(|e| Error::Io {
        path: out_dir.to_path_buf(),
        source: e,
    })?;
    let m = &a.mesh;
    let mut tris = Vec::new();
    let mut tri_ref = Vec::new();
    for (t, i) in m.boundary_faces() {
        tris.push(m.face_vertices(t, i));
        tri_ref.push(m.face_ref[t][i]);
    }
    let medit = Medit3 {
        points: m.points.clone(),
        point_ref: vec![0; m.n_points()],
        tets: m.tets.clone(),
        tet_ref: m.tet_ref.clone(),
        tris,
        tri_ref,
    };
    let mesh_path = out_dir.join(format!("{name}.mesh"));
    io::write_medit3_features(&mesh_path, &medit, &m.features)?;
    let u = a.level_set.clone().unwrap_or_default();
    let q: Vec<f64> = (0..m.n_tets())
        .map(|t| {
            let mm = m.tets[t].map(|v| a.metric[v as usize]);
            anisomesh::adapt::mean_ratio(m.tet_points(t), &mm)
        })
        .collect();
    let vtu_path = out_dir.join(format!("{name}.vtu"));
    let point_fields: Vec<(&str, &[f64])> = if u.is_empty() {
        Vec::new()
    } else {
        vec![("u", &u)]
    };
    io::write_vtu3(&vtu_path, m, &point_fields, &[("mean_ratio", &q)])?;
    let mut written = vec![mesh_path, vtu_path];
    if !u.is_empty() && source.is_some() {
        let sol_path = out_dir.join(format!("{name}.sol"));
        io::write_sol(&sol_path, &io::Sol::scalar_dim(3, u.clone()))?;
        written.push(sol_path);
    }
    if let Some(s) = source {
        println!("metric: {s}");
    }
    let stats = tet_stats(m, &a.metric);
    println!(
        "vertices {}  tetrahedra {}  edges in [1/sqrt2, sqrt2] {:.2}%  mean ratio min {:.3} mean {:.3}",
        r.vertices,
        r.tetrahedra,
        100.0 * stats.edge_length_in_range,
        stats.quality_min,
        stats.quality_mean
    );
    if let (Some(v), Some(s)) = (r.volume, r.surface_area) {
        print!("volume {v:.10}  surface area {s:.6}");
        if let Some(e) = r.exact_volume {
            let what = if source.is_some() { "input" } else { "exact" };
            print!("  ({what} volume {e:.10}: error {:+.3e})", v - e);
        }
        println!();
    }
    if !m.features.is_empty() {
        println!(
            "kept {} ridge edges and {} corners of the input's boundary",
            m.features.ridges.len(),
            m.features.corners.len()
        );
    }
    println!(
        "{:.2} s, {:.0} vertices/s ({} cycles, {} splits, {} collapses, {} swaps, {} moves{})",
        r.seconds,
        r.vertices as f64 / r.seconds.max(1e-9),
        r.adapt.cycles,
        r.adapt.splits,
        r.adapt.collapses,
        r.adapt.flips,
        r.adapt.moves,
        if r.adapt.converged {
            ""
        } else {
            ", not converged"
        }
    );
    for s in &r.stages {
        let sizes = match (s.eps, s.band) {
            (Some(eps), Some(band)) => {
                format!("eps {eps:.2e} hmin {:.2e} band {band:.2e}", s.hmin)
            }
            _ if s.scale == 1.0 => "target metric".to_string(),
            _ => format!("sizes at least {:.2e}", s.hmin),
        };
        println!(
            "stage x{:<3} {sizes}: vertices {} -> {} (peak {}), \
             complexity {:.0} ({:.2} vertices per unit), {} passes, s split/collapse/swap/smooth \
             {:.1}/{:.1}/{:.1}/{:.1}",
            s.scale,
            s.start_vertices,
            s.vertices,
            s.peak_vertices,
            s.complexity,
            s.vertices as f64 / s.complexity.max(1e-300),
            s.passes,
            s.seconds[0],
            s.seconds[1],
            s.seconds[2],
            s.seconds[3]
        );
    }
    let json = serde_json::to_string_pretty(r).map_err(|e| Error::InvalidInput(e.to_string()))?;
    let report_path = out_dir.join("report.json");
    atomic_write(&report_path, |w| w.write_all(json.as_bytes()))?;
    let png_path = out_dir.join(format!("{name}.png"));
    picture(&png_path, m, &u, &q)?;
    written.extend([report_path, png_path]);
    for p in &written {
        println!("wrote {}", p.display());
    }
    Ok(())
}

/// The zero level of the P1 level set `u` shaded, beside the cut through the tetrahedra at
/// the middle `y` of the mesh coloured by their mean ratio.
fn picture(
    path: &std::path::Path,
    m: &anisomesh::mesh3::Mesh3,
    u: &[f64],
    q: &[f64],
) -> Result<()> {
    use crate::app::plot::surface::{
        render_surfaces_rgb, render_tet_cut_rgb, CutPlane, SurfacePanel, View,
    };
    let mut surface = anisomesh::levelset::TriangleSurface::default();
    if u.len() == m.n_points() {
        for t in 0..m.n_tets() {
            surface.add_tet_zero_level(m.tet_points(t), m.tets[t].map(|v| u[v as usize]));
        }
        surface.weld(1e-12);
    }
    // The cut through the middle of the bounding box (y = 0 for the default box).
    let (lo, hi) = m
        .points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.y), hi.max(p.y))
        });
    let y = if lo <= hi { 0.5 * (lo + hi) } else { 0.0 };
    let cut = render_tet_cut_rgb(
        m,
        &CutPlane {
            point: DVec3::new(0.0, y, 0.0),
            normal: DVec3::Y,
        },
        q,
        &format!("cut y = {y}, mean ratio"),
        &View::facing(DVec3::NEG_Y),
    )?;
    let image = if surface.triangles.is_empty() {
        cut
    } else {
        let zero = render_surfaces_rgb(
            &[SurfacePanel {
                surface: &surface,
                scalars: None,
                title: "zero level".into(),
            }],
            &View::default(),
        )?;
        crate::app::plot::RgbImage::side_by_side(&[zero, cut])?
    };
    image.save_png(path)
}
