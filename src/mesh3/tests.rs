use super::*;
use crate::error::MeshDefect;

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
