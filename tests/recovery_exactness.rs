//! Exactness of the derivative recoveries (004 §4.3 least squares, 003 §6.2 PPR, double L2
//! projection): quadratics reproduced to round-off by the least-squares Hessian and gradient and
//! by PPR at *every* vertex (boundary and corners included) on perturbed unstructured meshes,
//! boundary-heavy meshes, stretched meshes of aspect ratio 100 and 1e4, and (property test) random
//! affine images of perturbed meshes; linear fields reproduced by all methods, also where the
//! lower-degree fallback is needed; input errors reported, not panicked on; results independent of
//! the thread count.

#[path = "recovery_common.rs"]
mod common;

use anisomesh::recovery::{gradient_ls, gradient_ppr, hessian_double_l2, hessian_ls, recover_ls};
use anisomesh::{DVec2, Error, GridPattern, Mesh2, Sym2};
use common::*;

const TOL: f64 = 1e-10;

/// Meshes for the exactness checks: perturbed UnionJack and CrissCross grids (up to 0.3 h) and
/// boundary-heavy small ones (most vertices on the boundary).
fn meshes() -> Vec<(String, Mesh2)> {
    let mut out = Vec::new();
    for (n, pattern) in [
        (8, GridPattern::UnionJack),
        (16, GridPattern::UnionJack),
        (8, GridPattern::CrissCross),
        (12, GridPattern::Right),
    ] {
        out.push((
            format!("{pattern:?} {n}x{n} perturbed"),
            perturbed_square(n, pattern, 0.3, 17 + n as u64),
        ));
    }
    let mut small = Mesh2::rectangle(
        DVec2::ZERO,
        DVec2::new(2.0, 1.0),
        4,
        2,
        GridPattern::UnionJack,
    )
    .unwrap();
    perturb(&mut small, 0.5, 0.3, 5);
    out.push((
        "UnionJack 4x2 (12 of 15 vertices on the boundary)".into(),
        small,
    ));
    let cc = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 2, 2, GridPattern::CrissCross).unwrap();
    out.push(("CrissCross 2x2".into(), cc));
    out.push(("pentagon fan (6 vertices)".into(), pentagon()));
    out
}

/// The smallest accepted mesh: a centre vertex and a regular pentagon around it.
fn pentagon() -> Mesh2 {
    let mut pts = vec![DVec2::new(0.1, -0.05)];
    for k in 0..5 {
        let a = std::f64::consts::TAU * k as f64 / 5.0;
        pts.push(DVec2::new(a.cos(), a.sin()));
    }
    let tris = (0..5u32).map(|k| [0, 1 + k, 1 + (k + 1) % 5]).collect();
    let m = Mesh2::from_triangles(pts, tris).unwrap();
    m.check().unwrap();
    m
}

#[test]
fn quadratics_are_recovered_exactly_at_every_vertex() {
    for (name, mesh) in meshes() {
        let u = sample(&mesh, &QUAD);
        let r = recover_ls(&mesh, &u).unwrap();
        let (vh, eh) = worst(&hessian_errors(&mesh, &QUAD, &r.hessian));
        let (vg, eg) = worst(&gradient_errors(&mesh, &QUAD, &r.gradient));
        let (vp, ep) = worst(&gradient_errors(
            &mesh,
            &QUAD,
            &gradient_ppr(&mesh, &u).unwrap(),
        ));
        println!("{name}: LS Hessian {eh:.1e} (vertex {vh}), LS gradient {eg:.1e} (vertex {vg}), PPR gradient {ep:.1e} (vertex {vp})");
        assert!(eh <= TOL, "{name}: LS Hessian error {eh:e} at vertex {vh}");
        assert!(eg <= TOL, "{name}: LS gradient error {eg:e} at vertex {vg}");
        assert!(
            ep <= TOL,
            "{name}: PPR gradient error {ep:e} at vertex {vp}"
        );
        // The convenience wrappers return the same numbers.
        assert_eq!(hessian_ls(&mesh, &u).unwrap(), r.hessian);
        assert_eq!(gradient_ls(&mesh, &u).unwrap(), r.gradient);
    }
}

