//! The command line. `main` maps [`run`]'s result to the exit code: 0 when every
//! verdict equals the one its derivation file declares, 1 when any differs, 2 for
//! malformed input (with a located diagnostic on stderr; nothing is written then).

use crate::check::{decide_claim, decide_claim_recorded, inherit, Decided};
use crate::decide::watch::{self, Watch};
use crate::derivation::only::Reading;
use crate::derivation::{load_files, DerivationFile, LoadError, Strategy};
use crate::lang::Diagnostic;
use crate::report;
use clap::{Parser, Subcommand, ValueEnum};
use std::collections::BTreeMap;
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// The guide's chapters (`docs/src`, an mdBook: `mdbook build docs`), in the order of
/// its summary; `cosserat-check guide` prints them one after another.
pub const GUIDE: [&str; 16] = [
    include_str!("../docs/src/introduction.md"),
    include_str!("../docs/src/tutorial.md"),
    include_str!("../docs/src/table.md"),
    include_str!("../docs/src/commands.md"),
    include_str!("../docs/src/files.md"),
    include_str!("../docs/src/fields.md"),
    include_str!("../docs/src/assumptions.md"),
    include_str!("../docs/src/strategies.md"),
    include_str!("../docs/src/reading.md"),
    include_str!("../docs/src/cli.md"),
    include_str!("../docs/src/file-reference.md"),
    include_str!("../docs/src/grammar.md"),
    include_str!("../docs/src/json.md"),
    include_str!("../docs/src/limits.md"),
    include_str!("../docs/src/trust.md"),
    include_str!("../docs/src/case-study.md"),
];

/// Decides every claim of a set of derivation files, equation by equation, and prints
/// the derivation table. Without a subcommand it runs `check` on the corpus in
/// ./derivations (the paper whose files ship with the crate).
#[derive(Debug, Parser)]
#[command(name = "cosserat-check", version, about, long_about = None)]
#[command(
    after_help = "Exit status: 0 when every verdict equals the one declared in the derivation files, 1 when any differs or a claim without a declared verdict fails, 2 for malformed input (nothing is written then), 3 when the checker itself failed on some claim (that claim is `undecided (internal error)`; the others are decided and written).\nThe guide (the derivation-file format, every strategy, the JSON contract): `cosserat-check guide`; files to start from: `cosserat-check examples --out DIR`; this help as a manual page: `cosserat-check manpage`."
)]
#[command(args_conflicts_with_subcommands = true)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// Without a subcommand, the options of `check`.
    #[command(flatten)]
    pub check: CheckArgs,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Decide every claim of the paper and print the derivation table.
    Check(CheckArgs),
    /// List every printed statement that fails: as printed, the counterexample, the
    /// correction and its verdict, the reason.
    Errata(CheckArgs),
    /// Show how one claim was decided, in enough detail to audit it by hand.
    Explain(ExplainArgs),
    /// Check your own derivation files (same format, table and exit codes).
    Verify(VerifyArgs),
    /// Plot scalar expressions of a derivation file against one parameter: a figure
    /// table of the file (--figure), or curves given here (--y, --x, --set).
    Plot(PlotArgs),
    /// Check every proof of a JSON report (`--format json`) again with the kernel
    /// alone, from the statements it records; exit 0 when every proof is accepted, 1
    /// when one is refused, 2 when the file is not a report.
    Recheck(RecheckArgs),
    /// Write the paper's derivation files and the examples (embedded in the binary)
    /// into a directory, as `derivations/*.toml` and `derivations/examples/*.toml`, so
    /// that every documented command works from there. An existing file with other
    /// content is never replaced (exit 2, nothing written).
    Examples(ExamplesArgs),
    /// Print a shell completion script (e.g. `completions bash > /etc/bash_completion.d/cosserat-check`).
    Completions(CompletionsArgs),
    /// Print the manual page (roff; e.g. `manpage > cosserat-check.1; man ./cosserat-check.1`).
    Manpage,
    /// Print the user guide (Markdown): the derivation-file format, every strategy,
    /// the reports and the JSON contract.
    Guide,
    /// Write a derivation file from a paper's LaTeX (or Markdown with `$$…$$` displays):
    /// one claim per numbered displayed equation, decided on its reading, with the
    /// declarations, definitions and notation the equations imply; what cannot be read
    /// is kept as a commented claim and listed in `to_complete`, with its line, reason
    /// and the edit that would let it be read, which `verify` prints. The file starts
    /// with `drafted = true`: a failure that a tie the paper may state in words would
    /// remove (between symbols the draft took as independent) is undecided, never an
    /// accusation, when the text gives a reason for such a tie (listed in `tied`, with
    /// its line: "equal and opposite", "symmetric", an equation left to complete, a
    /// labelled variant). `verify` accepts the file unchanged
    Draft(DraftArgs),
}

#[derive(Debug, Clone, clap::Args)]
pub struct DraftArgs {
    /// The paper: LaTeX (`equation`, `align`, `gather`, `multline`, `\[…\]` with
    /// `\tag`) or Markdown with `$$…$$` displays ending in `(N)`; `-` reads standard
    /// input.
    #[arg(value_name = "PAPER")]
    pub paper: PathBuf,
    /// The index range 1..=N; without it, a sentence of the paper such as "indices
    /// ranging from 1 to 3" sets it (unless another range is named too), else 3.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u8).range(2..=3))]
    pub dimension: Option<u8>,
    /// The paper's unit normal (a letter such as `n`), which `\langle … \rangle`
    /// averages over; without it, the letter the text calls "the unit normal" (or, for
    /// n, "unit vector"), if it names one.
    #[arg(long, value_name = "NAME")]
    pub normal: Option<String>,
    /// Write the file here (replaced atomically, never the paper) instead of standard
    /// output; `-` is standard output.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
}

#[derive(Debug, Clone, clap::Args)]
pub struct ExamplesArgs {
    /// The directory to write into (created if it does not exist).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
}

#[derive(Debug, Clone, clap::Args)]
pub struct CompletionsArgs {
    /// The shell.
    #[arg(value_enum)]
    pub shell: clap_complete::Shell,
}

#[derive(Debug, Clone, clap::Args)]
pub struct RecheckArgs {
    /// The JSON report (as `check --format json` or `verify --format json` writes it).
    #[arg(value_name = "REPORT")]
    pub report: PathBuf,
    /// The derivation files the report was made from (repeat for several): each proof
    /// must then be about the statement its claim's file gives, so that a true proof
    /// moved onto another claim, or a statement edited in the report, is refused.
    #[arg(long = "file", value_name = "FILE")]
    pub files: Vec<PathBuf>,
}

