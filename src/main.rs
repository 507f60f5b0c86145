//! `cosserat-check`: checks the paper's derivations and prints the derivation table.
//! All logic lives in the library (`cosserat_check::cli`); this only maps the result
//! to an exit code.

use clap::Parser;
use cosserat_check::cli::{run, Cli, Status};
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = Cli::parse();
    let stdout = std::io::stdout();
    match run(cli, &mut stdout.lock()) {
        Ok(Status::AsExpected) => ExitCode::SUCCESS,
        Ok(Status::Unexpected) => ExitCode::from(1),
        Err(e) => {
            eprintln!("{e}");
            ExitCode::from(2)
        }
    }
}
