//! The boundary of the `j = 2` band and the spatial error of the transparent heat problem
//! (000 §2.3, Table 2.1): the sphere `r = 1/3`, the second spherical harmonic, `t = 0.01`, BDF2
//! (first step Crank–Nicolson), with one ingredient of the transparent vector `Γ` of 000 (2.9) or
//! of the boundary layer replaced at a time:
//!
//! - `transparent`: the scheme of `anisomesh dtgrid heat --time bdf2`;
//! - `extrapolated`: the boundary rows completed by ghost values outside the band
//!   (`anisomesh dtgrid heat --bc extrapolated --time bdf2`, `backends::dtgrid::ghost`);
//! - `extrapolated-exact-phi`: the same with the exact `Φ` on the ghost nodes;
//! - `ghost-exact`: the completed rows with the exact solution on the ghost nodes (lagged);
//! - `exact-flux`: `Γ` from the exact gradient of the solution at the face Gauss points;
//! - `recovered`: `Γ` from nodal central differences (second-order one-sided at the band's edge)
//!   interpolated to the face Gauss points;
//! - `exact-normal`: `Γ` with `A = |∇φ| P[φ]` from the exact normal instead of the Q1 `∇Φ`;
//! - `gauss3`: `Γ` with 3 × 3 Gauss points per face;
//! - `exact-boundary`: no `Γ`; the exact solution is held on the boundary layer (Dirichlet);
//! - `extension`: no `Γ`; the boundary layer takes the value of `2Uᵏ − Uᵏ⁻¹` at its closest
//!   point on the sphere (Dirichlet);
//! - `consistent-mass`: the transparent scheme with the consistent mass
//!   `∫ I_h⁰(|∇Φ|) Θ_i Θ_j` instead of the lumped one of 000 §2.1.
//!
//! `cargo run --release --example dtgrid_heat_boundary -- VARIANT TAU N...`
//! (e.g. `exact-boundary 2e-5 33 65`); prints the error on the discrete surface, its order and
//! the largest nodal errors on the interior and on the boundary nodes. Without arguments it
//! compares `transparent` and `exact-boundary` at `τ = 1e-4` on 17³ and 33³ (seconds).

use anisomesh::backends::dtgrid::fem::{assemble, elements, transparent_vector, Element, Weight};
use anisomesh::backends::dtgrid::ghost::GhostRows;
use anisomesh::backends::dtgrid::lattice::{
    band_around, crossing_cells_of_fn, Lattice, NarrowBand, C3,
};
use anisomesh::backends::dtgrid::scheme::{
    solve_all, solve_dirichlet, solve_general, system_matrix,
};
use anisomesh::backends::dtgrid::surface::{surface_integral, zero_level};
use anisomesh::backends::dtgrid::{Band, SortedBand};
use anisomesh::fem::q1::{shape, shape_grad};
use anisomesh::geom::DVec3;
use anisomesh::{Error, Result};

const R: f64 = 1.0 / 3.0;
const T_END: f64 = 0.01;

/// The variants (see the module comment).
const VARIANTS: [&str; 11] = [
    "extrapolated",
    "extrapolated-exact-phi",
    "ghost-exact",
    "transparent",
    "exact-flux",
    "recovered",
    "exact-normal",
    "gauss3",
    "exact-boundary",
    "extension",
    "consistent-mass",
];

fn y(p: DVec3) -> f64 {
    (p.z / p.length()).powi(2) - 1.0 / 3.0
}

/// The band's exact solution: the level set `|x| = r` decays as `e^{−6t/r²}`.
fn exact(p: DVec3, t: f64) -> f64 {
    (-6.0 * t / p.length_squared()).exp() * y(p)
}

fn exact_grad(p: DVec3, t: f64) -> DVec3 {
    let r = p.length();
    let e = (-6.0 * t / (r * r)).exp();
    let grad_zr = DVec3::new(0.0, 0.0, 1.0 / r) - p * (p.z / (r * r * r));
    grad_zr * (2.0 * p.z / r * e) + p / r * (e * y(p) * 12.0 * t / (r * r * r))
}

/// `|g| P` for the gradient `g` of the level-set function (000 §2.1).
fn tensor(g: DVec3) -> [[f64; 3]; 3] {
    let (len, g) = (g.length(), g.to_array());
    std::array::from_fn(|r| std::array::from_fn(|s| f64::from(r == s) * len - g[r] * g[s] / len))
}

/// The gradient of the Q1 function with corner values `v` at reference point `xi`.
fn q1_grad(v: &[f64; 8], xi: &[f64; 3], h: f64) -> DVec3 {
    (0..8).fold(DVec3::ZERO, |g, k| {
        g + DVec3::from_array(shape_grad(3, k, xi)) * (v[k] / h)
    })
}

