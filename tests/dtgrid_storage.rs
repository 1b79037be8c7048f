//! The DT-Grid storage against a dense reference (a `BTreeSet` of coordinates) on random bands in
//! 2D and 3D: membership, order, index round trip, cells, neighbourhoods, dilation, value
//! transfer, the implicit-function band and the typed errors.

use anisomesh::backends::dtgrid::grid::transfer_values;
use anisomesh::backends::dtgrid::{Band, DtCoord, DtGrid, Implicit};
use anisomesh::Error;
use proptest::prelude::*;
use std::collections::BTreeSet;

/// Every coordinate of the box `lo..=hi` along all `d` axes.
fn box_coords<C: DtCoord>(lo: i32, hi: i32) -> Vec<C> {
    let d = C::DIM;
    let m = (hi - lo + 1) as usize;
    (0..m.pow(d as u32))
        .map(|mut k| {
            let mut a = [0i32; 3];
            for v in a.iter_mut().take(d).rev() {
                *v = lo + (k % m) as i32;
                k /= m;
            }
            C::from_slice(&a[..d])
        })
        .collect()
}

fn check_against_reference<C: DtCoord>(set: &BTreeSet<C>, n: i32) {
    let g = DtGrid::<C>::from_sorted(set.iter().copied()).unwrap();
    assert_eq!(g.len(), set.len());
    // Order and index round trip.
    let coords: Vec<C> = g.coords().collect();
    assert_eq!(coords, set.iter().copied().collect::<Vec<_>>());
    for (i, &c) in coords.iter().enumerate() {
        assert_eq!(g.index(c), Some(i));
    }
    // Membership over the box and a margin around it.
    for c in box_coords::<C>(-2, n + 2) {
        assert_eq!(g.index(c).is_some(), set.contains(&c), "{c:?}");
    }
    // Cells: all lowest corners whose 2^d corners are in the set.
    let pos = |c: C| coords.binary_search(&c).ok().map(|i| i as u32);
    let want: Vec<(C, Vec<u32>)> = coords
        .iter()
        .filter_map(|&c| {
            let idx: Option<Vec<u32>> = (0..1 << C::DIM).map(|k| pos(c.corner(k))).collect();
            idx.map(|v| (c, v))
        })
        .collect();
    let got: Vec<(C, Vec<u32>)> = g
        .cells()
        .map(|(c, cell)| (c, cell.as_ref().to_vec()))
        .collect();
    assert_eq!(got, want);
    // Neighbourhoods.
    let d = C::DIM;
    let mut visited = 0;
    g.for_each_neighbourhood(|c, node, nbrs| {
        assert_eq!(coords[node], c);
        assert_eq!(nbrs.len(), 3usize.pow(d as u32));
        for (m, &nb) in nbrs.iter().enumerate() {
            let mut q = c;
            let mut k = m;
            for a in 0..d {
                q = q.offset(a, (k % 3) as i32 - 1);
                k /= 3;
            }
            assert_eq!(nb, pos(q).map(|i| i as usize), "{c:?} neighbour {m}");
        }
        visited += 1;
    });
    assert_eq!(visited, set.len());
    // Dilation (Chebyshev, clipped to the grid) against the dense dilation.
    for j in [1u32, 2] {
        let dil = g.dilate(j, n as usize).unwrap();
        let dense: BTreeSet<C> = box_coords::<C>(0, n)
            .into_iter()
            .filter(|&q| {
                set.iter()
                    .any(|&s| (0..d).all(|a| (q.get(a) - s.get(a)).abs() <= j as i32))
            })
            .collect();
        assert_eq!(
            dil.coords().collect::<Vec<_>>(),
            dense.into_iter().collect::<Vec<_>>()
        );
        // Values carried over where the node exists in both bands.
        let vals: Vec<f64> = (0..g.len()).map(|i| i as f64 + 0.5).collect();
        let moved = transfer_values(&g, &vals, &dil, -1.0).unwrap();
        for (c, v) in dil.coords().zip(&moved) {
            assert_eq!(*v, g.index(c).map_or(-1.0, |i| vals[i]));
        }
    }
}

fn set_strategy<C: DtCoord>(n: i32, max: usize) -> impl Strategy<Value = BTreeSet<C>> {
    let d = C::DIM;
    prop::collection::vec(prop::collection::vec(0..=n, d), 0..max)
        .prop_map(|v| v.into_iter().map(|a| C::from_slice(&a)).collect())
}

