//! The volume drift of repeated redistancing (003 §8, Fig. 8.4): the sphere of radius 0.25
//! redistanced `n` times, and the volume inside the zero level of a P1 or P2 field on tetrahedra.

use indicatif::ProgressBar;

use super::torus::{nodes3, refined_box};
use anisomesh::error::Result;
use anisomesh::fem::lagrange::{self, P2Dofs};
use anisomesh::geom::DVec3;
use anisomesh::levelset::redistance::{
    redistance_geometric_cells, redistance_ppr_cells, PprOptions,
};
use anisomesh::mesh3::Mesh3;

/// Fraction of a simplex where the linear function with vertex values `u` is negative: the
/// divided-difference formula `Σ_{u_i < 0} (-u_i)^d / Π_{j ≠ i} (u_j - u_i)`, with the one-vertex
/// cases in product form for stability.
fn negative_fraction(u: &[f64; 4]) -> f64 {
    let neg = u.iter().filter(|&&v| v < 0.0).count();
    match neg {
        0 => 0.0,
        4 => 1.0,
        1 | 3 => {
            let lone_neg = neg == 1;
            let i = (0..4).find(|&i| (u[i] < 0.0) == lone_neg).unwrap_or(0);
            let p: f64 = (0..4)
                .filter(|&j| j != i)
                .map(|j| u[i] / (u[i] - u[j]))
                .product();
            if lone_neg {
                p
            } else {
                1.0 - p
            }
        }
        _ => {
            // Two and two: perturb coincident values slightly (the formula divides by u_j - u_i).
            let mut w = *u;
            let scale = w.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
            for i in 0..4 {
                for j in 0..i {
                    if (w[i] - w[j]).abs() < 1e-9 * scale {
                        w[i] += 2e-9 * scale * (i as f64);
                    }
                }
            }
            (0..4)
                .filter(|&i| w[i] < 0.0)
                .map(|i| {
                    (-w[i]).powi(3)
                        / (0..4)
                            .filter(|&j| j != i)
                            .map(|j| w[j] - w[i])
                            .product::<f64>()
                })
                .sum()
        }
    }
}

/// Volume of `{f < 0}` for the P1 (exact) or P2 (64 sub-tetrahedra per cut tetrahedron) field
/// `f` on `m`.
fn negative_volume(m: &Mesh3, f: &[f64], k: usize) -> f64 {
    let dofs = (k == 2).then(|| P2Dofs::for_tets(&m.tets, m.n_points()));
    let mut vol = 0.0;
    for t in 0..m.n_tets() {
        let v = m.tet_volume(t);
        let nodes: Vec<u32> = match &dofs {
            Some(d) => d.cell(t).to_vec(),
            None => m.tets[t].to_vec(),
        };
        let vals: Vec<f64> = nodes.iter().map(|&n| f[n as usize]).collect();
        if vals.iter().all(|&x| x < 0.0) && k == 1 {
            vol += v;
            continue;
        }
        if vals.iter().all(|&x| x > 0.0) {
            continue;
        }
        if k == 1 {
            vol += v * negative_fraction(&[vals[0], vals[1], vals[2], vals[3]]);
            continue;
        }
        if vals.iter().all(|&x| x < 0.0) {
            vol += v;
            continue;
        }
        // Two levels of 8-subdivision in barycentric coordinates; P2 evaluated at sub-vertices.
        let eval = |l: [f64; 4]| -> f64 {
            let s = lagrange::p2_tet_values(l);
            s.iter().zip(&vals).map(|(a, b)| a * b).sum()
        };
        let mut subs: Vec<[[f64; 4]; 4]> = vec![[
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ]];
        for _ in 0..2 {
            subs = subs.iter().flat_map(split8).collect();
        }
        let frac: f64 = subs
            .iter()
            .map(|s| negative_fraction(&s.map(eval)) / 64.0)
            .sum();
        vol += v * frac;
    }
    vol
}

/// The 8 children of a tetrahedron given by 4 barycentric points (all of volume 1/8).
fn split8(s: &[[f64; 4]; 4]) -> [[[f64; 4]; 4]; 8] {
    let m = |i: usize, j: usize| -> [f64; 4] { std::array::from_fn(|k| 0.5 * (s[i][k] + s[j][k])) };
    let (m01, m02, m03, m12, m13, m23) = (m(0, 1), m(0, 2), m(0, 3), m(1, 2), m(1, 3), m(2, 3));
    [
        [s[0], m01, m02, m03],
        [m01, s[1], m12, m13],
        [m02, m12, s[2], m23],
        [m03, m13, m23, s[3]],
        [m02, m13, m01, m12],
        [m02, m13, m12, m23],
        [m02, m13, m23, m03],
        [m02, m13, m03, m01],
    ]
}

