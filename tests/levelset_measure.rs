//! Enclosed and interface measures of P1 level sets, one code path for triangles and
//! tetrahedra: exact for planes, identical to the planar functions, second order for a sphere.

use anisomesh::levelset::shapes::{Shape, Sphere};
use anisomesh::levelset::{enclosed_area, enclosed_measure, interface_length, interface_measure};
use anisomesh::mesh3::Mesh3;
use anisomesh::{DVec2, DVec3, GridPattern, Mesh2};
use std::f64::consts::PI;

fn kuhn(n: usize) -> Mesh3 {
    Mesh3::kuhn_box(DVec3::splat(-1.0), DVec3::splat(1.0), [n, n, n]).unwrap()
}

/// A plane is reproduced exactly by P1: the volume under `z = a + b x + c y` over the unit cube
/// is `a + b/2 + c/2` and its area `sqrt(1 + b² + c²)`, whatever the signs at the vertices (the
/// cuts take every form: corner, two-and-two, vertices on the plane).
#[test]
fn plane_measures_are_exact_in_3d() {
    let m = Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [7, 6, 5]).unwrap();
    for (a, b, c) in [(0.3, 0.2, 0.1), (0.5, -0.25, 0.125), (0.6, 0.0, 0.0)] {
        let u: Vec<f64> = m
            .points
            .iter()
            .map(|p| p.z - (a + b * p.x + c * p.y))
            .collect();
        let vol = enclosed_measure(&m.points, &m.tets, &u).unwrap();
        let area = interface_measure(&m.points, &m.tets, &u).unwrap();
        let want_area = (1.0f64 + b * b + c * c).sqrt();
        assert!((vol - (a + b / 2.0 + c / 2.0)).abs() < 1e-14, "{vol}");
        assert!((area - want_area).abs() < 1e-13, "{area} vs {want_area}");
    }
}

/// On triangles the generic measures give exactly the bits of `enclosed_area` and
/// `interface_length`.
#[test]
fn generic_measures_equal_the_planar_ones() {
    for pattern in [GridPattern::UnionJack, GridPattern::Right] {
        let m = Mesh2::rectangle(DVec2::splat(-1.0), DVec2::splat(1.0), 23, 19, pattern).unwrap();
        // A wavy level set with exact zeros at some vertices.
        let u: Vec<f64> = m
            .points
            .iter()
            .map(|p| {
                let v = p.length() - 0.6 + 0.1 * (5.0 * p.x).sin() * p.y;
                if (p.x - 0.0).abs() < 1e-12 {
                    0.0
                } else {
                    v
                }
            })
            .collect();
        let a = enclosed_area(&m, &u).unwrap();
        let l = interface_length(&m, &u).unwrap();
        assert_eq!(
            a.to_bits(),
            enclosed_measure(&m.points, &m.tris, &u).unwrap().to_bits()
        );
        assert_eq!(
            l.to_bits(),
            interface_measure(&m.points, &m.tris, &u).unwrap().to_bits()
        );
    }
}

/// The enclosed volume and interface area of the P1 interpolant of a sphere's distance on Kuhn
/// meshes converge at second order.
#[test]
fn sphere_volume_and_area_converge_at_second_order() {
    let s = Sphere {
        centre: DVec3::new(0.0123, -0.0071, 0.0057),
        radius: 0.6,
    };
    let (v, a) = (s.exact_area().unwrap(), s.exact_perimeter().unwrap());
    assert!((v - 4.0 / 3.0 * PI * 0.216).abs() < 1e-15 && (a - 4.0 * PI * 0.36).abs() < 1e-15);
    let (mut ev, mut ea) = (vec![], vec![]);
    let ns = [8, 16, 32];
    for n in ns {
        let m = kuhn(n);
        let u: Vec<f64> = m.points.iter().map(|&p| s.distance(p)).collect();
        let vh = enclosed_measure(&m.points, &m.tets, &u).unwrap();
        let ah = interface_measure(&m.points, &m.tets, &u).unwrap();
        // The interpolant of a convex distance lies above it: the volume is underestimated.
        assert!(vh < v && ah < a, "{vh} {ah}");
        ev.push((v - vh) / v);
        ea.push((a - ah) / a);
    }
    for k in 0..ns.len() - 1 {
        let (ov, oa) = ((ev[k] / ev[k + 1]).log2(), (ea[k] / ea[k + 1]).log2());
        println!(
            "n = {:>2}: volume error {:.3e}, order {ov:.2}; area error {:.3e}, order {oa:.2}",
            ns[k + 1],
            ev[k + 1],
            ea[k + 1]
        );
        assert!((ov - 2.0).abs() < 0.3, "volume order {ov} ({ev:?})");
        assert!((oa - 2.0).abs() < 0.3, "area order {oa} ({ea:?})");
    }
    assert!(ev[2] < 6e-3 && ea[2] < 3e-3, "{ev:?} {ea:?}");
}

