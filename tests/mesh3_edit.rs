//! The local edits of `EditMesh3`, each followed by the invariant check of both the editable
//! form and the compacted `Mesh3`, and the volume kept.

use anisomesh::geom::DVec3;
use anisomesh::mesh3::{EditMesh3, Mesh3, VertexKind};

fn cube(n: usize) -> EditMesh3 {
    let m = Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [n, n, n]).unwrap();
    EditMesh3::from_mesh(&m).unwrap()
}

fn valid(e: &EditMesh3) {
    e.check().unwrap();
    let (m, _) = e.to_mesh();
    m.check().unwrap();
    assert!((m.volume() - 1.0).abs() < 1e-12, "volume {}", m.volume());
}

fn edges(e: &EditMesh3) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    let mut nb = Vec::new();
    for a in 0..e.points.len() as u32 {
        e.vertex_neighbours(a, &mut nb);
        out.extend(nb.iter().filter(|&&b| b > a).map(|&b| (a, b)));
    }
    out
}

#[test]
fn split_every_edge_once() {
    let mut e = cube(2);
    let nb0 = e.bfaces.len();
    for (a, b) in edges(&e) {
        let p = 0.5 * (e.points[a as usize] + e.points[b as usize]);
        assert!(e.split_edge(a, b, p).is_some());
        valid(&e);
    }
    assert!(e.bfaces.len() > nb0);
    // Not an edge any more: refused, mesh unchanged.
    assert!(e.split_edge(0, 26, DVec3::splat(0.5)).is_none());
    valid(&e);
}

#[test]
fn collapses_keep_the_boundary() {
    let mut e = cube(3);
    let n_corner = |e: &EditMesh3| {
        [DVec3::ZERO, DVec3::ONE, DVec3::X, DVec3::Y, DVec3::Z]
            .iter()
            .filter(|&&c| {
                e.points
                    .iter()
                    .enumerate()
                    .any(|(v, &p)| p == c && e.alive(v as u32))
            })
            .count()
    };
    let mut done = 0;
    for (a, b) in edges(&e) {
        for (x, y) in [(a, b), (b, a)] {
            if e.alive(x) && e.alive(y) && e.collapse_edge(x, y) {
                done += 1;
                valid(&e);
            }
        }
    }
    assert!(done > 10, "{done} collapses");
    assert_eq!(n_corner(&e), 5, "corners are kept");
    // Every boundary vertex still lies on a face of the cube.
    for v in 0..e.points.len() as u32 {
        if e.alive(v) && e.vertex_kind(v) != VertexKind::Interior {
            let p = e.points[v as usize];
            assert!(p.to_array().iter().any(|&c| c == 0.0 || c == 1.0), "{p}");
        }
    }
}

#[test]
fn edge_removal_and_face_swap_roundtrip() {
    let mut e = cube(3);
    // Move the interior vertices off the grid so that the swaps are not degenerate.
    for v in 0..e.points.len() as u32 {
        let p = e.points[v as usize];
        let w = DVec3::new((7.3 * p.y).sin(), (5.1 * p.z).cos(), (3.7 * p.x).sin());
        e.move_vertex(v, p + 0.04 * w);
    }
    valid(&e);
    let mut removed = 0;
    let mut swapped = 0;
    for (a, b) in edges(&e) {
        if !(e.alive(a) && e.alive(b)) {
            continue;
        }
        if let Some((q, tets)) = e.best_edge_removal(a, b, f64::NEG_INFINITY, |_| 1.0, |_, _| true)
        {
            assert!(q > 0.0);
            e.replace_shell(a, b, &tets);
            removed += 1;
            valid(&e);
            // Swap a face of the new tetrahedra 2-3 and remove the edge it creates 3-2.
            for t in &tets {
                let mut f = [t[1], t[2], t[3]];
                f.sort_unstable();
                if let Some(new) = e.face_swap_check(f) {
                    e.face_swap_apply(f, new);
                    swapped += 1;
                    valid(&e);
                    let (d, x) = (new[0][0], new[0][1]);
                    let (_, back) = e
                        .best_edge_removal(d, x, f64::NEG_INFINITY, |_| 1.0, |_, _| true)
                        .unwrap();
                    assert_eq!(back.len(), 2);
                    e.replace_shell(d, x, &back);
                    valid(&e);
                    break;
                }
            }
        }
    }
    assert!(
        removed > 0 && swapped > 0,
        "{removed} removals, {swapped} swaps"
    );
}

