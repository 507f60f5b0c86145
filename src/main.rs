//! `cosserat-check`: checks the paper's derivations and prints the derivation table.
//! All logic lives in the library (`cosserat_check::cli`); this sets the allocator and
//! the deep stack the checker runs on, and maps the result (or an escaped resource
//! limit) to an exit code.

use clap::{CommandFactory, FromArgMatches};
use cosserat_check::cli::{about, run, Cli, Output, RunError, Status};
use std::io::IsTerminal;
use std::process::ExitCode;

/// mimalloc instead of the system allocator: the checker allocates many small,
/// short-lived values (monomials, tensors, tape buffers), and glibc's malloc and free
/// took about a fifth of a whole-paper run. The allocator changes no value computed.
/// It is built without transparent huge pages (`no_thp`): zeroing them cost a short
/// run up to 10 ms and doubled the peak memory (21 against 11 MiB for one small file,
/// 51 against 25 MiB for the paper).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> ExitCode {
    // The about text names the works of the embedded corpus, read from its files.
    let matches = Cli::command().about(about()).get_matches();
    let cli = Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit());
    // The run gets the deep stack that chained definitions need (see `parallel::STACK`).
    match std::thread::Builder::new()
        .stack_size(cosserat_check::parallel::STACK)
        .spawn(move || checked(cli))
    {
        // A polynomial operator past its limits unwinds with the limit (`kernel::poly::
        // beyond`); inside a claim's decision it makes the claim undecided, and one that
        // reaches here was outside every decision: a defect of the checker.
        Ok(run) => run.join().unwrap_or_else(|payload| {
            match payload.downcast::<cosserat_check::kernel::PolyError>() {
                Ok(e) => {
                    eprintln!("internal error of the checker: {e}, outside any claim's decision; please report it");
                    ExitCode::from(3)
                }
                Err(payload) => std::panic::resume_unwind(payload),
            }
        }),
        Err(e) => {
            eprintln!("internal error: the checking thread could not start: {e}");
            ExitCode::from(3)
        }
    }
}

fn checked(cli: Cli) -> ExitCode {
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
        Ok(Status::InternalError) => ExitCode::from(3),
        // The reader went away (`… | head`): nothing is wrong with the input or the
        // run, so the run ends quietly, as ripgrep does.
        Err(RunError::Output(e)) if e.kind() == std::io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("{}", cosserat_check::report::words::inert(&e.to_string()));
            match e {
                RunError::Internal(_) => ExitCode::from(3),
                _ => ExitCode::from(2),
            }
        }
    }
}
