//! `anisomesh measure M.mesh --shape star|sphere [--level-set U.sol | --regions IN,OUT]`: the
//! distance between the discrete surface of a tetrahedral mesh and an exact star-shaped surface
//! in both directions (median, 99th percentile, maximum) and the enclosed volume error
//! ([`anisomesh::levelset::compare_radial`]).
//!
//! The discrete surface is, in this order: the P1 zero level of `--level-set`; the faces
//! between the tetrahedra labelled `IN` and `OUT` with `--regions` (what `mmg3d_O3 -ls`
//! writes: `--regions 3,2`, taken by default when the mesh has both labels); otherwise the P1
//! zero level of the exact shape's level set evaluated at the vertices (what `adapt --dim 3`
//! adapts: for the star, whose `u = |x| − ρ` is not a distance, `u/|∇u|`).

use anisomesh::geom::DVec3;
use anisomesh::io;
use anisomesh::levelset::compare_radial::{
    compare_to_radial, interface_triangles, zero_level_triangles, RadialComparison, RadialSurface,
};
use anisomesh::levelset::{Normalized, Shape, StarSurface};
use anisomesh::{Error, Result};
use std::path::Path;

/// The options `--shape` reads (a view of [`super::measure::MeasureArgs`]).
pub struct ShapeMeasure<'a> {
    /// The measured mesh.
    pub mesh: &'a Path,
    /// star or sphere.
    pub shape: &'a str,
    /// A level set on the mesh's vertices.
    pub level_set: Option<&'a Path>,
    /// "IN,OUT" region labels.
    pub regions: Option<&'a str>,
    /// Sampling level of the exact surface.
    pub level: u32,
    /// Print JSON.
    pub json: bool,
}

fn parse_regions(s: &str) -> Result<(i32, i32)> {
    let v: Vec<&str> = s.split(',').map(str::trim).collect();
    match v[..] {
        [a, b] => match (a.parse::<i32>(), b.parse::<i32>()) {
            (Ok(a), Ok(b)) if a != b => Ok((a, b)),
            _ => Err(Error::InvalidInput(format!(
                "--regions '{s}': expected two different integer labels IN,OUT (e.g. 3,2)"
            ))),
        },
        _ => Err(Error::InvalidInput(format!(
            "--regions '{s}': expected IN,OUT (e.g. 3,2)"
        ))),
    }
}

/// Runs the comparison and prints it.
pub fn run(a: &ShapeMeasure<'_>) -> Result<()> {
    let star = StarSurface::PAPER;
    let star_rho = move |d: DVec3| star.radius_towards(d);
    let sphere_rho = |_: DVec3| 0.5;
    let (exact, level_set): (RadialSurface<'_>, Box<dyn Fn(DVec3) -> f64>) = match a.shape {
        "star" => (
            RadialSurface {
                centre: DVec3::ZERO,
                rho: &star_rho,
                volume: star.exact_area().unwrap_or(f64::NAN),
            },
            // What `adapt --dim 3` adapts: the star's u seen as the first-order distance
            // u/|∇u| (the same zero level; its P1 interpolant is the adapted mesh's).
            Box::new(move |p| {
                Normalized {
                    inner: star,
                    cap: 4.0,
                }
                .distance(p)
            }),
        ),
        "sphere" => (
            RadialSurface {
                centre: DVec3::ZERO,
                rho: &sphere_rho,
                volume: 4.0 / 3.0 * std::f64::consts::PI * 0.125,
            },
            Box::new(|p: DVec3| p.length() - 0.5),
        ),
        s => {
            return Err(Error::InvalidInput(format!(
                "--shape '{s}': expected star (004 §5) or sphere (radius 0.5), both centred at \
                 the origin"
            )))
        }
    };
    let m = io::read_medit3(a.mesh)?;
    if m.tets.is_empty() {
        return Err(Error::InvalidInput(format!(
            "{}: no tetrahedra (--shape measures a tetrahedral mesh)",
            a.mesh.display()
        )));
    }
    let has = |r: i32| m.tet_ref.contains(&r);
    let regions = match (a.level_set, a.regions) {
        (Some(_), Some(_)) => {
            return Err(Error::InvalidInput(
                "--level-set and --regions: give one of them".into(),
            ))
        }
        (None, Some(r)) => Some(parse_regions(r)?),
        (None, None) if has(3) && has(2) => Some((3, 2)),
        _ => None,
    };
    let (triangles, volume, what) = if let Some((inside, outside)) = regions {
        let (t, v) = interface_triangles(&m.points, &m.tets, &m.tet_ref, inside, outside)?;
        (
            t,
            v,
            format!("the faces between regions {inside} and {outside}"),
        )
    } else {
        let (u, what) = match a.level_set {
            Some(p) => {
                let user = super::user_files::read_user_mesh(a.mesh)?;
                (
                    super::user_files::read_scalar(p, &user)?,
                    format!("the P1 zero level of {}", p.display()),
                )
            }
            None => (
                m.points.iter().map(|&p| level_set(p)).collect(),
                format!(
                    "the P1 zero level of the {}'s level set at the vertices",
                    a.shape
                ),
            ),
        };
        let (t, v) = zero_level_triangles(&m.points, &m.tets, &u)?;
        (t, v, what)
    };
    let c = compare_to_radial(&triangles, volume, &exact, a.level)?;
    if a.json {
        let v = serde_json::json!({
            "mesh": a.mesh.display().to_string(),
            "vertices": m.points.len(),
            "tetrahedra": m.tets.len(),
            "shape": a.shape,
            "discrete_surface": what,
            "comparison": c,
        });
        println!(
            "{}",
            serde_json::to_string_pretty(&v)
                .map_err(|e| Error::InvalidInput(format!("JSON output: {e}")))?
        );
    } else {
        print_comparison(a, m.points.len(), m.tets.len(), &what, &c);
    }
    Ok(())
}

fn print_comparison(
    a: &ShapeMeasure<'_>,
    vertices: usize,
    tets: usize,
    what: &str,
    c: &RadialComparison,
) {
    println!(
        "{}: {vertices} vertices, {tets} tetrahedra; {what}: {} triangles",
        a.mesh.display(),
        c.triangles
    );
    for (name, s) in [
        ("exact surface -> discrete", &c.exact_to_discrete),
        ("discrete -> exact surface", &c.discrete_to_exact),
    ] {
        println!(
            "  {name}: median {:.3e}  99th percentile {:.3e}  max {:.3e}  ({} samples)",
            s.median, s.p99, s.max, s.samples
        );
    }
    println!(
        "  volume {:.10}  exact {:.10}  error {:+.3e} (relative {:+.2e})",
        c.volume,
        c.exact_volume,
        c.volume_error,
        c.volume_error / c.exact_volume
    );
}
