//! Claims about rational functions of parameters (issue 13, item 6): `sign`,
//! `monotone`, `limit` and `roots`. Every claim that holds has a wrong twin (a changed
//! coefficient, a flipped sign or direction, a dropped root) that must come out
//! `fails` with a confirmed counterexample; proofs come from the kernel, and the one
//! claim without a certificate is labelled sampled.

use cosserat_check::decide::Strength;
use cosserat_check::derivation::Verdict;
use cosserat_check::kernel::check::Checked as Fact;

use crate::common;

#[test]
fn scalar_claims_and_their_twins_are_decided_as_declared() {
    common::assert_as_declared("tests/soundness/rational-claims.toml", 44, |rows| {
        for r in rows {
            let o = &r.outcome;
            let id = r.claim.id.as_str();
            match o.verdict() {
                Verdict::Holds if id == "sign-sampled" => {
                    assert_eq!(o.strength(), Strength::Sampled, "no certificate applies");
                    assert!(cosserat_check::report::evidence(o).contains("exact samples (seed 1)"));
                }
                Verdict::Holds => {
                    assert_eq!(o.strength(), Strength::Proof, "{id}");
                    assert!(!o.proofs().first().expect(id).summary().is_empty());
                    assert!(
                        cosserat_check::report::evidence(o).contains("proof: "),
                        "{id}: the kernel's facts are shown"
                    );
                }
                Verdict::Fails | Verdict::Conditional => {
                    let cx = o.counterexample.as_ref().expect(id);
                    assert!(cx.reverified.is_some(), "{id}: confirmed by a second route");
                }
                Verdict::Undecided => panic!("{id} undecided"),
            }
        }
        let evidence = |id: &str| {
            let r = rows.iter().find(|r| r.claim.id == id).unwrap();
            cosserat_check::report::evidence(&r.outcome)
        };
        // What the kernel checked behind each proof.
        let facts = |id: &str| {
            let r = rows.iter().find(|r| r.claim.id == id).unwrap();
            r.outcome.proofs()[0].summary().to_vec()
        };
        assert!(matches!(
            facts("sign-pole-excluded")[0],
            Fact::SignOnInterval { poles: 1, .. }
        ));
        assert!(matches!(
            facts("sign-coefficients")[0],
            Fact::CoefficientSigns { .. }
        ));
        assert!(matches!(facts("limit-removable")[0], Fact::Limit { .. }));
        assert!(
            matches!(&facts("roots-cubic")[0], Fact::Roots { roots, exactly: true, .. } if roots.len() == 3)
        );
        // Exact turning points and where the claim holds.
        assert!(evidence("hump-turning-point").contains("d/dx = 0 at x = 1; holds on 0 < x ≤ 1"));
        assert!(evidence("cubic-turning-points")
            .contains("holds on x ≤ ≈ -0.5773502692 and ≈ 0.5773502692 ≤ x"));
        assert!(evidence("reciprocal-across-pole").contains("holds on x < 0 and 0 < x"));
        // A strict sign broken only at an irrational zero, and a root left out.
        assert!(evidence("sign-double-root-strict").contains("≈ -1.414213562"));
        assert!(evidence("roots-irrational-missed").contains("≈ 1.414213562 (a root not stated)"));
        assert!(evidence("limit-removable-twin").contains("left 2, right 1"));
        assert!(
            evidence("limit-sign-from-parameter-twin").contains("left −∞ on some side, right +∞")
        );
    });
}

#[test]
fn the_worked_example_is_decided_as_declared() {
    common::assert_as_declared("derivations/examples/rational-functions.toml", 8, |_| {});
}

fn claim(body: &str) -> String {
    common::one_claim(
        "dimension = 2\nscalars = [\"x\", \"a\"]\ntensors = [\"s_ij\"]",
        body,
    )
}

#[test]
fn malformed_scalar_claims_are_located_errors() {
    let cases = [
        ("strategy = \"sign\"\nsides = [\"x\", \"0\"]", "needs `relation`"),
        ("strategy = \"sign\"\nsides = [\"x\", \"0\"]\nrelation = \"=>\"", "unknown relation `=>`"),
        ("strategy = \"sign\"\nsides = [\"x\", \"0\", \"1\"]\nrelation = \">\"", "compares exactly two sides"),
        ("strategy = \"sign\"\nsides = [\"x\", \"0\"]\nrelation = \">\"\ngiven = [\"x > y\"]", "cannot read `x > y` as a bound"),
        ("strategy = \"sign\"\nsides = [\"x\", \"0\"]\nrelation = \">\"\ngiven = [\"x > 1\", \"x < 0\"]", "no value satisfies it"),
        ("define = [\"q = x^2\"]\nsides = [\"q\", \"x^2\"]\ngiven = [\"q > 0\"]", "a bound on a definition or on any other expression is a hypothesis"),
        ("strategy = \"monotone\"\nfunction = \"x\"\ndirection = \"up\"\nin = \"x\"", "unknown direction `up`"),
        ("strategy = \"monotone\"\nfunction = \"x\"\ndirection = \"increasing\"", "needs `in`"),
        ("strategy = \"monotone\"\nfunction = \"x\"\ndirection = \"increasing\"\nin = \"s\"", "`s` is not a scalar parameter"),
        ("strategy = \"limit\"\nfunction = \"x\"\nin = \"x\"\ntends_to = \"zero\"\nlimit = \"0\"", "cannot read `zero`"),
        ("strategy = \"limit\"\nfunction = \"x\"\nin = \"x\"\ntends_to = \"0\"\nlimit = \"x\"", "depends on `x`"),
        ("strategy = \"roots\"\nfunction = \"x\"\nin = \"x\"", "needs `roots`"),
        ("strategy = \"roots\"\nfunction = \"x - a\"\nin = \"x\"\nroots = [\"a\"]", "must be a rational number"),
        ("strategy = \"limit\"\nfunction = \"x\"\nin = \"x\"\ntends_to = \"0\"\nlimit = \"0\"\ndirection = \"increasing\"", "`direction` does not apply"),
    ];
    let cases = cases.map(|(body, want)| (claim(body), want));
    common::assert_located_errors(&cases);
}

#[test]
fn a_cancelled_divisor_is_no_pole_of_a_monotone_function() {
    // (x² − 1)/(x − 1) is x + 1 with x = 1 left out: a removable point, which the
    // evidence never calls a pole, with or without a factor of one sign.
    for (function, given) in [
        ("(x^2 - 1)/(x - 1)", ""),
        ("a (x^2 - 1)/(x - 1)", "given = [\"a > 0\"]\n"),
    ] {
        let text = claim(&format!(
            "strategy = \"monotone\"\nfunction = \"{function}\"\nin = \"x\"\ndirection = \"increasing\"\n{given}"
        ));
        let file = cosserat_check::derivation::load_str("t.toml", &text).unwrap();
        let d = cosserat_check::check::decide_claim(&file.claims[0]).unwrap();
        let ev = cosserat_check::report::evidence(&d.outcome);
        assert_ne!(d.outcome.verdict(), Verdict::Fails, "{function}: {ev}");
        assert!(!ev.contains("pole at"), "{function}: {ev}");
    }
}
