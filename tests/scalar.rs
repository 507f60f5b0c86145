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
fn signs_on_exactly_a_set_and_root_counts_are_decided_as_declared() {
    common::assert_as_declared("tests/soundness/sets-and-counts.toml", 31, |rows| {
        for r in rows {
            let (o, id) = (&r.outcome, r.claim.id.as_str());
            // Every verdict here is a proof: Sturm counts, sign charts, certificates.
            assert_eq!(o.strength(), Strength::Proof, "{id}");
            match o.verdict() {
                // A sign on exactly a set: the set and each box of the rest proved.
                // (Two when the set reaches the domain's end.)
                Verdict::Holds if id == "iff-a-pole-alone-outside" => {
                    assert_eq!(o.proofs().len(), 2, "{id}")
                }
                Verdict::Holds if id.starts_with("iff-") => {
                    assert_eq!(o.proofs().len(), 3, "{id}")
                }
                Verdict::Holds => assert_eq!(o.proofs().len(), 1, "{id}"),
                _ => {
                    let cx = o.counterexample.as_ref().expect(id);
                    assert!(cx.reverified.is_some(), "{id}: confirmed by a second route");
                }
            }
        }
        let evidence = |id: &str| {
            let r = rows.iter().find(|r| r.claim.id == id).unwrap();
            cosserat_check::report::evidence(&r.outcome)
        };
        // Which part failed, in words: inside the set, or outside it.
        assert!(evidence("iff-isotropic-moduli-set-too-large")
            .contains("(the part inside the set it is claimed on) on 0 < E, -1 < nu < 1"));
        assert!(evidence("iff-isotropic-moduli-set-too-small")
            .contains("(a part outside the set it is claimed on, where its negation is claimed) on 0 < E, nu ≤ 0"));
        assert!(evidence("iff-isotropic-moduli").contains(
            "left − right > 0 where 0 < E, -1 < nu < 1/2, left − right ≤ 0 where 0 < E, nu ≤ -1, \
             left − right ≤ 0 where 0 < E, 1/2 ≤ nu"
        ));
        // An irrational root, isolated; a count that is off, with the roots found.
        assert!(evidence("count-rayleigh-root").contains("root at x ≈ 0.8452994616"));
        assert!(evidence("count-rayleigh-root").contains("exactly 1 real root for 0 < x < 1"));
        assert!(
            evidence("count-distinct-multiplicity-twin").contains("left 2, right 3 at x=-2 and 1")
        );
        assert!(evidence("count-open-ends-twin").contains("at x=no real root"));
        // A one-point domain: its root once, and a pole there no crash.
        assert!(evidence("count-one-point-twin").ends_with("left 1, right 2 at x=1"));
        assert!(evidence("iff-a-pole-alone-outside")
            .contains("≤ 0 for 0 ≤ x ≤ 0 (its one point evaluated exactly)"));
        // Roots of parameters: the factorisation proved, or the parameter point where
        // the zeros differ (no coupling: no root at all).
        assert!(evidence("roots-of-parameters-localisation").contains("exact division"));
        assert!(evidence("roots-of-parameters-localisation-uncoupled-twin")
            .contains("left [], right [0] at G=1, H=0, k=1, p=0, q=0"));
        assert!(evidence("roots-of-parameters-localisation-planted")
            .contains("left [1/3], right [1/2] at G=1, H=0, k=1, p=1, q=0"));
    });
}

#[test]
fn a_part_of_a_sign_on_exactly_a_set_is_rechecked_with_the_others() {
    let (report, bound) = report_and_recheck("tests/soundness/sets-and-counts.toml");
    assert_eq!(bound(&report), (31, 0));
    // A part left out, or one part's proof given for all three: refused.
    let dropped = with_proofs(&report, "iff-isotropic-moduli", |p| {
        p.pop();
    });
    assert_eq!(bound(&dropped), (30, 1));
    let copied = with_proofs(&report, "iff-isotropic-moduli", |p| {
        let first = p[0].clone();
        p.iter_mut().for_each(|x| *x = first.clone());
    });
    assert_eq!(bound(&copied), (30, 1));
}

