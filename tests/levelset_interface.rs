//! Zero level of P1 fields: extraction, enclosed area, length and distance to the exact shape.

use anisomesh::levelset::{
    enclosed_area, extract_zero_level, interface_distance, interface_length, nodal_distance,
    Circle, Shape, Zalesak,
};
use anisomesh::{DVec2, Error, GridPattern, Mesh2};
use std::f64::consts::PI;

fn grid(lo: f64, hi: f64, n: usize, pattern: GridPattern) -> Mesh2 {
    Mesh2::rectangle(DVec2::splat(lo), DVec2::splat(hi), n, n, pattern).unwrap()
}

/// Least-squares slope of `log e` against `log h`.
fn order(h: &[f64], e: &[f64]) -> f64 {
    let n = h.len() as f64;
    let (x, y): (Vec<f64>, Vec<f64>) = h.iter().zip(e).map(|(h, e)| (h.ln(), e.ln())).unzip();
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(&y).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = x.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

#[test]
fn circle_measures_converge_at_second_order() {
    let circle = Circle {
        centre: DVec2::new(0.0123, -0.0071),
        radius: 0.5,
    };
    let (mut hs, mut ea, mut el, mut eh) = (vec![], vec![], vec![], vec![]);
    // From h/R = 1/8: at h/R = 1/4 the Hausdorff distance is still pre-asymptotic.
    for n in [32, 64, 128, 256] {
        let mesh = grid(-1.0, 1.0, n, GridPattern::UnionJack);
        let u = nodal_distance(&mesh, &circle);
        let lines = extract_zero_level(&mesh, &u).unwrap();
        assert_eq!(lines.len(), 1);
        assert!(lines[0].closed);
        // Closed curves run counter-clockwise around the inside.
        let p = &lines[0].points;
        let signed: f64 = (0..p.len())
            .map(|i| 0.5 * p[i].perp_dot(p[(i + 1) % p.len()]))
            .sum();
        let area = enclosed_area(&mesh, &u).unwrap();
        assert!(
            (signed - area).abs() < 1e-12,
            "shoelace {signed} vs clipped {area}"
        );
        let length = interface_length(&mesh, &u).unwrap();
        assert!((length - lines[0].length()).abs() < 1e-12);
        let err = interface_distance(&lines, &circle, 4);
        hs.push(2.0 / n as f64);
        ea.push((area - PI * 0.25).abs());
        el.push((length - PI).abs());
        eh.push(err.hausdorff);
    }
    let (oa, ol, oh) = (order(&hs, &ea), order(&hs, &el), order(&hs, &eh));
    eprintln!("area errors {ea:?} order {oa:.3}");
    eprintln!("length errors {el:?} order {ol:.3}");
    eprintln!("hausdorff {eh:?} order {oh:.3}");
    assert!((oa - 2.0).abs() < 0.2, "area order {oa}");
    assert!((ol - 2.0).abs() < 0.2, "length order {ol}");
    assert!((oh - 2.0).abs() < 0.2, "Hausdorff order {oh}");
}

#[test]
fn linear_field_zero_level_is_exact() {
    let mesh = grid(0.0, 1.0, 10, GridPattern::UnionJack);
    let f = |p: DVec2| p.x + 0.5 * p.y - 0.6;
    let u: Vec<f64> = mesh.points.iter().map(|&p| f(p)).collect();
    let lines = extract_zero_level(&mesh, &u).unwrap();
    assert_eq!(lines.len(), 1);
    let line = &lines[0];
    assert!(!line.closed);
    for p in &line.points {
        assert!(f(*p).abs() < 1e-14, "{p} is off the line");
    }
    let exact_length = 0.5f64.hypot(1.0);
    assert!((line.length() - exact_length).abs() < 1e-12);
    assert!((interface_length(&mesh, &u).unwrap() - exact_length).abs() < 1e-12);
    // {x + y/2 < 0.6} ∩ [0,1]²: a trapezoid of area 0.6 - 0.25.
    assert!((enclosed_area(&mesh, &u).unwrap() - 0.35).abs() < 1e-12);
    // Ends on the boundary: (0.6, 0) and (0.1, 1); the negative side is on the left.
    let (a, b) = (line.points[0], *line.points.last().unwrap());
    assert!((a - DVec2::new(0.6, 0.0)).length() < 1e-12, "{a}");
    assert!((b - DVec2::new(0.1, 1.0)).length() < 1e-12, "{b}");
}

#[test]
fn zero_vertices_give_one_clean_chain() {
    // u = x - 0.5 vanishes exactly on a column of vertices.
    let mesh = grid(0.0, 1.0, 10, GridPattern::CrissCross);
    let u: Vec<f64> = mesh.points.iter().map(|p| p.x - 0.5).collect();
    assert!(u.iter().filter(|&&v| v == 0.0).count() >= 11);
    let lines = extract_zero_level(&mesh, &u).unwrap();
    assert_eq!(lines.len(), 1);
    let pts = &lines[0].points;
    assert!(pts.windows(2).all(|w| w[0] != w[1]));
    assert!(pts.iter().all(|p| p.x == 0.5));
    assert_eq!(pts[0].y, 0.0);
    assert_eq!(pts.last().unwrap().y, 1.0);
    assert!((lines[0].length() - 1.0).abs() < 1e-14);
    assert!((enclosed_area(&mesh, &u).unwrap() - 0.5).abs() < 1e-14);
}

#[test]
fn interface_meeting_the_boundary() {
    // A quarter disk around the corner (1, 1) of the unit square.
    let circle = Circle {
        centre: DVec2::new(1.0, 1.0),
        radius: 0.5,
    };
    let (mut hs, mut ea) = (vec![], vec![]);
    for n in [16, 32, 64] {
        let mesh = grid(0.0, 1.0, n, GridPattern::Right);
        let u = nodal_distance(&mesh, &circle);
        let lines = extract_zero_level(&mesh, &u).unwrap();
        assert_eq!(lines.len(), 1);
        assert!(!lines[0].closed);
        hs.push(1.0 / n as f64);
        ea.push((enclosed_area(&mesh, &u).unwrap() - PI / 16.0).abs());
    }
    let o = order(&hs, &ea);
    assert!((o - 2.0).abs() < 0.25, "order {o}, errors {ea:?}");
}

#[test]
fn zalesak_on_a_fine_grid() {
    let z = Zalesak::default();
    let n = 400; // h = 0.01 on [-2, 2]²
    let h = 4.0 / n as f64;
    let mesh = grid(-2.0, 2.0, n, GridPattern::UnionJack);
    let u = nodal_distance(&mesh, &z);
    let lines = extract_zero_level(&mesh, &u).unwrap();
    assert_eq!(lines.len(), 1);
    assert!(lines[0].closed);
    let area = enclosed_area(&mesh, &u).unwrap();
    let length = interface_length(&mesh, &u).unwrap();
    let err = interface_distance(&lines, &z, 4);
    let (ea, el) = (
        (area - z.exact_area().unwrap()).abs(),
        (length - z.exact_perimeter().unwrap()).abs(),
    );
    eprintln!("zalesak h = {h}: area err {ea:e}, length err {el:e}, {err:?}");
    // Expected bounds: the smooth parts contribute O(h²); each of the 4 corners is cut within
    // one cell (area O(h²), length O(h) per corner). The distance is 1-Lipschitz, so near a
    // corner the discrete zero level stays within a cell of the exact one: Hausdorff < h.
    // (Measured at h = 0.01: area 1.3e-5 = 0.13 h², length 2.2e-2 = 2.2 h, Hausdorff 0.68 h,
    // set by the exact corners; to_exact 0.33 h.)
    assert!(ea < 4.0 * h * h, "area error {ea}");
    assert!(el < 4.0 * h, "length error {el}");
    assert!(err.hausdorff < h, "Hausdorff {}", err.hausdorff);
    assert!(err.to_exact_max < 0.5 * h, "to exact {}", err.to_exact_max);
    assert!(err.to_exact_max <= err.hausdorff && err.from_exact_max <= err.hausdorff);
}

#[test]
fn empty_and_invalid_fields() {
    let mesh = grid(0.0, 1.0, 4, GridPattern::Right);
    let pos = vec![1.0; mesh.n_points()];
    assert!(matches!(
        extract_zero_level(&mesh, &pos),
        Err(Error::EmptyLevelSet(_))
    ));
    assert_eq!(enclosed_area(&mesh, &pos).unwrap(), 0.0);
    assert_eq!(interface_length(&mesh, &pos).unwrap(), 0.0);
    let neg = vec![-1.0; mesh.n_points()];
    assert!((enclosed_area(&mesh, &neg).unwrap() - 1.0).abs() < 1e-14);

    let mut bad: Vec<f64> = mesh.points.iter().map(|p| p.x - 0.3).collect();
    bad[7] = f64::NAN;
    for r in [
        extract_zero_level(&mesh, &bad).map(|_| 0.0),
        enclosed_area(&mesh, &bad),
        interface_length(&mesh, &bad),
    ] {
        let e = r.unwrap_err();
        assert!(matches!(e, Error::InvalidField { .. }));
        assert!(e.to_string().contains("vertex 7"), "{e}");
    }
    assert!(matches!(
        extract_zero_level(&mesh, &pos[1..]),
        Err(Error::InvalidField { .. })
    ));
    // No polylines: infinite distance rather than a silent zero.
    let c = Circle {
        centre: DVec2::ZERO,
        radius: 0.5,
    };
    assert!(interface_distance(&[], &c, 4).hausdorff.is_infinite());
    assert!(c.exact_area().is_some());
}

mod robustness {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]
        /// Random fields with many exact zeros: extraction either reports an empty level set or
        /// returns chains whose total length is the interface length, with no repeated points,
        /// open chains ending on the boundary of the square, and the area within [0, 1].
        #[test]
        fn chains_are_consistent(
            vals in proptest::collection::vec(prop_oneof![Just(-1.0), Just(0.0), Just(1.0), -1.0f64..1.0], 49),
            pattern in prop_oneof![Just(GridPattern::Right), Just(GridPattern::UnionJack)],
        ) {
            let mesh = grid(0.0, 1.0, 6, pattern);
            let u = vals;
            let area = enclosed_area(&mesh, &u).unwrap();
            prop_assert!((-1e-15..=1.0 + 1e-15).contains(&area));
            let length = interface_length(&mesh, &u).unwrap();
            match extract_zero_level(&mesh, &u) {
                Err(Error::EmptyLevelSet(_)) => prop_assert_eq!(length, 0.0),
                Err(e) => prop_assert!(false, "unexpected error {}", e),
                Ok(lines) => {
                    let total: f64 = lines.iter().map(|l| l.length()).sum();
                    prop_assert!((total - length).abs() < 1e-12, "{} vs {}", total, length);
                    let on_boundary = |p: DVec2| p.x == 0.0 || p.x == 1.0 || p.y == 0.0 || p.y == 1.0;
                    for l in &lines {
                        prop_assert!(l.points.windows(2).all(|w| w[0] != w[1]));
                        if !l.closed {
                            prop_assert!(on_boundary(l.points[0]) && on_boundary(*l.points.last().unwrap()));
                        }
                    }
                }
            }
        }
    }
}
