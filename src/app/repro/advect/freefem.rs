//! The same transport in FreeFem++ (its usual recipe): `convect` (characteristics with the
//! velocity frozen at the middle of each period) followed by `adaptmesh(Th, phi, err, hmin,
//! hmax)` (BAMG's Hessian metric of the level set) every period, from a square grid adapted four
//! times to the exact initial level set. The initial, halfway and final meshes and level sets
//! are saved and measured with the same code as ours (exact P1 area, symmetric difference,
//! Hausdorff distance). Absent FreeFem++: [`FreeFemRun::status`] says so and nothing else runs.

use super::cases::Case;
use crate::app::repro::peers::{find_program, run_with_timeout};
use anisomesh::advect::{hausdorff, symmetric_difference, Snapshot};
use anisomesh::error::{Error, Result};
use anisomesh::io::{atomic_write, read_mesh};
use anisomesh::levelset::interface::{enclosed_area, extract_zero_level, interface_length};
use serde::Serialize;
use std::path::Path;
use std::process::Command;
use std::time::Duration;

/// The outcome of a FreeFem++ run.
#[derive(Debug, Clone, Serialize)]
pub struct FreeFemRun {
    /// `ok`, `unavailable` or the failure.
    pub status: String,
    /// `err`, `hmin`, `hmax` given to `adaptmesh`.
    pub err: f64,
    /// Smallest size.
    pub hmin: f64,
    /// Largest size.
    pub hmax: f64,
    /// Area of the initial and final `{phi < 0}`.
    pub area_initial: f64,
    /// Area of the final `{phi < 0}`.
    pub area_final: f64,
    /// Length of the zero level at the start, halfway and at the end.
    pub perimeter_initial: f64,
    /// Length of the zero level halfway.
    pub perimeter_half: f64,
    /// Length of the final zero level.
    pub perimeter_final: f64,
    /// Symmetric difference with the initial shape (time-reversed flows).
    pub area_symmetric_difference: f64,
    /// Hausdorff distance between the final and the initial zero levels.
    pub hausdorff: f64,
    /// Mean and largest vertex count over the periods.
    pub vertices_mean: f64,
    /// Largest vertex count.
    pub vertices_max: usize,
    /// Wall-clock seconds of the FreeFem++ process.
    pub seconds: f64,
    /// The halfway state (for the figures).
    #[serde(skip)]
    pub half: Option<Snapshot>,
}

const SCRIPT: &str = r#"real T = @T@; int nsteps = @N@; real dt = T / nsteps;
real err = @ERR@, hmin = @HMIN@, hmax = @HMAX@;
mesh Th = square(40, 40, [@X0@ + (@X1@ - @X0@) * x, @Y0@ + (@Y1@ - @Y0@) * y]);
fespace Vh(Th, P1);
func phi0 = @PHI@;
Vh phi = phi0;
for (int i = 0; i < 4; i++) {
  Th = adaptmesh(Th, phi, err=err, hmin=hmin, hmax=hmax, nbvx=1000000);
  phi = phi0;
}
macro save(name) { savemesh(Th, "@DIR@/" + name + ".mesh"); ofstream f("@DIR@/" + name + ".txt"); f.precision(17); f << phi[].n << "\n"; for (int j = 0; j < phi[].n; j++) f << phi[][j] << "\n"; } //
save("ff_initial");
cout << "V 0 " << Th.nv << endl;
real t = 0;
for (int k = 0; k < nsteps; k++) {
  real tm = t + dt / 2;
  Vh u1 = @U@, u2 = @V@;
  phi = convect([u1, u2], -dt, phi);
  t += dt;
  Th = adaptmesh(Th, phi, err=err, hmin=hmin, hmax=hmax, nbvx=1000000);
  phi = phi;
  cout << "V " << (k + 1) << " " << Th.nv << endl;
  if (2 * (k + 1) == nsteps) save("ff_half");
}
save("ff_final");
"#;

/// FreeFem's spelling of one of our expressions (`^` is its power too; `t` becomes the
/// mid-period time `tm`).
fn to_freefem(e: &str) -> String {
    let mut out = String::new();
    let chars: Vec<char> = e.chars().collect();
    for (i, &c) in chars.iter().enumerate() {
        let prev = i.checked_sub(1).map(|j| chars[j]);
        let next = chars.get(i + 1).copied();
        let ident = |ch: Option<char>| ch.is_some_and(|ch| ch.is_alphanumeric() || ch == '_');
        if c == 't' && !ident(prev) && !ident(next) {
            out.push_str("tm");
        } else {
            out.push(c);
        }
    }
    out
}

