//! Exact rational functions of scalar parameters (issue 13, item 3): identities with
//! divisions by sums are proved with the set where they hold, their wrong twins fail
//! with a confirmed counterexample off every pole, and divisors that are not
//! polynomials in scalar parameters are refused where they stand.

use cosserat_check::cli::decide_all;
use cosserat_check::decide::Strength;
use cosserat_check::derivation::load_str;
use cosserat_check::derivation::Verdict;
use cosserat_check::kernel::check::Checked;

use crate::common;

#[test]
fn identities_hold_where_their_divisors_do_not_vanish_and_twins_fail() {
    common::assert_as_declared("tests/soundness/rational.toml", 26, |rows| {
        for r in rows {
            let o = &r.outcome;
            match o.verdict() {
                Verdict::Holds => {
                    let facts = o.proofs().first().expect("a kernel proof").summary();
                    let Some(Checked::PolynomialIdentity { nonzero, .. }) = facts.first() else {
                        panic!("{}: {facts:?}", r.claim.id);
                    };
                    assert!(
                        !nonzero.is_empty(),
                        "{}: every claim divides by a sum",
                        r.claim.id
                    );
                }
                Verdict::Fails => {
                    let cx = o.counterexample.as_ref().expect("a counterexample");
                    assert!(
                        cx.reverified.is_some(),
                        "{}: the point is confirmed by the interpreter",
                        r.claim.id
                    );
                    assert_ne!(cx.lhs_value, cx.rhs_value, "{}", r.claim.id);
                }
                _ => panic!("{}: {:?}", r.claim.id, o.verdict()),
            }
        }
        let conditions = |id: &str| {
            let r = rows.iter().find(|r| r.claim.id == id).unwrap();
            cosserat_check::report::evidence(&r.outcome)
        };
        assert!(
            conditions("shear-modulus-from-E-nu")
                .ends_with("holds where 2*G + 3*lambda ≠ 0, G + lambda ≠ 0"),
            "{}",
            conditions("shear-modulus-from-E-nu")
        );
        // A divisor written as a product keeps its factors apart.
        assert!(conditions("poisson-from-lame").ends_with("holds where 2*nu - 1 ≠ 0, nu + 1 ≠ 0"));
    });
}

fn refusal(sides: &str, extra: &str) -> String {
    let text = format!(
        "section = \"t\"\ntitle = \"t\"\ndimension = 2\nnormal = \"n\"\nposition = \"x\"\nfields = [\"u_i\", \"theta\"]\ntensors = [\"a_i\"]\nscalars = [\"p\", \"q\"]\n{extra}\n[[claim]]\nid = \"c\"\nprinted = 'x'\nexpect = \"holds\"\nsides = [{sides}]\n"
    );
    let files = load_str("div.toml", &text).unwrap();
    decide_all(std::slice::from_ref(&files), None)
        .expect_err("refused")
        .to_string()
}

#[test]
fn divisors_with_the_normal_or_a_field_are_refused() {
    let e = refusal("\"1 / (p + n_1)\", \"0\"", "");
    assert!(
        e.contains("div.toml:14:15") && e.contains("`n_1` is a component of the normal"),
        "{e}"
    );
    let e = refusal("\"1 / (p + theta)\", \"0\"", "");
    assert!(e.contains("`theta` varies with position"), "{e}");
    let e = refusal("\"q / (p - p)\", \"0\"", "");
    assert!(e.contains("the divisor is identically zero"), "{e}");
    // A divisor that an assumption makes zero is zero.
    let e = refusal("\"q / (p - 2 q)\", \"0\"", "assume = [\"p = 2 q\"]");
    assert!(e.contains("the divisor is identically zero"), "{e}");
}

#[test]
fn a_divisor_that_is_a_single_term_works_as_before() {
    // The normal and tensor components may divide as single terms (Laurent
    // polynomials); the statement is read where they are nonzero.
    let text = "section = \"t\"\ntitle = \"t\"\ndimension = 2\ntensors = [\"a_i\"]\nscalars = [\"p\"]\n\n[[claim]]\nid = \"c\"\nprinted = 'x'\nexpect = \"holds\"\nsides = [\"a_1 p / (2 a_1)\", \"p / 2\"]\n";
    let files = load_str("one.toml", text).unwrap();
    let rows = decide_all(std::slice::from_ref(&files), None).unwrap();
    assert!(rows[0].as_expected());
    let Some(Checked::PolynomialIdentity { nonzero, .. }) =
        rows[0].outcome.proofs()[0].summary().first()
    else {
        panic!()
    };
    assert!(nonzero.is_empty());
}

#[test]
fn the_worked_example_decides_as_declared() {
    common::assert_as_declared("derivations/examples/moduli.toml", 5, |_| {});
    common::assert_as_declared("derivations/examples/inverse.toml", 5, |rows| {
        assert!(rows.iter().all(|r| r.outcome.strength() == Strength::Proof));
    });
}
