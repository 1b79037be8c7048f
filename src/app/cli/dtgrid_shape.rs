//! `anisomesh dtgrid heat|mcf --shape sphere|torus|star` or `--expr "..."`: one run of the band
//! problems of 000 §2 on the zero level of any implicit function in (−½, ½)³, mean curvature
//! motion through the DT-Grid back end ([`DtGridBackend`]) and the heat equation through
//! [`shape_heat`]. Writes the row report (`dtgrid_mcf.json` / `dtgrid_heat.json` and CSV, with
//! `radius_final` and `radius_exact` when the shape is a sphere), the zero level as `.vtu`, a
//! shaded picture of the surface and a picture of a slice of the band (nodes coloured by value).

use crate::app::plot::surface::{render_surfaces, SurfacePanel, View};
use crate::app::repro::dtgrid::{format_table, write_rows, Row};
use crate::app::repro::surface_mcf::write_surface_vtu;
use anisomesh::backends::dtgrid::lattice::{Lattice, C3};
use anisomesh::backends::dtgrid::mcf::McfOptions;
use anisomesh::backends::dtgrid::scheme::Bc;
use anisomesh::backends::dtgrid::shape_heat::shape_heat;
use anisomesh::backends::dtgrid::{Band, DtGrid, DtGridBackend, DtGridOptions};
use anisomesh::backends::{BuildSpec, LevelSetBackend, D3};
use anisomesh::levelset::{Expr, Shape, StarSurface, Torus, TriangleSurface, Variables};
use anisomesh::{DVec3, Error, Result};
use std::path::Path;
use std::time::Instant;

/// The options of one shape run.
#[derive(Debug, Clone)]
pub struct ShapeRun<'a> {
    /// Grid nodes per side.
    pub n: usize,
    /// Band half-width `j`.
    pub band: usize,
    /// Boundary condition name.
    pub bc: &'a str,
    /// Most solves per step (mcf).
    pub inner: usize,
    /// Time step (default `h²`).
    pub tau: Option<f64>,
    /// Final time.
    pub t_end: f64,
    /// `sphere`, `torus` or `star` (default sphere).
    pub shape: Option<&'a str>,
    /// An implicit function of `x, y, z`, negative inside.
    pub expr: Option<&'a str>,
    /// Output directory.
    pub output: &'a Path,
}

type Function = Box<dyn Fn(DVec3) -> f64 + Send + Sync>;

/// The implicit function, its name and its radius when it is a sphere about the origin.
fn implicit(r: &ShapeRun, sphere_radius: f64) -> Result<(Function, String, Option<f64>)> {
    if let Some(src) = r.expr {
        let e = Expr::parse_with(src, Variables::XYZ)?;
        return Ok((Box::new(move |p| e.eval3(p)), src.to_string(), None));
    }
    Ok(match r.shape.unwrap_or("sphere") {
        "sphere" => (
            Box::new(move |p: DVec3| p.length() - sphere_radius),
            format!("sphere r = {sphere_radius:.4}"),
            Some(sphere_radius),
        ),
        "torus" => {
            let t = Torus {
                centre: DVec3::ZERO,
                major: 0.25,
                minor: 0.1,
            };
            (
                Box::new(move |p| t.distance(p)),
                "torus R = 0.25, r = 0.1".into(),
                None,
            )
        }
        "star" => {
            let s = StarSurface {
                centre: DVec3::ZERO,
                r0: 0.225,
                amplitude: 0.15,
            };
            (
                Box::new(move |p| s.distance(p)),
                "star ρ = 0.225 + 0.15 cos 6θ cos² 3φ".into(),
                None,
            )
        }
        other => {
            return Err(Error::InvalidInput(format!(
                "--shape {other}: sphere, torus or star"
            )))
        }
    })
}

/// The grid spacing of `n` nodes per side on (−½, ½)³.
fn spacing(n: usize) -> Result<f64> {
    Ok(Lattice::unit(n)?.h)
}

