//! Band finite elements (000 §2): convergence orders of the surface heat equation and of mean
//! curvature motion on coarse grids, and the errors for bad input.

use anisomesh::backends::dtgrid::heat::{sphere_heat, HeatOptions};
use anisomesh::backends::dtgrid::lattice::C3;
use anisomesh::backends::dtgrid::scheme::Bc;
use anisomesh::backends::dtgrid::{DtGrid, SortedBand};

/// The storage the commands use: the DT-Grid run-length encoding (000 §3).
type B = DtGrid<C3>;

#[test]
fn dt_grid_and_sorted_storage_give_the_same_solution() {
    // The band finite elements only see the `Band` seam: both storages must give the same
    // numbers to the last bit.
    let opts = HeatOptions::paper(17, 2, Bc::Transparent);
    let a = sphere_heat::<DtGrid<C3>>(&opts).unwrap();
    let b = sphere_heat::<SortedBand<C3>>(&opts).unwrap();
    assert_eq!(a.nodes, b.nodes);
    assert_eq!(
        a.error.to_bits(),
        b.error.to_bits(),
        "{} vs {}",
        a.error,
        b.error
    );
}

#[test]
fn heat_transparent_converges_at_second_order_from_j2() {
    let mut errs = Vec::new();
    for n in [17, 33, 65] {
        let r = sphere_heat::<B>(&HeatOptions::paper(n, 2, Bc::Transparent)).unwrap();
        println!(
            "heat transparent j=2 n={n}: {:.3e} ({} nodes)",
            r.error, r.nodes
        );
        errs.push(r.error);
    }
    let order = (errs[1] / errs[2]).log2();
    assert!(order > 1.6, "order {order} from {errs:?}");
}

#[test]
fn heat_natural_on_the_thinnest_band_does_not_converge_at_second_order() {
    let mut errs = Vec::new();
    for bc in [Bc::Natural, Bc::Transparent] {
        let r = sphere_heat::<B>(&HeatOptions::paper(65, 1, bc)).unwrap();
        println!("heat {} j=1 n=65: {:.3e}", bc.name(), r.error);
        errs.push(r.error);
    }
    assert!(errs[0] > 2.0 * errs[1], "{errs:?}");
}

use anisomesh::backends::dtgrid::mcf::{sphere_mcf, McfOptions};

fn mcf_errors(j: usize, inner: usize, tau_of_h: impl Fn(f64) -> f64, ns: &[usize]) -> Vec<f64> {
    let o = McfOptions {
        j,
        inner,
        ..McfOptions::default()
    };
    mcf_runs(&o, tau_of_h, ns).iter().map(|r| r.0).collect()
}

/// (error, mean solves per step) of the shrinking sphere of 000 Table 2.2 on each grid.
fn mcf_runs(o: &McfOptions, tau_of_h: impl Fn(f64) -> f64, ns: &[usize]) -> Vec<(f64, f64)> {
    let (j, inner) = (o.j, o.inner);
    ns.iter()
        .map(|&n| {
            let h = 1.0 / (n - 1) as f64;
            let r = sphere_mcf::<B>(n, 0.25, 0.0059, tau_of_h(h), o).unwrap();
            println!(
                "mcf j={j} inner={inner} n={n}: error {:.3e} radius {:.5} exact {:.5} solves/step {:.2}",
                r.error, r.radius_final, r.radius_exact, r.mean_solves
            );
            (r.error, r.mean_solves)
        })
        .collect()
}

#[test]
fn mcf_with_inner_iterations_converges_at_second_order() {
    // 000 Table 2.2 (τ = h², 17³ and 33³): j = 2 0.0128, 0.0028; j = 4 0.0076, 0.0018.
    // Measured: j = 2 9.65e-3, 2.78e-3 (order 1.79, 2.39 on to 65³); j = 4 7.69e-3, 2.50e-3
    // (order 1.62, 1.82 on to 65³).
    for (j, min_order, paper) in [(2, 1.7, 0.002848), (4, 1.5, 0.001830)] {
        let e = mcf_errors(j, 5, |h| h * h, &[17, 33]);
        let order = (e[0] / e[1]).log2();
        assert!(order > min_order, "j = {j}: order {order} from {e:?}");
        assert!(e[1] < 1.5 * paper, "j = {j}: {e:?}");
    }
}

