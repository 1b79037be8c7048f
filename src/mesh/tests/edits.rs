//! The mesh edits through the public API, with the invariant checker after every edit: on a
//! planar grid (`Mesh2::check`) and on a closed surface in space (`TriMesh<DVec3>`,
//! `check_topology`), with a listener that records what each edit reports.

use crate::error::{Error, MeshDefect};
use crate::geom::{DVec2, DVec3};
use crate::mesh::{EditListener, GridPattern, Mesh2, TriMesh, NONE};

/// Records the events of the edits.
#[derive(Debug, Default)]
struct Events {
    vertices: Vec<u32>,
    moved: Vec<u32>,
    added: Vec<u32>,
    changed: Vec<u32>,
    removed: Vec<u32>,
}

impl EditListener for Events {
    fn vertex_added(&mut self, v: u32) {
        self.vertices.push(v);
    }
    fn vertex_moved(&mut self, v: u32) {
        self.moved.push(v);
    }
    fn triangle_added(&mut self, t: u32, _tri: [u32; 3]) {
        self.added.push(t);
    }
    fn triangle_changed(&mut self, t: u32, _tri: [u32; 3]) {
        self.changed.push(t);
    }
    fn triangle_removed(&mut self, t: u32) {
        self.removed.push(t);
    }
}

fn square(n: usize) -> Mesh2 {
    Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, n, n, GridPattern::UnionJack).unwrap()
}

/// The first interior edge `(t, i)` of the mesh.
fn interior_edge(m: &Mesh2) -> (u32, usize) {
    (0..m.n_tris())
        .flat_map(|t| (0..3).map(move |i| (t, i)))
        .find(|&(t, i)| m.neighbours[t][i] != NONE)
        .map(|(t, i)| (t as u32, i))
        .unwrap()
}

#[test]
fn split_edge_then_collapse_restores_a_valid_planar_mesh() {
    let mut m = square(2);
    let (t, i) = interior_edge(&m);
    let [a, b] = m.edge_vertices(t as usize, i);
    let mid = 0.5 * (m.points[a as usize] + m.points[b as usize]);
    let mut ev = Events::default();
    let v = m.add_vertex(mid, 0, &mut ev);
    let s = m.split_edge(t, i, v, &mut ev);
    m.check().unwrap();
    assert_eq!(m.n_live_tris(), 10);
    assert!((m.area() - 1.0).abs() < 1e-15);
    assert_eq!(ev.vertices, vec![v]);
    assert_eq!(ev.added, vec![s.t1, s.t3]);
    assert_eq!(ev.changed, vec![s.t, s.t2]);
    assert_eq!(m.vertex_fan(v).len(), 4);
    // Collapse the new vertex back onto an end of the edge.
    let fan = m.vertex_fan(v);
    let mut ev = Events::default();
    m.collapse_edge(v, a, &fan, &mut ev);
    m.check().unwrap();
    assert_eq!(m.n_live_tris(), 8);
    assert_eq!(m.vert_tri[v as usize], NONE);
    assert_eq!(ev.removed.len(), 2);
    assert!((m.area() - 1.0).abs() < 1e-15);
    m.compact();
    m.check().unwrap();
    assert_eq!(m.n_points(), 9);
}

#[test]
fn split_of_a_boundary_edge_keeps_its_label_on_both_halves() {
    let mut m = square(1);
    let (t, i) = (0..m.n_tris())
        .flat_map(|t| (0..3).map(move |i| (t, i)))
        .find(|&(t, i)| m.neighbours[t][i] == NONE && m.edge_ref[t][i] == 1)
        .unwrap();
    let [a, b] = m.edge_vertices(t, i);
    let mid = 0.5 * (m.points[a as usize] + m.points[b as usize]);
    let v = m.add_vertex(mid, 1, &mut ());
    let s = m.split_edge(t as u32, i, v, &mut ());
    m.check().unwrap();
    assert_eq!(s.t2, NONE);
    assert_eq!(s.t3, NONE);
    let bottom: Vec<i32> = m
        .boundary_edges()
        .into_iter()
        .filter(|e| e.0 == v || e.1 == v)
        .map(|e| e.2)
        .collect();
    assert_eq!(bottom, vec![1, 1]);
}

#[test]
fn split_triangle_flip_and_move_keep_the_mesh_valid() {
    let mut m = square(2);
    let c = m.tri_points(0).iter().fold(DVec2::ZERO, |s, &p| s + p) / 3.0;
    let mut ev = Events::default();
    let v = m.add_vertex(c, 0, &mut ev);
    let [t1, t2] = m.split_triangle(0, v, &mut ev);
    m.check().unwrap();
    assert_eq!(ev.added, vec![t1, t2]);
    assert_eq!(m.vertex_ring(v).len(), 3);
    // Flip an edge of the new vertex's fan that is an old interior edge of the grid.
    let (t, i) = (0..m.n_tris())
        .flat_map(|t| (0..3).map(move |i| (t, i)))
        .find(|&(t, i)| m.tris[t][i] == v && m.neighbours[t][i] != NONE)
        .unwrap();
    let mut ev = Events::default();
    let u = m.flip_edge(t as u32, i, &mut ev);
    m.check().unwrap();
    assert_eq!(ev.changed, vec![t as u32, u]);
    assert_eq!(m.vertex_ring(v).len(), 4);
    assert!((m.area() - 1.0).abs() < 1e-15);
    // Move the vertex a little inside its fan.
    let fan = m.vertex_fan(v);
    let mut ev = Events::default();
    m.move_vertex(v, c + DVec2::new(0.01, 0.0), &fan, &mut ev);
    m.check().unwrap();
    assert_eq!(ev.moved, vec![v]);
    assert_eq!(ev.changed, fan);
}

