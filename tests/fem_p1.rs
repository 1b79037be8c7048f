//! P1 matrices, CSR patterns, Dirichlet elimination and solvers: algebraic identities.

use anisomesh::fem::csr::{dot, Csr};
use anisomesh::fem::dirichlet::{apply_dirichlet, boundary_mask};
use anisomesh::fem::p1::{self, Coef};
use anisomesh::fem::solve::{cg, solve_lu, solve_spd, CgOptions, Cholesky, PrecondKind};
use anisomesh::{DVec2, GridPattern, Mesh2, Sym2};

/// A perturbed, unstructured-looking mesh of a skewed quadrilateral.
fn skewed_mesh() -> Mesh2 {
    let mut m = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 9, 7, GridPattern::UnionJack).unwrap();
    for p in &mut m.points {
        let q = *p;
        *p = DVec2::new(
            q.x + 0.3 * q.y + 0.03 * (7.0 * q.y).sin(),
            0.8 * q.y + 0.04 * (5.0 * q.x).sin() * q.x * (1.0 - q.x),
        );
    }
    m.check().unwrap();
    m
}

#[test]
fn pattern_is_sorted_with_diagonal_and_symmetric() {
    let m = skewed_mesh();
    let a = Csr::p1_pattern(&m).unwrap();
    assert_eq!(a.n, m.n_points());
    for i in 0..a.n {
        let row = &a.col[a.row_ptr[i]..a.row_ptr[i + 1]];
        assert!(row.windows(2).all(|w| w[0] < w[1]));
        assert!(row.contains(&(i as u32)));
        for &j in row {
            assert!(a.find(j as usize, i).is_some());
        }
    }
    // nnz = n + 2 * (number of edges)
    assert_eq!(a.nnz(), m.n_points() + 2 * m.edges().len());
    assert!(a.clone().add(0, a.n - 1, 1.0).is_err());
}

#[test]
fn mass_sums_to_area_and_lumped_is_row_sum() {
    let m = skewed_mesh();
    let mm = p1::mass(&m).unwrap();
    let ones = vec![1.0; m.n_points()];
    let total = dot(&ones, &mm.mul(&ones));
    assert!(
        (total - m.area()).abs() < 1e-14 * m.area(),
        "{total} vs {}",
        m.area()
    );
    let lumped = p1::lumped_mass(&m).unwrap();
    for (l, r) in lumped.iter().zip(mm.row_sums()) {
        assert!((l - r).abs() < 1e-15);
    }
    assert!(mm.asymmetry() == 0.0);
    // x^T M x = ∫ x^2 for the linear field x (exact: P1 field, mass matrix exact)
    let x: Vec<f64> = m.points.iter().map(|p| p.x).collect();
    let quad: f64 = m
        .live_tris()
        .map(|t| {
            let p = m.tri_points(t);
            let s = p[0].x + p[1].x + p[2].x;
            let s2 = p[0].x * p[0].x + p[1].x * p[1].x + p[2].x * p[2].x;
            m.tri_area(t) * (s * s + s2) / 12.0
        })
        .sum();
    assert!((dot(&x, &mm.mul(&x)) - quad).abs() < 1e-14);
}

#[test]
fn stiffness_kills_constants_and_integrates_gradients() {
    let m = skewed_mesh();
    let k = Sym2::new(3.0, -0.7, 0.9);
    let ks = vec![k; m.n_tris()];
    for coef in [
        Coef::Const(2.5),
        Coef::Tensor(&ks),
        Coef::Field(&|p: DVec2| 1.0 + p.x * p.y),
    ] {
        let a = p1::stiffness(&m, &coef).unwrap();
        let ones = vec![1.0; m.n_points()];
        let r = a.mul(&ones);
        assert!(r.iter().all(|v| v.abs() < 1e-13), "{}", r[0]);
        assert!(a.asymmetry() < 1e-15);
    }
    // For the linear field v = (1,2)·x: v^T A v = |Ω| (g^T K g).
    let a = p1::stiffness(&m, &Coef::Tensor(&ks)).unwrap();
    let g = DVec2::new(1.0, 2.0);
    let v: Vec<f64> = m.points.iter().map(|p| p.dot(g)).collect();
    let e = dot(&v, &a.mul(&v));
    assert!((e - m.area() * k.quad(g)).abs() < 1e-12);
}

