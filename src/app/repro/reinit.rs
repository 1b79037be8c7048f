//! The redistancing experiments of 003 §8 (tables 8.1-8.4, volume drift).
//!
//! - Example 1 (torus, `r = 0.2`, `R = 0.4` in `[-1, 1]³`): a Kuhn mesh with `h_0 = 2/3`, locally
//!   refined by newest-vertex bisection to `h_ℓ = 2^{-ℓ} h_0` near the torus; input
//!   `φ_h = I_h φ^{(α)}` with `φ^{(α)} = d^{ex} q^{(α)}`, `q^{(α)}(x) = 9 + 4 cos(α x_1 x_2 / |x|)`;
//!   errors `e_∞ = max_{v ∈ N(T_{Γ_h})} |I_h d_h(v) - d^{ex}(v)|` and
//!   `e^∇_∞ = max_{T ∈ T_{Γ_h}} |(|T|^{-1} ∫_T |∇ I_h d_h|²)^{1/2} - 1|` for `k = 1, 2`
//!   (tables 8.1 `α = 1`, 8.2 `α = 10`, 8.3 `α = 50`).
//! - The 2D analogue: a circle of radius 0.5 (centre (0.03, -0.02)) in `[-1, 1]²` on uniform
//!   union-jack grids with `h_ℓ = 2^{-ℓ} (2/3)`, same `q^{(α)}`.
//! - The Zalesak slotted disk of 004 (exact signed distance from [`anisomesh::levelset::shapes`]) in
//!   `[-2, 2]²` with the same `h_ℓ` and `q^{(α)}`: its corners break the smoothness the analysis
//!   of 003 §7 assumes, so this table shows what happens there (max errors sit at the corners).
//! - Repeated redistancing of a sphere of radius 0.25 (Fig. 8.4): `d̃^0_h = I_h d^{ex}`, then 100
//!   redistancings (initialisation + fast marching extension); relative volume error
//!   `|V^n - 4/3 π r³| / (4/3 π r³)`. The volume inside the zero level is exact for P1 (per
//!   tetrahedron, closed form) and for P2 is computed on 64 sub-tetrahedra per cut tetrahedron.

use std::io::{IsTerminal, Write};
use std::path::PathBuf;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde::Serialize;

use anisomesh::error::{Error, Result};
use anisomesh::fem::lagrange::{self, P2Dofs};
use anisomesh::geom::{DVec2, DVec3};
use anisomesh::levelset::redistance::{
    redistance_geometric_cells, redistance_ppr, redistance_ppr_cells, PprOptions, PprReport,
};
use anisomesh::mesh::{GridPattern, Mesh2};
use anisomesh::mesh3::Mesh3;

/// Options of [`run`].
#[derive(Debug, Clone)]
pub struct ReinitOptions {
    /// Refinement levels `ℓ` of the torus (003 §8 uses 3..=8).
    pub levels_3d: Vec<u32>,
    /// Levels of the 2D circle.
    pub levels_2d: Vec<u32>,
    /// Values of `α` (1, 10 and the stress case 50).
    pub alphas: Vec<u32>,
    /// Polynomial degrees `k`.
    pub degrees: Vec<usize>,
    /// Levels of the sphere volume-drift test (003 uses 5 and 6).
    pub volume_levels: Vec<u32>,
    /// Number of repeated redistancings (003: 100).
    pub volume_reps: usize,
    /// Directory for `reinit.json` (nothing written when `None`).
    pub out_dir: Option<PathBuf>,
    /// Print the tables to standard output.
    pub print: bool,
}

impl Default for ReinitOptions {
    fn default() -> Self {
        ReinitOptions {
            levels_3d: (3..=5).collect(),
            levels_2d: (3..=8).collect(),
            alphas: vec![1, 10, 50],
            degrees: vec![1, 2],
            volume_levels: vec![4],
            volume_reps: 100,
            out_dir: None,
            print: true,
        }
    }
}

