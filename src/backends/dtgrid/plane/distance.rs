//! The signed distance extension of 000 §2.4 in the plane: the distance of every node of a new
//! band to the zero level of a band field on an old band, measured to the bicubic zero level
//! ([`super::cubic`]; second order and more for `j ≥ 2`, where the `4 × 4` stencils of the cut
//! cells are band nodes; the bilinear zero level near the band's edge, first order, which is
//! what `j = 1` gives).
//!
//! Every node finds its nearest cut cell by propagation: the corners of the cut cells take the
//! nearest of their own cells, then, layer by layer, every node takes the nearest among the
//! cells its `3 × 3` neighbours found (distances to the chords a cell's pieces are made of).
//! The distance is then to the bicubic zero level of that cell and the cut cells around it:
//! each cell's closest point by Newton's method on the optimality system from the closest chord
//! point ([`super::cubic::Patch::closest`]), the nearest of those that lie in their own cell.

use super::cubic::Field;
use super::lattice::{neighbours, Plane, NONE};
use super::level::{zero_level, ZeroLevel};
use super::{Grid2, C2};
use crate::backends::dtgrid::band::{Band, GridCoord};
use crate::geom::{point_segment_distance, DVec2};
use rayon::prelude::*;

/// Which values of the field are kept on the new band instead of the distance.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Keep {
    /// None: the signed distance everywhere (signs from the field where the node is in the old
    /// band).
    Nothing,
    /// The corners of the cut cells: the field times a local least-squares factor fitting it to
    /// the distance there, so the zero level does not move while the gradient is renormalised.
    Crossing,
    /// Every node of the old band (the extension of `Φ^k` onto a new band, 000 §2.4).
    OldBand,
}

/// The distance of `p` to the chords of cut cell `cell`.
fn chord_distance(z: &ZeroLevel, ranges: &[std::ops::Range<usize>], cell: u32, p: DVec2) -> f64 {
    ranges[cell as usize]
        .clone()
        .map(|s| {
            let g = &z.segments[s];
            point_segment_distance(p, g.a, g.mid)
                .0
                .min(point_segment_distance(p, g.mid, g.b).0)
        })
        .fold(f64::INFINITY, f64::min)
}

/// The closest point of cut cell `cell`'s chords to `p`.
fn closest_chord_point(
    z: &ZeroLevel,
    ranges: &[std::ops::Range<usize>],
    cell: u32,
    p: DVec2,
) -> DVec2 {
    let mut best = (f64::INFINITY, p);
    for s in ranges[cell as usize].clone() {
        let g = &z.segments[s];
        for (a, b) in [(g.a, g.mid), (g.mid, g.b)] {
            let (d, t) = point_segment_distance(p, a, b);
            if d < best.0 {
                best = (d, a + t * (b - a));
            }
        }
    }
    best.1
}

