//! Ghost values outside the band: the boundary rows of the band heat equation completed by the
//! cells just outside the band (an alternative to the transparent vector `Γ` of 000 (2.9)).
//!
//! The band cuts off the test function `Θ_i` of a boundary node `i` (a node of `I^{j+1} \ I^j`,
//! 000 (2.8)); the transparent flux of 000 (2.9) replaces the missing part of `∫ A[Φ] ∇U · ∇Θ_i`
//! by a face integral, which is not consistent (the `O(h)` errors of `∇I_h u` cancel only over a
//! whole support). Here the missing cells — the *outside cells*, every cell with a boundary node
//! as a corner and no interior node — are added back: their corners outside the band (the *ghost
//! nodes*) carry values extrapolated from the band along the grid direction `e` (one of the 26
//! neighbour offsets) closest to the inward normal `ν = −sign(Φ) ∇Φ/|∇Φ|`,
//!
//! `U(x_g) ≈ 3U(x_g + e) − 3U(x_g + 2e) + U(x_g + 3e)`,
//!
//! from nodal values, exact for quadratics, so the ghost error is `O(h³)` and the completed rows'
//! defect `O(h)`; where three band nodes do not line up, the linear `2U(x_g + e) − U(x_g + 2e)`,
//! and failing that the trilinear interpolant at `x_g + δν`, `x_g + 2δν`. A linear
//! extrapolation everywhere leaves an `O(h²)` ghost error, an `O(1)` row defect like the
//! transparent flux's, and the error stalls (docs/dtgrid.md); the constant extension along the
//! normals is only `O(h)` (the heat solution on a band is not constant along the normals). `Φ`
//! on the ghost nodes is extrapolated the same way, exact up to `O(h³)` for a distance
//! function, so the outside cells carry the weights `|∇Φ| P[Φ]` and `I_h⁰(|∇Φ|)` of 000 §2.1 like
//! any element.
//!
//! With the outside cells every band node's support is complete: the boundary rows read
//! `M_i U_t + Σ_{e ∋ i} a_e(U, Θ_i) = 0` over all cells around `i`, the outside cells' lumped
//! mass is added to the boundary nodes ([`GhostRows::mass`]) and the outside cells' part of the
//! rows to the stiffness ([`GhostRows::complete`], implicit and not symmetric: BiCGStab). The
//! lagged form [`GhostRows::vector`], `G_i = −Σ_{outside e ∋ i} a_e(V, Θ_i)` for a band field
//! `V` completed by its ghost values, keeps the matrix symmetric but is unstable at `τ = h²`.

use super::band::Band;
use super::fem::{element_mass, element_stiffness, Weight};
use super::lattice::{Lattice, NarrowBand, C3};
use crate::error::{Error, Result};
use crate::fem::q1::{shape, shape_grad, Q1};
use crate::fem::Csr;
use crate::geom::DVec3;

/// A corner of an outside cell: a band node or a ghost node (indices into their lists).
#[derive(Debug, Clone, Copy)]
enum Corner {
    Band(u32),
    Ghost(u32),
}

/// The outside cells of a band with their ghost extrapolation and element matrices.
#[derive(Debug, Clone)]
pub struct GhostRows {
    /// Per outside cell: its 8 corners.
    cells: Vec<[Corner; 8]>,
    /// Per outside cell: the element stiffness (row-major) with the weights of the problem.
    stiff: Vec<[f64; 64]>,
    /// Per ghost node: the range of its extrapolation terms in `terms`.
    start: Vec<usize>,
    /// The extrapolation terms `(band node, weight)` of all ghost nodes.
    terms: Vec<(u32, f64)>,
    /// The lumped mass of the outside cells per band node (zero at interior nodes).
    pub mass: Vec<f64>,
    /// The ghost nodes' coordinates, sorted.
    nodes: Vec<C3>,
}

/// The corner `q` of the cell with lowest corner `c` (bit `a` of `q` along axis `a`).
fn corner(c: C3, q: usize) -> C3 {
    [
        c[0] + (q & 1) as i32,
        c[1] + ((q >> 1) & 1) as i32,
        c[2] + ((q >> 2) & 1) as i32,
    ]
}

/// The band cell containing `x` (all 8 corners band nodes) as its corner indices and the
/// reference point of `x` in it; `None` when a corner is not in the band.
fn cell_at<B: Band<Coord = C3>>(
    lat: &Lattice,
    band: &B,
    x: DVec3,
) -> Option<([usize; 8], [f64; 3])> {
    let rel = (x - DVec3::splat(lat.lo)) / lat.h;
    let c = [rel.x.floor(), rel.y.floor(), rel.z.floor()];
    let xi = [rel.x - c[0], rel.y - c[1], rel.z - c[2]];
    let c = [c[0] as i32, c[1] as i32, c[2] as i32];
    let mut idx = [0; 8];
    for (q, i) in idx.iter_mut().enumerate() {
        *i = band.index(corner(c, q))?;
    }
    Some((idx, xi))
}