#[test]
fn mcf_inner_iteration_stops_early_without_losing_accuracy() {
    // The stopping test of 000 §2.4 (mean boundary update below δh, band unchanged up to a
    // fraction δ of its nodes) against the iteration run to a tolerance 100 times smaller.
    let o = McfOptions {
        j: 2,
        inner: 8,
        ..McfOptions::default()
    };
    let strict = McfOptions { delta: 1e-4, ..o };
    let fast = mcf_runs(&o, |h| h * h, &[33])[0];
    let tight = mcf_runs(&strict, |h| h * h, &[33])[0];
    assert!(fast.1 <= 3.0, "solves per step {fast:?}");
    assert!(tight.1 > fast.1, "{tight:?} {fast:?}");
    assert!((fast.0 / tight.0 - 1.0).abs() < 0.03, "{fast:?} {tight:?}");
}

#[test]
fn mcf_with_inner_iterations_and_large_steps_converges_at_first_order() {
    // 000 Table 2.2 (j = 2, τ = h/8): 0.0246, 0.0143; measured 0.0171, 0.0071.
    let e = mcf_errors(2, 5, |h| h / 8.0, &[17, 33]);
    let order = (e[0] / e[1]).log2();
    assert!(order > 0.8, "order {order} from {e:?}");
}

#[test]
fn mcf_element_product_takes_the_assembled_steps() {
    // Dirichlet solves with M + τL applied element by element (the default) against the
    // assembled matrix: the same system up to the order of summation. One step of the sphere
    // r = 1/3 on 65³ (j = 1, τ = h², inner iteration), then Table 2.2's run on 33³ (j = 2).
    use anisomesh::backends::dtgrid::lattice::Lattice;
    use anisomesh::backends::dtgrid::mcf::McfState;
    use anisomesh::backends::dtgrid::Band;
    let lat = Lattice::unit(65).unwrap();
    let start: McfState<B> = McfState::new(lat, 1, &|p| p.length() - 1.0 / 3.0).unwrap();
    let oe = McfOptions::default();
    assert!(oe.element_product);
    let o = McfOptions {
        element_product: false,
        ..oe
    };
    let (mut a, mut e) = (start.clone(), start);
    let tau = lat.h * lat.h;
    let (ra, re) = (a.step(tau, &o).unwrap(), e.step(tau, &oe).unwrap());
    println!(
        "assembled: {} solves, {} CG; element product: {} solves, {} CG",
        ra.solves, ra.cg_iterations, re.solves, re.cg_iterations
    );
    assert_eq!(ra.solves, re.solves);
    assert!(ra.cg_iterations.abs_diff(re.cg_iterations) <= ra.solves);
    assert!(a.nb.band.coords().eq(e.nb.band.coords()));
    let worst = a
        .phi
        .iter()
        .zip(&e.phi)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    println!(
        "largest difference of Φ after the step: {:.2e} h",
        worst / lat.h
    );
    assert!(worst < 1e-6 * lat.h, "{worst}");
    let (ta, te) = (
        mcf_runs(&McfOptions { j: 2, ..o }, |h| h * h, &[33])[0],
        mcf_runs(&McfOptions { j: 2, ..oe }, |h| h * h, &[33])[0],
    );
    assert!((te.0 / ta.0 - 1.0).abs() < 1e-3, "{ta:?} {te:?}");
}

#[test]
fn mcf_without_inner_iterations_does_not_converge() {
    // 000 Table 2.2 (j = 1, τ = h/8, no inner iteration): 0.026, 0.051; measured 0.018, 0.032.
    let e = mcf_errors(1, 1, |h| h / 8.0, &[17, 33]);
    assert!(e[1] > e[0], "{e:?}");
}

#[test]
fn bad_input_gives_typed_errors() {
    use anisomesh::backends::dtgrid::lattice::Lattice;
    use anisomesh::backends::dtgrid::mcf::McfState;
    use anisomesh::Error;
    let o = McfOptions::default();
    // A sphere that vanishes before t_end: the motion stops with EmptyLevelSet.
    let r = sphere_mcf::<B>(17, 0.1, 0.01, 1.0 / 128.0, &o);
    assert!(matches!(r, Err(Error::EmptyLevelSet(_))), "{r:?}");
    // A shape that does not fit in the grid with its band.
    let lat = Lattice::unit(17).unwrap();
    let r = McfState::<B>::new(lat, 2, &|p| p.length() - 0.48);
    assert!(matches!(r, Err(Error::InvalidInput(_))), "{r:?}");
    // A NaN in the level-set function.
    let r = McfState::<B>::new(lat, 1, &|p| {
        if p.x > 0.2 {
            f64::NAN
        } else {
            p.length() - 0.3
        }
    });
    assert!(matches!(r, Err(Error::InvalidField { .. })), "{r:?}");
    // Dirichlet conditions are not a heat option.
    assert!(sphere_heat::<B>(&HeatOptions::paper(17, 1, Bc::Dirichlet)).is_err());
}
