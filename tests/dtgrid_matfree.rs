//! The matrix-free band step in `f32` against the assembled `f64` one: the operator, the
//! windowed rebuild, one step of mean curvature motion, and the typed errors.

use anisomesh::backends::dtgrid::distance::{extend_distance, Keep};
use anisomesh::backends::dtgrid::fem::{elements, Weight};
use anisomesh::backends::dtgrid::lattice::{
    band_around, crossing_cells_of_fn, Lattice, NarrowBand, C3,
};
use anisomesh::backends::dtgrid::lean::{extend_windowed, LeanOptions, LeanState};
use anisomesh::backends::dtgrid::matfree::MatFree;
use anisomesh::backends::dtgrid::mcf::{McfOptions, McfState};
use anisomesh::backends::dtgrid::scheme::Bc;
use anisomesh::backends::dtgrid::sparse_init::crossing_cells_pruned;
use anisomesh::backends::dtgrid::stencil::assemble_scaled;
use anisomesh::backends::dtgrid::{Band, DtGrid};
use anisomesh::error::Error;
use anisomesh::geom::DVec3;

/// An off-centre sphere band of half-width 2 on `n³` nodes with a field that is not a distance.
fn band(n: usize) -> (Lattice, NarrowBand<DtGrid<C3>>, Vec<f32>) {
    let lat = Lattice::unit(n).unwrap();
    let f = |p: DVec3| (p - DVec3::new(0.03, -0.02, 0.01)).length() - 0.29;
    let cross = crossing_cells_of_fn(&lat, &f).unwrap();
    let nb: NarrowBand<DtGrid<C3>> = band_around(&lat, &cross, 2).unwrap();
    let phi: Vec<f32> = nb
        .band
        .coords()
        .map(|c| (f(lat.pos(c)) * (1.0 + 0.3 * lat.pos(c).x)) as f32)
        .collect();
    (lat, nb, phi)
}

#[test]
fn matrix_free_operator_equals_the_assembled_matrix() {
    let (lat, nb, phi) = band(29);
    let n = nb.band.len();
    let phi64: Vec<f64> = phi.iter().map(|&v| v as f64).collect();
    let el = elements(&nb);
    for (eps, tau) in [(1e-3, lat.h * lat.h), (0.5, 3.7 * lat.h)] {
        let (mass, a) =
            assemble_scaled(&lat, &el, n, &phi64, Weight::Mcf { eps }, tau, true).unwrap();
        let op = MatFree::new(&lat, &nb, &phi, eps, tau).unwrap();
        // Mass and diagonal: f32 rounding of the f64 values.
        let d = a.diagonal();
        for i in 0..n {
            assert!(
                (op.mass[i] as f64 - mass[i]).abs() <= 1e-7 * mass[i].abs(),
                "{i}"
            );
            assert!((op.diag[i] as f64 - d[i]).abs() <= 1e-7 * d[i].abs(), "{i}");
        }
        // Products with a rough vector: the stiffness exact to f64 rounding, the mass term to
        // the f32 rounding of the stored mass.
        let x: Vec<f32> = (0..n)
            .map(|i| (((i * 7919) % 1000) as f32 / 500.0 - 1.0) * (1.0 + phi[i]))
            .collect();
        let x64: Vec<f64> = x.iter().map(|&v| v as f64).collect();
        let want = a.mul(&x64);
        let mut got = vec![0.0; n];
        op.apply(&x, &mut got);
        let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let err = want
            .iter()
            .zip(&got)
            .zip(&mass)
            .map(|((w, g), m)| (w - g).abs() / (m * 1.0).max(1e-300))
            .fold(0.0f64, f64::max);
        // |error| ≤ f32 rounding of m_i times |x_i| ≤ 2: relative to the mass, ≤ 1.2e-7.
        assert!(
            err < 1.2e-7,
            "eps {eps}: relative error {err:e} (scale {scale:e})"
        );
        // The same on one thread and on several.
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let mut got1 = vec![0.0; n];
        one.install(|| {
            let op1 = MatFree::new(&lat, &nb, &phi, eps, tau).unwrap();
            op1.apply(&x, &mut got1)
        });
        assert_eq!(got, got1);
    }
}