#[test]
fn linear_fields_are_recovered_exactly_by_all_methods() {
    for (name, mesh) in meshes() {
        let u = sample(&mesh, &LINEAR);
        let r = recover_ls(&mesh, &u).unwrap();
        let l2 = hessian_double_l2(&mesh, &u).unwrap();
        let ppr = gradient_ppr(&mesh, &u).unwrap();
        let e_ls_h = worst(&hessian_errors(&mesh, &LINEAR, &r.hessian)).1;
        let e_ls_g = worst(&gradient_errors(&mesh, &LINEAR, &r.gradient)).1;
        let e_ppr = worst(&gradient_errors(&mesh, &LINEAR, &ppr)).1;
        let e_l2 = worst(&hessian_errors(&mesh, &LINEAR, &l2)).1;
        println!(
            "{name}: LS H {e_ls_h:.1e}, LS g {e_ls_g:.1e}, PPR g {e_ppr:.1e}, L2 H {e_l2:.1e}"
        );
        for (what, e) in [
            ("LS Hessian", e_ls_h),
            ("LS gradient", e_ls_g),
            ("PPR gradient", e_ppr),
            ("double L2 Hessian", e_l2),
        ] {
            assert!(e <= TOL, "{name}: {what} error {e:e} on a linear field");
        }
    }
}

/// Stretched grids of aspect ratio `k` (cells `hx = k hy`) — `k = 100` axis-aligned and rotated by
/// 30 degrees, `k = 1e4` rotated — with a field of matching anisotropy `u = q(S R^T p)`,
/// `S = diag(1, k)` (Hessian entries up to `4.6 k^2`). The round-off floor of derivatives from
/// nodal values is relative to the derivative's size (`eps |u| / hy^2` for the Hessian, and the
/// rotated coordinates themselves are only known to `eps / hy ~ 1e-11` relative at `k = 1e4`), so
/// errors are measured relative to the exact derivative's size. Measured: `k = 100`: LS Hessian
/// 1.9e-14 (aligned) and 3.7e-13 (rotated), gradients <= 1.9e-14; `k = 1e4`: 2.1e-11 and 1.7e-12.
/// Asserted: <= 1e-10 at `k = 100`, <= 1e-9 at `k = 1e4`.
#[test]
fn stretched_meshes_of_aspect_100_and_1e4_still_recover_quadratics() {
    let (nx, ny) = (12, 12);
    for (aspect, angle_deg, tol) in [
        (100.0f64, 0.0f64, TOL),
        (100.0, 30.0, TOL),
        (1e4, 30.0, 1e-9),
    ] {
        let mut mesh = Mesh2::rectangle(
            DVec2::ZERO,
            DVec2::new(1.0, 1.0 / aspect),
            nx,
            ny,
            GridPattern::UnionJack,
        )
        .unwrap();
        perturb(&mut mesh, 1.0 / (aspect * ny as f64), 0.2, 3); // moves of 0.2 hy
        let rot = DVec2::from_angle(angle_deg.to_radians());
        for p in &mut mesh.points {
            *p = rot.rotate(*p);
        }
        mesh.check().unwrap();
        // q0(S R^T p) with S = diag(1, aspect): in global coordinates g = R S g0 and
        // H = R (S H0 S) R^T. Values are evaluated in the mesh frame (no cancellation).
        let field = RotatedStretchedQ {
            rot,
            stretch: aspect,
            q: QUAD,
        };
        let u = sample(&mesh, &field);
        let rec = recover_ls(&mesh, &u).unwrap();
        let ppr = gradient_ppr(&mesh, &u).unwrap();
        let h_scale = sym_norm(field.hessian(DVec2::ZERO));
        let g_scale = mesh
            .points
            .iter()
            .map(|&p| field.gradient(p).length())
            .fold(0.0, f64::max);
        let eh = worst(&hessian_errors(&mesh, &field, &rec.hessian)).1 / h_scale;
        let eg = worst(&gradient_errors(&mesh, &field, &rec.gradient)).1 / g_scale;
        let ep = worst(&gradient_errors(&mesh, &field, &ppr)).1 / g_scale;
        println!("aspect {aspect}, rotated {angle_deg} deg: relative errors LS H {eh:.1e}, LS g {eg:.1e}, PPR g {ep:.1e}");
        assert!(eh <= tol && eg <= tol && ep <= tol, "{eh:e} {eg:e} {ep:e}");
    }
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let mesh = perturbed_square(16, GridPattern::UnionJack, 0.3, 9);
    let u = sample(&mesh, &Smooth);
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                (
                    recover_ls(&mesh, &u).unwrap(),
                    gradient_ppr(&mesh, &u).unwrap(),
                    hessian_double_l2(&mesh, &u).unwrap(),
                )
            })
    };
    assert_eq!(run(1), run(2));
}

