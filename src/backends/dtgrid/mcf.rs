//! Mean curvature motion of a level set on a narrow band (000 §2.2–§2.4, Table 2.2): each step
//! solves `(M[Φ^k] + τ L[Φ^k]) Φ^{k+1} = M[Φ^k] Φ^k` (000 (2.5)) on the band with Dirichlet
//! values on its boundary layer (000 (2.12)). With more than one solve per step this is the
//! nested inner iteration of 000 §2.4: after each solve the band is rebuilt around the new zero
//! level, the new iterate is replaced by its signed distance on the new band (the next Dirichlet
//! data; on the corners of the crossed cells the iterate itself, renormalised, so redistancing
//! does not move the zero level — see [`super::distance`]), `Φ^k` is extended onto the new band (old values kept, new nodes by the signed distance
//! to its zero level), and the step is solved again, until the band stops changing and the
//! boundary data change by less than `δ`. With one solve the Dirichlet data are `Φ^k` itself
//! (the scheme "without inner iterations"). After each step `Φ^{k+1}` is a signed distance
//! function on the band around its zero level. Natural and transparent (000 (2.11))
//! conditions take one solve per step on the band of `Φ^k`.

use super::band::Band;
use super::distance::{extend_distance, extend_from_level, level, zero_level_integral, Keep};
use super::elemop::ElementOperator;
use super::fem::{elements, transparent_vector, Element, Weight};
use super::lattice::{band_around, Lattice, NarrowBand, C3};
use super::scheme::{solve_all, solve_dirichlet_rtol, solve_dirichlet_with, Bc};
use super::stencil::assemble_scaled;
use crate::error::{Error, Result};
use crate::fem::Csr;
use std::time::Instant;

/// The options of a mean curvature step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct McfOptions {
    /// The band half-width `j` in cells.
    pub j: usize,
    /// The boundary condition.
    pub bc: Bc,
    /// The most solves per step (1: no inner iteration).
    pub inner: usize,
    /// The regularisation `ε` of `|∇Φ|_ε`.
    pub eps: f64,
    /// The inner iteration stops when the boundary data change by less than `delta · h` in the
    /// mean over the boundary nodes and the rebuilt band differs from the last one in fewer than
    /// `delta` times its nodes (nodes the zero level passes by less than the tolerance).
    pub delta: f64,
    /// The relative residual at which CG stops (relative to the residual of the initial guess,
    /// the last iterate).
    pub cg_rtol: f64,
    /// Dirichlet solves apply `M + τ L` element by element ([`ElementOperator`], the default)
    /// instead of assembling it: the same system up to the order of summation, faster and
    /// smaller (see `docs/dtgrid.md`); the different rounding changes Table 2.2's errors by up
    /// to about 10⁻⁴ relative against the assembled matrix (`false`).
    pub element_product: bool,
}

impl Default for McfOptions {
    fn default() -> Self {
        McfOptions {
            j: 1,
            bc: Bc::Dirichlet,
            inner: 5,
            eps: 1e-3,
            delta: 1e-2,
            cg_rtol: 1e-6,
            element_product: true,
        }
    }
}

/// Seconds spent in each phase of a step: wall-clock, and the processor time of the whole
/// process (all threads) in `*_cpu`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PhaseTimes {
    /// Rebuilding the band and the signed distance extension.
    pub rebuild: f64,
    /// Assembling the band matrices.
    pub assembly: f64,
    /// Solving the linear systems.
    pub solve: f64,
    /// Processor seconds of the rebuild.
    pub rebuild_cpu: f64,
    /// Processor seconds of the assembly.
    pub assembly_cpu: f64,
    /// Processor seconds of the solves.
    pub solve_cpu: f64,
}

/// A wall-clock and processor-time stopwatch.
struct Clock(Instant, f64);

impl Clock {
    fn start() -> Clock {
        Clock(Instant::now(), cpu_seconds())
    }

    /// (wall, processor) seconds since the start.
    fn read(&self) -> (f64, f64) {
        (self.0.elapsed().as_secs_f64(), cpu_seconds() - self.1)
    }
}

/// The processor time of this process (all threads), in seconds.
pub fn cpu_seconds() -> f64 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime writes into the timespec it is given.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut t) };
    if rc != 0 {
        return f64::NAN;
    }
    t.tv_sec as f64 + 1e-9 * t.tv_nsec as f64
}

/// What one step did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepReport {
    /// Linear solves (1 + inner iterations).
    pub solves: usize,
    /// CG iterations over all solves.
    pub cg_iterations: usize,
    /// The phase times.
    pub times: PhaseTimes,
}

