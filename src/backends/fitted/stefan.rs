//! The Stefan loop of 001 §6 on an interface-fitted mesh. Per step (001 §6 steps 2–9): the
//! zero level fitted into the base mesh and the curvature κ on it ([`StefanCurvature`]: a
//! least-squares parabola along the interface, or as 001 by local averaging (5.2) on the base
//! mesh interpolated onto the cut points); one
//! implicit Euler step of the heat equation (6.1) on the fitted mesh with the Gibbs–Thomson value
//! `T = −ε_C(θ) κ − ε_V(θ) v_n` (6.2) on the interface (`θ` the angle of the outward normal, `v_n`
//! the previous step's extended velocity) and insulated walls (6.3) or prescribed boundary
//! values; the Stefan velocity `v_n = −[∂T/∂n]` (6.4) at the interface vertices; its extension
//! off the interface ([`VelocityExtension`]: by default the least-squares extension of 001 §3,
//! [`super::extend_velocity`], on a band around the interface); unrefinement (the extension
//! restricted to the base vertices); `φ ← φ − Δt v_ext` on the base vertices of the band; and
//! redistancing to the exact distance to the P1 zero level
//! ([`crate::levelset::redistance::redistance_geometric`]), negative in the solid, by default
//! optionally keeping the values at the ends of the cut edges
//! ([`StefanOptions::keep_interface`]).
//!
//! Cuts within `snap_distance` of a base vertex are snapped to it (the fitting's one snapping
//! rule, [`FitOptions::snap`]): the gradient-jump rows of the extension on thinner slivers
//! would dominate its normal equations.

use super::curvature::{interface_fit_curvature, vertex_curvature, vertex_normals};
use super::extension::{extend_velocity, ExtensionKind, ExtensionOptions};
use super::fit::{fit, FitOptions, FittedMesh, REF_INSIDE};
use super::stefan_energy::{interface_dual_lengths, restrict_conservative, StefanBudget};
use super::stefan_flux::{stefan_velocity_quadratic, stefan_velocity_residual};
use crate::error::{Error, Result};
use crate::fem::p1::lumped_mass;
use crate::flows::stefan::{heat_step, stefan_velocity};
use crate::geom::{simplex, DVec2};
use crate::levelset::interface::enclosed_area;
use crate::levelset::redistance::redistance_geometric;
use crate::mesh::{check_p1_field, Mesh2};

/// The state of the Stefan loop on the base mesh.
#[derive(Debug, Clone)]
pub struct StefanState {
    /// Signed distance to the interface at the base vertices, negative in the solid.
    pub phi: Vec<f64>,
    /// Temperature at the base vertices.
    pub temperature: Vec<f64>,
    /// The extended normal velocity of the last step at the base vertices (0 outside the
    /// band; enters the kinetic term of (6.2)).
    pub velocity: Vec<f64>,
    /// Current time.
    pub time: f64,
}

impl StefanState {
    /// A state at rest: the level set `phi`, the temperature, the time; velocity 0.
    pub fn new(phi: Vec<f64>, temperature: Vec<f64>, time: f64) -> StefanState {
        let velocity = vec![0.0; phi.len()];
        StefanState {
            phi,
            temperature,
            velocity,
            time,
        }
    }
}

/// What one step of [`stefan_step`] did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StefanStepReport {
    /// Vertices of the fitted mesh.
    pub fitted_vertices: usize,
    /// Largest `|v_n|` over the interface vertices.
    pub max_vn: f64,
    /// Conjugate-gradient iterations of the heat step.
    pub cg_iterations: usize,
    /// Unknowns of the velocity extension (0 for the averaged one).
    pub extension_unknowns: usize,
    /// Largest `|T|` prescribed on the interface by (6.2).
    pub max_interface_temperature: f64,
    /// The step's terms of the energy balance `∫T − A` (latent heat 1).
    pub budget: StefanBudget,
}

