//! PPR redistancing through the command line with `k = 1` (vertex `.sol`, or `--expr`) and
//! `k = 2` (`--expr E --order 2`, the expression sampled at the P2 nodes): the errors against
//! the exact distance to the true curve on a refinement sequence show 003's orders, about 2 for
//! `k = 1` and 3 for `k = 2` (003 §6, Tables 8.1–8.4: `e_∞` on the nodes of the cut cells).

use anisomesh::io::{self, SolField};
use anisomesh::{DVec2, GridPattern, Mesh2};
use std::path::PathBuf;

mod common;
use common::{anisomesh_ok, s, scratch};

fn tmp(name: &str) -> PathBuf {
    scratch("cli-p2").join(name)
}

/// A level set that is not a distance, whose zero level is the circle of radius 0.6.
const EXPR: &str = "(x^2 + y^2 - 0.36) * (1 + 0.3 * sin(2*x + y))";

fn u(p: DVec2) -> f64 {
    (p.length_squared() - 0.36) * (1.0 + 0.3 * (2.0 * p.x + p.y).sin())
}

/// A grid of `[-1, 1]²` with `n` cells per side, interior vertices moved by up to 0.2 h
/// (pseudo-random, fixed), so that no error cancels by symmetry.
fn mesh(n: usize) -> Mesh2 {
    let mut m = Mesh2::rectangle(
        DVec2::splat(-1.0),
        DVec2::splat(1.0),
        n,
        n,
        GridPattern::Right,
    )
    .unwrap();
    let h = 2.0 / n as f64;
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    for p in &mut m.points {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        let t = (state >> 11) as f64 / (1u64 << 53) as f64 * std::f64::consts::TAU;
        if p.x.abs() < 1.0 - 1e-9 && p.y.abs() < 1.0 - 1e-9 {
            *p += DVec2::new(t.cos(), t.sin()) * (0.2 * h);
        }
    }
    m
}

/// `max |d - (|x| - 0.6)|` on the vertices of the triangles cut by the zero level.
fn band_error(n: usize, order: usize) -> f64 {
    let m = mesh(n);
    let mp = tmp(&format!("p2_{n}.mesh"));
    io::write_medit2(&mp, &m).unwrap();
    let out = tmp(&format!("p2_{n}_k{order}.sol"));
    let order_s = order.to_string();
    anisomesh_ok(&[
        "redistance",
        "--input",
        s(&mp),
        "--expr",
        EXPR,
        "--order",
        &order_s,
        "--method",
        "ppr",
        "-o",
        s(&out),
    ]);
    let SolField::Scalar(d) = io::read_sol(&out).unwrap().fields.remove(0) else {
        panic!("not a scalar field")
    };
    assert_eq!(d.len(), m.n_points());
    let mut e: f64 = 0.0;
    for t in m.live_tris() {
        let v = m.tris[t].map(|i| i as usize);
        let vals = v.map(|i| u(m.points[i]));
        if vals.iter().any(|&x| x <= 0.0) && vals.iter().any(|&x| x >= 0.0) {
            for i in v {
                e = e.max((d[i] - (m.points[i].length() - 0.6)).abs());
            }
        }
    }
    e
}

fn orders(errs: &[f64]) -> Vec<f64> {
    errs.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

#[test]
fn ppr_from_the_command_line_has_order_two_for_p1_and_three_for_p2() {
    let levels = [16, 32, 64, 128];
    let k1: Vec<f64> = levels.iter().map(|&n| band_error(n, 1)).collect();
    let k2: Vec<f64> = levels.iter().map(|&n| band_error(n, 2)).collect();
    let (o1, o2) = (orders(&k1), orders(&k2));
    let sci = |v: &[f64]| v.iter().map(|e| format!("{e:.3e}")).collect::<Vec<_>>();
    eprintln!("n = {levels:?}");
    eprintln!("k = 1: errors {:?}, orders {o1:.2?}", sci(&k1));
    eprintln!("k = 2: errors {:?}, orders {o2:.2?}", sci(&k2));
    assert!(o1.iter().all(|&o| (1.6..2.6).contains(&o)), "k = 1: {o1:?}");
    assert!(o2.iter().all(|&o| (2.5..3.6).contains(&o)), "k = 2: {o2:?}");
    assert!(k2[2] < k1[2] / 4.0, "P2 not more accurate: {k1:?} {k2:?}");
}