/// The gradient of `U` at a face point: element corners, reference point, position.
type FaceGradient<'a> = dyn Fn(&[u32; 8], &[f64; 3], DVec3) -> DVec3 + 'a;

/// `Γ_j = ∫_{∂Ω_n} A ∇U · ν Θ_j da` over the faces no other element shares, with `A` from `Φ`
/// (or the exact normal) and `∇U` from `grad(element, ξ, x)`, `gauss` points per face side.
fn gamma(
    lat: &Lattice,
    elems: &[Element],
    phi: &[f64],
    exact_normal: bool,
    gauss: usize,
    grad: &FaceGradient,
) -> Vec<f64> {
    let h = lat.h;
    let (pts, wts) = if gauss == 2 {
        let g = 0.5 / 3f64.sqrt();
        (vec![0.5 - g, 0.5 + g], vec![0.5, 0.5])
    } else {
        let g = 0.5 * 0.6f64.sqrt();
        (
            vec![0.5 - g, 0.5, 0.5 + g],
            vec![5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0],
        )
    };
    let is_element = |c: C3| elems.binary_search_by(|e| e.0.cmp(&c)).is_ok();
    let mut out = vec![0.0; phi.len()];
    for (c, idx) in elems {
        let v: [f64; 8] = std::array::from_fn(|k| phi[idx[k] as usize]);
        for (axis, side) in (0..3).flat_map(|a| [(a, 0usize), (a, 1)]) {
            let mut nb = *c;
            nb[axis] += if side == 1 { 1 } else { -1 };
            if is_element(nb) {
                continue;
            }
            let sign = if side == 1 { 1.0 } else { -1.0 };
            for (s, ws) in pts.iter().zip(&wts) {
                for (t, wt) in pts.iter().zip(&wts) {
                    let mut xi = [0.0; 3];
                    xi[axis] = side as f64;
                    xi[(axis + 1) % 3] = *s;
                    xi[(axis + 2) % 3] = *t;
                    let x = lat.pos(*c) + DVec3::from_array(xi) * h;
                    let a = tensor(if exact_normal {
                        x / x.length()
                    } else {
                        q1_grad(&v, &xi, h)
                    });
                    let flux = sign * DVec3::from_array(a[axis]).dot(grad(idx, &xi, x));
                    for k in 0..8 {
                        out[idx[k] as usize] += ws * wt * h * h * flux * shape(3, k, &xi);
                    }
                }
            }
        }
    }
    out
}

/// Nodal gradients: central differences, second-order one-sided where a neighbour is missing.
fn nodal_grad(lat: &Lattice, band: &SortedBand<C3>, coords: &[C3], u: &[f64]) -> Vec<DVec3> {
    let h = lat.h;
    coords
        .iter()
        .enumerate()
        .map(|(i, &c)| {
            let d: [f64; 3] = std::array::from_fn(|a| {
                let at = |k: i32| {
                    let mut cc = c;
                    cc[a] += k;
                    band.index(cc).map(|j| u[j])
                };
                match (at(-1), at(1), at(-2), at(2)) {
                    (Some(m), Some(p), _, _) => (p - m) / (2.0 * h),
                    (None, Some(p), _, Some(p2)) => (-3.0 * u[i] + 4.0 * p - p2) / (2.0 * h),
                    (Some(m), None, Some(m2), _) => (3.0 * u[i] - 4.0 * m + m2) / (2.0 * h),
                    (None, Some(p), _, None) => (p - u[i]) / h,
                    (Some(m), None, None, _) => (u[i] - m) / h,
                    _ => 0.0,
                }
            });
            DVec3::from_array(d)
        })
        .collect()
}

/// The Q1 interpolant of the band field `u` at `x` (all 8 corners must be band nodes).
fn interpolate(lat: &Lattice, band: &SortedBand<C3>, u: &[f64], x: DVec3) -> Result<f64> {
    let rel = (x - DVec3::splat(lat.lo)) / lat.h;
    let c = [
        rel.x.floor() as i32,
        rel.y.floor() as i32,
        rel.z.floor() as i32,
    ];
    let xi = [
        rel.x - c[0] as f64,
        rel.y - c[1] as f64,
        rel.z - c[2] as f64,
    ];
    (0..8).try_fold(0.0, |s, k| {
        let corner = [
            c[0] + (k & 1) as i32,
            c[1] + ((k >> 1) & 1) as i32,
            c[2] + (k >> 2) as i32,
        ];
        let i = band
            .index(corner)
            .ok_or_else(|| Error::InvalidInput(format!("{x:?} is not in a cell of the band")))?;
        Ok(s + shape(3, k, &xi) * u[i])
    })
}

