//! A closed triangulated surface as a level set on a narrow band (000 §4: the dragon, scan
//! converted): the surface is placed in the paper's domain `(−½, ½)³` by a similarity
//! ([`Placement`]), its exact signed distance (a bounding-volume hierarchy over the triangles,
//! [`TriangulatedShape`]) is sampled on a band found by block pruning
//! ([`DtGrid::from_implicit`]), and the band of half-width `j` around the crossed cells carries
//! the signed distance to the discrete zero level — the state a mean curvature motion
//! ([`McfState`]) or a reaction–diffusion run ([`super::reaction`]) starts from.

use super::band::{Band, GridCoord};
use super::grid::{DtGrid, Implicit};
use super::lattice::{band_around, crossing_cells_of_band, Lattice, NarrowBand, C3};
use super::mcf::{rebuild, McfState};
use super::surface::zero_level;
use crate::error::{Error, Result};
use crate::fem::q1::shape;
use crate::geom::DVec3;
use crate::levelset::shapes::Shape;
use crate::levelset::triangulated::TriangulatedShape;
use crate::levelset::TriangleSurface;
use std::path::Path;

/// Reads a closed triangulated surface from an OBJ file and validates it
/// ([`TriangulatedShape::new`]: holes, non-manifold edges or vertices and degenerate triangles
/// are rejected; an inconsistent orientation is repaired, see
/// [`TriangulatedShape::flipped_triangles`]).
/// Errors: [`Error::Io`] for a missing or unreadable file, [`Error::InvalidInput`] naming the
/// file and the defect.
pub fn read_shape(path: &Path) -> Result<TriangulatedShape> {
    let mesh = crate::io::read_obj(path)?;
    TriangulatedShape::from_mesh(&mesh).map_err(|e| match e {
        Error::InvalidInput(m) => Error::InvalidInput(format!("{}: {m}", path.display())),
        e => e,
    })
}

/// The similarity `x ↦ (x − centre) · scale` that places a surface in the grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// The centre of the surface's bounding box (input coordinates).
    pub centre: DVec3,
    /// The scale factor.
    pub scale: f64,
}

impl Placement {
    /// The placed point.
    pub fn apply(&self, p: DVec3) -> DVec3 {
        (p - self.centre) * self.scale
    }

    /// The input point of a placed one.
    pub fn invert(&self, q: DVec3) -> DVec3 {
        q / self.scale + self.centre
    }

    /// Centres the bounding box of `s` at the origin and scales its largest side to
    /// `1 − 2 (j + 3) h` of the grid `lat`, so that the band of half-width `j` fits.
    /// Errors: [`Error::InvalidInput`] for a surface without extent or a grid too coarse for
    /// the band.
    pub fn fit(s: &TriangleSurface, lat: &Lattice, j: usize) -> Result<Placement> {
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for &p in &s.points {
            lo = lo.min(p);
            hi = hi.max(p);
        }
        let side = (hi - lo).max_element();
        let room = (lat.n - 1) as f64 * lat.h - 2.0 * (j as f64 + 3.0) * lat.h;
        if !(side.is_finite() && side > 0.0) || room <= 0.0 {
            return Err(Error::InvalidInput(format!(
                "cannot place a surface of extent {side} in a grid of {} nodes per side with a \
                 band of half-width {j}",
                lat.n
            )));
        }
        Ok(Placement {
            centre: 0.5 * (lo + hi),
            scale: room / side,
        })
    }

    /// The placed copy of `s`.
    pub fn surface(&self, s: &TriangleSurface) -> TriangleSurface {
        TriangleSurface {
            points: s.points.iter().map(|&p| self.apply(p)).collect(),
            triangles: s.triangles.clone(),
        }
    }
}

/// The band of half-width `j` around the zero level of `shape` (already placed in the grid)
/// carrying the signed distance to the discrete zero level. The signed distance of `shape` is
/// evaluated only near the surface (block pruning, [`DtGrid::from_implicit`]).
/// Errors: [`Error::InvalidInput`] when the band leaves the grid or `j = 0`,
/// [`Error::EmptyLevelSet`] when no cell is crossed (a surface smaller than a cell).
pub fn band_of_shape<B: Band<Coord = C3> + Clone>(
    lat: Lattice,
    j: usize,
    shape: &TriangulatedShape,
) -> Result<McfState<B>> {
    if j == 0 {
        return Err(Error::InvalidInput(
            "band half-width j = 0 (at least 1)".into(),
        ));
    }
    let g = Implicit {
        n: lat.n - 1,
        origin: [lat.lo; 3],
        h: lat.h,
        half_width: 3,
    };
    let wide = DtGrid::<C3>::from_implicit(&g, |p| shape.distance(DVec3::new(p[0], p[1], p[2])))?;
    let pts: Vec<DVec3> = wide.coords().map(|c| lat.pos(c)).collect();
    let phi = shape.distances(&pts);
    let cross = crossing_cells_of_band(&wide, &phi);
    let nb: NarrowBand<B> = band_around(&lat, &cross, j)?;
    let pts: Vec<DVec3> = nb.band.coords().map(|c| lat.pos(c)).collect();
    let v = shape.distances(&pts);
    let (nb, phi) = rebuild(&lat, &nb, &v)?;
    Ok(McfState { lat, nb, phi })
}

/// The zero level of `phi` on `band` with the vertices shared between cells merged (a closed
/// surface for shading and output).
pub fn welded_zero_level<B: Band<Coord = C3>>(
    lat: &Lattice,
    band: &B,
    phi: &[f64],
) -> TriangleSurface {
    let mut s = zero_level(lat, band, phi).surface;
    s.weld(1e-9 * lat.h);
    s
}

/// The Q1 interpolant of the band field `u` at `p`, from a grid cell containing `p` whose
/// corners are all band nodes; `None` when there is none.
pub fn interpolate<B: Band<Coord = C3>>(
    lat: &Lattice,
    band: &B,
    u: &[f64],
    p: DVec3,
) -> Option<f64> {
    let xi = (p - DVec3::splat(lat.lo)) / lat.h;
    let base = [xi.x, xi.y, xi.z].map(|v| v.floor() as i32);
    // A point on a cell face belongs to the cells on both sides: try the lower ones too.
    for k in 0..8 {
        let mut c = base;
        let mut ok = true;
        for a in 0..3 {
            if (k >> a) & 1 == 1 {
                let f = [xi.x, xi.y, xi.z][a] - base[a] as f64;
                if f > 1e-9 {
                    ok = false;
                }
                c[a] -= 1;
            }
        }
        if !ok {
            continue;
        }
        let vals: Option<Vec<f64>> = (0..8)
            .map(|q| band.index(c.corner(q)).map(|i| u[i]))
            .collect();
        if let Some(vals) = vals {
            let loc = [xi.x - c[0] as f64, xi.y - c[1] as f64, xi.z - c[2] as f64];
            return Some((0..8).map(|q| vals[q] * shape(3, q, &loc)).sum());
        }
    }
    None
}
