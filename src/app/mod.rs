//! The application around the library: the command line ([`cli`]), the paper reproductions,
//! benchmark flows and peer comparisons ([`repro`]), and the figures ([`plot`]). Nothing here is
//! library API: it prints, draws, parses arguments and starts peer programs, and it reaches the
//! library only through `anisomesh`'s public interface.

pub mod cli;
pub mod plot;
pub mod repro;

#[cfg(test)]
mod tests;
