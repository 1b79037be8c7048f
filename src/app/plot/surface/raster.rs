//! The software rasteriser behind the surface pictures: a camera (orthographic or perspective),
//! a z-buffer at `SS × SS` supersampling (averaged down: anti-aliasing), per-pixel interpolated
//! normals with ambient + Lambert + a weak Blinn highlight, per-vertex colours and wireframe
//! edges drawn where a pixel is within a line width of a marked triangle edge (so only visible
//! edges show).

use anisomesh::geom::DVec3;

/// Supersampling factor per axis.
pub const SS: usize = 3;

/// A triangle to draw: corner positions, normals, colours (linear RGB in `[0, 1]`) and which
/// edges (bit `i`: from corner `i` to `i + 1`) carry a wireframe line.
#[derive(Debug, Clone, Copy)]
pub struct Tri {
    pub p: [DVec3; 3],
    pub n: [DVec3; 3],
    pub c: [[f32; 3]; 3],
    pub edges: u8,
}

/// Orthographic or perspective camera looking at `centre` from `direction`.
#[derive(Debug, Clone, Copy)]
pub struct Camera {
    centre: DVec3,
    u: DVec3,
    v: DVec3,
    w: DVec3,
    /// Pixels (supersampled) per unit length at the centre plane.
    scale: f64,
    half: (f64, f64),
    /// Distance from the eye to the centre, for a perspective camera.
    eye: Option<f64>,
}

impl Camera {
    /// A camera framing the sphere `(centre, radius)` in a `width × height` (supersampled)
    /// image, viewing from `direction` (towards the eye) with `up` upwards; perspective with a
    /// 30° field of view when `perspective`. `fill` is the fraction of the half-size the sphere
    /// covers; `shift_y` moves the picture down by that many pixels (room for a title).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        centre: DVec3,
        radius: f64,
        direction: DVec3,
        up: DVec3,
        perspective: bool,
        (width, height): (usize, usize),
        fill: f64,
        shift_y: f64,
    ) -> Camera {
        let w = direction.normalize_or(DVec3::Z);
        let mut u = up.cross(w);
        if u.length_squared() < 1e-12 {
            u = w.any_orthonormal_vector();
        }
        let u = u.normalize();
        let v = w.cross(u);
        let radius = radius.max(1e-300);
        let half_px = 0.5 * width.min(height) as f64 * fill;
        let (scale, eye) = if perspective {
            let d = radius / (15f64).to_radians().sin();
            // A point of the sphere at depth r projects at most at r / sqrt(d² − r²) · d.
            (
                half_px * (d * d - radius * radius).sqrt() / (d * radius),
                Some(d),
            )
        } else {
            (half_px / radius, None)
        };
        Camera {
            centre,
            u,
            v,
            w,
            scale,
            half: (0.5 * width as f64, 0.5 * height as f64 + shift_y),
            eye,
        }
    }

    /// Screen position (pixels, `y` down) and depth (smaller is nearer).
    pub fn project(&self, p: DVec3) -> (f64, f64, f64) {
        let q = p - self.centre;
        let (mut x, mut y, z) = (q.dot(self.u), q.dot(self.v), q.dot(self.w));
        if let Some(d) = self.eye {
            let f = d / (d - z).max(1e-9 * d);
            x *= f;
            y *= f;
        }
        (
            self.half.0 + x * self.scale,
            self.half.1 - y * self.scale,
            -z,
        )
    }

    /// The unit vector from `p` towards the eye.
    fn eye_direction(&self, p: DVec3) -> DVec3 {
        match self.eye {
            Some(d) => (self.centre + d * self.w - p).normalize_or(self.w),
            None => self.w,
        }
    }

    /// The light direction: from the upper left, in front.
    fn light(&self) -> DVec3 {
        (-0.45 * self.u + 0.65 * self.v + 0.75 * self.w).normalize()
    }
}

/// A supersampled colour and depth buffer.
pub struct Canvas {
    pub width: usize,
    pub height: usize,
    depth: Vec<f64>,
    colour: Vec<[f32; 3]>,
}

impl Canvas {
    /// A white canvas of `width × height` supersampled pixels.
    pub fn new(width: usize, height: usize) -> Canvas {
        Canvas {
            width,
            height,
            depth: vec![f64::INFINITY; width * height],
            colour: vec![[1.0; 3]; width * height],
        }
    }

