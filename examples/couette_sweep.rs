//! temp experiment
use anisomesh::adapt::{adapt_to_shape, LevelSetMetric, ShapeAdaptOptions};
use anisomesh::flows::{CouetteCase, StokesSolver, Viscosity};
use anisomesh::levelset::Circle;
use anisomesh::DVec2;
use anisomesh::Mesh2;

fn frac_inside(f: [f64; 3]) -> f64 {
    let neg = f.iter().filter(|v| **v < 0.0).count();
    match neg {
        0 => 0.0,
        3 => 1.0,
        _ => {
            // lone vertex a
            let lone_neg = neg == 1;
            let a = (0..3).find(|&i| (f[i] < 0.0) == lone_neg).unwrap();
            let (b, c) = ((a + 1) % 3, (a + 2) % 3);
            let corner = f[a] * f[a] / ((f[a] - f[b]) * (f[a] - f[c]));
            if lone_neg {
                corner
            } else {
                1.0 - corner
            }
        }
    }
}

fn per_elem(mesh: &Mesh2, phi: &[f64], harmonic: bool) -> Vec<f64> {
    let (mi, mo) = (1.0, 1e-6);
    (0..mesh.n_tris())
        .map(|t| {
            let f = mesh.tris[t].map(|i| phi[i as usize]);
            let fr = frac_inside(f);
            if harmonic {
                1.0 / (fr / mi + (1.0 - fr) / mo)
            } else {
                fr * mi + (1.0 - fr) * mo
            }
        })
        .collect()
}

fn main() -> anisomesh::Result<()> {
    let case = CouetteCase::default();
    let solver = StokesSolver::Uzawa {
        rtol: 1e-10,
        max_iter: 3000,
    };
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().unwrap())
        .collect();
    for c in args.chunks(5) {
        let (eps, hmin, hmax, band, grade) = (c[0], c[1], c[2], c[3], c[4]);
        let metric = LevelSetMetric {
            eps,
            hmin,
            hmax,
            band,
            grade,
            ..Default::default()
        };
        let sopts = ShapeAdaptOptions {
            metric,
            ..Default::default()
        };
        let shape = Circle {
            centre: DVec2::splat(0.5),
            radius: 0.1,
        };
        let (mesh, phi, _) = adapt_to_shape(&shape, (DVec2::ZERO, DVec2::ONE), &sopts)?;
        let visc = Viscosity::TwoPhase {
            phi: phi.clone(),
            mu_in: 1.0,
            mu_out: 1e-6,
            width: 0.0,
        };
        let mut line = format!(
            "eps {eps:.0e} hmin {hmin:.0e} hmax {hmax} band {band:.0e} gr {grade} nv {:6}",
            mesh.n_points()
        );
        for (name, v) in [
            ("quad", visc.clone()),
            ("harm", Viscosity::PerElement(per_elem(&mesh, &phi, true))),
            ("arit", Viscosity::PerElement(per_elem(&mesh, &phi, false))),
        ] {
            let r = case.solve_with(&mesh, v, solver)?;
            line += &format!(
                " | {name} {:+.2e} rig {:.1e} it {:4}",
                r.fit.omega + 1.0,
                r.fit.max_deviation_rel,
                r.report.uzawa_iterations
            );
        }
        println!("{line}");
    }
    Ok(())
}