impl GhostRows {
    /// The outside cells of the band `nb` with the weights `w` of the band field `phi`.
    /// Ghost nodes may lie outside the grid (they are only positions).
    /// Error: [`Error::InvalidInput`] when a ghost node has no band cells to extrapolate from
    /// (see `extrapolation`).
    pub fn new<B: Band<Coord = C3>>(
        lat: &Lattice,
        nb: &NarrowBand<B>,
        phi: &[f64],
        w: Weight,
    ) -> Result<GhostRows> {
        Self::new_with(lat, nb, phi, w, None)
    }

    /// [`GhostRows::new`] with `Φ` on the ghost nodes from `ghost_phi` instead of extrapolated.
    /// Error: as [`GhostRows::new`].
    pub fn new_with<B: Band<Coord = C3>>(
        lat: &Lattice,
        nb: &NarrowBand<B>,
        phi: &[f64],
        w: Weight,
        ghost_phi: Option<&dyn Fn(DVec3) -> f64>,
    ) -> Result<GhostRows> {
        let n = nb.band.len();
        let h = lat.h;
        let interior = |c: C3| nb.band.index(c).is_some_and(|i| nb.interior[i]);
        let mut lows: Vec<C3> = Vec::new();
        for (i, c) in nb.band.coords().enumerate() {
            if nb.interior[i] {
                continue;
            }
            for q in 0..8i32 {
                let lo = [c[0] - (q & 1), c[1] - ((q >> 1) & 1), c[2] - ((q >> 2) & 1)];
                if (0..8).all(|k| !interior(corner(lo, k))) {
                    lows.push(lo);
                }
            }
        }
        lows.sort_unstable();
        lows.dedup();
        let mut ghosts: Vec<C3> = lows
            .iter()
            .flat_map(|&c| (0..8).map(move |q| corner(c, q)))
            .filter(|&x| nb.band.index(x).is_none())
            .collect();
        ghosts.sort_unstable();
        ghosts.dedup();
        let cells: Vec<[Corner; 8]> = lows
            .iter()
            .map(|&c| {
                std::array::from_fn(|q| {
                    let x = corner(c, q);
                    match nb.band.index(x) {
                        Some(i) => Corner::Band(i as u32),
                        None => Corner::Ghost(ghosts.binary_search(&x).unwrap_or(0) as u32),
                    }
                })
            })
            .collect();
        let mut start = vec![0];
        let mut terms = Vec::new();
        for &g in &ghosts {
            extrapolation(lat, nb, phi, g, &mut terms)?;
            start.push(terms.len());
        }
        let mut rows = GhostRows {
            cells,
            stiff: Vec::new(),
            start,
            terms,
            mass: vec![0.0; n],
            nodes: ghosts,
        };
        let phi_ghost = match ghost_phi {
            Some(f) => rows.nodes.iter().map(|&c| f(lat.pos(c))).collect(),
            None => rows.ghost_values(phi),
        };
        let q1 = Q1::new(3, 2)?;
        let mut stiff = Vec::with_capacity(rows.cells.len());
        for cell in &rows.cells {
            let v = corner_values(cell, phi, &phi_ghost);
            let mut ke = [0.0; 64];
            element_stiffness(&q1, w, &v, h, &mut ke);
            stiff.push(ke);
            let m = element_mass(w, &v, h);
            for c in cell {
                if let Corner::Band(i) = c {
                    rows.mass[*i as usize] += m;
                }
            }
        }
        rows.stiff = stiff;
        Ok(rows)
    }

    /// The number of outside cells and of ghost nodes.
    pub fn counts(&self) -> (usize, usize) {
        (self.cells.len(), self.start.len() - 1)
    }

    /// The ghost nodes' grid coordinates (they may lie outside the grid).
    pub fn ghost_nodes(&self) -> &[C3] {
        &self.nodes
    }

    /// The ghost values of the band field `u` (linear extrapolation along the inward normal).
    pub fn ghost_values(&self, u: &[f64]) -> Vec<f64> {
        self.start
            .windows(2)
            .map(|r| {
                self.terms[r[0]..r[1]]
                    .iter()
                    .map(|&(i, c)| c * u[i as usize])
                    .sum()
            })
            .collect()
    }

