//! The peer-comparison glue (`bench::peers`): inputs written and read back, peer output parsed,
//! a known mesh measured, timeouts enforced, and — when `mmg2d_O3` / `FreeFem++` are installed —
//! one small real run each whose output reads back as a valid mesh.

use crate::app::repro::peers::{
    background, bamg_script, evaluate_target, find_program, measure, parse_bamg_seconds,
    parse_mmg_elapsed, run_peer, run_with_timeout, target_metric, write_bamg_data, write_csv,
    write_levelset_input, write_metric_input, zalesak_exact, PeerKind, PeerOptions, PeerResult,
    PeerStatus,
};
use anisomesh::io::{self, SolField};
use anisomesh::DVec2;
use std::path::PathBuf;
use std::process::Command;
use std::time::Duration;

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "anisomesh-peers-test-{name}-{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn exact_derivatives_give_eq6_sizes_on_the_arc() {
    // On the arc at (0.5, 0.75): u = 0, ∇u = (1, 0), D²u = diag(0, 1/R), R = 0.5.
    let (u, g, h) = zalesak_exact(DVec2::new(0.5, 0.75));
    assert!(u.abs() < 1e-15, "{u}");
    assert!((g - DVec2::X).length() < 1e-9, "{g}");
    assert!(
        (h.yy - 2.0).abs() < 1e-6 && h.xx.abs() < 1e-6 && h.xy.abs() < 1e-6,
        "{h:?}"
    );
    // Inside the slot wall x = 0.06 (straight piece): zero Hessian.
    let (u, g, h) = zalesak_exact(DVec2::new(0.05, 0.6));
    assert!((u - 0.01).abs() < 1e-12, "{u}");
    assert!((g + DVec2::X).length() < 1e-9, "{g}");
    assert!(h.norm() < 1e-6, "{h:?}");
    // The target metric there: normal size hmin, tangential sqrt(eps R) on the arc.
    let eps = 1e-3;
    let mesh = anisomesh::Mesh2::from_triangles(
        vec![
            DVec2::new(0.5, 0.75),
            DVec2::new(0.6, 0.75),
            DVec2::new(0.5, 0.85),
        ],
        vec![[0, 1, 2]],
    )
    .unwrap();
    let (m, u) = evaluate_target(&mesh, &target_metric(eps));
    assert!(u[0].abs() < 1e-15);
    let (sizes, _) = m[0].sizes();
    let want = [(eps * 0.5f64).sqrt(), 1e-3];
    let (lo, hi) = (sizes[0].min(sizes[1]), sizes[0].max(sizes[1]));
    assert!(
        (lo - want[1]).abs() < 1e-9 && (hi - want[0]).abs() < 1e-8,
        "{sizes:?}"
    );
    // At (0.6, 0.75), u = 0.1, outside the band |u| < 0.004: sizes grown by 0.3 (|u| - 0.004),
    // from hmin across and sqrt(eps / κ) = sqrt(eps 0.6) along the level line.
    assert!((u[1] - 0.1).abs() < 1e-14);
    let (s, _) = m[1].sizes();
    let grow = 0.3 * (0.1 - 0.004);
    let (lo, hi) = (s[0].min(s[1]), s[0].max(s[1]));
    assert!((lo - (1e-3 + grow)).abs() < 1e-9, "{s:?}");
    assert!((hi - ((eps * 0.6f64).sqrt() + grow)).abs() < 1e-7, "{s:?}");
}

