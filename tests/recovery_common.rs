//! Shared helpers of the recovery tests (included with `#[path]` by `recovery_exactness.rs` and
//! `recovery_convergence.rs`): perturbed meshes, test functions with exact derivatives, errors.
#![allow(dead_code)]

use anisomesh::geom::signed_area;
use anisomesh::{DVec2, GridPattern, Mesh2, Sym2};

/// splitmix64: a small deterministic generator (no `rand` dependency).
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in `[0, 1)`.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Moves every interior vertex by a random offset of length up to `amp * h` (uniform in the
/// disk), keeping a move only if every triangle around the vertex keeps an area of at least
/// `h^2 / 20`. Boundary vertices stay. Calls `check()`.
pub fn perturb(mesh: &mut Mesh2, h: f64, amp: f64, seed: u64) {
    let mut rng = Rng::new(seed);
    let boundary = mesh.boundary_vertex_flags();
    for (v, &on_boundary) in boundary.iter().enumerate() {
        let (r, a) = (
            amp * h * rng.unit().sqrt(),
            std::f64::consts::TAU * rng.unit(),
        );
        if on_boundary {
            continue;
        }
        let old = mesh.points[v];
        mesh.points[v] = old + r * DVec2::new(a.cos(), a.sin());
        let ok = mesh.vertex_fan(v as u32).iter().all(|&t| {
            let [p, q, s] = mesh.tri_points(t as usize);
            signed_area(p, q, s) > h * h / 20.0
        });
        if !ok {
            mesh.points[v] = old;
        }
    }
    mesh.check().expect("perturbed mesh is valid");
}

/// The unit square with `n x n` cells of `pattern`, interior vertices moved by up to `amp * h`.
pub fn perturbed_square(n: usize, pattern: GridPattern, amp: f64, seed: u64) -> Mesh2 {
    let mut mesh = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, n, n, pattern).unwrap();
    perturb(&mut mesh, 1.0 / n as f64, amp, seed);
    mesh
}

/// A field with its exact gradient and Hessian.
pub trait Exact {
    fn value(&self, p: DVec2) -> f64;
    fn gradient(&self, p: DVec2) -> DVec2;
    fn hessian(&self, p: DVec2) -> Sym2;
}

/// `c0 + g . p + 1/2 p^T H p`.
pub struct Quadratic {
    pub c0: f64,
    pub g: DVec2,
    pub h: Sym2,
}

/// `1 + 2x - 3y + 0.7x^2 - 1.1xy + 2.3y^2`.
pub const QUAD: Quadratic = Quadratic {
    c0: 1.0,
    g: DVec2::new(2.0, -3.0),
    h: Sym2::new(1.4, -1.1, 4.6),
};

/// `0.5 - 1.25x + 2.5y`.
pub const LINEAR: Quadratic = Quadratic {
    c0: 0.5,
    g: DVec2::new(-1.25, 2.5),
    h: Sym2::new(0.0, 0.0, 0.0),
};

impl Exact for Quadratic {
    fn value(&self, p: DVec2) -> f64 {
        self.c0 + self.g.dot(p) + 0.5 * self.h.quad(p)
    }
    fn gradient(&self, p: DVec2) -> DVec2 {
        self.g + self.h.mul_vec(p)
    }
    fn hessian(&self, _: DVec2) -> Sym2 {
        self.h
    }
}

/// `sin(2x) cos(3y) + exp(xy)`.
pub struct Smooth;

impl Exact for Smooth {
    fn value(&self, p: DVec2) -> f64 {
        (2.0 * p.x).sin() * (3.0 * p.y).cos() + (p.x * p.y).exp()
    }
    fn gradient(&self, p: DVec2) -> DVec2 {
        let e = (p.x * p.y).exp();
        let (s2, c2) = (2.0 * p.x).sin_cos();
        let (s3, c3) = (3.0 * p.y).sin_cos();
        DVec2::new(2.0 * c2 * c3 + p.y * e, -3.0 * s2 * s3 + p.x * e)
    }
    fn hessian(&self, p: DVec2) -> Sym2 {
        let e = (p.x * p.y).exp();
        let (s2, c2) = (2.0 * p.x).sin_cos();
        let (s3, c3) = (3.0 * p.y).sin_cos();
        Sym2::new(
            -4.0 * s2 * c3 + p.y * p.y * e,
            -6.0 * c2 * s3 + (1.0 + p.x * p.y) * e,
            -9.0 * s2 * c3 + p.x * p.x * e,
        )
    }
}

/// Nodal values of `f`.
pub fn sample(mesh: &Mesh2, f: &dyn Exact) -> Vec<f64> {
    mesh.points.iter().map(|&p| f.value(p)).collect()
}

/// Frobenius norm of a symmetric 2x2 matrix.
pub fn sym_norm(s: Sym2) -> f64 {
    (s.xx * s.xx + 2.0 * s.xy * s.xy + s.yy * s.yy).sqrt()
}

pub fn sym_sub(a: Sym2, b: Sym2) -> Sym2 {
    Sym2::new(a.xx - b.xx, a.xy - b.xy, a.yy - b.yy)
}

/// Per-vertex errors of a recovered Hessian.
pub fn hessian_errors(mesh: &Mesh2, f: &dyn Exact, h: &[Sym2]) -> Vec<f64> {
    mesh.points
        .iter()
        .zip(h)
        .map(|(&p, &hv)| sym_norm(sym_sub(hv, f.hessian(p))))
        .collect()
}

/// Per-vertex errors of a recovered gradient.
pub fn gradient_errors(mesh: &Mesh2, f: &dyn Exact, g: &[DVec2]) -> Vec<f64> {
    mesh.points
        .iter()
        .zip(g)
        .map(|(&p, &gv)| (gv - f.gradient(p)).length())
        .collect()
}

/// Lumped vertex areas (`sum |T| / 3`), the weights of the discrete L2 norm.
pub fn lumped_areas(mesh: &Mesh2) -> Vec<f64> {
    let mut w = vec![0.0; mesh.n_points()];
    for t in mesh.live_tris() {
        let a = mesh.tri_area(t) / 3.0;
        for &v in &mesh.tris[t] {
            w[v as usize] += a;
        }
    }
    w
}

/// `(max, discrete L2)` of per-vertex errors over the vertices where `mask` is true.
pub fn norms(err: &[f64], weights: &[f64], mask: &[bool]) -> (f64, f64) {
    let mut max = 0.0f64;
    let (mut s, mut w) = (0.0, 0.0);
    for ((&e, &wt), &m) in err.iter().zip(weights).zip(mask) {
        if m {
            max = max.max(e);
            s += wt * e * e;
            w += wt;
        }
    }
    (max, (s / w.max(f64::MIN_POSITIVE)).sqrt())
}

/// Largest entry of `err`, with its vertex.
pub fn worst(err: &[f64]) -> (usize, f64) {
    err.iter()
        .copied()
        .enumerate()
        .fold((0, 0.0), |acc, (i, e)| if e > acc.1 { (i, e) } else { acc })
}