#[test]
fn load_integrates_polynomials_exactly() {
    let m = skewed_mesh();
    // Σ_i b_i = ∫ f for any f of degree <= 4 (degree-5 rule, φ sum to 1).
    let f = |p: DVec2| p.x.powi(3) * p.y - 2.0 * p.y * p.y + 1.0;
    let b = p1::load(&m, f).unwrap();
    let exact: f64 = m
        .live_tris()
        .map(|t| {
            let p = m.tri_points(t);
            m.tri_area(t)
                * anisomesh::fem::quadrature::tri_rule(7)
                    .mean(|l| f(l[0] * p[0] + l[1] * p[1] + l[2] * p[2]))
        })
        .sum();
    assert!((b.iter().sum::<f64>() - exact).abs() < 1e-13);
}

#[test]
fn dirichlet_elimination_keeps_symmetry_and_reproduces_linear_fields() {
    let m = skewed_mesh();
    let mut a = p1::stiffness(&m, &Coef::Const(1.0)).unwrap();
    let mut b = vec![0.0; m.n_points()];
    let fixed = boundary_mask(&m, &[]);
    let lin = |p: DVec2| 0.3 + 2.0 * p.x - p.y;
    let g = p1::interpolate(&m, lin);
    apply_dirichlet(&mut a, &mut b, &fixed, &g).unwrap();
    assert_eq!(a.asymmetry(), 0.0);
    // A harmonic (linear) field is reproduced exactly by every solver.
    let x = solve_spd(&a, &b).unwrap();
    let y = solve_lu(&a, &b).unwrap();
    let mut z = vec![0.0; m.n_points()];
    let rep = cg(&a, &b, &mut z, &CgOptions::default()).unwrap();
    assert!(rep.converged);
    for i in 0..m.n_points() {
        assert!((x[i] - g[i]).abs() < 1e-12);
        assert!((y[i] - g[i]).abs() < 1e-12);
        assert!((z[i] - g[i]).abs() < 1e-8);
    }
}

#[test]
fn lu_solves_a_nonsymmetric_system_and_cholesky_rejects_indefinite() {
    // Convection-diffusion-like nonsymmetric matrix.
    let n = 50;
    let mut t = vec![];
    for i in 0..n as u32 {
        t.push((i, i, 4.0));
        if i > 0 {
            t.push((i, i - 1, -1.5));
        }
        if i + 1 < n as u32 {
            t.push((i, i + 1, -0.5));
        }
    }
    t.push((3, 40, 0.7));
    let a = Csr::from_triplets(n, &t).unwrap();
    let xs: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
    let b = a.mul(&xs);
    let x = solve_lu(&a, &b).unwrap();
    for i in 0..n {
        assert!((x[i] - xs[i]).abs() < 1e-13);
    }
    let ind = Csr::from_triplets(2, &[(0, 0, 1.0), (1, 1, -1.0)]).unwrap();
    assert!(Cholesky::new(&ind).is_err());
}

#[test]
fn cg_reports_non_convergence_instead_of_failing() {
    let m = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 20, 20, GridPattern::Right).unwrap();
    let mut a = p1::stiffness(&m, &Coef::Const(1.0)).unwrap();
    let mut b = p1::load(&m, |_| 1.0).unwrap();
    let fixed = boundary_mask(&m, &[]);
    apply_dirichlet(&mut a, &mut b, &fixed, &vec![0.0; m.n_points()]).unwrap();
    let mut x = vec![0.0; m.n_points()];
    let opts = CgOptions {
        max_iter: 3,
        precond: PrecondKind::Jacobi,
        ..Default::default()
    };
    let rep = cg(&a, &b, &mut x, &opts).unwrap();
    assert!(!rep.converged && rep.iterations == 3 && rep.residual > 1e-6);
}

#[test]
fn matvec_and_cg_are_identical_for_one_and_two_threads() {
    let m = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 60, 60, GridPattern::CrissCross).unwrap();
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut a = p1::stiffness(&m, &Coef::Field(&|p: DVec2| 1.0 + p.x)).unwrap();
            p1::add_mass(&mut a, &m, 0.5).unwrap();
            let b = p1::load(&m, |p| (3.0 * p.x).sin() + p.y).unwrap();
            let mut x = vec![0.0; m.n_points()];
            let opts = CgOptions {
                precond: PrecondKind::Jacobi,
                ..Default::default()
            };
            let rep = cg(&a, &b, &mut x, &opts).unwrap();
            (a.val, x, rep.iterations)
        })
    };
    let (a1, x1, i1) = run(1);
    let (a2, x2, i2) = run(2);
    assert_eq!(i1, i2);
    assert!(
        a1 == a2 && x1 == x2,
        "results differ between 1 and 2 threads"
    );
}
