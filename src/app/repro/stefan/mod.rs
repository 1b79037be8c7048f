//! The Stefan problem on the interface-fitted mesh (001 §6): Frank's expanding circle against its
//! exact solution (`frank.rs`), and the pentagon seed of 001 §6 (`paper.rs`).

pub mod frank;
pub mod paper;
