//! 000 Table 4.1 as a comparison: one mean curvature step of the sphere `r = 1/3` about the
//! centre of the grid's cube `[−½, ½]³`, `τ = h²`, on the thinnest DT-Grid band of the `n³` lattice
//! (`h = 1/(n − 1)`, 000 §2.2) and on the parametric P1 icosphere whose longest edge is nearest
//! to `h` (002's θ-scheme, θ = 1, the scheme 000 compares with): rebuild, assembly and solve
//! seconds, degrees of freedom and CG iterations, beside the paper's rows.

use anisomesh::backends::dtgrid::lattice::{Lattice, C3};
use anisomesh::backends::dtgrid::mcf::{McfOptions, McfState};
use anisomesh::backends::dtgrid::{Band, DtGrid};
use anisomesh::backends::surface::{assemble_surface, ParametricSurface};
use anisomesh::error::Result;
use serde::Serialize;
use std::time::Instant;

/// One row of the comparison.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Table41Row {
    /// `narrow band` or `parametric`, with the source (`measured`, `000`).
    pub method: String,
    /// Seconds rebuilding the band and redistancing (`None` for the parametric surface).
    pub rebuild: Option<f64>,
    /// Seconds assembling the matrices.
    pub assembly: f64,
    /// Seconds in the linear solves.
    pub solve: f64,
    /// Degrees of freedom: band nodes, or 3 × surface vertices (000 counts coordinates).
    pub dof: usize,
    /// CG iterations (summed over the solves of the step).
    pub iterations: usize,
    /// The longest edge of the surface, or the grid spacing.
    pub h: f64,
}

/// The paper's rows (000 Table 4.1, a 3.6 GHz Pentium).
pub fn paper_rows() -> [Table41Row; 2] {
    [
        Table41Row {
            method: "narrow band (000)".into(),
            rebuild: Some(10.202),
            assembly: 14.133,
            solve: 5.864,
            dof: 1_098_484,
            iterations: 5,
            h: 1.0 / 512.0,
        },
        Table41Row {
            method: "parametric (000)".into(),
            rebuild: None,
            assembly: 0.780,
            solve: 4.296,
            dof: 196_614,
            iterations: 84,
            h: 1.0 / 512.0,
        },
    ]
}

/// The longest edge of a surface's triangles.
fn longest_edge(s: &ParametricSurface) -> f64 {
    s.triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
        .map(|(a, b)| (s.nodes[a as usize] - s.nodes[b as usize]).length())
        .fold(0.0, f64::max)
}

/// Runs both steps on the `n³` lattice (`n = 513` is the paper's) and returns the measured rows
/// followed by the paper's. Errors: a bad `n`, and those of the steps.
pub fn run(n: usize) -> Result<Vec<Table41Row>> {
    let lat = Lattice::unit(n)?;
    let h = lat.h;
    let tau = h * h;
    let radius = 1.0 / 3.0;
    let opts = McfOptions::default();
    let mut band: McfState<DtGrid<C3>> = McfState::new(lat, opts.j, &|p| p.length() - radius)?;
    let nodes = band.nb.band.len();
    let rep = band.step(tau, &opts)?;
    let mut rows = vec![Table41Row {
        method: "narrow band (measured)".into(),
        rebuild: Some(rep.times.rebuild),
        assembly: rep.times.assembly,
        solve: rep.times.solve,
        dof: nodes,
        iterations: rep.cg_iterations,
        h,
    }];
    // The icosphere level whose longest edge is nearest to h (in the log).
    let mut best: Option<(f64, ParametricSurface)> = None;
    for level in 1..=9 {
        let s = ParametricSurface::icosphere(radius, level, 1)?;
        let e = longest_edge(&s);
        let gap = (e / h).ln().abs();
        let better = match &best {
            None => true,
            Some((g, _)) => gap < *g,
        };
        if better {
            best = Some((gap, s));
        }
        if e < h {
            break;
        }
    }
    let Some((_, surface)) = best else {
        unreachable!("the loop visits level 1")
    };
    let edge = longest_edge(&surface);
    let t = Instant::now();
    let (m, a) = assemble_surface(&surface)?;
    let assembly = t.elapsed().as_secs_f64();
    let mut x: Vec<Vec<f64>> = (0..3)
        .map(|d| surface.nodes.iter().map(|p| p[d]).collect())
        .collect();
    let t = Instant::now();
    let stats = anisomesh::backends::surface::theta_solve(&m, &a, tau, 1.0, &mut x)?;
    let solve = t.elapsed().as_secs_f64();
    rows.push(Table41Row {
        method: "parametric (measured)".into(),
        rebuild: None,
        assembly,
        solve,
        dof: 3 * surface.n_vertices,
        iterations: stats.iterations,
        h: edge,
    });
    rows.extend(paper_rows());
    Ok(rows)
}

/// The rows as a table.
pub fn table(rows: &[Table41Row]) -> String {
    let mut s = format!(
        "\nsphere r = 1/3, one mean curvature step, tau = h^2 (000 Table 4.1)\n{:<24} {:>9} {:>9} \
         {:>9} {:>10} {:>6} {:>10}\n",
        "method", "rebuild", "assembly", "solve", "dof", "CG it", "h"
    );
    for r in rows {
        let rb = r.rebuild.map_or("-".into(), |v| format!("{v:.3}"));
        s += &format!(
            "{:<24} {:>9} {:>9.3} {:>9.3} {:>10} {:>6} {:>10.3e}\n",
            r.method, rb, r.assembly, r.solve, r.dof, r.iterations, r.h
        );
    }
    s
}
