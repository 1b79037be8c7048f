//! Error sources of the Zalesak rotation (004 §5.1) on a fixed uniform mesh, one at a time:
//! the initial P1 representation (area/perimeter of the interpolated exact distance), the foot
//! of the characteristics (exact rotation vs RK4 with sub-steps vs one midpoint step), the
//! evaluation at the feet (nodal P1 / nodal quadratic / L2-projected P1, 004 eq. (2)) and the
//! number of periods (16 vs 32).
//!
//! Usage: `cargo run --release --example zalesak_sources -- [n]` (default 200).

use anisomesh::advect::galerkin::pull_back;
use anisomesh::advect::{
    enclosed_area, interface_length, AdvectOptions, FieldEvaluator, FootOptions, FootScheme, Form,
    Inflow, Interpolation,
};
use anisomesh::bench::zalesak::{EXACT_AREA, EXACT_PERIMETER};
use anisomesh::levelset::shapes::{Shape, Zalesak};
use anisomesh::{DVec2, GridPattern, Mesh2};

fn main() -> anisomesh::Result<()> {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        // ANISOMESH_QUICK=1 (CI): a coarse grid.
        .unwrap_or(if std::env::var_os("ANISOMESH_QUICK").is_some() {
            60
        } else {
            200
        });
    let lo = DVec2::splat(-2.0);
    let mesh = Mesh2::rectangle(lo, -lo, n, n, GridPattern::UnionJack)?;
    let shape = Zalesak::default();
    let u0: Vec<f64> = mesh.points.iter().map(|&p| shape.distance(p)).collect();
    let (a0, p0) = (
        enclosed_area(&mesh, &u0).unwrap(),
        interface_length(&mesh, &u0).unwrap(),
    );
    println!(
        "n = {n}: initial P1 representation: area {:+.3e}, perimeter {:+.3e} (relative to exact)",
        (a0 - EXACT_AREA) / EXACT_AREA,
        (p0 - EXACT_PERIMETER) / EXACT_PERIMETER
    );
    let run = |periods: usize, foot: Option<FootOptions>, form: Form, interp: Interpolation| {
        let dt = 2.0 * std::f64::consts::PI / periods as f64;
        let (s, c) = dt.sin_cos();
        let mut u = u0.clone();
        for k in 0..periods {
            let eval = FieldEvaluator::new(&mesh, &u, interp, Inflow::Nearest).unwrap();
            u = match foot {
                // The exact foot of the rotation: x rotated by -dt.
                None => pull_back(
                    &eval,
                    &mesh,
                    &|x: DVec2| DVec2::new(c * x.x + s * x.y, -s * x.x + c * x.y),
                    form,
                    1e-12,
                )
                .unwrap(),
                Some(f) => {
                    let opts = AdvectOptions {
                        foot: f,
                        form,
                        interp,
                        ..AdvectOptions::default()
                    };
                    let v = anisomesh::advect::Rotation { omega: 1.0 };
                    anisomesh::advect::advect(
                        &mesh,
                        &u,
                        &mesh,
                        &v,
                        k as f64 * dt,
                        (k + 1) as f64 * dt,
                        &opts,
                    )
                    .unwrap()
                }
            };
        }
        let (a, p) = (
            enclosed_area(&mesh, &u).unwrap(),
            interface_length(&mesh, &u).unwrap(),
        );
        println!(
            "  {periods:2} periods, foot {:<38} {:<36} area drift {:+.3e}, perimeter drift {:+.3e}",
            match foot {
                None => "exact".to_string(),
                Some(f) => format!("{:?} x{}", f.scheme, f.substeps),
            },
            format!("{form:?} {interp:?}"),
            (a - a0) / EXACT_AREA,
            (p - p0) / EXACT_PERIMETER
        );
    };
    let l2 = Form::L2Projection { subdivisions: 0 };
    let rk4 = Some(FootOptions {
        scheme: FootScheme::Rk4,
        substeps: 4,
    });
    run(16, None, l2, Interpolation::P1);
    run(16, rk4, l2, Interpolation::P1);
    run(
        16,
        Some(FootOptions {
            scheme: FootScheme::Rk4,
            substeps: 1,
        }),
        l2,
        Interpolation::P1,
    );
    run(
        16,
        Some(FootOptions {
            scheme: FootScheme::Midpoint,
            substeps: 1,
        }),
        l2,
        Interpolation::P1,
    );
    run(16, None, Form::Nodal, Interpolation::P1);
    run(16, None, Form::Nodal, Interpolation::QUADRATIC);
    run(16, None, l2, Interpolation::QUADRATIC);
    run(
        16,
        None,
        Form::L2Projection { subdivisions: 1 },
        Interpolation::P1,
    );
    run(32, None, l2, Interpolation::P1);
    run(8, None, l2, Interpolation::P1);
    Ok(())
}