#[test]
fn fill_cavity_builds_the_star_of_a_new_vertex() {
    let mut m = square(3);
    let (t, i) = interior_edge(&m);
    let t2 = m.neighbours[t as usize][i];
    let [a, b] = m.edge_vertices(t as usize, i);
    let mid = 0.5 * (m.points[a as usize] + m.points[b as usize]);
    let cavity = [t, t2];
    let boundary = m.cavity_boundary(&cavity).unwrap();
    assert_eq!(boundary.len(), 4);
    let mut ev = Events::default();
    let v = m.add_vertex(mid, 0, &mut ev);
    let star = m.fill_cavity(v, &cavity, &boundary, &mut ev);
    m.check().unwrap();
    assert_eq!(star.len(), 4);
    assert_eq!(&star[..2], &cavity);
    assert_eq!(ev.added.len(), 2);
    assert_eq!(m.vertex_fan(v).len(), 4);
    assert!((m.area() - 1.0).abs() < 1e-15);
}

/// The regular octahedron: six unit points on the axes, eight outward triangles.
fn octahedron() -> TriMesh<DVec3> {
    let points = vec![
        DVec3::X,
        -DVec3::X,
        DVec3::Y,
        -DVec3::Y,
        DVec3::Z,
        -DVec3::Z,
    ];
    let mut tris = Vec::new();
    for (sx, x) in [(1.0, 0u32), (-1.0, 1)] {
        for (sy, y) in [(1.0, 2u32), (-1.0, 3)] {
            for (sz, z) in [(1.0, 4u32), (-1.0, 5)] {
                tris.push(if sx * sy * sz > 0.0 {
                    [x, y, z]
                } else {
                    [x, z, y]
                });
            }
        }
    }
    TriMesh::from_topology(points, tris).unwrap()
}

#[test]
fn octahedron_surface_reuses_the_topology_and_the_edits() {
    let mut m = octahedron();
    m.check_topology().unwrap();
    assert!(m.boundary_edges().is_empty());
    assert!(m.boundary_loops().is_empty());
    assert_eq!(m.edges().len(), 12);
    for v in 0..6 {
        assert_eq!(m.vertex_ring(v).len(), 4, "vertex {v}");
        assert!(!m.is_boundary_vertex(v));
    }
    // Split an edge at its midpoint, pushed out to the sphere: V - E + F stays 2.
    let (t, i) = (0, 0);
    let [a, b] = m.edge_vertices(t, i);
    let p = (m.points[a as usize] + m.points[b as usize]).normalize();
    let mut ev = Events::default();
    let v = m.add_vertex(p, 0, &mut ev);
    m.split_edge(t as u32, i, v, &mut ev);
    m.check_topology().unwrap();
    assert_eq!(ev.added.len(), 2);
    let (nv, ne, nf) = (m.n_points(), m.edges().len(), m.n_live_tris());
    assert_eq!((nv, ne, nf), (7, 15, 10));
    assert_eq!(m.vertex_ring(v).len(), 4);
    // Flip an edge not touching the new vertex, then collapse the new vertex away.
    let (tf, jf) = (0..m.n_tris())
        .flat_map(|t| (0..3).map(move |i| (t, i)))
        .find(|&(t, i)| {
            !m.tris[t].contains(&v) && !m.tris[m.neighbours[t][i] as usize].contains(&v)
        })
        .unwrap();
    let [fa, fb] = m.edge_vertices(tf, jf);
    let (ra, rb) = (m.vertex_ring(fa).len(), m.vertex_ring(fb).len());
    m.flip_edge(tf as u32, jf, &mut ());
    m.check_topology().unwrap();
    assert_eq!(m.vertex_ring(fa).len(), ra - 1);
    assert_eq!(m.vertex_ring(fb).len(), rb - 1);
    let fan = m.vertex_fan(v);
    m.collapse_edge(v, a, &fan, &mut ());
    m.check_topology().unwrap();
    assert_eq!(m.n_live_tris(), 8);
    m.compact();
    m.check_topology().unwrap();
    assert_eq!((m.n_points(), m.edges().len()), (6, 12));
}

#[test]
fn from_topology_rejects_inconsistent_orientation() {
    let m = octahedron();
    let mut tris = m.tris.clone();
    tris[3].swap(1, 2);
    match TriMesh::from_topology(m.points.clone(), tris) {
        Err(Error::InvalidMesh(MeshDefect::BadAdjacency { .. })) => {}
        other => panic!("expected an adjacency defect, got {other:?}"),
    }
}