#[test]
fn vertex_moves_respect_faces_and_ridges() {
    let mut e = cube(2);
    let centre = e
        .points
        .iter()
        .position(|&p| p == DVec3::splat(0.5))
        .unwrap() as u32;
    assert_eq!(e.vertex_kind(centre), VertexKind::Interior);
    assert!(e.move_vertex(centre, DVec3::new(0.55, 0.45, 0.5)));
    valid(&e);
    // Too far: a tetrahedron would invert.
    assert!(!e.move_vertex(centre, DVec3::new(1.5, 0.5, 0.5)));
    let face = e
        .points
        .iter()
        .position(|&p| p == DVec3::new(0.5, 0.5, 0.0))
        .unwrap() as u32;
    assert!(matches!(e.vertex_kind(face), VertexKind::Face(_)));
    assert!(e.move_vertex(face, DVec3::new(0.6, 0.4, 0.0)));
    assert!(
        !e.move_vertex(face, DVec3::new(0.6, 0.4, 0.01)),
        "off its plane"
    );
    let ridge = e
        .points
        .iter()
        .position(|&p| p == DVec3::new(0.5, 0.0, 0.0))
        .unwrap() as u32;
    assert_eq!(e.vertex_kind(ridge), VertexKind::Feature);
    assert!(!e.move_vertex(ridge, DVec3::new(0.55, 0.0, 0.0)));
    valid(&e);
}

#[test]
fn compaction_along_the_hilbert_curve_keeps_the_mesh() {
    let mut e = cube(3);
    for (a, b) in edges(&e).into_iter().take(40) {
        if e.alive(a) && e.alive(b) {
            e.collapse_edge(a, b);
        }
    }
    let order = anisomesh::mesh3::hilbert_order(&e.points, |v| e.alive(v as u32));
    let n = order.len();
    let old = e.compact(Some(&order));
    assert_eq!(old.len(), n);
    assert_eq!(e.points.len(), n);
    valid(&e);
}

#[test]
fn a_surface_without_volume_is_refused() {
    let m = Mesh3::default();
    assert!(EditMesh3::from_mesh(&m).is_ok());
    let bad = Mesh3::from_parts(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
        vec![[0, 1, 2, 3]],
        vec![0],
    );
    let mut flat = bad.clone();
    flat.points[3] = DVec3::new(0.3, 0.3, 0.0);
    assert!(EditMesh3::from_mesh(&flat).is_err());
    assert!(EditMesh3::from_mesh(&bad).is_ok());
}

/// The best of all triangulations of the ring `0..n` by enumeration: the largest worst
/// quality, `None` when none is valid (non-positive tetrahedra or an existing diagonal).
fn brute_best(e: &EditMesh3, a: u32, b: u32, ring: &[u32], i: usize, j: usize) -> Option<f64> {
    use anisomesh::metric::Sym3;
    if j < i + 2 {
        return Some(f64::INFINITY);
    }
    let n = ring.len();
    if !(i == 0 && j == n - 1) && e.is_edge(ring[i], ring[j]) {
        return None;
    }
    let q = |t: [u32; 4]| {
        let p = t.map(|v| e.points[v as usize]);
        anisomesh::adapt::mean_ratio(p, &[Sym3::iso(1.0); 4])
    };
    let mut best: Option<f64> = None;
    for k in i + 1..j {
        let up = [a, ring[i], ring[k], ring[j]];
        let down = [ring[i], ring[k], ring[j], b];
        let (qu, qd) = (q(up), q(down));
        if qu <= 0.0 || qd <= 0.0 {
            continue;
        }
        let (Some(l), Some(r)) = (
            brute_best(e, a, b, ring, i, k),
            brute_best(e, a, b, ring, k, j),
        ) else {
            continue;
        };
        let v = qu.min(qd).min(l).min(r);
        best = Some(best.map_or(v, |x: f64| x.max(v)));
    }
    best
}

#[test]
fn edge_removal_finds_the_best_triangulation() {
    use anisomesh::metric::Sym3;
    let mut e = cube(3);
    for v in 0..e.points.len() as u32 {
        let p = e.points[v as usize];
        let w = DVec3::new((7.3 * p.y).sin(), (5.1 * p.z).cos(), (3.7 * p.x).sin());
        e.move_vertex(v, p + 0.04 * w);
    }
    let q = |t: [u32; 4]| {
        let p = t.map(|v| e.points[v as usize]);
        anisomesh::adapt::mean_ratio(p, &[Sym3::iso(1.0); 4])
    };
    let mut compared = 0;
    for (a, b) in edges(&e) {
        let Some(ring) = e.edge_ring(a, b) else {
            continue;
        };
        let brute = brute_best(&e, a, b, &ring, 0, ring.len() - 1);
        let dp = e.best_edge_removal(a, b, f64::NEG_INFINITY, q, |_, _| true);
        assert_eq!(
            brute,
            dp.as_ref().map(|x| x.0),
            "edge {a}-{b}, ring {ring:?}"
        );
        if let Some((best, tets)) = dp {
            compared += 1;
            assert_eq!(tets.len(), 2 * ring.len() - 4);
            let worst = tets.iter().map(|&t| q(t)).fold(f64::INFINITY, f64::min);
            assert_eq!(worst, best);
            // A floor at the optimum leaves nothing; just below it, the same optimum.
            assert!(e.best_edge_removal(a, b, best, q, |_, _| true).is_none());
            let again = e.best_edge_removal(a, b, best * (1.0 - 1e-9), q, |_, _| true);
            assert_eq!(again.map(|x| x.0), Some(best));
        }
    }
    assert!(compared > 10, "{compared} edges compared");
}

