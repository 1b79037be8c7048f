//! The redistancing experiments of 003 §8 (tables 8.1-8.4, volume drift).
//!
//! - Example 1 (torus, `r = 0.2`, `R = 0.4` in `[-1, 1]³`): a Kuhn mesh with `h_0 = 2/3`, locally
//!   refined by newest-vertex bisection to `h_ℓ = 2^{-ℓ} h_0` near the torus; input
//!   `φ_h = I_h φ^{(α)}` with `φ^{(α)} = d^{ex} q^{(α)}`, `q^{(α)}(x) = 9 + 4 cos(α x_1 x_2 / |x|)`;
//!   errors `e_∞ = max_{v ∈ N(T_{Γ_h})} |I_h d_h(v) - d^{ex}(v)|` and
//!   `e^∇_∞ = max_{T ∈ T_{Γ_h}} |(|T|^{-1} ∫_T |∇ I_h d_h|²)^{1/2} - 1|` for `k = 1, 2`
//!   (tables 8.1 `α = 1`, 8.2 `α = 10`, 8.3 `α = 50`).
//! - The 2D analogue: a circle of radius 0.5 (centre (0.03, -0.02)) in `[-1, 1]²` on uniform
//!   union-jack grids with `h_ℓ = 2^{-ℓ} (2/3)`, same `q^{(α)}`.
//! - The Zalesak slotted disk of 004 (exact signed distance from [`anisomesh::levelset::shapes`]) in
//!   `[-2, 2]²` with the same `h_ℓ` and `q^{(α)}`: its corners break the smoothness the analysis
//!   of 003 §7 assumes, so this table shows what happens there (max errors sit at the corners).
//! - Repeated redistancing of a sphere of radius 0.25 (Fig. 8.4): `d̃^0_h = I_h d^{ex}`, then 100
//!   redistancings (initialisation + fast marching extension); relative volume error
//!   `|V^n - 4/3 π r³| / (4/3 π r³)`. The volume inside the zero level is exact for P1 (per
//!   tetrahedron, closed form) and for P2 is computed on 64 sub-tetrahedra per cut tetrahedron.
//!
//! Modules: [`types`] (options, rows, tables, report), [`cases`] (the input field and the 2D
//! tables), [`torus`] (the 3D tables), [`drift`] (the volume drift), [`print`] (the tables beside
//! the paper's values), [`output`] (`reinit.json` and the figures) and [`mod@run`] (all of it).

pub mod cases;
pub mod drift;
pub mod output;
pub mod print;
pub mod run;
pub mod torus;
pub mod types;

pub use run::run;
pub use types::ReinitOptions;
