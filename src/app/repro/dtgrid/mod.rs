//! The band finite element tables of 000 (Table 2.1: the heat equation on a sphere; Table 2.2:
//! a sphere shrinking by mean curvature), run cell by cell beside the paper's values, with the
//! observed orders, written as JSON (`dtgrid_heat.json`, `dtgrid_mcf.json`) and CSV.

use anisomesh::backends::dtgrid::heat::{sphere_heat, HeatOptions, TimeScheme};
use anisomesh::backends::dtgrid::lattice::{Lattice, C3};
use anisomesh::backends::dtgrid::mcf::{sphere_mcf, McfOptions, McfState};
use anisomesh::backends::dtgrid::scheme::Bc;
use anisomesh::backends::dtgrid::{Band, DtGrid};
use anisomesh::Result;
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

type B = DtGrid<C3>;

/// One table cell.
#[derive(Debug, Clone, Serialize)]
pub struct Row {
    /// Grid nodes per side.
    pub n: usize,
    /// Grid spacing.
    pub h: f64,
    /// Band half-width j.
    pub band: usize,
    /// Boundary condition name.
    pub bc: String,
    /// Most solves per step (1: no inner iteration); mean solves used for mcf rows.
    pub inner: f64,
    /// Time step.
    pub tau: f64,
    /// Time discretisation (`euler` or `bdf2`).
    pub time: String,
    /// Our error.
    pub error: f64,
    /// The paper's value, where it has one.
    pub paper_error: Option<f64>,
    /// Band nodes.
    pub nodes: usize,
    /// Wall seconds.
    pub seconds: f64,
    /// Final mean radius (mcf).
    pub radius_final: Option<f64>,
    /// Exact radius (mcf).
    pub radius_exact: Option<f64>,
}

/// 000 Table 2.1: rows (bc, j), columns 17³, 33³, 65³, 129³, 257³, 513³.
fn paper_heat(bc: Bc, j: usize, n: usize) -> Option<f64> {
    let col = [17, 33, 65, 129, 257, 513].iter().position(|&m| m == n)?;
    let t: [f64; 6] = match (bc, j) {
        (Bc::Natural, 1) => [0.008630, 0.003052, 0.002378, 0.004136, 0.004901, 0.004986],
        (Bc::Natural, 2) => [0.006465, 0.001884, 0.000911, 0.000408, 0.001375, 0.001108],
        (Bc::Natural, 4) => [f64::NAN, 0.001763, 0.000407, 0.000179, 0.000181, 0.000285],
        (Bc::Natural, 8) => [f64::NAN, f64::NAN, 0.000432, 0.000109, 1.98e-05, 2.77e-05],
        (Bc::Transparent, 1) => [0.005976, 0.000775, 0.000320, 0.000124, 0.000134, 7.91e-05],
        (Bc::Transparent, 2) => [0.006791, 0.001828, 0.000388, 8.24e-05, 0.000132, 4.99e-05],
        (Bc::Transparent, 4) => [f64::NAN, 0.001745, 0.000428, 0.000128, 1.86e-05, 5.31e-05],
        (Bc::Transparent, 8) => [f64::NAN, f64::NAN, 0.000432, 0.000109, 2.66e-05, 8.73e-06],
        _ => return None,
    };
    Some(t[col]).filter(|v| v.is_finite())
}

/// 000 Table 2.2: blocks 0 (τ = h², inner), 1 (τ = h/8, inner), 2 (τ = h/8, none); rows j.
fn paper_mcf(block: usize, j: usize, n: usize) -> Option<f64> {
    let col = [17, 33, 65, 129, 257].iter().position(|&m| m == n)?;
    let row = [1, 2, 4, 8].iter().position(|&m| m == j)?;
    const T: [[[f64; 5]; 4]; 3] = [
        [
            [0.018982, 0.006987, 0.004533, 0.002694, 0.001267],
            [0.012818, 0.002848, 0.001277, 0.000883, 0.000785],
            [0.007579, 0.001830, 0.000492, 0.000144, 6.16e-05],
            [0.006822, 0.001629, 0.000411, 9.65e-05, 2.33e-05],
        ],
        [
            [0.024438, 0.015436, 0.005113, 0.000767, 0.008048],
            [0.024601, 0.014252, 0.003951, 0.002080, 0.000305],
            [0.010950, 0.008937, 0.002940, 0.001370, 0.000603],
            [0.008948, 0.004677, 0.001996, 0.000910, 0.000393],
        ],
        [
            [0.026056, 0.050502, 0.042877, 0.047269, 0.049729],
            [0.006402, 0.014512, 0.024515, 0.036311, 0.043778],
            [0.006223, 0.002222, 0.007890, 0.019629, 0.030859],
            [0.176777, 0.003851, 0.000525, 0.004257, 0.012067],
        ],
    ];
    Some(T[block][row][col])
}

