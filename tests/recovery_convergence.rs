//! Convergence of the recovered derivatives of the interpolant of a smooth field,
//! `f = sin(2x) cos(3y) + exp(xy)` on the unit square, on meshes with h = 1/8 .. 1/64: perturbed
//! UnionJack and CrissCross grids (interior vertices moved randomly by up to 0.3 h) and the
//! unperturbed grids.
//!
//! Errors are taken over three vertex sets: a fixed inner square `[1/4, 3/4]^2` ("inner"), all
//! non-boundary vertices ("interior") and all vertices ("all"), in the max norm and the discrete
//! L2 norm (lumped vertex areas). The observed order is `log2(e_16 / e_64) / 2` (the mean over the
//! last two refinements; single steps on randomly perturbed meshes fluctuate by +-0.3). Each test
//! prints its table (`--nocapture`) and asserts the measured orders minus a margin of ~0.15.

#[path = "recovery_common.rs"]
mod common;

use anisomesh::recovery::{gradient_ppr, hessian_double_l2, recover_ls};
use anisomesh::{DVec2, GridPattern, Mesh2};
use common::*;

const LEVELS: [usize; 4] = [8, 16, 32, 64];
const SETS: [&str; 3] = ["inner", "interior", "all"];

/// `err[level][set] = (max, L2)` for one method.
type Table = Vec<[(f64, f64); 3]>;

struct Sweep {
    ls_hessian: Table,
    l2_hessian: Table,
    ls_gradient: Table,
    ppr_gradient: Table,
}

fn sweep(pattern: GridPattern, amp: f64, seed: u64) -> Sweep {
    let mut s = Sweep {
        ls_hessian: vec![],
        l2_hessian: vec![],
        ls_gradient: vec![],
        ppr_gradient: vec![],
    };
    for &n in &LEVELS {
        let mesh: Mesh2 = perturbed_square(n, pattern, amp, seed + n as u64);
        let u = sample(&mesh, &Smooth);
        let w = lumped_areas(&mesh);
        let boundary = mesh.boundary_vertex_flags();
        let inner: Vec<bool> = mesh
            .points
            .iter()
            .map(|p| p.cmpge(DVec2::splat(0.25)).all() && p.cmple(DVec2::splat(0.75)).all())
            .collect();
        let interior: Vec<bool> = boundary.iter().map(|b| !b).collect();
        let all = vec![true; mesh.n_points()];
        let sets = |e: &[f64]| {
            [
                norms(e, &w, &inner),
                norms(e, &w, &interior),
                norms(e, &w, &all),
            ]
        };
        let ls = recover_ls(&mesh, &u).unwrap();
        let l2 = hessian_double_l2(&mesh, &u).unwrap();
        let ppr = gradient_ppr(&mesh, &u).unwrap();
        s.ls_hessian
            .push(sets(&hessian_errors(&mesh, &Smooth, &ls.hessian)));
        s.l2_hessian
            .push(sets(&hessian_errors(&mesh, &Smooth, &l2)));
        s.ls_gradient
            .push(sets(&gradient_errors(&mesh, &Smooth, &ls.gradient)));
        s.ppr_gradient
            .push(sets(&gradient_errors(&mesh, &Smooth, &ppr)));
    }
    let title = format!("{pattern:?}, perturbation {amp} h, seed {seed}");
    for (name, t) in [
        ("LS Hessian (004 §4.3)", &s.ls_hessian),
        ("double-L2 Hessian", &s.l2_hessian),
        ("LS gradient", &s.ls_gradient),
        ("PPR gradient (003 §6.2)", &s.ppr_gradient),
    ] {
        print_table(&format!("{name} — {title}"), t);
    }
    s
}

fn print_table(title: &str, t: &Table) {
    println!("{title}");
    print!("{:>5}", "1/h");
    for set in SETS {
        print!(" | {:^31}", format!("{set}: max, L2 (order)"));
    }
    println!();
    for (i, row) in t.iter().enumerate() {
        print!("{:>5}", LEVELS[i]);
        for (k, &(mx, l2)) in row.iter().enumerate() {
            let o = |cur: f64, prev: Option<f64>| {
                prev.map_or("     ".into(), |p| format!("{:5.2}", (p / cur).log2()))
            };
            let (pm, pl) = if i > 0 {
                (Some(t[i - 1][k].0), Some(t[i - 1][k].1))
            } else {
                (None, None)
            };
            print!(" | {mx:.2e} {} {l2:.2e} {}", o(mx, pm), o(l2, pl));
        }
        println!();
    }
    println!(
        "  mean order 1/16 -> 1/64: {}",
        SETS.iter()
            .enumerate()
            .map(|(k, s)| format!(
                "{s} max {:.2}, L2 {:.2}",
                order(t, k, false),
                order(t, k, true)
            ))
            .collect::<Vec<_>>()
            .join("; ")
    );
}

