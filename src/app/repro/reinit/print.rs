//! The tables of the redistancing experiments as text, beside the paper's values (003 tables
//! 8.1-8.3) and orders, and the volume-drift line.

use super::types::Table;

/// The paper's values `(e_∞, e^∇_∞)` for levels 3..=8 (003 tables 8.1–8.3), by `(α, k)`.
fn paper(alpha: u32, k: usize) -> Option<[(f64, f64); 6]> {
    Some(match (alpha, k) {
        (1, 1) => [
            (1.21e-2, 2.50e-1),
            (3.01e-3, 1.53e-1),
            (7.54e-4, 8.32e-2),
            (1.90e-4, 4.25e-2),
            (4.68e-5, 2.12e-2),
            (1.19e-5, 1.07e-2),
        ],
        (1, 2) => [
            (5.73e-4, 1.66e-2),
            (7.21e-5, 3.46e-3),
            (9.94e-6, 8.70e-4),
            (1.24e-6, 2.13e-4),
            (1.58e-7, 5.31e-5),
            (2.07e-8, 1.34e-5),
        ],
        (10, 1) => [
            (1.15e-2, 2.40e-1),
            (3.24e-3, 1.61e-1),
            (7.91e-4, 8.02e-2),
            (2.07e-4, 4.32e-2),
            (5.18e-5, 2.24e-2),
            (1.32e-5, 1.11e-2),
        ],
        (10, 2) => [
            (7.16e-4, 1.77e-2),
            (1.04e-4, 3.78e-3),
            (1.56e-5, 1.10e-3),
            (1.87e-6, 3.10e-4),
            (2.44e-7, 7.32e-5),
            (3.09e-8, 1.91e-5),
        ],
        (50, 1) => [
            (4.07e-2, 6.23e-1),
            (1.05e-2, 2.32e-1),
            (2.91e-3, 1.01e-1),
            (7.63e-4, 5.76e-2),
            (1.94e-4, 3.04e-2),
            (4.84e-5, 1.58e-2),
        ],
        (50, 2) => [
            (7.47e-2, 8.10e-1),
            (2.86e-2, 3.10e-1),
            (5.66e-4, 1.63e-2),
            (6.87e-5, 2.48e-2),
            (7.21e-6, 1.52e-3),
            (8.78e-7, 3.90e-4),
        ],
        _ => return None,
    })
}

/// Prints table `t` with its measured orders, the paper's values and orders (3D, levels 3..=8)
/// and the redistancing statistics of each row.
pub(super) fn print_table(t: &Table) {
    let pap = if t.dim == 3 {
        paper(t.alpha, t.k)
    } else {
        None
    };
    let which = match t.alpha {
        1 => "   [paper: 003 Table 8.1]",
        10 => "   [paper: 003 Table 8.2]",
        50 => "   [paper: 003 Table 8.3]",
        _ => "",
    };
    println!(
        "\n{} ({}D), k = {}, alpha = {}{}",
        t.name,
        t.dim,
        t.k,
        t.alpha,
        if pap.is_some() { which } else { "" }
    );
    println!(
        "{:>3} {:>9} {:>9} {:>5} {:>9} {:>5} | {:>8} {:>5} {:>8} {:>5} | {:>9} {:>9} {:>4} {:>7} {:>7}",
        "l", "h", "e_inf", "ord", "e_grad", "ord", "paper e", "ord", "paper eg", "ord", "cells",
        "nodes", "n.c.", "s", "MiB"
    );
    let o = |x: Option<f64>| x.map_or("-".to_string(), |v| format!("{v:.2}"));
    for (i, r) in t.rows.iter().enumerate() {
        let at = |l: u32| {
            pap.filter(|_| (3..=8).contains(&l))
                .map(|p| p[(l - 3) as usize])
        };
        let (pe, pg) = at(r.level).map_or(("-".into(), "-".into()), |(a, b)| {
            (format!("{a:.2e}"), format!("{b:.2e}"))
        });
        // The paper's orders from its own values (levels differ by one: h halves).
        let prev = (i > 0 && t.rows[i - 1].level + 1 == r.level)
            .then(|| at(r.level - 1))
            .flatten();
        let (po, pgo) = match (prev, at(r.level)) {
            (Some(a), Some(b)) => (Some((a.0 / b.0).log2()), Some((a.1 / b.1).log2())),
            _ => (None, None),
        };
        println!(
            "{:>3} {:>9.3e} {:>9.3e} {:>5} {:>9.3e} {:>5} | {:>8} {:>5} {:>8} {:>5} | {:>9} {:>9} {:>4} {:>7.1} {:>7}",
            r.level,
            r.h,
            r.e_inf,
            o(r.order_inf),
            r.e_grad,
            o(r.order_grad),
            pe,
            o(po),
            pg,
            o(pgo),
            r.report.cells,
            r.report.nodes,
            r.report.not_converged,
            r.secs,
            r.peak_mib.map_or("-".into(), |m| format!("{m:.0}")),
        );
    }
}

/// One line of relative volume errors at repetitions 0, 1, 10, 20, 50 and the last (only those
/// that were run), with the paper's statement beside them.
pub fn drift_line(k: usize, level: u32, e: &[f64]) -> String {
    let last = e.len().saturating_sub(1);
    let mut marks: Vec<usize> = [0, 1, 10, 20, 50]
        .into_iter()
        .filter(|&n| n < last)
        .collect();
    marks.push(last);
    let vals: Vec<String> = marks
        .iter()
        .map(|&n| format!("e^{n} = {:.3e}", e[n]))
        .collect();
    format!(
        "sphere r = 0.25, k = {k}, level {level}: {}  (003 Fig. 8.4, levels 5-6: a mild \
         shrinking, weaker for k = 2; the text gives no numbers)",
        vals.join(", ")
    )
}
