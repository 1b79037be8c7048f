//! Reaction–diffusion on a band around a fixed surface and mean curvature motion of a
//! triangulated surface (000 §2.1, §4): an exact solution reproduced, the conserved total kept,
//! Turing patterns forming on the star, a triangulated sphere shrinking like √(R0² − 4t), and
//! the bad inputs (a hole, an inconsistent orientation, a missing file).

use anisomesh::backends::dtgrid::lattice::{Lattice, C3};
use anisomesh::backends::dtgrid::mcf::{McfOptions, McfState};
use anisomesh::backends::dtgrid::obj::{band_of_shape, read_shape, Placement};
use anisomesh::backends::dtgrid::reaction::{unit_hash, SurfaceOperator, Turing, TuringState};
use anisomesh::backends::dtgrid::scheme::Bc;
use anisomesh::backends::dtgrid::surface::{surface_integral, zero_level};
use anisomesh::backends::dtgrid::{Band, DtGrid};
use anisomesh::geom::DVec3;
use anisomesh::levelset::shapes::StarSurface;
use anisomesh::levelset::{icosphere, radial_surface, TriangulatedShape};
use anisomesh::Error;

type B = DtGrid<C3>;

/// The second spherical harmonic `(z/|x|)² − 1/3`, constant along the normals of spheres.
fn y2(p: DVec3) -> f64 {
    let l = p.length().max(1e-300);
    (p.z / l).powi(2) - 1.0 / 3.0
}

fn sphere_band(n: usize, j: usize, r: f64) -> McfState<B> {
    McfState::new(Lattice::unit(n).unwrap(), j, &|p: DVec3| p.length() - r).unwrap()
}

#[test]
fn linear_reaction_reproduces_the_exponential_of_a_spherical_harmonic() {
    // ∂ₜu = Δ_M u + λu on the sphere R = 1/3 with u(0) = Y₂: u = e^{(λ − 6/R²)t} Y₂.
    let (r, lambda, t_end) = (1.0 / 3.0, 20.0, 0.01);
    for bc in [Bc::Natural, Bc::Transparent] {
        let s = sphere_band(33, 2, r);
        let lat = s.lat;
        let op = SurfaceOperator::new(lat, &s.nb, &s.phi, bc).unwrap();
        let mut u: Vec<f64> = s.nb.band.coords().map(|c| y2(lat.pos(c))).collect();
        let steps = 20;
        let tau = t_end / steps as f64;
        let a = op.system(1.0, tau).unwrap();
        for _ in 0..steps {
            let f: Vec<f64> = u.iter().map(|u| lambda * u).collect();
            op.step(&a, 1.0, tau, &mut u, &f).unwrap();
        }
        let z = zero_level(&lat, &s.nb.band, &s.phi);
        let amp = ((lambda - 6.0 / (r * r)) * t_end).exp();
        let err =
            surface_integral(&lat, &s.nb.band, &z, &u, |x, v| (v - amp * y2(x)).powi(2)).sqrt();
        let norm = surface_integral(&lat, &s.nb.band, &z, &u, |x, _| (amp * y2(x)).powi(2)).sqrt();
        // Without the reaction the amplitude would be off by e^{-λt} − 1 ≈ 18 %.
        eprintln!("{}: relative L2 error {:.3e}", bc.name(), err / norm);
        assert!(
            err / norm < 0.015,
            "{}: relative L2 error {}",
            bc.name(),
            err / norm
        );
    }
}

#[test]
fn pure_diffusion_with_natural_conditions_conserves_the_total() {
    let s = sphere_band(25, 2, 0.3);
    let op = SurfaceOperator::new(s.lat, &s.nb, &s.phi, Bc::Natural).unwrap();
    let mut u: Vec<f64> = s.nb.band.coords().map(|c| unit_hash(7, c)).collect();
    let before = op.total(&u);
    let v0 = op.variance(&u);
    let tau = 1e-3;
    let a = op.system(1.0, tau).unwrap();
    let zero = vec![0.0; u.len()];
    for _ in 0..10 {
        op.step(&a, 1.0, tau, &mut u, &zero).unwrap();
    }
    eprintln!(
        "total drift {:.3e}, variance {:.3e} -> {:.3e}",
        (op.total(&u) - before) / before,
        v0,
        op.variance(&u)
    );
    assert!(
        ((op.total(&u) - before) / before).abs() < 1e-8,
        "{} {before}",
        op.total(&u)
    );
    // Diffusion smooths the random field.
    assert!(op.variance(&u) < 0.1 * v0, "{} {v0}", op.variance(&u));
    assert!(SurfaceOperator::new(s.lat, &s.nb, &s.phi, Bc::Dirichlet).is_err());
}

fn star_shape(level: u32) -> TriangulatedShape {
    let s = radial_surface(DVec3::ZERO, |d| StarSurface::PAPER.radius_towards(d), level);
    TriangulatedShape::new(s.points, s.triangles).unwrap()
}

fn placed(shape: &TriangulatedShape, lat: &Lattice, j: usize) -> (TriangulatedShape, Placement) {
    let p = Placement::fit(shape.surface(), lat, j).unwrap();
    let s = p.surface(shape.surface());
    (TriangulatedShape::new(s.points, s.triangles).unwrap(), p)
}