/// The block of 000 Table 2.2 whose scheme a single run uses (`None` when it is none of them):
/// Dirichlet conditions to `t = 0.0059` from `R0 = 0.25`, with inner iterations at `τ = h²`
/// (block 0) or `τ = h/8` (block 1), or without them at `τ = h/8` (block 2).
pub fn paper_block(h: f64, tau: f64, t_end: f64, o: &McfOptions) -> Option<usize> {
    let near = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b;
    if o.bc != Bc::Dirichlet || !near(t_end, 0.0059) {
        return None;
    }
    match (o.inner > 1, near(tau, h * h), near(tau, h / 8.0)) {
        (true, true, _) => Some(0),
        (true, false, true) => Some(1),
        (false, _, true) => Some(2),
        _ => None,
    }
}

/// One heat run as a row.
pub fn heat_row(o: &HeatOptions) -> Result<Row> {
    let t = Instant::now();
    let r = sphere_heat::<B>(o)?;
    Ok(Row {
        n: o.n,
        h: r.h,
        band: o.j,
        bc: o.bc.name().into(),
        inner: 1.0,
        tau: r.tau,
        time: o.time.name().into(),
        error: r.error,
        paper_error: paper_heat(o.bc, o.j, o.n),
        nodes: r.nodes,
        seconds: t.elapsed().as_secs_f64(),
        radius_final: None,
        radius_exact: None,
    })
}

/// One shrinking-sphere run as a row (`block` picks the paper's column set, `None` for none).
pub fn mcf_row(
    n: usize,
    tau: f64,
    t_end: f64,
    o: &McfOptions,
    block: Option<usize>,
) -> Result<Row> {
    let t = Instant::now();
    let r = sphere_mcf::<B>(n, 0.25, t_end, tau, o)?;
    Ok(Row {
        n,
        h: 1.0 / (n - 1) as f64,
        band: o.j,
        bc: o.bc.name().into(),
        inner: r.mean_solves,
        tau: r.tau,
        time: TimeScheme::Euler.name().into(),
        error: r.error,
        paper_error: block.and_then(|b| paper_mcf(b, o.j, n)),
        nodes: r.nodes,
        seconds: t.elapsed().as_secs_f64(),
        radius_final: Some(r.radius_final),
        radius_exact: Some(r.radius_exact),
    })
}

/// The heat table (000 Table 2.1) on the grids `ns` with the time discretisation `time` and the
/// time step `tau(h)`.
pub fn heat_table(ns: &[usize], time: TimeScheme, tau: impl Fn(f64) -> f64) -> Result<Vec<Row>> {
    let mut rows = Vec::new();
    for bc in [Bc::Natural, Bc::Transparent] {
        for j in [1, 2, 4, 8] {
            for &n in ns {
                // The paper leaves cells whose band would not fit the coarse grid empty.
                if (j == 4 && n < 33) || (j == 8 && n < 65) {
                    continue;
                }
                let h = 1.0 / (n - 1) as f64;
                rows.push(heat_row(&HeatOptions {
                    time,
                    tau: Some(tau(h)),
                    ..HeatOptions::paper(n, j, bc)
                })?);
            }
        }
    }
    Ok(rows)
}

/// The mean curvature table (000 Table 2.2) on the grids `ns`: the three blocks.
pub fn mcf_table(ns: &[usize]) -> Result<Vec<Row>> {
    let mut rows = Vec::new();
    for block in 0..3 {
        for j in [1, 2, 4, 8] {
            for &n in ns {
                let h = 1.0 / (n - 1) as f64;
                let tau = if block == 0 { h * h } else { h / 8.0 };
                let o = McfOptions {
                    j,
                    // At τ = h/8 a step moves the surface by ~h on 129³ and the inner
                    // iteration needs up to ~11 solves (its stopping test ends it earlier).
                    inner: [5, 20, 1][block],
                    ..McfOptions::default()
                };
                match mcf_row(n, tau, 0.0059, &o, Some(block)) {
                    Ok(r) => rows.push(r),
                    // A band wider than the grid: the cell stays empty, as in the paper.
                    Err(anisomesh::Error::InvalidInput(_)) => continue,
                    Err(e) => return Err(e),
                }
            }
        }
    }
    Ok(rows)
}

/// The table as text: one line per row with the paper's value, the ratio and the observed
/// order against the previous grid of the same row.
pub fn format_table(rows: &[Row]) -> String {
    let mut s = String::from(
        "    n  band bc           time  inner   tau        error      paper      ratio  order  nodes      s\n",
    );
    for (i, r) in rows.iter().enumerate() {
        let prev = i.checked_sub(1).map(|k| &rows[k]).filter(|p| {
            p.band == r.band && p.bc == r.bc && p.inner.round() == r.inner.round() && p.n < r.n
        });
        let order = prev.map_or(String::from("     "), |p| {
            format!("{:5.2}", (p.error / r.error).ln() / (p.h / r.h).ln())
        });
        let (paper, ratio) = r
            .paper_error
            .map_or(("      –   ".into(), "     ".into()), |p| {
                (format!("{p:10.3e}"), format!("{:5.2}", r.error / p))
            });
        s += &format!(
            "{:5} {:5} {:12} {:5} {:5.2} {:10.3e} {:10.3e} {} {} {} {:7} {:6.1}\n",
            r.n,
            r.band,
            r.bc,
            r.time,
            r.inner,
            r.tau,
            r.error,
            paper,
            ratio,
            order,
            r.nodes,
            r.seconds
        );
    }
    s
}