    /// Draws `tri` seen by `cam` (both sides; the back side is lit as if it faced the eye).
    /// `line` is the wireframe half-width in supersampled pixels.
    pub fn draw(&mut self, cam: &Camera, tri: &Tri, line: f64) {
        let s = tri.p.map(|p| cam.project(p));
        let area = (s[1].0 - s[0].0) * (s[2].1 - s[0].1) - (s[2].0 - s[0].0) * (s[1].1 - s[0].1);
        if area.is_nan() || area.abs() <= 1e-12 {
            return;
        }
        let x0 = s
            .iter()
            .map(|q| q.0)
            .fold(f64::INFINITY, f64::min)
            .floor()
            .max(0.0) as usize;
        let y0 = s
            .iter()
            .map(|q| q.1)
            .fold(f64::INFINITY, f64::min)
            .floor()
            .max(0.0) as usize;
        let x1 = (s
            .iter()
            .map(|q| q.0)
            .fold(f64::NEG_INFINITY, f64::max)
            .ceil())
        .min(self.width as f64 - 1.0);
        let y1 = (s
            .iter()
            .map(|q| q.1)
            .fold(f64::NEG_INFINITY, f64::max)
            .ceil())
        .min(self.height as f64 - 1.0);
        if x1.is_nan() || y1.is_nan() || x1 < 0.0 || y1 < 0.0 {
            return;
        }
        let (x1, y1) = (x1 as usize, y1 as usize);
        // Edge lengths on screen, for the distance of a pixel to the edge (i, i + 1).
        let len = [0, 1, 2].map(|i| {
            let (a, b) = (s[i], s[(i + 1) % 3]);
            ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2))
                .sqrt()
                .max(1e-12)
        });
        let light = cam.light();
        for y in y0..=y1 {
            let py = y as f64 + 0.5;
            for x in x0..=x1 {
                let px = x as f64 + 0.5;
                // Barycentric coordinates from the edge functions.
                let e = |i: usize, j: usize| {
                    (s[j].0 - s[i].0) * (py - s[i].1) - (s[j].1 - s[i].1) * (px - s[i].0)
                };
                let b = [e(1, 2) / area, e(2, 0) / area, e(0, 1) / area];
                if b.iter().any(|&bi| bi < 0.0) {
                    continue;
                }
                let depth = b[0] * s[0].2 + b[1] * s[1].2 + b[2] * s[2].2;
                let k = y * self.width + x;
                if depth >= self.depth[k] {
                    continue;
                }
                self.depth[k] = depth;
                let p = b[0] * tri.p[0] + b[1] * tri.p[1] + b[2] * tri.p[2];
                let to_eye = cam.eye_direction(p);
                let mut n =
                    (b[0] * tri.n[0] + b[1] * tri.n[1] + b[2] * tri.n[2]).normalize_or(to_eye);
                if n.dot(to_eye) < 0.0 {
                    n = -n;
                }
                let diffuse = n.dot(light).max(0.0);
                let half = (light + to_eye).normalize_or(to_eye);
                let spec = n.dot(half).max(0.0).powi(48) * 0.25;
                let shade = 0.32 + 0.6 * diffuse + 0.15 * n.dot(to_eye).max(0.0);
                let mut c = [0, 1, 2].map(|ch| {
                    let base = b[0] as f32 * tri.c[0][ch]
                        + b[1] as f32 * tri.c[1][ch]
                        + b[2] as f32 * tri.c[2][ch];
                    (base * shade as f32 + spec as f32).min(1.0)
                });
                if tri.edges != 0 {
                    // Distance (pixels) to edge (i, i + 1) = b_{i+2} · 2 area / length.
                    let d = (0..3)
                        .filter(|&i| tri.edges & (1 << i) != 0)
                        .map(|i| b[(i + 2) % 3] * area.abs() / len[i])
                        .fold(f64::INFINITY, f64::min);
                    if d < line {
                        let t = (1.0 - (d / line).powi(2)) as f32 * 0.85;
                        c = c.map(|v| v * (1.0 - t) + 0.08 * t);
                    }
                }
                self.colour[k] = c;
            }
        }
    }

    /// Averages `SS × SS` blocks into 8-bit RGB (gamma 1/2.2 is not applied: the colours are
    /// already display colours).
    pub fn downsample(&self) -> (usize, usize, Vec<u8>) {
        let (w, h) = (self.width / SS, self.height / SS);
        let mut out = vec![0u8; 3 * w * h];
        for y in 0..h {
            for x in 0..w {
                let mut acc = [0f32; 3];
                for dy in 0..SS {
                    for dx in 0..SS {
                        let c = self.colour[(y * SS + dy) * self.width + x * SS + dx];
                        for ch in 0..3 {
                            acc[ch] += c[ch];
                        }
                    }
                }
                for ch in 0..3 {
                    let v = acc[ch] / (SS * SS) as f32;
                    out[3 * (y * w + x) + ch] = (v.clamp(0.0, 1.0) * 255.0).round() as u8;
                }
            }
        }
        (w, h, out)
    }
}
