//! Least-squares quadratic fits on vertex patches: the common core of the least-squares Hessian
//! (004 §4.3) and of PPR (003 §6.2).
//!
//! At a vertex `x` the patch starts as the first ring and is widened ring by ring (up to
//! [`MAX_RINGS`]) while the fit is under-determined (fewer than `unknowns + 1` equations) or
//! ill-conditioned (a pivot of the column-scaled QR below [`MIN_PIVOT`]). Boundary vertices, which
//! have few neighbours on one side only, get their second ring this way.
//!
//! **Conditioning.** The offsets `d_i = x_i - x` are mapped to `d'_i = T d_i` with
//! `T = C^{-1/2}`, `C = (1/k) sum d_i d_i^T` the second-moment tensor of the patch. This scales the
//! patch to unit size *and* undoes its stretching, so a patch of aspect ratio 100 (or 1e4) is
//! as well conditioned as an isotropic one. P2 is invariant under linear maps, so the fit is still
//! exact for quadratics; the derivatives map back as `grad = T g'` and `H = T H' T`.
//! The columns are then scaled to unit norm and the system is solved by QR ([`super::lsq`]).
//!
//! **Fallback** (003 §6.2): if even the widened patch (or a tiny component) gives no
//! well-conditioned full quadratic, the fit drops the cross term `xy`, then fits a linear
//! polynomial (zero Hessian).

use super::lsq::{self, MAX_UNKNOWNS};
use crate::geom::DVec2;
use crate::mesh::{Mesh2, NONE};
use crate::metric::Sym2;

/// Rings a patch may grow to before the fit falls back to fewer unknowns.
pub(crate) const MAX_RINGS: usize = 4;

/// Smallest accepted pivot `|R_kk|` of the column-scaled QR (1 is perfect, 0 singular). Below it
/// the patch is widened.
pub(crate) const MIN_PIVOT: f64 = 2e-2;

/// Smallest pivot accepted by the fallback fits on the largest patch.
const FALLBACK_PIVOT: f64 = 1e-9;

/// How the value at the vertex itself enters the fit.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Value {
    /// `p(x) = u(x)` is kept: 5 unknowns (gradient, Hessian), one equation per neighbour — the
    /// Taylor expansion of 004 §4.3.
    Fixed,
    /// `p(x)` is fitted too: 6 unknowns, one equation per patch vertex including `x` — PPR,
    /// 003 §6.2.
    Fitted,
}

/// Monomials of the local fit in whitened coordinates `d'`.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Mono {
    One,
    X,
    Y,
    /// `x^2 / 2`
    Xx,
    Xy,
    /// `y^2 / 2`
    Yy,
}

impl Mono {
    #[inline]
    fn eval(self, d: DVec2) -> f64 {
        match self {
            Mono::One => 1.0,
            Mono::X => d.x,
            Mono::Y => d.y,
            Mono::Xx => 0.5 * d.x * d.x,
            Mono::Xy => d.x * d.y,
            Mono::Yy => 0.5 * d.y * d.y,
        }
    }
}

const FULL: [Mono; 6] = [Mono::One, Mono::X, Mono::Y, Mono::Xx, Mono::Xy, Mono::Yy];
const NO_CROSS: [Mono; 5] = [Mono::One, Mono::X, Mono::Y, Mono::Xx, Mono::Yy];
const LINEAR: [Mono; 3] = [Mono::One, Mono::X, Mono::Y];

/// The result of a fit at one vertex: gradient and Hessian of the fitted polynomial there.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Fit {
    pub gradient: DVec2,
    pub hessian: Sym2,
}

/// Per-thread scratch space: the patch and the dense least-squares system. Reused from vertex to
/// vertex, so the hot loop does not allocate once the buffers have grown.
#[derive(Default)]
pub(crate) struct Workspace {
    /// The patch; `verts[0]` is the centre vertex.
    verts: Vec<u32>,
    /// Start in `verts` of the outermost ring.
    ring_start: usize,
    a: Vec<f64>,
    b: Vec<f64>,
}

impl Workspace {
    fn start(&mut self, v: u32) {
        self.verts.clear();
        self.verts.push(v);
        self.ring_start = 0;
    }

    /// Adds the next ring; returns whether any vertex was added.
    fn grow(&mut self, mesh: &Mesh2) -> bool {
        let end = self.verts.len();
        for idx in self.ring_start..end {
            let w = self.verts[idx];
            let verts = &mut self.verts;
            mesh.for_each_fan_triangle(w, |t| {
                for &x in &mesh.tris[t as usize] {
                    if !verts.contains(&x) {
                        verts.push(x);
                    }
                }
            });
        }
        self.ring_start = end;
        self.verts.len() > end
    }

    /// Number of equations of a fit on the current patch.
    fn rows(&self, value: Value) -> usize {
        match value {
            Value::Fixed => self.verts.len() - 1,
            Value::Fitted => self.verts.len(),
        }
    }