#[derive(Debug, Clone, clap::Args)]
pub struct PlotArgs {
    /// The derivation file whose definitions, declarations and assumptions the curves use.
    #[arg(value_name = "FILE")]
    pub file: PathBuf,
    /// A `[[figure]]` table of the file, by id (an unknown id lists the file's figures).
    #[arg(long, value_name = "ID", conflicts_with_all = ["y", "x", "set", "given"])]
    pub figure: Option<String>,
    /// The curves: scalar expressions in the file's notation, separated by commas
    /// (outside brackets) or given by repeating --y.
    #[arg(long, value_name = "EXPR[,EXPR…]", required_unless_present = "figure")]
    pub y: Vec<String>,
    /// The parameter and its range: a declared scalar, NAME=FROM..TO[:STEP]
    /// (decimals or fractions; 100 steps when STEP is left out; at most 10,000 points).
    #[arg(
        long,
        value_name = "NAME=FROM..TO[:STEP]",
        required_unless_present = "figure"
    )]
    pub x: Option<String>,
    /// Fix a parameter for every curve, as an assumption NAME = VALUE (repeatable).
    #[arg(long, value_name = "NAME=VALUE")]
    pub set: Vec<String>,
    /// A bound on which square roots take their sign, as a claim's `given`
    /// (e.g. 'sig < 0'; repeatable).
    #[arg(long, value_name = "BOUND")]
    pub given: Vec<String>,
    /// Output format: the table of values or the picture.
    #[arg(long, value_enum, default_value_t = FigureFormat::Csv)]
    pub format: FigureFormat,
    /// With --format svg: a linear y axis, even when the data span more than a factor
    /// of 30 (which gives a logarithmic one by default).
    #[arg(long)]
    pub linear: bool,
    /// Time limit for evaluating all the curves, in seconds: past it the figure is not
    /// written and the exit status is 2 [default: 600].
    #[arg(long, value_name = "SECONDS", value_parser = parse_seconds)]
    pub time_limit: Option<Duration>,
    /// Write to FILE instead of standard output (`-` is standard output). A regular file is replaced atomically; a device or FIFO is written into, never replaced.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum FigureFormat {
    /// The parameter, then one column per curve (12 significant digits; empty cells
    /// where a curve is undefined).
    #[default]
    Csv,
    /// An SVG 85 mm wide (one journal column): the y range or a log axis from the data,
    /// a colour-blind-safe palette with one dash pattern per curve, labels as mathematics.
    Svg,
}

/// Options shared by the commands that print a table.
#[derive(Debug, Clone, clap::Args, Default)]
pub struct OutputArgs {
    /// Output format [default: compact when standard output is a terminal and there
    /// is no --out, else markdown]. The same files, options and seed give byte-identical
    /// output, run after run.
    #[arg(long, value_enum)]
    pub format: Option<Format>,
    /// With --format latex: a complete document instead of a table fragment.
    #[arg(long)]
    pub standalone: bool,
    /// Colours in the compact table: `auto` colours a terminal unless NO_COLOR is set
    /// or TERM is `dumb`.
    #[arg(long, value_enum, default_value_t = ColorChoice::Auto)]
    pub color: ColorChoice,
    /// Write to FILE instead of standard output, only after every claim is decided (`-` is standard output). A regular file is replaced atomically; a device or FIFO is written into, never replaced.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Decide only the claim with this id (e.g. eq33), reading only its file and the files of the claims it uses.
    #[arg(long, value_name = "ID")]
    pub only: Option<String>,
    /// Override the seed of every numeric claim.
    #[arg(long, value_name = "N")]
    pub seed: Option<u64>,
    /// Override the sample count of every numeric claim (at least 50).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(50..=1_000_000))]
    pub samples: Option<u64>,
    /// Time limit per claim, in seconds: a claim not decided within it is
    /// `undecided (time limit)` [default: 600].
    #[arg(long, value_name = "SECONDS", value_parser = parse_seconds)]
    pub time_limit: Option<Duration>,
    /// Time limit for the whole run, in seconds: a claim that starts when less than its
    /// own limit is left gets only what is left, and past it every claim still to be
    /// decided is `undecided (time limit)` [default: 3600].
    #[arg(long, value_name = "SECONDS", value_parser = parse_seconds)]
    pub run_limit: Option<Duration>,
}

fn parse_seconds(s: &str) -> Result<Duration, String> {
    let x: f64 = s
        .parse()
        .map_err(|_| format!("`{s}` is not a number of seconds"))?;
    if x.is_finite() && x > 0.0 && x <= 1e9 {
        Ok(Duration::from_secs_f64(x))
    } else {
        Err(format!(
            "`{s}`: the time limit must be a positive number of seconds"
        ))
    }
}

#[derive(Debug, Clone, clap::Args, Default)]
pub struct CheckArgs {
    #[command(flatten)]
    pub output: OutputArgs,
    /// Directory of derivation files (*.toml, read in name order). Defaults to
    /// ./derivations, or the paper's files embedded in the binary when there is none here.
    #[arg(long, value_name = "DIR")]
    pub dir: Option<PathBuf>,
}

#[derive(Debug, Clone, clap::Args)]
pub struct ExplainArgs {
    /// The claim to explain (e.g. eq33).
    pub id: String,
    /// Directory of derivation files (as for `check`).
    #[arg(long, value_name = "DIR", conflicts_with = "files")]
    pub dir: Option<PathBuf>,
    /// Derivation files to read instead of a directory (one or more after one
    /// `--file`, which may also be repeated).
    #[arg(long = "file", value_name = "FILE", num_args = 1..)]
    pub files: Vec<PathBuf>,
}

#[derive(Debug, Clone, clap::Args)]
pub struct VerifyArgs {
    /// Derivation files to check, in this order.
    #[arg(required = true, value_name = "FILE")]
    pub files: Vec<PathBuf>,
    /// Read a claim without `expect` as expecting `holds`: its failure is then an
    /// unexpected verdict, marked as such. Without it such a claim is reported as
    /// found (the exit status is still 1 when it fails).
    #[arg(long)]
    pub strict: bool,
    #[command(flatten)]
    pub output: OutputArgs,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum Format {
    /// One line per claim (verdict, strength, method, a short line of evidence),
    /// failures highlighted; the default on a terminal.
    Compact,
    /// A Markdown table with statements as inline LaTeX and the full evidence.
    #[default]
    Markdown,
    /// A LaTeX longtable (a fragment; --standalone for a whole document).
    Latex,
    /// The JSON contract (see `cosserat-check guide`).
    Json,
    /// Comma-separated values, one row per claim.
    Csv,
    /// One self-contained HTML page (works offline): statements as MathML, the
    /// derivation graph as SVG (click a claim to focus it), every claim's evidence.
    Html,
}

/// When the compact table is coloured.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum ColorChoice {
    /// On a terminal, without --out, unless NO_COLOR is set or TERM is `dumb`.
    #[default]
    Auto,
    Always,
    Never,
}