/// How the interface velocity is extended off the interface (001 §6 step 6).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum VelocityExtension {
    /// The least-squares extension of 001 §3 with the gradient-jump rows (3.9).
    LeastSquares,
    /// The harmonic extension of 001 §3 (continuous, kinked across the interface).
    Harmonic,
    /// Each base vertex at distance `d` from the nearest interface vertex gets the mean of `v_n`
    /// over the interface vertices within `d + smoothing`, weighted by their share of the
    /// interface length (constant along the normals, first order; smooths out short waves).
    Averaged {
        /// The averaging length beyond the nearest interface vertex.
        smoothing: f64,
    },
}

/// The angular dependence of a Gibbs–Thomson coefficient (001 §6), `θ` the angle of the outward
/// normal with the x axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Anisotropy {
    /// `ε(θ) = ε̄`.
    Isotropic,
    /// `ε(θ) = ε̄ (8/3) sin⁴(2(θ − phase))` (001 Fig. 6.3 with phase 45°; mean ε̄).
    Sin4 {
        /// Phase angle, radians.
        phase: f64,
    },
    /// `ε(θ) = ε̄ [1 − cos 4(θ + θ₀)]` (the fourfold anisotropy of 001 Fig. 6.4).
    Cos4 {
        /// Phase angle θ₀, radians.
        phase: f64,
    },
}

/// A Gibbs–Thomson coefficient `ε(θ)` of 001 (6.2): a mean value and its angular dependence.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coefficient {
    /// The mean value `ε̄`.
    pub mean: f64,
    /// The angular dependence.
    pub anisotropy: Anisotropy,
}

impl Coefficient {
    /// The coefficient 0 (no surface tension or no kinetic term).
    pub const ZERO: Coefficient = Coefficient {
        mean: 0.0,
        anisotropy: Anisotropy::Isotropic,
    };

    /// The value at the normal angle `theta` (radians).
    pub fn value(&self, theta: f64) -> f64 {
        match self.anisotropy {
            Anisotropy::Isotropic => self.mean,
            Anisotropy::Sin4 { phase } => {
                self.mean * (8.0 / 3.0) * (2.0 * (theta - phase)).sin().powi(4)
            }
            Anisotropy::Cos4 { phase } => self.mean * (1.0 - (4.0 * (theta + phase)).cos()),
        }
    }
}

/// Options of [`stefan_step`].
#[derive(Clone, Copy)]
pub struct StefanOptions<'a> {
    /// Time step.
    pub dt: f64,
    /// Half-width of the band around the interface in which the velocity is extended and the
    /// level set moved (the other base vertices keep their sign and get their new distance
    /// from the redistancing).
    pub band: f64,
    /// Cuts closer than this to a base vertex are snapped to it (a small fraction of `h`).
    pub snap_distance: f64,
    /// The velocity extension.
    pub extension: VelocityExtension,
    /// Surface tension coefficient `ε_C(θ)` of (6.2).
    pub eps_c: Coefficient,
    /// Kinetic coefficient `ε_V(θ)` of (6.2).
    pub eps_v: Coefficient,
    /// The temperature on the outer boundary at the new time, `boundary(p, t)` (for an exact
    /// solution); insulated walls (6.3) without it.
    pub boundary: Option<&'a dyn Fn(DVec2, f64) -> f64>,
    /// Keep the moved level set at the ends of the cut base edges when redistancing (only the
    /// other vertices get the distance to the P1 zero level), so that redistancing does not move
    /// the interface. Otherwise every vertex is redistanced, which shrinks a convex interface by
    /// `O(h² κ)` per step (the P1 interpolant of the distance to a polygon lies outside it near
    /// its corners).
    pub keep_interface: bool,
    /// How the one-sided normal derivatives of the Stefan condition (6.4) are computed.
    pub flux: StefanFlux,
    /// How the curvature of the Gibbs–Thomson relation (6.2) is computed.
    pub curvature: StefanCurvature,
    /// How the level set is moved with the extended velocity (001 §6 step 8).
    pub advection: StefanAdvection,
    /// Restrict the temperature to the base mesh keeping `∫T`
    /// (the heat of the kink across the interface, which the plain
    /// restriction cuts off, is given back to the vertices of the cut triangles). Otherwise the
    /// base vertices keep their values.
    pub conservative_transfer: bool,
}

