//! Riemannian metric fields: all metric mathematics in one module (004 §3.3–3.5, §4.2).
//!
//! A metric `M` (SPD) measures `|v|_M = sqrt(v^T M v)`; with `M = R diag(λ) R^T` the prescribed
//! sizes are `h_i = 1/sqrt(λ_i)` along the eigenvectors (004 §3.3). A metric *field* is a
//! `Vec<Sym2>` indexed by vertex.
//!
//! - [`sym`](mod@sym): [`SymTensor`], the trait over `Sym2` and `Sym3` that the generic metric
//!   mathematics below is written against.
//! - [`tensor`]: the `Sym2` storage type, closed-form eigen, `log`/`exp`/`powf`, sizes, bounding.
//! - [`intersect`](mod@intersect): intersection by simultaneous reduction (004 §3.5).
//! - [`interpolate`]: log-Euclidean means (element metrics, transfer).
//! - [`length`]: edge length, `Q_ani` (004 §3.4), mesh quality statistics.
//! - [`complexity`](mod@complexity): `∫ sqrt(det M)` and the vertex count it predicts.
//! - [`gradation`]: bounded size growth along edges (metric-space gradation).
//! - [`from_hessian`]: the multiscale `L^p` interpolation-error metric (Loseille–Alauzet).
//! - [`field`]: whole-field checks ([`validate_field`]).
//! - [`sym3`]: `Sym3`, the 3D metric; `eigen3`, its closed-form eigen-decomposition (nalgebra's
//!   iterative one as the fallback).
//! - [`levelset`]: the geometric metric of 004 eq. (6) and [`MetricBounds`].
//! - [`conformity`](mod@conformity): edge lengths, `Q_ani` and mean ratio of a triangle or
//!   tetrahedral mesh in a metric field (the measures of `anisomesh measure`).
//! - [`band`]: eq. (6) with bounds and growth outside a band, for `Sym2` and `Sym3`.
//! - [`ugawg`]: the UGAWG analytic 3D metric fields cube-linear and cube-polar-1.

pub mod band;
pub mod complexity;
pub mod conformity;
pub(crate) mod eigen3;
pub mod field;
pub mod from_hessian;
pub mod gradation;
pub mod interpolate;
pub mod intersect;
pub mod length;
pub mod levelset;
pub mod sym;
pub mod sym3;
pub mod tensor;
pub mod ugawg;

pub use complexity::{complexity, predicted_vertices};
pub use conformity::{conformity, conformity_analytic, conformity_ugawg, Conformity};
pub use field::validate_field;
pub use from_hessian::{interpolation_error_metric_iso, lp_metric, multiscale_lp, LpReport};
pub use gradation::{gradate, gradate_graph, gradate_tets};
pub use interpolate::{interpolate_log, lerp_log, lerp_sizes};
pub use intersect::{intersect, max_form_ratio};
pub use length::{edge_length, element_metric, q_ani, quality_stats, QualityStats};
pub use levelset::{geometric_metric, MetricBounds};
pub use sym::SymTensor;
pub use sym3::Sym3;
pub use tensor::Sym2;