#[test]
fn bad_fields_are_errors_naming_the_vertex() {
    let mesh = perturbed_square(4, GridPattern::UnionJack, 0.3, 1);
    let n = mesh.n_points();
    let mut u = sample(&mesh, &QUAD);
    u[7] = f64::NAN;
    u[9] = f64::INFINITY;
    for r in [
        recover_ls(&mesh, &u).map(|_| ()),
        gradient_ppr(&mesh, &u).map(|_| ()),
        hessian_double_l2(&mesh, &u).map(|_| ()),
    ] {
        match r {
            Err(Error::InvalidField { msg, .. }) => assert!(msg.contains("vertex 7"), "{msg}"),
            other => panic!("expected InvalidField, got {other:?}"),
        }
    }
    let short = vec![0.0; n - 3];
    match recover_ls(&mesh, &short) {
        Err(Error::InvalidField { msg, .. }) => {
            assert!(msg.contains(&format!("vertex {}", n - 3)), "{msg}")
        }
        other => panic!("expected InvalidField, got {other:?}"),
    }
    assert!(matches!(
        gradient_ppr(&mesh, &vec![0.0; n + 1]),
        Err(Error::InvalidField { .. })
    ));
}

#[test]
fn components_with_fewer_than_six_vertices_are_errors() {
    // Two triangles (4 vertices).
    let quad = Mesh2::from_triangles(
        vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y],
        vec![[0, 1, 2], [0, 2, 3]],
    )
    .unwrap();
    let u = vec![1.0; 4];
    assert!(matches!(recover_ls(&quad, &u), Err(Error::InvalidInput(_))));
    assert!(matches!(
        gradient_ppr(&quad, &u),
        Err(Error::InvalidInput(_))
    ));
    assert!(matches!(
        hessian_double_l2(&quad, &u),
        Err(Error::InvalidInput(_))
    ));

    // A valid 6-vertex fan plus a detached triangle (vertices 6, 7, 8): the error names vertex 6.
    let p = pentagon();
    let mut pts = p.points.clone();
    pts.extend([
        DVec2::new(5.0, 0.0),
        DVec2::new(6.0, 0.0),
        DVec2::new(5.0, 1.0),
    ]);
    let mut tris = p.tris.clone();
    tris.push([6, 7, 8]);
    let two = Mesh2::from_triangles(pts, tris).unwrap();
    match recover_ls(&two, &[0.0; 9]) {
        Err(Error::InvalidInput(msg)) => assert!(msg.contains("vertex 6"), "{msg}"),
        other => panic!("expected InvalidInput, got {other:?}"),
    }
    // The 6-vertex fan alone is fine.
    assert!(recover_ls(&p, &sample(&p, &QUAD)).is_ok());
}

/// An unreferenced vertex (no triangle) gets zero derivatives and does not disturb the others.
#[test]
fn unreferenced_vertices_get_zeros() {
    let base = perturbed_square(6, GridPattern::UnionJack, 0.3, 4);
    let mut pts = base.points.clone();
    pts.push(DVec2::new(7.0, 7.0));
    let mesh = Mesh2::from_triangles(pts, base.tris.clone()).unwrap();
    let u = sample(&mesh, &QUAD);
    let r = recover_ls(&mesh, &u).unwrap();
    let ppr = gradient_ppr(&mesh, &u).unwrap();
    let l2 = hessian_double_l2(&mesh, &u).unwrap();
    let last = mesh.n_points() - 1;
    assert_eq!(r.gradient[last], DVec2::ZERO);
    assert_eq!(r.hessian[last], Sym2::default());
    assert_eq!(ppr[last], DVec2::ZERO);
    assert_eq!(l2[last], Sym2::default());
    let eh = hessian_errors(&mesh, &QUAD, &r.hessian);
    assert!(eh[..last].iter().all(|&e| e <= TOL));
}

