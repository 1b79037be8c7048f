//! The `anisomesh` command line: argument parsing, then one call into the library per command.
//! Every error is printed as one line on standard error with a non-zero exit status.

mod cli;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args = cli::Cli::parse();
    match cli::run(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("anisomesh: error: {e}");
            ExitCode::FAILURE
        }
    }
}