/// Every cached value left after an edit belongs to a tetrahedron that the edit did not touch:
/// same slot, same vertices, no vertex moved.
#[test]
fn edits_reset_the_cache_of_what_they_change() {
    let mut e = cube(3);
    let mut seed = 12345u64;
    let mut next = |n: usize| {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 33) as usize % n
    };
    for step in 0..200 {
        e.cache.iter_mut().for_each(|c| *c = 1.0);
        let (tets, points) = (e.tets.clone(), e.points.clone());
        let es = edges(&e);
        let (a, b) = es[next(es.len())];
        let (pa, pb) = (e.points[a as usize], e.points[b as usize]);
        match step % 4 {
            0 => {
                e.split_edge(a, b, 0.5 * (pa + pb));
            }
            1 => {
                e.collapse_edge(a, b);
            }
            2 => {
                if let Some((_, new)) =
                    e.best_edge_removal(a, b, f64::NEG_INFINITY, |_| 1.0, |_, _| true)
                {
                    e.replace_shell(a, b, &new);
                }
            }
            _ => {
                e.move_vertex(a, pa + 0.1 * (pb - pa));
            }
        }
        e.check().unwrap();
        assert_eq!(e.cache.len(), e.tets.len());
        for (t, &c) in e.cache.iter().enumerate() {
            if c.is_nan() || e.tets[t][0] == u32::MAX {
                continue;
            }
            assert!(
                t < tets.len() && e.tets[t] == tets[t],
                "step {step}: slot {t}"
            );
            for v in e.tets[t] {
                assert_eq!(e.points[v as usize], points[v as usize], "step {step}");
            }
        }
    }
}

/// The per-tetrahedron stamps: a tetrahedron carries the time of its creation or of its last
/// vertex move; the others keep theirs, through compaction too; a move also resets the cache.
#[test]
fn tetrahedron_stamps_mark_exactly_the_changed_tetrahedra() {
    let mut e = cube(3);
    assert!(e.tet_stamp.iter().all(|&s| s == 0));
    e.cache.iter_mut().for_each(|c| *c = 1.0);
    let (a, b) = edges(&e)[5];
    e.now = 7;
    let before: Vec<[u32; 4]> = e.tets.clone();
    let p = 0.5 * (e.points[a as usize] + e.points[b as usize]);
    let m = e.split_edge(a, b, p).unwrap();
    for (t, tet) in e.tets.iter().enumerate() {
        let new = tet.contains(&m);
        assert_eq!(e.tet_stamp[t] == 7, new, "tet {t}");
        assert_eq!(e.cache[t].is_nan(), new, "tet {t}");
        if !new {
            assert_eq!(*tet, before[t]);
        }
    }
    // Move an interior vertex a little: its ball gets the new time and loses its cache.
    e.now = 9;
    let v = (0..e.points.len() as u32)
        .find(|&v| !e.on_boundary[v as usize] && v != m && e.alive(v))
        .unwrap();
    assert!(e.move_vertex(v, e.points[v as usize] + DVec3::splat(1e-3)));
    for (t, tet) in e.tets.iter().enumerate() {
        if tet.contains(&v) {
            assert_eq!(e.tet_stamp[t], 9);
            assert!(e.cache[t].is_nan());
        } else {
            assert!(e.tet_stamp[t] <= 7);
        }
    }
    let n9: usize = e.tet_stamp.iter().filter(|&&s| s == 9).count();
    let n7: usize = e.tet_stamp.iter().filter(|&&s| s == 7).count();
    e.compact(None);
    assert_eq!(e.tet_stamp.len(), e.tets.len());
    assert_eq!(e.tet_stamp.iter().filter(|&&s| s == 9).count(), n9);
    assert_eq!(e.tet_stamp.iter().filter(|&&s| s == 7).count(), n7);
    valid(&e);
}
