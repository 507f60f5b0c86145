//! The derivation graph: `uses` checked across files, the edges the definitions imply,
//! and root errors told from inherited failures by re-deciding a failing claim with the
//! failing claims it uses replaced by their corrections.

use cosserat_check::check::{Attribution, Decided};
use cosserat_check::cli::decide_all;
use cosserat_check::derivation::{load_dir, load_files, uses, DerivationFile};
use cosserat_check::report;
use std::path::Path;

fn attribution<'a>(rows: &'a [Decided<'_>], id: &str) -> &'a Attribution {
    rows.iter()
        .find(|r| r.claim.id == id)
        .and_then(|r| r.attribution.as_ref())
        .unwrap_or_else(|| panic!("{id} has no attribution"))
}

#[test]
fn a_failure_that_holds_once_the_lemma_is_corrected_is_inherited_and_an_own_error_is_root() {
    let files = load_files(&["tests/graph/inherited.toml"]).unwrap();
    let rows = decide_all(&files, None).unwrap();
    assert!(rows.iter().all(Decided::as_expected));
    assert!(attribution(&rows, "lemma").is_root());
    for id in ["step", "next"] {
        match attribution(&rows, id) {
            Attribution::Inherited { from, outcome } => {
                assert_eq!(from, &["lemma".to_owned()], "{id}");
                assert_eq!(outcome.verdict().as_str(), "holds", "{id}");
            }
            other => panic!("{id}: {other:?}"),
        }
    }
    // Its own sign is wrong: still failing with the lemma corrected.
    match attribution(&rows, "own-error") {
        Attribution::Root {
            corrected,
            outcome: Some(o),
        } => {
            assert_eq!(corrected, &["lemma".to_owned()]);
            assert_eq!(o.verdict().as_str(), "fails");
        }
        other => panic!("own-error: {other:?}"),
    }
    // It lists the lemma, but nothing the lemma states enters its check.
    assert!(matches!(
        attribution(&rows, "unrelated"),
        Attribution::Root {
            corrected,
            outcome: None
        } if corrected.is_empty()
    ));
    // The errata: each root error, with what inherits from it beneath it.
    let refs: Vec<&Decided<'_>> = rows.iter().collect();
    let order: Vec<(String, Vec<String>)> = report::graph::grouped(&refs)
        .into_iter()
        .map(|(r, under)| {
            (
                r.claim.id.clone(),
                under.iter().map(|u| u.claim.id.clone()).collect(),
            )
        })
        .collect();
    assert_eq!(
        order,
        [
            (
                "lemma".to_owned(),
                vec!["step".to_owned(), "next".to_owned()]
            ),
            ("own-error".to_owned(), vec![]),
            ("unrelated".to_owned(), vec![]),
        ]
    );
    let errata = report::errata::markdown(&refs, "p");
    assert!(
        errata
            .contains("Origin of the 5 failing or conditional claims: 3 root errors, 2 inherited"),
        "{errata}"
    );
    assert!(
        errata.contains("### step (Section 1) — inherited from lemma"),
        "{errata}"
    );
}

#[test]
fn without_the_corrected_form_the_origin_is_undetermined_not_root() {
    // The same file with the lemma's corrected form removed: step reads what the lemma
    // states, and nothing can replace it.
    let text = std::fs::read_to_string("tests/graph/inherited.toml")
        .unwrap()
        .replace(", corrected = \"s_i = 2 a_i\"", "");
    let files = cosserat_check::derivation::load_texts(&[("inherited.toml", &text)]).unwrap();
    let rows = decide_all(&files, None).unwrap();
    match attribution(&rows, "step") {
        Attribution::Undetermined { uncorrectable, .. } => {
            assert_eq!(uncorrectable, &["lemma".to_owned()])
        }
        other => panic!("{other:?}"),
    }
    let words = report::graph::attribution(attribution(&rows, "step"));
    assert!(words.contains("cannot tell"), "{words}");
}

#[test]
fn only_one_claim_still_decides_what_it_uses() {
    let files = load_files(&["tests/graph/inherited.toml"]).unwrap();
    let rows = decide_all(&files, Some("next")).unwrap();
    assert_eq!(rows.len(), 1);
    assert_eq!(attribution(&rows, "next").inherited_from(), ["lemma"]);
}

#[test]
fn a_missing_and_a_stale_edge_are_warned_about() {
    let files = load_files(&["tests/graph/warnings.toml"]).unwrap();
    let warnings: Vec<String> = uses::warnings(&files, &Default::default())
        .iter()
        .map(|d| d.warning())
        .collect();
    assert_eq!(warnings.len(), 2, "{warnings:#?}");
    assert!(warnings[0].starts_with(
        "warning: `reads-s-lists-u` reads `s`, which transcribes lemma-s, but its `uses` does not list lemma-s"
    ));
    assert!(
        warnings[0].contains("--> tests/graph/warnings.toml:25:7"),
        "{}",
        warnings[0]
    );
    assert!(warnings[1].starts_with(
        "warning: `reads-s-lists-u` uses lemma-u, but reads none of the definitions that transcribe it (u)"
    ));
}

fn paper() -> Vec<DerivationFile> {
    load_dir(&Path::new(env!("CARGO_MANIFEST_DIR")).join("derivations")).unwrap()
}

#[test]
fn the_papers_uses_agree_with_its_definitions() {
    let files = paper();
    let warnings: Vec<String> = uses::warnings(&files, &Default::default())
        .iter()
        .map(|d| d.warning())
        .collect();
    assert!(warnings.is_empty(), "{}", warnings.join("\n\n"));
    // Every claim but the first steps of a section rests on something.
    let listed = files
        .iter()
        .flat_map(|f| &f.claims)
        .filter(|c| !c.uses.is_empty())
        .count();
    assert!(listed >= 55, "only {listed} claims list what they use");
}

#[test]
fn the_paper_has_two_failures_inherited_from_eq21() {
    let files = paper();
    let rows = decide_all(&files, None).unwrap();
    let refs: Vec<&Decided<'_>> = rows.iter().collect();
    let s = report::Summary::of(&refs);
    assert_eq!(
        (s.root_errors, s.inherited, s.undetermined_origin),
        (12, 2, 1)
    );
    for id in ["eq23", "eq24"] {
        assert_eq!(attribution(&rows, id).inherited_from(), ["eq21"], "{id}");
    }
    // (54) does not follow even with the moment balance (60) corrected.
    match attribution(&rows, "eq54") {
        Attribution::Root {
            corrected,
            outcome: Some(o),
        } => {
            assert_eq!(corrected, &["eq60".to_owned()]);
            assert_eq!(o.verdict().as_str(), "fails");
        }
        other => panic!("eq54: {other:?}"),
    }
    // "The thickness decreases" is about (54), which has no correction to replace it.
    assert!(matches!(
        attribution(&rows, "sec6-thickness-decreases"),
        Attribution::Undetermined { .. }
    ));
    let json: serde_json::Value = serde_json::from_str(&report::json::render(&refs, "p")).unwrap();
    let eq23 = json["claims"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["id"] == "eq23")
        .unwrap();
    assert_eq!(eq23["root"], false);
    assert_eq!(eq23["inherited_from"], serde_json::json!(["eq21"]));
    assert_eq!(eq23["uses"], serde_json::json!(["eq17", "eq20", "eq21"]));
}

#[test]
fn an_id_no_file_read_has_is_warned_about_and_its_edge_not_followed() {
    let files = load_files(&["tests/graph/unknown.toml"]).unwrap();
    let warnings: Vec<String> = uses::warnings(&files, &Default::default())
        .iter()
        .map(|d| d.warning())
        .collect();
    assert_eq!(warnings.len(), 1, "{warnings:#?}");
    assert!(
        warnings[0].starts_with("warning: `lemma-2` is no claim of the files read"),
        "{}",
        warnings[0]
    );
    assert!(
        warnings[0].contains("--> tests/graph/unknown.toml:15:19"),
        "{}",
        warnings[0]
    );
}
