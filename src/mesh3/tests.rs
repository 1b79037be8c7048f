use super::*;
use crate::error::MeshDefect;
use crate::mesh::NONE;

#[test]
fn kuhn_box_is_valid() {
    let m = Mesh3::kuhn_box(DVec3::splat(-1.0), DVec3::splat(1.0), [3, 2, 2]).unwrap();
    m.check().unwrap();
    assert_eq!(m.n_tets(), 6 * 12);
    assert!((m.volume() - 8.0).abs() < 1e-13);
}

#[test]
fn three_uniform_bisections_halve_the_mesh() {
    let mut m = Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [2, 2, 2]).unwrap();
    for _ in 0..3 {
        let all = vec![true; m.n_tets()];
        m.refine(&all);
        m.check().unwrap();
    }
    assert_eq!(m.n_tets(), 8 * 48);
    assert_eq!(m.n_points(), 125);
    assert!((m.volume() - 1.0).abs() < 1e-13);
}

#[test]
fn local_refinement_is_conforming() {
    let mut m = Mesh3::kuhn_box(DVec3::splat(-1.0), DVec3::splat(1.0), [3, 3, 3]).unwrap();
    let sphere = |p: DVec3| p.length() - 0.5;
    m.refine_near(sphere, 0.1, 9);
    m.check().unwrap();
    assert!((m.volume() - 8.0).abs() < 1e-10, "volume {}", m.volume());
    // Near the sphere every tetrahedron has 9 bisections; far away fewer.
    let g_max = *m.generation.iter().max().unwrap();
    let g_min = *m.generation.iter().min().unwrap();
    assert_eq!(g_max, 9);
    assert!(g_min < 9);
    let (off, adj) = m.v2v();
    assert_eq!(off.len(), m.n_points() + 1);
    assert!(adj.len() > 2 * m.n_points());
}

#[test]
fn check_detects_a_hanging_node() {
    let mut m = Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [1, 1, 1]).unwrap();
    // Bisect one tetrahedron without closure.
    let (o, _) = m.maubach[0];
    let z = 0.5 * (m.points[o[0] as usize] + m.points[o[3] as usize]);
    m.points.push(z);
    let zi = (m.points.len() - 1) as u32;
    let c1 = [o[0], o[1], o[2], zi];
    let c2 = [o[1], o[2], o[3], zi];
    m.maubach[0] = (c1, 2);
    m.tets[0] = m.oriented(c1);
    m.maubach.push((c2, 2));
    m.tets.push(m.oriented(c2));
    m.generation.push(1);
    assert!(matches!(
        m.check(),
        Err(crate::Error::InvalidMesh(MeshDefect::HangingVertex { .. }))
    ));
}

#[test]
fn neighbours_and_face_labels() {
    let mut m = Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [2, 1, 1]).unwrap();
    m.check().unwrap();
    // 6 tetrahedra per cube, 2 boundary triangles per cube side: 2 (4 + 2 + 2 + ...) sides.
    let boundary: Vec<_> = m.boundary_faces().collect();
    assert_eq!(boundary.len(), 2 * (2 * 2 + 2 * 2 + 2));
    let mut per_label = [0usize; 7];
    for &(t, i) in &boundary {
        per_label[m.face_ref[t][i] as usize] += 1;
    }
    assert_eq!(per_label, [0, 2, 2, 4, 4, 4, 4]);
    // Refinement keeps the labels on the sides and the adjacency consistent.
    m.tet_ref[0] = 7;
    let marked: Vec<bool> = (0..m.n_tets()).map(|t| t % 2 == 0).collect();
    m.refine(&marked);
    m.check().unwrap();
    let mut per_label = [0usize; 7];
    for (t, i) in m.boundary_faces() {
        let l = m.face_ref[t][i] as usize;
        assert!(l >= 1, "unlabelled boundary face");
        per_label[l] += 1;
        // The face lies on the side its label names.
        let (axis, hi) = ((l - 1) / 2, (l - 1) % 2 == 1);
        let want = if hi { 1.0 } else { 0.0 };
        for v in m.face_vertices(t, i) {
            assert_eq!(m.points[v as usize][axis], want);
        }
    }
    assert!(per_label[1..].iter().all(|&c| c >= 2), "{per_label:?}");
    assert!(m.tet_ref.iter().filter(|&&r| r == 7).count() >= 2);
    // A broken adjacency or label is reported.
    let mut bad = m.clone();
    let (t, i) = (0, (0..4).find(|&i| m.neighbours[0][i] != NONE).unwrap());
    bad.neighbours[t][i] = NONE;
    assert!(matches!(
        bad.check(),
        Err(crate::Error::InvalidMesh(MeshDefect::BadAdjacency { .. }))
    ));
    let mut bad = m.clone();
    bad.face_ref[t][i] = 9;
    assert!(matches!(
        bad.check(),
        Err(crate::Error::InvalidMesh(MeshDefect::BadLabel { .. }))
    ));
}

#[test]
fn moves_in_an_axis_plane_keep_the_coordinate_exactly() {
    use super::edit::{in_plane, onto_plane};
    // A plane y = 0.3 whose normal came out of a cross product with a rounding residue.
    let p0 = DVec3::new(0.1, 0.3, 0.7);
    let n = DVec3::new(1e-17, -1.0, 3e-18);
    let mut p = p0;
    for k in 0..1000 {
        let d = DVec3::new(0.013 * (k as f64).sin(), 0.01, -0.007 * (k as f64).cos());
        p = onto_plane(p, n, p + d);
        assert_eq!(p.y, 0.3);
        assert!(in_plane(p0, n, p));
    }
    // One unit in the last place off the plane: refused (a tolerance of 1e-12 accepted it).
    assert!(!in_plane(p0, n, p + DVec3::new(0.0, 1e-16, 0.0)));
    // An oblique plane: projected to rounding.
    let n = DVec3::new(1.0, 2.0, 2.0) / 3.0;
    let q = onto_plane(p0, n, DVec3::new(1.0, -2.0, 0.5));
    assert!((q - p0).dot(n).abs() < 1e-14);
    assert!(in_plane(p0, n, q));
}
