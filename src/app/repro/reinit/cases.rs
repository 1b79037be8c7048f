//! The input of the tables of 003 §8 and its 2D cases: the perturbed distance
//! `φ^{(α)} = d^{ex} q^{(α)}` interpolated at the P1/P2 nodes, redistanced by PPR without the
//! fast-marching extension, on uniform grids of a circle and of the Zalesak disk.

use super::types::CaseResult;
use anisomesh::error::Result;
use anisomesh::fem::lagrange::P2Dofs;
use anisomesh::geom::DVec2;
use anisomesh::levelset::redistance::{redistance_ppr, PprOptions};
use anisomesh::levelset::shapes::{Shape, Zalesak};
use anisomesh::mesh::{GridPattern, Mesh2};

/// The coarsest mesh size `h_0` of 003 §8 (`h_ℓ = 2^{-ℓ} h_0`).
pub(super) const H0: f64 = 2.0 / 3.0;

/// `q^{(α)}(x) = 9 + 4 cos(α x_1 x_2 / |x|)` (003 §8).
pub(super) fn q_alpha(alpha: f64, x: f64, y: f64, norm: f64) -> f64 {
    9.0 + 4.0 * (alpha * x * y / norm.max(f64::MIN_POSITIVE)).cos()
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

/// The PPR options of the tables: degree `k`, initialisation on one layer of cells, no
/// fast-marching extension.
pub(super) fn table_opts(k: usize) -> PprOptions {
    PprOptions {
        degree: k,
        extend: false,
        layers: 1,
        ..PprOptions::default()
    }
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