    /// Least-squares fit of `basis` (without `One` for [`Value::Fixed`]) on the current patch.
    /// Returns the fit and the smallest QR pivot, or `None` if the system is singular.
    fn solve(
        &mut self,
        mesh: &Mesh2,
        u: &[f64],
        basis: &[Mono],
        value: Value,
    ) -> Option<(Fit, f64)> {
        let v = self.verts[0] as usize;
        let (pv, uv) = (mesh.points[v], u[v]);
        let neighbours = &self.verts[1..];
        if neighbours.is_empty() {
            return None;
        }
        // Second-moment tensor of the offsets and its inverse square root (whitening).
        let mut c = Sym2::default();
        for &w in neighbours {
            c = c.add(&Sym2::outer(mesh.points[w as usize] - pv));
        }
        let (l, e) = c.scale(1.0 / neighbours.len() as f64).eigen();
        if !(l[0] > 1e-24 * l[1] && l[1].is_finite()) {
            return None;
        }
        let t = Sym2::from_eigen([1.0 / l[0].sqrt(), 1.0 / l[1].sqrt()], e);

        let basis = match value {
            Value::Fixed => &basis[1..],
            Value::Fitted => basis,
        };
        let (m, n) = (self.rows(value), basis.len());
        let rows = match value {
            Value::Fixed => &self.verts[1..],
            Value::Fitted => &self.verts[..],
        };
        self.a.clear();
        self.a.resize(m * n, 0.0);
        self.b.clear();
        for (r, &w) in rows.iter().enumerate() {
            let d = t.mul_vec(mesh.points[w as usize] - pv);
            for (j, mono) in basis.iter().enumerate() {
                self.a[j * m + r] = mono.eval(d);
            }
            self.b.push(u[w as usize] - uv);
        }
        let mut x = [0.0; MAX_UNKNOWNS];
        let pivot = lsq::solve(&mut self.a, m, n, &mut self.b, &mut x)?;
        let (mut g, mut h) = (DVec2::ZERO, Sym2::default());
        for (mono, &xj) in basis.iter().zip(&x) {
            match mono {
                Mono::One => {}
                Mono::X => g.x = xj,
                Mono::Y => g.y = xj,
                Mono::Xx => h.xx = xj,
                Mono::Xy => h.xy = xj,
                Mono::Yy => h.yy = xj,
            }
        }
        let fit = Fit {
            gradient: t.mul_vec(g),
            hessian: congruence(&t, &h),
        };
        let finite = fit.gradient.is_finite()
            && [fit.hessian.xx, fit.hessian.xy, fit.hessian.yy]
                .iter()
                .all(|x| x.is_finite());
        finite.then_some((fit, pivot))
    }
}

/// `T H T` for symmetric `T` (the chain rule for the Hessian under `d' = T d`).
#[inline]
fn congruence(t: &Sym2, h: &Sym2) -> Sym2 {
    let (p, q, r) = (t.xx, t.xy, t.yy);
    let (a, b, c) = (h.xx, h.xy, h.yy);
    let (m00, m01) = (a * p + b * q, a * q + b * r);
    let (m10, m11) = (b * p + c * q, b * q + c * r);
    Sym2::new(p * m00 + q * m10, p * m01 + q * m11, q * m01 + r * m11)
}

/// Quadratic least-squares fit at vertex `v` on a patch widened as needed (module docs).
/// Unreferenced vertices get a zero fit. The caller has validated `mesh` and `u`.
pub(crate) fn fit_vertex(mesh: &Mesh2, u: &[f64], v: u32, value: Value, ws: &mut Workspace) -> Fit {
    if mesh.vert_tri[v as usize] == NONE {
        return Fit::default();
    }
    let needed = match value {
        Value::Fixed => FULL.len(),
        Value::Fitted => FULL.len() + 1,
    };
    ws.start(v);
    for _ in 0..MAX_RINGS {
        let grew = ws.grow(mesh);
        if grew && ws.rows(value) >= needed {
            if let Some((fit, pivot)) = ws.solve(mesh, u, &FULL, value) {
                if pivot >= MIN_PIVOT {
                    return fit;
                }
            }
        }
        if !grew {
            break;
        }
    }
    // 003 §6.2: fewer unknowns when the patch cannot determine a full quadratic.
    for basis in [&FULL[..], &NO_CROSS[..], &LINEAR[..]] {
        if let Some((fit, pivot)) = ws.solve(mesh, u, basis, value) {
            if pivot >= FALLBACK_PIVOT {
                return fit;
            }
        }
    }
    Fit::default()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::GridPattern;

    #[test]
    fn congruence_matches_matrix_product() {
        let t = Sym2::new(2.0, 0.3, 0.5);
        let h = Sym2::new(1.0, -0.7, 3.0);
        let r = congruence(&t, &h);
        // Explicit T H T.
        let tm = [[t.xx, t.xy], [t.xy, t.yy]];
        let hm = [[h.xx, h.xy], [h.xy, h.yy]];
        let mut out = [[0.0; 2]; 2];
        for (i, row) in out.iter_mut().enumerate() {
            for (j, o) in row.iter_mut().enumerate() {
                for k in 0..2 {
                    for l in 0..2 {
                        *o += tm[i][k] * hm[k][l] * tm[l][j];
                    }
                }
            }
        }
        assert!((r.xx - out[0][0]).abs() < 1e-14);
        assert!((r.xy - out[0][1]).abs() < 1e-14);
        assert!((r.xy - out[1][0]).abs() < 1e-14);
        assert!((r.yy - out[1][1]).abs() < 1e-14);
    }

    #[test]
    fn patch_grows_by_rings() {
        let mesh = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 6, 6, GridPattern::Right).unwrap();
        let centre = 3 * 7 + 3;
        let mut ws = Workspace::default();
        ws.start(centre);
        assert!(ws.grow(&mesh));
        assert_eq!(ws.verts.len(), 7);
        assert!(ws.grow(&mesh));
        assert_eq!(ws.verts.len(), 19);
        let corner = 0;
        ws.start(corner);
        assert!(ws.grow(&mesh));
        assert_eq!(ws.verts.len(), 4);
    }
}
