//! The oblique projection of a node on the zero level along the quasi-normal field, 003 §5 and
//! §6.3: `x^{k+1} = z - α n_h(x^k)` (6.11) with `α` a zero of `φ_h(z - α n_h(x^k))` (6.9),
//! found by the approximate Newton line search (6.10) and then `d_h(z) = <z - p_h(z), n_h(p_h(z))>`.
//!
//! Robustness additions the paper leaves open (§6.3 last paragraph, §9):
//! - damped Newton: each step is limited to the local mesh size `h`, so iterates stay near
//!   `Ω_{Γ_h}`;
//! - starting value `x^0 = z - α n_h(z)` as in the paper, and every line search warm-starts from
//!   the previous `α`;
//! - when Newton fails (leaves the mesh, a non-positive slope, no convergence, or a root farther
//!   than `2h`), the root is bracketed by sampling `α` on `[-3h, 3h]` in steps of `h/8` (smallest
//!   `|α|` first, as (5.1) asks) and refined by the Illinois method;
//! - robust starting value: the first-order guess `φ_h(z) / |G_h φ_h(z)|` is clamped to `[-h, h]`
//!   (a node of a cut cell of diameter `h` is within `h` of `Γ_h`; where `G_h φ_h` nearly
//!   vanishes — on the medial axis of `Γ` — the unclamped guess is unbounded);
//! - a result farther than `2h` from `z` (the iteration converged to another sheet of `Γ_h`, or
//!   `n_h` is meaningless because `z` lies on the medial axis) is rejected: the node gets the
//!   first-order value `φ_h(z) / |∇φ_h(z)|` of its cut cell, clamped to `[-h, h]`, and counts as
//!   not converged.

use super::ppr::Recovery;
use super::simplices::Simplices;
use crate::geom::DVec3;

/// Largest accepted `|α|` and `|d_h(z)|`, in units of the home cell's diameter `h`.
const ROOT_LIMIT: f64 = 2.0;

/// Iteration controls.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ObliqueParams {
    /// Relative tolerance (times `h`) on `|Δα|` and on `|x^{k+1} - x^k|`.
    pub tol: f64,
    pub max_outer: usize,
    pub max_newton: usize,
    pub damped: bool,
}

/// Outcome for one node.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Projection {
    pub d: f64,
    pub outer_iterations: usize,
    pub converged: bool,
    pub bracketed: bool,
}

struct Ctx<'a> {
    sx: &'a Simplices,
    phi: &'a [f64],
    rec: &'a Recovery<'a>,
}

impl Ctx<'_> {
    /// `φ_h(x)`, `(G_h φ_h)(x)` and the containing cell, or `None` outside the mesh.
    fn probe(&self, x: &DVec3, hint: &mut u32) -> Option<(f64, DVec3)> {
        let (c, lam) = self.sx.locate(x, *hint)?;
        *hint = c;
        Some((
            self.sx.eval(c as usize, &lam, self.phi),
            self.rec.at(c as usize, &lam),
        ))
    }

    fn normal(&self, x: &DVec3, hint: &mut u32) -> Option<DVec3> {
        let (_, g) = self.probe(x, hint)?;
        let l = g.length();
        (l > 0.0 && l.is_finite()).then(|| g / l)
    }

    fn phi_at(&self, x: &DVec3, hint: &mut u32) -> Option<f64> {
        let (c, lam) = self.sx.locate(x, *hint)?;
        *hint = c;
        Some(self.sx.eval(c as usize, &lam, self.phi))
    }

    /// Damped approximate Newton (6.10) for `φ_h(z - α n) = 0` from `alpha`.
    fn newton(
        &self,
        z: &DVec3,
        n: &DVec3,
        mut alpha: f64,
        h: f64,
        p: &ObliqueParams,
        hint: &mut u32,
    ) -> Option<f64> {
        for _ in 0..p.max_newton {
            let y = *z + *n * -alpha;
            let (f, g) = self.probe(&y, hint)?;
            if f == 0.0 {
                return Some(alpha);
            }
            let slope = g.dot(*n);
            if slope.is_nan() || slope <= 0.0 {
                return None;
            }
            let mut step = f / slope;
            if p.damped {
                step = step.clamp(-h, h);
            }
            alpha += step;
            if step.abs() <= p.tol * h {
                return Some(alpha);
            }
        }
        None
    }

    /// Bracketing fallback: the zero of `α ↦ φ_h(z - α n)` of smallest `|α|` in `[-3h, 3h]`.
    fn bracket(
        &self,
        z: &DVec3,
        n: &DVec3,
        h: f64,
        p: &ObliqueParams,
        hint: &mut u32,
    ) -> Option<f64> {
        let step = h / 8.0;
        let f = |a: f64, hint: &mut u32| self.phi_at(&(*z + *n * -a), hint);
        let f0 = f(0.0, hint)?;
        if f0 == 0.0 {
            return Some(0.0);
        }
        for j in 1..=24 {
            for s in [1.0, -1.0] {
                let (a0, a1) = (s * (j - 1) as f64 * step, s * j as f64 * step);
                let (Some(fa), Some(fb)) = (f(a0, hint), f(a1, hint)) else {
                    continue;
                };
                if fb == 0.0 {
                    return Some(a1);
                }
                if fa * fb < 0.0 {
                    return self.illinois(a0, fa, a1, fb, &f, p.tol * h, hint);
                }
            }
        }
        None
    }

    #[allow(clippy::too_many_arguments)]
    fn illinois(
        &self,
        mut a: f64,
        mut fa: f64,
        mut b: f64,
        mut fb: f64,
        f: &impl Fn(f64, &mut u32) -> Option<f64>,
        tol: f64,
        hint: &mut u32,
    ) -> Option<f64> {
        for _ in 0..200 {
            let c = (a * fb - b * fa) / (fb - fa);
            let fc = f(c, hint)?;
            if fc == 0.0 {
                return Some(c);
            }
            if fc * fb < 0.0 {
                a = b;
                fa = fb;
            } else {
                fa *= 0.5;
            }
            b = c;
            fb = fc;
            if (b - a).abs() <= tol {
                return Some(b);
            }
        }
        Some(b)
    }

    /// Line search: damped Newton, bracketing if it fails. Returns `(α, bracketed)`.
    fn line(
        &self,
        z: &DVec3,
        n: &DVec3,
        alpha: f64,
        h: f64,
        p: &ObliqueParams,
        hint: &mut u32,
    ) -> Option<(f64, bool)> {
        if let Some(a) = self.newton(z, n, alpha, h, p, hint) {
            if a.abs() <= ROOT_LIMIT * h {
                return Some((a, false));
            }
        }
        self.bracket(z, n, h, p, hint).map(|a| (a, true))
    }
}