/// One row of a convergence table.
#[derive(Debug, Clone, Serialize)]
pub struct Row {
    pub level: u32,
    pub h: f64,
    pub e_inf: f64,
    pub order_inf: Option<f64>,
    pub e_grad: f64,
    pub order_grad: Option<f64>,
    /// Redistancing statistics (not in the JSON).
    #[serde(skip)]
    pub report: PprReport,
    /// Wall time of the case (mesh, interpolation, redistancing, errors), seconds.
    #[serde(skip)]
    pub secs: f64,
    /// Peak resident memory of the process after the case (`VmHWM`, MiB; `None` off Linux).
    #[serde(skip)]
    pub peak_mib: Option<f64>,
}

/// Peak resident set size of this process in MiB (`VmHWM` of `/proc/self/status`).
pub fn peak_rss_mib() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}

/// One convergence table.
#[derive(Debug, Clone, Serialize)]
pub struct Table {
    pub name: String,
    pub dim: usize,
    pub k: usize,
    pub alpha: u32,
    pub rows: Vec<Row>,
}

/// Relative volume errors `e^n_Vol`, `n = 0..=reps`.
#[derive(Debug, Clone, Serialize)]
pub struct Drift {
    pub k: usize,
    pub level: u32,
    pub rel_error: Vec<f64>,
}

/// Everything [`run`] measured (serialised as `reinit.json`).
#[derive(Debug, Clone, Serialize)]
pub struct ReinitReport {
    pub tables: Vec<Table>,
    pub volume_drift: Vec<Drift>,
    /// The same drift test with geometric redistancing (k = 1 only), for reference.
    pub volume_drift_geometric: Vec<Drift>,
}

/// Errors of one case: `(h, e_∞, e^∇_∞, report)`.
pub type CaseResult = (f64, f64, f64, PprReport);

const H0: f64 = 2.0 / 3.0;

/// `q^{(α)}(x) = 9 + 4 cos(α x_1 x_2 / |x|)` (003 §8).
fn q_alpha(alpha: f64, x: f64, y: f64, norm: f64) -> f64 {
    9.0 + 4.0 * (alpha * x * y / norm.max(f64::MIN_POSITIVE)).cos()
}

/// Exact signed distance to the torus of 003 §8, Example 1.
pub fn torus_distance(p: DVec3) -> f64 {
    let (r, big_r) = (0.2, 0.4);
    (p.z * p.z + ((p.x * p.x + p.y * p.y).sqrt() - big_r).powi(2)).sqrt() - r
}

/// The level-`ℓ` mesh of `[-1, 1]³` refined near the zero level of `dist` (nested bands of width
/// `2 h_j`, `j = 1..=ℓ`): Kuhn mesh with `h_0 = 2/3` and 3 bisections per level.
pub fn refined_box(level: u32, dist: impl Fn(DVec3) -> f64 + Copy) -> Result<Mesh3> {
    let mut m = Mesh3::kuhn_box(DVec3::splat(-1.0), DVec3::splat(1.0), [3, 3, 3])?;
    for j in 1..=level {
        let h = H0 / f64::from(1u32 << j);
        m.refine_near(dist, 2.0 * h, (3 * j) as u8);
    }
    Ok(m)
}

/// Node positions of a P1/P2 field on tetrahedra (vertices, then [`P2Dofs::for_tets`] edges).
fn nodes3(m: &Mesh3, k: usize) -> Vec<DVec3> {
    let mut x = m.points.clone();
    if k == 2 {
        let d = P2Dofs::for_tets(&m.tets, m.n_points());
        x.extend(
            d.edges
                .iter()
                .map(|&[a, b]| 0.5 * (m.points[a as usize] + m.points[b as usize])),
        );
    }
    x
}

/// Node positions of a P1/P2 field on triangles.
fn nodes2(m: &Mesh2, k: usize) -> Vec<DVec2> {
    let mut x = m.points.clone();
    if k == 2 {
        let d = P2Dofs::for_mesh2(m);
        x.extend(
            d.edges
                .iter()
                .map(|&[a, b]| 0.5 * (m.points[a as usize] + m.points[b as usize])),
        );
    }
    x
}

fn table_opts(k: usize) -> PprOptions {
    PprOptions {
        degree: k,
        extend: false,
        layers: 1,
        ..PprOptions::default()
    }
}

#[cfg(test)]
/// Example 1 of 003 §8 at level `ℓ`, degree `k`, parameter `α` (initialisation phase only).
pub fn torus_case(level: u32, k: usize, alpha: f64) -> Result<CaseResult> {
    torus_case_on(&refined_box(level, torus_distance)?, level, k, alpha)
}