/// The values on the band `to` of the field `phi` on the band `from`: the signed distance to the
/// zero level of `phi` (see the module documentation), except where `keep` keeps `phi`. Signs
/// come from `phi` where the node is in `from`, else from the side of the closest point. Nodes
/// farther than `max_dist`, or not reached, get `±max_dist`.
pub fn extend_distance(
    plane: &Plane,
    from: &Grid2,
    phi: &[f64],
    to: &Grid2,
    keep: Keep,
    max_dist: f64,
) -> Vec<f64> {
    let field = Field {
        plane,
        band: from,
        u: phi,
    };
    let z = zero_level(&field);
    let ranges = z.cell_segments();
    let coords: Vec<C2> = to.coords().collect();
    let m = coords.len();
    // The old value of every new node, by one merge of the two sorted node lists.
    let mut old: Vec<Option<f64>> = vec![None; m];
    let mut it = from.coords().zip(phi.iter()).peekable();
    for (i, c) in coords.iter().enumerate() {
        while it.peek().is_some_and(|(o, _)| o < c) {
            it.next();
        }
        if let Some((o, v)) = it.peek() {
            if o == c {
                old[i] = Some(**v);
            }
        }
    }
    // Seeds: the corners of the cut cells take the nearest of their cells.
    let mut best = vec![NONE; m];
    let mut dist = vec![f64::INFINITY; m];
    let mut seed = vec![false; m];
    for (id, patch) in z.cells.iter().enumerate() {
        for k in 0..4 {
            let Some(i) = to.index(patch.cell.corner(k)) else {
                continue;
            };
            seed[i] = true;
            let d = chord_distance(&z, &ranges, id as u32, plane.pos(coords[i]));
            if d < dist[i] {
                dist[i] = d;
                best[i] = id as u32;
            }
        }
    }
    // Layers: every node takes the nearest of its neighbours' cells (Jacobi passes).
    let nbrs = neighbours(to);
    let layers = (max_dist / plane.h).ceil() as usize + 2;
    for _ in 0..layers {
        let next: Vec<(u32, f64)> = (0..m)
            .into_par_iter()
            .map(|i| {
                let p = plane.pos(coords[i]);
                let mut b = (best[i], dist[i]);
                let mut seen = [NONE; 9];
                for (k, &j) in nbrs[i].iter().enumerate() {
                    if j == NONE {
                        continue;
                    }
                    let c = best[j as usize];
                    if c == NONE || c == best[i] || seen[..k].contains(&c) {
                        continue;
                    }
                    seen[k] = c;
                    let d = chord_distance(&z, &ranges, c, p);
                    if d < b.1 || (d == b.1 && c < b.0) {
                        b = (c, d);
                    }
                }
                b
            })
            .collect();
        let changed = next.iter().zip(&best).any(|(n, b)| n.0 != *b);
        for (i, (c, d)) in next.into_iter().enumerate() {
            best[i] = c;
            dist[i] = d;
        }
        if !changed {
            break;
        }
    }
    // The distance to the bicubic zero level near the nearest cell and the cut cells around
    // it, and the side.
    let cut: Vec<C2> = z.cells.iter().map(|p| p.cell).collect();
    let exact: Vec<(f64, f64)> = (0..m)
        .into_par_iter()
        .map(|i| {
            let c = best[i];
            if c == NONE {
                return (f64::INFINITY, 1.0);
            }
            let p = plane.pos(coords[i]);
            let home = cut[c as usize];
            // The nearest point among those each cell's polynomial gives inside its own cell
            // (a cell's polynomial continued into its neighbours is not the zero level there),
            // else among all.
            // Cells are visited by their chords' distance and skipped once that exceeds the
            // nearest point found by h/4 (a chord is within h²κ/8 of the level in its cell).
            let mut cand: Vec<(f64, usize, DVec2)> = (0..9)
                .filter_map(|k| {
                    let cell = [home[0] + k % 3 - 1, home[1] + k / 3 - 1];
                    let id = cut.binary_search(&cell).ok()?;
                    let q0 = closest_chord_point(&z, &ranges, id as u32, p);
                    Some(((p - q0).length(), id, q0))
                })
                .collect();
            cand.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            let (mut own, mut any) = ((f64::INFINITY, 1.0), (f64::INFINITY, 1.0));
            for (chord, id, q0) in cand {
                if chord > own.0 + 0.25 * plane.h {
                    break;
                }
                let patch = &z.cells[id];
                let (q, converged) = patch.closest(p, q0);
                let q = if converged || patch.jet(q).value.abs() <= patch.jet(q0).value.abs() {
                    q
                } else {
                    q0
                };
                let d = (p - q).length();
                let g = patch.jet(q).grad;
                let side = if (p - q).dot(g) < 0.0 { -1.0 } else { 1.0 };
                if d < any.0 {
                    any = (d, side);
                }
                if d < own.0 && patch.contains(q, 1e-6) {
                    own = (d, side);
                }
            }
            if own.0.is_finite() {
                own
            } else {
                any
            }
        })
        .collect();
    let scale: Vec<f64> = if keep == Keep::Crossing {
        (0..m)
            .into_par_iter()
            .map(|i| {
                if !seed[i] {
                    return 1.0;
                }
                let (mut num, mut den) = (0.0, 0.0);
                for &k in &nbrs[i] {
                    if k == NONE || !seed[k as usize] {
                        continue;
                    }
                    if let Some(x) = old[k as usize] {
                        num += exact[k as usize].0.min(max_dist) * x.abs();
                        den += x * x;
                    }
                }
                if den > 0.0 && num > 0.0 {
                    num / den
                } else {
                    1.0
                }
            })
            .collect()
    } else {
        vec![1.0; m]
    };
    (0..m)
        .map(|i| {
            let kept = match keep {
                Keep::Nothing => None,
                Keep::Crossing => seed[i].then(|| old[i].map(|x| x * scale[i])).flatten(),
                Keep::OldBand => old[i],
            };
            if let Some(v) = kept {
                return v;
            }
            let s = match old[i] {
                Some(v) if v < 0.0 => -1.0,
                Some(_) => 1.0,
                None => exact[i].1,
            };
            s * exact[i].0.min(max_dist)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backends::dtgrid::plane::lattice::{band_around, crossing_cells_of_fn};

    #[test]
    fn distance_to_a_circle_from_a_non_distance_field() {
        let mut worst = Vec::new();
        for n in [33, 65] {
            let plane = Plane::new(n, 1.0 / (n - 1) as f64).unwrap();
            let (c, r) = (DVec2::new(0.49, 0.52), 0.27);
            let f = |p: DVec2| (p - c).length() - r;
            let nb = band_around(&plane, &crossing_cells_of_fn(&plane, &f).unwrap(), 2).unwrap();
            // A field that is not a distance (gradient 2|x − c|).
            let phi: Vec<f64> = nb
                .band
                .coords()
                .map(|q| (plane.pos(q) - c).length_squared() - r * r)
                .collect();
            let d = extend_distance(
                &plane,
                &nb.band,
                &phi,
                &nb.band,
                Keep::Nothing,
                8.0 * plane.h,
            );
            let w = nb
                .band
                .coords()
                .zip(&d)
                .map(|(q, di)| (di - f(plane.pos(q))).abs())
                .fold(0.0, f64::max);

            worst.push(w);
            // Keeping the crossing corners keeps every sign.
            let k = extend_distance(
                &plane,
                &nb.band,
                &phi,
                &nb.band,
                Keep::Crossing,
                8.0 * plane.h,
            );
            for (a, b) in phi.iter().zip(&k) {
                assert_eq!(*a < 0.0, *b < 0.0);
            }
        }
        // The quadratic field is reproduced by the bicubic patches: distances within the
        // closest-point iteration's tolerance, far below the h²/(8r) ≈ 4e-4 of the chords.
        assert!(worst[0] < 2e-5 && worst[1] < 2e-5, "{worst:?}");
    }
}
