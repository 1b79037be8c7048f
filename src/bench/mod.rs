//! Benchmark flows: one file per benchmark, each returning a typed report.
