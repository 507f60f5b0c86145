//! The literal 0 matches any free indices everywhere the README says so (issue 17,
//! item 5): as a side, a term of a sum, a definition's body and a closed-form
//! gradient, and as a side of a matrix equation; each use has a twin that must fail.

use crate::common;

#[test]
fn zero_is_a_zero_tensor_of_any_rank_and_wrong_uses_fail() {
    common::assert_as_declared("tests/soundness/literal-zero.toml", 11, |rows| {
        assert!(rows.iter().any(|r| r.claim.id.ends_with("-wrong")));
    });
}