/// The system `M[Φ^k] + τ L[Φ^k]` of a step: applied element by element (Dirichlet conditions
/// with [`McfOptions::element_product`]; CG needs only products) or assembled.
enum System {
    Elements(ElementOperator),
    Matrix(Vec<Element>, Csr),
}

/// A level set on a band moving by mean curvature.
#[derive(Debug, Clone)]
pub struct McfState<B> {
    /// The grid.
    pub lat: Lattice,
    /// The band around the current zero level.
    pub nb: NarrowBand<B>,
    /// `Φ` on the band nodes (a signed distance function after each step).
    pub phi: Vec<f64>,
}

/// `phi` at the nodes of `to`: its value where `from` has the node, else the signed distance to
/// its zero level (with the sign of the nearest triangle's side).
fn extend<B: Band<Coord = C3>>(
    lat: &Lattice,
    from: &B,
    phi: &[f64],
    to: &B,
    shells: i32,
) -> Vec<f64> {
    extend_distance(lat, from, phi, to, Keep::OldBand, shells as f64 * lat.h)
}

/// The mean change `|new − old|` of the boundary data over the boundary nodes of `new_nb` that
/// `old_nb` also holds (the update of the Dirichlet data in the stopping test of 000 §2.4).
fn boundary_change<B: Band<Coord = C3>>(
    new_nb: &NarrowBand<B>,
    new: &[f64],
    old_nb: &NarrowBand<B>,
    old: &[f64],
) -> f64 {
    let (mut sum, mut count) = (0.0, 0usize);
    for ((k, v), _) in old_index(&old_nb.band, &new_nb.band)
        .zip(new)
        .zip(&new_nb.interior)
        .filter(|(_, &int)| !int)
    {
        if let Some(k) = k {
            sum += (v - old[k]).abs();
            count += 1;
        }
    }
    if count == 0 {
        f64::INFINITY
    } else {
        sum / count as f64
    }
}

/// Per node of `to`, in storage order: its index in `from`, if `from` has it (one merge of the
/// two sorted node lists, no search).
fn old_index<'a, B: Band<Coord = C3>>(
    from: &'a B,
    to: &'a B,
) -> impl Iterator<Item = Option<usize>> + 'a {
    let mut old = from.coords().enumerate().peekable();
    to.coords().map(move |c| {
        while old.next_if(|(_, o)| *o < c).is_some() {}
        old.next_if(|(_, o)| *o == c).map(|(k, _)| k)
    })
}

/// `Φ^k` (a signed distance on `from`) on the band `to`, where `d` is the signed distance to the
/// new iterate's zero level: kept where `from` has the node; on a new node `d` plus the mean of
/// `Φ^k − d` over its `3³` neighbours in both bands (two distance functions differ by the normal
/// displacement of their zero levels, which varies slowly). A new node without such neighbours
/// falls back to the distance transform of `Φ^k`.
fn extend_phi<B: Band<Coord = C3>>(
    lat: &Lattice,
    from: &B,
    phi: &[f64],
    to: &B,
    d: &[f64],
    shells: i32,
) -> Vec<f64> {
    let mut out = Vec::with_capacity(to.len());
    for (i, (c, k)) in to.coords().zip(old_index(from, to)).enumerate() {
        if let Some(k) = k {
            out.push(phi[k]);
            continue;
        }
        let (mut sum, mut count) = (0.0, 0usize);
        for dz in -1..=1 {
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let q = [c[0] + dx, c[1] + dy, c[2] + dz];
                    if let (Some(k), Some(l)) = (from.index(q), to.index(q)) {
                        sum += phi[k] - d[l];
                        count += 1;
                    }
                }
            }
        }
        if count == 0 {
            return extend(lat, from, phi, to, shells);
        }
        out.push(d[i] + sum / count as f64);
    }
    out
}

/// The band of half-width `j` around the zero level of `phi` on `nb` and the signed distance to
/// that zero level on it (signs from `phi` where the node was in `nb`).
/// Errors: [`Error::EmptyLevelSet`] when the zero level has vanished, [`Error::InvalidInput`]
/// when the band leaves the grid.
pub fn rebuild<B: Band<Coord = C3>>(
    lat: &Lattice,
    nb: &NarrowBand<B>,
    phi: &[f64],
) -> Result<(NarrowBand<B>, Vec<f64>)> {
    rebuild_keeping(lat, nb, phi, Keep::Nothing)
}

