//! A claim whose exact expansion passes a resource limit is `undecided` with the limit
//! and its location; the file's other claims are decided (issue 13).

use cosserat_check::cli::decide_all;
use cosserat_check::decide::finding::Finding;
use cosserat_check::derivation::{load_files, Verdict};
use cosserat_check::report;

#[test]
fn a_limit_makes_one_claim_undecided_and_the_rest_are_decided() {
    let files = load_files(&["tests/soundness/resource-limits.toml"]).unwrap();
    let rows = decide_all(&files, None).unwrap();
    assert_eq!(rows.len(), 7);
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
            if r.claim.id == "average-of-a-large-product" {
                assert!(words.contains("this expands to 828100 terms"), "{words}");
            }
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
            Verdict::Undecided,
            Verdict::Holds,
            Verdict::Fails
        ]
    );
}

/// A power of a short sum is bounded by the multisets of its terms, C(t + k − 1, k):
/// (a_i b_i)^16 has 153 terms and (n_i A_ij n_j)^5 has 1,287, well inside the limit
/// (a bound by monomials of that degree said 74,613 and 646,646 and refused them). A
/// slip in such a power is still found.
#[test]
fn powers_of_short_sums_are_decided() {
    let text = String::from("section = \"t\"\ntitle = \"t\"\ndimension = 3\ntensors = [\"a_i\", \"b_i\", \"A_ij\"]\nnormal = \"n\"\n")
        + "[[claim]]\nid = \"p16\"\nprinted = 'x'\nexpect = \"holds\"\nsides = [\"(a_i b_i)^16\", \"((a_i b_i)^8)^2\"]\n"
        + "[[claim]]\nid = \"avg16\"\nprinted = 'x'\nexpect = \"holds\"\nsides = [\"avg((a_i n_i)^16)\", \"avg((a_i n_i)^8 (a_j n_j)^8)\"]\n"
        + "[[claim]]\nid = \"q5\"\nprinted = 'x'\nexpect = \"holds\"\nsides = [\"(n_i A_ij n_j)^5\", \"(n_i A_ij n_j)^2 (n_k A_kl n_l)^3\"]\n"
        + "[[claim]]\nid = \"slip\"\nprinted = 'x'\nexpect = \"fails\"\nreason = \"r\"\nsides = [\"(a_i b_i)^16\", \"((a_i b_i)^8)^2 + a_1^16\"]\n";
    let file = cosserat_check::derivation::load_str("f.toml", &text).unwrap();
    let rows = decide_all(std::slice::from_ref(&file), None).unwrap();
    for r in &rows {
        assert!(
            r.as_expected(),
            "{}: {}",
            r.claim.id,
            report::evidence(&r.outcome)
        );
    }
}
