//! Band finite elements (000 §2): convergence orders of the surface heat equation and of mean
//! curvature motion on coarse grids, and the errors for bad input.

use anisomesh::backends::dtgrid::heat::{sphere_heat, HeatOptions};
use anisomesh::backends::dtgrid::lattice::C3;
use anisomesh::backends::dtgrid::scheme::Bc;
use anisomesh::backends::dtgrid::SortedBand;

type B = SortedBand<C3>;

#[test]
fn heat_transparent_converges_at_second_order_from_j2() {
    let mut errs = Vec::new();
    for n in [17, 33, 65] {
        let r = sphere_heat::<B>(&HeatOptions::paper(n, 2, Bc::Transparent)).unwrap();
        println!("heat transparent j=2 n={n}: {:.3e} ({} nodes)", r.error, r.nodes);
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
