//! A claim whose exact expansion passes a resource limit is `undecided` with the limit
//! and its location; the file's other claims are decided (issue 13).

use cosserat_check::cli::decide_all;
use cosserat_check::derivation::{load_files, Verdict};
use cosserat_check::report;
use cosserat_check::strategy::finding::Finding;

#[test]
fn a_limit_makes_one_claim_undecided_and_the_rest_are_decided() {
    let files = load_files(&["tests/soundness/resource-limits.toml"]).unwrap();
    let rows = decide_all(&files, None).unwrap();
    assert_eq!(rows.len(), 6);
    for r in &rows {
        assert!(
            r.as_expected(),
            "{}: {}",
            r.claim.id,
            r.outcome.verdict_text()
        );
        if r.outcome.verdict() == Verdict::Undecided {
            let Some(Finding::ResourceLimit { what, at, .. }) = &r.outcome.finding else {
                panic!("{}: {:?}", r.claim.id, r.outcome.finding);
            };
            assert!(
                at.starts_with("tests/soundness/resource-limits.toml:"),
                "{at}"
            );
            let words = report::evidence(&r.outcome);
            assert!(words.starts_with("undecided (resource limit): "), "{words}");
            assert!(words.contains(what.as_str()));
        }
    }
    let verdicts: Vec<Verdict> = rows.iter().map(|r| r.outcome.verdict()).collect();
    assert_eq!(
        verdicts,
        [
            Verdict::Undecided,
            Verdict::Undecided,
            Verdict::Undecided,
            Verdict::Undecided,
            Verdict::Holds,
            Verdict::Fails
        ]
    );
}
