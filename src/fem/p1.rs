//! Continuous P1 (linear Lagrange) finite elements on triangles: element matrices, global
//! assembly of mass, lumped mass, stiffness and load, interpolation and error norms.
//!
//! Per-element data (coefficients) is indexed by triangle *slot* `t` of `mesh.tris`; tombstones
//! are skipped. A P1 field is a `Vec<f64>` indexed by vertex.

use super::assembly::{assemble_matrix, assemble_vector};
use super::csr::Csr;
use super::quadrature::tri_rule;
use crate::error::{Error, MeshDefect, Result};
use crate::geom::DVec2;
use crate::mesh::{check_p1_field, Mesh2};
use crate::metric::Sym2;

/// Geometry of one P1 triangle: its area and the (constant) gradients of the three barycentric
/// basis functions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct P1Geom {
    /// Area of the triangle.
    pub area: f64,
    /// Gradient of the barycentric basis function of each vertex.
    pub grad: [DVec2; 3],
}

impl P1Geom {
    /// Area and basis gradients of the triangle `p` (counter-clockwise):
    /// `∇λ_i = (p_{i+2} - p_{i+1})^⊥ / (2|K|)` with `(x, y)^⊥ = (-y, x)`.
    #[inline]
    pub fn new(p: [DVec2; 3]) -> P1Geom {
        let two_a = (p[1] - p[0]).perp_dot(p[2] - p[0]);
        let g = |i: usize| {
            let e = p[(i + 2) % 3] - p[(i + 1) % 3];
            DVec2::new(-e.y, e.x) / two_a
        };
        P1Geom {
            area: 0.5 * two_a,
            grad: [g(0), g(1), g(2)],
        }
    }

    /// Local stiffness `|K| ∇λ_i · A ∇λ_j` for a constant tensor `A` on the element.
    #[inline]
    #[allow(clippy::needless_range_loop)]
    pub fn stiffness(&self, a: Sym2) -> [[f64; 3]; 3] {
        let mut k = [[0.0; 3]; 3];
        for i in 0..3 {
            let ag = a.mul_vec(self.grad[i]);
            for j in i..3 {
                k[i][j] = self.area * ag.dot(self.grad[j]);
                k[j][i] = k[i][j];
            }
        }
        k
    }

    /// Local consistent mass `|K|/12 (1 + δ_ij)`.
    #[inline]
    pub fn mass(&self) -> [[f64; 3]; 3] {
        let d = self.area / 6.0;
        let o = self.area / 12.0;
        [[d, o, o], [o, d, o], [o, o, d]]
    }
}

