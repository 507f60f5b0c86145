//! The README and the guide (`docs/src`, an mdBook) match the program: every example command in their `sh`
//! blocks runs with the exit status its comment gives, the derivation-file example
//! verifies, and every field of the JSON contract is in the JSON output.

use std::path::{Path, PathBuf};
use std::process::Command;

const README: &str = concat!(
    include_str!("../README.md"),
    "\n",
    include_str!("../docs/src/introduction.md"),
    "\n",
    include_str!("../docs/src/tutorial.md"),
    "\n",
    include_str!("../docs/src/table.md"),
    "\n",
    include_str!("../docs/src/commands.md"),
    "\n",
    include_str!("../docs/src/files.md"),
    "\n",
    include_str!("../docs/src/fields.md"),
    "\n",
    include_str!("../docs/src/assumptions.md"),
    "\n",
    include_str!("../docs/src/strategies.md"),
    "\n",
    include_str!("../docs/src/reading.md"),
    "\n",
    include_str!("../docs/src/cli.md"),
    "\n",
    include_str!("../docs/src/file-reference.md"),
    "\n",
    include_str!("../docs/src/grammar.md"),
    "\n",
    include_str!("../docs/src/json.md"),
    "\n",
    include_str!("../docs/src/limits.md"),
    "\n",
    include_str!("../docs/src/trust.md"),
    "\n",
    include_str!("../docs/src/case-study.md")
);

/// The contents of every fenced block of `lang`.
fn blocks(lang: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut current: Option<String> = None;
    for line in README.lines() {
        match (&mut current, line.trim_start().strip_prefix("```")) {
            (None, Some(tag)) if tag.trim() == lang => current = Some(String::new()),
            (Some(_), Some("")) => out.extend(current.take()),
            (Some(text), _) => {
                text.push_str(line);
                text.push('\n');
            }
            (None, _) => {}
        }
    }
    out
}

/// A scratch directory where `derivations` is the crate's own, so that commands read
/// the paper and anything they write stays out of the source tree.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("cosserat-readme-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let here = Path::new(env!("CARGO_MANIFEST_DIR")).join("derivations");
    std::os::unix::fs::symlink(here, dir.join("derivations")).unwrap();
    dir
}

