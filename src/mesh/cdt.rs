//! Initial meshes of polygonal domains ([`PolygonDomain`], validated in `polygon.rs`):
//! constrained Delaunay triangulation with Ruppert-style refinement (maximum area, minimum
//! angle) through `spade`, copied into a [`Mesh2`]. Loop segments are subdivided to at most the
//! loop's `h`; the angle criterion then grades the mesh away from fine loops. Corners are
//! flagged (and required) where a loop turns by more than 30 degrees.

use super::polygon::{classify, invalid, loop_area2, validate, LoopKind, PolygonDomain};
use super::{next, prev, Mesh2, NONE};
use crate::error::Result;
use crate::geom::{orient2d, DVec2};
use rstar::{primitives::GeomWithData, RTree};
use spade::{
    AngleLimit, ConstrainedDelaunayTriangulation, Point2, RefinementParameters, Triangulation,
};
use std::collections::{HashMap, HashSet};

/// Constrained Delaunay mesh of the polygon `outer` minus `holes` (outer edges labelled 1, hole
/// `k` labelled `k + 2`), refined to `max_area` and `min_angle_deg` when given.
pub fn from_polygon(
    outer: &[DVec2],
    holes: &[Vec<DVec2>],
    max_area: Option<f64>,
    min_angle_deg: Option<f64>,
) -> Result<Mesh2> {
    let mut d = PolygonDomain::new(outer.to_vec(), 1);
    for (k, h) in holes.iter().enumerate() {
        d = d.hole(h.clone(), k as i32 + 2);
    }
    d.max_area = max_area;
    d.min_angle_deg = min_angle_deg;
    d.mesh()
}

impl PolygonDomain {
    /// Meshes the domain: a constrained Delaunay triangulation of its loops (see the module
    /// documentation).
    pub fn mesh(&self) -> Result<Mesh2> {
        mesh_domain(self)
    }
}

/// Meshes the domain `d` (see the module documentation).
fn mesh_domain(d: &PolygonDomain) -> Result<Mesh2> {
    let loops = validate(d)?;
    // Vertices: each loop's points with subdivision points; constraint edges between them.
    let mut pts: Vec<DVec2> = Vec::new();
    let mut edges: Vec<[usize; 2]> = Vec::new();
    let mut corner = Vec::new();
    let mut label = Vec::new();
    for (k, l) in loops.iter().enumerate() {
        let start = pts.len();
        let n = l.len();
        for i in 0..n {
            let (a, b) = (l[i], l[(i + 1) % n]);
            let (u, w) = (a - l[(i + n - 1) % n], b - a);
            let turn = u.perp_dot(w).atan2(u.dot(w)).abs();
            corner.push(turn > 30f64.to_radians());
            label.push(d.loops[k].label);
            pts.push(a);
            let pieces = match d.loops[k].h {
                Some(h) => ((b - a).length() / h).ceil().max(1.0),
                None => 1.0,
            };
            if pieces > 1e7 {
                return Err(invalid(format!(
                    "loop {k}: target size too small for its length"
                )));
            }
            for s in 1..pieces as usize {
                corner.push(false);
                label.push(d.loops[k].label);
                pts.push(a + (b - a) * (s as f64 / pieces));
            }
        }
        let m = pts.len() - start;
        for i in 0..m {
            edges.push([start + i, start + (i + 1) % m]);
        }
    }
    let n_input = pts.len();
    let verts: Vec<Point2<f64>> = pts.iter().map(|p| Point2::new(p.x, p.y)).collect();
    let mut conflicts = 0usize;
    let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> =
        ConstrainedDelaunayTriangulation::try_bulk_load_cdt(verts, edges, |_| conflicts += 1)
            .map_err(|e| invalid(format!("triangulation failed: {e:?}")))?;
    if conflicts > 0 || cdt.num_vertices() != n_input {
        return Err(invalid(
            "loops overlap (duplicate points or intersecting segments after subdivision)".into(),
        ));
    }
    let has_interfaces = d
        .loops
        .iter()
        .any(|l| matches!(l.kind, LoopKind::Interface { .. }));
    if d.max_area.is_some() || d.min_angle_deg.is_some() {
        let outer_area = 0.5 * loop_area2(&loops[0]).abs();
        let estimate = d.max_area.map_or(0.0, |a| 4.0 * outer_area / a);
        if estimate > 5e7 {
            return Err(invalid(format!(
                "max_area {} would need about {estimate:.0} vertices",
                d.max_area.unwrap_or(0.0)
            )));
        }
        let cap = (estimate as usize).max(10 * n_input) + 1000;
        let mut params = RefinementParameters::<f64>::new()
            .with_angle_limit(AngleLimit::from_deg(d.min_angle_deg.unwrap_or(0.0)))
            .exclude_outer_faces(!has_interfaces)
            .with_max_additional_vertices(cap);
        if let Some(a) = d.max_area {
            params = params.with_max_allowed_area(a);
        }
        cdt.refine(params);
    }
    extract(d, &loops, &cdt, &corner, &label)
}

