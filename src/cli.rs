//! The command line: `cosserat-check [check] [--format …] [--only ID] [--dir DIR]`.
//!
//! Exit codes: 0 when every verdict equals the one its derivation file declares, 1
//! when any differs, 2 for malformed input (with a located diagnostic on stderr).

use crate::derivation::{load_dir, DerivationFile, LoadError};
use crate::report;
use crate::strategy::{decide_claim, Decided};
use clap::{Parser, Subcommand, ValueEnum};
use std::io::Write;
use std::path::PathBuf;

/// Checks the derivations of Papanicolopoulos & Veveakis, "Sliding and rolling
/// dissipation in Cosserat plasticity", equation by equation, and prints the
/// derivation table. Without a subcommand it runs `check`.
#[derive(Debug, Parser)]
#[command(name = "cosserat-check", version, about, long_about = None)]
#[command(
    after_help = "Exit status: 0 when every verdict equals the one declared in the derivation files, 1 when any differs, 2 for malformed input."
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Decide every claim and print the derivation table.
    Check(CheckArgs),
}

#[derive(Debug, Clone, clap::Args, Default)]
pub struct CheckArgs {
    /// Output format of the table.
    #[arg(long, value_enum, default_value_t = Format::Markdown)]
    pub format: Format,
    /// Check only the claim with this id (e.g. eq33).
    #[arg(long, value_name = "ID")]
    pub only: Option<String>,
    /// Directory of derivation files (*.toml, read in name order). Defaults to
    /// ./derivations, or the one shipped with the crate when there is none here.
    #[arg(long, value_name = "DIR")]
    pub dir: Option<PathBuf>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum Format {
    /// A Markdown table with statements as inline LaTeX.
    #[default]
    Markdown,
    /// The JSON contract (see README).
    Json,
}

/// The outcome of a run, mapped to the process exit code by `main`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    AsExpected,
    Unexpected,
}

/// An error that ends a run with exit code 2.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    #[error("{0}")]
    Input(String),
    #[error("error: cannot write the output: {0}")]
    Output(#[from] std::io::Error),
}

impl From<LoadError> for RunError {
    fn from(e: LoadError) -> Self {
        RunError::Input(e.to_string())
    }
}

fn default_dir() -> PathBuf {
    let here = PathBuf::from("derivations");
    if here.is_dir() {
        here
    } else {
        PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/derivations"))
    }
}

/// Decides every claim of the files (or only `only`), in file and claim order.
pub fn decide_all<'f>(
    files: &'f [DerivationFile],
    only: Option<&str>,
) -> Result<Vec<Decided<'f>>, RunError> {
    let claims: Vec<_> = files
        .iter()
        .flat_map(|f| &f.claims)
        .filter(|c| only.is_none_or(|id| c.id == id))
        .collect();
    if let (Some(id), true) = (only, claims.is_empty()) {
        let known: Vec<&str> = files
            .iter()
            .flat_map(|f| &f.claims)
            .map(|c| c.id.as_str())
            .collect();
        return Err(RunError::Input(format!(
            "error: no claim has id `{id}`\n  = help: known ids: {}",
            known.join(", ")
        )));
    }
    claims
        .into_iter()
        .map(|c| decide_claim(c).map_err(|d| RunError::Input(d.to_string())))
        .collect()
}

/// Runs the command line, writing the report to `out`.
pub fn run(cli: Cli, out: &mut dyn Write) -> Result<Status, RunError> {
    let args = match cli.command {
        Some(Command::Check(a)) => a,
        None => CheckArgs::default(),
    };
    let dir = args.dir.clone().unwrap_or_else(default_dir);
    let started = std::time::Instant::now();
    let files = load_dir(&dir)?;
    let rows = decide_all(&files, args.only.as_deref())?;
    let text = match args.format {
        Format::Markdown => report::markdown::render(&rows),
        Format::Json => report::json::render(&rows),
    };
    out.write_all(text.as_bytes())?;
    out.flush()?;
    if std::io::IsTerminal::is_terminal(&std::io::stderr()) {
        eprintln!(
            "checked {} claims from {} in {:.1} ms",
            rows.len(),
            dir.display(),
            started.elapsed().as_secs_f64() * 1e3
        );
    }
    Ok(if rows.iter().all(Decided::as_expected) {
        Status::AsExpected
    } else {
        Status::Unexpected
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn cli_definition_is_consistent() {
        Cli::command().debug_assert();
    }
}
