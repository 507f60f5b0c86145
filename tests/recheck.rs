//! `recheck`: every proof of the paper's JSON report is checked again by the kernel
//! from the statement the report records, and a report whose proof, statement,
//! conclusion or verdict was edited is refused.

use cosserat_check::cli::Status;
use cosserat_check::recheck::recheck;
use serde_json::Value;

fn paper_report() -> Value {
    let (status, text) = crate::common::run_cli(&["check", "--format", "json"], false);
    assert_eq!(status, Status::AsExpected);
    serde_json::from_str(&text).unwrap()
}

/// The number of accepted and refused proofs of a (possibly edited) report.
fn rechecked(report: &Value) -> (usize, usize) {
    let r = recheck(&report.to_string(), None).unwrap();
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
    // The certificate a reader sees first, reworded or removed, or one added to a
    // verdict that is not a proof.
    refused(&|r| {
        let row = with_fact(r, "identity");
        row["certificate"]["facts"][0]["components"] = Value::from(99);
    });
    refused(&|r| {
        let row = with_fact(r, "refutation");
        row["certificate"] = Value::Null;
    });
    let mut r = base.clone();
    let sampled = r["claims"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .find(|c| c["strength"] == "sampled")
        .expect("a sampled verdict");
    sampled["certificate"] = serde_json::json!({"facts": [{"kind": "identity"}]});
    assert_eq!(rechecked(&r), (accepted, 1));
    // A summary that does not count the rows' verdicts; the genuine one is accepted.
    let genuine = recheck(&base.to_string(), None).unwrap();
    assert_eq!(genuine.summary_refused, 0);
    assert!(genuine.not_proofs > 0);
    let mut r = base.clone();
    r["summary"]["fails"] = Value::from(0);
    let edited = recheck(&r.to_string(), None).unwrap();
    assert_eq!(
        (edited.accepted, edited.refused, edited.summary_refused),
        (accepted, 0, 1)
    );
}

#[test]
fn a_file_that_is_not_a_report_is_refused_with_its_reason() {
    assert!(recheck("not json", None)
        .unwrap_err()
        .to_string()
        .contains("not a JSON report"));
    assert!(recheck("{}", None)
        .unwrap_err()
        .to_string()
        .contains("no `claims`"));
    // A proof that is not well written.
    let r = serde_json::json!({"claims": [{"id": "x", "verdict": "holds", "strength": "proof", "proofs": [{"conclusion": "holds"}]}]});
    let out = recheck(&r.to_string(), None).unwrap();
    assert_eq!((out.accepted, out.refused), (0, 1));
    assert!(out.lines[0].contains("not well written"), "{:?}", out.lines);
    // An id with a terminal escape is shown inert.
    let r = serde_json::json!({"claims": [{"id": "\u{1b}[2Jx", "verdict": "holds", "strength": "proof", "proofs": []}]});
    let out = recheck(&r.to_string(), None).unwrap();
    assert!(!out.lines[0].contains('\u{1b}'), "{:?}", out.lines);
}

/// Reports forged by hand, each with one false proof that an earlier kernel accepted
/// (or crashed or hung on): `(file under tests/forged/, the forged claim, why false)`.
/// The other claims of a file are genuine proofs the checker wrote, accepted again.
const FORGED: &[(&str, &str, &str)] = &[
    (
        "circle-with-a-wrong-radius",
        "mohr-circle",
        "Mohr's circle refuting 'not a circle' with F = s_11 s_22 - 2 s_12^2: the locus is not on it",
    ),
    (
        "negative-constant-denominator",
        "s2",
        "(x^2+1)(a^2+1)/(-2) > 0: a negative constant denominator was dropped",
    ),
    (
        "point-omits-eliminated-variable",
        "f1",
        "y <= 1 refuted at y = 5 under x = y, 0 <= x <= 1: x = 5 is outside the box",
    ),
    (
        "eliminated-value-outside-box",
        "f1",
        "x = 2 fixed by an assumption, outside the box 0 <= x <= 1: a point of no claim",
    ),
    (
        "planted-derivative-definition",
        "g1",
        "grad(s^2, s) = 42 through a definition named like the derivative",
    ),
    (
        "scalar-named-like-normal-component",
        "unit",
        "a_1^2 + a_2^2 + a_3^2 = 1 with scalars a_k read as the unit normal a",
    ),
    (
        "scalar-named-like-tensor-component",
        "unit",
        "a scalar sigma_12 read as the component of the tensor sigma",
    ),
    (
        "letter-limit-read-as-ill-formed",
        "l13",
        "a true identity with 13 summed letters refuted as ill-formed",
    ),
    (
        "divisor-vanishing-on-sphere",
        "unit",
        "x + (n.n - 1)/(n.n - 1) = x: the divisor vanishes wherever n is a unit vector",
    ),
    (
        "power-past-degree-limit",
        "s2",
        "a sign by coefficients with a denominator power past the degree bound (a panic)",
    ),
    (
        "power-of-four-billion",
        "unit",
        "a root hint raised to the power 4·10^9 (a hang)",
    ),
    (
        "divided-by-huge-power",
        "d",
        "a division by a power past 64 expanded without a bound (a hang)",
    ),
    (
        "proportional-at-different-parameters",
        "navier-divided-by-G",
        "a law times -G refuted by ratios at G = 3 and G = -1 (the factor may depend on G)",
    ),
    (
        "assumption-fixes-a-coordinate",
        "fixed-coordinate",
        "d(x_1 x_1)/dx_1 = 0 under x_1 = 1: the coordinate fixed before differentiating",
    ),
    (
        "factor-on-a-box-that-fixes-it",
        "degenerate-box",
        "G b_i = G · b_i on the box G = 0, where no nonzero factor exists",
    ),
    (
        "a-factor-per-equality",
        "one-factor-per-equality",
        "2 b_i ∝ b_i and b_i ∝ b_i read with a factor per equality (2, then 1): a proportionality has one factor",
    ),
    (
        "factor-reads-a-field",
        "heat-conduction-times-the-field",
        "-k T_,ii = λ T T_,ii with λ = -k/T: a factor that reads the field T",
    ),
];

#[test]
fn forged_proofs_are_refused_and_genuine_ones_beside_them_accepted() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/forged");
    let mut files: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    let mut listed: Vec<String> = FORGED.iter().map(|f| format!("{}.json", f.0)).collect();
    listed.sort();
    assert_eq!(
        files, listed,
        "every forged report is listed with its reason"
    );
    for (file, forged, why) in FORGED {
        let text = std::fs::read_to_string(dir.join(format!("{file}.json"))).unwrap();
        let report: Value = serde_json::from_str(&text).unwrap();
        let proved = report["claims"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|c| c["strength"] == "proof")
            .count();
        let out = recheck(&text, None).unwrap();
        assert_eq!(
            (out.accepted, out.refused),
            (proved - 1, 1),
            "{file} ({why}): {:?}",
            out.lines
        );
        let line = out
            .lines
            .iter()
            .find(|l| l.starts_with(&format!("{forged}: ")))
            .unwrap_or_else(|| panic!("{file}: no line for {forged}: {:?}", out.lines));
        assert!(line.contains("REFUSED"), "{file} ({why}): {line}");
    }
}

