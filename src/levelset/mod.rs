//! Level-set functions: implicit shapes, zero-level extraction and measures, redistancing.

pub mod redistance;
