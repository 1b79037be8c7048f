//! Each adaptation operator on small meshes, with `check()` after every operation: boundaries,
//! labels and corners preserved, areas preserved by split/flip/collapse on straight boundaries.

use super::{aniso, params, rel, square};
use crate::adapt::params::MetricInterpolation;
use crate::adapt::tri::Ctx;
use crate::adapt::tri::{collapse, flip, insert, refine, smooth, split};
use crate::adapt::NoSource;
use crate::geom::DVec2;
use crate::mesh::{GridPattern, Mesh2, NONE};
use crate::metric::Sym2;

#[test]
fn split_every_long_edge_keeps_mesh_valid_area_and_labels() {
    let mut mesh = square(3);
    let a0 = mesh.area();
    let mut metric = vec![aniso(0.05, 0.2); mesh.n_points()];
    let mut u: Vec<Vec<f64>> = vec![mesh.points.iter().map(|p| 2.0 * p.x - p.y).collect()];
    let labels0: Vec<i32> = {
        let mut l: Vec<i32> = mesh.boundary_edges().iter().map(|e| e.2).collect();
        l.sort();
        l.dedup();
        l
    };
    let mut ctx = Ctx::new(&mut mesh, &mut metric, &mut u, None, params());
    let mut total = 0;
    for _ in 0..20 {
        let n = refine::pass(&mut ctx);
        ctx.mesh.check().unwrap();
        total += n;
        if n == 0 {
            break;
        }
    }
    assert!(total > 20, "only {total} splits");
    // Every edge now short enough.
    for (e, _, _) in ctx.mesh.edges() {
        let (a, b) = (e[0] as usize, e[1] as usize);
        let d = ctx.mesh.points[b] - ctx.mesh.points[a];
        assert!(
            d.x.abs() <= 0.05 * 1.5 && d.y.abs() <= 0.2 * 1.5,
            "edge {d}"
        );
    }
    drop(ctx);
    assert!(rel(mesh.area(), a0) < 1e-13);
    // Linear field reproduced exactly at new vertices.
    for (v, p) in mesh.points.iter().enumerate() {
        assert!((u[0][v] - (2.0 * p.x - p.y)).abs() < 1e-14);
    }
    // Boundary vertices lie on the square, labels unchanged, corners kept.
    let mut labels: Vec<i32> = mesh.boundary_edges().iter().map(|e| e.2).collect();
    labels.sort();
    labels.dedup();
    assert_eq!(labels, labels0);
    for (a, b, lab) in mesh.boundary_edges() {
        for v in [a, b] {
            let p = mesh.points[v as usize];
            let on = p.x == 0.0 || p.x == 1.0 || p.y == 0.0 || p.y == 1.0;
            assert!(on, "boundary vertex {v} at {p} off the square");
        }
        let m = 0.5 * (mesh.points[a as usize] + mesh.points[b as usize]);
        let expect = if m.y == 0.0 {
            1
        } else if m.x == 1.0 {
            2
        } else if m.y == 1.0 {
            3
        } else {
            4
        };
        assert_eq!(lab, expect);
    }
    assert_eq!(mesh.corner.iter().filter(|&&c| c).count(), 4);
}

#[test]
fn split_of_a_boundary_edge_puts_the_vertex_on_it_with_its_label() {
    let mut mesh = square(1);
    let mut metric = vec![aniso(0.3, 10.0); mesh.n_points()];
    let mut fields: Vec<Vec<f64>> = vec![];
    let mut ctx = Ctx::new(&mut mesh, &mut metric, &mut fields, None, params());
    // Find the bottom edge.
    let (t, i) = (0..ctx.mesh.n_tris())
        .flat_map(|t| (0..3).map(move |i| (t, i)))
        .find(|&(t, i)| ctx.mesh.neighbours[t][i] == NONE && ctx.mesh.edge_ref[t][i] == 1)
        .unwrap();
    let plan = split::check(&ctx, t as u32, i).expect("bottom edge is long in x");
    let v = split::apply(&mut ctx, &plan);
    ctx.mesh.check().unwrap();
    assert_eq!(ctx.mesh.points[v as usize].y, 0.0);
    assert_eq!(ctx.mesh.vert_ref[v as usize], 1);
    assert!((ctx.mesh.area() - 1.0).abs() < 1e-15);
}

