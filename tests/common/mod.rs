//! Helpers shared by the test files that decide a soundness corpus.

use cosserat_check::check::Decided;
use cosserat_check::cli::decide_all;
use cosserat_check::derivation::load_files;

/// Decides every claim of `path`, asserts that there are `count` and that each verdict
/// (and each correction's) is the declared one, and hands the rows to `inspect`.
pub fn assert_as_declared(path: &str, count: usize, inspect: impl FnOnce(&[Decided<'_>])) {
    let files = load_files(&[path]).unwrap();
    let rows = decide_all(&files, None).unwrap();
    assert_eq!(rows.len(), count, "{path}");
    for r in &rows {
        assert!(
            r.as_expected(),
            "{}: {} (declared {}): {}",
            r.claim.id,
            r.outcome.verdict_text(),
            r.claim.expect,
            cosserat_check::report::evidence(&r.outcome)
        );
    }
    inspect(&rows);
}

/// Asserts that `count` rows fail and that each failure's counterexample was confirmed
/// by the second evaluation `how`.
pub fn assert_failures_confirmed(
    rows: &[Decided<'_>],
    count: usize,
    how: cosserat_check::decide::Reverified,
) {
    use cosserat_check::derivation::Verdict;
    let failed: Vec<_> = rows
        .iter()
        .filter(|r| r.outcome.verdict() == Verdict::Fails)
        .collect();
    assert_eq!(failed.len(), count);
    for r in failed {
        let cx = r.outcome.counterexample.as_ref().expect("a counterexample");
        assert_eq!(cx.reverified, Some(how), "{}", r.claim.id);
    }
}

/// The located error a file gets: from loading, or else from deciding it.
pub fn error_of(text: &str) -> String {
    match cosserat_check::derivation::load_str("f.toml", text) {
        Err(e) => e.to_string(),
        Ok(f) => decide_all(std::slice::from_ref(&f), None)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_else(|| panic!("accepted: {text}")),
    }
}

/// A file with `header` (its declarations) and one claim `c`, declared to hold, whose
/// other fields are `rest`.
pub fn one_claim(header: &str, rest: &str) -> String {
    format!("section = \"t\"\ntitle = \"t\"\n{header}\n[[claim]]\nid = \"c\"\nprinted = 'x'\nexpect = \"holds\"\n{rest}\n")
}

/// Each file is refused with an error located in it (`f.toml:`) whose message says
/// what its case expects.
pub fn assert_located_errors<T: AsRef<str>>(cases: &[(T, &str)]) {
    for (text, want) in cases {
        let e = error_of(text.as_ref());
        assert!(e.contains(want), "{}\n→ {e}", text.as_ref());
        assert!(e.contains("f.toml:"), "located: {e}");
    }
}

/// The evidence written for claim `id` among `rows`.
pub fn evidence_of(rows: &[Decided<'_>], id: &str) -> String {
    let r = rows.iter().find(|r| r.claim.id == id).expect(id);
    cosserat_check::report::evidence(&r.outcome)
}

/// A test's external tool is missing: it says it is skipped, or fails where the tools
/// are required (`COSSERAT_REQUIRE_TOOLS` set, as `.ci/run` does after installing them).
pub fn tool_missing(what: &str) {
    assert!(
        std::env::var_os("COSSERAT_REQUIRE_TOOLS").is_none(),
        "{what} is missing, and COSSERAT_REQUIRE_TOOLS requires it"
    );
    eprintln!("skipped: {what} is missing");
}

/// The outcome of every claim of the file `text` (named f.toml in diagnostics).
pub fn outcomes_of(text: &str) -> Vec<cosserat_check::decide::Outcome> {
    let f = cosserat_check::derivation::load_str("f.toml", text).expect("loads");
    decide_all(std::slice::from_ref(&f), None)
        .unwrap()
        .into_iter()
        .map(|r| r.outcome)
        .collect()
}

/// Runs the command line `args` (without the program's name) in process, as if
/// standard output were a terminal or not: its status and what it wrote.
pub fn run_cli(args: &[&str], terminal: bool) -> (cosserat_check::cli::Status, String) {
    let (status, out) = try_cli(args, terminal);
    (status.unwrap_or_else(|e| panic!("{e}")), out)
}

/// The error the command line `args` ends with (as its message on standard error).
pub fn cli_error(args: &[&str]) -> cosserat_check::cli::RunError {
    match try_cli(args, false).0 {
        Err(e) => e,
        Ok(s) => panic!("{args:?} succeeded: {s:?}"),
    }
}

fn try_cli(
    args: &[&str],
    terminal: bool,
) -> (
    Result<cosserat_check::cli::Status, cosserat_check::cli::RunError>,
    String,
) {
    use clap::Parser;
    use cosserat_check::cli::{run, Cli, Output};
    let cli =
        Cli::try_parse_from(std::iter::once("cosserat-check").chain(args.iter().copied())).unwrap();
    let mut out = Vec::new();
    let status = run(
        cli,
        &mut Output {
            stream: &mut out,
            terminal,
        },
    );
    (status, String::from_utf8(out).unwrap())
}
