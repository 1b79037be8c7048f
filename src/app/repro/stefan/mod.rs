//! The Stefan problem on the interface-fitted mesh (001 §6): Frank's expanding circle against its
//! exact solution (`frank.rs`).

pub mod frank;