/// Sets with long runs and full cells: a random union of boxes.
fn boxes_strategy<C: DtCoord>(n: i32) -> impl Strategy<Value = BTreeSet<C>> {
    let d = C::DIM;
    prop::collection::vec((prop::collection::vec(0..=n, d), 0..4i32), 1..6).prop_map(move |bs| {
        let mut s = BTreeSet::new();
        for (lo, w) in bs {
            for c in box_coords::<C>(0, w) {
                let q: Vec<i32> = (0..d).map(|a| (lo[a] + c.get(a)).min(n)).collect();
                s.insert(C::from_slice(&q));
            }
        }
        s
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn random_sets_2d(s in set_strategy::<[i32; 2]>(9, 60)) {
        check_against_reference(&s, 9);
    }
    #[test]
    fn random_boxes_2d(s in boxes_strategy::<[i32; 2]>(11)) {
        check_against_reference(&s, 11);
    }
    #[test]
    fn random_sets_3d(s in set_strategy::<[i32; 3]>(5, 120)) {
        check_against_reference(&s, 5);
    }
    #[test]
    fn random_boxes_3d(s in boxes_strategy::<[i32; 3]>(6)) {
        check_against_reference(&s, 6);
    }
}

#[test]
fn implicit_band_equals_brute_force() {
    // A circle and a sphere, off-centre, with grids that are not powers of two.
    for (n, j) in [(37usize, 2u32), (64, 1), (100, 3)] {
        let g = Implicit {
            n,
            origin: [-0.5; 3],
            h: 1.0 / n as f64,
            half_width: j,
        };
        let f = |p: &[f64]| ((p[0] - 0.07).powi(2) + (p[1] + 0.11).powi(2)).sqrt() - 0.3;
        let band = DtGrid::<[i32; 2]>::from_implicit(&g, f).unwrap();
        let w = j as f64 * g.h;
        let want: Vec<[i32; 2]> = box_coords::<[i32; 2]>(0, n as i32)
            .into_iter()
            .filter(|c| {
                let p = [
                    g.origin[0] + g.h * c[0] as f64,
                    g.origin[1] + g.h * c[1] as f64,
                ];
                f(&p).abs() <= w
            })
            .collect();
        assert!(!want.is_empty());
        assert_eq!(band.coords().collect::<Vec<_>>(), want);
    }
    for (n, j) in [(29usize, 2u32), (40, 1)] {
        let g = Implicit {
            n,
            origin: [-0.5; 3],
            h: 1.0 / n as f64,
            half_width: j,
        };
        let f = |p: &[f64]| (p[0] * p[0] + (p[1] - 0.05).powi(2) + p[2] * p[2]).sqrt() - 1.0 / 3.0;
        let band = DtGrid::<[i32; 3]>::from_implicit(&g, f).unwrap();
        let w = j as f64 * g.h;
        let want: Vec<[i32; 3]> = box_coords::<[i32; 3]>(0, n as i32)
            .into_iter()
            .filter(|c| {
                let p: Vec<f64> = (0..3).map(|a| g.origin[a] + g.h * c[a] as f64).collect();
                f(&p).abs() <= w
            })
            .collect();
        assert_eq!(band.coords().collect::<Vec<_>>(), want);
    }
}

#[test]
fn sphere_band_memory_is_proportional_to_the_band() {
    // Index bytes per node of a sphere band stay near 1 and do not grow with the grid.
    let f = |p: &[f64]| (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() - 1.0 / 3.0;
    let mut per_node = Vec::new();
    for n in [128usize, 256] {
        let g = Implicit {
            n,
            origin: [-0.5; 3],
            h: 1.0 / n as f64,
            half_width: 2,
        };
        let band = DtGrid::<[i32; 3]>::from_implicit(&g, f).unwrap();
        let bytes = band.index_bytes() as f64 / band.len() as f64;
        per_node.push(bytes);
        // About 4πr²·(2j+1)/h² nodes.
        let expect = 4.0 * std::f64::consts::PI / 9.0 * 5.0 * (n * n) as f64;
        let ratio = band.len() as f64 / expect;
        assert!(
            (0.8..1.2).contains(&ratio),
            "n {n}: {} nodes, ratio {ratio}",
            band.len()
        );
    }
    assert!(per_node.iter().all(|&b| b < 2.5), "{per_node:?}");
    assert!(per_node[1] < per_node[0], "{per_node:?}");
}

#[test]
fn sign_change_seed_and_rebuild_follow_a_moved_circle() {
    // The band of one circle, the field of a shifted circle on it, rebuilt around the new zero
    // level: the new band equals the implicit band of the shifted circle dilated from its seed.
    let n = 80;
    let g = Implicit {
        n,
        origin: [-0.5; 3],
        h: 1.0 / n as f64,
        half_width: 4,
    };
    let f0 = |p: &[f64]| (p[0] * p[0] + p[1] * p[1]).sqrt() - 0.3;
    let f1 = |p: &[f64]| ((p[0] - 0.02) * (p[0] - 0.02) + p[1] * p[1]).sqrt() - 0.3;
    let band = DtGrid::<[i32; 2]>::from_implicit(&g, f0).unwrap();
    let pt = |c: [i32; 2]| {
        [
            g.origin[0] + g.h * c[0] as f64,
            g.origin[1] + g.h * c[1] as f64,
        ]
    };
    let u: Vec<f64> = band.coords().map(|c| f1(&pt(c))).collect();
    let seed = band.sign_change_seed(&u).unwrap();
    assert!(!seed.is_empty());
    for c in seed.coords() {
        // Every seed node is within one cell diagonal of the new zero level.
        assert!(f1(&pt(c)).abs() <= g.h * 2f64.sqrt() + 1e-12, "{c:?}");
    }
    let rebuilt = seed.dilate(2, n).unwrap();
    let moved = transfer_values(&band, &u, &rebuilt, f64::NAN).unwrap();
    for (c, v) in rebuilt.coords().zip(&moved) {
        // Seed within √2·h of the zero level, then 2 cells Chebyshev (at most 2√2·h).
        assert!(f1(&pt(c)).abs() <= 3.0 * 2f64.sqrt() * g.h + 1e-12, "{c:?}");
        if band.index(c).is_some() {
            assert_eq!(*v, f1(&pt(c)));
        } else {
            assert!(v.is_nan());
        }
    }
    // Every node within one cell of the new zero level is in the rebuilt band.
    let close = DtGrid::<[i32; 2]>::from_implicit(&Implicit { half_width: 1, ..g }, f1).unwrap();
    for c in close.coords() {
        assert!(rebuilt.index(c).is_some(), "{c:?}");
    }
}

#[test]
fn typed_errors() {
    let unsorted = DtGrid::<[i32; 2]>::from_sorted([[0, 1], [0, 0]]);
    assert!(matches!(unsorted, Err(Error::InvalidInput(_))));
    let repeated = DtGrid::<[i32; 3]>::from_sorted([[0, 1, 2], [0, 1, 2]]);
    assert!(matches!(repeated, Err(Error::InvalidInput(_))));
    let outside = DtGrid::<[i32; 2]>::from_sorted_in([[0, 1], [3, 11]], 10);
    assert!(matches!(outside, Err(Error::InvalidInput(_))));
    let negative = DtGrid::<[i32; 2]>::from_sorted_in([[-1, 1]], 10);
    assert!(matches!(negative, Err(Error::InvalidInput(_))));
    let huge = DtGrid::<[i32; 2]>::from_sorted([[0, i32::MAX]]);
    assert!(matches!(huge, Err(Error::InvalidInput(_))));
    let wide = Implicit {
        n: 8,
        origin: [0.0; 3],
        h: 0.1,
        half_width: 5,
    };
    let r = DtGrid::<[i32; 2]>::from_implicit(&wide, |p| p[0]);
    assert!(matches!(r, Err(Error::InvalidInput(_))));
    let bad_h = Implicit {
        n: 8,
        origin: [0.0; 3],
        h: f64::NAN,
        half_width: 1,
    };
    let r = DtGrid::<[i32; 2]>::from_implicit(&bad_h, |p| p[0]);
    assert!(matches!(r, Err(Error::InvalidInput(_))));
    let g = DtGrid::<[i32; 2]>::from_sorted_in([[0, 0], [5, 5]], 10).unwrap();
    assert!(matches!(g.dilate(11, 10), Err(Error::InvalidInput(_))));
    assert!(matches!(g.dilate(1, 4), Err(Error::InvalidInput(_))));
    assert!(matches!(
        transfer_values(&g, &[1.0], &g, 0.0),
        Err(Error::InvalidField { .. })
    ));
    assert!(matches!(
        g.sign_change_seed(&[]),
        Err(Error::InvalidField { .. })
    ));
    // The empty band.
    let e = DtGrid::<[i32; 3]>::from_sorted([]).unwrap();
    assert!(e.is_empty());
    assert_eq!(e.coords().count(), 0);
    assert_eq!(e.cells().count(), 0);
    assert_eq!(e.index([0, 0, 0]), None);
}