/// [`rebuild`], keeping the values of `phi` where `keep` says.
pub fn rebuild_keeping<B: Band<Coord = C3>>(
    lat: &Lattice,
    nb: &NarrowBand<B>,
    phi: &[f64],
    keep: Keep,
) -> Result<(NarrowBand<B>, Vec<f64>)> {
    // One pass over the old band's cells gives the crossed cells and their triangles.
    let l = level(lat, &nb.band, phi);
    let new: NarrowBand<B> = band_around(lat, &l.crossing_cells(), nb.j).map_err(|e| match e {
        Error::EmptyLevelSet(_) => Error::EmptyLevelSet(
            "the zero level vanished during the motion (no band cell is crossed)".into(),
        ),
        e => e,
    })?;
    let d = extend_from_level(
        lat,
        &l,
        &nb.band,
        phi,
        &new.band,
        keep,
        shells(nb.j) as f64 * lat.h,
    );
    Ok((new, d))
}

fn shells(j: usize) -> i32 {
    2 * j as i32 + 4
}

impl<B: Band<Coord = C3> + Clone> McfState<B> {
    /// The level set `f` (negative inside) on the grid `lat`: the band of half-width `j` around
    /// its zero level carrying the signed distance to that zero level.
    /// Errors: [`Error::EmptyLevelSet`], [`Error::InvalidInput`] (the shape does not fit),
    /// [`Error::InvalidField`] (NaN in `f`).
    pub fn new(
        lat: Lattice,
        j: usize,
        f: &(impl Fn(crate::geom::DVec3) -> f64 + Sync),
    ) -> Result<McfState<B>> {
        let cross = super::lattice::crossing_cells_of_fn(&lat, f)?;
        let nb: NarrowBand<B> = band_around(&lat, &cross, j)?;
        let v: Vec<f64> = nb.band.coords().map(|c| f(lat.pos(c))).collect();
        let (nb, phi) = rebuild(&lat, &nb, &v)?;
        Ok(McfState { lat, nb, phi })
    }

    /// One time step of length `tau`.
    /// Errors: [`Error::EmptyLevelSet`] when the zero level vanishes, [`Error::InvalidInput`]
    /// when the band leaves the grid or for extrapolated conditions (heat only), solver errors.
    pub fn step(&mut self, tau: f64, o: &McfOptions) -> Result<StepReport> {
        if tau.is_nan() || tau <= 0.0 || o.inner == 0 || o.bc == Bc::Extrapolated {
            return Err(Error::InvalidInput(format!(
                "mean curvature step: tau = {tau}, solves per step = {}, conditions {} (tau and \
                 solves positive; dirichlet, natural or transparent)",
                o.inner,
                o.bc.name()
            )));
        }
        let lat = self.lat;
        let w = Weight::Mcf { eps: o.eps };
        let mut rep = StepReport::default();
        let mut nb = self.nb.clone();
        let mut phik = self.phi.clone();
        let mut approx = self.phi.clone();
        let solves = if o.bc == Bc::Dirichlet { o.inner } else { 1 };
        // The system of the last solve, reused while `Φ^k` and the band stay the same.
        let mut system: Option<(System, Vec<f64>)> = None;
        for m in 1..=solves {
            let t = Clock::start();
            let n = nb.band.len();
            let (sys, b) = match system.take() {
                Some(s) => s,
                None => {
                    let el = elements(&nb);
                    let (sys, mass) = if o.bc == Bc::Dirichlet && o.element_product {
                        let op = ElementOperator::new(el, n, &phik, lat.h, o.eps, tau)?;
                        let mass = op.mass.clone();
                        (System::Elements(op), mass)
                    } else {
                        let (mass, a) = assemble_scaled(&lat, &el, n, &phik, w, tau, true)?;
                        (System::Matrix(el, a), mass)
                    };
                    let b: Vec<f64> = mass.iter().zip(&phik).map(|(m, p)| m * p).collect();
                    (sys, b)
                }
            };
            let (w_s, c_s) = t.read();
            rep.times.assembly += w_s;
            rep.times.assembly_cpu += c_s;
            let t = Clock::start();
            let mut x = approx.clone();
            rep.cg_iterations += match &sys {
                System::Elements(op) => {
                    let fixed: Vec<bool> = nb.interior.iter().map(|i| !i).collect();
                    let apply = |v: &[f64], y: &mut [f64]| op.apply(v, y, Some(&fixed));
                    solve_dirichlet_with(apply, &op.diag, &b, &fixed, &mut x, o.cg_rtol)?
                }
                System::Matrix(el, a) if o.bc == Bc::Transparent => {
                    let g = transparent_vector(&lat, el, n, &phik, &approx, w);
                    let b: Vec<f64> = b.iter().zip(&g).map(|(b, g)| b + tau * g).collect();
                    solve_all(a, &b, &mut x)?
                }
                System::Matrix(_, a) if o.bc == Bc::Dirichlet => {
                    let fixed: Vec<bool> = nb.interior.iter().map(|i| !i).collect();
                    solve_dirichlet_rtol(a, &b, &fixed, &mut x, o.cg_rtol)?
                }
                System::Matrix(_, a) => solve_all(a, &b, &mut x)?,
            };
            rep.solves += 1;
            let (w_s, c_s) = t.read();
            rep.times.solve += w_s;
            rep.times.solve_cpu += c_s;
            let t = Clock::start();
            let (new_nb, new_approx) = rebuild_keeping(&lat, &nb, &x, Keep::Crossing)?;
            let same =
                new_nb.band.len() == nb.band.len() && new_nb.band.coords().eq(nb.band.coords());
            let done = same || {
                let gained = old_index(&nb.band, &new_nb.band)
                    .filter(Option::is_none)
                    .count();
                let lost = nb.band.len() + gained - new_nb.band.len();
                ((gained + lost) as f64) < o.delta * nb.band.len() as f64
            };
            let done =
                done && boundary_change(&new_nb, &new_approx, &nb, &approx) < o.delta * lat.h;
            // On the same band the extension of `Φ^k` is the one it already has.
            if m < solves && !done && !same {
                phik = extend_phi(
                    &lat,
                    &self.nb.band,
                    &self.phi,
                    &new_nb.band,
                    &new_approx,
                    shells(nb.j),
                );
            } else {
                system = Some((sys, b));
            }
            nb = new_nb;
            approx = new_approx;
            let (w_s, c_s) = t.read();
            rep.times.rebuild += w_s;
            rep.times.rebuild_cpu += c_s;
            if done {
                break;
            }
        }
        self.nb = nb;
        self.phi = approx;
        Ok(rep)
    }

