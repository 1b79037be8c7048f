//! One implicit Euler step of the heat equation (001 (6.1)) with the temperature prescribed at
//! the interface vertices (the Gibbs–Thomson relation (6.2)) and insulated outer walls (6.3).

use crate::error::{Error, Result};
use crate::fem::{self, CgOptions, CgReport, Csr};
use crate::mesh::{check_p1_field, Mesh2};

/// Advances the P1 temperature `temperature` by `dt`: `(M_L + dt K) Tⁿ⁺¹ = M_L Tⁿ` with the
/// lumped mass `M_L` (so the discrete maximum principle holds on acute meshes), `Tⁿ⁺¹ =
/// interface_values` where `on_interface`, and the natural condition `∂T/∂n = 0` on `∂Ω`.
///
/// `on_interface` and `interface_values` are indexed by vertex (`interface_values` is read only
/// where `on_interface`). Errors: sizes that do not match the mesh, non-finite values, a
/// non-positive or non-finite `dt`, degenerate triangles.
pub fn heat_step(
    mesh: &Mesh2,
    on_interface: &[bool],
    interface_values: &[f64],
    temperature: &[f64],
    dt: f64,
) -> Result<(Vec<f64>, CgReport)> {
    let n = mesh.n_points();
    if !(dt.is_finite() && dt > 0.0) {
        return Err(Error::InvalidInput(format!(
            "heat step: the time step must be finite and positive (got {dt})"
        )));
    }
    check_p1_field(mesh.n_points(), temperature, "temperature")?;
    if on_interface.len() != n || interface_values.len() != n {
        return Err(Error::InvalidInput(format!(
            "heat step: the mesh has {n} vertices but the interface mask and values have {} and {}",
            on_interface.len(),
            interface_values.len()
        )));
    }
    if let Some(v) = (0..n).find(|&v| on_interface[v] && !interface_values[v].is_finite()) {
        return Err(Error::InvalidInput(format!(
            "heat step: the interface value at vertex {v} is not finite ({})",
            interface_values[v]
        )));
    }
    let lumped = fem::p1::lumped_mass(mesh)?;
    let mut a: Csr = fem::p1::stiffness(mesh, &fem::p1::Coef::Const(dt))?;
    for (i, m) in lumped.iter().enumerate() {
        a.add(i, i, *m)?;
    }
    let mut b: Vec<f64> = lumped.iter().zip(temperature).map(|(m, t)| m * t).collect();
    fem::dirichlet::apply_dirichlet(&mut a, &mut b, on_interface, interface_values)?;
    let mut x = temperature.to_vec();
    for v in 0..n {
        if on_interface[v] {
            x[v] = interface_values[v];
        }
    }
    let opts = CgOptions {
        rtol: 1e-12,
        ..CgOptions::default()
    };
    let report = fem::solve::cg(&a, &b, &mut x, &opts)?;
    Ok((x, report))
}