/// Mean observed order over the last two refinements (1/16 -> 1/64) for set `k`.
fn order(t: &Table, k: usize, l2: bool) -> f64 {
    let pick = |r: &[(f64, f64); 3]| if l2 { r[k].1 } else { r[k].0 };
    let n = t.len();
    (pick(&t[n - 3]) / pick(&t[n - 1])).log2() / 2.0
}

const INNER: usize = 0;
const INTERIOR: usize = 1;
const ALL: usize = 2;

/// LS Hessian, measured (mean order 1/16 -> 1/64, perturbed 0.3 h):
/// UnionJack seed 1000: interior max 0.85, interior L2 1.03, all max 0.87, all L2 1.27
/// (inner-square max 0.69: single steps 0.38 and 0.99);
/// CrissCross seed 5: interior max 1.03, interior L2 1.03, all max 1.00, all L2 1.07.
/// UnionJack seeds 7 and 99: interior max 0.88 and 0.92. (Unperturbed UnionJack: inner order 2.0,
/// the symmetric patches cancel the first-order term.) Asserted: interior max >= 0.7, interior
/// and all L2 >= 0.85, all max >= 0.7 (boundary vertices and corners included).
#[test]
fn ls_hessian_converges_at_first_order_on_perturbed_meshes() {
    for (pattern, seed) in [(GridPattern::UnionJack, 1000), (GridPattern::CrissCross, 5)] {
        let s = sweep(pattern, 0.3, seed);
        let t = &s.ls_hessian;
        assert!(order(t, INTERIOR, false) >= 0.7, "{pattern:?} interior max");
        assert!(order(t, INTERIOR, true) >= 0.85, "{pattern:?} interior L2");
        assert!(order(t, ALL, true) >= 0.85, "{pattern:?} all L2");
        assert!(order(t, ALL, false) >= 0.7, "{pattern:?} all max");
        // Absolute level at h = 1/64: interior max error about 0.2 (|H| ~ 10 here).
        assert!(
            t[3][INTERIOR].0 < 0.3,
            "{pattern:?}: {:e}",
            t[3][INTERIOR].0
        );
    }
}

/// PPR and LS gradients (both quadratic fits, so nearly identical), measured mean orders
/// 1/16 -> 1/64 on 0.3 h perturbed meshes: UnionJack interior max 1.96, all max 1.85 (PPR) /
/// 1.96 (LS), all L2 1.99 / 1.98; CrissCross interior max 1.99, all max 2.04, all L2 2.04.
/// Superconvergent (second order) even with boundary vertices included. Asserted: interior max
/// >= 1.75, all L2 >= 1.85, all max >= 1.7.
#[test]
fn ppr_and_ls_gradients_superconverge_on_perturbed_meshes() {
    for (pattern, seed) in [(GridPattern::UnionJack, 1000), (GridPattern::CrissCross, 5)] {
        let s = sweep(pattern, 0.3, seed);
        for (name, t) in [("PPR", &s.ppr_gradient), ("LS", &s.ls_gradient)] {
            assert!(
                order(t, INTERIOR, false) >= 1.75,
                "{name} {pattern:?} interior max"
            );
            assert!(order(t, ALL, true) >= 1.85, "{name} {pattern:?} all L2");
            assert!(order(t, ALL, false) >= 1.7, "{name} {pattern:?} all max");
        }
    }
}

/// The double lumped L2 projection is not consistent at and next to the boundary (the first
/// projection is only first-order there, and the second differentiates that error), nor on
/// randomly perturbed meshes. Measured on unperturbed UnionJack grids: inner-square max error
/// order 1.99 (h = 1/16 .. 1/64), interior max error 3.3 at every h (order 0.01: the rows next to
/// the boundary), all-vertex L2 order 0.55. On 0.3 h perturbed meshes the inner max error stays
/// O(1) (2.6 at h = 1/64, order -0.25) while the LS Hessian's is 0.17 — the reason 004 §4.3
/// prefers least squares. Asserted: structured inner max order >= 1.5, structured interior max
/// order < 0.5, and on perturbed meshes at h = 1/64 the LS inner max error at least 5x smaller
/// than the double-L2 one.
#[test]
fn double_l2_hessian_converges_only_away_from_the_boundary_of_structured_meshes() {
    let s = sweep(GridPattern::UnionJack, 0.0, 5);
    let t = &s.l2_hessian;
    let o = order(t, INNER, false);
    println!("structured inner max order {o:.2}");
    assert!(o >= 1.5, "structured inner max order {o}");
    // Next to the boundary it does not converge (documented above, checked so the doc stays true).
    assert!(order(t, INTERIOR, false) < 0.5);
    let p = sweep(GridPattern::UnionJack, 0.3, 1000);
    let (ls, l2) = (p.ls_hessian[3][INNER].0, p.l2_hessian[3][INNER].0);
    println!("perturbed, h = 1/64, inner max: LS {ls:.2e}, double L2 {l2:.2e}");
    assert!(5.0 * ls < l2, "LS {ls:e} vs double L2 {l2:e}");
}