    /// The band stiffness `stiff` completed by the outside cells: row `i` gains
    /// `Σ_{outside e ∋ i} a_e(·, Θ_i)` with the ghost values written as their extrapolation from
    /// band nodes, so that `(L_full U)_i = (stiff U)_i − G_i(U)` (not symmetric).
    /// Error: only for a band node index out of range.
    pub fn complete(&self, stiff: &Csr) -> Result<Csr> {
        let mut t: Vec<(u32, u32, f64)> = Vec::with_capacity(stiff.nnz() + 64 * self.cells.len());
        for i in 0..stiff.n {
            for p in stiff.row_ptr[i]..stiff.row_ptr[i + 1] {
                t.push((i as u32, stiff.col[p], stiff.val[p]));
            }
        }
        for (cell, ke) in self.cells.iter().zip(&self.stiff) {
            for (a, ca) in cell.iter().enumerate() {
                let Corner::Band(i) = *ca else { continue };
                for (b, cb) in cell.iter().enumerate() {
                    let k = ke[a * 8 + b];
                    match *cb {
                        Corner::Band(j) => t.push((i, j, k)),
                        Corner::Ghost(g) => {
                            let g = g as usize;
                            for &(j, c) in &self.terms[self.start[g]..self.start[g + 1]] {
                                t.push((i, j, k * c));
                            }
                        }
                    }
                }
            }
        }
        Csr::from_triplets(stiff.n, &t)
    }

    /// `G_i = −Σ_{outside e ∋ i} a_e(V, Θ_i)` for the band field `u` completed by its ghost
    /// values (zero at interior nodes).
    pub fn vector(&self, u: &[f64]) -> Vec<f64> {
        self.vector_with(u, &self.ghost_values(u))
    }

    /// [`GhostRows::vector`] with the given ghost values (one per [`GhostRows::ghost_nodes`]).
    pub fn vector_with(&self, u: &[f64], ghost: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; u.len()];
        for (cell, ke) in self.cells.iter().zip(&self.stiff) {
            let v = corner_values(cell, u, ghost);
            for (a, c) in cell.iter().enumerate() {
                if let Corner::Band(i) = c {
                    let row: f64 = (0..8).map(|b| ke[a * 8 + b] * v[b]).sum();
                    out[*i as usize] -= row;
                }
            }
        }
        out
    }
}

/// The corner values of an outside cell from the band field `u` and its ghost values.
fn corner_values(cell: &[Corner; 8], u: &[f64], ghost: &[f64]) -> [f64; 8] {
    std::array::from_fn(|q| match cell[q] {
        Corner::Band(i) => u[i as usize],
        Corner::Ghost(g) => ghost[g as usize],
    })
}

/// The extrapolation distances `δ / h` tried in turn.
const DELTAS: [f64; 9] = [1.0, 1.25, 1.5, 1.75, 2.0, 2.25, 2.5, 2.75, 3.0];

