//! `ppr-walkthrough`: parses the command line and runs the walkthrough; exit status 2 for a
//! level or set it refuses, 1 for any other failure.

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    match ppr_walkthrough::run(ppr_walkthrough::Args::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("ppr-walkthrough: error: {e:#}");
            ExitCode::from(ppr_walkthrough::bad_input::exit_status(&e))
        }
    }
}
