//! The `anisomesh` command line: argument parsing, then one call into the library per command.
//! Every error is printed as one line on standard error with a non-zero exit status.

mod app;

use app::cli;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    // A closed pipe (`anisomesh info f | head`) ends the program quietly, as in other Unix tools,
    // instead of a panic in `println!`.
    #[cfg(unix)]
    // SAFETY: called once at start-up, before any other thread exists.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let args = cli::Cli::parse();
    match cli::run(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("anisomesh: error: {e}");
            ExitCode::FAILURE
        }
    }
}