/// Coefficient of a stiffness (diffusion) operator `-div(A ∇u)`.
#[derive(Clone, Copy)]
pub enum Coef<'a> {
    /// `A = c I` everywhere.
    Const(f64),
    /// `A = c_t I` on triangle slot `t`.
    PerElement(&'a [f64]),
    /// `A = A_t` (symmetric tensor) on triangle slot `t`.
    Tensor(&'a [Sym2]),
    /// `A = c(x) I`, integrated with the degree-5 rule on each triangle.
    Field(&'a (dyn Fn(DVec2) -> f64 + Sync)),
    /// `A = A(x)`, integrated with the degree-5 rule on each triangle.
    TensorField(&'a (dyn Fn(DVec2) -> Sym2 + Sync)),
}

/// The live triangles as `(slots, vertex triples)`.
pub fn live_elements(mesh: &Mesh2) -> (Vec<usize>, Vec<[u32; 3]>) {
    let slots: Vec<usize> = mesh.live_tris().collect();
    let elems = slots.iter().map(|&t| mesh.tris[t]).collect();
    (slots, elems)
}

/// Checks that every live triangle has positive area (needed by every P1 computation).
pub fn check_areas(mesh: &Mesh2) -> Result<()> {
    for t in mesh.live_tris() {
        let a = mesh.tri_area(t);
        if a.is_nan() || a <= 0.0 {
            return Err(if a == 0.0 {
                MeshDefect::DegenerateTriangle { tri: t }
            } else {
                MeshDefect::InvertedTriangle {
                    tri: t,
                    signed_area: a,
                }
            }
            .into());
        }
    }
    Ok(())
}

/// Maps barycentric coordinates to a point.
#[inline]
pub fn bary_point(p: &[DVec2; 3], l: &[f64; 3]) -> DVec2 {
    l[0] * p[0] + l[1] * p[1] + l[2] * p[2]
}

fn check_len(name: &str, len: usize, mesh: &Mesh2) -> Result<()> {
    if len != mesh.n_tris() {
        return Err(Error::InvalidField {
            name: name.into(),
            msg: format!(
                "{len} per-element values for {} triangle slots",
                mesh.n_tris()
            ),
        });
    }
    Ok(())
}

/// The tensor coefficient averaged over triangle slot `t` (exact for per-element data, degree-5
/// quadrature for fields).
fn element_tensor(coef: &Coef, mesh: &Mesh2, t: usize) -> Sym2 {
    match *coef {
        Coef::Const(c) => Sym2::scalar(c),
        Coef::PerElement(c) => Sym2::scalar(c[t]),
        Coef::Tensor(a) => a[t],
        Coef::Field(f) => {
            let p = mesh.tri_points(t);
            Sym2::scalar(tri_rule(5).mean(|l| f(bary_point(&p, l))))
        }
        Coef::TensorField(f) => {
            let p = mesh.tri_points(t);
            let r = tri_rule(5);
            let mut s = Sym2::default();
            for (l, w) in r.points.iter().zip(&r.weights) {
                let a = f(bary_point(&p, l));
                s.xx += w * a.xx;
                s.xy += w * a.xy;
                s.yy += w * a.yy;
            }
            s
        }
    }
}

/// Adds the stiffness matrix `∫ ∇φ_j · A ∇φ_i` to `a` (whose pattern must contain the P1
/// pattern of `mesh`, e.g. from [`Csr::p1_pattern`]).
pub fn add_stiffness(a: &mut Csr, mesh: &Mesh2, coef: &Coef) -> Result<()> {
    match coef {
        Coef::PerElement(c) => check_len("stiffness coefficient", c.len(), mesh)?,
        Coef::Tensor(c) => check_len("stiffness tensor", c.len(), mesh)?,
        _ => {}
    }
    check_areas(mesh)?;
    let (slots, elems) = live_elements(mesh);
    assemble_matrix(a, &elems, |e| {
        let t = slots[e];
        P1Geom::new(mesh.tri_points(t)).stiffness(element_tensor(coef, mesh, t))
    })
}

/// Adds `scale` times the consistent mass matrix `∫ φ_i φ_j` to `a`.
pub fn add_mass(a: &mut Csr, mesh: &Mesh2, scale: f64) -> Result<()> {
    check_areas(mesh)?;
    let (slots, elems) = live_elements(mesh);
    assemble_matrix(a, &elems, |e| {
        let mut m = P1Geom::new(mesh.tri_points(slots[e])).mass();
        m.iter_mut().flatten().for_each(|v| *v *= scale);
        m
    })
}

/// The P1 stiffness matrix for the coefficient `coef`.
pub fn stiffness(mesh: &Mesh2, coef: &Coef) -> Result<Csr> {
    let mut a = Csr::p1_pattern(mesh)?;
    add_stiffness(&mut a, mesh, coef)?;
    Ok(a)
}

/// The P1 consistent mass matrix.
pub fn mass(mesh: &Mesh2) -> Result<Csr> {
    let mut a = Csr::p1_pattern(mesh)?;
    add_mass(&mut a, mesh, 1.0)?;
    Ok(a)
}

/// The lumped (row-sum) mass: `|K|/3` from each triangle to each of its vertices.
pub fn lumped_mass(mesh: &Mesh2) -> Result<Vec<f64>> {
    check_areas(mesh)?;
    let (slots, elems) = live_elements(mesh);
    let mut m = vec![0.0; mesh.n_points()];
    assemble_vector(&mut m, &elems, |e| [mesh.tri_area(slots[e]) / 3.0; 3])?;
    Ok(m)
}

/// The load vector `∫ f φ_i`, with the degree-5 rule on each triangle.
pub fn load(mesh: &Mesh2, f: impl Fn(DVec2) -> f64 + Sync) -> Result<Vec<f64>> {
    check_areas(mesh)?;
    let (slots, elems) = live_elements(mesh);
    let mut b = vec![0.0; mesh.n_points()];
    let rule = tri_rule(5);
    assemble_vector(&mut b, &elems, |e| {
        let t = slots[e];
        let p = mesh.tri_points(t);
        let area = mesh.tri_area(t);
        let mut fe = [0.0; 3];
        for (l, w) in rule.points.iter().zip(&rule.weights) {
            let fx = w * area * f(bary_point(&p, l));
            for k in 0..3 {
                fe[k] += fx * l[k];
            }
        }
        fe
    })?;
    Ok(b)
}

/// The P1 interpolant of `f` (values at the vertices).
pub fn interpolate(mesh: &Mesh2, f: impl Fn(DVec2) -> f64) -> Vec<f64> {
    mesh.points.iter().map(|&p| f(p)).collect()
}

/// `‖u_h - u‖_{L2}` for the P1 field `uh`, with a degree-7 rule (at least `degree`) per element.
pub fn l2_error(mesh: &Mesh2, uh: &[f64], u: impl Fn(DVec2) -> f64) -> Result<f64> {
    check_p1_field(mesh.n_points(), uh, "P1 field")?;
    let rule = tri_rule(7);
    let s: f64 = mesh
        .live_tris()
        .map(|t| {
            let p = mesh.tri_points(t);
            let v = mesh.tris[t].map(|i| uh[i as usize]);
            mesh.tri_area(t)
                * rule.mean(|l| {
                    let e = l[0] * v[0] + l[1] * v[1] + l[2] * v[2] - u(bary_point(&p, l));
                    e * e
                })
        })
        .sum();
    Ok(s.sqrt())
}

/// `|u_h - u|_{H1} = ‖∇u_h - ∇u‖_{L2}` for the P1 field `uh`, degree-7 rule per element.
pub fn h1_seminorm_error(mesh: &Mesh2, uh: &[f64], grad_u: impl Fn(DVec2) -> DVec2) -> Result<f64> {
    check_p1_field(mesh.n_points(), uh, "P1 field")?;
    let rule = tri_rule(7);
    let s: f64 = mesh
        .live_tris()
        .map(|t| {
            let p = mesh.tri_points(t);
            let g = P1Geom::new(p);
            let gh: DVec2 = (0..3)
                .map(|k| uh[mesh.tris[t][k] as usize] * g.grad[k])
                .sum();
            g.area * rule.mean(|l| (gh - grad_u(bary_point(&p, l))).length_squared())
        })
        .sum();
    Ok(s.sqrt())
}

/// The gradient of the P1 field `u` on each triangle slot (zero on tombstones).
pub fn gradients(mesh: &Mesh2, u: &[f64]) -> Result<Vec<DVec2>> {
    check_p1_field(mesh.n_points(), u, "P1 field")?;
    Ok((0..mesh.n_tris())
        .map(|t| {
            if mesh.is_deleted(t) {
                return DVec2::ZERO;
            }
            let g = P1Geom::new(mesh.tri_points(t));
            (0..3)
                .map(|k| u[mesh.tris[t][k] as usize] * g.grad[k])
                .sum()
        })
        .collect())
}
