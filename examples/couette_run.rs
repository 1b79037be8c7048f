//! Runs the Couette benchmark (004 §5.1) once and prints the report.
//!
//! Usage: `cargo run --release --example couette_run -- [--fitted] [eps=..] [hmax=..]
//! [hmin=..] [band=..] [grade=..] [--quadrature] [h=..] [out=DIR]`

use anisomesh::bench::couette::{run, CouetteOptions};

fn main() -> anisomesh::Result<()> {
    let mut o = CouetteOptions::default();
    for a in std::env::args().skip(1) {
        let (k, v) = a.split_once('=').unwrap_or((a.as_str(), ""));
        let x: f64 = v.parse().unwrap_or(f64::NAN);
        match k {
            "--fitted" => o.fitted = true,
            "eps" => o.eps = x,
            "hmax" => o.hmax = x,
            "hmin" => o.hmin = x,
            "band" => o.band = x,
            "grade" => o.grade = x,
            "--quadrature" => o.interface = anisomesh::flows::InterfaceViscosity::Quadrature,
            "width" => o.width = x,
            "h" => o.h_interface = x,
            "out" => o.out_dir = Some(v.into()),
            _ => eprintln!("ignored argument {a}"),
        }
    }
    let r = run(&o)?;
    println!("{}", serde_json::to_string_pretty(&r).unwrap_or_default());
    Ok(())
}
