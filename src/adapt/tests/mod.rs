//! Unit tests of the adaptation operators and their workspace, driving single operators through
//! a `Ctx`, with `check()` after every operation.

use super::params::{MetricInterpolation, OpParams};
use crate::geom::DVec2;
use crate::mesh::{GridPattern, Mesh2};
use crate::metric::Sym2;

mod operators;
mod workspace;

/// The unit square as a `n x n` union-jack grid.
fn square(n: usize) -> Mesh2 {
    Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, n, n, GridPattern::UnionJack).unwrap()
}

/// The default operator parameters of [`super::AdaptOptions`], without insertion.
fn params() -> OpParams {
    OpParams {
        l_min: std::f64::consts::FRAC_1_SQRT_2,
        l_max: std::f64::consts::SQRT_2,
        q_max: 5.0,
        curve_tol: 0.0,
        insertion: false,
        interpolation: MetricInterpolation::default(),
    }
}

/// Anisotropic metric with sizes `hx`, `hy` along the axes.
fn aniso(hx: f64, hy: f64) -> Sym2 {
    Sym2::new(1.0 / (hx * hx), 0.0, 1.0 / (hy * hy))
}

/// Relative difference of `a` from `b`.
fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}
