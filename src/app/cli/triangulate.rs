//! `anisomesh triangulate --shape star|sphere|torus [--level L] -o FILE.obj`: writes a closed
//! triangulation of a built-in surface (the 004 §5 star on a refined icosahedron, a sphere, the
//! 003 §8 torus on a parametric grid), checks it as a closed manifold and reports its triangle
//! count and volume error; optionally a shaded picture and a picture of the signed distance to
//! the surface on the plane through its centre.

use crate::app::plot::surface::{render_surfaces, render_tet_cut, CutPlane, SurfacePanel, View};
use anisomesh::levelset::{
    icosphere, radial_surface, torus_surface, Shape, StarSurface, Torus, TriangleSurface,
    TriangulatedShape,
};
use anisomesh::mesh3::Mesh3;
use anisomesh::{io, DVec3, Error, Result};
use clap::Args;
use std::f64::consts::PI;
use std::path::PathBuf;

/// Options of `anisomesh triangulate`.
#[derive(Debug, Args)]
pub struct TriangulateArgs {
    /// The surface: star (004 §5), sphere (radius 0.5) or torus (R = 0.4, r = 0.2).
    #[arg(long, value_parser = ["star", "sphere", "torus"], default_value = "star")]
    shape: String,
    /// Refinement level, 0..=9: star and sphere have 20·4^L triangles (default 6); the torus
    /// an 8·2^L × 4·2^L grid, 64·4^L triangles (default 4).
    #[arg(long)]
    level: Option<u32>,
    /// Output OBJ file.
    #[arg(short, long)]
    output: PathBuf,
    /// Digits after the decimal point of the coordinates in the OBJ file.
    #[arg(long, default_value_t = 7)]
    decimals: usize,
    /// Also write a shaded picture of the surface (PNG).
    #[arg(long)]
    png: Option<PathBuf>,
    /// Also write the signed distance to the surface on the plane z = 0 (PNG), sampled at the
    /// centroids of a 64³ Kuhn tetrahedral grid cut by the plane.
    #[arg(long)]
    slice_png: Option<PathBuf>,
    /// Draw triangle edges in the pictures.
    #[arg(long)]
    wireframe: bool,
}

/// The surface and its exact enclosed volume.
fn build(shape: &str, level: Option<u32>) -> Result<(TriangleSurface, f64)> {
    let check = |l: u32| {
        if l > 9 {
            Err(Error::InvalidInput(format!(
                "--level {l}: at most 9 (5 million triangles)"
            )))
        } else {
            Ok(l)
        }
    };
    Ok(match shape {
        "star" => {
            let star = StarSurface::PAPER;
            let s = radial_surface(
                star.centre,
                |d| star.radius_towards(d),
                check(level.unwrap_or(6))?,
            );
            (s, star.exact_area().unwrap_or(f64::NAN))
        }
        "sphere" => {
            let mut s = icosphere(check(level.unwrap_or(6))?);
            for p in &mut s.points {
                *p *= 0.5;
            }
            (s, 4.0 / 3.0 * PI * 0.125)
        }
        _ => {
            let l = check(level.unwrap_or(4))?;
            let t = Torus::PAPER;
            let s = torus_surface(t.centre, t.major, t.minor, 8 << l, 4 << l);
            (s, 2.0 * PI * PI * t.major * t.minor * t.minor)
        }
    })
}

/// Builds, validates and writes the surface; prints what it measured.
pub fn run(a: TriangulateArgs) -> Result<()> {
    let (surface, exact) = build(&a.shape, a.level)?;
    let shape = TriangulatedShape::new(surface.points.clone(), surface.triangles.clone())?;
    io::write_obj(&a.output, &surface.points, &surface.triangles, a.decimals)?;
    println!(
        "{}: {} ({} vertices, {} triangles, {} component(s), {} flipped)",
        a.output.display(),
        a.shape,
        surface.points.len(),
        surface.triangles.len(),
        shape.components(),
        shape.flipped_triangles()
    );
    println!(
        "  volume {:.10} (exact {exact:.10}, relative error {:.3e}), area {:.10}",
        shape.volume(),
        (shape.volume() - exact).abs() / exact,
        shape.area()
    );
    if let Some(png) = &a.png {
        let view = View {
            wireframe: a.wireframe,
            ..View::default()
        };
        let panel = SurfacePanel {
            surface: &surface,
            scalars: None,
            title: format!("{}: {} triangles", a.shape, surface.triangles.len()),
        };
        render_surfaces(png, &[panel], &view)?;
        println!("  picture {}", png.display());
    }
    if let Some(png) = &a.slice_png {
        slice(&shape, png, &a)?;
        println!("  distance slice {}", png.display());
    }
    Ok(())
}

/// The signed distance on the plane `z = 0` through a Kuhn grid of `[−1, 1]³`.
fn slice(shape: &TriangulatedShape, png: &std::path::Path, a: &TriangulateArgs) -> Result<()> {
    let n = 64;
    let mesh = Mesh3::kuhn_box(DVec3::splat(-1.0), DVec3::splat(1.0), [n; 3])?;
    let plane = CutPlane {
        point: DVec3::ZERO,
        normal: DVec3::Z,
    };
    let centroids: Vec<DVec3> = (0..mesh.tets.len())
        .map(|t| mesh.tet_points(t).iter().sum::<DVec3>() / 4.0)
        .collect();
    let cut: Vec<usize> = (0..mesh.tets.len())
        .filter(|&t| {
            let z = mesh.tet_points(t).map(|p| p.z);
            z.iter().any(|&v| v < 0.0) && z.iter().any(|&v| v >= 0.0)
        })
        .collect();
    let d = shape.distances(&cut.iter().map(|&t| centroids[t]).collect::<Vec<_>>());
    let mut values = vec![f64::NAN; mesh.tets.len()];
    for (&t, &v) in cut.iter().zip(&d) {
        values[t] = v;
    }
    let view = View {
        wireframe: a.wireframe,
        colour_label: "signed distance".into(),
        ..View::facing(DVec3::Z)
    };
    let title = format!("{}: signed distance on z = 0", a.shape);
    render_tet_cut(png, &mesh, &plane, &values, &title, &view)
}