/// Copies the triangles inside the domain into a `Mesh2` with labels.
fn extract(
    d: &PolygonDomain,
    loops: &[Vec<DVec2>],
    cdt: &ConstrainedDelaunayTriangulation<Point2<f64>>,
    corner: &[bool],
    label: &[i32],
) -> Result<Mesh2> {
    let pos: Vec<DVec2> = cdt
        .vertices()
        .map(|v| {
            let p = v.position();
            DVec2::new(p.x, p.y)
        })
        .collect();
    let mut tris: Vec<[u32; 3]> = Vec::with_capacity(cdt.num_inner_faces());
    for f in cdt.inner_faces() {
        let mut t = f.vertices().map(|v| v.fix().index() as u32);
        if orient2d(pos[t[0] as usize], pos[t[1] as usize], pos[t[2] as usize]) < 0.0 {
            t.swap(1, 2);
        }
        tris.push(t);
    }
    let constraint: HashSet<(u32, u32)> = cdt
        .undirected_edges()
        .filter(|e| e.is_constraint_edge())
        .map(|e| {
            let [a, b] = e.vertices().map(|v| v.fix().index() as u32);
            (a.min(b), a.max(b))
        })
        .collect();
    // Regions: flood fill across non-constraint edges.
    let mut half: HashMap<(u32, u32), usize> = HashMap::with_capacity(3 * tris.len());
    for (t, tri) in tris.iter().enumerate() {
        for i in 0..3 {
            half.insert((tri[next(i)], tri[prev(i)]), t);
        }
    }
    let mut region = vec![usize::MAX; tris.len()];
    let mut region_ref: Vec<Option<i32>> = Vec::new();
    for seed in 0..tris.len() {
        if region[seed] != usize::MAX {
            continue;
        }
        let r = region_ref.len();
        let tri = tris[seed];
        let c = (pos[tri[0] as usize] + pos[tri[1] as usize] + pos[tri[2] as usize]) / 3.0;
        region_ref.push(classify(d, loops, c));
        region[seed] = r;
        let mut stack = vec![seed];
        while let Some(t) = stack.pop() {
            for i in 0..3 {
                let (a, b) = (tris[t][next(i)], tris[t][prev(i)]);
                if constraint.contains(&(a.min(b), a.max(b))) {
                    continue;
                }
                if let Some(&nb) = half.get(&(b, a)) {
                    if region[nb] == usize::MAX {
                        region[nb] = r;
                        stack.push(nb);
                    }
                }
            }
        }
    }
    // Keep the triangles of the domain; renumber vertices in spade order.
    let mut vmap = vec![NONE; pos.len()];
    let mut kept = Vec::new();
    let mut kept_ref = Vec::new();
    for (t, tri) in tris.iter().enumerate() {
        if let Some(r) = region_ref[region[t]] {
            kept.push(*tri);
            kept_ref.push(r);
            for &v in tri {
                vmap[v as usize] = 0;
            }
        }
    }
    let mut points = Vec::new();
    for (v, m) in vmap.iter_mut().enumerate() {
        if *m == 0 {
            *m = points.len() as u32;
            points.push(pos[v]);
        }
    }
    let old_of: Vec<usize> = (0..pos.len()).filter(|&v| vmap[v] != NONE).collect();
    let kept: Vec<[u32; 3]> = kept.iter().map(|t| t.map(|v| vmap[v as usize])).collect();
    let mut mesh = Mesh2::from_parts(points, kept, kept_ref)?;
    // Labels of constraint edges from the nearest input loop segment.
    let seg_label = SegmentLabels::new(d, loops);
    for ([a, b], t, i) in mesh.edges() {
        let (oa, ob) = (old_of[a as usize] as u32, old_of[b as usize] as u32);
        let (t, i) = (t as usize, i as usize);
        let lab = if constraint.contains(&(oa.min(ob), oa.max(ob))) {
            seg_label.at(0.5 * (mesh.points[a as usize] + mesh.points[b as usize]))
        } else {
            0
        };
        mesh.edge_ref[t][i] = lab;
        let nb = mesh.neighbours[t][i];
        if nb != NONE {
            if let Some(j) = mesh.mirror_edge(t, nb as usize) {
                mesh.edge_ref[nb as usize][j] = lab;
            }
        }
        if lab != 0 {
            mesh.vert_ref[a as usize] = lab;
            mesh.vert_ref[b as usize] = lab;
        }
    }
    for (new, &old) in old_of.iter().enumerate() {
        if old < corner.len() {
            mesh.corner[new] = corner[old];
            mesh.required[new] = corner[old];
            mesh.vert_ref[new] = label[old];
        }
    }
    mesh.check()?;
    Ok(mesh)
}

