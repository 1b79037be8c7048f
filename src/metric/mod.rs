//! Riemannian metric fields: all metric mathematics in one module (owner: metric work).
//! `tensor.rs` holds the `Sym2` storage type.

pub mod tensor;

pub use tensor::Sym2;
