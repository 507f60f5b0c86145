//! `recheck`: every proof of the paper's JSON report is checked again by the kernel
//! from the statement the report records, and a report whose proof, statement,
//! conclusion or verdict was edited is refused.

use clap::Parser;
use cosserat_check::cli::{run, Cli, Output, Status};
use cosserat_check::recheck::recheck;
use serde_json::Value;

fn paper_report() -> Value {
    let cli = Cli::try_parse_from(["cosserat-check", "check", "--format", "json"]).unwrap();
    let mut bytes = Vec::new();
    let status = run(
        cli,
        &mut Output {
            stream: &mut bytes,
            terminal: false,
        },
    )
    .unwrap();
    assert_eq!(status, Status::AsExpected);
    serde_json::from_slice(&bytes).unwrap()
}

/// The number of accepted and refused proofs of a (possibly edited) report.
fn rechecked(report: &Value) -> (usize, usize) {
    let r = recheck(&report.to_string()).unwrap();
    (r.accepted, r.refused)
}

/// The first claim row (or correction) whose first proof's fact has this kind.
fn with_fact<'a>(report: &'a mut Value, kind: &str) -> &'a mut Value {
    let is = |row: &Value| row["proofs"][0]["fact"]["kind"] == kind;
    let claims = report["claims"].as_array().unwrap();
    let found = (0..claims.len()).find_map(|k| {
        if is(&claims[k]) {
            Some((k, false))
        } else if is(&claims[k]["correction"]) {
            Some((k, true))
        } else {
            None
        }
    });
    match found {
        Some((k, false)) => &mut report["claims"][k],
        Some((k, true)) => &mut report["claims"][k]["correction"],
        None => panic!("no proof of kind {kind}"),
    }
}

#[test]
fn every_proof_of_the_paper_is_accepted_again() {
    let report = paper_report();
    let proved = report["claims"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|c| std::iter::once(c).chain(c.get("correction").filter(|x| !x.is_null())))
        .filter(|row| row["strength"] == "proof")
        .count();
    assert!(proved >= 60, "{proved}");
    assert_eq!(rechecked(&report), (proved, 0));
}

#[test]
fn an_edited_proof_statement_conclusion_or_verdict_is_refused() {
    let base = paper_report();
    let (accepted, _) = rechecked(&base);
    let refused = |edit: &dyn Fn(&mut Value)| {
        let mut r = base.clone();
        edit(&mut r);
        let (a, refused) = rechecked(&r);
        assert_eq!((a, refused), (accepted - 1, 1));
    };
    // A refutation's point moved.
    refused(&|r| {
        let row = with_fact(r, "refutation");
        let point = row["proofs"][0]["fact"]["at"]["point"]
            .as_array_mut()
            .unwrap();
        let x = point
            .iter_mut()
            .find(|p| p[1] != "0")
            .expect("a nonzero coordinate");
        x[1] = Value::from("12345/7");
    });
    // A proportionality's factor changed.
    refused(&|r| {
        let row = with_fact(r, "proportional");
        row["proofs"][0]["fact"]["factors"][0] = Value::from("-3");
    });
    // A side of an identity replaced by another term.
    refused(&|r| {
        let row = with_fact(r, "identity");
        row["proofs"][0]["statement"]["claim"]["equal"]["chains"][0][0] =
            serde_json::json!({"const": {"value": "7", "free": []}});
    });
    // The conclusion, or the verdict, said otherwise.
    refused(&|r| {
        let row = with_fact(r, "identity");
        row["proofs"][0]["conclusion"] = Value::from("fails");
    });
    refused(&|r| {
        let row = with_fact(r, "refutation");
        row["verdict"] = Value::from("holds");
    });
    // A verdict of strength proof without its proof.
    refused(&|r| {
        let row = with_fact(r, "sign-by-coefficients");
        row["proofs"] = Value::Array(Vec::new());
    });
    // What the kernel checked, reworded.
    refused(&|r| {
        let row = with_fact(r, "identity");
        row["proofs"][0]["summary"][0]["components"] = Value::from(99);
    });
}

#[test]
fn a_file_that_is_not_a_report_is_refused_with_its_reason() {
    assert!(recheck("not json")
        .unwrap_err()
        .contains("not a JSON report"));
    assert!(recheck("{}").unwrap_err().contains("no `claims`"));
    // A proof that is not well written.
    let r = serde_json::json!({"claims": [{"id": "x", "verdict": "holds", "strength": "proof", "proofs": [{"conclusion": "holds"}]}]});
    let out = recheck(&r.to_string()).unwrap();
    assert_eq!((out.accepted, out.refused), (0, 1));
    assert!(out.lines[0].contains("not well written"), "{:?}", out.lines);
    // An id with a terminal escape is shown inert.
    let r = serde_json::json!({"claims": [{"id": "\u{1b}[2Jx", "verdict": "holds", "strength": "proof", "proofs": []}]});
    let out = recheck(&r.to_string()).unwrap();
    assert!(!out.lines[0].contains('\u{1b}'), "{:?}", out.lines);
}
