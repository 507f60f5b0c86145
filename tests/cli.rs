//! The command line end to end: exit codes 0/1/2, formats, `--only`, and located
//! diagnostics for malformed input.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn bin() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_cosserat-check"));
    c.current_dir(env!("CARGO_MANIFEST_DIR"));
    c
}

fn run(args: &[&str]) -> Output {
    bin().args(args).output().expect("the binary runs")
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// A fresh directory holding one derivation file.
fn dir_with(name: &str, contents: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("cosserat-check-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("claims.toml"), contents).unwrap();
    dir
}

const HEADER: &str =
    "section = \"t\"\ntitle = \"test\"\ndimension = 3\nnormal = \"n\"\ntensors = [\"sigma_ij\"]\n";

#[test]
fn no_arguments_checks_the_paper_and_prints_markdown() {
    let out = run(&[]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    assert!(stdout.starts_with("# Derivation table"));
    assert!(stdout.contains("| eq33 | 3.4 |"));
    assert!(stdout.contains("0 unexpected."));
}

#[test]
fn json_format_and_only() {
    let out = run(&["check", "--format", "json", "--only", "eq26"]);
    assert_eq!(out.status.code(), Some(0));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let claims = v["claims"].as_array().unwrap();
    assert_eq!(claims.len(), 1);
    assert_eq!(claims[0]["verdict"], "fails");
    assert_eq!(claims[0]["correction"]["verdict"], "holds");
    assert_eq!(claims[0]["counterexample"]["lhs_value"], "1/5");
}

#[test]
fn unknown_id_is_an_input_error() {
    let out = run(&["check", "--only", "eq999"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("no claim has id `eq999`"));
    assert!(out.stdout.is_empty());
}

#[test]
fn an_unexpected_verdict_exits_1() {
    let dir = dir_with(
        "unexpected",
        &format!("{HEADER}[[claim]]\nid = \"wrong\"\nprinted = 'x'\nexpect = \"holds\"\nsides = [\"avg(n_i n_j)\", \"1/2 delta_ij\"]\n"),
    );
    let out = run(&["check", "--dir", dir.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = text(&out.stdout);
    assert!(stdout.contains("**fails** ✗ (declared: holds)"), "{stdout}");
    assert!(stdout.contains("1 unexpected."));
}

#[test]
fn malformed_input_exits_2_with_a_located_caret() {
    let dir = dir_with(
        "malformed",
        &format!("{HEADER}[[claim]]\nid = \"bad\"\nprinted = 'x'\nexpect = \"holds\"\nsides = [\"sigma_ki n_k n_k\", \"0\"]\n"),
    );
    let out = run(&["check", "--dir", dir.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let stderr = text(&out.stderr);
    let file = Path::new(&dir).join("claims.toml");
    assert!(
        stderr.contains(&format!("{}:10:26", file.display())),
        "{stderr}"
    );
    assert!(
        stderr.contains("index `k` occurs 3 times in one product"),
        "{stderr}"
    );
    assert!(
        stderr.contains(&format!("   | {}^\n", " ".repeat(25))),
        "{stderr}"
    );
}

#[test]
fn missing_directory_and_bad_flags_exit_2() {
    let out = run(&["check", "--dir", "/nonexistent/cosserat"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("cannot read /nonexistent/cosserat"));
    let out = run(&["check", "--format", "pdf"]);
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn help_documents_every_option() {
    let out = run(&["check", "--help"]);
    assert_eq!(out.status.code(), Some(0));
    let help = text(&out.stdout);
    for word in ["--format", "--only", "--dir", "markdown", "json"] {
        assert!(help.contains(word), "--help lacks {word}");
    }
    let top = text(&run(&["--help"]).stdout);
    assert!(top.contains("Exit status"));
}
