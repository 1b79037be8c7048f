//! Property test: adaptation to random metric fields (sizes 1e-3..1, anisotropy up to 1000,
//! random orientations, smooth or rough) on random domains — structured squares, squares with
//! square holes, domains with a circular hole and a labelled interface circle — always yields a
//! valid mesh (`check()` after every pass), preserves the area, the holes, the corners and the
//! sub-domain areas (straight boundaries and interfaces: only split/collapse along them).

use anisomesh::adapt::{adapt, AdaptOptions};
use anisomesh::mesh::{circle_points, PolygonDomain};
use anisomesh::{DVec2, GridPattern, Mesh2, Sym2};
use proptest::prelude::*;

fn square_pts(c: DVec2, h: f64) -> Vec<DVec2> {
    vec![
        c + DVec2::new(-h, -h),
        c + DVec2::new(h, -h),
        c + DVec2::new(h, h),
        c + DVec2::new(-h, h),
    ]
}

fn domain(kind: u8, n: usize, hole: (f64, f64, f64)) -> Mesh2 {
    let h = 1.0 / n as f64;
    match kind % 3 {
        0 => {
            let pat = [
                GridPattern::Right,
                GridPattern::UnionJack,
                GridPattern::CrissCross,
            ][n % 3];
            Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, n, n, pat).unwrap()
        }
        1 => {
            let c = DVec2::new(0.3 + 0.4 * hole.0, 0.3 + 0.4 * hole.1);
            let r = 0.05 + 0.15 * hole.2;
            PolygonDomain::new(square_pts(DVec2::splat(0.5), 0.5), 1)
                .with_size(h)
                .hole(square_pts(c, r), 2)
                .with_size(h)
                .mesh()
                .unwrap()
        }
        _ => {
            let c = DVec2::new(0.35 + 0.3 * hole.0, 0.35 + 0.3 * hole.1);
            PolygonDomain::new(square_pts(DVec2::splat(0.5), 0.5), 1)
                .with_size(h)
                .hole(circle_points(c, 0.05 + 0.05 * hole.2, 12), 2)
                .interface(circle_points(c, 0.22, 16), 3, 7)
                .with_size(h)
                .mesh()
                .unwrap()
        }
    }
}

/// A metric with sizes `h_big`, `h_big / aniso` (clamped so that `h1 h2 >= 8e-3`, keeping the
/// meshes small) along the angle `theta`.
fn metric_of(h_big: f64, aniso: f64, theta: f64) -> Sym2 {
    let h_small = (h_big / aniso).max(8e-3 / h_big).clamp(1e-3, h_big);
    let d = DVec2::new(theta.cos(), theta.sin());
    Sym2::from_eigen(
        [1.0 / (h_big * h_big), 1.0 / (h_small * h_small)],
        [d, d.perp()],
    )
}

#[derive(Debug, Clone)]
struct Field {
    /// Two anchor metrics `(log10 h_big, log10 aniso, theta)` blended along a random direction,
    /// plus per-vertex noise when `rough`.
    a: (f64, f64, f64),
    b: (f64, f64, f64),
    dir: f64,
    rough: bool,
    seed: u64,
    /// A boundary layer along a random line: `(offset, angle, log10 normal size, log10 aniso)`;
    /// normal sizes down to 1e-3 and anisotropy up to 1000 in a thin band, intersected with the
    /// background field.
    layer: Option<(f64, f64, f64, f64)>,
}

fn field_strategy() -> impl Strategy<Value = Field> {
    let anchor = (-1.0f64..0.0, 0.0f64..3.0, 0.0f64..std::f64::consts::PI);
    let layer = proptest::option::of((0.2f64..0.8, 0.0f64..3.2, -3.0f64..-2.0, 1.0f64..3.0));
    (
        anchor.clone(),
        anchor,
        0.0f64..6.3,
        any::<bool>(),
        any::<u64>(),
        layer,
    )
        .prop_map(|(a, b, dir, rough, seed, layer)| Field {
            a,
            b,
            dir,
            rough,
            seed,
            layer,
        })
}