impl ColorChoice {
    /// Whether to colour, for output to a terminal (`terminal`) or elsewhere.
    fn colours(self, terminal: bool) -> bool {
        match self {
            ColorChoice::Always => true,
            ColorChoice::Never => false,
            ColorChoice::Auto => {
                terminal
                    && std::env::var_os("NO_COLOR").is_none_or(|v| v.is_empty())
                    && std::env::var_os("TERM").is_none_or(|t| t != "dumb")
            }
        }
    }
}

/// The outcome of a run, mapped to the process exit code by `main`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    AsExpected,
    Unexpected,
    /// The checker failed on some claim (a panic caught as that claim's internal
    /// error): a defect of the checker, whatever the other verdicts.
    InternalError,
}

impl Status {
    /// The status of a run that decided `rows`.
    fn of(rows: &[Decided<'_>]) -> Status {
        let internal = rows.iter().any(|r| {
            std::iter::once(&r.outcome)
                .chain(&r.correction)
                .any(crate::check::isolate::is_internal_error)
                || std::iter::once(&r.transcription)
                    .chain(&r.correction_transcription)
                    .any(|t| t.is_internal_error())
        });
        if internal {
            Status::InternalError
        } else if rows
            .iter()
            .all(|r| r.as_expected() && !r.fails_undeclared())
        {
            Status::AsExpected
        } else {
            Status::Unexpected
        }
    }
}

/// An error that ends a run with exit code 2.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    #[error("{0}")]
    Input(String),
    /// A defect of the checker, not of the input (exit 3).
    #[error("internal error of the checker: {0}; please report it")]
    Internal(String),
    #[error("error: cannot write the output: {0}")]
    Output(#[from] std::io::Error),
}

impl From<LoadError> for RunError {
    fn from(e: LoadError) -> Self {
        RunError::Input(e.to_string())
    }
}

/// Progress on stderr for long runs, only when stderr is a terminal: claims decided out
/// of all, and what each worker is doing (the claim, samples or search evaluations done
/// out of the total, seconds).
struct Progress {
    started: Instant,
    enabled: bool,
    shown: bool,
}

impl Progress {
    fn new() -> Self {
        Progress {
            started: Instant::now(),
            enabled: std::io::stderr().is_terminal(),
            shown: false,
        }
    }

    /// Progress that is never shown (library callers).
    fn quiet() -> Self {
        Progress {
            enabled: false,
            ..Progress::new()
        }
    }

    fn show(&mut self, done: usize, n: usize, working: &[String]) {
        if self.enabled && self.started.elapsed() > Duration::from_secs(1) {
            let now = if working.is_empty() {
                String::new()
            } else {
                format!(" · {}", report::words::inert(&working.join(" · ")))
            };
            eprint!("\r\x1b[2Kdecided {done}/{n}{now}");
            self.shown = true;
        }
    }

    fn done(&mut self, n: usize) {
        if self.shown {
            eprintln!(
                "\r\x1b[2Kdecided {n} claim{} in {:.1} s",
                if n == 1 { "" } else { "s" },
                self.started.elapsed().as_secs_f64()
            );
        }
    }
}

/// How claims are decided: with their records (for `explain`), under a time limit.
#[derive(Clone, Copy)]
struct Run {
    keep: bool,
    limit: Duration,
    /// When the whole run must end (`--run-limit`): no claim gets time past it.
    deadline: Option<std::time::Instant>,
}

impl Run {
    /// The time a claim starting now gets: its own limit, within the run's.
    fn limit_now(&self) -> Duration {
        self.deadline.map_or(self.limit, |d| {
            self.limit
                .min(d.saturating_duration_since(std::time::Instant::now()))
        })
    }
}

/// The default time limit of a whole run (`--run-limit`).
pub const DEFAULT_RUN_LIMIT: Duration = Duration::from_secs(3_600);

/// Decides every claim of the files (or only `only`), in file and claim order.
pub fn decide_all<'f>(
    files: &'f [DerivationFile],
    only: Option<&str>,
) -> Result<Vec<Decided<'f>>, RunError> {
    let run = Run {
        keep: false,
        limit: watch::DEFAULT_LIMIT,
        deadline: None,
    };
    decide_with_progress(files, only, run, &mut Progress::quiet())
}

/// Decides the claims (all, or the one with id `only`), each under its time limit;
/// with `run.keep`, each outcome records what its decision evaluated (for `explain`).
fn decide_with_progress<'f>(
    files: &'f [DerivationFile],
    only: Option<&str>,
    run: Run,
    progress: &mut Progress,
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
    let mut rows = decide_claims(claims, run, progress)?;
    // With `--only`, a failure is attributed by deciding the claims it uses as well.
    if let (Some(id), Some(r)) = (only, rows.first()) {
        if inherit::failing(r.outcome.verdict()) {
            let ancestors = inherit::ancestors(id, &crate::derivation::uses::by_id(files));
            rows.extend(decide_claims(ancestors, run, progress)?);
        }
    }
    inherit::attribute(&mut rows, run.limit_now()).map_err(|d| RunError::Input(d.to_string()))?;
    rows.retain(|r| only.is_none_or(|id| r.claim.id == id));
    Ok(rows)
}

/// Decides `claims` on this machine's cores, each under its time limit, in their order.
fn decide_claims<'f>(
    claims: Vec<&'f crate::derivation::Claim>,
    run: Run,
    progress: &mut Progress,
) -> Result<Vec<Decided<'f>>, RunError> {
    decide_each(claims, run, progress)
        .into_iter()
        .map(|r| match r {
            Some(r) => r.map_err(|d| RunError::Input(d.to_string())),
            None => Err(RunError::Internal("a worker stopped".into())),
        })
        .collect()
}

/// Decides each claim under its time limit: its decision or its located error, in claim
/// order (`None`: its worker stopped).
fn decide_each<'f>(
    claims: Vec<&'f crate::derivation::Claim>,
    run: Run,
    progress: &mut Progress,
) -> Vec<Option<Result<Decided<'f>, Diagnostic>>> {
    let n = claims.len();
    // Claims are independent: the workers take the next claim as they finish one, and
    // the results are put back in claim order, so the output and the first error
    // reported do not depend on scheduling. Longest first, so that a slow claim does not
    // start last while the other workers idle.
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by_key(|&k| std::cmp::Reverse(expected_cost(claims[k])));
    let watches: Vec<Mutex<Option<Arc<Watch>>>> = (0..crate::parallel::workers(n))
        .map(|_| Mutex::new(None))
        .collect();
    let mut slots: Vec<Option<Result<Decided<'f>, Diagnostic>>> = (0..n).map(|_| None).collect();
    let mut done = 0;
    let decide = |k: usize, worker: usize| {
        let c = claims[k];
        let slot = &watches[worker];
        let w = Watch::new(&c.id, run.limit_now());
        *slot.lock().unwrap_or_else(|e| e.into_inner()) = Some(w.clone());
        let r = watch::under(&w, || {
            if run.keep {
                decide_claim_recorded(c)
            } else {
                decide_claim(c)
            }
        });
        *slot.lock().unwrap_or_else(|e| e.into_inner()) = None;
        r
    };
    // A claim's panic is isolated where it is decided; a worker that stops all the same
    // leaves its claim without a result, which is an error below.
    let _ = crate::parallel::pool(&order, Duration::from_millis(200), decide, |finished| {
        if let Some((k, r)) = finished {
            slots[k] = Some(r);
            done += 1;
        }
        let working: Vec<String> = watches
            .iter()
            .filter_map(|w| {
                w.lock()
                    .unwrap_or_else(|e| e.into_inner())
                    .as_ref()
                    .map(|w| w.status())
            })
            .collect();
        progress.show(done, n, &working);
    });
    slots
}

