//! The options of the redistancing experiments and what they measure: one row per level, one
//! table per shape, degree and `α`, the volume drift of the sphere, and the report serialised as
//! `reinit.json`.

use std::path::PathBuf;

use serde::Serialize;

use anisomesh::levelset::redistance::PprReport;

/// Options of [`super::run()`].
#[derive(Debug, Clone)]
pub struct ReinitOptions {
    /// Refinement levels `ℓ` of the torus (003 §8 uses 3..=8).
    pub levels_3d: Vec<u32>,
    /// Levels of the 2D circle.
    pub levels_2d: Vec<u32>,
    /// Values of `α` (1, 10 and the stress case 50).
    pub alphas: Vec<u32>,
    /// Polynomial degrees `k`.
    pub degrees: Vec<usize>,
    /// Levels of the sphere volume-drift test (003 uses 5 and 6).
    pub volume_levels: Vec<u32>,
    /// Number of repeated redistancings (003: 100).
    pub volume_reps: usize,
    /// Directory for `reinit.json` (nothing written when `None`).
    pub out_dir: Option<PathBuf>,
    /// Print the tables to standard output.
    pub print: bool,
}

impl Default for ReinitOptions {
    fn default() -> Self {
        ReinitOptions {
            levels_3d: (3..=5).collect(),
            levels_2d: (3..=8).collect(),
            alphas: vec![1, 10, 50],
            degrees: vec![1, 2],
            volume_levels: vec![4],
            volume_reps: 100,
            out_dir: None,
            print: true,
        }
    }
}

/// One row of a convergence table.
#[derive(Debug, Clone, Serialize)]
pub struct Row {
    pub level: u32,
    pub h: f64,
    pub e_inf: f64,
    pub order_inf: Option<f64>,
    pub e_grad: f64,
    pub order_grad: Option<f64>,
    /// Redistancing statistics (not in the JSON).
    #[serde(skip)]
    pub report: PprReport,
    /// Wall time of the case (mesh, interpolation, redistancing, errors), seconds.
    #[serde(skip)]
    pub secs: f64,
    /// Peak resident memory of the process after the case (`VmHWM`, MiB; `None` off Linux).
    #[serde(skip)]
    pub peak_mib: Option<f64>,
}

/// One convergence table.
#[derive(Debug, Clone, Serialize)]
pub struct Table {
    pub name: String,
    pub dim: usize,
    pub k: usize,
    pub alpha: u32,
    pub rows: Vec<Row>,
}

/// Relative volume errors `e^n_Vol`, `n = 0..=reps`.
#[derive(Debug, Clone, Serialize)]
pub struct Drift {
    pub k: usize,
    pub level: u32,
    pub rel_error: Vec<f64>,
}

/// Everything [`super::run()`] measured (serialised as `reinit.json`).
#[derive(Debug, Clone, Serialize)]
pub struct ReinitReport {
    pub tables: Vec<Table>,
    pub volume_drift: Vec<Drift>,
    /// The same drift test with geometric redistancing (k = 1 only), for reference.
    pub volume_drift_geometric: Vec<Drift>,
}

/// Errors of one case: `(h, e_∞, e^∇_∞, report)`.
pub type CaseResult = (f64, f64, f64, PprReport);