/// The error `‖U − u‖_{L²(M_h)}` at `t = 0.01` of `variant` on `n³`, `j = 2`, step about `tau`,
/// and the largest nodal errors on the interior and on the boundary nodes.
fn run(variant: &str, n: usize, tau: f64) -> Result<(f64, f64, f64)> {
    let lat = Lattice::unit(n)?;
    let f = |p: DVec3| p.length() - R;
    let nb: NarrowBand<SortedBand<C3>> = band_around(&lat, &crossing_cells_of_fn(&lat, &f)?, 2)?;
    let coords: Vec<C3> = nb.band.coords().collect();
    let nn = coords.len();
    let phi: Vec<f64> = coords.iter().map(|&c| f(lat.pos(c))).collect();
    let el = elements(&nb);
    let mut m = assemble(&lat, &el, nn, &phi, Weight::Heat)?;
    let h = lat.h;
    let ghost = if variant.starts_with("extrapolated") || variant == "ghost-exact" {
        let exact_phi = variant == "extrapolated-exact-phi";
        let g = GhostRows::new_with(&lat, &nb, &phi, Weight::Heat, exact_phi.then_some(&f))?;
        m.mass.iter_mut().zip(&g.mass).for_each(|(m, g)| *m += g);
        if variant != "ghost-exact" {
            m.stiff = g.complete(&m.stiff)?;
        }
        Some(g)
    } else {
        None
    };
    // The consistent mass on the stiffness pattern (the same element couplings).
    let mut mc = m.stiff.clone();
    mc.clear_values();
    for (_, idx) in &el {
        let v: [f64; 8] = std::array::from_fn(|k| phi[idx[k] as usize]);
        let w = q1_grad(&v, &[0.5; 3], h).length() * h * h * h;
        for (a, &ia) in idx.iter().enumerate() {
            for (b, &ib) in idx.iter().enumerate() {
                let f: f64 = (0..3)
                    .map(|k| {
                        if (a ^ b) >> k & 1 == 0 {
                            1.0 / 3.0
                        } else {
                            1.0 / 6.0
                        }
                    })
                    .product();
                mc.add(ia as usize, ib as usize, w * f)?;
            }
        }
    }
    let consistent = variant == "consistent-mass";
    let mass_mul = |v: &[f64]| -> Vec<f64> {
        if consistent {
            mc.mul(v)
        } else {
            v.iter().zip(&m.mass).map(|(v, m)| v * m).collect()
        }
    };
    let system = |t: f64| -> Result<anisomesh::fem::Csr> {
        if consistent {
            let mut a = m.stiff.clone();
            a.val
                .iter_mut()
                .zip(&mc.val)
                .for_each(|(a, c)| *a = t * *a + c);
            Ok(a)
        } else {
            system_matrix(&m, t)
        }
    };
    let dirichlet = variant == "exact-boundary" || variant == "extension";
    let fixed: Vec<bool> = nb.interior.iter().map(|i| !i).collect();
    let flux = |v: &[f64], t: f64| -> Vec<f64> {
        let discrete = |idx: &[u32; 8], xi: &[f64; 3], _: DVec3| {
            q1_grad(&std::array::from_fn(|k| v[idx[k] as usize]), xi, h)
        };
        match variant {
            "exact-flux" => gamma(&lat, &el, &phi, false, 2, &|_, _, x| exact_grad(x, t)),
            "recovered" => {
                let g = nodal_grad(&lat, &nb.band, &coords, v);
                let at = |idx: &[u32; 8], xi: &[f64; 3], _: DVec3| {
                    (0..8).fold(DVec3::ZERO, |s, k| s + g[idx[k] as usize] * shape(3, k, xi))
                };
                gamma(&lat, &el, &phi, false, 2, &at)
            }
            "exact-normal" => gamma(&lat, &el, &phi, true, 2, &discrete),
            "gauss3" => gamma(&lat, &el, &phi, false, 3, &discrete),
            "ghost-exact" => ghost.as_ref().map_or(vec![0.0; nn], |g| {
                let ex: Vec<f64> = g
                    .ghost_nodes()
                    .iter()
                    .map(|&c| exact(lat.pos(c), t))
                    .collect();
                g.vector_with(v, &ex)
            }),
            _ if dirichlet || ghost.is_some() => vec![0.0; nn],
            _ => transparent_vector(&lat, &el, nn, &phi, v, Weight::Heat),
        }
    };
    // The boundary layer's values at time `t` for the Dirichlet variants, from the guess `g`.
    let boundary = |u: &mut [f64], g: &[f64], t: f64| -> Result<()> {
        for (i, &c) in coords.iter().enumerate().filter(|(i, _)| fixed[*i]) {
            let x = lat.pos(c);
            u[i] = if variant == "exact-boundary" {
                exact(x, t)
            } else {
                interpolate(&lat, &nb.band, g, x * (R / x.length()))?
            };
        }
        Ok(())
    };
    let solve = |a, b: &[f64], u: &mut [f64], g: &[f64], t: f64| -> Result<usize> {
        if dirichlet {
            boundary(u, g, t)?;
            solve_dirichlet(a, b, &fixed, u)
        } else if variant.starts_with("extrapolated") {
            solve_general(a, b, u)
        } else {
            solve_all(a, b, u)
        }
    };
    let steps = (T_END / tau - 1e-9).ceil().max(2.0) as usize;
    let tau = T_END / steps as f64;
    let mut u: Vec<f64> = coords.iter().map(|&c| y(lat.pos(c))).collect();
    let mut prev = u.clone();
    // Crank–Nicolson (the exact flux at both ends), then BDF2 with Γ[2Uᵏ − Uᵏ⁻¹].
    let a = system(0.5 * tau)?;
    let (lu, mu) = (m.stiff.mul(&u), mass_mul(&u));
    let (g0, g1) = (flux(&u, 0.0), flux(&u, tau));
    let b: Vec<f64> = (0..nn)
        .map(|i| mu[i] - 0.5 * tau * (lu[i] - g0[i] - g1[i]))
        .collect();
    solve(&a, &b, &mut u, &prev, tau)?;
    let t2 = 2.0 * tau / 3.0;
    let a = system(t2)?;
    for k in 1..steps {
        let guess: Vec<f64> = (0..nn).map(|i| 2.0 * u[i] - prev[i]).collect();
        let g = flux(&guess, (k + 1) as f64 * tau);
        let mu = mass_mul(
            &(0..nn)
                .map(|i| (4.0 * u[i] - prev[i]) / 3.0)
                .collect::<Vec<_>>(),
        );
        let b: Vec<f64> = (0..nn).map(|i| mu[i] + t2 * g[i]).collect();
        prev.copy_from_slice(&u);
        u.copy_from_slice(&guess);
        solve(&a, &b, &mut u, &guess, (k + 1) as f64 * tau)?;
    }
    let z = zero_level(&lat, &nb.band, &phi);
    let decay = (-6.0 * T_END / (R * R)).exp();
    let e2 = surface_integral(&lat, &nb.band, &z, &u, |x, ux| (ux - decay * y(x)).powi(2));
    let (mut interior, mut edge) = (0.0f64, 0.0f64);
    for (i, &c) in coords.iter().enumerate() {
        let e = (u[i] - exact(lat.pos(c), T_END)).abs();
        let m = if fixed[i] { &mut edge } else { &mut interior };
        *m = m.max(e);
    }
    Ok((e2.sqrt(), interior, edge))
}

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.is_empty() {
        for variant in ["transparent", "exact-boundary"] {
            compare(variant, 1e-4, &[17, 33])?;
        }
        return Ok(());
    }
    let usage = || {
        Error::InvalidInput(format!(
            "usage: dtgrid_heat_boundary [VARIANT TAU N...] (VARIANT one of {VARIANTS:?})"
        ))
    };
    let variant = args
        .first()
        .filter(|v| VARIANTS.contains(&v.as_str()))
        .ok_or_else(usage)?;
    let tau: f64 = args.get(1).and_then(|t| t.parse().ok()).ok_or_else(usage)?;
    let ns: Vec<usize> = args[2..]
        .iter()
        .map(|s| s.parse().map_err(|_| usage()))
        .collect::<Result<_>>()?;
    compare(variant, tau, &ns)
}

/// Runs `variant` at time step `tau` on the grids `ns` and prints each error with its order.
fn compare(variant: &str, tau: f64, ns: &[usize]) -> Result<()> {
    let mut last: Option<(usize, f64)> = None;
    for &n in ns {
        let (e, interior, edge) = run(variant, n, tau)?;
        let order = last.map_or(String::new(), |(n0, e0)| {
            format!(
                "  order {:.2}",
                (e0 / e).ln() / ((n - 1) as f64 / (n0 - 1) as f64).ln()
            )
        });
        println!(
            "{variant:<14} j = 2  n = {n:4}  error {e:.4e}{order}  \
             (largest nodal error: interior {interior:.2e}, boundary {edge:.2e})"
        );
        last = Some((n, e));
    }
    Ok(())
}