/// A rough relative cost of deciding a claim and its correction, for scheduling only:
/// sampled strategies by their samples (a `maxn` costs a grid of angles per sample, a
/// gradient a pass per eight variables), exact ones a constant.
fn expected_cost(claim: &crate::derivation::Claim) -> u64 {
    let checks = std::iter::once(&claim.check).chain(claim.correction.iter().map(|c| &c.check));
    checks
        .map(|check| {
            let maximises = check
                .chains
                .iter()
                .flatten()
                .map(|s| s.text.as_str())
                .chain(check.defs.iter().map(|d| d.text.as_str()))
                .any(|t| t.contains("maxn("));
            let samples = |s: &crate::derivation::Sampling| s.samples as u64;
            match &check.strategy {
                Strategy::Numeric { sampling, .. } => {
                    samples(sampling) * if maximises { 400 } else { 4 }
                }
                Strategy::Gradient { sampling, .. } => samples(sampling) * 20,
                Strategy::Convex { sampling, .. } => samples(sampling) * 10,
                Strategy::Scalar { .. } => 200,
                Strategy::Exact { .. }
                | Strategy::Proportional { .. }
                | Strategy::NotCircle { .. } => 50,
            }
        })
        .sum()
}

/// Applies `--seed` and `--samples` to every sampled claim.
fn override_sampling(files: &mut [DerivationFile], seed: Option<u64>, samples: Option<u64>) {
    for claim in files.iter_mut().flat_map(|f| f.claims.iter_mut()) {
        let checks = std::iter::once(&mut claim.check)
            .chain(claim.correction.iter_mut().map(|c| &mut c.check));
        for check in checks {
            let sampling = match &mut check.strategy {
                Strategy::Numeric { sampling, .. }
                | Strategy::Gradient { sampling, .. }
                | Strategy::Convex { sampling, .. } => sampling,
                Strategy::Scalar {
                    samples: n,
                    seed: s,
                    ..
                } => {
                    *s = seed.unwrap_or(*s);
                    *n = samples.map_or(*n, |k| k as usize);
                    continue;
                }
                Strategy::Exact { .. }
                | Strategy::Proportional { .. }
                | Strategy::NotCircle { .. } => continue,
            };
            if let Some(s) = seed {
                sampling.seed = s;
            }
            if let Some(n) = samples {
                sampling.samples = n as usize;
            }
        }
    }
}

/// The derivation files to check: `files`, or those of `dir`, or of ./derivations when
/// there is one (an edited file is checked as edited), else the paper's files embedded
/// in the binary. For one claim (`only`), only the files deciding it reads
/// ([`crate::derivation::only`]).
fn read(dir: Option<PathBuf>, files: &[PathBuf], only: Option<&str>) -> Result<Reading, RunError> {
    use crate::derivation::{load::toml_files, only as one};
    let paths = if files.is_empty() {
        match dir {
            Some(d) => toml_files(&d)?,
            None if Path::new("derivations").is_dir() => toml_files(Path::new("derivations"))?,
            None => {
                return Ok(match only {
                    Some(id) => one::load_texts_for(crate::corpus::FILES, id)?,
                    None => Reading::whole(crate::corpus::load()?),
                })
            }
        }
    } else {
        files.to_vec()
    };
    Ok(match only {
        Some(id) => one::load_files_for(&paths, id)?,
        None => Reading::whole(load_files(&paths)?),
    })
}

/// Renders `rows` in the requested format, credited to the papers of the rows (of
/// the files read, when there are no rows) before the errata filter.
fn render(
    files: &[DerivationFile],
    rows: &[Decided<'_>],
    args: &OutputArgs,
    (errata, explain): (bool, &str),
    terminal: bool,
) -> String {
    let papers: Vec<&str> = files.iter().map(|f| f.paper.as_str()).collect();
    let paper = report::paper_of(&report::refs(rows), &papers);
    let rows: Vec<&Decided<'_>> = rows
        .iter()
        .filter(|r| !errata || report::is_erratum(r))
        .collect();
    let format = args.format.unwrap_or(if terminal && args.out.is_none() {
        Format::Compact
    } else {
        Format::Markdown
    });
    match (format, errata) {
        (Format::Compact, _) => report::compact::render(
            &rows,
            &paper,
            (
                args.color.colours(terminal && args.out.is_none()),
                (terminal && args.out.is_none())
                    .then(terminal_columns)
                    .flatten(),
            ),
            explain,
            errata,
        ),
        (Format::Markdown, false) => report::markdown::render(&rows, &paper),
        (Format::Markdown, true) => report::errata::markdown(&rows, &paper),
        (Format::Latex, false) => report::latex::render(&rows, args.standalone, &paper),
        (Format::Latex, true) => report::latex::errata(&rows, args.standalone, &paper),
        (Format::Json, _) => report::json::render(&rows, &paper),
        (Format::Csv, _) => report::csv::render(&rows),
        (Format::Html, _) => report::html::render(&rows, &paper),
    }
}

/// The width of the terminal standard output is: `COLUMNS` when set, else asked of
/// the terminal.
fn terminal_columns() -> Option<usize> {
    std::env::var("COLUMNS")
        .ok()
        .and_then(|c| c.trim().parse::<usize>().ok())
        .filter(|&c| c > 0)
        .or_else(|| terminal_size::terminal_size().map(|(w, _)| usize::from(w.0)))
}

/// `--out` must not name a file that was read as input.
fn refuse_inputs(path: &Path, inputs: &[&str]) -> Result<(), RunError> {
    let Ok(target) = path.canonicalize() else {
        return Ok(()); // It does not exist yet, so it is no input.
    };
    for input in inputs {
        if Path::new(input).canonicalize().is_ok_and(|p| p == target) {
            return Err(RunError::Input(format!(
                "error: --out {} is an input file; refusing to write the table over it\n  \
                 = help: name another file",
                path.display()
            )));
        }
    }
    Ok(())
}

/// Replaces the regular file `path` (or creates it) with `text` atomically: through a
/// temporary file created exclusively, under an unpredictable name, in the same
/// directory, renamed over it. A symbolic link is followed, so the file it names is
/// replaced and the link stays. Anything else that exists there (a device, a FIFO, a
/// directory) is never replaced: a device or FIFO is written directly, a directory is
/// an error.
fn write_file(path: &Path, text: &str) -> std::io::Result<()> {
    use std::io::ErrorKind;
    let target = match std::fs::metadata(path) {
        Ok(m) if m.is_file() => path.canonicalize()?,
        Ok(m) if m.is_dir() => {
            return Err(std::io::Error::new(
                ErrorKind::IsADirectory,
                "it is a directory",
            ))
        }
        Ok(_) => {
            // A device or FIFO (/dev/null, /dev/stdout, a pipe): write into it.
            let mut f = std::fs::OpenOptions::new().write(true).open(path)?;
            f.write_all(text.as_bytes())?;
            return f.flush();
        }
        Err(e) if e.kind() == ErrorKind::NotFound => path.to_path_buf(),
        Err(e) => return Err(e),
    };
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = target.file_name().unwrap_or_default().to_string_lossy();
    let (tmp, mut file) = (0..16)
        .find_map(|_| {
            let tmp = dir.join(format!(".{name}.{:016x}.tmp", unpredictable()));
            match std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&tmp)
            {
                Ok(f) => Some(Ok((tmp, f))),
                Err(e) if e.kind() == ErrorKind::AlreadyExists => None,
                Err(e) => Some(Err(e)),
            }
        })
        .unwrap_or_else(|| {
            Err(std::io::Error::new(
                ErrorKind::AlreadyExists,
                "no temporary file could be created beside it",
            ))
        })?;
    let written = file
        .write_all(text.as_bytes())
        .and_then(|()| file.sync_all())
        .and_then(|()| {
            if let Ok(m) = std::fs::metadata(&target) {
                std::fs::set_permissions(&tmp, m.permissions())?;
            }
            std::fs::rename(&tmp, &target)
        });
    if written.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    written
}

