//! Edge lengths from vertex metrics only, against an independent adaptive-Simpson integration of
//! the analytic metric along every edge: which rule between the end tensors reproduces the share
//! of edges in `[1/√2, √2]`. Cases: an adapted Zalesak mesh in 004 eq. (6) (band and linear
//! growth outside it, whose kink at the band's edge no vertex sees), a Kuhn mesh 17³ in UGAWG
//! cube-linear and cube-polar-1. Also checks that [`conformity_analytic`] (what `measure
//! --ugawg` and `--expr-metric`-style analytic rating use) agrees with the adaptive integration
//! to 1e-3 in the share (measured: better than 1e-5).

use anisomesh::adapt::{run, AdaptTarget, LevelSetMetric, RunOptions};
use anisomesh::levelset::{Shape, Zalesak};
use anisomesh::mesh3::Mesh3;
use anisomesh::metric::conformity::cell_edges;
use anisomesh::metric::ugawg::UgawgCase;
use anisomesh::metric::{conformity, conformity_analytic, interpolate_log, SymTensor};
use anisomesh::{DVec2, DVec3};

const L_MIN: f64 = std::f64::consts::FRAC_1_SQRT_2;
const L_MAX: f64 = std::f64::consts::SQRT_2;

/// Adaptive Simpson on `[a, b]` to absolute tolerance `tol`.
fn simpson(f: &dyn Fn(f64) -> f64, a: f64, b: f64, tol: f64) -> f64 {
    // The classic recursion carries the end and middle values down.
    #[allow(clippy::too_many_arguments)]
    fn rec(
        f: &dyn Fn(f64) -> f64,
        a: f64,
        b: f64,
        fa: f64,
        fm: f64,
        fb: f64,
        whole: f64,
        tol: f64,
        depth: u32,
    ) -> f64 {
        let m = 0.5 * (a + b);
        let (lm, rm) = (0.5 * (a + m), 0.5 * (m + b));
        let (flm, frm) = (f(lm), f(rm));
        let left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
        let right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
        let delta = left + right - whole;
        // The tolerance is kept above round-off of the integral (else noise recurses forever).
        if depth == 0 || delta.abs() <= 15.0 * tol.max(1e-15 * whole.abs()) {
            return left + right + delta / 15.0;
        }
        rec(f, a, m, fa, flm, fm, left, 0.5 * tol, depth - 1)
            + rec(f, m, b, fm, frm, fb, right, 0.5 * tol, depth - 1)
    }
    let (fa, fm, fb) = (f(a), f(0.5 * (a + b)), f(b));
    let whole = (b - a) / 6.0 * (fa + 4.0 * fm + fb);
    rec(f, a, b, fa, fm, fb, whole, tol, 30)
}

/// The rules from the end metrics `ma`, `mb` of the edge `e`.
#[derive(Debug, Clone, Copy)]
enum Rule {
    /// `sqrt(ℓ_a ℓ_b)`.
    GeometricMean,
    /// `(ℓ_a − ℓ_b) / ln(ℓ_a / ℓ_b)`: the density varies geometrically (the library's
    /// `edge_length`, the formula MMG documents for anisotropic lengths).
    LogMean,
    /// The size varies linearly: `ℓ_a ℓ_b ln(ℓ_a / ℓ_b) / (ℓ_a − ℓ_b)`.
    LinearSize,
    /// `M(t) = exp((1 − t) ln M_a + t ln M_b)` integrated (adaptive Simpson).
    LogEuclidean,
    /// `M(t) = (1 − t) M_a + t M_b` integrated.
    LinearTensor,
}

const RULES: [Rule; 5] = [
    Rule::GeometricMean,
    Rule::LogMean,
    Rule::LinearSize,
    Rule::LogEuclidean,
    Rule::LinearTensor,
];

fn rule_length<const D: usize, S: SymTensor<D>>(rule: Rule, e: S::Vec, ma: &S, mb: &S) -> f64 {
    let (la, lb) = (ma.quad(e).sqrt(), mb.quad(e).sqrt());
    let tol = 1e-10 * la.max(lb);
    match rule {
        Rule::GeometricMean => (la * lb).sqrt(),
        Rule::LogMean => anisomesh::metric::length::geometric_mean_length(la, lb),
        Rule::LinearSize => {
            if (la - lb).abs() <= 1e-6 * la {
                0.5 * (la + lb)
            } else {
                la * lb * (la / lb).ln() / (la - lb)
            }
        }
        Rule::LogEuclidean => simpson(
            &|t| interpolate_log(&[(1.0 - t, *ma), (t, *mb)]).quad(e).sqrt(),
            0.0,
            1.0,
            tol,
        ),
        Rule::LinearTensor => simpson(
            &|t| ma.scale(1.0 - t).add(&mb.scale(t)).quad(e).sqrt(),
            0.0,
            1.0,
            tol,
        ),
    }
}