fn evaluate(f: &Field, mesh: &Mesh2) -> Vec<Sym2> {
    let d = DVec2::new(f.dir.cos(), f.dir.sin());
    let mut s = f.seed | 1;
    let mut rnd = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    mesh.points
        .iter()
        .map(|&p| {
            let t = (p.dot(d) * 0.7 + 0.5).clamp(0.0, 1.0);
            let g = |x: f64, y: f64| x + t * (y - x);
            let (mut hb, mut an, mut th) = (g(f.a.0, f.b.0), g(f.a.1, f.b.1), g(f.a.2, f.b.2));
            if f.rough {
                hb += 0.5 * (rnd() - 0.5);
                an += 1.0 * (rnd() - 0.5);
                th += 1.5 * (rnd() - 0.5);
            }
            let m = metric_of(10f64.powf(hb.min(0.0)), 10f64.powf(an.clamp(0.0, 3.0)), th);
            match f.layer {
                Some((off, ang, hn, an)) => {
                    let nrm = DVec2::new(ang.cos(), ang.sin());
                    let dist = (p - DVec2::splat(0.5)).dot(nrm) - (off - 0.5);
                    let h_n = 10f64.powf(hn);
                    if dist.abs() < 8.0 * h_n {
                        let h_t = (h_n * 10f64.powf(an)).min(1.0);
                        let l = Sym2::from_eigen(
                            [1.0 / (h_t * h_t), 1.0 / (h_n * h_n)],
                            [nrm.perp(), nrm],
                        );
                        anisomesh::metric::intersect(&m, &l)
                    } else {
                        m
                    }
                }
                None => m,
            }
        })
        .collect()
}

fn sub_area(m: &Mesh2, r: i32) -> f64 {
    m.live_tris()
        .filter(|&t| m.tri_ref[t] == r)
        .map(|t| m.tri_area(t))
        .sum()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, max_shrink_iters: 50, .. ProptestConfig::default() })]

    #[test]
    fn adaptation_always_gives_a_valid_mesh(
        kind in 0u8..3,
        n in 3usize..9,
        hole in (0.0f64..1.0, 0.0f64..1.0, 0.0f64..1.0),
        field in field_strategy(),
    ) {
        let mut mesh = domain(kind, n, hole);
        let area0 = mesh.area();
        let refs: Vec<i32> = {
            let mut r = mesh.tri_ref.clone();
            r.sort();
            r.dedup();
            r
        };
        let sub0: Vec<f64> = refs.iter().map(|&r| sub_area(&mesh, r)).collect();
        let loops0 = mesh.boundary_loops().len();
        let corners0: Vec<DVec2> = (0..mesh.n_points()).filter(|&v| mesh.corner[v]).map(|v| mesh.points[v]).collect();
        let mut metric = evaluate(&field, &mesh);
        let mut fields = vec![mesh.points.iter().map(|p| p.x - 2.0 * p.y).collect::<Vec<f64>>()];
        let opts = AdaptOptions::default().check_each_pass(true).max_cycles(5);
        let rep = adapt(&mut mesh, &mut metric, &mut fields, None, &opts);
        prop_assert!(rep.is_ok(), "{:?}", rep.err());
        mesh.check().unwrap();
        prop_assert_eq!(metric.len(), mesh.n_points());
        prop_assert!((mesh.area() - area0).abs() <= 1e-11 * area0);
        for (k, &r) in refs.iter().enumerate() {
            let a = sub_area(&mesh, r);
            // Interfaces are polygons (straight pieces): their areas are kept too.
            prop_assert!((a - sub0[k]).abs() <= 1e-10, "sub-domain {} area {} vs {}", r, a, sub0[k]);
        }
        prop_assert_eq!(mesh.boundary_loops().len(), loops0);
        for c in corners0 {
            prop_assert!(mesh.points.contains(&c), "corner {} lost", c);
        }
        // The linear field is carried exactly (interpolation of a linear function).
        for (v, p) in mesh.points.iter().enumerate() {
            prop_assert!((fields[0][v] - (p.x - 2.0 * p.y)).abs() < 1e-9);
        }
    }
}