/// A number nobody can guess before the run (the standard library's randomly seeded
/// hasher over the time and a counter): the temporary file's name.
fn unpredictable() -> u64 {
    use std::hash::{BuildHasher, Hasher};
    static COUNTER: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let mut h = std::collections::hash_map::RandomState::new().build_hasher();
    h.write_u128(
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos()),
    );
    h.write_u64(COUNTER.fetch_add(1, std::sync::atomic::Ordering::Relaxed));
    h.write_u32(std::process::id());
    h.finish()
}

/// Writes `text` to `out_file` (or `out`, also for `-`). A file is never one of the
/// `inputs`, and is replaced atomically ([`write_file`]), so that an interrupted run
/// never leaves half a table.
fn emit(
    text: &str,
    out_file: &Option<PathBuf>,
    inputs: &[&str],
    out: &mut dyn Write,
) -> Result<(), RunError> {
    match out_file {
        Some(path) if path.as_os_str() != "-" => {
            refuse_inputs(path, inputs)?;
            write_file(path, text).map_err(|e| {
                RunError::Input(format!("error: cannot write {}: {e}", path.display()))
            })?
        }
        _ => {
            out.write_all(text.as_bytes())?;
            out.flush()?;
        }
    }
    Ok(())
}

fn table(
    read: Reading,
    args: &OutputArgs,
    (errata, explain): (bool, &str),
    out: &mut Output<'_>,
) -> Result<Status, RunError> {
    let mut files = read.files;
    override_sampling(&mut files, args.seed, args.samples);
    // Where `uses` and the definitions disagree: warnings, which change no verdict.
    for w in crate::derivation::uses::warnings(&files, &read.unread_ids) {
        eprintln!("{}\n", report::words::inert(&w.warning()));
    }
    let mut progress = Progress::new();
    let run = Run {
        keep: false,
        limit: args.time_limit.unwrap_or(watch::DEFAULT_LIMIT),
        deadline: Some(std::time::Instant::now() + args.run_limit.unwrap_or(DEFAULT_RUN_LIMIT)),
    };
    let rows = decide_with_progress(&files, args.only.as_deref(), run, &mut progress)?;
    progress.done(rows.len());
    let inputs: Vec<&str> = files.iter().map(|f| f.path.as_str()).collect();
    emit(
        &render(&files, &rows, args, (errata, explain), out.terminal),
        &args.out,
        &inputs,
        out.stream,
    )?;
    for f in &files {
        if let Some(list) = to_complete(f) {
            eprintln!("{list}");
        }
    }
    Ok(Status::of(&rows))
}

/// The equations a drafted file lists as not read and that are still no claim of it,
/// each with its reason and the edit that would let it be read (the guided loop of
/// `draft`): `None` when there are none.
fn to_complete(file: &crate::derivation::DerivationFile) -> Option<String> {
    let open: Vec<_> = file
        .to_complete
        .iter()
        .filter(|t| file.claims.iter().all(|c| c.id != t.id))
        .collect();
    if open.is_empty() {
        return None;
    }
    // One line each: a line break in a file's text could forge an entry or a summary.
    let line = |s: &str| report::words::inert(&s.replace(['\n', '\r'], " "));
    let mut text = format!(
        "\n{}: {} equation{} to complete (commented in the file):\n",
        line(&file.path),
        open.len(),
        if open.len() == 1 { "" } else { "s" }
    );
    for t in open {
        text.push_str(&format!(
            "- {} (line {} of the paper): {}\n",
            t.id,
            t.line,
            line(&t.reason)
        ));
        if let Some(edit) = &t.edit {
            text.push_str(&format!("  edit: {}\n", line(edit)));
        }
    }
    Some(text)
}

/// The command that explains one claim of this run's files, for the compact table's
/// footer: `explain ID` reads the same files only when told which.
fn explain_hint(dir: Option<&Path>, files: &[PathBuf]) -> String {
    fn quoted(p: &Path) -> String {
        let t = p.display().to_string();
        if !t.is_empty()
            && t.chars()
                .all(|c| c.is_ascii_alphanumeric() || "._/-+=:,@".contains(c))
        {
            t
        } else {
            format!("'{}'", t.replace('\'', "'\\''"))
        }
    }
    let mut hint = "cosserat-check explain ID".to_owned();
    if let Some(d) = dir {
        hint.push_str(&format!(" --dir {}", quoted(d)));
    }
    if !files.is_empty() {
        hint.push_str(" --file");
        for f in files {
            hint.push(' ');
            hint.push_str(&quoted(f));
        }
    }
    hint
}

/// Where a run writes its report.
pub struct Output<'a> {
    pub stream: &'a mut dyn Write,
    /// Whether `stream` is a terminal: the table is then compact and coloured unless
    /// a format is asked for.
    pub terminal: bool,
}

