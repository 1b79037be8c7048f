//! The [`Adapter`] used by the transient fixed point with the anisotropic engine: the
//! geometric level-set metric of each field (004 eq. (6), through
//! [`crate::adapt::LevelSetMetric`], derivatives recovered by [`crate::recovery::recover_ls`]),
//! intersected over the fields (004 §3.5, [`crate::metric::intersect()`]), then
//! [`crate::adapt::adapt`].

use super::fixed_point::Adapter;
use crate::adapt::{adapt, AdaptOptions, AdaptReport, LevelSetMetric};
use crate::error::{Error, Result};
use crate::mesh::Mesh2;
use crate::metric::{intersect, Sym2};
use crate::recovery::recover_ls;
use rayon::prelude::*;

/// Adapts to the intersection of the level-set metrics of the given fields.
#[derive(Debug, Clone)]
pub struct LevelSetAdapter {
    /// The metric of one level set (eq. (6), bounds, band, gradation, isotropic variant).
    pub metric: LevelSetMetric,
    /// The remeshing options.
    pub opts: AdaptOptions,
    /// Reports of the adaptations performed so far.
    pub reports: Vec<AdaptReport>,
}

impl LevelSetAdapter {
    /// An adapter with the given metric and remeshing options.
    pub fn new(metric: LevelSetMetric, opts: AdaptOptions) -> Result<LevelSetAdapter> {
        metric.validate()?;
        Ok(LevelSetAdapter {
            metric,
            opts,
            reports: Vec::new(),
        })
    }

    /// The intersected metric field of `fields` on `mesh`.
    pub fn metric_field(&self, mesh: &Mesh2, fields: &[Vec<f64>]) -> Result<Vec<Sym2>> {
        let mut out: Option<Vec<Sym2>> = None;
        for u in fields {
            let r = recover_ls(mesh, u)?;
            let m: Vec<Sym2> = (0..mesh.n_points())
                .into_par_iter()
                .map(|v| self.metric.metric(u[v], r.gradient[v], &r.hessian[v]))
                .collect();
            out = Some(match out {
                None => m,
                Some(prev) => prev
                    .par_iter()
                    .zip(&m)
                    .map(|(a, b)| intersect(a, b))
                    .collect(),
            });
        }
        out.ok_or_else(|| Error::InvalidInput("level-set adapter: no field given".into()))
    }
}

impl Adapter for LevelSetAdapter {
    fn adapt(&mut self, mesh: &Mesh2, fields: &[Vec<f64>]) -> Result<Mesh2> {
        let mut metric = self.metric_field(mesh, fields)?;
        let mut m = mesh.clone();
        let rep = adapt(&mut m, &mut metric, &mut [], None, &self.opts)?;
        self.reports.push(rep);
        Ok(m)
    }
}
