//! Never an invalid mesh: the tetrahedral adaptation under random metric fields (sizes from
//! 10⁻³ to 1, anisotropy up to 1,000, random orientations, smoothly varying in space) on a box
//! and on a box with a cubic hole, with every mesh invariant checked after every pass. The box
//! is scaled to the metric so that each mesh stays small (mostly a few hundred vertices).

use anisomesh::adapt::{run3, tet_stats, AdaptOptions, Run3Options, Target3};
use anisomesh::geom::DVec3;
use anisomesh::mesh3::Mesh3;
use anisomesh::metric::Sym3;

/// xorshift64*: a small deterministic generator for the test.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A random orthonormal frame (from a random unit quaternion).
fn frame(r: &mut Rng) -> [DVec3; 3] {
    let q = glam::DQuat::from_xyzw(
        r.next() - 0.5,
        r.next() - 0.5,
        r.next() - 0.5,
        r.next() - 0.5,
    )
    .normalize();
    [q * DVec3::X, q * DVec3::Y, q * DVec3::Z]
}

/// A random field: sizes `h_i (1 + 0.4 sin(k·x + φ_i))` along a random frame, with the smallest
/// size in [1e-3, 1] and anisotropy up to 1000; and the box edge that gives a few hundred
/// vertices.
fn field(r: &mut Rng) -> (impl Fn(DVec3) -> Sym3 + Sync, f64) {
    let hmin = 10f64.powf(-3.0 + 3.0 * r.next());
    let aniso = 10f64.powf(3.0 * r.next()).min(1.0 / hmin).max(1.0);
    let h = [hmin, hmin * aniso.sqrt().powf(r.next() * 2.0), hmin * aniso];
    // The box edge `l` with `Π max(1, l / h_i)` = 20 (bisection on log l).
    let count = |l: f64| h.iter().map(|&x| (l / x).max(1.0)).product::<f64>();
    let (mut lo, mut hi) = (h[0], 1e3);
    for _ in 0..60 {
        let mid = (lo * hi).sqrt();
        if count(mid) < 20.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let l = lo;
    let e = frame(r);
    let k = DVec3::new(r.next(), r.next(), r.next()) * (6.0 / l);
    let phase = [r.next() * 6.3, r.next() * 6.3, r.next() * 6.3];
    let f = move |p: DVec3| {
        let mut m = Sym3::default();
        for i in 0..3 {
            let hi = h[i] * (1.0 + 0.4 * (k.dot(p) + phase[i]).sin());
            m = m.add(&Sym3::outer(e[i]).scale(1.0 / (hi * hi)));
        }
        m
    };
    (f, l)
}

/// The Kuhn mesh of `[0, l]³` with 4 cells per direction, without the central 2 × 2 × 2 cells.
fn holed_box(l: f64) -> Mesh3 {
    let m = Mesh3::kuhn_box(DVec3::ZERO, DVec3::splat(l), [4, 4, 4]).unwrap();
    let mut tets = Vec::new();
    for t in 0..m.n_tets() {
        let c = m.tet_points(t).iter().fold(DVec3::ZERO, |a, &p| a + p) / (4.0 * l);
        if !(c.cmpgt(DVec3::splat(0.25)).all() && c.cmplt(DVec3::splat(0.75)).all()) {
            tets.push(m.tets[t]);
        }
    }
    let n = tets.len();
    Mesh3::from_parts(m.points.clone(), tets, vec![0; n])
}

#[test]
fn random_metric_fields_never_break_the_mesh() {
    let mut r = Rng(0x9E37_79B9_7F4A_7C15);
    let mut worst_in_range = 1.0f64;
    for case in 0..100 {
        let (f, l) = field(&mut r);
        let hole = case % 2 == 1;
        let opts = Run3Options {
            lo: DVec3::ZERO,
            hi: DVec3::splat(l),
            cells: 2,
            adapt: AdaptOptions::default()
                .max_cycles(3)
                .final_sweeps(1)
                .check_each_pass(true)
                .max_vertices(Some(200_000)),
            ..Run3Options::default()
        };
        let start = hole.then(|| holed_box(l));
        let expected = if hole { 0.875 } else { 1.0 } * l * l * l;
        let a = run3(Target3::Metric(&f), start.as_ref(), &opts)
            .unwrap_or_else(|e| panic!("case {case}: {e}"));
        a.mesh.check().unwrap();
        let v = a.mesh.volume();
        assert!(
            (v - expected).abs() < 1e-9 * expected,
            "case {case}: volume {v} vs {expected}"
        );
        // Every boundary triangle of the box (and of its hole) lies exactly in its plane: its
        // three vertices share one coordinate bit for bit, however often they moved.
        for t in 0..a.mesh.n_tets() {
            for i in 0..4 {
                if a.mesh.neighbours[t][i] != anisomesh::mesh::NONE {
                    continue;
                }
                let f = a
                    .mesh
                    .face_vertices(t, i)
                    .map(|v| a.mesh.points[v as usize]);
                assert!(
                    (0..3).any(|k| f[0][k] == f[1][k] && f[1][k] == f[2][k]),
                    "case {case}: boundary triangle {f:?} off its plane"
                );
            }
        }
        let s = tet_stats(&a.mesh, &a.metric);
        assert!(s.quality_min > 0.0, "case {case}");
        worst_in_range = worst_in_range.min(s.edge_length_in_range);
    }
    eprintln!("worst fraction of edges in range over the fields: {worst_in_range:.3}");
}
