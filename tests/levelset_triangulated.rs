//! The exact signed distance to triangulated surfaces (`levelset::triangulated`) and the radial
//! and torus triangulations (`levelset::radial`): distances against closed forms and a
//! brute-force reference, validation errors, orientation repair, volume convergence.

use anisomesh::io::parse_obj;
use anisomesh::levelset::{
    icosphere, radial_surface, torus_surface, Shape, StarSurface, TriangleSurface,
    TriangulatedShape,
};
use anisomesh::{DVec3, Error};
use std::path::Path;

/// A deterministic pseudo-random point in `[-s, s]³`.
fn points(n: usize, s: f64, mut seed: u64) -> Vec<DVec3> {
    let mut rnd = move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    };
    (0..n)
        .map(|_| s * DVec3::new(rnd(), rnd(), rnd()))
        .collect()
}

fn shape(s: &TriangleSurface) -> TriangulatedShape {
    TriangulatedShape::new(s.points.clone(), s.triangles.clone()).expect("valid surface")
}

/// Brute force: the distance to every triangle (sampled exactly through the closest point of
/// each) and the sign from the winding number (sum of the solid angles, Van Oosterom and
/// Strackee's formula), independent of the pseudo-normals.
fn brute_force(s: &TriangleSurface, p: DVec3) -> f64 {
    let mut d = f64::INFINITY;
    let mut winding = 0.0;
    for t in &s.triangles {
        let [a, b, c] = t.map(|v| s.points[v as usize]);
        let (q, _) = anisomesh::levelset::triangulated::closest::closest_point(p, a, b, c);
        d = d.min((p - q).length());
        let (a, b, c) = (a - p, b - p, c - p);
        let (la, lb, lc) = (a.length(), b.length(), c.length());
        let num = a.dot(b.cross(c));
        let den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
        winding += 2.0 * num.atan2(den);
    }
    if winding / (4.0 * std::f64::consts::PI) > 0.5 {
        -d
    } else {
        d
    }
}

const CUBE_OBJ: &str = "\
v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5
v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5
f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8
";

/// The signed distance to the box `[-h, h]³`.
fn box_distance(p: DVec3, h: f64) -> f64 {
    let q = p.abs() - DVec3::splat(h);
    q.max(DVec3::ZERO).length() + q.max_element().min(0.0)
}

/// The unit cube read from an OBJ file (quads, fan-triangulated): distances equal the exact box
/// distance to round-off, inside and outside, also near edges and corners where the face
/// normals alone would give the wrong sign; volume 1 and area 6.
#[test]
fn cube_obj_has_exact_distances() {
    let mesh = parse_obj(Path::new("cube.obj"), CUBE_OBJ.as_bytes()).unwrap();
    let cube = TriangulatedShape::from_mesh(&mesh).unwrap();
    assert_eq!(cube.flipped_triangles(), 0);
    assert!((cube.volume() - 1.0).abs() < 1e-14);
    assert!((cube.area() - 6.0).abs() < 1e-14);
    assert_eq!(cube.exact_area(), Some(cube.volume()));
    let pts = points(4000, 1.2, 1);
    let d = cube.distances(&pts);
    let mut inside = 0;
    for (&p, &dp) in pts.iter().zip(&d) {
        assert!((dp - box_distance(p, 0.5)).abs() < 1e-12, "{p}: {dp}");
        assert!((dp - brute_force(cube.surface(), p)).abs() < 1e-12);
        inside += usize::from(dp < 0.0);
    }
    assert!(inside > 200, "{inside} points inside");
    // Just outside an edge and a corner, along the diagonal: the closest feature is the edge
    // or the vertex, and the sign must still be positive (and negative just inside).
    for dir in [DVec3::new(1.0, 1.0, 0.0), DVec3::ONE] {
        let q = 0.5 * dir;
        for eps in [1e-9, 1e-3, 0.3] {
            let n = dir.normalize();
            assert!((cube.distance(q + eps * n) - eps).abs() < 1e-12);
            assert!(cube.distance(q - eps * n) < 0.0);
        }
    }
    // The gradient is the unit direction away from the closest point.
    let g = cube.gradient(DVec3::new(0.9, 0.1, -0.2));
    assert!((g - DVec3::X).length() < 1e-12, "{g}");
}

