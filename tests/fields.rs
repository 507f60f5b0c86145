//! Fields and their derivatives (issue 13, item 1): textbook field identities hold,
//! their wrong twins fail with counterexamples confirmed by the second route (explicit
//! Taylor-polynomial fields, derivatives by central differences), sampled strategies
//! say undecided, and slips in the notation are located errors.

use cosserat_check::cli::decide_all;
use cosserat_check::decide::Reverified;
use cosserat_check::derivation::{load_str, Verdict};

use crate::common;

#[test]
fn identities_hold_and_their_twins_fail_confirmed_by_differences() {
    common::assert_as_declared("tests/soundness/fields.toml", 27, |rows| {
        common::assert_failures_confirmed(rows, 13, Reverified::TaylorDifferences);
    });
}

#[test]
fn differential_hypotheses_are_decided_and_refuted_at_fields_that_satisfy_them() {
    common::assert_as_declared("tests/soundness/differential.toml", 24, |rows| {
        common::assert_failures_confirmed(rows, 12, Reverified::TaylorDifferences);
    });
}

#[test]
fn differential_hypotheses_outside_the_supported_class_are_located_errors() {
    let fields = "fields = [\"phi\", \"psi\", \"u_i\", \"w(x_1)\"]\nnormal = \"n\"";
    let cases = [
        (
            "assume = [\"phi_,kk = phi^3\"]\nsides = [\"phi_,kk\", \"phi^3\"]",
            "f.toml:12:12",
            "must be linear in the fields",
        ),
        (
            "assume = [\"x_1 phi_,kk = 0\"]\nsides = [\"phi\", \"phi\"]",
            "f.toml:12:12",
            "coefficients constant in position",
        ),
        (
            "assume = [\"phi_,1 = psi\", \"phi_,2 = 0\"]\nsides = [\"phi\", \"phi\"]",
            "f.toml:12:28",
            "they give `phi_,12` two different values, so they imply -psi_,2 = 0",
        ),
        // A field on some coordinates only would lose that restriction when an
        // assumption replaces, eliminates or ties it (w = psi made psi_,2 free).
        (
            "assume = [\"w = psi\"]\nsides = [\"psi_,2\", \"0\"]",
            "f.toml:12:12",
            "`w` depends on some coordinates only, and an assumption that mentions it would lose that",
        ),
        (
            "assume = [\"w_,1 = psi\"]\nsides = [\"psi_,2\", \"0\"]",
            "f.toml:12:12",
            "as a hypothesis (`w_,2 = 0`)",
        ),
        (
            "assume = [\"phi_,1 = 0\", \"phi_,1 = 1\"]\nsides = [\"phi\", \"phi\"]",
            "f.toml:12:26",
            "this one says -1 = 0, a relation without derivatives (or a contradiction)",
        ),
        (
            "assume = [\"x_k x_k = 1\"]\nsides = [\"phi\", \"phi\"]",
            "f.toml:12:12",
            "varies with position",
        ),
        (
            "assume = [\"phi_,k n_k = 0\"]\nsides = [\"phi\", \"phi\"]",
            "f.toml:12:12",
            "varies with the normal",
        ),
        (
            "assume = [\"phi_,kk = 0\"]\nstrategy = \"numeric\"\nsides = [\"phi\", \"phi\"]",
            "f.toml:12:12",
            "decided exactly",
        ),
    ];
    for (claim, at, message) in cases {
        let e = common::error_of(&one_claim(fields, claim));
        assert!(e.contains(at) && e.contains(message), "{claim}: {e}");
    }
}

fn one_claim(header: &str, claim: &str) -> String {
    format!(
        "section = \"t\"\ntitle = \"t\"\ndimension = 3\nposition = \"x\"\n{header}\n\n[[claim]]\nid = \"c\"\nprinted = 'c'\nexpect = \"holds\"\n{claim}\n"
    )
}

#[test]
fn slips_are_located_errors() {
    let fields = "fields = [\"u_i\"]\ntensors = [\"s_ij\"]";
    let cases = [
        (
            "sides = [\"s_ij,j\", \"0\"]",
            "f.toml:12:11",
            "`s` is not a field, so its derivative is zero",
        ),
        (
            "sides = [\"d(u_i)/dy_i\", \"0\"]",
            "f.toml:12:19",
            "`y` is not the declared position",
        ),
        (
            "sides = [\"u_1,4\", \"0\"]",
            "f.toml:12:15",
            "coordinate 4 is outside 1..=3",
        ),
        (
            "sides = [\"d(u_k u_k)/dx_k\", \"0\"]",
            "f.toml:12:25",
            "summed inside what is differentiated",
        ),
        ("sides = [\"u_i,j\", \"u_j\"]", "f.toml", "free indices"),
    ];
    for (claim, at, message) in cases {
        let e = common::error_of(&one_claim(fields, claim));
        assert!(e.contains(at) && e.contains(message), "{claim}: {e}");
    }
    let decl_cases = [
        ("fields = [\"w_i(y_2)\"]", "`y_2` is not a coordinate"),
        ("fields = [\"w_i(x_4)\"]", "`x_4` is not a coordinate"),
        ("fields = [\"w_i(x_2, x_2)\"]", "x_2 is listed twice"),
        ("fields = [\"w_i(x_2\"]", "never closed"),
        ("fields = [\"w_ii\"]", "distinct index letters"),
        ("fields = [\"u_i\", \"u_j\"]", "declared twice"),
    ];
    for (header, message) in decl_cases {
        let e = common::error_of(&one_claim(header, "sides = [\"1\", \"1\"]"));
        assert!(e.contains(message), "{header}: {e}");
    }
}

#[test]
fn sampled_strategies_leave_derivatives_undecided() {
    let text = one_claim(
        "fields = [\"u_i\"]",
        "strategy = \"numeric\"\nsides = [\"sqrt(1 + u_i,j u_i,j)\", \"1\"]",
    );
    let f = load_str("f.toml", &text).unwrap();
    let rows = decide_all(std::slice::from_ref(&f), None).unwrap();
    assert_eq!(rows[0].outcome.verdict(), Verdict::Undecided);
    let words = cosserat_check::report::evidence(&rows[0].outcome);
    assert!(words.contains("differentiates fields"), "{words}");
}

#[test]
fn the_worked_example_is_decided_as_declared() {
    common::assert_as_declared("derivations/examples/fields.toml", 4, |_| {});
}

#[test]
fn a_pointwise_statement_about_fields_is_confirmed_at_the_point() {
    // No derivative: the fields are values at a point, confirmed to rounding, not to
    // the accuracy of differences.
    let text = one_claim(
        "fields = [\"u_i\"]",
        "expect = \"fails\"\nreason = \"r\"\nsides = [\"u_i u_i\", \"u_1 u_1\"]",
    )
    .replace("expect = \"holds\"\n", "");
    let f = load_str("f.toml", &text).unwrap();
    let rows = decide_all(std::slice::from_ref(&f), None).unwrap();
    assert!(rows[0].as_expected());
    let cx = rows[0].outcome.counterexample.as_ref().unwrap();
    assert_eq!(cx.reverified, Some(Reverified::FloatingPoint));
}
