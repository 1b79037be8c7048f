//! The size of the mesh a metric asks for, before adapting: its complexity `C = ∫ sqrt(det M)`
//! and the vertex count `2 C / sqrt(3)` of a unit mesh ([`crate::metric::complexity()`], 004 §3.3).
//!
//! For a metric given on a mesh the integral is taken over that mesh. For the geometric metric
//! of 004 eq. (6) of an exact shape the metric is known everywhere but concentrates in a band
//! much thinner than any sampling grid, so the integral is split at a distance `T` from the zero
//! level:
//! - away from the interface (`|u| ≥ T`), the midpoint rule on a `256 × 256` grid of the domain;
//! - in the tube `|u| < T`, an integral along the zero level (segments of the grid's P1 zero
//!   level) of the integral along the normal, `∫_{-T}^{T} sqrt(det M(p + d n)) dd`, on a grid in
//!   `d` that is uniform inside the band of eq. (6) and geometric outside it.
//!
//! The tube ignores the curvature of the zero level (`dA = (1 - κ d) ds dd`) and the grid sees
//! the zero level at its own resolution, so the estimate is an order of magnitude, good to
//! about a factor two, not a prediction of the adapted count.

use super::sources::LevelSetMetric;
use crate::geom::DVec2;
use crate::levelset::{extract_zero_level, Shape};
use crate::mesh::{GridPattern, Mesh2};
use crate::metric::{predicted_vertices, Sym2};
use rayon::prelude::*;

/// Cells per side of the sampling grid.
const GRID: usize = 256;
/// Samples along each normal, per side of the zero level: inside the band and beyond it.
const NORMAL_SAMPLES: usize = 48;

/// The vertex count the eq. (6) metric `lm` of `shape` asks for on the rectangle `domain`
/// (module documentation), together with whether the sampling grid saw a zero level.
pub fn shape_vertices(
    shape: &dyn Shape,
    lm: &LevelSetMetric,
    domain: (DVec2, DVec2),
) -> (f64, bool) {
    let density = |p: DVec2| {
        let m = lm.metric(shape.distance(p), shape.gradient(p), &shape.hessian(p));
        m.det().max(0.0).sqrt()
    };
    let (lo, hi) = domain;
    let cell = (hi - lo) / GRID as f64;
    let tube = cell.length();
    // Far field: the midpoint rule on the cells whose centre is at least `tube` away.
    let far: f64 = (0..GRID * GRID)
        .into_par_iter()
        .map(|k| {
            let c = lo + cell * DVec2::new((k % GRID) as f64 + 0.5, (k / GRID) as f64 + 0.5);
            if shape.distance(c).abs() >= tube {
                density(c) * cell.x * cell.y
            } else {
                0.0
            }
        })
        .sum();
    // The tube: along the zero level of the grid's P1 interpolant.
    let Ok(grid) = Mesh2::rectangle(lo, hi, GRID, GRID, GridPattern::UnionJack) else {
        return (predicted_vertices(far), false);
    };
    let u: Vec<f64> = grid.points.iter().map(|&p| shape.distance(p)).collect();
    let segments: Vec<(DVec2, DVec2)> = extract_zero_level(&grid, &u)
        .map(|lines| {
            lines
                .iter()
                .flat_map(|l| l.segments().collect::<Vec<_>>())
                .collect()
        })
        .unwrap_or_default();
    let normal_offsets = normal_grid(lm.band.min(tube), tube);
    let near: f64 = segments
        .par_iter()
        .map(|&(a, b)| {
            let (mid, len) = (0.5 * (a + b), (b - a).length());
            let n = shape.gradient(mid).normalize_or_zero();
            if len == 0.0 || n == DVec2::ZERO {
                return 0.0;
            }
            // Step back onto the exact zero level along the normal.
            let p = mid - shape.distance(mid) * n;
            let line: f64 = normal_offsets
                .windows(2)
                .map(|w| {
                    let (d0, d1) = (w[0], w[1]);
                    let dm = 0.5 * (d0 + d1);
                    (d1 - d0) * (density(p + dm * n) + density(p - dm * n))
                })
                .sum();
            line * len
        })
        .sum();
    (predicted_vertices(far + near), !segments.is_empty())
}

/// Offsets `0 = d_0 < d_1 < … = tube` along a normal: uniform up to `band`, geometric beyond.
fn normal_grid(band: f64, tube: f64) -> Vec<f64> {
    let band = band.clamp(tube * 1e-9, tube);
    let mut d: Vec<f64> = (0..=NORMAL_SAMPLES)
        .map(|k| band * k as f64 / NORMAL_SAMPLES as f64)
        .collect();
    let ratio = (tube / band).powf(1.0 / NORMAL_SAMPLES as f64);
    if ratio > 1.0 + 1e-12 {
        d.extend((1..=NORMAL_SAMPLES).map(|k| band * ratio.powi(k as i32)));
    }
    d
}

/// The vertex count a metric field given on `mesh` asks for.
pub fn field_vertices(mesh: &Mesh2, metric: &[Sym2]) -> f64 {
    predicted_vertices(crate::metric::complexity(mesh, metric))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::levelset::Circle;

    #[test]
    fn normal_grid_is_increasing_and_ends_at_the_tube() {
        let d = normal_grid(1e-4, 0.02);
        assert!(d.windows(2).all(|w| w[1] > w[0]));
        assert!((d[d.len() - 1] - 0.02).abs() < 1e-12);
        assert_eq!(d[NORMAL_SAMPLES], 1e-4);
    }

    /// An isotropic metric of constant size `h` asks for `2 |Ω| / (sqrt(3) h²)` vertices.
    #[test]
    fn constant_size_gives_the_unit_mesh_count() {
        let lm = LevelSetMetric {
            hmin: 0.05,
            hmax: 0.05,
            ..LevelSetMetric::default()
        };
        let circle = Circle {
            centre: DVec2::ZERO,
            radius: 0.5,
        };
        let domain = (DVec2::splat(-1.0), DVec2::splat(1.0));
        let (n, seen) = shape_vertices(&circle, &lm, domain);
        let exact = predicted_vertices(4.0 / (0.05 * 0.05));
        assert!(seen);
        assert!((n / exact - 1.0).abs() < 0.02, "{n} vs {exact}");
    }
}