#[test]
fn every_example_command_runs_with_the_exit_status_it_states() {
    let commands: Vec<String> = blocks("sh")
        .iter()
        .flat_map(|b| b.lines().map(str::to_owned).collect::<Vec<_>>())
        .filter(|l| l.starts_with("cosserat-check"))
        .collect();
    assert!(commands.len() >= 8, "only {} examples", commands.len());
    let dir = scratch("examples");
    for line in &commands {
        let (command, comment) = line.split_once('#').unwrap_or((line, ""));
        let expected = comment
            .split("exit ")
            .nth(1)
            .and_then(|s| s.trim().split(|c: char| !c.is_ascii_digit()).next())
            .and_then(|s| s.parse::<i32>().ok())
            .unwrap_or(0);
        let args: Vec<&str> = command.split_whitespace().skip(1).collect();
        let out = Command::new(env!("CARGO_BIN_EXE_cosserat-check"))
            .args(&args)
            .current_dir(&dir)
            .output()
            .expect("the binary runs");
        assert_eq!(
            out.status.code(),
            Some(expected),
            "`{line}`: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let wrote_a_file = args.contains(&"--out");
        assert_eq!(out.stdout.is_empty(), wrote_a_file, "`{line}`");
        if let Some(k) = args.iter().position(|a| *a == "--out") {
            let written = std::fs::read(dir.join(args[k + 1])).unwrap();
            assert!(!written.is_empty(), "`{line}` wrote nothing");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_derivation_file_example_verifies() {
    let examples = blocks("toml");
    assert!(!examples.is_empty());
    let dir = scratch("toml");
    for (k, toml) in examples.iter().enumerate() {
        let file = dir.join(format!("example-{k}.toml"));
        std::fs::write(&file, toml).unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_cosserat-check"))
            .args(["verify", file.to_str().unwrap()])
            .output()
            .unwrap();
        assert_eq!(
            out.status.code(),
            Some(0),
            "README toml block {k}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn every_field_of_the_json_contract_is_in_the_output() {
    let contract = &blocks("json")[0];
    let contract: serde_json::Value = serde_json::from_str(contract).expect("the contract parses");
    let out = Command::new(env!("CARGO_BIN_EXE_cosserat-check"))
        .args(["--format", "json"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    let actual: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in contract.as_object().unwrap().keys() {
        assert!(actual.get(key).is_some(), "top-level `{key}` missing");
    }
    let claim = contract["claims"][0].as_object().unwrap();
    for row in actual["claims"].as_array().unwrap() {
        for key in claim.keys() {
            assert!(row.get(key).is_some(), "{}: `{key}` missing", row["id"]);
        }
    }
    for key in contract["summary"].as_object().unwrap().keys() {
        assert!(
            actual["summary"].get(key).is_some(),
            "summary `{key}` missing"
        );
    }
}

/// The guide is an mdBook: its summary lists every chapter in `docs/src` once, in the
/// order `cosserat-check guide` prints them, and the examples above are read from the
/// same chapters.
#[test]
fn the_book_summary_lists_the_chapters_the_guide_prints() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/src");
    let summary = std::fs::read_to_string(src.join("SUMMARY.md")).unwrap();
    let linked: Vec<String> = summary
        .lines()
        .filter_map(|l| l.split_once("](").map(|(_, rest)| rest))
        .filter_map(|rest| rest.split_once(')').map(|(file, _)| file.to_owned()))
        .collect();
    let mut files: Vec<String> = std::fs::read_dir(&src)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".md") && n != "SUMMARY.md")
        .collect();
    files.sort();
    let mut sorted = linked.clone();
    sorted.sort();
    assert_eq!(sorted, files, "every chapter once in SUMMARY.md");
    let printed: Vec<String> = linked
        .iter()
        .map(|f| std::fs::read_to_string(src.join(f)).unwrap())
        .collect();
    assert_eq!(
        printed,
        cosserat_check::cli::GUIDE,
        "the guide prints the chapters in order"
    );
    for chapter in &printed {
        assert!(
            README.contains(chapter.as_str()),
            "the examples read every chapter"
        );
    }
}

/// The command-line reference (`docs/src/cli.md`) as the argument parser defines it:
/// every command, its usage, and every argument with its help, possible values and
/// default. The test below keeps the chapter current (`UPDATE_DOCS=1` rewrites it).
fn cli_reference() -> String {
    use clap::CommandFactory;
    use std::fmt::Write as _;
    let mut root = cosserat_check::cli::Cli::command();
    root.build();
    let mut out = String::from(
        "# Command-line reference\n\nEvery command and option, as the program's argument parser defines them (`cosserat-check --help` and `cosserat-check COMMAND --help` print the same text; `cosserat-check manpage` prints it as a manual page). A test regenerates this chapter from the parser and fails when it is out of date.\n",
    );
    let mut commands = vec![root.clone()];
    commands.extend(
        root.get_subcommands()
            .filter(|c| c.get_name() != "help")
            .cloned(),
    );
    for mut c in commands {
        let name = c
            .get_bin_name()
            .map(str::to_owned)
            .unwrap_or_else(|| c.get_name().to_owned());
        let _ = write!(out, "\n## `{name}`\n\n");
        if let Some(about) = c.get_long_about().or(c.get_about()) {
            let _ = writeln!(out, "{about}\n");
        }
        let usage = c.render_usage().to_string();
        let _ = writeln!(out, "```text\n{}\n```\n", usage.trim_end());
        let args: Vec<&clap::Arg> = c
            .get_arguments()
            .filter(|a| !a.is_hide_set() && !["help", "version"].contains(&a.get_id().as_str()))
            .collect();
        for a in args {
            let values = a
                .get_value_names()
                .map(|v| {
                    v.iter()
                        .map(|n| format!("<{n}>"))
                        .collect::<Vec<_>>()
                        .join(" ")
                })
                .unwrap_or_default();
            let takes = a.get_num_args().is_some_and(|n| n.takes_values());
            let form = match (a.get_long(), a.get_short()) {
                (Some(l), Some(s)) => format!("-{s}, --{l}"),
                (Some(l), None) => format!("--{l}"),
                (None, Some(s)) => format!("-{s}"),
                (None, None) => String::new(),
            };
            let form = match (form.is_empty(), takes) {
                (true, _) => values,
                (false, true) => format!("{form} {values}"),
                (false, false) => form,
            };
            let help = a
                .get_long_help()
                .or(a.get_help())
                .map(|h| h.to_string())
                .unwrap_or_default();
            let mut help = help.trim().replace('\n', " ");
            if !help.ends_with('.') {
                help.push('.');
            }
            let _ = write!(out, "- `{form}`: {help}");
            let possible = a.get_possible_values();
            if takes
                && !possible.is_empty()
                && !possible
                    .iter()
                    .all(|p| ["true", "false"].contains(&p.get_name()))
            {
                let list: Vec<String> = possible
                    .iter()
                    .filter(|p| !p.is_hide_set())
                    .map(|p| match p.get_help() {
                        Some(h) => format!("`{}` ({h})", p.get_name()),
                        None => format!("`{}`", p.get_name()),
                    })
                    .collect();
                let _ = write!(out, " Values: {}.", list.join("; "));
            }
            let defaults: Vec<String> = a
                .get_default_values()
                .iter()
                .map(|d| d.to_string_lossy().into_owned())
                .collect();
            if takes && !defaults.is_empty() {
                let _ = write!(out, " Default: `{}`.", defaults.join(" "));
            }
            out.push('\n');
        }
        if let Some(after) = c.get_after_long_help().or(c.get_after_help()) {
            let _ = write!(out, "\n{}\n", after.to_string().trim());
        }
    }
    out
}

#[test]
fn the_cli_reference_is_generated_from_the_argument_parser() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/src/cli.md");
    let want = cli_reference();
    if std::env::var_os("UPDATE_DOCS").is_some() {
        std::fs::write(&path, &want).unwrap();
    }
    let have = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        have == want,
        "docs/src/cli.md is out of date: run `UPDATE_DOCS=1 cargo test --release the_cli_reference` and review the change"
    );
}
