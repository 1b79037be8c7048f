//! Vertex order along a 3D Hilbert curve, for cache-friendly renumbering of tetrahedral meshes.
//!
//! Coordinates are quantised to 21 bits per axis in the bounding box; the key is the Hilbert
//! index computed with Skilling's transpose form ("Programming the Hilbert curve", AIP Conf.
//! Proc. 707, 2004): Gray-code the interleaved bits after undoing the per-level rotations.

use crate::geom::DVec3;

const BITS: u32 = 21;

/// The Hilbert index of the quantised point `x` (each entry below `2^21`).
fn hilbert_key(mut x: [u32; 3]) -> u64 {
    let m = 1u32 << (BITS - 1);
    // Inverse undo of the excess work.
    let mut q = m;
    while q > 1 {
        let p = q - 1;
        for i in 0..3 {
            if x[i] & q != 0 {
                x[0] ^= p;
            } else {
                let t = (x[0] ^ x[i]) & p;
                x[0] ^= t;
                x[i] ^= t;
            }
        }
        q >>= 1;
    }
    // Gray encode.
    for i in 1..3 {
        x[i] ^= x[i - 1];
    }
    let mut t = 0;
    let mut q = m;
    while q > 1 {
        if x[2] & q != 0 {
            t ^= q - 1;
        }
        q >>= 1;
    }
    for v in &mut x {
        *v ^= t;
    }
    // Interleave the transposed bits, most significant level first.
    let mut key = 0u64;
    for b in (0..BITS).rev() {
        for v in &x {
            key = (key << 1) | u64::from((v >> b) & 1);
        }
    }
    key
}

/// The indices `0..points.len()` for which `keep` holds, sorted along the Hilbert curve
/// through the bounding box of those points (ties by index).
pub fn hilbert_order(points: &[DVec3], keep: impl Fn(usize) -> bool) -> Vec<u32> {
    let idx: Vec<usize> = (0..points.len()).filter(|&i| keep(i)).collect();
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for &i in &idx {
        lo = lo.min(points[i]);
        hi = hi.max(points[i]);
    }
    let scale = ((1u64 << BITS) - 1) as f64 / (hi - lo).max_element().max(f64::MIN_POSITIVE);
    let mut keyed: Vec<(u64, u32)> = idx
        .iter()
        .map(|&i| {
            let q = ((points[i] - lo) * scale)
                .to_array()
                .map(|c| c.max(0.0) as u32);
            (hilbert_key(q), i as u32)
        })
        .collect();
    keyed.sort_unstable();
    keyed.into_iter().map(|(_, i)| i).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn consecutive_cells_of_a_grid_are_neighbours() {
        // On a 2^3-per-axis grid the Hilbert order visits the cells with unit steps.
        let mut pts = Vec::new();
        for k in 0..8 {
            for j in 0..8 {
                for i in 0..8 {
                    pts.push(DVec3::new(i as f64, j as f64, k as f64));
                }
            }
        }
        let o = hilbert_order(&pts, |_| true);
        assert_eq!(o.len(), 512);
        for w in o.windows(2) {
            let d = pts[w[0] as usize] - pts[w[1] as usize];
            assert!((d.length() - 1.0).abs() < 1e-12, "step {d}");
        }
    }
}