/// [`torus_case`] on the given level-`ℓ` mesh (from [`refined_box`] with [`torus_distance`]).
pub fn torus_case_on(m: &Mesh3, level: u32, k: usize, alpha: f64) -> Result<CaseResult> {
    let x = nodes3(m, k);
    let phi: Vec<f64> = x
        .iter()
        .map(|p| torus_distance(*p) * q_alpha(alpha, p.x, p.y, p.length()))
        .collect();
    let out = redistance_ppr_cells(&m.points, &m.tets, &phi, &table_opts(k))?;
    let e_inf = x
        .iter()
        .enumerate()
        .filter(|(i, _)| out.band[*i])
        .map(|(i, p)| (out.values[i] - torus_distance(*p)).abs())
        .fold(0.0, f64::max);
    Ok((
        H0 / f64::from(1u32 << level),
        e_inf,
        out.report.e_grad,
        out.report,
    ))
}

/// The 2D analogue: a circle of radius 0.5 centred at (0.03, -0.02) on a uniform grid of
/// `[-1, 1]²` with `h_ℓ = 2^{-ℓ} h_0` (`h_0 = 2/3`).
pub fn circle_case(level: u32, k: usize, alpha: f64) -> Result<CaseResult> {
    let n = 3usize << level;
    let m = Mesh2::rectangle(
        DVec2::splat(-1.0),
        DVec2::splat(1.0),
        n,
        n,
        GridPattern::UnionJack,
    )?;
    let d = |p: DVec2| (p - DVec2::new(0.03, -0.02)).length() - 0.5;
    let x = nodes2(&m, k);
    let phi: Vec<f64> = x
        .iter()
        .map(|&p| d(p) * q_alpha(alpha, p.x, p.y, p.length()))
        .collect();
    let out = redistance_ppr(&m, &phi, &table_opts(k))?;
    let e_inf = x
        .iter()
        .enumerate()
        .filter(|(i, _)| out.band[*i])
        .map(|(i, &p)| (out.values[i] - d(p)).abs())
        .fold(0.0, f64::max);
    Ok((2.0 / n as f64, e_inf, out.report.e_grad, out.report))
}

/// The Zalesak disk of 004 on a uniform grid of `[-2, 2]²` with `h_ℓ = 2^{-ℓ} h_0`.
pub fn zalesak_case(level: u32, k: usize, alpha: f64) -> Result<CaseResult> {
    use anisomesh::levelset::shapes::{Shape, Zalesak};
    let z = Zalesak::default();
    let n = 6usize << level;
    let m = Mesh2::rectangle(
        DVec2::splat(-2.0),
        DVec2::splat(2.0),
        n,
        n,
        GridPattern::UnionJack,
    )?;
    let x = nodes2(&m, k);
    let phi: Vec<f64> = x
        .iter()
        .map(|&p| z.distance(p) * q_alpha(alpha, p.x, p.y, p.length()))
        .collect();
    let out = redistance_ppr(&m, &phi, &table_opts(k))?;
    let e_inf = x
        .iter()
        .enumerate()
        .filter(|(i, _)| out.band[*i])
        .map(|(i, &p)| (out.values[i] - z.distance(p)).abs())
        .fold(0.0, f64::max);
    Ok((4.0 / n as f64, e_inf, out.report.e_grad, out.report))
}

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

