//! The adapted-mesh back end through the level-set back-end contract: measured areas,
//! perimeters, curvatures, mean curvature motion of a circle, rotation and redistancing.

use anisomesh::backends::{AdaptedBackend, AdaptedOptions, BuildSpec, LevelSetBackend, D2};
use anisomesh::levelset::{Circle, Shape};
use anisomesh::DVec2;
use std::f64::consts::PI;

const LO: DVec2 = DVec2::new(-1.0, -1.0);
const HI: DVec2 = DVec2::new(1.0, 1.0);

fn build(shape: &dyn Shape, h: f64, opts: AdaptedOptions) -> AdaptedBackend {
    let spec = BuildSpec::<D2> {
        function: shape,
        domain: (LO, HI),
        resolution: h,
    };
    AdaptedBackend::new(&spec, opts).expect("build")
}

fn circle(r: f64) -> Circle {
    Circle {
        centre: DVec2::new(0.1, -0.05),
        radius: r,
    }
}

/// Radius of the circle with the back end's enclosed area.
fn radius(b: &dyn LevelSetBackend<D2>) -> f64 {
    (b.enclosed_measure().unwrap() / PI).sqrt()
}

/// Area-weighted mean and maximum of `||∇u_h| − 1|` over the triangles whose vertices all lie
/// within `width` of the zero level.
fn gradient_defect(b: &AdaptedBackend, width: f64) -> (f64, f64) {
    let (mesh, u) = (b.mesh(), b.values());
    let (mut sum, mut area, mut max) = (0.0, 0.0, 0.0f64);
    for t in mesh.live_tris() {
        let tri = mesh.tris[t];
        if tri.iter().any(|&v| u[v as usize].abs() > width) {
            continue;
        }
        let [p0, p1, p2] = mesh.tri_points(t);
        let (e1, e2) = (p1 - p0, p2 - p0);
        let det = e1.perp_dot(e2);
        let (d1, d2) = (
            u[tri[1] as usize] - u[tri[0] as usize],
            u[tri[2] as usize] - u[tri[0] as usize],
        );
        // Solve [e1; e2] g = [d1; d2].
        let g = DVec2::new(d1 * e2.y - d2 * e1.y, e1.x * d2 - e2.x * d1) / det;
        let dev = (g.length() - 1.0).abs();
        let a = mesh.tri_area(t);
        sum += a * dev;
        area += a;
        max = max.max(dev);
    }
    (sum / area, max)
}

#[test]
fn explore() {
    for h in [0.01, 0.005] {
        let c = circle(0.5);
        let t = std::time::Instant::now();
        let b = build(&c, h, AdaptedOptions::default());
        let area = b.enclosed_measure().unwrap();
        let per = b.interface_measure().unwrap();
        let k = b.interface_curvature().unwrap();
        let (gm, gx) = gradient_defect(&b, 5.0 * h);
        eprintln!(
            "h {h}: {} vertices, {:.2}s, area rel {:.2e}, perimeter rel {:.2e}, kappa mean {:.4} range {:?} maxrel {:.3}, grad {gm:.2e} {gx:.2e}",
            b.dof(),
            t.elapsed().as_secs_f64(),
            area / (PI * 0.25) - 1.0,
            per / PI - 1.0,
            k.mean(),
            k.range(),
            k.max_rel_error(2.0)
        );
    }
}

#[test]
fn explore_mcf() {
    for (h, dt) in [(0.01f64, 0.004f64), (0.005, 0.002)] {
        let c = circle(0.5);
        let t = std::time::Instant::now();
        let mut b = build(&c, h, AdaptedOptions::default());
        let steps = (0.06 / dt).round() as usize;
        let mut err = 0.0f64;
        for _ in 0..steps {
            let rep = b.advance_mean_curvature(dt).unwrap();
            let exact = (0.25 - 2.0 * rep.time).sqrt();
            let r = radius(&b);
            err = err.max((r - exact).abs());
            eprintln!(
                "  t {:.3} R {r:.5} exact {exact:.5} err {:.2e} dof {} cg {} inner {} conv {} {:.2}s",
                rep.time,
                r - exact,
                rep.dof,
                rep.linear_iterations,
                rep.inner_iterations,
                rep.converged,
                rep.seconds
            );
        }
        eprintln!(
            "h {h} dt {dt}: max err {err:.2e}, {:.2}s",
            t.elapsed().as_secs_f64()
        );
    }
}

#[test]
fn explore_readapt() {
    let c = circle(0.5);
    let mut b = build(&c, 0.005, AdaptedOptions::default());
    eprintln!("R0 {:.6}", radius(&b));
    for _ in 0..10 {
        b.advance_mean_curvature(1e-9).unwrap();
        eprintln!("R {:.6} dof {}", radius(&b), b.dof());
    }
}

#[test]
fn explore_laplacian() {
    use anisomesh::fem::p1::{lumped_mass, mass, stiffness, Coef};
    use anisomesh::fem::solve::cg;
    use anisomesh::fem::CgOptions;
    for aniso in [1e4, 1.0001] {
        let c = circle(0.5);
        let opts = AdaptedOptions {
            max_aniso: aniso,
            ..AdaptedOptions::default()
        };
        let b = build(&c, 0.005, opts);
        let (mesh, u) = (b.mesh(), b.values());
        let k = stiffness(mesh, &Coef::Const(1.0)).unwrap();
        let m = mass(mesh).unwrap();
        let ml = lumped_mass(mesh).unwrap();
        let ku: Vec<f64> = k.mul(u).iter().map(|v| -v).collect();
        let mut x = vec![0.0; u.len()];
        cg(&m, &ku, &mut x, &CgOptions::default()).unwrap();
        let (mut s1, mut s2, mut n) = (0.0, 0.0, 0);
        for v in 0..u.len() {
            if u[v].abs() < 0.005 {
                let r = (mesh.points[v] - c.centre).length();
                s1 += x[v] * r;
                s2 += ku[v] / ml[v] * r;
                n += 1;
            }
        }
        eprintln!(
            "aniso {aniso}: dof {} consistent lap*r mean {:.4}, lumped {:.4}",
            b.dof(),
            s1 / n as f64,
            s2 / n as f64
        );
    }
}
