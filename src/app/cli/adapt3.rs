//! `anisomesh adapt --dim 3`: adapt the Kuhn mesh of `[−1, 1]³` to an implicit surface (the 004
//! star, a sphere, a torus or an expression in x, y, z) with the geometric metric of 004 eq. (6)
//! and write the mesh (`.mesh`), a `.vtu` with the level set and the quality, and
//! `report.json` and a PNG (the zero level shaded, the cut at `y = 0` by mean ratio).

use anisomesh::adapt::{run3, tet_stats, LevelSetMetric, Run3Options, Target3};
use anisomesh::geom::DVec3;
use anisomesh::io::{self, atomic_write, Medit3};
use anisomesh::levelset::{Expr, Shape, Sphere, StarSurface, Torus, Variables};
use anisomesh::{Error, Result};
use std::path::Path;

/// A level-set expression in x, y, z as a 3D shape (derivatives by differences).
struct ExprShape3(Expr);

impl Shape<DVec3> for ExprShape3 {
    fn distance(&self, p: DVec3) -> f64 {
        self.0.eval3(p)
    }
    fn name(&self) -> String {
        "expr".into()
    }
}

/// The 3D shape chosen on the command line (default: the 004 star).
fn shape3(name: Option<&str>, expr: Option<&str>) -> Result<(String, Box<dyn Shape<DVec3>>)> {
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

/// Runs the 3D adaptation and prints its numbers. `metric` is the eq. (6) setting after the
/// command-line flags; `max_vertices` bounds the run.
pub fn run(
    name: Option<&str>,
    expr: Option<&str>,
    metric: impl Fn(LevelSetMetric) -> LevelSetMetric,
    max_vertices: f64,
    out_dir: &Path,
) -> Result<()> {
    let (name, shape) = shape3(name, expr)?;
    let base = Run3Options::default();
    let mut opts = Run3Options {
        metric: metric(base.metric),
        ..base
    };
    opts.adapt = opts
        .adapt
        .max_vertices(Some(max_vertices.min(1e9) as usize));
    let a = run3(Target3::Shape(shape.as_ref()), None, &opts)?;
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
    let mesh_path = out_dir.join(format!("{name}3d.mesh"));
    io::write_medit3(&mesh_path, &medit)?;
    let u = a.level_set.clone().unwrap_or_default();
    let q: Vec<f64> = (0..m.n_tets())
        .map(|t| {
            let mm = m.tets[t].map(|v| a.metric[v as usize]);
            anisomesh::adapt::mean_ratio(m.tet_points(t), &mm)
        })
        .collect();
    let vtu_path = out_dir.join(format!("{name}3d.vtu"));
    io::write_vtu3(&vtu_path, m, &[("u", &u)], &[("mean_ratio", &q)])?;
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
            print!("  (exact volume {e:.10}: error {:+.3e})", v - e);
        }
        println!();
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
    let json = serde_json::to_string_pretty(r).map_err(|e| Error::InvalidInput(e.to_string()))?;
    let report_path = out_dir.join("report.json");
    atomic_write(&report_path, |w| w.write_all(json.as_bytes()))?;
    let png_path = out_dir.join(format!("{name}3d.png"));
    picture(&png_path, m, &u, &q)?;
    for p in [&mesh_path, &vtu_path, &report_path, &png_path] {
        println!("wrote {}", p.display());
    }
    Ok(())
}

/// The zero level of the P1 level set `u` shaded, beside the cut through the tetrahedra at
/// `y = 0` coloured by their mean ratio.
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
    let cut = render_tet_cut_rgb(
        m,
        &CutPlane {
            point: DVec3::ZERO,
            normal: DVec3::Y,
        },
        q,
        "cut y = 0, mean ratio",
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
