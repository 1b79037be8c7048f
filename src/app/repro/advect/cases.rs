//! The transport cases: the single vortex (LeVeque 1996, Rider & Kothe 1998), the four-vortex
//! deformation, the Zalesak rotation (004 §5.1) and a user's shape and velocity expressions.

use anisomesh::advect::ExprVelocity;
use anisomesh::error::{Error, Result};
use anisomesh::geom::DVec2;
use anisomesh::levelset::shapes::{Shape, Zalesak};
use anisomesh::levelset::Expr;
use std::sync::Arc;

/// The initial level set of a case (negative inside).
pub type LevelSet = Arc<dyn Fn(DVec2) -> f64 + Send + Sync>;

/// A transport problem: shape, velocity, domain, time interval and its default resolution.
#[derive(Clone)]
pub struct Case {
    /// Short name (`vortex`, `deformation`, `zalesak`, `custom`).
    pub name: String,
    /// The initial shape, as text.
    pub shape_source: String,
    /// The initial level set.
    pub phi0: LevelSet,
    /// The velocity.
    pub velocity: ExprVelocity,
    /// The domain `[lo, hi]`.
    pub domain: (DVec2, DVec2),
    /// The final time.
    pub t_end: f64,
    /// Whether the exact shape at `t_end` is the initial one (time-reversed or periodic flow).
    pub returns: bool,
    /// Default number of periods.
    pub periods: usize,
    /// Default adaptation: `hmin`, `hmax`, `eps`, `band`.
    pub sizes: [f64; 4],
}

/// A disk of radius `r` centred at `c` (signed distance, negative inside).
fn disk(c: DVec2, r: f64) -> LevelSet {
    Arc::new(move |p: DVec2| (p - c).length() - r)
}

/// The single vortex with reversal time `t`: the disk `r = 0.15` at `(0.5, 0.75)` in the unit
/// square, `u = -sin²(πx) sin(2πy) cos(πt/T)`, `v = sin²(πy) sin(2πx) cos(πt/T)`.
pub fn vortex(t: f64) -> Result<Case> {
    let velocity = ExprVelocity::parse(&format!(
        "-sin(pi*x)^2*sin(2*pi*y)*cos(pi*t/{t}); sin(pi*y)^2*sin(2*pi*x)*cos(pi*t/{t})"
    ))?;
    Ok(Case {
        name: "vortex".into(),
        shape_source: "sqrt((x-0.5)^2+(y-0.75)^2)-0.15".into(),
        phi0: disk(DVec2::new(0.5, 0.75), 0.15),
        velocity,
        domain: (DVec2::ZERO, DVec2::ONE),
        t_end: t,
        returns: true,
        periods: (4.0 * t).round().max(8.0) as usize,
        sizes: [2.5e-4, 0.05, 2.5e-4, 1e-3],
    })
}

/// The four-vortex deformation with reversal time `t`: the disk `r = 0.15` centred at
/// `(0.5, 0.5)`, `u = sin(4π(x + ½)) sin(4π(y + ½)) cos(πt/T)`,
/// `v = cos(4π(x + ½)) cos(4π(y + ½)) cos(πt/T)`. The cells of this field are closed between
/// `y = 1/8` and `y = 7/8` only (`v ≠ 0` on the walls `y = 0, 1`): the single vortex's disk at
/// `(0.5, 0.75)` reaches above `y = 7/8` and is carried out of the square, so the disk is
/// centred where its cells are closed.
pub fn deformation(t: f64) -> Result<Case> {
    let velocity = ExprVelocity::parse(&format!(
        "sin(4*pi*(x+0.5))*sin(4*pi*(y+0.5))*cos(pi*t/{t}); cos(4*pi*(x+0.5))*cos(4*pi*(y+0.5))*cos(pi*t/{t})"
    ))?;
    Ok(Case {
        name: "deformation".into(),
        shape_source: "sqrt((x-0.5)^2+(y-0.5)^2)-0.15".into(),
        phi0: disk(DVec2::new(0.5, 0.5), 0.15),
        periods: (16.0 * t).round().max(8.0) as usize,
        velocity,
        t_end: t,
        ..vortex(t)?
    })
}

/// The Zalesak rotation of 004 §5.1: the slotted disk in `[-2, 2]²`, `v = (-y, x)`, one
/// revolution in 16 periods, with the sizes of `anisomesh zalesak`.
pub fn zalesak() -> Result<Case> {
    let shape = Zalesak::default();
    Ok(Case {
        name: "zalesak".into(),
        shape_source: "zalesak slotted disk".into(),
        phi0: Arc::new(move |p| shape.distance(p)),
        velocity: ExprVelocity::parse("-y; x")?,
        domain: (DVec2::splat(-2.0), DVec2::splat(2.0)),
        t_end: 2.0 * std::f64::consts::PI,
        returns: true,
        periods: 16,
        sizes: [1e-3, 0.2, 1.2e-3, 2e-3],
    })
}

/// A user's shape expression (in `x`, `y`) and velocity `"U; V"` (in `x`, `y`, `t`).
pub fn custom(
    shape: &str,
    velocity: &str,
    domain: (DVec2, DVec2),
    t_end: f64,
    returns: bool,
) -> Result<Case> {
    let e = Expr::parse(shape).map_err(|e| Error::InvalidInput(format!("shape: {e}")))?;
    let velocity = ExprVelocity::parse(velocity)?;
    let ext = (domain.1 - domain.0).max_element();
    Ok(Case {
        name: "custom".into(),
        shape_source: shape.into(),
        phi0: Arc::new(move |p| e.eval(p)),
        velocity,
        domain,
        t_end,
        returns,
        periods: 32,
        sizes: [2.5e-4 * ext, 0.05 * ext, 2.5e-4 * ext, 1e-3 * ext],
    })
}

/// The built-in case `name` with the final (reversal) time `t_end` where the case takes one.
pub fn builtin(name: &str, t_end: Option<f64>) -> Result<Case> {
    match name {
        "vortex" => vortex(t_end.unwrap_or(8.0)),
        "deformation" => deformation(t_end.unwrap_or(2.0)),
        "zalesak" => {
            let mut c = zalesak()?;
            if let Some(t) = t_end {
                let turns = t / c.t_end;
                c.returns = (turns - turns.round()).abs() < 1e-9;
                c.t_end = t;
                c.periods = (16.0 * turns).round().max(1.0) as usize;
            }
            Ok(c)
        }
        other => Err(Error::InvalidInput(format!(
            "unknown case {other:?} (vortex, deformation, zalesak)"
        ))),
    }
}