#[test]
fn collapse_removes_short_edges_never_corners_and_keeps_area() {
    let mut mesh = square(8);
    let a0 = mesh.area();
    let mut metric = vec![Sym2::iso(0.4); mesh.n_points()];
    let mut f: Vec<Vec<f64>> = vec![mesh.points.iter().map(|p| p.x).collect()];
    let mut ctx = Ctx::new(&mut mesh, &mut metric, &mut f, None, params());
    let mut total = 0;
    for _ in 0..10 {
        let n = collapse::pass(&mut ctx);
        ctx.mesh.check().unwrap();
        flip::pass(&mut ctx);
        ctx.mesh.check().unwrap();
        total += n;
        if n == 0 {
            break;
        }
    }
    assert!(total > 40, "only {total} collapses");
    let corners = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
    for c in corners {
        let v = ctx.mesh.points.iter().position(|&p| p == c).unwrap();
        assert!(ctx.mesh.vert_tri[v] != NONE, "corner {c} was removed");
    }
    drop(ctx);
    assert!(rel(mesh.area(), a0) < 1e-13);
    let live: usize = mesh.vert_tri.iter().filter(|&&t| t != NONE).count();
    assert!(live < 40, "{live} vertices left");
    // Boundary vertices only slid along their own side.
    for (a, b, lab) in mesh.boundary_edges() {
        for v in [a, b] {
            let p = mesh.points[v as usize];
            let ok = match lab {
                1 => p.y == 0.0,
                2 => p.x == 1.0,
                3 => p.y == 1.0,
                _ => p.x == 0.0,
            };
            assert!(ok, "vertex {v} at {p} is not on side {lab}");
        }
    }
}

#[test]
fn collapse_refuses_corners_and_cross_curve_moves() {
    let mut mesh = square(2);
    let mut metric = vec![Sym2::iso(10.0); mesh.n_points()];
    let mut f: Vec<Vec<f64>> = vec![];
    let mut ctx = Ctx::new(&mut mesh, &mut metric, &mut f, None, params());
    let id = |i: u32, j: u32| j * 3 + i;
    // Corner (0,0) onto (1,0): refused.
    assert!(collapse::check(&mut ctx, id(0, 0), id(1, 0)).is_none());
    // Bottom mid-vertex onto the centre (off its curve): refused.
    assert!(collapse::check(&mut ctx, id(1, 0), id(1, 1)).is_none());
    // Bottom mid-vertex along the bottom onto a corner: allowed.
    let plan = collapse::check(&mut ctx, id(1, 0), id(0, 0)).expect("along its curve");
    collapse::apply(&mut ctx, &plan);
    ctx.mesh.check().unwrap();
    assert!((ctx.mesh.area() - 1.0).abs() < 1e-15);
}

#[test]
fn flip_improves_the_worse_quality_and_keeps_area() {
    // A square split along the "wrong" diagonal for a metric stretched along (1, 1).
    let pts = vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
    let mut mesh = Mesh2::from_triangles(pts, vec![[0, 1, 3], [1, 2, 3]]).unwrap();
    let d = DVec2::new(1.0, 1.0).normalize();
    let m = Sym2::from_eigen([1.0 / 2.0, 1.0 / 0.4], [d, d.perp()]);
    let mut metric = vec![m; 4];
    let mut f: Vec<Vec<f64>> = vec![];
    let mut ctx = Ctx::new(&mut mesh, &mut metric, &mut f, Some(&NoSource), params());
    assert_eq!(flip::pass(&mut ctx), 1);
    ctx.mesh.check().unwrap();
    assert_eq!(flip::pass(&mut ctx), 0);
    drop(ctx);
    assert!((mesh.area() - 1.0).abs() < 1e-15);
    let has_diag = mesh.edges().iter().any(|(e, _, _)| *e == [0, 2]);
    assert!(has_diag);
}

#[test]
fn smoothing_recentres_a_perturbed_vertex() {
    let mut mesh =
        Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 2, 2, GridPattern::CrissCross).unwrap();
    // Vertex 4 is the centre of the grid ((1,1) of the 3x3 points).
    let c = 4usize;
    assert_eq!(mesh.points[c], DVec2::new(0.5, 0.5));
    mesh.points[c] = DVec2::new(0.62, 0.41);
    mesh.check().unwrap();
    let mut metric = vec![Sym2::iso(0.5); mesh.n_points()];
    let mut f: Vec<Vec<f64>> = vec![mesh.points.iter().map(|p| p.x + p.y).collect()];
    let mut ctx = Ctx::new(&mut mesh, &mut metric, &mut f, None, params());
    for _ in 0..30 {
        smooth::pass(&mut ctx);
        ctx.mesh.check().unwrap();
    }
    let p = ctx.mesh.points[c];
    assert!((p - DVec2::splat(0.5)).length() < 0.03, "centre at {p}");
    drop(ctx);
    for (v, p) in mesh.points.iter().enumerate() {
        assert!(
            (f[0][v] - (p.x + p.y)).abs() < 1e-12,
            "field not transported at {v}"
        );
    }
}

