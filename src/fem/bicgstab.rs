//! BiCGStab (van der Vorst 1992) with the diagonal (Jacobi) preconditioner, for sparse systems
//! that are not symmetric; beside CG ([`super::solve`]) in the one finite element layer.

use super::csr::{dot, norm, Csr};
use super::solve::{CgOptions, CgReport};
use crate::error::{Error, Result};

/// Solves `A x = b` by right-preconditioned BiCGStab from the guess in `x`, preconditioned by
/// the diagonal of `A` (`opts.precond` is ignored). The report's residual is relative to `‖b‖`;
/// a breakdown (`ρ = 0`, `ω = 0` or `r̂₀ · v = 0`) ends the iteration unconverged.
/// Errors: [`Error::InvalidInput`] when the sizes of `a`, `b` and `x` differ.
pub fn bicgstab(a: &Csr, b: &[f64], x: &mut [f64], opts: &CgOptions) -> Result<CgReport> {
    if b.len() != a.n || x.len() != a.n {
        return Err(Error::InvalidInput(format!(
            "BiCGStab: matrix has {} rows, rhs {}, solution {}",
            a.n,
            b.len(),
            x.len()
        )));
    }
    let o = opts;
    let n = b.len();
    let d = a.diagonal();
    let precond = |v: &[f64], out: &mut [f64]| {
        out.iter_mut()
            .zip(v)
            .zip(&d)
            .for_each(|((o, v), d)| *o = v / d)
    };
    let mut r = vec![0.0; n];
    a.matvec(x, &mut r);
    r.iter_mut().zip(b).for_each(|(r, b)| *r = b - *r);
    let r0 = r.clone();
    let tol = (o.rtol * norm(b)).max(o.atol);
    let (mut rho, mut alpha, mut omega) = (1.0, 1.0, 1.0);
    let (mut p, mut v) = (vec![0.0; n], vec![0.0; n]);
    let (mut ph, mut s, mut sh, mut t) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut rep = CgReport {
        residual: norm(&r),
        ..Default::default()
    };
    while rep.iterations < o.max_iter {
        if rep.residual <= tol {
            rep.converged = true;
            break;
        }
        rep.iterations += 1;
        let rho_new = dot(&r0, &r);
        if rho_new == 0.0 || omega == 0.0 {
            break;
        }
        let beta = rho_new / rho * (alpha / omega);
        rho = rho_new;
        p.iter_mut()
            .zip(&r)
            .zip(&v)
            .for_each(|((p, r), v)| *p = r + beta * (*p - omega * v));
        precond(&p, &mut ph);
        a.matvec(&ph, &mut v);
        let r0v = dot(&r0, &v);
        if r0v == 0.0 {
            break;
        }
        alpha = rho / r0v;
        s.iter_mut()
            .zip(&r)
            .zip(&v)
            .for_each(|((s, r), v)| *s = r - alpha * v);
        if norm(&s) <= tol {
            x.iter_mut().zip(&ph).for_each(|(x, p)| *x += alpha * p);
            rep.residual = norm(&s);
            continue;
        }
        precond(&s, &mut sh);
        a.matvec(&sh, &mut t);
        let tt = dot(&t, &t);
        omega = if tt > 0.0 { dot(&t, &s) / tt } else { 0.0 };
        x.iter_mut()
            .zip(ph.iter().zip(&sh))
            .for_each(|(x, (p, s))| *x += alpha * p + omega * s);
        r.iter_mut()
            .zip(s.iter().zip(&t))
            .for_each(|(r, (s, t))| *r = s - omega * t);
        rep.residual = norm(&r);
    }
    rep.residual /= norm(b).max(f64::MIN_POSITIVE);
    Ok(rep)
}
