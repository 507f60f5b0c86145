//! `cosserat-check`: checks the paper's derivations and prints the derivation table.
//! All logic lives in the library (`cosserat_check::cli`); this only maps the result
//! to an exit code.

use clap::Parser;
use cosserat_check::cli::{run, Cli, Output, Status};
use std::io::IsTerminal;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = Cli::parse();
    let stdout = std::io::stdout();
    let terminal = stdout.is_terminal();
    let mut stream = stdout.lock();
    let mut out = Output {
        stream: &mut stream,
        terminal,
    };
    match run(cli, &mut out) {
        Ok(Status::AsExpected) => ExitCode::SUCCESS,
        Ok(Status::Unexpected) => ExitCode::from(1),
        Err(e) => {
            eprintln!("{e}");
            ExitCode::from(2)
        }
    }
}