/// The paper's values `(e_∞, e^∇_∞)` for levels 3..=8 (003 tables 8.1–8.3), by `(α, k)`.
fn paper(alpha: u32, k: usize) -> Option<[(f64, f64); 6]> {
    Some(match (alpha, k) {
        (1, 1) => [
            (1.21e-2, 2.50e-1),
            (3.01e-3, 1.53e-1),
            (7.54e-4, 8.32e-2),
            (1.90e-4, 4.25e-2),
            (4.68e-5, 2.12e-2),
            (1.19e-5, 1.07e-2),
        ],
        (1, 2) => [
            (5.73e-4, 1.66e-2),
            (7.21e-5, 3.46e-3),
            (9.94e-6, 8.70e-4),
            (1.24e-6, 2.13e-4),
            (1.58e-7, 5.31e-5),
            (2.07e-8, 1.34e-5),
        ],
        (10, 1) => [
            (1.15e-2, 2.40e-1),
            (3.24e-3, 1.61e-1),
            (7.91e-4, 8.02e-2),
            (2.07e-4, 4.32e-2),
            (5.18e-5, 2.24e-2),
            (1.32e-5, 1.11e-2),
        ],
        (10, 2) => [
            (7.16e-4, 1.77e-2),
            (1.04e-4, 3.78e-3),
            (1.56e-5, 1.10e-3),
            (1.87e-6, 3.10e-4),
            (2.44e-7, 7.32e-5),
            (3.09e-8, 1.91e-5),
        ],
        (50, 1) => [
            (4.07e-2, 6.23e-1),
            (1.05e-2, 2.32e-1),
            (2.91e-3, 1.01e-1),
            (7.63e-4, 5.76e-2),
            (1.94e-4, 3.04e-2),
            (4.84e-5, 1.58e-2),
        ],
        (50, 2) => [
            (7.47e-2, 8.10e-1),
            (2.86e-2, 3.10e-1),
            (5.66e-4, 1.63e-2),
            (6.87e-5, 2.48e-2),
            (7.21e-6, 1.52e-3),
            (8.78e-7, 3.90e-4),
        ],
        _ => return None,
    })
}

fn progress(len: u64, msg: &str) -> ProgressBar {
    let b = ProgressBar::new(len);
    if std::io::stderr().is_terminal() {
        b.set_draw_target(ProgressDrawTarget::stderr());
        if let Ok(s) = ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} {elapsed}") {
            b.set_style(s);
        }
    } else {
        b.set_draw_target(ProgressDrawTarget::hidden());
    }
    b.set_message(msg.to_string());
    b
}

fn with_orders(mut rows: Vec<Row>) -> Vec<Row> {
    for i in 1..rows.len() {
        let rh = (rows[i - 1].h / rows[i].h).ln();
        rows[i].order_inf = Some((rows[i - 1].e_inf / rows[i].e_inf).ln() / rh);
        rows[i].order_grad = Some((rows[i - 1].e_grad / rows[i].e_grad).ln() / rh);
    }
    rows
}

fn print_table(t: &Table) {
    let pap = if t.dim == 3 {
        paper(t.alpha, t.k)
    } else {
        None
    };
    let which = match t.alpha {
        1 => "   [paper: 003 Table 8.1]",
        10 => "   [paper: 003 Table 8.2]",
        50 => "   [paper: 003 Table 8.3]",
        _ => "",
    };
    println!(
        "\n{} ({}D), k = {}, alpha = {}{}",
        t.name,
        t.dim,
        t.k,
        t.alpha,
        if pap.is_some() { which } else { "" }
    );
    println!(
        "{:>3} {:>9} {:>9} {:>5} {:>9} {:>5} | {:>8} {:>5} {:>8} {:>5} | {:>9} {:>9} {:>4} {:>7} {:>7}",
        "l", "h", "e_inf", "ord", "e_grad", "ord", "paper e", "ord", "paper eg", "ord", "cells",
        "nodes", "n.c.", "s", "MiB"
    );
    let o = |x: Option<f64>| x.map_or("-".to_string(), |v| format!("{v:.2}"));
    for (i, r) in t.rows.iter().enumerate() {
        let at = |l: u32| {
            pap.filter(|_| (3..=8).contains(&l))
                .map(|p| p[(l - 3) as usize])
        };
        let (pe, pg) = at(r.level).map_or(("-".into(), "-".into()), |(a, b)| {
            (format!("{a:.2e}"), format!("{b:.2e}"))
        });
        // The paper's orders from its own values (levels differ by one: h halves).
        let prev = (i > 0 && t.rows[i - 1].level + 1 == r.level)
            .then(|| at(r.level - 1))
            .flatten();
        let (po, pgo) = match (prev, at(r.level)) {
            (Some(a), Some(b)) => (Some((a.0 / b.0).log2()), Some((a.1 / b.1).log2())),
            _ => (None, None),
        };
        println!(
            "{:>3} {:>9.3e} {:>9.3e} {:>5} {:>9.3e} {:>5} | {:>8} {:>5} {:>8} {:>5} | {:>9} {:>9} {:>4} {:>7.1} {:>7}",
            r.level,
            r.h,
            r.e_inf,
            o(r.order_inf),
            r.e_grad,
            o(r.order_grad),
            pe,
            o(po),
            pg,
            o(pgo),
            r.report.cells,
            r.report.nodes,
            r.report.not_converged,
            r.secs,
            r.peak_mib.map_or("-".into(), |m| format!("{m:.0}")),
        );
    }
}

