//! PPR redistancing on tetrahedra: 003 §8 Example 1 (torus, alpha = 1) on levels 3..=5 (the
//! deeper levels are in `bench::reinit::run`). Values are compared with 003 Table 8.1.

use anisomesh::bench::reinit::torus_case;

/// 003 Table 8.1, levels 3, 4, 5: (e_inf, e_grad).
const PAPER_K1: [(f64, f64); 3] = [(1.21e-2, 2.50e-1), (3.01e-3, 1.53e-1), (7.54e-4, 8.32e-2)];
const PAPER_K2: [(f64, f64); 3] = [(5.73e-4, 1.66e-2), (7.21e-5, 3.46e-3), (9.94e-6, 8.70e-4)];

fn run(k: usize) -> Vec<(f64, f64, f64)> {
    (3..=5)
        .map(|l| {
            let (h, e, g, r) = torus_case(l, k, 1.0).unwrap();
            assert_eq!(r.not_converged, 0, "level {l}: {r:?}");
            eprintln!(
                "k={k} l={l}: e_inf {e:.3e} e_grad {g:.3e} ({} band nodes)",
                r.band_nodes
            );
            (h, e, g)
        })
        .collect()
}

fn order(a: (f64, f64), b: (f64, f64)) -> f64 {
    (a.1 / b.1).ln() / (a.0 / b.0).ln()
}

#[test]
fn torus_p1() {
    let r = run(1);
    for (i, &(_, e, g)) in r.iter().enumerate() {
        let (pe, pg) = PAPER_K1[i];
        assert!(
            (e / pe - 1.0).abs() < 0.25,
            "level {}: e_inf {e:e} vs paper {pe:e}",
            i + 3
        );
        assert!(g < pg, "level {}: e_grad {g:e} vs paper {pg:e}", i + 3);
    }
    // e_inf order over levels 3 -> 5 (paper: 2.00).
    let o = order((r[0].0, r[0].1), (r[2].0, r[2].1));
    assert!((o - 2.0).abs() < 0.2, "e_inf order {o}");
    // e_grad order 4 -> 5 (paper: 0.87).
    let og = order((r[1].0, r[1].2), (r[2].0, r[2].2));
    assert!((og - 1.0).abs() < 0.2, "e_grad order {og}");
}

#[test]
fn torus_p2() {
    let r = run(2);
    for (i, &(_, e, g)) in r.iter().enumerate() {
        let (pe, pg) = PAPER_K2[i];
        assert!(
            (e / pe - 1.0).abs() < 0.25,
            "level {}: e_inf {e:e} vs paper {pe:e}",
            i + 3
        );
        assert!(
            (g / pg - 1.0).abs() < 0.25,
            "level {}: e_grad {g:e} vs paper {pg:e}",
            i + 3
        );
    }
    // Orders 4 -> 5 (paper: 2.86 and 1.99).
    let o = order((r[1].0, r[1].1), (r[2].0, r[2].1));
    assert!((o - 3.0).abs() < 0.2, "e_inf order {o}");
    let og = order((r[1].0, r[1].2), (r[2].0, r[2].2));
    assert!((og - 2.0).abs() < 0.2, "e_grad order {og}");
}

#[test]
fn bench_writes_the_json_shape() {
    use anisomesh::bench::reinit::{run, ReinitOptions};
    let dir = std::env::temp_dir().join(format!("anisomesh-reinit-{}", std::process::id()));
    let opts = ReinitOptions {
        levels_3d: vec![],
        levels_2d: vec![2, 3],
        alphas: vec![1],
        degrees: vec![1],
        volume_levels: vec![],
        out_dir: Some(dir.clone()),
        print: false,
        ..ReinitOptions::default()
    };
    let rep = run(&opts).unwrap();
    assert_eq!(rep.tables.len(), 2);
    assert!(dir.join("reinit_circle_einf.png").exists());
    let text = std::fs::read_to_string(dir.join("reinit.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let t = &v["tables"][0];
    assert_eq!(t["name"], "circle");
    assert_eq!(t["dim"], 2);
    assert_eq!(t["k"], 1);
    assert_eq!(t["alpha"], 1);
    let row = &t["rows"][1];
    for key in ["level", "h", "e_inf", "order_inf", "e_grad", "order_grad"] {
        assert!(row.get(key).is_some(), "missing {key}");
    }
    assert_eq!(row.as_object().unwrap().len(), 6);
    assert!(v["volume_drift"].as_array().unwrap().is_empty());
    std::fs::remove_dir_all(&dir).ok();
}