#[test]
fn windowed_extension_equals_the_whole_band_extension() {
    let (lat, nb, phi) = band(33);
    let phi64: Vec<f64> = phi.iter().map(|&v| v as f64).collect();
    // The band of the zero level moved by a third of a cell.
    let moved: Vec<f64> = phi64.iter().map(|v| v - 0.3 * lat.h).collect();
    let cross: Vec<C3> = nb
        .band
        .cells()
        .filter(|(_, idx)| {
            let v = idx.map(|i| moved[i as usize]);
            v.iter().any(|&x| x < 0.0) && v.iter().any(|&x| x >= 0.0)
        })
        .map(|(c, _)| c)
        .collect();
    let to: NarrowBand<DtGrid<C3>> = band_around(&lat, &cross, 2).unwrap();
    let moved32: Vec<f32> = moved.iter().map(|&v| v as f32).collect();
    let moved64: Vec<f64> = moved32.iter().map(|&v| v as f64).collect();
    let dmax = 8.0 * lat.h;
    for keep in [Keep::Nothing, Keep::Crossing, Keep::OldBand] {
        let whole = extend_distance(&lat, &nb.band, &moved64, &to.band, keep, dmax);
        for chunk in [300, 2000, usize::MAX] {
            let win =
                extend_windowed(&lat, &nb.band, &moved32, &to.band, keep, dmax, chunk).unwrap();
            assert_eq!(win.len(), whole.len());
            for (i, (a, b)) in whole.iter().zip(&win).enumerate() {
                assert_eq!(*a as f32, *b, "{keep:?} chunk {chunk} node {i}");
            }
        }
    }
}

/// The largest `|a − b|` over the nodes where `|a| ≤ 1.5 h`, and over all nodes.
fn differences(a: &[f64], b: &[f32], h: f64) -> (f64, f64) {
    let (mut near, mut all) = (0.0f64, 0.0f64);
    for (x, y) in a.iter().zip(b) {
        let d = (x - *y as f64).abs();
        all = all.max(d);
        if x.abs() <= 1.5 * h {
            near = near.max(d);
        }
    }
    (near, all)
}

#[test]
fn matrix_free_step_agrees_with_the_assembled_step() {
    let n = 33;
    let lat = Lattice::unit(n).unwrap();
    let h = lat.h;
    let f = |p: DVec3| p.length() - 0.25;
    let s0: McfState<DtGrid<C3>> = McfState::new(lat, 2, &f).unwrap();
    for inner in [1, 5] {
        let o = McfOptions {
            j: 2,
            inner,
            ..McfOptions::default()
        };
        let mut a = s0.clone();
        let mut b = LeanState::from_state(&s0);
        let lo = LeanOptions {
            mcf: o,
            chunk_nodes: 4000,
            ..LeanOptions::default()
        };
        for _ in 0..4 {
            let ra = a.step(h * h, &o).unwrap();
            let rb = b.step(h * h, &lo).unwrap();
            // Without inner iterations the two schemes solve the same systems; with them, the
            // f32 data may stop the inner iteration one solve earlier or later.
            if inner == 1 {
                assert_eq!(ra.solves, rb.solves);
            }
        }
        let ra = a.surface_mean(|x| x.length()).unwrap();
        let rb = b.surface_mean(|x| x.length(), 5).unwrap();
        if inner == 1 {
            assert_eq!(a.nb.band, b.nb.band);
            let (near, all) = differences(&a.phi, &b.phi, h);
            // Measured: 4.9e-5 h near the zero level, 9.6e-3 h on the outer layers (where the
            // distance extension's nearest-triangle search is sensitive to rounding), radius
            // 6.3e-8 h.
            assert!(
                near < 2e-4 * h,
                "max |ΔΦ| near the zero level {:e} h",
                near / h
            );
            assert!(all < 3e-2 * h, "max |ΔΦ| {:e} h", all / h);
            assert!((ra - rb).abs() < 1e-6 * h, "radius {ra} {rb}");
        } else {
            assert!(
                (ra - rb).abs() < 1e-3 * h,
                "inner {inner}: radius {ra} {rb}"
            );
        }
    }
}

