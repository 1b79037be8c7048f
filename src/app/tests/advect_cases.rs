//! `anisomesh advect` on reduced configurations: the single vortex with T = 1 on coarse
//! anisotropic meshes (about 1,500 vertices, a second of CPU), its output files, the built-in
//! case table and the Pareto fronts of the comparison.

use crate::app::repro::advect::{builtin, custom, output, run, RunSettings};
use anisomesh::geom::DVec2;

#[test]
fn coarse_single_vortex_returns_and_writes_its_files() {
    let dir = std::env::temp_dir().join(format!("anisomesh_advect_{}", std::process::id()));
    let case = builtin("vortex", Some(1.0)).unwrap();
    assert!(case.returns);
    let mut s = RunSettings::for_case(&case);
    s.sizes = [2e-3, 0.1, 2e-3, 4e-3];
    s.snapshot_times = vec![0.5];
    let (rep, res) = run(&case, &s).unwrap();
    // Disk of radius 0.15.
    let exact = std::f64::consts::PI * 0.15 * 0.15;
    assert!(
        (rep.area_initial - exact).abs() < 2e-3 * exact,
        "{}",
        rep.area_initial
    );
    assert!(rep.area_error().abs() < 0.01, "area {}", rep.area_error());
    let sd = rep.symmetric_difference_relative();
    assert!(sd > 0.0 && sd < 0.03, "symmetric difference {sd}");
    assert!(rep.hausdorff.unwrap() < 5e-3, "{:?}", rep.hausdorff);
    assert!(rep.vertices_max < 4000, "{}", rep.vertices_max);
    // Halfway the disk is stretched: its perimeter grows (measured 1.186 from 0.942).
    let mid = res.steps.iter().find(|x| x.time >= 0.5).unwrap();
    assert!(
        mid.perimeter > 1.15 * rep.perimeter_initial,
        "{}",
        mid.perimeter
    );
    output::write_all(&dir, &rep, &res).unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("advect.json")).unwrap()).unwrap();
    for key in [
        "area_initial",
        "area_final",
        "perimeter_initial",
        "perimeter_final",
        "vertices_mean",
        "vertices_max",
        "seconds",
        "area_symmetric_difference",
        "hausdorff",
    ] {
        assert!(
            json.get(key).is_some_and(|v| !v.is_null()),
            "advect.json lacks {key}"
        );
    }
    let csv = std::fs::read_to_string(dir.join("advect.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 1 + s.periods);
    let mesh = anisomesh::io::read_mesh(&dir.join("advect_final.mesh")).unwrap();
    assert_eq!(mesh.n_points(), res.last.mesh.n_points());
    for f in ["advect_frames.png", "advect_half.png", "advect_final.png"] {
        let len = std::fs::metadata(dir.join(f)).unwrap().len();
        assert!(len > 10_000, "{f}: {len} bytes");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn cases_and_their_errors() {
    for (name, t) in [("vortex", 8.0), ("deformation", 2.0)] {
        let c = builtin(name, None).unwrap();
        assert_eq!(c.t_end, t);
        assert!(c.returns);
        // The velocity vanishes on the walls of the unit square.
        for p in [DVec2::new(0.0, 0.3), DVec2::new(1.0, 0.7)] {
            assert!(anisomesh::advect::Velocity::at(&c.velocity, 0.1, p).x.abs() < 1e-12);
        }
    }
    let z = builtin("zalesak", Some(std::f64::consts::PI)).unwrap();
    assert!(!z.returns);
    assert_eq!(z.periods, 8);
    for e in [
        builtin("spiral", None).err().unwrap().to_string(),
        custom("x +", "1; 0", (DVec2::ZERO, DVec2::ONE), 1.0, false)
            .err()
            .unwrap()
            .to_string(),
        custom("x", "1", (DVec2::ZERO, DVec2::ONE), 1.0, false)
            .err()
            .unwrap()
            .to_string(),
    ] {
        assert!(!e.contains('\n') && !e.is_empty(), "{e}");
    }
}
