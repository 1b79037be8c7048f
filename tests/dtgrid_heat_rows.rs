//! Where the spatial error of the transparent band heat equation on the `j = 2` band comes from
//! (000 §2.3, Table 2.1): the rows of the boundary nodes. For the exact solution `u` of the
//! sphere problem the scheme's rows `M u_t + L u − Γ[u]` (relative to `M u_t`) are consistent at
//! interior nodes and stay `O(1)` at the boundary nodes, whose test functions the band cuts off;
//! with the exact solution held on the boundary layer instead, the `j = 2` error is second order.

use anisomesh::backends::dtgrid::fem::{assemble, elements, transparent_vector, Weight};
use anisomesh::backends::dtgrid::ghost::GhostRows;
use anisomesh::backends::dtgrid::heat::{sphere_heat, HeatOptions, TimeScheme};
use anisomesh::backends::dtgrid::lattice::{
    band_around, crossing_cells_of_fn, Lattice, NarrowBand, C3,
};
use anisomesh::backends::dtgrid::scheme::{solve_dirichlet, system_matrix, Bc};
use anisomesh::backends::dtgrid::surface::{surface_integral, zero_level};
use anisomesh::backends::dtgrid::{Band, DtGrid};
use anisomesh::geom::DVec3;

const R: f64 = 1.0 / 3.0;
const T_END: f64 = 0.01;

/// The second spherical harmonic, constant along the normals of the sphere.
fn y(p: DVec3) -> f64 {
    (p.z / p.length()).powi(2) - 1.0 / 3.0
}

/// The band's exact solution: on the level set `|x| = r` the harmonic decays as `e^{−6t/r²}`.
fn exact(p: DVec3, t: f64) -> f64 {
    (-6.0 * t / p.length_squared()).exp() * y(p)
}

/// The band of half-width `j` around the sphere on `n³` nodes: lattice, band, node coordinates,
/// `Φ`.
fn band(n: usize, j: usize) -> (Lattice, NarrowBand<DtGrid<C3>>, Vec<C3>, Vec<f64>) {
    let lat = Lattice::unit(n).unwrap();
    let f = |p: DVec3| p.length() - R;
    let cross = crossing_cells_of_fn(&lat, &f).unwrap();
    let nb: NarrowBand<DtGrid<C3>> = band_around(&lat, &cross, j).unwrap();
    let coords: Vec<C3> = nb.band.coords().collect();
    let phi = coords.iter().map(|&c| f(lat.pos(c))).collect();
    (lat, nb, coords, phi)
}

/// The root mean square of `|M u_t + L u − Γ[u]| / (M max|u_t|)` at `t = 0` over the interior
/// and over the boundary nodes of the `j = 2` band on `n³`; with `ghost`, the rows completed by
/// the outside cells (extrapolated conditions: `Γ = 0`, the completed `M` and `L`).
fn row_defects(n: usize, ghost: bool) -> (f64, f64) {
    let (lat, nb, coords, phi) = band(n, 2);
    let nn = coords.len();
    let el = elements(&nb);
    let mut m = assemble(&lat, &el, nn, &phi, Weight::Heat).unwrap();
    if ghost {
        let g = GhostRows::new(&lat, &nb, &phi, Weight::Heat).unwrap();
        m.mass.iter_mut().zip(&g.mass).for_each(|(m, g)| *m += g);
        m.stiff = g.complete(&m.stiff).unwrap();
    }
    let u: Vec<f64> = coords.iter().map(|&c| exact(lat.pos(c), 0.0)).collect();
    let ut: Vec<f64> = coords
        .iter()
        .map(|&c| -6.0 / lat.pos(c).length_squared() * y(lat.pos(c)))
        .collect();
    let lu = m.stiff.mul(&u);
    let g = if ghost {
        vec![0.0; nn]
    } else {
        transparent_vector(&lat, &el, nn, &phi, &u, Weight::Heat)
    };
    let scale = ut.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let mut sums = [(0.0, 0usize); 2];
    for i in 0..nn {
        let r = (m.mass[i] * ut[i] + lu[i] - g[i]) / (m.mass[i] * scale);
        let s = &mut sums[usize::from(!nb.interior[i])];
        s.0 += r * r;
        s.1 += 1;
    }
    let rms = |(s, c): (f64, usize)| (s / c as f64).sqrt();
    (rms(sums[0]), rms(sums[1]))
}

#[test]
fn boundary_rows_of_the_j2_band_are_not_consistent() {
    let (i33, b33) = row_defects(33, false);
    let (i65, b65) = row_defects(65, false);
    println!(
        "row defect rms, interior / boundary: 33³ {i33:.3e} / {b33:.3e}, 65³ {i65:.3e} / {b65:.3e}"
    );
    // Interior rows converge; boundary rows do not and are far larger.
    assert!(i33 / i65 > 2.0, "interior {i33} -> {i65}");
    assert!(b65 > 0.8 * b33, "boundary {b33} -> {b65}");
    assert!(b65 > 20.0 * i65, "boundary {b65} vs interior {i65}");
}