#[test]
fn turing_patterns_form_on_the_star() {
    let lat = Lattice::unit(41).unwrap();
    let (shape, _) = placed(&star_shape(4), &lat, 1);
    let s: McfState<B> = band_of_shape(lat, 1, &shape).unwrap();
    let p = Turing::paper_at(lat.h);
    let mut st = TuringState::new(lat, &s.nb, &s.phi, p, 1.0, Bc::Natural).unwrap();
    for _ in 0..10 {
        st.step().unwrap();
    }
    let v1 = st.op.variance(&st.a);
    for _ in 0..190 {
        st.step().unwrap();
    }
    let v = st.op.variance(&st.a);
    eprintln!("variance of a: {v1:.3e} after 10 steps, {v:.3e} after 200");
    // From the small perturbation of the random β the variance grows by orders of magnitude
    // and saturates; the mean stays near the homogeneous state a = 4.
    assert!(v > 100.0 * v1 && v > 0.1, "variance {v1} -> {v}");
    let mean = st.op.mean(&st.a);
    assert!((mean - 4.0).abs() < 0.5, "mean {mean}");
    assert!(st.a.iter().chain(&st.b).all(|x| x.is_finite()));
    // The same seed gives the same pattern; invalid parameters are refused.
    assert!(Turing { alpha: 12.0, ..p }.check().is_err());
}

#[test]
fn triangulated_sphere_shrinks_by_mean_curvature() {
    let lat = Lattice::unit(33).unwrap();
    let (shape, place) = placed(
        &{
            let s = icosphere(4);
            TriangulatedShape::new(s.points, s.triangles).unwrap()
        },
        &lat,
        1,
    );
    let r0 = place.scale; // the unit icosphere scaled
    let mut s: McfState<B> = band_of_shape(lat, 1, &shape).unwrap();
    let start = s.surface_mean(|x| x.length()).unwrap();
    assert!((start - r0).abs() < 2e-3, "{start} {r0}");
    let (t_end, steps) = (0.01, 10);
    let o = McfOptions::default();
    for _ in 0..steps {
        s.step(t_end / steps as f64, &o).unwrap();
    }
    let r = s.surface_mean(|x| x.length()).unwrap();
    let exact = (r0 * r0 - 4.0 * t_end).sqrt();
    assert!(r0 - exact > 0.05);
    // h = 1/32, τ ≈ h²: the scheme's own error is a few per mille of the radius per 0.01.
    assert!((r - exact).abs() < 0.025 * exact, "R = {r}, exact {exact}");
    // The same sphere given analytically moves the same way: the OBJ route adds only the
    // chord error of the triangulation.
    let mut a = sphere_band(33, 1, r0);
    for _ in 0..steps {
        a.step(t_end / steps as f64, &o).unwrap();
    }
    let ra = a.surface_mean(|x| x.length()).unwrap();
    eprintln!("R0 {r0:.5}: OBJ {r:.5}, analytic {ra:.5}, exact {exact:.5}");
    assert!((r - ra).abs() < 1e-3, "OBJ {r}, analytic {ra}");
}

fn write(name: &str, text: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("dtgrid_surfaces_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

const OCTA_V: &str = "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n";

#[test]
fn bad_obj_input_gives_one_line_errors_or_a_repair() {
    // The octahedron with one face missing: a hole.
    let faces = [
        [1, 3, 5],
        [3, 2, 5],
        [2, 4, 5],
        [4, 1, 5],
        [3, 1, 6],
        [2, 3, 6],
        [4, 2, 6],
        [1, 4, 6],
    ];
    let obj = |fs: &[[i32; 3]]| {
        let mut s = OCTA_V.to_string();
        for f in fs {
            s += &format!("f {} {} {}\n", f[0], f[1], f[2]);
        }
        s
    };
    let hole = write("hole.obj", &obj(&faces[..7]));
    match read_shape(&hole) {
        Err(e @ Error::InvalidInput(_)) => {
            let m = e.to_string();
            assert!(
                m.contains("hole") && m.contains("hole.obj") && !m.contains('\n'),
                "{m}"
            );
        }
        other => panic!("expected a typed error, got {other:?}"),
    }
    // One face reversed: repaired, reported, and the volume is that of the octahedron.
    let mut flipped = faces;
    flipped[2] = [flipped[2][1], flipped[2][0], flipped[2][2]];
    let s = read_shape(&write("flipped.obj", &obj(&flipped))).unwrap();
    assert_eq!(s.flipped_triangles(), 1);
    assert!((s.volume() - 4.0 / 3.0).abs() < 1e-12, "{}", s.volume());
    // A missing file: a one-line I/O error naming it.
    let e = read_shape(std::path::Path::new("/nonexistent/star.obj")).unwrap_err();
    assert!(matches!(e, Error::Io { .. }));
    let m = e.to_string();
    assert!(
        m.contains("/nonexistent/star.obj") && !m.contains('\n'),
        "{m}"
    );
    // A grid too coarse for the band: a typed error, no panic.
    let lat = Lattice::unit(5).unwrap();
    assert!(Placement::fit(s.surface(), &lat, 2).is_err());
}

#[test]
fn shipped_star_is_valid_and_closed() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("meshes/star.obj");
    let s = read_shape(&path).unwrap();
    assert_eq!(s.flipped_triangles(), 0);
    assert_eq!(s.components(), 1);
    // The star r = 0.45 + 0.3 cos 6θ cos² 3φ reaches 0.75 along its lobes.
    let far = s
        .surface()
        .points
        .iter()
        .map(|p| p.length())
        .fold(0.0, f64::max);
    assert!((far - 0.75).abs() < 0.01, "{far}");
}