/// An icosphere: distances to it are within its chord error of `|p| − 1`, and agree with the
/// brute-force reference (distance over all triangles, sign by winding number).
#[test]
fn icosphere_distance_within_chord_error() {
    let s = icosphere(4);
    let sphere = shape(&s);
    // The surface lies between the sphere and the planes of its triangles.
    let chord = s
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| s.points[v as usize]);
            1.0 - a.dot((b - a).cross(c - a).normalize())
        })
        .fold(0.0, f64::max);
    assert!(chord > 0.0 && chord < 2e-3, "chord error {chord}");
    let pts = points(20000, 1.6, 2);
    let d = sphere.distances(&pts);
    let mut worst = 0.0f64;
    for (&p, &dp) in pts.iter().zip(&d) {
        let e = (dp - (p.length() - 1.0)).abs();
        worst = worst.max(e);
        assert!(e <= chord + 1e-12, "{p}: {dp} vs {}", p.length() - 1.0);
    }
    eprintln!("icosphere level 4: chord error {chord:.3e}, worst distance error {worst:.3e}");
    for &p in &pts[..400] {
        assert!((sphere.distance(p) - brute_force(&s, p)).abs() < 1e-12);
    }
    let seq: Vec<f64> = pts.iter().map(|&p| sphere.distance(p)).collect();
    assert_eq!(seq, d, "parallel and sequential evaluations differ");
}

/// The star of 004 §5 at a coarse level: random points against the brute force, which is where
/// concave edges and saddle vertices test the pseudo-normal sign.
#[test]
fn star_distance_matches_brute_force() {
    let s = radial_surface(DVec3::ZERO, |d| StarSurface::PAPER.radius_towards(d), 3);
    let star = shape(&s);
    assert_eq!(star.flipped_triangles(), 0);
    let pts = points(3000, 0.9, 3);
    let d = star.distances(&pts);
    let mut inside = 0;
    for (&p, &dp) in pts.iter().zip(&d) {
        assert!((dp - brute_force(&s, p)).abs() < 1e-12, "{p}: {dp}");
        inside += usize::from(dp < 0.0);
    }
    assert!(inside > 100, "{inside} inside");
    // Points on the vertices are at distance zero.
    for &p in s.points.iter().take(50) {
        assert!(star.distance(p).abs() < 1e-15);
    }
}

/// Half of the triangles reversed: the repair reverses them back (triangle 0, the seed, kept
/// its orientation, so exactly the odd ones flip) and the distances are those of the
/// consistent surface. The whole surface reversed comes back outward.
#[test]
fn inconsistent_orientation_is_repaired() {
    let s = icosphere(3);
    let good = shape(&s);
    let mut bad = s.clone();
    for (i, t) in bad.triangles.iter_mut().enumerate() {
        if i % 2 == 1 {
            t.swap(1, 2);
        }
    }
    let fixed = shape(&bad);
    assert_eq!(fixed.flipped_triangles(), s.triangles.len() / 2);
    assert_eq!(fixed.surface().triangles, s.triangles);
    let pts = points(2000, 1.5, 4);
    assert_eq!(good.distances(&pts), fixed.distances(&pts));
    let mut inverted = s.clone();
    for t in &mut inverted.triangles {
        t.swap(1, 2);
    }
    let fixed = shape(&inverted);
    assert_eq!(fixed.flipped_triangles(), s.triangles.len());
    assert!((fixed.volume() - good.volume()).abs() < 1e-14);
    assert_eq!(good.distances(&pts), fixed.distances(&pts));
}

