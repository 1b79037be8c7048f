//! Level-set back ends behind one contract, [`LevelSetBackend`]: every back end answers the same
//! questions — build from an implicit function, advance by mean curvature, advect, redistance,
//! enclosed measure, interface measure, interface curvature, zero level — so one problem runs
//! through all of them and their answers can be compared.
//!
//! A back end owns its discretisation (an adapted triangulation, a narrow band of a uniform
//! grid, an interface-fitted mesh, ...) and a level-set function `u` on it, negative inside and
//! positive outside (004 §2.1). The contract speaks only of the function and its zero level
//! `Γ = {u = 0}`, never of meshes: a back end that is not simplicial (the DT-Grid band of 000 §3)
//! implements it with its own storage.
//!
//! **Dimension.** The trait is generic over a [`Dimension`] marker, [`D2`] or [`D3`], which names
//! the point type (`DVec2`, `DVec3`), the implicit function a back end is built from and the
//! shape of the zero level (closed or open polylines in 2D, a triangle surface in 3D). A back end
//! implements the contract for the dimensions it supports; `Box<dyn LevelSetBackend<D2>>` is a
//! 2D back end of any kind.
//!
//! **Cost and accuracy** are each back end's own: every step returns a [`StepReport`] (degrees
//! of freedom, phase times, solver iterations, whether the inner loops converged), and "a valid
//! result whose inner loop did not converge" is reported there, not as an error.
//!
//! Files: `mod.rs` (the contract), `report.rs` (step reports, curvature samples), `implicit.rs` (a closure as an implicit shape), `adapted/` (the anisotropic
//! adapted mesh of 004), `dtgrid/` (Q1 finite elements on a DT-Grid narrow band, 000),
//! `fitted/` (the interface-fitted mesh of 001), `surface/` (parametric curves and surfaces moved
//! by Dziuk's scheme, 002: the reference the level-set back ends are cross-checked against).

pub mod adapted;
pub mod dtgrid;
pub mod fitted;
mod implicit;
mod report;
pub mod surface;

pub use crate::levelset::TriangleSurface;
pub use adapted::{AdaptedBackend, AdaptedOptions, McfScheme, Redistancing};
pub use dtgrid::{DtGridBackend, DtGridOptions};
pub use fitted::{fit, FitOptions, FittedMesh};
pub use implicit::FnShape;
pub use report::{CurvatureSamples, PhaseTimes, StepReport};
pub use surface::{ParametricCurve, ParametricSurface};

use crate::error::Result;
use crate::geom::{DVec2, DVec3};
use crate::levelset::{Polyline, Shape};

/// A space dimension for back ends: the point type, the implicit functions a back end is built
/// from and the shape of the zero level.
pub trait Dimension: 'static {
    /// The number of space dimensions.
    const DIM: usize;
    /// A point (`DVec2` or `DVec3`).
    type Point: Copy + std::fmt::Debug + Send + Sync;
    /// An implicit function whose zero level is the interface, negative inside (004 §2.1).
    type Function<'a>: ?Sized + Sync + 'a;
    /// The discrete zero level: polylines in 2D, a triangle surface in 3D.
    type ZeroLevel: std::fmt::Debug + Clone;
    /// The Euclidean length of a vector.
    fn length(v: Self::Point) -> f64;
}

/// Two space dimensions: points `DVec2`, implicit functions [`Shape`] (signed distance with
/// gradient and Hessian, exact or by differences; [`FnShape`] wraps a plain closure), zero level
/// as [`Polyline`]s (closed curves run counter-clockwise around the inside).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct D2;

impl Dimension for D2 {
    const DIM: usize = 2;
    type Point = DVec2;
    type Function<'a> = dyn Shape + 'a;
    type ZeroLevel = Vec<Polyline>;
    fn length(v: DVec2) -> f64 {
        v.length()
    }
}

/// Three space dimensions: points `DVec3`, implicit functions given by their value, zero level
/// as a [`TriangleSurface`] (triangles oriented with the inside behind them).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct D3;

impl Dimension for D3 {
    const DIM: usize = 3;
    type Point = DVec3;
    type Function<'a> = dyn Fn(DVec3) -> f64 + Send + Sync + 'a;
    type ZeroLevel = TriangleSurface;
    fn length(v: DVec3) -> f64 {
        v.length()
    }
}

/// What a back end is built from: an implicit function, the box it lives in and the resolution
/// across the interface.
pub struct BuildSpec<'a, D: Dimension> {
    /// The implicit function; its zero level is the initial interface. It need not be a distance
    /// function: the back end's field after building is a signed distance to the zero level
    /// (up to the back end's discretisation error).
    pub function: &'a D::Function<'a>,
    /// The computational box `(lo, hi)`.
    pub domain: (D::Point, D::Point),
    /// The length scale resolved across the interface: the smallest mesh size of an adapted mesh
    /// (`hmin` of 004 eq. (6)), the grid spacing of a narrow band (000 §2), the base mesh size of
    /// an interface-fitted mesh (001 §2). Back ends derive their other parameters from it
    /// through their own options.
    pub resolution: f64,
}

impl<D: Dimension> Clone for BuildSpec<'_, D> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<D: Dimension> Copy for BuildSpec<'_, D> {}

/// A velocity field `v(t, x)` in dimension `D`.
pub type VelocityField<'a, D> =
    &'a (dyn Fn(f64, <D as Dimension>::Point) -> <D as Dimension>::Point + Sync);