/// A definition chain deeper than any stack: the kernel stops at its depth bound and
/// refuses the proof, instead of overflowing the stack (which aborts the process).
#[test]
fn a_definition_chain_twenty_thousand_deep_is_refused_not_a_crash() {
    let leaf = |of: Value| serde_json::json!({"leaf": {"of": of, "slots": []}});
    let mut definitions = vec![serde_json::json!({"name": "d0", "formal": [],
        "body": leaf(serde_json::json!({"symbol": "x"}))})];
    for k in 1..20_000 {
        definitions.push(serde_json::json!({"name": format!("d{k}"), "formal": [],
            "body": {"neg": leaf(serde_json::json!({"def": format!("d{}", k - 1)}))}}));
    }
    let report = serde_json::json!({"claims": [{
        "id": "chain", "verdict": "holds", "strength": "proof",
        "proofs": [{"conclusion": "holds", "statement": {
            "context": {"dim": 2, "normal": null, "in_plane": false, "symbols": {"x": 0},
                "fields": {}, "position": null, "definitions": definitions,
                "equations": [], "substitutions": [], "given": []},
            "claim": {"equal": {"chains": [[leaf(serde_json::json!({"def": "d19999"})),
                {"neg": leaf(serde_json::json!({"symbol": "x"}))}]]}}},
            "fact": {"kind": "identity", "roots": []},
            "summary": [{"kind": "polynomial-identity", "components": 1, "modulo_unit_normal": 0}]}]}]});
    let out = recheck(&report.to_string(), None).unwrap();
    assert_eq!((out.accepted, out.refused), (0, 1), "{:?}", out.lines);
    assert!(out.lines[0].contains("bound"), "{:?}", out.lines);
}

#[test]
fn with_the_files_a_proof_moved_onto_another_claim_or_an_edited_statement_is_refused() {
    let files = cosserat_check::corpus::load().unwrap();
    let statements = cosserat_check::recheck::statements_of(&files).unwrap();
    let lookup = |id: &str, correction: bool| statements.get(&(id.to_owned(), correction)).cloned();
    let base = paper_report();
    let bound = |report: &Value| {
        let r = recheck(&report.to_string(), Some(&lookup)).unwrap();
        (r.accepted, r.refused)
    };
    // Every proof of the paper is about the statement its file gives.
    let (accepted, refused) = bound(&base);
    assert_eq!(refused, 0);
    assert_eq!((accepted, 0), rechecked(&base));
    // A true proof (with its certificate) moved onto a claim that fails: alone, the
    // report is consistent; with the files, it is refused.
    let mut r = base.clone();
    let claims = r["claims"].as_array_mut().unwrap();
    let from = claims
        .iter()
        .position(|c| c["strength"] == "proof" && c["verdict"] == "holds")
        .unwrap();
    let to = claims
        .iter()
        .position(|c| {
            c["strength"] == "proof" && c["verdict"] == "fails" && c["correction"].is_null()
        })
        .unwrap();
    let (proofs, certificate) = (
        claims[from]["proofs"].clone(),
        claims[from]["certificate"].clone(),
    );
    claims[to]["proofs"] = proofs;
    claims[to]["certificate"] = certificate;
    claims[to]["verdict"] = Value::from("holds");
    let summary = &mut r["summary"];
    summary["holds"] = Value::from(summary["holds"].as_u64().unwrap() + 1);
    summary["fails"] = Value::from(summary["fails"].as_u64().unwrap() - 1);
    assert_eq!(
        rechecked(&r),
        (accepted, 0),
        "without the files the move is not seen"
    );
    assert_eq!(bound(&r), (accepted - 1, 1));
    // A claim the files do not have.
    let mut r = base.clone();
    r["claims"][from]["id"] = Value::from("no-such-claim");
    assert_eq!(bound(&r), (accepted - 1, 1));
}
