//! The terminal view (issue 17, item 3): a compact table with one short line of
//! evidence per claim and failures highlighted when standard output is a terminal;
//! piped output stays the Markdown table, byte for byte.

use cosserat_check::report::compact::EVIDENCE_WIDTH;

fn output(args: &[&str], terminal: bool) -> String {
    crate::common::run_cli(args, terminal).1
}

const FILE: &str = "tests/user/irrelevant-symbols.toml";

#[test]
fn a_terminal_gets_one_short_line_per_claim_with_failures_highlighted() {
    let text = output(&["verify", FILE], true);
    let rows: Vec<&str> = text.lines().filter(|l| l.contains("-slip")).collect();
    assert_eq!(rows.len(), 4, "{text}");
    for row in &rows {
        assert!(row.contains("\x1b[1;31mFAILS\x1b[0m"), "{row}");
        let evidence = row.rsplit("  ").next().unwrap();
        assert!(evidence.chars().count() <= EVIDENCE_WIDTH, "{row}");
    }
    assert!(text.contains("claim") && text.contains("strength") && text.contains("method"));
    assert!(text.contains("4 claims: 0 hold, 4 fail"));
    assert!(text.contains("explain ID"));
}

#[test]
fn long_evidence_is_shortened_and_the_full_evidence_stays_in_markdown() {
    let compact = output(&["check", "--only", "eq23"], true);
    let markdown = output(&["check", "--only", "eq23", "--format", "markdown"], true);
    let row = compact.lines().find(|l| l.starts_with("eq23")).unwrap();
    assert!(row.len() < 200, "{row}");
    assert!(markdown.len() > 2 * compact.len());
    assert!(markdown.contains("| eq23 |"));
}

#[test]
fn piped_output_is_the_markdown_table_byte_for_byte() {
    let piped = output(&["verify", FILE], false);
    let markdown = output(&["verify", FILE, "--format", "markdown"], true);
    assert_eq!(piped, markdown);
    assert!(piped.starts_with("# Derivation table"));
    assert!(!piped.contains('\x1b'));
}

#[test]
fn compact_on_request_has_no_colour_when_piped() {
    let text = output(&["verify", FILE, "--format", "compact"], false);
    assert!(!text.contains('\x1b'), "{text}");
    assert_eq!(text.matches("FAILS").count(), 4, "{text}");
}

#[test]
fn out_writes_markdown_even_from_a_terminal() {
    let dir = std::env::temp_dir().join(format!("cosserat-compact-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("table.md");
    let printed = output(&["verify", FILE, "--out", file.to_str().unwrap()], true);
    assert!(printed.is_empty());
    let written = std::fs::read_to_string(&file).unwrap();
    assert!(written.starts_with("# Derivation table"), "{written}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn compact_errata_put_each_inherited_failure_beneath_its_root_error() {
    let text = output(
        &["errata", "--format", "compact", "--color", "never"],
        false,
    );
    let ids: Vec<&str> = text
        .lines()
        .skip_while(|l| !l.starts_with("claim "))
        .skip(1)
        .take_while(|l| !l.is_empty())
        .map(|l| l.split("  3.").next().unwrap().trim_end())
        .collect();
    let at = |id: &str| {
        ids.iter()
            .position(|l| *l == id)
            .unwrap_or_else(|| panic!("{id}: {ids:?}"))
    };
    // eq23 and eq24 inherit their failure from eq21's transport law.
    assert_eq!(at("  ↳ eq23"), at("eq21") + 1, "{text}");
    assert_eq!(at("  ↳ eq24"), at("eq21") + 2, "{text}");
    assert_eq!(ids.iter().filter(|l| l.contains('↳')).count(), 2, "{text}");
}
