//! The Couette benchmark of 004 §5.1 through `bench::couette::run`: the issue's targets on the
//! default adapted mesh, the body-fitted reference, and thread-count independence.

use anisomesh::bench::couette::{run, CouetteOptions, CouetteReport};

fn in_pool(threads: usize, opts: &CouetteOptions) -> CouetteReport {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(|| run(opts).unwrap())
}

#[test]
fn adapted_default_meets_the_issue_targets_and_is_thread_independent() {
    let opts = CouetteOptions::default();
    let r1 = in_pool(1, &opts);
    println!("{}", serde_json::to_string_pretty(&r1).unwrap());
    assert!(r1.converged && r1.residual < 1e-8, "{r1:?}");
    assert!(r1.vertices <= 4000, "{} vertices", r1.vertices);
    assert!((r1.omega + 1.0).abs() <= 2e-4, "omega {}", r1.omega);
    assert!(r1.rigidity <= 1e-3, "rigidity {}", r1.rigidity);
    let r2 = in_pool(2, &opts);
    assert_eq!(r1.vertices, r2.vertices);
    assert_eq!(r1.uzawa_iterations, r2.uzawa_iterations);
    assert_eq!(r1.omega.to_bits(), r2.omega.to_bits());
    assert_eq!(r1.rigidity.to_bits(), r2.rigidity.to_bits());
}

#[test]
fn fitted_reference_turns_rigidly_at_minus_one() {
    let opts = CouetteOptions {
        fitted: true,
        ..CouetteOptions::default()
    };
    let r = run(&opts).unwrap();
    println!("{}", serde_json::to_string_pretty(&r).unwrap());
    assert!(r.converged, "{r:?}");
    assert!((r.omega + 1.0).abs() <= 5e-4, "omega {}", r.omega);
    assert!(r.rigidity <= 1e-4, "rigidity {}", r.rigidity);
}
