//! The data files of the Zalesak rotation: `zalesak.json` (the report) and `zalesak.csv` (the
//! time series), each written atomically.

use std::path::Path;

use super::types::ZalesakReport;
use anisomesh::advect::StepStats;
use anisomesh::error::{Error, Result};
use anisomesh::io::atomic_write;

/// Writes `zalesak.json` (the report) and `zalesak.csv` (the time series) into `dir`
/// ([`atomic_write`]).
pub fn write_outputs(dir: &Path, report: &ZalesakReport) -> Result<()> {
    write_report_and_series(dir, "zalesak", report, &report.series)
}

/// Writes `<name>.json` (the report) and `<name>.csv` (the per-period time series) into `dir`
/// ([`atomic_write`]): the data files of every transport run.
pub fn write_report_and_series(
    dir: &Path,
    name: &str,
    report: &impl serde::Serialize,
    series: &[StepStats],
) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let json = serde_json::to_vec_pretty(report)
        .map_err(|e| Error::InvalidInput(format!("{name} report serialisation: {e}")))?;
    atomic_write(&dir.join(format!("{name}.json")), |w| w.write_all(&json))?;
    let mut csv = String::from(
        "period,time,area,perimeter,vertices,fixed_point_iterations,l1_change,seconds\n",
    );
    for s in series {
        csv.push_str(&format!(
            "{},{:.12},{:.12},{:.12},{},{},{:.3e},{:.3}\n",
            s.period,
            s.time,
            s.area,
            s.perimeter,
            s.vertices,
            s.fixed_point_iterations,
            s.l1_change,
            s.seconds
        ));
    }
    atomic_write(&dir.join(format!("{name}.csv")), |w| {
        w.write_all(csv.as_bytes())
    })
}