#[test]
fn lean_state_from_a_function_and_typed_errors() {
    let lat = Lattice::unit(49).unwrap();
    let f = |p: DVec3| (p - DVec3::new(0.01, 0.02, -0.03)).length() - 0.3;
    let a: McfState<DtGrid<C3>> = McfState::with_lipschitz(lat, 2, &f, 1.0).unwrap();
    let b = LeanState::new(lat, 2, &f, 1.0, 5000).unwrap();
    assert_eq!(a.nb.band, b.nb.band);
    assert_eq!(a.nb.interior, b.nb.interior);
    let (near, all) = differences(&a.phi, &b.phi, lat.h);
    // Measured: 1.9e-5 h near the zero level, 1.6e-2 h on the outer layers.
    assert!(near < 1e-4 * lat.h, "{near:e}");
    assert!(all < 3e-2 * lat.h, "{all:e}");
    let mut s = b.clone();
    let bad = LeanOptions {
        mcf: McfOptions {
            bc: Bc::Transparent,
            ..McfOptions::default()
        },
        ..LeanOptions::default()
    };
    assert!(matches!(s.step(1e-4, &bad), Err(Error::InvalidInput(_))));
    assert!(matches!(
        s.step(f64::NAN, &LeanOptions::default()),
        Err(Error::InvalidInput(_))
    ));
    let nan = LeanState::new(
        lat,
        2,
        &|p: DVec3| if p.z > 0.1 { f64::NAN } else { f(p) },
        1.0,
        5000,
    );
    assert!(matches!(nan, Err(Error::InvalidField { .. })), "{nan:?}");
    // A sphere of two cells vanishes within a few large steps: a typed error, no panic.
    let mut tiny = LeanState::new(lat, 1, &|p: DVec3| p.length() - 1.5 * lat.h, 1.0, 5000).unwrap();
    let o = LeanOptions {
        mcf: McfOptions {
            j: 1,
            ..McfOptions::default()
        },
        ..LeanOptions::default()
    };
    let mut last = Ok(Default::default());
    for _ in 0..50 {
        last = tiny.step(0.01, &o);
        if last.is_err() {
            break;
        }
    }
    assert!(matches!(last, Err(Error::EmptyLevelSet(_))), "{last:?}");
}

#[test]
fn pruned_crossing_cells_equal_the_dense_pass() {
    // Grids that are not powers of two, off-centre shapes, a non-distance with its bound.
    let shapes: [(&(dyn Fn(DVec3) -> f64 + Sync), f64); 3] = [
        (
            &|p: DVec3| (p - DVec3::new(0.031, -0.017, 0.009)).length() - 0.29,
            1.0,
        ),
        (
            &|p: DVec3| {
                let q = DVec3::new(p.x / 0.4, p.y / 0.3, p.z / 0.25);
                q.length_squared() - 1.0
            },
            // |∇f| = 2|(x/a², y/b², z/c²)| ≤ 2·0.5√3/0.0625 on the unit box.
            2.0 * 0.5 * 3f64.sqrt() / 0.0625,
        ),
        (
            &|p: DVec3| {
                let r = (p.x * p.x + p.y * p.y).sqrt() - 0.25;
                (r * r + p.z * p.z).sqrt() - 0.1
            },
            1.0,
        ),
    ];
    for n in [23, 48, 61] {
        let lat = Lattice::unit(n).unwrap();
        for (f, l) in &shapes {
            let g = |p: DVec3| f(p);
            let dense = crossing_cells_of_fn(&lat, &g).unwrap();
            let pruned = crossing_cells_pruned(&lat, &g, *l).unwrap();
            assert!(!dense.is_empty());
            assert_eq!(dense, pruned, "n = {n}");
        }
    }
    // The whole state: band and values identical to the dense construction.
    let lat = Lattice::unit(49).unwrap();
    let f = |p: DVec3| (p - DVec3::new(0.02, 0.0, -0.03)).length() - 0.3;
    let a: McfState<DtGrid<C3>> = McfState::new(lat, 2, &f).unwrap();
    let b: McfState<DtGrid<C3>> = McfState::with_lipschitz(lat, 2, &f, 1.0).unwrap();
    assert_eq!(a.nb.band, b.nb.band);
    assert_eq!(a.nb.interior, b.nb.interior);
    assert_eq!(a.phi, b.phi);
    // Typed errors: NaN, a bad bound, a shape that does not fit.
    let nan = crossing_cells_pruned(
        &lat,
        &|p: DVec3| {
            if p.x > 0.2 {
                f64::NAN
            } else {
                p.length() - 0.3
            }
        },
        1.0,
    );
    assert!(matches!(nan, Err(Error::InvalidField { .. })), "{nan:?}");
    assert!(crossing_cells_pruned(&lat, &f, 0.0).is_err());
    let big = McfState::<DtGrid<C3>>::with_lipschitz(lat, 2, &|p: DVec3| p.length() - 0.49, 1.0);
    assert!(matches!(big, Err(Error::InvalidInput(_))), "{big:?}");
}