/// The JSON report of `path`, and a recheck of a report against the statements the
/// file gives: (accepted, refused).
fn report_and_recheck(
    path: &str,
) -> (
    serde_json::Value,
    impl Fn(&serde_json::Value) -> (usize, usize),
) {
    let (_, text) = common::run_cli(&["verify", path, "--format", "json"], false);
    let report: serde_json::Value = serde_json::from_str(&text).unwrap();
    let files = cosserat_check::derivation::load_files(&[path]).unwrap();
    let statements = cosserat_check::recheck::statements_of(&files).unwrap();
    let bound = move |r: &serde_json::Value| {
        let lookup = |id: &str, c: bool| statements.get(&(id.to_owned(), c)).cloned();
        let r = cosserat_check::recheck::recheck(&r.to_string(), Some(&lookup)).unwrap();
        (r.accepted, r.refused)
    };
    (report, bound)
}

/// `report` with the proofs of claim `id` edited by `edit`, and its certificate made
/// to match them (so that only the proofs' coverage can be refused).
fn with_proofs(
    report: &serde_json::Value,
    id: &str,
    edit: impl Fn(&mut Vec<serde_json::Value>),
) -> serde_json::Value {
    let k = report["claims"]
        .as_array()
        .unwrap()
        .iter()
        .position(|c| c["id"] == id)
        .unwrap();
    let mut r = report.clone();
    let c = &mut r["claims"][k];
    let mut proofs = c["proofs"].as_array().unwrap().clone();
    edit(&mut proofs);
    let facts: Vec<serde_json::Value> = proofs
        .iter()
        .flat_map(|p| p["summary"].as_array().unwrap().clone())
        .collect();
    c["proofs"] = serde_json::Value::Array(proofs);
    c["certificate"] = serde_json::json!({ "facts": facts });
    r
}

#[test]
fn stationary_points_and_extrema_are_decided_as_declared() {
    let path = "tests/soundness/stationary.toml";
    common::assert_as_declared(path, 14, |rows| {
        for r in rows {
            let (o, id) = (&r.outcome, r.claim.id.as_str());
            match o.verdict() {
                // Every part proved: the ends of the interval, the derivative ≥ 0 and
                // ≤ 0, and the second derivative for an extremum.
                Verdict::Holds => {
                    assert_eq!(o.strength(), Strength::Proof, "{id}");
                    let parts = match id {
                        "cubic-stationary" => 2,
                        "cubic-minimum" => 3,
                        "sine-of-double-angle-maximum" | "maximum-power-transfer" => 4,
                        _ => 5,
                    };
                    assert_eq!(o.proofs().len(), parts, "{id}");
                }
                Verdict::Fails => {
                    assert_eq!(o.strength(), Strength::Proof, "{id}");
                    let cx = o.counterexample.as_ref().expect(id);
                    assert!(cx.reverified.is_some(), "{id}: confirmed by a second route");
                }
                // A true statement the test says nothing about: never refuted.
                _ => assert!(
                    id == "flat-maximum" || id == "maximum-at-a-closed-end",
                    "{id}"
                ),
            }
        }
        let evidence = |id: &str| common::evidence_of(rows, id);
        assert!(evidence("parabola-maximum")
            .contains("decided a strict local maximum (the second-derivative test) at t = a/2"));
        assert!(evidence("parabola-wrong-point").contains("the derivative in t at t = a/3 is ≤ 0"));
        assert!(
            evidence("parabola-outside").contains("the point t = a/2 is > 1 (inside the interval)")
        );
        assert!(evidence("cubic-minimum-every-a-wrong").contains("values at a=-1/2: left -3"));
        assert!(evidence("flat-maximum").contains("the second-derivative test decides nothing"));
        assert!(evidence("maximum-at-a-closed-end").contains("reaches an end of the interval"));
    });
    // Every proof is about a part its file gives (a refutation by the weaker part
    // that tells it from an undecided test included); a holds needs all its parts.
    let (report, bound) = report_and_recheck(path);
    assert_eq!(bound(&report), (12, 0));
    let dropped = with_proofs(&report, "parabola-maximum", |p| {
        p.pop();
    });
    assert_eq!(
        bound(&dropped),
        (11, 1),
        "the second derivative's part left out"
    );
}

