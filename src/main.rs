//! The `anisomesh` command line: a thin layer over the library.

fn main() {
    println!("anisomesh {}", env!("CARGO_PKG_VERSION"));
}