/// Nearest-segment lookup of loop labels.
struct SegmentLabels {
    tree: RTree<GeomWithData<rstar::primitives::Line<[f64; 2]>, i32>>,
}

impl SegmentLabels {
    fn new(d: &PolygonDomain, loops: &[Vec<DVec2>]) -> Self {
        let mut v = Vec::new();
        for (k, l) in loops.iter().enumerate() {
            for i in 0..l.len() {
                let (a, b) = (l[i], l[(i + 1) % l.len()]);
                v.push(GeomWithData::new(
                    rstar::primitives::Line::new(a.to_array(), b.to_array()),
                    d.loops[k].label,
                ));
            }
        }
        SegmentLabels {
            tree: RTree::bulk_load(v),
        }
    }

    fn at(&self, p: DVec2) -> i32 {
        self.tree
            .nearest_neighbor(p.to_array())
            .map_or(0, |s| s.data)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::circle_points;

    fn square(lo: f64, hi: f64) -> Vec<DVec2> {
        vec![
            DVec2::new(lo, lo),
            DVec2::new(hi, lo),
            DVec2::new(hi, hi),
            DVec2::new(lo, hi),
        ]
    }

    #[test]
    fn square_with_hole_area_and_labels() {
        let hole: Vec<DVec2> = square(0.4, 0.6).into_iter().rev().collect();
        let m = from_polygon(&square(0.0, 1.0), &[hole], Some(0.002), Some(25.0)).unwrap();
        m.check().unwrap();
        assert!((m.area() - 0.96).abs() < 1e-12, "area {}", m.area());
        assert!(m.live_tris().all(|t| m.tri_area(t) <= 0.002 * (1.0 + 1e-9)));
        let b = m.boundary_edges();
        let len = |l: i32| -> f64 {
            b.iter()
                .filter(|e| e.2 == l)
                .map(|e| (m.points[e.0 as usize] - m.points[e.1 as usize]).length())
                .sum()
        };
        assert!((len(1) - 4.0).abs() < 1e-12 && (len(2) - 0.8).abs() < 1e-12);
        assert_eq!(m.corner.iter().filter(|&&c| c).count(), 8);
        assert_eq!(m.boundary_loops().len(), 2);
        // Minimum angle (spade guarantees the limit away from input angles; here all are 90°).
        let min_angle = m
            .live_tris()
            .flat_map(|t| {
                let p = m.tri_points(t);
                (0..3).map(move |i| {
                    let (u, v) = (p[next(i)] - p[i], p[prev(i)] - p[i]);
                    u.perp_dot(v).atan2(u.dot(v)).to_degrees()
                })
            })
            .fold(180.0, f64::min);
        assert!(min_angle > 24.0, "min angle {min_angle}");
    }

    #[test]
    fn interface_circle_refined() {
        let c = DVec2::splat(0.5);
        let m = PolygonDomain::new(square(0.0, 1.0), 1)
            .interface(circle_points(c, 0.25, 64), 5, 7)
            .with_size(0.02)
            .with_min_angle(25.0)
            .mesh()
            .unwrap();
        m.check().unwrap();
        assert!((m.area() - 1.0).abs() < 1e-12);
        let inner: f64 = m
            .live_tris()
            .filter(|&t| m.tri_ref[t] == 7)
            .map(|t| m.tri_area(t))
            .sum();
        // Inscribed 64-gon of radius 0.25: (64/2) r^2 sin(2 pi / 64).
        let polygon = 32.0 * 0.0625 * (std::f64::consts::TAU / 64.0).sin();
        assert!((inner - polygon).abs() < 1e-12, "{inner} vs {polygon}");
        // Interface edges labelled 5, no longer than h.
        let iface: Vec<_> = m
            .edges()
            .into_iter()
            .filter(|&(_, t, i)| m.edge_ref[t as usize][i as usize] == 5)
            .collect();
        assert!(
            iface.len() >= 64
                && iface.iter().all(|&([a, b], _, _)| {
                    (m.points[a as usize] - m.points[b as usize]).length() <= 0.02 + 1e-12
                })
        );
        assert!(iface
            .iter()
            .all(|&(_, t, i)| m.neighbours[t as usize][i as usize] != NONE));
    }

    #[test]
    fn unrefined_polygon_uses_only_input_points() {
        let l = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(2.0, 0.0),
            DVec2::new(2.0, 1.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(1.0, 2.0),
            DVec2::new(0.0, 2.0),
            DVec2::new(0.0, 0.0),
        ];
        let m = from_polygon(&l, &[], None, None).unwrap();
        assert_eq!((m.n_points(), m.n_tris()), (6, 4));
        assert!((m.area() - 3.0).abs() < 1e-14);
        // The re-entrant corner turns by 90°: all six vertices are corners.
        assert_eq!(m.corner.iter().filter(|&&c| c).count(), 6);
    }
}