fn share(lengths: &[f64]) -> f64 {
    lengths
        .iter()
        .filter(|&&l| (L_MIN..=L_MAX).contains(&l))
        .count() as f64
        / lengths.len() as f64
}

/// For each rule: (share in range, largest relative length error) against `exact`.
fn compare<const D: usize, S: SymTensor<D>>(
    name: &str,
    points: &[S::Vec],
    edges: &[[u32; 2]],
    at: &[S],
    exact: &[f64],
) -> Vec<(f64, f64)> {
    let s_exact = share(exact);
    eprintln!("{name}: {} edges, exact share {s_exact:.5}", edges.len());
    RULES
        .iter()
        .map(|&r| {
            let l: Vec<f64> = edges
                .iter()
                .map(|&[a, b]| {
                    let (a, b) = (a as usize, b as usize);
                    rule_length(r, points[b] - points[a], &at[a], &at[b])
                })
                .collect();
            let rel = l
                .iter()
                .zip(exact)
                .map(|(x, y)| ((x - y) / y).abs())
                .fold(0.0, f64::max);
            let sh = share(&l);
            eprintln!(
                "  {r:?}: share {sh:.5} (off by {:+.5}), largest relative length error {rel:.3e}",
                sh - s_exact
            );
            (sh, rel)
        })
        .collect()
}

fn exact_lengths<P, S, const D: usize>(
    points: &[P],
    edges: &[[u32; 2]],
    m: &(impl Fn(P) -> S + Sync),
) -> Vec<f64>
where
    P: anisomesh::geom::Point<D>,
    S: SymTensor<D, Vec = P>,
{
    edges
        .iter()
        .map(|&[a, b]| {
            let (pa, pb) = (points[a as usize], points[b as usize]);
            let e = pb - pa;
            let scale = m(pa).quad(e).sqrt().max(m(pb).quad(e).sqrt());
            simpson(&|t| m(pa + e * t).quad(e).sqrt(), 0.0, 1.0, 1e-11 * scale)
        })
        .collect()
}

/// Moves every vertex by 1e-3 of its shortest edge in a pseudo-random direction: the untouched
/// background of an adapted mesh has edges of length exactly `√2` in the metric (right-angle
/// diagonals of size `hmax`), whose side of the bound round-off decides otherwise.
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

#[test]
fn zalesak_vertex_metric_rules_against_adaptive_integration() {
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
    let edges = cell_edges(&cells);
    let exact = exact_lengths(&mesh.points, &edges, &metric);
    let c = conformity_analytic(&mesh.points, &cells, &metric).unwrap();
    eprintln!(
        "conformity_analytic share {:.6} vs adaptive Simpson {:.6}",
        c.edge_length_in_range,
        share(&exact)
    );
    assert!((c.edge_length_in_range - share(&exact)).abs() <= 1e-3);
    let at: Vec<_> = mesh.points.iter().map(|&p| metric(p)).collect();
    let v = conformity(&mesh.points, &cells, &at).unwrap();
    let rules = compare("zalesak eq. (6)", &mesh.points, &edges, &at, &exact);
    // The library's vertex rule is the linear size, the closest to the integration here.
    assert!((v.edge_length_in_range - rules[2].0).abs() < 0.5 / edges.len() as f64);
    let off = |r: &(f64, f64)| (r.0 - share(&exact)).abs();
    assert!(off(&rules[2]) <= 5e-3, "{rules:?}");
    assert!(rules.iter().all(|r| off(&rules[2]) <= off(r)), "{rules:?}");
}

#[test]
fn ugawg_vertex_metric_rules_against_adaptive_integration() {
    for case in [UgawgCase::CubeLinear, UgawgCase::CubePolar1] {
        let mesh = Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [17; 3]).unwrap();
        let metric = |p: DVec3| case.metric(p);
        let edges = cell_edges(&mesh.tets);
        let exact = exact_lengths(&mesh.points, &edges, &metric);
        let c = conformity_analytic(&mesh.points, &mesh.tets, &metric).unwrap();
        eprintln!(
            "{}: conformity_analytic share {:.6} vs adaptive Simpson {:.6}",
            case.name(),
            c.edge_length_in_range,
            share(&exact)
        );
        assert!((c.edge_length_in_range - share(&exact)).abs() <= 1e-3);
        let at = case.field(&mesh.points);
        let rules = compare(case.name(), &mesh.points, &edges, &at, &exact);
        let v = conformity(&mesh.points, &mesh.tets, &at).unwrap();
        assert!((v.edge_length_in_range - rules[2].0).abs() < 0.5 / edges.len() as f64);
        assert!(
            (v.edge_length_in_range - share(&exact)).abs() <= 1e-3,
            "{rules:?}"
        );
    }
}