#[test]
fn delaunay_insertion_builds_a_valid_star_and_keeps_area() {
    let mut mesh = square(6);
    let a0 = mesh.area();
    // Stretched metric along (1, 1): the metric circumcircles are long ellipses, so cavities
    // hold more than the two triangles of the edge.
    let d = DVec2::new(1.0, 1.0).normalize();
    let m = Sym2::from_eigen([1.0 / 0.3f64.powi(2), 1.0 / 0.02f64.powi(2)], [d, d.perp()]);
    let mut metric = vec![m; mesh.n_points()];
    let mut f: Vec<Vec<f64>> = vec![mesh.points.iter().map(|p| 3.0 * p.x + p.y).collect()];
    let mut ctx = Ctx::new(&mut mesh, &mut metric, &mut f, None, params());
    let mut inserted = 0;
    let mut big_cavity = 0;
    for t in 0..ctx.mesh.n_tris() {
        for i in 0..3 {
            if ctx.mesh.is_deleted(t) || ctx.mesh.neighbours[t][i] == NONE {
                continue;
            }
            if let Some(sp) = split::check(&ctx, t as u32, i) {
                if let Some(ip) = insert::check(&mut ctx, &sp) {
                    big_cavity += (ip.cavity.len() > 2) as usize;
                    insert::apply(&mut ctx, &ip);
                    ctx.mesh.check().unwrap();
                    inserted += 1;
                }
            }
        }
    }
    assert!(inserted >= 20, "{inserted} insertions");
    assert!(
        big_cavity >= 5,
        "{big_cavity} cavities beyond the edge's two triangles"
    );
    drop(ctx);
    assert!(rel(mesh.area(), a0) < 1e-13);
    for (v, p) in mesh.points.iter().enumerate() {
        assert!((f[0][v] - (3.0 * p.x + p.y)).abs() < 1e-12);
    }
}

/// The Delaunay insertion kernel gives the new vertex the metric of the chosen interpolation
/// rule (as plain splits do): linear sizes between the edge ends, or the log-Euclidean mean.
#[test]
fn insertion_kernel_interpolates_the_metric_by_the_chosen_rule() {
    use crate::metric::{interpolate_log, lerp_sizes};
    for rule in [
        MetricInterpolation::LogEuclidean,
        MetricInterpolation::LinearSizes,
    ] {
        let mut mesh = square(4);
        let mut metric: Vec<Sym2> = mesh
            .points
            .iter()
            .map(|p| aniso(0.01 + 0.2 * p.x, 0.05 + 0.1 * p.y))
            .collect();
        let mut p = params();
        p.insertion = true;
        p.interpolation = rule;
        let ctx = Ctx::new(&mut mesh, &mut metric, &mut [], None, p);
        let mut ctx = ctx;
        let mut checked = 0;
        for t in 0..ctx.mesh.n_tris() {
            for i in 0..3 {
                let Some(sp) = split::check(&ctx, t as u32, i) else {
                    continue;
                };
                let Some(ip) = insert::check(&mut ctx, &sp) else {
                    continue;
                };
                let [a, b] = ip.ends;
                let (ma, mb) = (ctx.metric[a as usize], ctx.metric[b as usize]);
                let want = match rule {
                    MetricInterpolation::LinearSizes => lerp_sizes(&ma, &mb, ip.s),
                    MetricInterpolation::LogEuclidean => {
                        interpolate_log(&[(1.0 - ip.s, ma), (ip.s, mb)])
                    }
                };
                let d = (ip.m.xx - want.xx).abs()
                    + (ip.m.xy - want.xy).abs()
                    + (ip.m.yy - want.yy).abs();
                assert!(
                    d <= 1e-9 * want.xx.abs().max(want.yy.abs()),
                    "{rule:?}: {ip:?} vs {want:?}"
                );
                checked += 1;
            }
        }
        assert!(checked >= 10, "{rule:?}: {checked} insertions checked");
    }
}
