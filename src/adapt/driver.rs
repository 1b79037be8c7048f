//! The adaptation driver of triangle meshes (004 §3.5): [`adapt`] with its options
//! ([`AdaptOptions`]) and report ([`AdaptReport`]). It validates the inputs, runs the
//! split/collapse cycles of `cycle.rs` on the triangle context (until the edge lengths are in
//! `[l_min, l_max]` or a cycle cap is reached, each cycle followed by flips and one smoothing
//! sweep, [`CycleSmoothing`]; then a few final flip/smooth sweeps), and compacts the mesh at the
//! end, remapping the metric and the fields.

use super::cycle::run_cycles;
pub use super::options::{AdaptOptions, AdaptReport, CycleSmoothing, PassKind, PassReport};
use super::params::OpParams;
use super::sources::MetricSource;
use super::tri::{compact_with_data, Ctx};
use crate::error::{Error, Result};
use crate::mesh::{Mesh2, NONE};
use crate::metric::Sym2;
use std::time::Instant;

/// Checks the inputs of [`adapt`]: a valid mesh, one SPD metric per vertex, fields of the right
/// length without NaN.
pub fn validate_inputs(mesh: &Mesh2, metric: &[Sym2], fields: &[Vec<f64>]) -> Result<()> {
    mesh.check()?;
    if metric.len() != mesh.n_points() {
        return Err(Error::InvalidInput(format!(
            "adapt: the metric has {} tensors for {} vertices",
            metric.len(),
            mesh.n_points()
        )));
    }
    for (v, m) in metric.iter().enumerate() {
        if mesh.vert_tri[v] != NONE {
            m.validate(v)?;
        }
    }
    for (k, f) in fields.iter().enumerate() {
        if f.len() != mesh.n_points() {
            return Err(Error::InvalidField {
                name: format!("field {k}"),
                msg: format!("{} values for {} vertices", f.len(), mesh.n_points()),
            });
        }
        if let Some(v) = f.iter().position(|x| !x.is_finite()) {
            return Err(Error::InvalidField {
                name: format!("field {k}"),
                msg: format!("non-finite value at vertex {v}"),
            });
        }
    }
    Ok(())
}

/// Adapts `mesh` to the vertex metric field `metric` (004 §3.5): afterwards (if `converged`)
/// every edge has metric length in `[l_min, l_max]` up to what collapses could not remove, and
/// the elements have been flipped and smoothed toward `Q_ani = 1`. The P1 `fields` are carried
/// through every operation (interpolated, or evaluated by `source` when it provides them); the
/// metric at new vertices comes from `source` when it has one (`metric_at` returns `Some`), else
/// it is interpolated by the rule of `opts.interpolation`. The mesh is compacted at the end; metric and fields are
/// renumbered with it.
///
/// Errors: an invalid mesh, a metric of the wrong length or not SPD (naming the vertex), a field
/// of the wrong length or with NaN, invalid options.
pub fn adapt(
    mesh: &mut Mesh2,
    metric: &mut Vec<Sym2>,
    fields: &mut [Vec<f64>],
    source: Option<&dyn MetricSource>,
    opts: &AdaptOptions,
) -> Result<AdaptReport> {
    let t0 = Instant::now();
    opts.validate()?;
    validate_inputs(mesh, metric, fields)?;
    let params = OpParams {
        l_min: opts.l_min,
        l_max: opts.l_max,
        q_max: opts.q_max,
        curve_tol: opts.curve_tol,
        insertion: opts.insertion,
        interpolation: opts.interpolation,
    };
    let mut rep = AdaptReport::default();
    run_cycles(
        &mut Ctx::new(mesh, metric, fields, source, params),
        opts,
        &mut rep,
    )?;
    compact_with_data(mesh, metric, fields);
    if opts.check_each_pass {
        mesh.check()?;
    }
    rep.seconds = t0.elapsed().as_secs_f64();
    Ok(rep)
}