/// The sphere test of 003 §8 (Fig. 8.4): relative volume errors `e^n_Vol = |V^n - V| / V`
/// after `n = 0..=reps` redistancings.
pub fn sphere_drift(
    level: u32,
    k: usize,
    reps: usize,
    bar: Option<&ProgressBar>,
) -> Result<Vec<f64>> {
    Ok(sphere_drift_signed(level, k, reps, bar)?
        .into_iter()
        .map(f64::abs)
        .collect())
}

/// As [`sphere_drift`] but signed, `(V^n - V) / V` (negative: the zero level lies inside the
/// sphere). `d̃^0_h = I_h d^{ex}` on the level-`ℓ` mesh refined near the sphere of radius 0.25,
/// then `d̃^n_h` = PPR redistancing of `d̃^{n-1}_h` (initialisation on two layers of cells, then
/// fast marching).
pub fn sphere_drift_signed(
    level: u32,
    k: usize,
    reps: usize,
    bar: Option<&ProgressBar>,
) -> Result<Vec<f64>> {
    let opts = PprOptions {
        degree: k,
        ..PprOptions::default()
    };
    drift_with(level, k, reps, bar, |m, f| {
        Ok(redistance_ppr_cells(&m.points, &m.tets, f, &opts)?.values)
    })
}

/// The reference for [`sphere_drift_signed`] with `k = 1`: the same loop with geometric
/// redistancing (exact distance to the piecewise-planar zero level, 004 §2.2) instead of PPR. It
/// shows how much of the drift any redistancing to `Γ_h` of a P1 field has.
pub fn sphere_drift_geometric_signed(
    level: u32,
    reps: usize,
    bar: Option<&ProgressBar>,
) -> Result<Vec<f64>> {
    drift_with(level, 1, reps, bar, |m, f| {
        redistance_geometric_cells(&m.points, &m.tets, f)
    })
}

fn drift_with(
    level: u32,
    k: usize,
    reps: usize,
    bar: Option<&ProgressBar>,
    redistance: impl Fn(&Mesh3, &[f64]) -> Result<Vec<f64>>,
) -> Result<Vec<f64>> {
    let r = 0.25;
    let d = move |p: DVec3| p.length() - r;
    let m = refined_box(level, d)?;
    let x = nodes3(&m, k);
    let exact = 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
    let mut f: Vec<f64> = x.iter().map(|&p| d(p)).collect();
    let mut errs = vec![(negative_volume(&m, &f, k) - exact) / exact];
    for _ in 0..reps {
        f = redistance(&m, &f)?;
        errs.push((negative_volume(&m, &f, k) - exact) / exact);
        if let Some(b) = bar {
            b.inc(1);
        }
    }
    Ok(errs)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn negative_fraction_matches_sampling() {
        let u = [-0.3, -0.1, 0.2, 0.5];
        // Monte-Carlo-free check: a fine regular sampling of the reference tetrahedron.
        let n = 60;
        let (mut neg, mut all) = (0usize, 0usize);
        for a in 0..n {
            for b in 0..n - a {
                for c in 0..n - a - b {
                    let l = [
                        (a as f64 + 0.25) / n as f64,
                        (b as f64 + 0.25) / n as f64,
                        (c as f64 + 0.25) / n as f64,
                    ];
                    let l0 = 1.0 - l[0] - l[1] - l[2];
                    let f = l0 * u[0] + l[0] * u[1] + l[1] * u[2] + l[2] * u[3];
                    all += 1;
                    neg += usize::from(f < 0.0);
                }
            }
        }
        let approx = neg as f64 / all as f64;
        assert!(
            (negative_fraction(&u) - approx).abs() < 0.02,
            "{} vs {approx}",
            negative_fraction(&u)
        );
        assert!((negative_fraction(&[-1.0, 1.0, 1.0, 1.0]) - 0.125).abs() < 1e-15);
        assert!((negative_fraction(&[1.0, -1.0, -1.0, -1.0]) - 0.875).abs() < 1e-15);
    }
}
