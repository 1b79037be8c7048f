//! Error versus vertex count: anisotropic-adapted, isotropic-adapted and uniform meshes around
//! one shape, each measured by the interface error of the nodal interpolant of the shape's exact
//! signed distance.
//!
//! For every mesh of a sweep, `u_h = I_h d` ([`anisomesh::levelset::nodal_distance`]) and its zero
//! level `Γ_h` give:
//! - the two-sided interface distance `d_H(Γ_h, Γ)` ([`anisomesh::levelset::interface_distance`]);
//! - the relative area error `|A(u_h < 0) - A| / A` ([`anisomesh::levelset::enclosed_area`] against
//!   [`anisomesh::levelset::Shape::exact_area`]) and the relative perimeter error (the measures of
//!   004 §5.1);
//! - the vertex count and the seconds spent generating the mesh;
//! - the Hausdorff distance split into the part attained within [`measure::CORNER_RADIUS`] of a
//!   corner of the shape and the rest ([`measure::hausdorff_split`]: on the Zalesak disk the
//!   corners decide without the corner features of
//!   [`anisomesh::adapt::ShapeAdaptOptions::features`]; with them the rest does).
//!
//! The three families:
//! 1. **anisotropic**: the geometric metric of 004 eq. (6), `M = ∇u∇uᵀ/h_min² + |D²u|/ε`, with
//!    exact derivatives of the shape, adapted by [`anisomesh::adapt::adapt_to_shape`] (evaluate →
//!    adapt rounds until the vertex count settles, default options). `ε` decreases over the
//!    sweep and `h_min = 0.1 √ε`, the other parameters are those of `anisomesh adapt`
//!    ([`measure::metric_with`]), so that `ε = 1e-4` is the paper's setting (004 §5.1:
//!    `h_min = 0.001`, `h_max = 0.2`). A fixed `h_min` would not make a sweep: the isotropic
//!    variant would be the same mesh for every `ε`. Optionally the kinks of the distance (the
//!    medial axis at the slot corners) are seen at the scale `h_min`
//!    ([`ConvergenceOptions::kink_scale`]).
//! 2. **isotropic**: the same source with `isotropic = true` (`M` replaced by `λ_max I`, the
//!    smallest size of eq. (6) in every direction), same `ε`, same bounds and band.
//! 3. **uniform**: `Mesh2::rectangle` union-jack grids of the domain at increasing resolution.
//!
//! On the Zalesak disk the installed peers ([`sweep::PEER_KINDS`]) are run on the anisotropic
//! family's metric at every `ε` ([`crate::app::repro::peers::run_peer_with`]).
//!
//! Domains: Zalesak `[-2, 2]²` (004 §5.1), circle and flower `[-1, 1]²` (their doc comments in
//! [`anisomesh::levelset::shape_by_name`]).
//!
//! "Anisotropy pays" ([`types::AnisotropyGain`]): at equal Hausdorff error — each family's vertex
//! count interpolated log-log between its sweep points, and from the fitted power laws — the
//! ratio of isotropic to anisotropic vertex counts, and the plain ratio at equal `ε`. The paper's
//! own comparison (004 §5.1: about 10 times more vertices for "the corresponding isotropic graded
//! mesh" at `h_min = 0.001`) is at equal smallest size, not at equal error: [`claim`].
//!
//! Modules: [`types`] (options, rows, report; imports none of its siblings), [`measure`] (domains,
//! metrics, adapted meshes and their interface errors), [`gain`] (vertex ratios at equal error),
//! [`sweep`] (the run), [`figure`] (its CSV and figure), [`claim`] (the comparison at equal
//! smallest size) and [`fronts`] (best mesh against best mesh). Each imports [`types`] and lower
//! layers, never a module that imports it.

pub mod claim;
pub mod figure;
pub mod fronts;
pub mod gain;
pub mod measure;
pub mod sweep;
pub mod types;

pub use sweep::run;
pub use types::ConvergenceOptions;