/// The `j = 2` error `‖U − u‖_{L²(M_h)}` at `t = 0.01` by BDF2 (first step Crank–Nicolson) at
/// `τ = h²` with the exact solution on the boundary layer (Dirichlet, 000 (2.12)).
fn exact_boundary_error(n: usize) -> f64 {
    let (lat, nb, coords, phi) = band(n, 2);
    let nn = coords.len();
    let el = elements(&nb);
    let m = assemble(&lat, &el, nn, &phi, Weight::Heat).unwrap();
    let fixed: Vec<bool> = nb.interior.iter().map(|i| !i).collect();
    let steps = (T_END / (lat.h * lat.h) - 1e-9).ceil() as usize;
    let tau = T_END / steps as f64;
    let set_boundary = |u: &mut [f64], t: f64| {
        for (i, &c) in coords.iter().enumerate() {
            if fixed[i] {
                u[i] = exact(lat.pos(c), t);
            }
        }
    };
    let mut u: Vec<f64> = coords.iter().map(|&c| exact(lat.pos(c), 0.0)).collect();
    let mut prev = u.clone();
    let a = system_matrix(&m, 0.5 * tau).unwrap();
    let lu = m.stiff.mul(&u);
    let b: Vec<f64> = (0..nn)
        .map(|i| m.mass[i] * u[i] - 0.5 * tau * lu[i])
        .collect();
    set_boundary(&mut u, tau);
    solve_dirichlet(&a, &b, &fixed, &mut u).unwrap();
    let a = system_matrix(&m, 2.0 * tau / 3.0).unwrap();
    for k in 1..steps {
        let b: Vec<f64> = (0..nn)
            .map(|i| m.mass[i] * (4.0 * u[i] - prev[i]) / 3.0)
            .collect();
        let guess: Vec<f64> = (0..nn).map(|i| 2.0 * u[i] - prev[i]).collect();
        prev.copy_from_slice(&u);
        u.copy_from_slice(&guess);
        set_boundary(&mut u, (k + 1) as f64 * tau);
        solve_dirichlet(&a, &b, &fixed, &mut u).unwrap();
    }
    let z = zero_level(&lat, &nb.band, &phi);
    let decay = (-6.0 * T_END / (R * R)).exp();
    surface_integral(&lat, &nb.band, &z, &u, |x, ux| (ux - decay * y(x)).powi(2)).sqrt()
}

#[test]
fn exact_boundary_values_make_the_j2_band_second_order() {
    let e33 = exact_boundary_error(33);
    let e65 = exact_boundary_error(65);
    let order = (e33 / e65).log2();
    let mut o = HeatOptions::paper(65, 2, Bc::Transparent);
    o.time = TimeScheme::Bdf2;
    let transparent = sphere_heat::<DtGrid<C3>>(&o).unwrap().error;
    println!(
        "j = 2, BDF2, τ = h²: exact boundary layer {e33:.4e}, {e65:.4e} (order {order:.2}); \
         transparent on 65³ {transparent:.4e}"
    );
    assert!(order > 1.7, "order {order}");
    assert!(transparent > 2.0 * e65, "{transparent} vs {e65}");
}

#[test]
fn extrapolated_conditions_make_the_j2_band_second_order() {
    // The completed boundary rows are consistent: their defect falls with h.
    let (i33, b33) = row_defects(33, true);
    let (i65, b65) = row_defects(65, true);
    println!(
        "completed rows, defect rms interior / boundary: 33³ {i33:.3e} / {b33:.3e}, \
         65³ {i65:.3e} / {b65:.3e}"
    );
    let run = |n: usize, bc: Bc| {
        let mut o = HeatOptions::paper(n, 2, bc);
        o.time = TimeScheme::Bdf2;
        sphere_heat::<DtGrid<C3>>(&o).unwrap().error
    };
    let (e33, e65) = (run(33, Bc::Extrapolated), run(65, Bc::Extrapolated));
    let order = (e33 / e65).log2();
    let transparent = run(65, Bc::Transparent);
    println!(
        "j = 2, BDF2, τ = h²: extrapolated {e33:.4e}, {e65:.4e} (order {order:.2}); \
         transparent on 65³ {transparent:.4e}"
    );
    assert!(order > 1.7, "order {order}");
    assert!(e65 < 0.6 * transparent, "{e65} vs {transparent}");
    assert!(b33 / b65 > 1.5, "boundary {b33} -> {b65}");
}
