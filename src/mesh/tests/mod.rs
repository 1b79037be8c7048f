use super::*;

mod edits;
use crate::error::{Error, MeshDefect};
use crate::geom::DVec2;

fn unit_square(n: usize, pattern: GridPattern) -> Mesh2 {
    Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, n, n, pattern).unwrap()
}

#[test]
fn grids_of_every_pattern_pass_check_and_have_unit_area() {
    for pattern in [
        GridPattern::Right,
        GridPattern::Left,
        GridPattern::UnionJack,
        GridPattern::CrissCross,
    ] {
        let m = unit_square(7, pattern);
        m.check().unwrap();
        assert!((m.area() - 1.0).abs() < 1e-13, "{pattern:?}");
        let per_cell = if pattern == GridPattern::CrissCross {
            4
        } else {
            2
        };
        assert_eq!(m.n_tris(), per_cell * 49);
        // Euler: V - E + F = 1 for a disk.
        let e = m.edges().len();
        assert_eq!(m.n_points() as i64 - e as i64 + m.n_tris() as i64, 1);
        // Boundary labels 1..4 each cover a unit length.
        for label in 1..=4 {
            let len: f64 = m
                .boundary_edges()
                .iter()
                .filter(|e| e.2 == label)
                .map(|e| (m.points[e.0 as usize] - m.points[e.1 as usize]).length())
                .sum();
            assert!((len - 1.0).abs() < 1e-13, "label {label}: {len}");
        }
    }
}

#[test]
fn rings_fans_and_loops() {
    let m = unit_square(4, GridPattern::Right);
    // Interior vertex (1,1): 6 triangles, 6 neighbours.
    let v = 6; // grid vertex (1, 1)
    assert_eq!(m.vertex_fan(v).len(), 6);
    assert_eq!(m.vertex_ring(v).len(), 6);
    assert!(!m.is_boundary_vertex(v));
    // Corner (1,0): one triangle, two neighbours.
    assert_eq!(m.vertex_fan(4).len(), 1);
    assert_eq!(m.vertex_ring(4).len(), 2);
    assert_eq!(m.vertex_ring(0).len(), 3);
    assert!(m.is_boundary_vertex(0));
    // Patch of two rings around an interior vertex.
    assert!(m.vertex_patch(12, 2).len() >= 12);
    let loops = m.boundary_loops();
    assert_eq!(loops.len(), 1);
    assert_eq!(loops[0].len(), 16);
    let (off, adj) = m.v2v();
    assert_eq!(off[v as usize + 1] - off[v as usize], 6);
    assert_eq!(adj.len(), 2 * m.edges().len());
}