/// One line of relative volume errors at repetitions 0, 1, 10, 20, 50 and the last (only those
/// that were run), with the paper's statement beside them.
pub fn drift_line(k: usize, level: u32, e: &[f64]) -> String {
    let last = e.len().saturating_sub(1);
    let mut marks: Vec<usize> = [0, 1, 10, 20, 50]
        .into_iter()
        .filter(|&n| n < last)
        .collect();
    marks.push(last);
    let vals: Vec<String> = marks
        .iter()
        .map(|&n| format!("e^{n} = {:.3e}", e[n]))
        .collect();
    format!(
        "sphere r = 0.25, k = {k}, level {level}: {}  (003 Fig. 8.4, levels 5-6: a mild \
         shrinking, weaker for k = 2; the text gives no numbers)",
        vals.join(", ")
    )
}

/// Run the experiments of 003 §8 (module documentation), print the tables beside the paper's
/// values, and write `reinit.json` when `out_dir` is set.
pub fn run(opts: &ReinitOptions) -> Result<ReinitReport> {
    let mut tables = Vec::new();
    let sets = [
        ("circle", 2usize, &opts.levels_2d),
        ("zalesak", 2, &opts.levels_2d),
        ("torus", 3, &opts.levels_3d),
    ];
    let cases: Vec<(&str, usize, u32, usize)> = sets
        .iter()
        .filter(|(_, _, l)| !l.is_empty())
        .flat_map(|&(name, dim, _)| {
            opts.alphas
                .iter()
                .flat_map(move |&a| opts.degrees.iter().map(move |&k| (name, dim, a, k)))
        })
        .collect();
    let n_levels = |dim: usize| {
        if dim == 2 {
            opts.levels_2d.len()
        } else {
            opts.levels_3d.len()
        }
    };
    let total: usize = cases.iter().map(|c| n_levels(c.1)).sum();
    let bar = progress(total as u64, "tables");
    // Torus meshes by level, built once (the deepest levels take seconds and hundreds of MiB).
    let mut meshes: std::collections::HashMap<u32, Mesh3> = std::collections::HashMap::new();
    for (name, dim, alpha, k) in cases {
        let levels = if dim == 2 {
            &opts.levels_2d
        } else {
            &opts.levels_3d
        };
        let mut rows = Vec::new();
        for &l in levels {
            let a = f64::from(alpha);
            let t0 = std::time::Instant::now();
            let (h, e_inf, e_grad, report) = match name {
                "circle" => circle_case(l, k, a)?,
                "zalesak" => zalesak_case(l, k, a)?,
                _ => {
                    let m = match meshes.entry(l) {
                        std::collections::hash_map::Entry::Occupied(e) => e.into_mut(),
                        std::collections::hash_map::Entry::Vacant(e) => {
                            e.insert(refined_box(l, torus_distance)?)
                        }
                    };
                    torus_case_on(m, l, k, a)?
                }
            };
            rows.push(Row {
                level: l,
                h,
                e_inf,
                order_inf: None,
                e_grad,
                order_grad: None,
                report,
                secs: t0.elapsed().as_secs_f64(),
                peak_mib: peak_rss_mib(),
            });
            bar.inc(1);
        }
        let t = Table {
            name: name.into(),
            dim,
            k,
            alpha,
            rows: with_orders(rows),
        };
        if opts.print {
            bar.suspend(|| print_table(&t));
        }
        tables.push(t);
    }
    bar.finish_and_clear();
    let mut volume_drift = Vec::new();
    let mut volume_drift_geometric = Vec::new();
    for &l in &opts.volume_levels {
        for &k in &opts.degrees {
            let bar = progress(opts.volume_reps as u64, &format!("sphere k={k} l={l}"));
            let e = sphere_drift(l, k, opts.volume_reps, Some(&bar))?;
            bar.finish_and_clear();
            if opts.print {
                println!("\n{}", drift_line(k, l, &e));
            }
            volume_drift.push(Drift {
                k,
                level: l,
                rel_error: e,
            });
        }
        if opts.degrees.contains(&1) {
            let bar = progress(opts.volume_reps as u64, &format!("sphere geometric l={l}"));
            let e: Vec<f64> = sphere_drift_geometric_signed(l, opts.volume_reps, Some(&bar))?
                .into_iter()
                .map(f64::abs)
                .collect();
            bar.finish_and_clear();
            if opts.print {
                println!("geometric redistancing, {}", drift_line(1, l, &e));
            }
            volume_drift_geometric.push(Drift {
                k: 1,
                level: l,
                rel_error: e,
            });
        }
    }
    let report = ReinitReport {
        tables,
        volume_drift,
        volume_drift_geometric,
    };
    if let Some(dir) = &opts.out_dir {
        write_json(dir, &report)?;
        write_plots(dir, &report)?;
    }
    Ok(report)
}