    /// The area-weighted mean of `g(x)` over the zero level (e.g. `||x| − r|` for a sphere),
    /// quadrature points on the trilinear zero level.
    /// Error: [`Error::EmptyLevelSet`] when the zero level is empty.
    pub fn surface_mean(&self, g: impl Fn(crate::geom::DVec3) -> f64) -> Result<f64> {
        let (area, s) = zero_level_integral(&self.lat, &self.nb.band, &self.phi, g);
        if area.is_nan() || area <= 0.0 {
            return Err(Error::EmptyLevelSet("the zero level has no area".into()));
        }
        Ok(s / area)
    }
}

/// The outcome of a shrinking-sphere run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphereMcfResult {
    /// The mean of `||x| − r(t_end)|` over the final zero level (000 Table 2.2).
    pub error: f64,
    /// The mean radius of the final zero level.
    pub radius_final: f64,
    /// `r(t_end) = √(R0² − 4 t_end)`.
    pub radius_exact: f64,
    /// Band nodes at the end.
    pub nodes: usize,
    /// Time steps.
    pub steps: usize,
    /// The time step used.
    pub tau: f64,
    /// Mean solves per step.
    pub mean_solves: f64,
}

/// The sphere of radius `r0` about the origin moving by mean curvature to `t_end` on `n³` nodes
/// with time step `tau` (rounded so that the steps end at `t_end`).
/// Errors: as [`McfState::new`] and [`McfState::step`]; [`Error::EmptyLevelSet`] when the sphere
/// vanishes before `t_end` (`4 t_end ≥ r0²`).
pub fn sphere_mcf<B: Band<Coord = C3> + Clone>(
    n: usize,
    r0: f64,
    t_end: f64,
    tau: f64,
    o: &McfOptions,
) -> Result<SphereMcfResult> {
    let lat = Lattice::unit(n)?;
    let mut s: McfState<B> = McfState::new(lat, o.j, &|p| p.length() - r0)?;
    if !(t_end.is_finite() && t_end > 0.0 && tau.is_finite() && tau > 0.0) {
        return Err(Error::InvalidInput(format!("t_end = {t_end}, tau = {tau}")));
    }
    let steps = (t_end / tau - 1e-9).ceil().max(1.0) as usize;
    let tau = t_end / steps as f64;
    let mut solves = 0;
    for _ in 0..steps {
        solves += s.step(tau, o)?.solves;
    }
    if 4.0 * t_end >= r0 * r0 {
        return Err(Error::EmptyLevelSet(format!(
            "the sphere of radius {r0} vanishes at t = {} before t_end = {t_end}",
            r0 * r0 / 4.0
        )));
    }
    let exact = (r0 * r0 - 4.0 * t_end).sqrt();
    Ok(SphereMcfResult {
        error: s.surface_mean(|x| (x.length() - exact).abs())?,
        radius_final: s.surface_mean(|x| x.length())?,
        radius_exact: exact,
        nodes: s.nb.band.len(),
        steps,
        tau,
        mean_solves: solves as f64 / steps as f64,
    })
}