/// Two disjoint spheres, one given inward: two components, both outward after the repair, and
/// the distance is the smaller of the two sphere distances (within the chord error).
#[test]
fn two_components_are_oriented_independently() {
    let a = icosphere(3);
    let mut s = a.clone();
    let base = s.points.len() as u32;
    s.points.extend(
        a.points
            .iter()
            .map(|&p| 0.5 * p + DVec3::new(3.0, 0.0, 0.0)),
    );
    s.triangles.extend(
        a.triangles
            .iter()
            .map(|t| [t[0] + base, t[2] + base, t[1] + base]),
    );
    let two = shape(&s);
    assert_eq!(two.components(), 2);
    assert_eq!(two.flipped_triangles(), a.triangles.len());
    let single = shape(&a);
    assert!((two.volume() - 1.125 * single.volume()).abs() < 1e-12);
    for p in [
        DVec3::new(3.0, 0.0, 0.1),
        DVec3::new(1.8, 0.2, 0.0),
        DVec3::ZERO,
    ] {
        let exact = (p.length() - 1.0).min((p - DVec3::new(3.0, 0.0, 0.0)).length() - 0.5);
        assert!((two.distance(p) - exact).abs() < 1e-2, "{p}");
    }
}

fn invalid_message(points: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> String {
    match TriangulatedShape::new(points, triangles) {
        Err(Error::InvalidInput(m)) => m,
        Err(e) => panic!("wrong error kind: {e}"),
        Ok(_) => panic!("accepted an invalid surface"),
    }
}

/// Holes, non-manifold edges and vertices, degenerate triangles, non-finite coordinates and bad
/// indices are typed errors naming the first offender and the count.
#[test]
fn invalid_surfaces_are_rejected() {
    let s = icosphere(2);
    let mut holed = s.triangles.clone();
    holed.remove(7);
    let m = invalid_message(s.points.clone(), holed);
    assert!(
        m.contains("not closed") && m.contains("(3 boundary edges)"),
        "{m}"
    );

    let mut two_holes = s.triangles.clone();
    two_holes.remove(30);
    two_holes.remove(7);
    let m = invalid_message(s.points.clone(), two_holes);
    // The first offender is the lowest-numbered triangle beside a removed one (4, next to 7).
    assert!(
        m.contains("(6 boundary edges)") && m.contains("of triangle 4 "),
        "{m}"
    );

    let mut doubled = s.triangles.clone();
    doubled.push(s.triangles[5]);
    let m = invalid_message(s.points.clone(), doubled);
    assert!(
        m.contains("non-manifold") && m.contains("(3 non-manifold edges)"),
        "{m}"
    );

    let mut pts = s.points.clone();
    pts[3] = DVec3::new(f64::NAN, 0.0, 0.0);
    let m = invalid_message(pts, s.triangles.clone());
    assert!(m.contains("vertex 3") && m.contains("non-finite"), "{m}");

    let mut pts = s.points.clone();
    let t = s.triangles[4];
    pts[t[2] as usize] = 0.5 * (pts[t[0] as usize] + pts[t[1] as usize]);
    let m = invalid_message(pts, s.triangles.clone());
    assert!(m.contains("degenerate"), "{m}");

    let mut tris = s.triangles.clone();
    tris[0][1] = 100_000;
    let m = invalid_message(s.points.clone(), tris);
    assert!(m.contains("triangle 0"), "{m}");

    assert!(invalid_message(s.points.clone(), vec![]).contains("no triangles"));

    // Two tetrahedra touching at one vertex: every edge is manifold, the vertex is not.
    let pts = vec![
        DVec3::ZERO,
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(0.0, 0.0, 1.0),
        DVec3::new(-1.0, 0.0, 0.0),
        DVec3::new(0.0, -1.0, 0.0),
        DVec3::new(0.0, 0.0, -1.0),
    ];
    let tet = |a: u32, b: u32, c: u32, d: u32| vec![[a, c, b], [a, b, d], [b, c, d], [c, a, d]];
    let mut tris = tet(0, 1, 2, 3);
    tris.extend(tet(0, 4, 5, 6));
    let m = invalid_message(pts, tris);
    assert!(
        m.contains("vertex 0") && m.contains("(1 such vertices)"),
        "{m}"
    );
}

/// The radial star surface: its enclosed volume converges to the exact volume of the 004 §5
/// star (0.4805422178) at second order in the edge length (measured orders 1.76, 1.93, 1.98
/// from level 3 to 6: the asymptotic ones are checked); the icosphere's to 4π/3.
#[test]
fn star_volume_converges_at_second_order() {
    let exact = StarSurface::PAPER.exact_area().unwrap();
    assert!((exact - 0.4805422178).abs() < 1e-9);
    let err = |level| {
        let s = radial_surface(DVec3::ZERO, |d| StarSurface::PAPER.radius_towards(d), level);
        assert_eq!(s.triangles.len(), 20 << (2 * level));
        (s.enclosed_volume() - exact).abs() / exact
    };
    let e: Vec<f64> = (3..=6).map(err).collect();
    eprintln!("star volume relative errors, levels 3..6: {e:?}");
    for w in e[1..].windows(2) {
        let order = (w[0] / w[1]).log2();
        assert!((1.8..2.3).contains(&order), "order {order} ({e:?})");
    }
    assert!(e[3] < 3e-3, "level 6 error {}", e[3]);
    let sphere = icosphere(5);
    let v = 4.0 / 3.0 * std::f64::consts::PI;
    assert!((sphere.enclosed_volume() - v).abs() / v < 2e-3);
}

/// The parametric torus: closed (accepted by the validation with no flip) and its volume
/// converges to `2 π² R r²` at second order.
#[test]
fn torus_surface_is_closed_and_converges() {
    let (big, small) = (0.4, 0.2);
    let exact = 2.0 * std::f64::consts::PI.powi(2) * big * small * small;
    let err = |n: usize| {
        let s = torus_surface(DVec3::ZERO, big, small, 2 * n, n);
        let t = shape(&s);
        assert_eq!(t.flipped_triangles(), 0);
        (s.enclosed_volume() - exact).abs() / exact
    };
    let (e1, e2) = (err(16), err(32));
    let order = (e1 / e2).log2();
    assert!((1.8..2.3).contains(&order), "order {order} ({e1} -> {e2})");
    let t = shape(&torus_surface(DVec3::ZERO, big, small, 128, 64));
    assert!(t.distance(DVec3::ZERO) > 0.19 && t.distance(DVec3::new(0.4, 0.0, 0.0)) < -0.19);
}

/// The shipped star meshes (`meshes/star.obj`, level 6, and `meshes/star_coarse.obj`, level 4,
/// written by `anisomesh triangulate`) read back as closed, outward surfaces with the volume
/// errors of their levels, and their distance vanishes on the exact star (within the chord
/// error) along the axes.
#[test]
fn shipped_star_meshes_are_valid() {
    let exact = StarSurface::PAPER.exact_area().unwrap();
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("meshes");
    for (file, triangles, max_err) in [
        ("star.obj", 81920, 2.2e-3),
        ("star_coarse.obj", 5120, 3.3e-2),
    ] {
        let mesh = anisomesh::io::read_obj(&dir.join(file)).unwrap();
        assert_eq!(mesh.tris.len(), triangles);
        let star = TriangulatedShape::from_mesh(&mesh).unwrap();
        assert_eq!(star.flipped_triangles(), 0, "{file}");
        assert_eq!(star.components(), 1);
        let err = (star.volume() - exact).abs() / exact;
        assert!(err < max_err, "{file}: volume error {err}");
        if triangles == 81920 {
            // On the tips along x and z (vertices of the icosphere lie near, not on, them).
            for d in [DVec3::X, DVec3::Z, DVec3::new(1.0, 1.0, 0.5).normalize()] {
                let p = StarSurface::PAPER.radius_towards(d) * d;
                assert!(star.distance(p).abs() < 5e-3, "{file}: {d}");
            }
        }
    }
}
