//! Scientific notation (exact), π and exp, log, atan, asin, acos (sampled): identities
//! hold, their wrong twins fail, and exact mode refuses π with a located error; names
//! with `_` inside (`sigma_el_ij`, `E_lg`) read as declared.

use cosserat_check::cli::decide_all;
use cosserat_check::derivation::load_str;

use crate::common;

#[test]
fn identities_hold_and_their_twins_fail() {
    common::assert_as_declared("tests/soundness/notation.toml", 18, |_| {});
}

#[test]
fn names_with_underscores_hold_and_their_twins_fail() {
    common::assert_as_declared("tests/soundness/names.toml", 8, |_| {});
}

#[test]
fn exact_mode_refuses_pi_where_it_stands() {
    let text = "section = \"t\"\ntitle = \"t\"\ndimension = 2\nscalars = [\"x\"]\n\n[[claim]]\nid = \"c\"\nprinted = 'x'\nexpect = \"holds\"\nsides = [\"2 pi x\", \"pi x + pi x\"]\n";
    let files = load_str("pi.toml", text).unwrap();
    let err = decide_all(std::slice::from_ref(&files), None)
        .expect_err("exact mode refuses pi")
        .to_string();
    assert!(err.contains("pi.toml:10:13"), "{err}");
    assert!(err.contains("π is not a rational number"), "{err}");
}