#[test]
fn v2v_lists_each_ring_once_sorted_and_skips_deleted_triangles() {
    let mut m = unit_square(7, GridPattern::UnionJack);
    // Tombstones and an unused vertex, as the adaptation leaves them.
    for t in [3, 17, 40] {
        m.tris[t] = [NONE; 3];
    }
    m.points.push(DVec2::new(2.0, 2.0));
    let (off, adj) = m.v2v();
    assert_eq!(off.len(), m.n_points() + 1);
    // Reference: every directed edge of a live triangle, sorted, deduplicated.
    let mut pairs = Vec::new();
    for t in m.live_tris() {
        let tri = m.tris[t];
        for i in 0..3 {
            pairs.push((tri[i], tri[next(i)]));
            pairs.push((tri[next(i)], tri[i]));
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    let mut got = Vec::new();
    for v in 0..m.n_points() {
        for &w in &adj[off[v]..off[v + 1]] {
            got.push((v as u32, w));
        }
    }
    assert_eq!(got, pairs);
    let last = m.n_points() - 1;
    assert_eq!(
        off[last],
        off[last + 1],
        "an unused vertex has an empty ring"
    );
}

#[test]
fn locate_inside_and_outside() {
    let m = unit_square(10, GridPattern::UnionJack);
    for &(x, y) in &[
        (0.05, 0.05),
        (0.93, 0.41),
        (0.5, 0.5),
        (1.0, 1.0),
        (0.0, 0.37),
    ] {
        let loc = m.locate(DVec2::new(x, y), 0);
        match loc {
            Location::Inside { tri, bary } => {
                let [a, b, c] = m.tri_points(tri as usize);
                let q = bary[0] * a + bary[1] * b + bary[2] * c;
                assert!((q - DVec2::new(x, y)).length() < 1e-13);
                assert!(bary.iter().all(|&l| l >= -1e-14));
            }
            _ => panic!("({x},{y}) not found"),
        }
    }
    assert!(matches!(
        m.locate(DVec2::new(1.5, 0.5), 3),
        Location::Outside { .. }
    ));
}

#[test]
fn compact_removes_tombstones_and_orphans() {
    let mut m = unit_square(3, GridPattern::Right);
    let n0 = m.n_tris();
    // Delete the two triangles of the top-right cell (touching the corner vertex 15).
    let corner = 15u32;
    let fan = m.vertex_fan(corner);
    for &t in &fan {
        let t = t as usize;
        for i in 0..3 {
            let nb = m.neighbours[t][i];
            if nb != NONE {
                let j = m.mirror_edge(t, nb as usize).unwrap();
                m.neighbours[nb as usize][j] = NONE;
                m.edge_ref[nb as usize][j] = 1;
            }
        }
        m.tris[t] = [NONE; 3];
    }
    let map = m.compact();
    assert_eq!(map[corner as usize], NONE);
    assert_eq!(m.n_tris(), n0 - fan.len());
    m.check().unwrap();
}

fn defect(r: crate::error::Result<Mesh2>) -> MeshDefect {
    match r {
        Err(Error::InvalidMesh(d)) => d,
        other => panic!("expected a mesh defect, got {other:?}"),
    }
}

#[test]
fn bad_triangles_are_rejected_with_the_offending_entity() {
    let p = vec![
        DVec2::new(0.0, 0.0),
        DVec2::new(1.0, 0.0),
        DVec2::new(0.0, 1.0),
        DVec2::new(1.0, 1.0),
    ];
    assert!(matches!(
        defect(Mesh2::from_triangles(p.clone(), vec![[0, 1, 2], [2, 1, 7]])),
        MeshDefect::IndexOutOfRange {
            tri: 1,
            vertex: 7,
            ..
        }
    ));
    assert!(matches!(
        defect(Mesh2::from_triangles(p.clone(), vec![[0, 1, 2], [1, 2, 3]])),
        MeshDefect::InvertedTriangle { tri: 1, .. }
    ));
    assert!(matches!(
        defect(Mesh2::from_triangles(p.clone(), vec![[0, 1, 2], [0, 1, 2]])),
        MeshDefect::DuplicateTriangle {
            first: 0,
            second: 1
        }
    ));
    assert!(matches!(
        defect(Mesh2::from_triangles(p.clone(), vec![[0, 1, 1]])),
        MeshDefect::RepeatedVertex { tri: 0 }
    ));
    let mut nanp = p.clone();
    nanp[2].y = f64::NAN;
    assert!(matches!(
        defect(Mesh2::from_triangles(nanp, vec![[0, 1, 2]])),
        MeshDefect::NonFiniteCoordinate { vertex: 2 }
    ));
    let col = vec![DVec2::ZERO, DVec2::X, DVec2::new(2.0, 0.0)];
    assert!(matches!(
        defect(Mesh2::from_triangles(col, vec![[0, 1, 2]])),
        MeshDefect::DegenerateTriangle { tri: 0 }
    ));
}

#[test]
fn check_finds_hanging_vertices_and_duplicates() {
    // Two triangles below a long edge, one above spanning it: a T-junction at (0.5, 0).
    let p = vec![
        DVec2::new(0.0, 0.0),
        DVec2::new(1.0, 0.0),
        DVec2::new(0.5, 0.0),
        DVec2::new(0.5, 1.0),
        DVec2::new(0.5, -1.0),
    ];
    let m = Mesh2::from_triangles(p, vec![[0, 1, 3], [0, 4, 2], [2, 4, 1]]).unwrap();
    let r = m.check();
    assert!(
        matches!(
            r,
            Err(Error::InvalidMesh(
                MeshDefect::HangingVertex { vertex: 2, .. }
                    | MeshDefect::BadVertexData { vertex: 0, .. }
            ))
        ),
        "{r:?}"
    );
    let m = unit_square(2, GridPattern::Right);
    m.check().unwrap();
    let mut m2 = unit_square(2, GridPattern::Right);
    m2.points.push(m2.points[0]);
    m2.vert_ref.push(0);
    m2.corner.push(false);
    m2.required.push(false);
    m2.vert_tri.push(NONE);
    m2.check().unwrap(); // an unreferenced duplicate is harmless
    m2.neighbours[0][0] = NONE;
    assert!(matches!(
        m2.check(),
        Err(Error::InvalidMesh(MeshDefect::BadAdjacency { .. }))
    ));
}