/// Six vertices on a circle (a triangulated regular hexagon) lie on a conic, so no patch
/// determines a quadratic: the fits fall back to fewer unknowns (003 §6.2) and must still be
/// finite and exact for linear fields.
#[test]
fn conic_patches_fall_back_to_lower_degree() {
    let pts: Vec<DVec2> = (0..6)
        .map(|k| DVec2::from_angle(std::f64::consts::TAU * k as f64 / 6.0))
        .collect();
    let tris = vec![[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5]];
    let mesh = Mesh2::from_triangles(pts, tris).unwrap();
    mesh.check().unwrap();
    let u = sample(&mesh, &LINEAR);
    let r = recover_ls(&mesh, &u).unwrap();
    let ppr = gradient_ppr(&mesh, &u).unwrap();
    let eg = worst(&gradient_errors(&mesh, &LINEAR, &r.gradient)).1;
    let eh = worst(&hessian_errors(&mesh, &LINEAR, &r.hessian)).1;
    let ep = worst(&gradient_errors(&mesh, &LINEAR, &ppr)).1;
    println!("hexagon: LS g {eg:.1e}, LS H {eh:.1e}, PPR g {ep:.1e}");
    assert!(eg <= TOL && eh <= TOL && ep <= TOL, "{eg:e} {eh:e} {ep:e}");
    let q = sample(&mesh, &QUAD);
    let r = recover_ls(&mesh, &q).unwrap();
    assert!(r.gradient.iter().all(|g| g.is_finite()));
    assert!(r
        .hessian
        .iter()
        .all(|h| h.xx.is_finite() && h.xy.is_finite() && h.yy.is_finite()));
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(48))]

    /// Property: for a random quadratic on a random perturbed 6x6 UnionJack mesh mapped by a random
    /// rotation and anisotropic scaling (aspect up to 1e3), the LS Hessian and the PPR gradient are
    /// exact to 1e-9 relative to the exact derivative's size, at every vertex.
    #[test]
    fn random_quadratics_on_random_affine_meshes_are_exact(
        seed in 0u64..10_000,
        angle in 0.0..std::f64::consts::PI,
        log_aspect in 0.0..3.0f64,
        c in proptest::array::uniform6(-3.0..3.0f64),
    ) {
        let mut mesh = perturbed_square(6, GridPattern::UnionJack, 0.3, seed);
        let (rot, k) = (DVec2::from_angle(angle), 10f64.powf(log_aspect));
        for p in &mut mesh.points {
            *p = rot.rotate(DVec2::new(p.x, p.y / k));
        }
        mesh.check().unwrap();
        // The quadratic in the mesh's own frame (so its anisotropy matches the mesh's).
        let local = Quadratic { c0: c[0], g: DVec2::new(c[1], c[2]), h: Sym2::new(c[3], c[4], c[5]) };
        let field = RotatedStretchedQ { rot, stretch: k, q: local };
        let u = sample(&mesh, &field);
        let r = recover_ls(&mesh, &u).unwrap();
        let ppr = gradient_ppr(&mesh, &u).unwrap();
        let h_scale = sym_norm(field.hessian(DVec2::ZERO)).max(1e-300);
        let g_scale = mesh.points.iter().map(|&p| field.gradient(p).length()).fold(1e-300, f64::max);
        let eh = worst(&hessian_errors(&mesh, &field, &r.hessian)).1 / h_scale;
        let ep = worst(&gradient_errors(&mesh, &field, &ppr)).1 / g_scale;
        proptest::prop_assert!(eh <= 1e-9 && ep <= 1e-9, "LS H {:e}, PPR g {:e}", eh, ep);
    }
}

/// `q(S R^T p)` for a general quadratic `q`, `S = diag(1, stretch)`.
struct RotatedStretchedQ {
    rot: DVec2,
    stretch: f64,
    q: Quadratic,
}

impl RotatedStretchedQ {
    fn local(&self, p: DVec2) -> DVec2 {
        let l = DVec2::new(self.rot.x, -self.rot.y).rotate(p);
        DVec2::new(l.x, self.stretch * l.y)
    }
}

impl Exact for RotatedStretchedQ {
    fn value(&self, p: DVec2) -> f64 {
        self.q.value(self.local(p))
    }
    fn gradient(&self, p: DVec2) -> DVec2 {
        let g = self.q.gradient(self.local(p));
        self.rot.rotate(DVec2::new(g.x, self.stretch * g.y))
    }
    fn hessian(&self, _: DVec2) -> Sym2 {
        let (c, s, k) = (self.rot.x, self.rot.y, self.stretch);
        let h0 = self.q.h;
        let (a, b, d) = (h0.xx, k * h0.xy, k * k * h0.yy);
        Sym2::new(
            c * c * a - 2.0 * c * s * b + s * s * d,
            c * s * (a - d) + (c * c - s * s) * b,
            s * s * a + 2.0 * c * s * b + c * c * d,
        )
    }
}