/// The level-set update of 001 §6 step 8 on the base vertices of the band.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StefanAdvection {
    /// `φ ← φ − Δt v`: the level-set equation (001 (1.5)) for a signed distance (`|∇φ| = 1`).
    Plain,
    /// `φ ← φ − Δt v |∇φ|` (001 (1.5)), `|∇φ|` at a vertex the area-weighted mean of the P1
    /// gradient norms of its triangles cut by the zero level (all its triangles if none is cut),
    /// so the zero level moves with `v` where `φ` is not a distance (the ends of the cut edges
    /// that [`StefanOptions::keep_interface`] does not redistance).
    LevelSet,
}

/// The curvature `κ` of the Gibbs–Thomson relation (001 (6.2)) at the interface vertices.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StefanCurvature {
    /// 001 §6 step 2–3: the local-averaging curvature (5.2) at the base vertices
    /// ([`super::vertex_curvature`]), interpolated onto the cut points. Scattered on a
    /// redistanced level set (second differences of the cut points over one cell).
    LocalAveraging,
    /// The least-squares parabola through the interface vertices within `half_width` along the
    /// interface ([`super::interface_fit_curvature`]).
    InterfaceFit {
        /// Arc length on each side of the vertex.
        half_width: f64,
    },
}

/// The one-sided gradients of the Stefan condition (001 (6.4)) at the interface vertices.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StefanFlux {
    /// The area-weighted mean of each side's P1 gradients around the vertex
    /// ([`crate::flows::stefan::stefan_velocity`]): first order, biased where `∂²T/∂n² ≠ 0`.
    /// The bias depends on how the grid cuts the interface: without surface tension it selects
    /// the grid's directions (the pentagon seed of 001 Fig. 6.1 grows eight arms along the axes
    /// and diagonals of the Union-Jack grid, needles along the axes); with surface tension its
    /// smoothing keeps the arms of 001 Figs. 6.2–6.4 smooth.
    P1Mean,
    /// Each side's least-squares quadratic through the vertex over two rings
    /// ([`super::stefan_velocity_quadratic`]): second order for smooth `T`.
    Quadratic,
    /// The heat the heat step supplied at each interface vertex (its residual) per unit
    /// interface length and time ([`super::stefan_velocity_residual`]): the front's latent heat
    /// equals the heat supplied, so `∫T − A` is conserved.
    Residual {
        /// Passes of the conservative smoothing along the interface.
        smoothing_passes: usize,
    },
}

impl<'a> StefanOptions<'a> {
    /// The loop without surface tension or kinetic term: harmonic extension on a band of `3h`,
    /// cuts within `h/100` snapped, every vertex redistanced, insulated walls, the curvature
    /// (when `eps_c` is set) from the interface fit over `3h`
    /// ([`StefanCurvature::InterfaceFit`]: on the Union-Jack grid the local averaging (5.2)
    /// scatters by 13–49 % of κ, the fit by 2–7 %).
    ///
    /// The harmonic extension is the default because it is stable without surface tension: its
    /// kink across `Γ` damps the shortest waves of `v_n` (whose P1 one-sided gradients are
    /// noisy) after unrefinement. The least-squares extension passes them on unchanged, and with
    /// `ε_C = 0` the interface then breaks up within a few hundred steps (Frank's circle at
    /// n = 64, the pentagon seed at 129²); with `ε_C = 0.001` it ran stably on the pentagon,
    /// with the anisotropic `0.001 (8/3) sin⁴(2(θ − 45°))` (zero at four angles) it did not.
    pub fn new(dt: f64, h: f64) -> StefanOptions<'a> {
        StefanOptions {
            dt,
            band: 3.0 * h,
            snap_distance: 0.01 * h,
            extension: VelocityExtension::Harmonic,
            eps_c: Coefficient::ZERO,
            eps_v: Coefficient::ZERO,
            boundary: None,
            keep_interface: false,
            flux: StefanFlux::P1Mean,
            curvature: StefanCurvature::InterfaceFit {
                half_width: 3.0 * h,
            },
            advection: StefanAdvection::Plain,
            conservative_transfer: false,
        }
    }
}

