//! The bad-input corpus: every file under tests/bad/ is malformed in one way. Each must
//! produce a located diagnostic (file:line:col, the line, a caret), exit code 2, no
//! output and no panic; each message is snapshot-tested so a change in wording shows up
//! as a diff to review.

use clap::Parser;
use cosserat_check::cli::{run, Cli, Output, RunError};
use std::path::Path;

fn bad_files() -> Vec<String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .expect("tests/bad exists")
        .filter_map(Result::ok)
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    names.sort();
    names
}

#[test]
fn every_bad_file_gets_a_located_message_and_no_output() {
    let names = bad_files();
    assert!(names.len() >= 30, "only {} bad files", names.len());
    for name in names {
        let path = format!("tests/bad/{name}");
        let cli = Cli::try_parse_from(["cosserat-check", "verify", &path]).unwrap();
        let mut out = Vec::new();
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            run(
                cli,
                &mut Output {
                    stream: &mut out,
                    terminal: false,
                },
            )
        }));
        let message = match result {
            Err(_) => panic!("{name}: the checker panicked"),
            Ok(Ok(status)) => panic!("{name}: accepted ({status:?}) instead of refused"),
            Ok(Err(RunError::Output(e))) => panic!("{name}: output error {e}"),
            Ok(Err(RunError::Internal(e))) => panic!("{name}: internal error {e}"),
            Ok(Err(RunError::Input(m))) => m,
        };
        assert!(out.is_empty(), "{name}: wrote output despite the error");
        assert!(message.starts_with("error: "), "{name}: {message}");
        assert!(
            message.contains(&format!("--> {path}:")),
            "{name}: no file:line:col in\n{message}"
        );
        assert!(
            message
                .lines()
                .any(|l| l.trim_start().starts_with('|') && l.contains('^')),
            "{name}: no caret in\n{message}"
        );
        let stem = name.trim_end_matches(".toml");
        insta::with_settings!({
            snapshot_path => concat!(env!("CARGO_MANIFEST_DIR"), "/snapshots"),
            prepend_module_to_snapshot => false,
        }, {
            insta::assert_snapshot!(format!("bad_input__{stem}"), message);
        });
    }
}

#[test]
fn the_binary_exits_2_on_bad_input() {
    for name in ["03-index-three-times", "13-not-text", "33-empty-file"] {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_cosserat-check"))
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .args(["verify", &format!("tests/bad/{name}.toml")])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{name}");
        assert!(out.stdout.is_empty(), "{name}");
    }
}