/// `reinit_<name>_einf.png`, `reinit_<name>_egrad.png` (log-log against `h`, fitted slopes) and
/// `reinit_volume.png` (relative volume error against the number of redistancings).
fn write_plots(dir: &std::path::Path, report: &ReinitReport) -> Result<()> {
    use crate::app::plot::{lines_png, loglog_png, LinesPlot, LogLogPlot, Series};
    let mut names: Vec<&str> = report.tables.iter().map(|t| t.name.as_str()).collect();
    names.dedup();
    for name in names {
        for (what, label) in [("einf", "e_inf"), ("egrad", "e_grad")] {
            let series = report
                .tables
                .iter()
                .filter(|t| t.name == name && t.rows.len() > 1)
                .map(|t| Series {
                    name: format!("k={} alpha={}", t.k, t.alpha),
                    points: t
                        .rows
                        .iter()
                        .map(|r| (r.h, if what == "einf" { r.e_inf } else { r.e_grad }))
                        .collect(),
                    show_fit_slope: true,
                    ..Series::default()
                })
                .collect::<Vec<_>>();
            if series.is_empty() {
                continue;
            }
            let plot = LogLogPlot {
                title: format!("{name}: {label} (003 §8)"),
                x_label: "h".into(),
                y_label: label.into(),
                series,
                ..LogLogPlot::default()
            };
            loglog_png(&dir.join(format!("reinit_{name}_{what}.png")), &plot)?;
        }
    }
    let mut ks: Vec<usize> = report.volume_drift.iter().map(|d| d.k).collect();
    ks.sort_unstable();
    ks.dedup();
    for k in ks {
        let geo = report.volume_drift_geometric.iter().filter(|_| k == 1);
        let series = report
            .volume_drift
            .iter()
            .filter(|d| d.k == k)
            .map(|d| (format!("PPR, level {}", d.level), d))
            .chain(geo.map(|d| (format!("geometric, level {}", d.level), d)))
            .map(|(name, d)| Series {
                name,
                points: d
                    .rel_error
                    .iter()
                    .enumerate()
                    .map(|(n, &e)| (n as f64, e))
                    .collect(),
                ..Series::default()
            })
            .collect();
        let plot = LinesPlot {
            title: format!("sphere r = 0.25, k = {k}: relative volume error (003 Fig. 8.4)"),
            x_label: "redistancings n".into(),
            y_label: "e_Vol^n".into(),
            series,
            ..LinesPlot::default()
        };
        lines_png(&dir.join(format!("reinit_volume_k{k}.png")), &plot)?;
    }
    Ok(())
}

/// Write `dir/reinit.json` atomically (temporary file, then rename).
fn write_json(dir: &std::path::Path, report: &ReinitReport) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let path = dir.join("reinit.json");
    let tmp = dir.join(".reinit.json.tmp");
    let text = serde_json::to_string_pretty(report)
        .map_err(|e| Error::InvalidInput(format!("reinit.json: {e}")))?;
    let mut f = std::fs::File::create(&tmp).map_err(|e| Error::io(&tmp, e))?;
    f.write_all(text.as_bytes())
        .map_err(|e| Error::io(&tmp, e))?;
    drop(f);
    std::fs::rename(&tmp, &path).map_err(|e| Error::io(&path, e))
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