/// Area-weighted means of `(||x| − r|, |x|)` over the triangles (centroid rule).
fn sphere_means(s: &TriangleSurface, r: f64) -> (f64, f64) {
    let (mut e, mut m, mut area) = (0.0, 0.0, 0.0);
    for t in &s.triangles {
        let [a, b, c] = t.map(|i| s.points[i as usize]);
        let w = 0.5 * (b - a).cross(c - a).length();
        let x = ((a + b + c) / 3.0).length();
        e += w * (x - r).abs();
        m += w * x;
        area += w;
    }
    (e / area, m / area)
}

/// The cells of the grid plane `z = k` whose four corners are band nodes, as two triangles each
/// (world coordinates), with the band values at their vertices.
fn band_slice(
    lat: &Lattice,
    band: &DtGrid<C3>,
    phi: &[f64],
    shift: DVec3,
    k: i32,
) -> (TriangleSurface, Vec<f64>) {
    let mut s = TriangleSurface::default();
    let mut vals = Vec::new();
    for c in band.coords().filter(|c| c[2] == k) {
        let quad =
            [[0, 0], [1, 0], [1, 1], [0, 1]].map(|[i, j]| band.index([c[0] + i, c[1] + j, k]));
        if let [Some(a), Some(b), Some(cc), Some(d)] = quad {
            let base = s.points.len() as u32;
            for (i, (dx, dy)) in [(0, 0), (1, 0), (1, 1), (0, 1)].into_iter().enumerate() {
                s.points.push(lat.pos([c[0] + dx, c[1] + dy, k]) + shift);
                vals.push(phi[[a, b, cc, d][i]]);
            }
            s.triangles.push([base, base + 1, base + 2]);
            s.triangles.push([base, base + 2, base + 3]);
        }
    }
    (s, vals)
}

/// Writes `<name>_surface.vtu`, `<name>_surface.png` (the given panels) and `<name>_band.png`
/// (the slice of the band through the middle of the final surface); returns the paths written.
fn write_pictures(
    dir: &Path,
    name: &str,
    panels: &[SurfacePanel],
    last: &TriangleSurface,
    slice: (&Lattice, &DtGrid<C3>, &[f64], DVec3),
) -> Result<Vec<String>> {
    let vtu = dir.join(format!("{name}_surface.vtu"));
    write_surface_vtu(&vtu, last)?;
    let png = dir.join(format!("{name}_surface.png"));
    render_surfaces(&png, panels, &View::default())?;
    let (lat, band, phi, shift) = slice;
    let zs = last.points.iter().map(|p| p.z);
    let (zlo, zhi) = zs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), z| {
        (a.min(z), b.max(z))
    });
    let k = ((0.5 * (zlo + zhi) - shift.z - lat.lo) / lat.h).round() as i32;
    let (s, v) = band_slice(lat, band, phi, shift, k);
    let band_png = dir.join(format!("{name}_band.png"));
    let view = View {
        colour_label: "u".into(),
        size: 700,
        ..View::facing(DVec3::Z)
    };
    let title = format!(
        "band nodes on z = {:.3}",
        lat.lo + shift.z + k as f64 * lat.h
    );
    render_surfaces(
        &band_png,
        &[SurfacePanel {
            surface: &s,
            scalars: Some(&v),
            title,
        }],
        &view,
    )?;
    Ok([vtu, png, band_png]
        .iter()
        .map(|p| p.display().to_string())
        .collect())
}