/// Writes `name.json` (`{"rows": [...]}`) and `name.csv` into `dir`.
pub fn write_rows(dir: &Path, name: &str, rows: &[Row]) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| anisomesh::Error::Io {
        path: dir.to_path_buf(),
        source: e,
    })?;
    let json = serde_json::to_string_pretty(&serde_json::json!({ "rows": rows }))
        .map_err(|e| anisomesh::Error::InvalidInput(e.to_string()))?;
    anisomesh::io::atomic_write(&dir.join(format!("{name}.json")), |w| {
        w.write_all(json.as_bytes())
    })?;
    anisomesh::io::atomic_write(&dir.join(format!("{name}.csv")), |w| {
        writeln!(
            w,
            "n,h,band,bc,time,inner,tau,error,paper_error,nodes,seconds"
        )?;
        for r in rows {
            writeln!(
                w,
                "{},{},{},{},{},{},{},{},{},{},{}",
                r.n,
                r.h,
                r.band,
                r.bc,
                r.time,
                r.inner,
                r.tau,
                r.error,
                r.paper_error.map_or(String::new(), |p| p.to_string()),
                r.nodes,
                r.seconds
            )?;
        }
        Ok(())
    })
}

/// The phases of one mean curvature step (000 Table 4.1) and the speed of the band
/// matrix–vector product.
#[derive(Debug, Clone, Copy)]
pub struct StepTiming {
    /// Band nodes.
    pub nodes: usize,
    /// Interior band nodes (`I^j`, the unknowns of the Dirichlet solve; 000 Table 4.1 counts
    /// these as degrees of freedom).
    pub interior: usize,
    /// The step's report (solves, CG iterations, wall and processor seconds per phase).
    pub step: anisomesh::backends::dtgrid::mcf::StepReport,
    /// Stored entries of the system matrix `M + τ L`.
    pub nnz: usize,
    /// Band nodes per processor second of the CSR product `(M + τ L) x` on one core.
    pub matvec_rate: f64,
    /// Bytes per second it moves at least (row pointers, columns, values, `x` and `y` once).
    pub matvec_bandwidth: f64,
}

/// One mean curvature step of the sphere `r = 1/3` on `n³` nodes with half-width `j`, `τ = h²`
/// (000 Table 4.1), and the system matrix's product timed on one core (a one-thread pool).
pub fn step_timing(n: usize, j: usize) -> Result<StepTiming> {
    use anisomesh::backends::dtgrid::fem::{elements, Weight};
    use anisomesh::backends::dtgrid::mcf::cpu_seconds;
    use anisomesh::backends::dtgrid::stencil::assemble_scaled;
    let lat = Lattice::unit(n)?;
    let mut s: McfState<B> = McfState::new(lat, j, &|p| p.length() - 1.0 / 3.0)?;
    let nodes = s.nb.band.len();
    let interior = s.nb.interior.iter().filter(|&&i| i).count();
    let tau = lat.h * lat.h;
    let (nnz, matvec_rate, matvec_bandwidth) = {
        let el = elements(&s.nb);
        let (_, a) = assemble_scaled(
            &lat,
            &el,
            nodes,
            &s.phi,
            Weight::Mcf { eps: 1e-3 },
            tau,
            true,
        )?;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .map_err(|e| anisomesh::Error::InvalidInput(format!("thread pool: {e}")))?;
        let x = s.phi.clone();
        let mut y = vec![0.0; nodes];
        // Processor time of the process (the pool's one thread works, the caller waits), so
        // other work on the machine does not count against the product.
        let secs = pool.install(|| {
            a.matvec(&x, &mut y);
            let reps = (2e8 / a.nnz().max(1) as f64).ceil().clamp(3.0, 200.0) as usize;
            let t = cpu_seconds();
            for _ in 0..reps {
                a.matvec(&x, &mut y);
            }
            (cpu_seconds() - t) / reps as f64
        });
        let bytes = 8 * (nodes + 1) + 12 * a.nnz() + 16 * nodes;
        (a.nnz(), nodes as f64 / secs, bytes as f64 / secs)
    };
    let o = McfOptions {
        j,
        ..McfOptions::default()
    };
    let step = s.step(tau, &o)?;
    Ok(StepTiming {
        nodes,
        interior,
        step,
        nnz,
        matvec_rate,
        matvec_bandwidth,
    })
}
