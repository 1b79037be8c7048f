//! `metric::conformity` against an independent computation: the length of every edge integrated
//! along the edge in the analytic metric (composite Gauss–Legendre, 64 panels × 3 points), on an
//! adapted Zalesak mesh (004 eq. (6)) in 2D and on a Kuhn mesh of the unit cube in the UGAWG
//! cube-linear and cube-polar-1 metrics in 3D. The share of edges in `[1/√2, √2]` must agree to
//! 1e-3 for [`conformity_analytic`]; the end-point formula of [`conformity`] (vertex metrics
//! only) is within 0.1 and printed beside it.

use anisomesh::adapt::{run, AdaptTarget, LevelSetMetric, RunOptions};
use anisomesh::levelset::{Shape, Zalesak};
use anisomesh::mesh3::Mesh3;
use anisomesh::metric::conformity::cell_edges;
use anisomesh::metric::ugawg::UgawgCase;
use anisomesh::metric::{conformity, conformity_analytic, Sym2, SymTensor};
use anisomesh::{DVec2, DVec3};

const L_MIN: f64 = std::f64::consts::FRAC_1_SQRT_2;
const L_MAX: f64 = std::f64::consts::SQRT_2;

/// `∫_0^1 sqrt(e^T M(a + t e) e) dt` by 64 panels of 3-point Gauss–Legendre.
fn exact_length<P, S, const D: usize>(a: P, b: P, m: &impl Fn(P) -> S) -> f64
where
    P: anisomesh::geom::Point<D>,
    S: SymTensor<D, Vec = P>,
{
    let (x, w) = (
        [-(0.6f64).sqrt(), 0.0, (0.6f64).sqrt()],
        [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0],
    );
    let e = b - a;
    let panels = 64;
    let h = 1.0 / panels as f64;
    let mut s = 0.0;
    for k in 0..panels {
        let c = (k as f64 + 0.5) * h;
        for i in 0..3 {
            let t = c + 0.5 * h * x[i];
            s += 0.5 * h * w[i] * m(a + e * t).quad(e).sqrt();
        }
    }
    s
}

/// Moves every vertex by 1e-3 of its shortest edge in a pseudo-random direction: the untouched
/// background of an adapted mesh has edges of length exactly `√2` in the metric (right-angle
/// diagonals of size `hmax`), whose side of the bound is decided by round-off otherwise.
fn jitter(points: &mut [DVec2], cells: &[[u32; 3]]) {
    let mut shortest = vec![f64::INFINITY; points.len()];
    for [a, b] in cell_edges(cells) {
        let l = (points[a as usize] - points[b as usize]).length();
        for v in [a, b] {
            shortest[v as usize] = shortest[v as usize].min(l);
        }
    }
    let mut state = 0x2545_f491_4f6c_dd1du64;
    for (p, h) in points.iter_mut().zip(&shortest) {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        let t = (state >> 11) as f64 / (1u64 << 53) as f64 * std::f64::consts::TAU;
        *p += DVec2::new(t.cos(), t.sin()) * (1e-3 * h);
    }
}

fn share_in_range(lengths: &[f64]) -> f64 {
    lengths
        .iter()
        .filter(|&&l| (L_MIN..=L_MAX).contains(&l))
        .count() as f64
        / lengths.len() as f64
}

#[test]
fn zalesak_metric_share_agrees_with_edge_integration() {
    let lm = LevelSetMetric {
        eps: 1e-3,
        hmin: 5e-3,
        hmax: 0.2,
        band: 5e-3,
        ..LevelSetMetric::default()
    };
    let opts = RunOptions {
        metric: lm,
        ..RunOptions::default()
    };
    let domain = (DVec2::splat(-2.0), DVec2::splat(2.0));
    let out = run(AdaptTarget::shape(Zalesak::default(), domain), &opts).unwrap();
    let z = Zalesak::default();
    let metric = |p: DVec2| lm.metric(z.distance(p), z.gradient(p), &z.hessian(p));
    let mut mesh = out.mesh;
    let cells: Vec<[u32; 3]> = mesh.live_tris().map(|t| mesh.tris[t]).collect();
    jitter(&mut mesh.points, &cells);
    let mesh = &mesh;
    let at_vertices: Vec<Sym2> = mesh.points.iter().map(|&p| metric(p)).collect();
    let v = conformity(&mesh.points, &cells, &at_vertices).unwrap();
    let c = conformity_analytic(&mesh.points, &cells, &metric).unwrap();
    let exact: Vec<f64> = cell_edges(&cells)
        .iter()
        .map(|&[a, b]| exact_length(mesh.points[a as usize], mesh.points[b as usize], &metric))
        .collect();
    let share = share_in_range(&exact);
    eprintln!(
        "zalesak: {} vertices, {} edges, share {:.5} (analytic) {:.5} (vertex metrics) vs {:.5} \
         (edge integration)",
        mesh.n_points(),
        c.edges,
        c.edge_length_in_range,
        v.edge_length_in_range,
        share
    );
    assert!((v.edge_length_in_range - share).abs() <= 0.1);
    assert_eq!(c.edges, exact.len());
    assert!(c.edge_length_in_range > 0.8, "{c:?}");
    assert!((c.edge_length_in_range - share).abs() <= 1e-3);
    assert_eq!(c.inverted, 0);
    assert!(c.mean_ratio_min > 0.0 && c.mean_ratio_mean <= 1.0 + 1e-12);
}

fn ugawg_case(case: UgawgCase, n: usize) -> (f64, f64, f64, usize) {
    let mesh = Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [n; 3]).unwrap();
    let metric = |p: DVec3| case.metric(p);
    let v = conformity(&mesh.points, &mesh.tets, &case.field(&mesh.points)).unwrap();
    let c = conformity_analytic(&mesh.points, &mesh.tets, &metric).unwrap();
    let exact: Vec<f64> = cell_edges(&mesh.tets)
        .iter()
        .map(|&[a, b]| exact_length(mesh.points[a as usize], mesh.points[b as usize], &metric))
        .collect();
    assert_eq!(c.edges, exact.len());
    assert_eq!(c.inverted, 0);
    (
        c.edge_length_in_range,
        v.edge_length_in_range,
        share_in_range(&exact),
        c.edges,
    )
}

#[test]
fn ugawg_metrics_share_agrees_with_edge_integration() {
    // 17 cells per side: no edge sits exactly on a bound (with 20, the xy diagonals measure
    // exactly 1/√2 in the 0.1 sizes).
    for case in [UgawgCase::CubeLinear, UgawgCase::CubePolar1] {
        let (ours, vertex, exact, edges) = ugawg_case(case, 17);
        eprintln!(
            "{}: Kuhn 17^3, {edges} edges, share {ours:.5} (analytic) {vertex:.5} (vertex \
             metrics) vs {exact:.5} (edge integration)",
            case.name()
        );
        assert!((vertex - exact).abs() <= 0.1);
        assert!(ours > 0.05, "{ours}");
        assert!((ours - exact).abs() <= 1e-3);
    }
}