/// Mean curvature motion of the zero level through the DT-Grid back end.
pub fn mcf(r: &ShapeRun) -> Result<()> {
    let t0 = Instant::now();
    let (f, name, sphere) = implicit(r, 0.25)?;
    let h = spacing(r.n)?;
    let tau0 = r.tau.unwrap_or(h * h);
    if !(tau0.is_finite() && tau0 > 0.0 && r.t_end.is_finite() && r.t_end > 0.0) {
        return Err(Error::InvalidInput(format!(
            "--tau {tau0} and --t-end {} must be positive",
            r.t_end
        )));
    }
    let steps = (r.t_end / tau0 - 1e-9).ceil().max(1.0) as usize;
    let tau = r.t_end / steps as f64;
    let opts = DtGridOptions {
        mcf: McfOptions {
            j: r.band,
            bc: Bc::parse(r.bc)?,
            inner: r.inner,
            ..McfOptions::default()
        },
        tau_per_h2: tau / (h * h) * (1.0 + 1e-9),
        ..DtGridOptions::default()
    };
    let spec = BuildSpec::<D3> {
        function: &*f,
        domain: (DVec3::splat(-0.5), DVec3::splat(0.5)),
        resolution: h,
    };
    let mut b = DtGridBackend::new(&spec, opts)?;
    let first = b.zero_level()?;
    let mut solves = 0;
    for _ in 0..steps {
        solves += b.advance_mean_curvature(tau)?.inner_iterations;
    }
    let last = b.zero_level()?;
    let exact = sphere.map(|r0| (r0 * r0 - 4.0 * r.t_end).max(0.0).sqrt());
    let (error, radius_final) = match exact {
        Some(e) => {
            let (err, mean) = sphere_means(&last, e);
            (err, Some(mean))
        }
        None => (f64::NAN, None),
    };
    let row = Row {
        n: r.n,
        h,
        band: r.band,
        bc: r.bc.into(),
        inner: solves as f64 / steps as f64,
        tau,
        time: "euler".into(),
        error,
        paper_error: None,
        nodes: b.dof(),
        seconds: t0.elapsed().as_secs_f64(),
        radius_final,
        radius_exact: exact,
    };
    println!(
        "{name} by mean curvature to t = {} on {}³, {steps} steps (DT-Grid back end)",
        r.t_end, r.n
    );
    print!("{}", format_table(std::slice::from_ref(&row)));
    if let (Some(f), Some(e)) = (radius_final, exact) {
        println!("radius_final {f:.6}, radius_exact {e:.6}");
    }
    println!(
        "volume {:.6e}, area {:.6e}",
        b.enclosed_measure()?,
        b.interface_measure()?
    );
    write_rows(r.output, "dtgrid_mcf", &[row])?;
    let panels = [
        SurfacePanel {
            surface: &first,
            scalars: None,
            title: "t = 0".into(),
        },
        SurfacePanel {
            surface: &last,
            scalars: None,
            title: format!("t = {}", r.t_end),
        },
    ];
    let band = (b.lattice(), b.band(), b.values(), b.shift());
    for p in write_pictures(r.output, "dtgrid_mcf", &panels, &last, band)? {
        println!("wrote {p}");
    }
    Ok(())
}

/// The heat equation on the zero level with the initial data `(z/|x|)² − 1/3` (000 §2.1).
pub fn heat(r: &ShapeRun) -> Result<()> {
    let t0 = Instant::now();
    let (f, name, sphere) = implicit(r, 1.0 / 3.0)?;
    let lat = Lattice::unit(r.n)?;
    let y = |p: DVec3| {
        let l = p.length().max(1e-300);
        (p.z / l).powi(2) - 1.0 / 3.0
    };
    let exact = sphere.map(|rs| {
        let decay = (-6.0 * r.t_end / (rs * rs)).exp();
        move |p: DVec3| decay * y(p)
    });
    let out = shape_heat(
        lat,
        r.band,
        Bc::parse(r.bc)?,
        &f,
        y,
        r.tau.unwrap_or(lat.h * lat.h),
        r.t_end,
        exact.as_ref().map(|e| e as &dyn Fn(DVec3) -> f64),
    )?;
    let row = Row {
        n: r.n,
        h: lat.h,
        band: r.band,
        bc: r.bc.into(),
        inner: 1.0,
        tau: out.tau,
        time: "euler".into(),
        error: out.error.unwrap_or(f64::NAN),
        paper_error: None,
        nodes: out.state.nb.band.len(),
        seconds: t0.elapsed().as_secs_f64(),
        radius_final: None,
        radius_exact: None,
    };
    println!(
        "heat equation on {name} to t = {} on {}³, {} steps",
        r.t_end, r.n, out.steps
    );
    print!("{}", format_table(std::slice::from_ref(&row)));
    write_rows(r.output, "dtgrid_heat", &[row])?;
    let panels = [SurfacePanel {
        surface: &out.surface,
        scalars: Some(&out.surface_u),
        title: format!("u at t = {}", r.t_end),
    }];
    let band = (&out.state.lat, &out.state.nb.band, &out.u[..], DVec3::ZERO);
    for p in write_pictures(r.output, "dtgrid_heat", &panels, &out.surface, band)? {
        println!("wrote {p}");
    }
    Ok(())
}