/// Wrong lengths and NaN values are typed errors; an empty level set measures zero.
#[test]
fn bad_input_and_empty_level_set() {
    let m = kuhn(2);
    assert!(enclosed_measure(&m.points, &m.tets, &[0.0; 3]).is_err());
    let mut u = vec![1.0; m.n_points()];
    assert_eq!(interface_measure(&m.points, &m.tets, &u).unwrap(), 0.0);
    assert_eq!(enclosed_measure(&m.points, &m.tets, &u).unwrap(), 0.0);
    u[3] = f64::NAN;
    assert!(matches!(
        interface_measure(&m.points, &m.tets, &u),
        Err(anisomesh::Error::InvalidField { .. })
    ));
}

/// The volume of an implicit function's negative part on refined tetrahedra: the children
/// cover each tetrahedron, the error of a ball's volume falls by about 4 per level of
/// refinement from that of the P1 interpolant, and the P1 field shifted by `correct_volume`
/// encloses that volume.
#[test]
fn implicit_volume_converges_and_a_shift_restores_it() {
    use anisomesh::advect::correct_volume;
    use anisomesh::levelset::implicit_volume::{implicit_volume, MAX_DEPTH};
    use anisomesh::Error;
    let m = kuhn(6);
    let all = |_: DVec3| -1.0;
    let box_volume = implicit_volume(&m.points, &m.tets, &all, 3).unwrap();
    assert!((box_volume - 8.0).abs() < 1e-12, "{box_volume}");
    let r = 0.7;
    let ball = move |p: DVec3| p.length_squared() - r * r;
    let exact = 4.0 / 3.0 * PI * r * r * r;
    let err: Vec<f64> = (0..4)
        .map(|k| (implicit_volume(&m.points, &m.tets, &ball, k).unwrap() - exact).abs())
        .collect();
    // Measured: 2.4e-1, 5.9e-2, 1.5e-2, 3.8e-3.
    for k in 1..4 {
        let ratio = err[k - 1] / err[k];
        assert!((3.0..5.5).contains(&ratio), "{err:?}");
    }
    assert!(err[3] < 5e-3 * exact, "{err:?}");
    let mut u: Vec<f64> = m.points.iter().map(|&p| ball(p)).collect();
    let target = implicit_volume(&m.points, &m.tets, &ball, 3).unwrap();
    let c = correct_volume(&m.points, &m.tets, &mut u, target, 1e-12).unwrap();
    let after = enclosed_measure(&m.points, &m.tets, &u).unwrap();
    assert!(
        c.shift < 0.0 && (after / target - 1.0).abs() < 1e-11,
        "{c:?}"
    );
    assert!(matches!(
        implicit_volume(&m.points, &m.tets, &ball, MAX_DEPTH + 1),
        Err(Error::InvalidInput(_))
    ));
    let nan = |p: DVec3| if p.x > 0.1 { f64::NAN } else { p.x };
    assert!(matches!(
        implicit_volume(&m.points, &m.tets, &nan, 1),
        Err(Error::InvalidField { .. })
    ));
    assert!(correct_volume(&m.points, &m.tets, &mut u, 9.0, 1e-12).is_err());
}