/// `|∇φ|` at the base vertices for [`StefanAdvection::LevelSet`]: the area-weighted mean of the
/// P1 gradient norms of the triangles around each vertex that the zero level cuts (a sign change
/// or a zero among the vertex values), or of all its triangles when none is cut.
fn gradient_norms(base: &Mesh2, phi: &[f64]) -> Vec<f64> {
    let n = base.n_points();
    // Per vertex: [Σ area·|∇φ| over cut triangles, Σ area (cut), same over all triangles].
    let mut acc = vec![[0.0f64; 4]; n];
    for t in base.live_tris() {
        let tri = base.tris[t];
        let f = tri.map(|v| phi[v as usize]);
        let g = simplex::p1_gradient(&base.tri_points(t), &f).length();
        let a = base.tri_area(t).abs();
        let lo = f.iter().fold(f64::INFINITY, |m, &x| m.min(x));
        let hi = f.iter().fold(f64::NEG_INFINITY, |m, &x| m.max(x));
        let cut = lo <= 0.0 && hi >= 0.0;
        for &v in &tri {
            let e = &mut acc[v as usize];
            if cut {
                e[0] += a * g;
                e[1] += a;
            }
            e[2] += a * g;
            e[3] += a;
        }
    }
    acc.iter()
        .map(|e| {
            if e[1] > 0.0 {
                e[0] / e[1]
            } else if e[3] > 0.0 {
                e[2] / e[3]
            } else {
                1.0
            }
        })
        .collect()
}

fn check_options(o: &StefanOptions) -> Result<()> {
    let positive = |x: f64, what: &str| {
        if x.is_finite() && x > 0.0 {
            Ok(())
        } else {
            Err(Error::InvalidInput(format!(
                "Stefan step: the {what} must be finite and positive (got {x})"
            )))
        }
    };
    positive(o.dt, "time step")?;
    positive(o.band, "velocity band")?;
    if !(o.snap_distance.is_finite() && o.snap_distance >= 0.0) {
        return Err(Error::InvalidInput(format!(
            "Stefan step: the snapping distance must be finite and non-negative (got {})",
            o.snap_distance
        )));
    }
    if let VelocityExtension::Averaged { smoothing } = o.extension {
        if !(smoothing.is_finite() && smoothing >= 0.0) {
            return Err(Error::InvalidInput(format!(
                "Stefan step: the smoothing length must be finite and non-negative (got {smoothing})"
            )));
        }
    }
    for (c, name) in [
        (o.eps_c, "surface tension"),
        (o.eps_v, "kinetic coefficient"),
    ] {
        let phase_ok = match c.anisotropy {
            Anisotropy::Isotropic => true,
            Anisotropy::Sin4 { phase } | Anisotropy::Cos4 { phase } => phase.is_finite(),
        };
        if !(c.mean.is_finite() && c.mean >= 0.0 && phase_ok) {
            return Err(Error::InvalidInput(format!(
                "Stefan step: the {name} must be finite and non-negative with a finite phase \
                 (got {c:?})"
            )));
        }
    }
    Ok(())
}

/// The length-weighted mean extension ([`VelocityExtension::Averaged`]) at the base vertices
/// within `band`; other entries 0.
fn averaged_extension(
    fm: &FittedMesh,
    iface: &[usize],
    vn: &[f64],
    band: f64,
    smoothing: f64,
) -> Vec<f64> {
    let m = &fm.mesh;
    let weight = interface_dual_lengths(fm);
    let mut out = vec![0.0; fm.n_base_vertices];
    for (v, o) in out.iter_mut().enumerate() {
        if fm.u[v].abs() > band {
            continue;
        }
        let x = m.points[v];
        let d2: Vec<f64> = iface
            .iter()
            .map(|&w| (m.points[w] - x).length_squared())
            .collect();
        let dmin = d2.iter().fold(f64::INFINITY, |a, &b| a.min(b)).sqrt();
        let reach = (dmin + smoothing).powi(2);
        let (mut sw, mut sv) = (0.0f64, 0.0f64);
        for (k, &w) in iface.iter().enumerate() {
            if d2[k] <= reach {
                sw += weight[w];
                sv += weight[w] * vn[w];
            }
        }
        if sw > 0.0 {
            *o = sv / sw;
        }
    }
    out
}

