//! The Zalesak slotted-disk rotation (004 §5.1).
//!
//! A disk of radius 0.5 centred at (0, 0.75) with a slot `|x| ≤ 0.06` cut from the bottom of the
//! disk up to `y = 0.85`, in `[-2, 2]²`, rotated by `u = (-y, x)` for one revolution (`2π`) in 16
//! periods of `π/8`. The level set (exact signed distance at the vertices, negative inside) is
//! advected by the characteristics-Galerkin scheme (004 eq. (2)); after one revolution the shape
//! should be back in place. Reported: area and perimeter of the P1 zero level before and after
//! (exact: 0.7135424760 and 4.3340766629; the paper: 0.71316 → 0.706 and 4.3275 → 4.2985
//! without mass correction at about 6,500 vertices per adapted mesh), and the distance between
//! the final and the exact interface.
//!
//! Modules: [`exact`] (the exact shape, its measures and the paper's values), [`types`] (options,
//! time series, report), [`run`](mod@run) (the rotation, period by period), [`sources`] (the
//! error sources measured apart), [`output`] (`zalesak.json`, `zalesak.csv`) and [`figures`].

pub mod exact;
pub mod figures;
pub mod output;
pub mod run;
pub mod sources;
pub mod types;

pub use run::run;
pub use types::{ZalesakMesh, ZalesakOptions};
