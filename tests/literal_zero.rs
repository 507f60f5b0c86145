//! The literal 0 matches any free indices everywhere the README says so (issue 17,
//! item 5): as a side, a term of a sum, a definition's body and a closed-form
//! gradient; each use has a twin that must fail.

use cosserat_check::cli::decide_all;
use cosserat_check::derivation::load_files;

#[test]
fn zero_is_a_zero_tensor_of_any_rank_and_wrong_uses_fail() {
    let files = load_files(&["tests/soundness/literal-zero.toml"]).unwrap();
    let rows = decide_all(&files, None).unwrap();
    assert_eq!(rows.len(), 9);
    for r in &rows {
        assert!(
            r.as_expected(),
            "{}: {} (declared {})",
            r.claim.id,
            r.outcome.verdict_text(),
            r.claim.expect
        );
    }
    assert!(rows.iter().any(|r| r.claim.id.ends_with("-wrong")));
}