#[test]
fn inputs_round_trip_through_medit_files() {
    let dir = scratch("inputs");
    let mesh = background(6).unwrap();
    assert_eq!(mesh.n_points(), 36);
    let (metric, u) = evaluate_target(&mesh, &target_metric(1e-2));
    let (mp, sp) = write_metric_input(&dir, "bg", &mesh, &metric).unwrap();
    let back = io::read_medit2(&mp).unwrap();
    back.check().unwrap();
    assert_eq!(back.n_points(), 36);
    for (a, b) in back.points.iter().zip(&mesh.points) {
        assert!((*a - *b).length() < 1e-14);
    }
    match &io::read_sol_for(&sp, 36).unwrap().fields[0] {
        SolField::Tensor2(m) => {
            for (a, b) in m.iter().zip(&metric) {
                assert!(a.sub(b).norm() <= 1e-12 * b.norm(), "{a:?} {b:?}");
            }
        }
        f => panic!("not a tensor field: {f:?}"),
    }
    let (_, sp) = write_levelset_input(&dir, "ls", &mesh, &u).unwrap();
    match &io::read_sol_for(&sp, 36).unwrap().fields[0] {
        SolField::Scalar(v) => assert!(v.iter().zip(&u).all(|(a, b)| (a - b).abs() < 1e-14)),
        f => panic!("not a scalar field: {f:?}"),
    }
    // The BAMG data file and script.
    let data = dir.join("d.txt");
    write_bamg_data(&data, &[[1.0, 2.0, 3.0], [4.5, -1e-300, 6.0]]).unwrap();
    let text = std::fs::read_to_string(&data).unwrap();
    let nums: Vec<f64> = text
        .split_whitespace()
        .map(|t| t.parse().unwrap())
        .collect();
    assert_eq!(nums, vec![2.0, 1.0, 2.0, 3.0, 4.5, -1e-300, 6.0]);
    let edp = bamg_script(&mp, &data, &dir.join("o.mesh"), "adaptmesh(Th, a)");
    for tag in ["@IN@", "@DATA@", "@OUT@", "@ADAPT@"] {
        assert!(!edp.contains(tag), "{tag} left in the script");
    }
    assert!(edp.contains("mesh Ta = adaptmesh(Th, a);"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn peer_output_lines_parse() {
    let mmg = "  -- MESH PACKED UP\n   ELAPSED TIME  0.781s\n\n   ELAPSED TIME  12.5s\n";
    assert_eq!(parse_mmg_elapsed(mmg), Some(12.5));
    assert_eq!(parse_mmg_elapsed("nothing"), None);
    assert_eq!(
        parse_mmg_elapsed("   ELAPSED TIME  25m21s (1521.280s)\n"),
        Some(1521.28)
    );
    assert_eq!(
        parse_bamg_seconds("x\nBAMG_SECONDS 0.25\nBAMG_VERTICES 9"),
        Some(0.25)
    );
    assert_eq!(parse_bamg_seconds("BAMG_SECONDS nan?"), None);
}

#[test]
fn a_uniform_grid_measures_as_expected() {
    // 161 x 161 vertices (h = 0.025): the P1 zero level of the exact distance is within
    // h²κ/8-ish of the arc, but the slot corners cut by the grid cost up to half a cell
    // diagonal (0.0177); measured 0.0136.
    let mesh = background(161).unwrap();
    let r = measure(PeerKind::Anisomesh, &mesh, &target_metric(1e-3));
    assert!(r.is_ok() && r.valid);
    assert_eq!(r.vertices, 161 * 161);
    assert_eq!(r.triangles, 2 * 160 * 160);
    assert!(r.area_rel_error.abs() < 3e-3, "{}", r.area_rel_error);
    assert!(
        r.perimeter_rel_error.abs() < 1e-2,
        "{}",
        r.perimeter_rel_error
    );
    assert!(
        r.hausdorff > 5e-3 && r.hausdorff < 0.0177,
        "{}",
        r.hausdorff
    );
    // A uniform grid is far too coarse across the interface for eq. (6): most edges are long.
    assert!(r.edge_length_in_range < 0.5, "{}", r.edge_length_in_range);
    assert!(r.q_ani_mean > 1.0 && r.q_ani_max >= r.q_ani_mean);
}

#[test]
fn missing_programs_and_timeouts_are_reported() {
    assert!(find_program("anisomesh-no-such-peer-xyz").is_none());
    let r = PeerResult::unavailable(PeerKind::Mmg2dMetric, 1e-3, "mmg2d_O3 not found");
    assert!(!r.is_ok() && r.vertices == 0 && r.hausdorff.is_nan());
    let row = r.csv_row();
    assert!(row.starts_with("mmg2d-metric,unavailable,1e-3,"), "{row}");
    assert_eq!(
        row.split(',').count(),
        PeerResult::CSV_HEADER.split(',').count()
    );
    let dir = scratch("timeout");
    write_csv(&dir.join("sub").join("x.csv"), &[r]).unwrap();
    assert!(std::fs::read_to_string(dir.join("sub/x.csv"))
        .unwrap()
        .contains("unavailable"));
    if find_program("sleep").is_some() {
        let mut cmd = Command::new("sleep");
        cmd.arg("20");
        let out = run_with_timeout(&mut cmd, Duration::from_millis(300), &dir, "sleep").unwrap();
        assert!(
            out.timed_out && !out.success && out.seconds < 5.0,
            "{out:?}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

fn small_opts(name: &str) -> PeerOptions {
    PeerOptions {
        background: 20,
        iterations: 1,
        timeout: Duration::from_secs(60),
        work_dir: scratch(name),
        ..PeerOptions::default()
    }
}

fn check_real_run(kind: PeerKind, name: &str) {
    let program = kind.program().unwrap();
    if find_program(program).is_none() {
        println!("skipped: {program} not found");
        return;
    }
    let opts = small_opts(name);
    let r = run_peer(kind, 1e-2, &opts);
    assert_eq!(r.status, PeerStatus::Ok, "{r:?}");
    let dir = opts.work_dir.join(format!("{}_eps{:e}", kind.slug(), 1e-2));
    let out = io::read_medit2(&dir.join("out0.mesh")).unwrap();
    out.check().unwrap();
    assert!(r.valid);
    assert_eq!(out.n_points(), r.vertices);
    // Refined around the interface: more vertices than the 20 x 20 background, and the zero
    // level much closer to the exact one than the background's (~0.1).
    assert!(r.vertices > 600, "{}", r.vertices);
    assert!(r.hausdorff < 0.05 && r.area_rel_error.abs() < 0.02, "{r:?}");
    assert!(r.seconds > 0.0 && r.seconds < 60.0);
    let _ = std::fs::remove_dir_all(&opts.work_dir);
}

#[test]
fn mmg2d_small_real_run() {
    check_real_run(PeerKind::Mmg2dMetric, "mmg");
}

#[test]
fn bamg_small_real_run() {
    check_real_run(PeerKind::BamgMetric, "bamg");
}