/// One step of the Stefan loop (001 §6 steps 2–9) on `base` (see the module documentation).
///
/// Errors: a non-positive or non-finite `dt` or `band`, negative or non-finite coefficients,
/// fields of the wrong size or with non-finite values, a level set with no zero level
/// ([`Error::EmptyLevelSet`]), the solvers' errors.
pub fn stefan_step(
    base: &Mesh2,
    state: &mut StefanState,
    o: &StefanOptions,
) -> Result<StefanStepReport> {
    check_options(o)?;
    let nb = base.n_points();
    check_p1_field(nb, &state.phi, "level set")?;
    check_p1_field(nb, &state.temperature, "temperature")?;
    check_p1_field(nb, &state.velocity, "velocity")?;
    let surface_tension = o.eps_c.mean > 0.0;
    // Step 2: curvature on the base mesh (boundary vertices: 0).
    let kappa_base: Vec<f64> = match o.curvature {
        StefanCurvature::LocalAveraging if surface_tension => {
            let k = vertex_curvature(base, &state.phi)?;
            k.kappa.into_iter().map(|k| k.unwrap_or(0.0)).collect()
        }
        _ => vec![0.0; nb],
    };
    // Step 3: fit, interpolate κ, T and the previous velocity onto the fitted mesh.
    let max_phi = state.phi.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
    let fit_opts = FitOptions {
        iso: 0.0,
        snap: if max_phi > 0.0 {
            (o.snap_distance / max_phi).max(1e-12)
        } else {
            1e-12
        },
    };
    let fm = fit(base, &state.phi, &fit_opts)?;
    let m = &fm.mesh;
    let n = m.n_points();
    let mut on = vec![false; n];
    for [a, b] in fm.interface_edges() {
        on[a as usize] = true;
        on[b as usize] = true;
    }
    for (flag, &u) in on.iter_mut().zip(&fm.u) {
        if u == 0.0 {
            *flag = true;
        }
    }
    let kappa = match o.curvature {
        StefanCurvature::InterfaceFit { half_width } if surface_tension => {
            interface_fit_curvature(&fm, half_width)?
        }
        _ => fm.extend_from_base(&kappa_base)?,
    };
    let v_old = fm.extend_from_base(&state.velocity)?;
    let temp = fm.extend_from_base(&state.temperature)?;
    let normals = vertex_normals(&fm, &on);
    // Step 4: the heat step with the Gibbs–Thomson values (6.2).
    let t_new = state.time + o.dt;
    let mut fixed = on.clone();
    let mut values = vec![0.0; n];
    let mut max_t_gamma = 0.0f64;
    for v in 0..n {
        if on[v] {
            let theta = normals[v].y.atan2(normals[v].x);
            values[v] = -o.eps_c.value(theta) * kappa[v] - o.eps_v.value(theta) * v_old[v];
            max_t_gamma = max_t_gamma.max(values[v].abs());
        }
    }
    if let Some(bc) = o.boundary {
        for (v, &b) in m.boundary_vertex_flags().iter().enumerate() {
            if b && !on[v] {
                fixed[v] = true;
                values[v] = bc(m.points[v], t_new);
            }
        }
    }
    let mass_base = lumped_mass(base)?;
    let mass_fit = lumped_mass(m)?;
    let heat = |mass: &[f64], t: &[f64]| -> f64 { mass.iter().zip(t).map(|(a, b)| a * b).sum() };
    let area_old = enclosed_area(base, &state.phi)?;
    let area_fit = fm.area_inside();
    let heat_base_old = heat(&mass_base, &state.temperature);
    let heat_fit_old = heat(&mass_fit, &temp);
    let temp_old = temp.clone();
    let assignment_heat: f64 = (0..n)
        .filter(|&v| on[v])
        .map(|v| mass_fit[v] * (values[v] - temp[v]))
        .sum();
    let (temp, cg) = heat_step(m, &fixed, &values, &temp, o.dt)?;
    let heat_fit_new = heat(&mass_fit, &temp);
    // Step 5: the Stefan condition (6.4).
    let dual = interface_dual_lengths(&fm);
    let vn = match o.flux {
        StefanFlux::P1Mean => stefan_velocity(m, REF_INSIDE, &on, &normals, &temp)?,
        StefanFlux::Quadratic => stefan_velocity_quadratic(m, REF_INSIDE, &on, &normals, &temp)?,
        StefanFlux::Residual { smoothing_passes } => {
            stefan_velocity_residual(&fm, &on, &temp_old, &temp, o.dt, smoothing_passes)?
        }
    };
    let iface: Vec<usize> = (0..n).filter(|&v| on[v]).collect();
    let max_vn = iface.iter().fold(0.0f64, |a, &v| a.max(vn[v].abs()));
    let front_heat = o.dt * iface.iter().map(|&v| vn[v] * dual[v]).sum::<f64>();
    // Steps 6–7: extension, unrefinement.
    let (velocity, unknowns) = match o.extension {
        VelocityExtension::Averaged { smoothing } => {
            (averaged_extension(&fm, &iface, &vn, o.band, smoothing), 0)
        }
        kind => {
            let opts = ExtensionOptions {
                kind: if kind == VelocityExtension::Harmonic {
                    ExtensionKind::Harmonic
                } else {
                    ExtensionKind::LeastSquares
                },
                band: Some(o.band),
            };
            let e = extend_velocity(&fm, &vn, &on, &opts)?;
            (e.values[..fm.n_base_vertices].to_vec(), e.unknowns)
        }
    };
    // Steps 8–9: move the level set in the band, redistance.
    let mut phi = fm.u[..fm.n_base_vertices].to_vec();
    let grad = match o.advection {
        StefanAdvection::Plain => vec![1.0; phi.len()],
        StefanAdvection::LevelSet => gradient_norms(base, &phi),
    };
    for ((p, &v), &g) in phi.iter_mut().zip(&velocity).zip(&grad) {
        if p.abs() <= o.band {
            *p -= o.dt * v * g;
        }
    }
    let area_adv = enclosed_area(base, &phi)?;
    let mut redistanced = redistance_geometric(base, &phi)?;
    if o.keep_interface {
        for t in base.live_tris() {
            for i in 0..3 {
                let [a, b] = base.edge_vertices(t, i);
                let (a, b) = (a as usize, b as usize);
                if phi[a] * phi[b] <= 0.0 {
                    redistanced[a] = phi[a];
                    redistanced[b] = phi[b];
                }
            }
        }
    }
    let area_new = enclosed_area(base, &redistanced)?;
    state.phi = redistanced;
    state.temperature = if o.conservative_transfer {
        restrict_conservative(&fm, base, &temp, &mass_base)
    } else {
        fm.restrict_to_base(&temp)?
    };
    let budget = StefanBudget {
        transfer_in: heat_fit_old - heat_base_old,
        interface_heat: heat_fit_new - heat_fit_old,
        assignment_heat,
        front_heat,
        transfer_out: heat(&mass_base, &state.temperature) - heat_fit_new,
        area_snap: area_fit - area_old,
        area_advection: area_adv - area_fit,
        area_redistance: area_new - area_adv,
    };
    state.velocity = velocity;
    state.time = t_new;
    Ok(StefanStepReport {
        fitted_vertices: n,
        max_vn,
        cg_iterations: cg.iterations,
        extension_unknowns: unknowns,
        max_interface_temperature: max_t_gamma,
        budget,
    })
}

/// The deviation of the zero level of `phi` on `base` from the circle of radius `r` centred at
/// the origin: the mean and the largest `||p| − r|` over the vertices of the fitted interface, and
/// the radius `√(A/π)` of the disc with the enclosed area `A`.
///
/// Errors: those of [`fit`].
pub fn circle_deviation(base: &Mesh2, phi: &[f64], r: f64) -> Result<(f64, f64, f64)> {
    let fm = fit(base, phi, &FitOptions::default())?;
    let mut seen = vec![false; fm.mesh.n_points()];
    let (mut sum, mut max, mut count) = (0.0f64, 0.0f64, 0usize);
    for [a, b] in fm.interface_edges() {
        for v in [a as usize, b as usize] {
            if !seen[v] {
                seen[v] = true;
                let e = (fm.mesh.points[v].length() - r).abs();
                sum += e;
                max = max.max(e);
                count += 1;
            }
        }
    }
    let mean = if count > 0 { sum / count as f64 } else { 0.0 };
    Ok((mean, max, (fm.area_inside() / std::f64::consts::PI).sqrt()))
}