/// The contract every level-set back end implements (see the module documentation).
///
/// The back end holds a time `t` (0 after building), a discretisation and a level-set function
/// `u` on it, negative inside. The steps move `t` forward; the queries do not change the state.
/// Every method returns [`crate::Error`] on bad input or a broken state (a non-finite time step,
/// a zero level that vanished: [`crate::Error::EmptyLevelSet`]) and never panics.
pub trait LevelSetBackend<D: Dimension> {
    /// A short name for tables and reports (`"adapted"`, `"dtgrid"`, `"fitted"`, ...).
    fn name(&self) -> &'static str;

    /// Builds the back end from `spec` with its default options: the discretisation resolves the
    /// zero level of `spec.function` at `spec.resolution`, and `u` is a signed distance to it
    /// (004 §2.2, 000 §2.3, 001 §4). Errors: invalid options or domain, a function with no zero
    /// level in the domain ([`crate::Error::EmptyLevelSet`]).
    fn build(spec: &BuildSpec<'_, D>) -> Result<Self>
    where
        Self: Sized;

    /// The current time.
    fn time(&self) -> f64;

    /// The degrees of freedom of the level-set function (vertices, band nodes).
    fn dof(&self) -> usize;

    /// Moves the zero level by mean curvature over `[t, t + dt]`: the normal velocity is `-κ`
    /// with `κ = div(∇u/|∇u|)` (the sum of the principal curvatures, positive where the inside is
    /// convex), so a circle of radius `R0` follows `R(t) = √(R0² − 2t)` and a sphere
    /// `R(t) = √(R0² − 4t)` (000 §2, eq. (2.4)–(2.5); 002). Afterwards `u` is close to a
    /// signed distance to the new zero level (how close is the back end's documented choice;
    /// [`LevelSetBackend::redistance`] gives the distance itself). Error: [`crate::Error::EmptyLevelSet`] when the zero level
    /// vanishes during the step (the state is then unspecified).
    fn advance_mean_curvature(&mut self, dt: f64) -> Result<StepReport>;

    /// Transports `u` by the velocity field `v(t, x)` over `[t, t + dt]`:
    /// `u(t + dt, x) = u(t, X(t))` along the characteristics `dX/ds = v(s, X)` (004 §2.2,
    /// eq. (2)). `u` is not redistanced (call [`LevelSetBackend::redistance`]); for a
    /// divergence-free `v` the enclosed measure is kept up to the scheme's error.
    fn advect(&mut self, velocity: VelocityField<'_, D>, dt: f64) -> Result<StepReport>;

    /// Replaces `u` by a signed distance to its zero level: `|∇u| = 1` near `Γ` up to the
    /// discretisation error, sign kept, zero level moved by at most that error (004 §2.2; 003
    /// §5–§6; 001 §4; 000 §2.3). The time does not change.
    fn redistance(&mut self) -> Result<StepReport>;

    /// The measure of the inside `{u < 0}`: area in 2D, volume in 3D, of the back end's own
    /// discrete zero level (004 §5.1).
    fn enclosed_measure(&self) -> Result<f64>;

    /// The measure of the zero level: length in 2D, area in 3D (004 §5.1).
    fn interface_measure(&self) -> Result<f64>;

    /// Samples of the curvature `κ = div(∇u/|∇u|)` on the zero level (1/R on a circle, 2/R on a
    /// sphere), with the points where they are taken (001 §5, 000 §2, 004 §4.3).
    fn interface_curvature(&self) -> Result<CurvatureSamples<D>>;

    /// The discrete zero level (polylines in 2D, a triangle surface in 3D).
    fn zero_level(&self) -> Result<D::ZeroLevel>;

    /// The values of `u` at `points`; `None` where the back end does not represent `u` (outside
    /// the domain, or outside a narrow band).
    fn evaluate(&self, points: &[D::Point]) -> Result<Vec<Option<f64>>>;
}

/// Checks a time step: finite and positive.
pub(crate) fn check_dt(dt: f64, what: &str) -> Result<()> {
    if dt.is_finite() && dt > 0.0 {
        Ok(())
    } else {
        Err(crate::Error::InvalidInput(format!(
            "{what}: the time step must be finite and positive (got {dt})"
        )))
    }
}

/// The number of equal sub-steps of an advection step from `ta` to `tb` that move no point of
/// `points` by more than `cell` per sub-step, from the largest speed `|v(ta, x)|`, `|v(tb, x)|`
/// over the points. Errors: [`crate::Error::InvalidField`] for a non-finite velocity (naming the
/// point), [`crate::Error::InvalidInput`] for more than 10⁹ sub-steps (`what` names the step).
pub(crate) fn advection_substeps<D: Dimension>(
    points: &[D::Point],
    velocity: VelocityField<'_, D>,
    (ta, tb): (f64, f64),
    cell: f64,
    what: &str,
) -> Result<usize> {
    use rayon::prelude::*;
    let vmax = points
        .par_iter()
        .map(|&x| {
            let s = D::length(velocity(ta, x)).max(D::length(velocity(tb, x)));
            if s.is_finite() {
                Ok(s)
            } else {
                Err(crate::Error::InvalidField {
                    name: "velocity".into(),
                    msg: format!("non-finite at {x:?}"),
                })
            }
        })
        .try_reduce(|| 0.0, |a, b| Ok(a.max(b)))?;
    let dt = tb - ta;
    let steps = (vmax * dt / cell).ceil().max(1.0);
    if steps > 1e9 {
        return Err(crate::Error::InvalidInput(format!(
            "{what}: dt = {dt} at speed {vmax} needs {steps} sub-steps"
        )));
    }
    Ok(steps as usize)
}
