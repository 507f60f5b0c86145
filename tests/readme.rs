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
    include_str!("../docs/src/table.md"),
    "\n",
    include_str!("../docs/src/commands.md"),
    "\n",
    include_str!("../docs/src/files.md"),
    "\n",
    include_str!("../docs/src/reading.md"),
    "\n",
    include_str!("../docs/src/trust.md")
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