fn read_state(dir: &Path, name: &str) -> Result<Snapshot> {
    let mesh = read_mesh(&dir.join(format!("{name}.mesh")))?;
    let p = dir.join(format!("{name}.txt"));
    let text = std::fs::read_to_string(&p).map_err(|e| Error::io(&p, e))?;
    let mut it = text.split_whitespace();
    let n: usize = it
        .next()
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| Error::InvalidInput(format!("{}: no count", p.display())))?;
    let u: Vec<f64> = it.filter_map(|s| s.parse().ok()).collect();
    if u.len() != n || n != mesh.n_points() {
        return Err(Error::InvalidInput(format!(
            "{}: {} values for {} vertices",
            p.display(),
            u.len(),
            mesh.n_points()
        )));
    }
    Ok(Snapshot { time: 0.0, mesh, u })
}

/// Runs FreeFem++ on `case` with `periods` periods and `adaptmesh(err, hmin, hmax)` in `dir`.
pub fn run(case: &Case, periods: usize, sizes: [f64; 3], dir: &Path) -> Result<FreeFemRun> {
    let [err, hmin, hmax] = sizes;
    let mut out = FreeFemRun {
        status: "unavailable: FreeFem++ is not on PATH".into(),
        err,
        hmin,
        hmax,
        area_initial: f64::NAN,
        area_final: f64::NAN,
        perimeter_initial: f64::NAN,
        perimeter_half: f64::NAN,
        perimeter_final: f64::NAN,
        area_symmetric_difference: f64::NAN,
        hausdorff: f64::NAN,
        vertices_mean: f64::NAN,
        vertices_max: 0,
        seconds: 0.0,
        half: None,
    };
    let Some(prog) = find_program("FreeFem++") else {
        return Ok(out);
    };
    if anisomesh::levelset::Expr::parse(&case.shape_source).is_err() {
        out.status = "not run: the shape is not an expression".into();
        return Ok(out);
    }
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let abs = dir.canonicalize().map_err(|e| Error::io(dir, e))?;
    let (lo, hi) = case.domain;
    let script = SCRIPT
        .replace("@T@", &format!("{}", case.t_end))
        .replace("@N@", &periods.to_string())
        .replace("@ERR@", &format!("{err}"))
        .replace("@HMIN@", &format!("{hmin}"))
        .replace("@HMAX@", &format!("{hmax}"))
        .replace("@X0@", &format!("({})", lo.x))
        .replace("@X1@", &format!("({})", hi.x))
        .replace("@Y0@", &format!("({})", lo.y))
        .replace("@Y1@", &format!("({})", hi.y))
        .replace("@PHI@", &to_freefem(&case.shape_source))
        .replace("@U@", &to_freefem(case.velocity.u.source()))
        .replace("@V@", &to_freefem(case.velocity.v.source()))
        .replace("@DIR@", &abs.to_string_lossy());
    let path = dir.join("freefem_advect.edp");
    atomic_write(&path, |w| w.write_all(script.as_bytes()))?;
    let mut cmd = Command::new(prog);
    cmd.arg("-nw").arg("-v").arg("0").arg(&path);
    let o = run_with_timeout(&mut cmd, Duration::from_secs(1800), dir, "freefem_advect")?;
    out.seconds = o.seconds;
    if !o.success {
        let last = o
            .stderr
            .lines()
            .chain(o.stdout.lines())
            .last()
            .unwrap_or("");
        out.status = if o.timed_out {
            "failed: timed out".into()
        } else {
            format!("failed: {last}")
        };
        return Ok(out);
    }
    let verts: Vec<usize> = o
        .stdout
        .lines()
        .filter_map(|l| l.strip_prefix("V "))
        .filter_map(|l| l.split_whitespace().nth(1)?.parse().ok())
        .collect();
    out.vertices_mean = verts.iter().sum::<usize>() as f64 / verts.len().max(1) as f64;
    out.vertices_max = verts.iter().copied().max().unwrap_or(0);
    let init = read_state(dir, "ff_initial")?;
    let last = read_state(dir, "ff_final")?;
    out.area_initial = enclosed_area(&init.mesh, &init.u)?;
    out.area_final = enclosed_area(&last.mesh, &last.u)?;
    out.perimeter_initial = interface_length(&init.mesh, &init.u)?;
    out.perimeter_final = interface_length(&last.mesh, &last.u)?;
    if let Ok(mut h) = read_state(dir, "ff_half") {
        out.perimeter_half = interface_length(&h.mesh, &h.u)?;
        h.time = 0.5 * case.t_end;
        out.half = Some(h);
    }
    if case.returns {
        let phi = &*case.phi0;
        out.area_symmetric_difference = symmetric_difference(&last.mesh, &last.u, phi, 3)?;
        out.hausdorff = hausdorff(
            &extract_zero_level(&init.mesh, &init.u)?,
            &extract_zero_level(&last.mesh, &last.u)?,
            4,
        );
    }
    out.status = "ok".into();
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_becomes_the_mid_period_time() {
        assert_eq!(
            to_freefem("sin(pi*t/8)*cos(t)+sqrt(x)"),
            "sin(pi*tm/8)*cos(tm)+sqrt(x)"
        );
    }
}