/// Oblique projection of node `z` (value `phi_z`, lying in cell `cell` of size `h`) and the
/// resulting approximate signed distance `d_h(z)`, 003 (6.9)–(6.11).
#[allow(clippy::too_many_arguments)]
pub(crate) fn project(
    sx: &Simplices,
    phi: &[f64],
    rec: &Recovery,
    z: &DVec3,
    phi_z: f64,
    cell: u32,
    h: f64,
    p: &ObliqueParams,
) -> Projection {
    if phi_z == 0.0 {
        return Projection {
            d: 0.0,
            outer_iterations: 0,
            converged: true,
            bracketed: false,
        };
    }
    let ctx = Ctx { sx, phi, rec };
    let mut hint = cell;
    let mut out = Projection::default();
    // A first-order guess, used when everything else fails: φ / |G_h φ_h| at z.
    let fallback = cell_guess(sx, phi, cell, z, phi_z, h);
    let g0 = rec.at_node_or_cell(sx, cell, z);
    let mut guess = phi_z / g0.length();
    if !guess.is_finite() || guess.abs() > h {
        guess = fallback;
    }
    out.d = fallback;
    let Some(n0) = ctx.normal(z, &mut hint) else {
        return out;
    };
    // x^0 = z - α n_h(z) with φ_h(x^0) = 0 (003 §6.3).
    let Some((mut alpha, br)) = ctx.line(z, &n0, guess, h, p, &mut hint) else {
        return out;
    };
    out.bracketed |= br;
    let mut x = *z + n0 * -alpha;
    for k in 0..p.max_outer {
        out.outer_iterations = k + 1;
        let Some(nk) = ctx.normal(&x, &mut hint) else {
            return out;
        };
        let Some((a, br)) = ctx.line(z, &nk, alpha, h, p, &mut hint) else {
            return out;
        };
        out.bracketed |= br;
        alpha = a;
        let xn = *z + nk * -alpha;
        let moved = (xn - x).length();
        x = xn;
        if moved <= p.tol * h {
            out.converged = true;
            break;
        }
    }
    // d_h(z) = <z - p_h(z), n_h(p_h(z))>.
    if let Some(np) = ctx.normal(&x, &mut hint) {
        out.d = (*z - x).dot(np);
    } else {
        out.d = alpha;
        out.converged = false;
    }
    if !out.d.is_finite() || out.d.abs() > ROOT_LIMIT * h {
        out.d = fallback;
        out.converged = false;
    }
    out
}

/// The first-order value `φ_h(z) / |∇φ_h(z)|` with the gradient of `φ_h` in the cut cell `cell`,
/// clamped to `[-h, h]` (also when the gradient vanishes).
fn cell_guess(sx: &Simplices, phi: &[f64], cell: u32, z: &DVec3, phi_z: f64, h: f64) -> f64 {
    let lam = sx.bary(cell as usize, z);
    let g = sx.grad_in(cell as usize, &lam, phi).length();
    let d = phi_z / g;
    if d.is_finite() {
        d.clamp(-h, h)
    } else {
        h.copysign(phi_z)
    }
}

impl Recovery<'_> {
    /// `G_h φ_h` at a point `z` of cell `cell` (used for the first-order guess).
    fn at_node_or_cell(&self, sx: &Simplices, cell: u32, z: &DVec3) -> DVec3 {
        let lam = sx.bary(cell as usize, z);
        self.at(cell as usize, &lam)
    }
}