/// Runs the command line, writing the report to `out`.
pub fn run(cli: Cli, out: &mut Output<'_>) -> Result<Status, RunError> {
    match cli.command.unwrap_or(Command::Check(cli.check)) {
        Command::Check(a) => {
            let explain = explain_hint(a.dir.as_deref(), &[]);
            let read = read(a.dir, &[], a.output.only.as_deref())?;
            table(read, &a.output, (false, &explain), out)
        }
        Command::Errata(a) => {
            let explain = explain_hint(a.dir.as_deref(), &[]);
            let read = read(a.dir, &[], a.output.only.as_deref())?;
            table(read, &a.output, (true, &explain), out)
        }
        Command::Verify(a) => {
            let explain = explain_hint(None, &a.files);
            let mut read = read(None, &a.files, a.output.only.as_deref())?;
            if a.strict {
                for claim in read.files.iter_mut().flat_map(|f| f.claims.iter_mut()) {
                    claim.declared = true;
                }
            }
            table(read, &a.output, (false, &explain), out)
        }
        Command::Plot(a) => plot(&a, out),
        Command::Recheck(a) => {
            let path = a.report.display().to_string();
            let text = read_bounded(&a.report, crate::recheck::MAX_REPORT_BYTES)
                .map_err(|e| RunError::Input(format!("error: cannot read {path}: {e}")))?;
            let statements = if a.files.is_empty() {
                None
            } else {
                let files = crate::derivation::load_files(&a.files)?;
                Some(
                    crate::recheck::statements_of(&files)
                        .map_err(|d| RunError::Input(d.to_string()))?,
                )
            };
            let lookup = |id: &str, correction: bool| {
                statements
                    .as_ref()
                    .and_then(|s| s.get(&(id.to_owned(), correction)).cloned())
            };
            let r = crate::recheck::recheck(&text, statements.is_some().then_some(&lookup))
                .map_err(|e| RunError::Input(format!("error: {path}: {e}")))?;
            let mut text = r.lines.join("\n");
            text.push_str(&format!(
                "\n\n{} proved verdict{} checked again by the kernel: {} accepted, {} refused. {} verdict{} of strength sampled, or undecided, {} nothing for the kernel to check: `verify` decides {} again.\n",
                r.accepted + r.refused,
                if r.accepted + r.refused == 1 { "" } else { "s" },
                r.accepted,
                r.refused,
                r.not_proofs,
                if r.not_proofs == 1 { "" } else { "s" },
                if r.not_proofs == 1 { "has" } else { "have" },
                if r.not_proofs == 1 { "it" } else { "them" },
            ));
            if r.summary_refused > 0 {
                text.push_str(
                    "The report's summary does not count its claims' verdicts: refused.\n",
                );
            }
            emit(&text, &None, &[], out.stream)?;
            Ok(if r.refused == 0 && r.summary_refused == 0 {
                Status::AsExpected
            } else {
                Status::Unexpected
            })
        }
        Command::Examples(a) => {
            let written = write_examples(&a.out)?;
            let all = crate::corpus::FILES.len() + crate::corpus::EXAMPLES.len();
            let kept = if written < all {
                format!(" ({} were there already, unchanged)", all - written)
            } else {
                String::new()
            };
            let here = a.out.as_os_str() == "." || a.out.as_os_str().is_empty();
            let go = if here {
                String::new()
            } else {
                format!("cd {} && ", a.out.display())
            };
            let text = format!(
                "wrote {written} of {all} files under {}{kept}; try: {go}cosserat-check\n",
                a.out.display(),
            );
            emit(&report::words::inert(&text), &None, &[], out.stream)?;
            Ok(Status::AsExpected)
        }
        Command::Completions(a) => {
            let mut cmd = <Cli as clap::CommandFactory>::command();
            let mut bytes = Vec::new();
            clap_complete::generate(a.shell, &mut cmd, "cosserat-check", &mut bytes);
            out.stream.write_all(&bytes)?;
            Ok(Status::AsExpected)
        }
        Command::Draft(a) => draft(&a, out),
        Command::Guide => {
            out.stream.write_all(GUIDE.join("\n").as_bytes())?;
            Ok(Status::AsExpected)
        }
        Command::Manpage => {
            let cmd = <Cli as clap::CommandFactory>::command().about(about());
            let mut bytes = Vec::new();
            clap_mangen::Man::new(cmd).render(&mut bytes)?;
            out.stream.write_all(&bytes)?;
            Ok(Status::AsExpected)
        }
        Command::Explain(a) => {
            let files = read(a.dir, &a.files, Some(&a.id))?.files;
            let run = Run {
                keep: true,
                limit: watch::DEFAULT_LIMIT,
                deadline: None,
            };
            let rows = decide_with_progress(&files, Some(&a.id), run, &mut Progress::new())?;
            emit(&report::explain::render(&rows[0]), &None, &[], out.stream)?;
            Ok(Status::of(&rows[..1]))
        }
    }
}

/// Writes the embedded corpus and examples under `dir`; returns how many files were
/// written. A file already there with the same text is left alone; one with other text
/// (or anything that is not a regular file) is an error, found before anything is
/// written.
fn write_examples(dir: &Path) -> Result<usize, RunError> {
    if crate::derivation::load::is_stdin(dir) {
        return Err(RunError::Input(
            "error: examples --out needs a directory; `-` (standard output) cannot hold files\n  \
             = help: name a directory, e.g. --out my-derivations"
                .to_owned(),
        ));
    }
    let all: Vec<(&str, &str)> = crate::corpus::FILES
        .iter()
        .chain(crate::corpus::EXAMPLES)
        .copied()
        .collect();
    let mut todo = Vec::new();
    // The directories under DIR that the files go into are real directories (or are
    // created): a symbolic link there would lead the files out of DIR.
    let mut folders: Vec<PathBuf> = all
        .iter()
        .flat_map(|(name, _)| {
            Path::new(name)
                .ancestors()
                .skip(1)
                .filter(|a| !a.as_os_str().is_empty())
                .map(|a| dir.join(a))
                .collect::<Vec<_>>()
        })
        .collect();
    folders.sort();
    folders.dedup();
    for folder in &folders {
        match std::fs::symlink_metadata(folder) {
            Ok(m) if !m.is_dir() => {
                return Err(RunError::Input(format!(
                    "error: {}: is not a directory (a symbolic link or a file); nothing was written
  = help: write into an empty directory",
                    report::words::inert(&folder.display().to_string())
                )))
            }
            _ => {}
        }
    }
    for (name, text) in &all {
        let path = dir.join(name);
        let shown = report::words::inert(&path.display().to_string());
        let refuse = |why: String| {
            Err(RunError::Input(format!(
                "error: {shown}: {why}; nothing was written\n  = help: write into an empty \
                 directory"
            )))
        };
        match std::fs::symlink_metadata(&path) {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => todo.push((path, *text)),
            Ok(m) if m.is_file() && std::fs::read(&path).is_ok_and(|b| b == text.as_bytes()) => {}
            Ok(m) if m.is_file() => return refuse("exists with other content".into()),
            Ok(_) => return refuse("exists and is not a regular file".into()),
            // A file where a directory of the path should be, or no access.
            Err(e) => return refuse(format!("cannot be written there ({e})")),
        }
    }
    for (path, text) in &todo {
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent)?;
        }
        // Created exclusively: a file that appeared since the check is not replaced.
        std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(path)
            .and_then(|mut f| f.write_all(text.as_bytes()))?;
    }
    Ok(todo.len())
}