/// Appends the extrapolation terms of the ghost node `g`: with `ν` the inward normal (the Q1
/// gradient of `Φ` one cell inside, oriented away from the zero level), the quadratic
/// `(3, −3, 1)` along the first grid direction (closest to `ν` first) with three band nodes in
/// line, else the linear `(2, −1)` with two, else `2 I_h(x + δν) − I_h(x + 2δν)` with the
/// smallest `δ` of [`DELTAS`] that puts both points in band cells (then the grid directions).
/// Error: [`Error::InvalidInput`] when no direction gives two points in band cells.
fn extrapolation<B: Band<Coord = C3>>(
    lat: &Lattice,
    nb: &NarrowBand<B>,
    phi: &[f64],
    g: C3,
    terms: &mut Vec<(u32, f64)>,
) -> Result<()> {
    let h = lat.h;
    let x = lat.pos(g);
    // The direction into the band from the neighbouring band nodes, and the side of the zero
    // level they lie on.
    let (mut d0, mut side) = (DVec3::ZERO, 0.0);
    for q in 0..27 {
        let c = [g[0] + q % 3 - 1, g[1] + (q / 3) % 3 - 1, g[2] + q / 9 - 1];
        if let Some(i) = nb.band.index(c) {
            d0 += lat.pos(c) - x;
            side += phi[i];
        }
    }
    let d0 = d0.normalize_or_zero();
    let mut dir = d0;
    let inside = DELTAS
        .iter()
        .find_map(|&d| cell_at(lat, &nb.band, x + d0 * (d * h)));
    if let Some((idx, xi)) = inside {
        let grad = (0..8).fold(DVec3::ZERO, |s, k| {
            s + DVec3::from_array(shape_grad(3, k, &xi)) * (phi[idx[k]] / h)
        });
        let n = grad.normalize_or_zero() * -side.signum();
        if n.dot(d0) > 0.5 {
            dir = n;
        }
    }
    // The grid directions into the band, closest to the normal first.
    let mut dirs: Vec<C3> = (0..27)
        .filter(|&q| q != 13)
        .map(|q| [q % 3 - 1, (q / 3) % 3 - 1, q / 9 - 1])
        .collect();
    let unit = |o: C3| DVec3::new(o[0] as f64, o[1] as f64, o[2] as f64).normalize();
    dirs.sort_by(|a, b| unit(*b).dot(dir).total_cmp(&unit(*a).dot(dir)));
    let along = |o: C3, k: i32| {
        nb.band
            .index([g[0] + k * o[0], g[1] + k * o[1], g[2] + k * o[2]])
    };
    // Nodal values along a grid direction: quadratic (3, −3, 1), else linear (2, −1).
    for st in [&[3.0, -3.0, 1.0][..], &[2.0, -1.0][..]] {
        for &o in &dirs {
            let nodes: Option<Vec<usize>> = (1..=st.len() as i32).map(|k| along(o, k)).collect();
            if let Some(nodes) = nodes {
                terms.extend(nodes.iter().zip(st).map(|(&i, &c)| (i as u32, c)));
                return Ok(());
            }
        }
    }
    let dirs: Vec<DVec3> = dirs.into_iter().map(unit).collect();
    for dir in std::iter::once(dir).chain(dirs) {
        for delta in DELTAS {
            let p1 = cell_at(lat, &nb.band, x + dir * (delta * h));
            let p2 = cell_at(lat, &nb.band, x + dir * (2.0 * delta * h));
            if let (Some((i1, x1)), Some((i2, x2))) = (p1, p2) {
                for k in 0..8 {
                    terms.push((i1[k] as u32, 2.0 * shape(3, k, &x1)));
                    terms.push((i2[k] as u32, -shape(3, k, &x2)));
                }
                return Ok(());
            }
        }
    }
    Err(Error::InvalidInput(format!(
        "ghost node {g:?}: no two band cells along any direction into the band (band too thin)"
    )))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backends::dtgrid::fem::{assemble, elements};
    use crate::backends::dtgrid::lattice::{band_around, crossing_cells_of_fn};
    use crate::backends::dtgrid::SortedBand;

    #[test]
    fn ghost_values_are_exact_for_linear_fields_and_rows_are_complete() {
        let lat = Lattice::unit(21).unwrap();
        let f = |p: DVec3| p.length() - 0.3;
        let cross = crossing_cells_of_fn(&lat, &f).unwrap();
        let nb: NarrowBand<SortedBand<C3>> = band_around(&lat, &cross, 2).unwrap();
        let n = nb.band.len();
        let phi: Vec<f64> = nb.band.coords().map(|c| f(lat.pos(c))).collect();
        let ghost = GhostRows::new(&lat, &nb, &phi, Weight::Heat).unwrap();
        let (cells, nodes) = ghost.counts();
        assert!(cells > 0 && nodes > 0);
        // Linear fields are extrapolated exactly, quadratic ones wherever three nodes line up.
        let lin = |p: DVec3| 0.3 + p.x - 2.0 * p.y + 0.5 * p.z;
        let quad = |p: DVec3| lin(p) + p.x * p.y - 3.0 * p.z * p.z;
        let u: Vec<f64> = nb.band.coords().map(|c| lin(lat.pos(c))).collect();
        let uq: Vec<f64> = nb.band.coords().map(|c| quad(lat.pos(c))).collect();
        let (gl, gq) = (ghost.ghost_values(&u), ghost.ghost_values(&uq));
        let mut exact_quadratic = 0;
        for (k, &c) in ghost.ghost_nodes().iter().enumerate() {
            let x = lat.pos(c);
            assert!((gl[k] - lin(x)).abs() < 1e-12, "{c:?}");
            exact_quadratic += usize::from((gq[k] - quad(x)).abs() < 1e-12);
        }
        assert!(
            exact_quadratic * 10 > 9 * nodes,
            "{exact_quadratic} of {nodes}"
        );
        // Constants have no outside flux; the mass goes to boundary nodes only.
        let ones = vec![1.0; n];
        assert!(ghost.vector(&ones).iter().all(|v| v.abs() < 1e-14));
        for (i, m) in ghost.mass.iter().enumerate() {
            assert!(*m >= 0.0);
            if nb.interior[i] {
                assert_eq!(*m, 0.0);
            }
        }
        // Complete rows: for a linear field, band stiffness minus the outside vector is the
        // full-support row, which vanishes for the isotropic weight ≈ 1.
        let w1 = Weight::Mcf { eps: 1e8 };
        let g1 = GhostRows::new(&lat, &nb, &phi, w1).unwrap();
        let el = elements(&nb);
        let m1 = assemble(&lat, &el, n, &phi, w1).unwrap();
        let lu = m1.stiff.mul(&u);
        let gu = g1.vector(&u);
        for i in 0..n {
            assert!((lu[i] - gu[i]).abs() < 1e-9 * 1e-8, "{} {}", lu[i], gu[i]);
        }
    }
}