#[test]
fn principal_values_through_the_characteristic_polynomial_are_decided_as_declared() {
    common::assert_as_declared("tests/soundness/principal-values.toml", 8, |rows| {
        for r in rows {
            let (o, id) = (&r.outcome, r.claim.id.as_str());
            assert_eq!(o.strength(), Strength::Proof, "{id}");
        }
        let evidence = |id: &str| common::evidence_of(rows, id);
        assert!(evidence("three-principal-values")
            .contains("root at lam ≈ 0.5857864376, root at lam = 2, root at lam ≈ 3.414213562"));
        assert!(evidence("three-principal-values-twin")
            .contains("left 3, right 2 at lam ≈ 0.5857864376 and 2 and ≈ 3.414213562"));
        assert!(evidence("positive-definite-twin").contains("left 2, right 3 at lam=1 and 3"));
        assert!(evidence("isotropic-stiffness").contains("(lam − (3*K)) (lam − (2*G))^2"));
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
        ("strategy = \"proportional\"\ndefine = [\"q = x^2\"]\nsides = [\"q\", \"x^2\"]\ngiven = [\"q > 0\"]", "a hypothesis of an exact identity"),
        ("strategy = \"monotone\"\nfunction = \"x\"\ndirection = \"up\"\nin = \"x\"", "unknown direction `up`"),
        ("strategy = \"monotone\"\nfunction = \"x\"\ndirection = \"increasing\"", "needs `in`"),
        ("strategy = \"monotone\"\nfunction = \"x\"\ndirection = \"increasing\"\nin = \"s\"", "`s` is not a scalar parameter"),
        ("strategy = \"limit\"\nfunction = \"x\"\nin = \"x\"\ntends_to = \"zero\"\nlimit = \"0\"", "cannot read `zero`"),
        ("strategy = \"limit\"\nfunction = \"x\"\nin = \"x\"\ntends_to = \"0\"\nlimit = \"x\"", "depends on `x`"),
        ("strategy = \"roots\"\nfunction = \"x\"\nin = \"x\"", "needs `roots`"),
        ("strategy = \"limit\"\nfunction = \"x\"\nin = \"x\"\ntends_to = \"0\"\nlimit = \"0\"\ndirection = \"increasing\"", "`direction` does not apply"),
        ("strategy = \"roots\"\nfunction = \"x\"\nin = \"x\"\nroots = []\ncount = 1", "not both"),
        ("strategy = \"roots\"\nfunction = \"x\"\nin = \"x\"\ncount = -1", "count must be between 0 and 100000"),
        ("strategy = \"sign\"\nsides = [\"x\", \"0\"]\nrelation = \">\"\ncount = 1", "`count` does not apply to strategy = \"sign\""),
        ("strategy = \"sign\"\nsides = [\"x\", \"0\"]\nrelation = \">\"\nroots = []", "`roots` does not apply to strategy = \"sign\""),
        ("strategy = \"roots\"\nfunction = \"x\"\nin = \"x\"\ncount = 1\nexactly_when = [\"x > 0\"]", "`exactly_when` does not apply to strategy = \"roots\""),
        ("sides = [\"x\", \"x\"]\nexactly_when = [\"x > 0\"]", "`exactly_when` does not apply to strategy = \"exact\""),
        ("sides = [\"x\", \"x\"]\nin = \"x\"", "`in` does not apply to strategy = \"exact\""),
        ("strategy = \"sign\"\nsides = [\"x\", \"0\"]\nrelation = \">\"\nexactly_when = []", "needs at least one bound"),
        ("strategy = \"sign\"\nsides = [\"x\", \"0\"]\nrelation = \">\"\nexactly_when = [\"x > a\"]", "cannot read `x > a` as a bound"),
        ("strategy = \"sign\"\nsides = [\"x\", \"0\"]\nrelation = \">\"\nexactly_when = [\"s > 0\"]", "`s` is not a scalar parameter"),
        ("strategy = \"stationary\"\nfunction = \"x^2\"\nin = \"x\"\nkind = \"stationary\"", "needs `at`"),
        ("strategy = \"stationary\"\nfunction = \"x^2\"\nin = \"x\"\nat = \"0\"", "needs `kind`"),
        ("strategy = \"stationary\"\nfunction = \"x^2\"\nin = \"x\"\nat = \"0\"\nkind = \"maximum\"", "unknown kind `maximum`"),
        ("strategy = \"stationary\"\nfunction = \"x^2\"\nin = \"x\"\nat = \"x/2\"\nkind = \"stationary\"", "the point reads `x` itself"),
        ("strategy = \"stationary\"\nfunction = \"x^2\"\nat = \"0\"\nkind = \"stationary\"", "needs `in`"),
        ("strategy = \"sign\"\nsides = [\"x\", \"0\"]\nrelation = \">\"\nat = \"0\"", "`at` does not apply to strategy = \"sign\""),
        ("strategy = \"monotone\"\nfunction = \"x\"\ndirection = \"increasing\"\nin = \"x\"\nkind = \"stationary\"", "`kind` does not apply to strategy = \"monotone\""),
        ("sides = [\"x\", \"x\"]\nat = \"0\"", "`at` does not apply to strategy = \"exact\""),
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