/// `draft`: the derivation file on standard output (or `--out`), what it holds on
/// standard error.
fn draft(a: &DraftArgs, out: &mut Output<'_>) -> Result<Status, RunError> {
    let label = if crate::derivation::load::is_stdin(&a.paper) {
        "<stdin>".to_owned()
    } else {
        a.paper.display().to_string()
    };
    let bytes = crate::derivation::load::read_bounded(&a.paper)?;
    if bytes.len() > crate::derivation::draft::MAX_SOURCE_BYTES {
        return Err(RunError::Input(report::words::inert(&format!(
            "error: cannot read {label}: larger than the {} MiB a draft reads (its file must stay within the {} MiB of a derivation file)",
            crate::derivation::draft::MAX_SOURCE_BYTES >> 20,
            crate::derivation::load::MAX_FILE_BYTES >> 20
        ))));
    }
    let source = String::from_utf8(bytes).map_err(|e| {
        let good = &e.as_bytes()[..e.utf8_error().valid_up_to()];
        let line = 1 + good.iter().filter(|&&b| b == b'\n').count();
        let col = 1 + good.iter().rev().take_while(|&&b| b != b'\n').count();
        RunError::Input(report::words::inert(&format!(
            "error: {label}:{line}:{col}: not UTF-8 text"
        )))
    })?;
    if let Some(n) = &a.normal {
        let letter = n.len() == 1 && n.chars().all(|c| c.is_ascii_alphabetic());
        let reserved = crate::derivation::draft::RESERVED.contains(&n.as_str());
        if reserved || (!letter && !crate::lang::latex::GREEK.contains(&n.as_str())) {
            return Err(RunError::Input(format!(
                "error: --normal {}: a letter or a Greek letter's name, such as n, that the language does not reserve",
                report::words::inert(n)
            )));
        }
    }
    let options = crate::derivation::draft::Options {
        dimension: a.dimension.map(usize::from),
        normal: a.normal.clone(),
    };
    let d = draft_decided(&label, &source, &options)?;
    // Standard input may be the file `--out` names (`draft - --out p.tex < p.tex`).
    let inputs = [label.as_str(), "/dev/stdin"];
    let inputs = if crate::derivation::load::is_stdin(&a.paper) {
        &inputs[..]
    } else {
        &inputs[..1]
    };
    emit(&d.toml, &a.out, inputs, out.stream)?;
    let next = match &a.out {
        Some(p) if p.as_os_str() != "-" => format!("cosserat-check verify {}", p.display()),
        _ => "save it, then cosserat-check verify FILE".to_owned(),
    };
    eprintln!(
        "{}",
        report::words::inert(&format!(
            "drafted {} of {} numbered equations as claims ({} to complete, listed at the top of the file); next: {next}",
            d.claims,
            d.equations,
            d.equations - d.claims
        ))
    );
    Ok(Status::AsExpected)
}

/// A draft whose every claim is decided without an input error: a claim whose exact
/// decision asks for sampling (a square root of 2, π, `|…|`, a cosine) is decided with
/// `strategy = "numeric"`; a claim (or the definition it states) that the decision
/// refuses otherwise goes to `to_complete` with the reason, and the draft is written
/// again.
fn draft_decided(
    label: &str,
    source: &str,
    options: &crate::derivation::draft::Options,
) -> Result<crate::derivation::draft::Draft, RunError> {
    use crate::derivation::draft;
    let mut refused: BTreeMap<String, String> = BTreeMap::new();
    let mut numeric: std::collections::BTreeSet<String> = std::collections::BTreeSet::new();
    // Past it, claims are undecided (time limit), never refused: the draft ends.
    let deadline = Instant::now() + DRAFT_RUN_LIMIT;
    loop {
        let drafted = draft::draft(label, source, options, (&refused, &numeric));
        let file = crate::derivation::load_str("draft.toml", &drafted.toml)
            .map_err(|e| RunError::Internal(format!("a draft was refused: {e}")))?;
        let run = Run {
            keep: false,
            limit: DRAFT_CLAIM_LIMIT,
            deadline: Some(deadline),
        };
        let claims: Vec<_> = file.claims.iter().collect();
        let before = (refused.len(), numeric.len());
        for (claim, r) in
            claims
                .iter()
                .zip(decide_each(claims.clone(), run, &mut Progress::quiet()))
        {
            let (id, why) = match r {
                Some(Ok(_)) => continue,
                Some(Err(e))
                    if e.help
                        .as_deref()
                        .is_some_and(|h| h.contains("strategy = \"numeric\""))
                        && numeric.insert(claim.id.clone()) =>
                {
                    continue
                }
                Some(Err(e)) => (
                    draft::owner(&drafted.toml, e.line).unwrap_or_else(|| claim.id.clone()),
                    e.message,
                ),
                None => (claim.id.clone(), "its decision stopped".to_owned()),
            };
            refused.entry(id).or_insert(why);
        }
        if (refused.len(), numeric.len()) == before {
            return Ok(drafted);
        }
    }
}

/// The time limit of each claim while a draft is checked.
const DRAFT_CLAIM_LIMIT: Duration = Duration::from_secs(10);
/// The time limit of checking a draft, all rounds together.
const DRAFT_RUN_LIMIT: Duration = Duration::from_secs(300);

/// A file's text, refused past `limit` bytes before it is read whole.
fn read_bounded(path: &Path, limit: usize) -> std::io::Result<String> {
    use std::io::Read;
    let mut text = String::new();
    std::fs::File::open(path)?
        .take(limit as u64 + 1)
        .read_to_string(&mut text)?;
    if text.len() > limit {
        return Err(std::io::Error::other(format!(
            "larger than {} MiB",
            limit >> 20
        )));
    }
    Ok(text)
}

/// The one-line description of `--help`: what the tool is, and the works whose
/// derivation files are embedded (their `paper = …` lines), which the default run checks.
pub fn about() -> String {
    let mut papers: Vec<&str> = Vec::new();
    for (_, text) in crate::corpus::FILES {
        let paper = text.lines().find_map(|l| {
            let value = l.strip_prefix("paper = \"")?.strip_suffix('"')?;
            Some(value)
        });
        if let Some(p) = paper.filter(|p| !papers.contains(p)) {
            papers.push(p);
        }
    }
    format!(
        "A derivation checker for continuum mechanics: decides each claim of derivation files, equation by equation. Without files it checks {}.",
        if papers.is_empty() { "./derivations".to_owned() } else { papers.join("; ") }
    )
}

/// The figure `plot` draws: the file's table, or one made of the command line's curves.
fn figure_of(a: &PlotArgs) -> Result<crate::derivation::Figure, RunError> {
    let path = a.file.display().to_string();
    if let Some(id) = &a.figure {
        let file = load_files(std::slice::from_ref(&a.file))?.remove(0);
        let ids: Vec<String> = file.figures.iter().map(|f| f.id.clone()).collect();
        return file
            .figures
            .into_iter()
            .find(|f| f.id == *id)
            .ok_or_else(|| {
                RunError::Input(format!(
                    "error: {path} has no figure `{id}` (its figures: {})",
                    if ids.is_empty() {
                        "none".to_owned()
                    } else {
                        ids.join(", ")
                    }
                ))
            });
    }
    let text = std::fs::read_to_string(&a.file)
        .map_err(|e| RunError::Input(format!("error: cannot read {path}: {e}")))?;
    let quoted = |s: &str| toml::Value::String(s.trim().to_owned()).to_string();
    let list = |items: &[String]| {
        let items: Vec<String> = items.iter().map(|s| quoted(s)).collect();
        format!("[{}]", items.join(", "))
    };
    let curves: Vec<String> =
        a.y.iter()
            .flat_map(|y| split_top_level(y))
            .map(|y| {
                format!(
                    "{{ y = {}, label = {} }}",
                    quoted(&y),
                    quoted(&format!("${}$", y.trim()))
                )
            })
            .collect();
    let sets: Vec<String> = a.set.iter().map(|s| s.replacen('=', " = ", 1)).collect();
    let table = format!(
        "\n\n# From the command line of `cosserat-check plot`:\n[[figure]]\nid = \"command-line\"\ntitle = {}\nx = {}\nset = {}\ngiven = {}\ncurves = [{}]\n",
        quoted(&path),
        quoted(a.x.as_deref().unwrap_or_default()),
        list(&sets),
        list(&a.given),
        curves.join(", ")
    );
    let label = format!("{path} with the command line");
    let mut file = crate::derivation::load_str(&label, &format!("{text}{table}"))?;
    Ok(file
        .figures
        .pop()
        .expect("the command line's figure is read"))
}

/// `EXPR,EXPR`: split at the commas outside brackets.
fn split_top_level(s: &str) -> Vec<String> {
    let (mut out, mut depth, mut current) = (Vec::new(), 0i32, String::new());
    for c in s.chars() {
        match c {
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => depth -= 1,
            ',' if depth == 0 => {
                out.push(std::mem::take(&mut current));
                continue;
            }
            _ => {}
        }
        current.push(c);
    }
    out.push(current);
    out.into_iter().filter(|y| !y.trim().is_empty()).collect()
}

fn plot(a: &PlotArgs, out: &mut Output<'_>) -> Result<Status, RunError> {
    let figure = figure_of(a)?;
    let mut columns = Vec::with_capacity(figure.curves.len());
    let limit = a.time_limit.unwrap_or(watch::DEFAULT_LIMIT);
    let w = Watch::new("plot", limit);
    for curve in &figure.curves {
        // Under the time limit: a long evaluation is stopped (`interrupt::tick`).
        let evaluated = watch::under(&w, || {
            crate::kernel::interrupt::stoppable(|| {
                crate::check::probe::curve_values(curve, &figure.x)
            })
        })
        .map_err(|_| {
            RunError::Input(format!(
                "error: the curves were not evaluated within {} s\n  = help: raise it with --time-limit, or plot fewer points",
                limit.as_secs_f64()
            ))
        })?;
        let (values, gap) = evaluated.map_err(|e| RunError::Input(format!("error: {e}")))?;
        if let Some(why) = gap {
            let missing = values.iter().filter(|v| v.is_none()).count();
            eprintln!(
                "note: `{}` is undefined at {missing} of {} points (first: {why}); left out of the curve",
                report::words::inert(&report::plot::plain(&curve.label)),
                values.len()
            );
        }
        columns.push(values);
    }
    let text = match a.format {
        FigureFormat::Csv => report::plot::csv(&figure, &columns),
        FigureFormat::Svg => report::plot::svg(
            &figure,
            &columns,
            if a.linear {
                report::plot::Scale::Linear
            } else {
                report::plot::Scale::Auto
            },
        ),
    };
    let input = a.file.display().to_string();
    emit(&text, &a.out, &[input.as_str()], out.stream)?;
    Ok(Status::AsExpected)
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn cli_definition_is_consistent() {
        Cli::command().debug_assert();
    }

    /// A panic in one claim (provoked by the test-only hook) is that claim's internal
    /// error: the other claims are decided, the report is written, the status is 3.
    #[test]
    fn a_panic_in_one_claim_is_its_internal_error_and_the_run_goes_on() {
        use crate::check::isolate::{PROVOKE_PANIC, PROVOKE_TRANSCRIPTION_PANIC};
        use clap::Parser;
        let dir = std::env::temp_dir().join(format!("cc-panic-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("panics.toml");
        let claim = |id: &str| {
            format!(
                "[[claim]]\nid = \"{id}\"\nprinted = 'x = x'\nexpect = \"holds\"\nsides = [\"x\", \"x\"]\n\n"
            )
        };
        let text = format!(
            "paper = \"t\"\nsection = \"1\"\ntitle = \"t\"\ndimension = 3\nscalars = [\"x\"]\n\n{}{}{}{}",
            claim("before"),
            claim(PROVOKE_PANIC),
            claim(PROVOKE_TRANSCRIPTION_PANIC),
            claim("after")
        );
        std::fs::write(&file, text).unwrap();
        let cli = Cli::try_parse_from([
            "cosserat-check",
            "verify",
            file.to_str().unwrap(),
            "--format",
            "json",
        ])
        .unwrap();
        let mut bytes = Vec::new();
        let status = run(
            cli,
            &mut Output {
                stream: &mut bytes,
                terminal: false,
            },
        )
        .unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(status, Status::InternalError);
        let json: serde_json::Value = serde_json::from_slice(&bytes).unwrap();
        let verdicts: Vec<(&str, &str)> = json["claims"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| (c["id"].as_str().unwrap(), c["verdict"].as_str().unwrap()))
            .collect();
        assert_eq!(
            verdicts,
            [
                ("before", "holds"),
                (PROVOKE_PANIC, "undecided"),
                // A panic in the transcription check leaves the verdict standing.
                (PROVOKE_TRANSCRIPTION_PANIC, "holds"),
                ("after", "holds")
            ]
        );
        let text = String::from_utf8(bytes).unwrap();
        assert!(text.contains("internal error"), "{text}");
        assert!(text.contains("provoked by the test hook"), "{text}");
        assert!(
            text.contains("provoked by the transcription test hook"),
            "{text}"
        );
    }
}
