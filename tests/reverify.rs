//! Every counterexample is evaluated a second time before a `fails` is printed
//! (`decide::reverify`): exact counterexamples by the floating-point interpreter,
//! sampled ones exactly where the statement is polynomial and by the interpreter
//! otherwise. A floating-point violation that the exact evaluation does not confirm is
//! never a counterexample. A sampled `fails` stays of strength `sampled` even when the
//! point is confirmed exactly: strength `proof` comes only from the kernel.

use cosserat_check::check::decide_claim;
use cosserat_check::decide::finding::{Finding, Unresolved};
use cosserat_check::decide::{Outcome, Reverified, Strength};
use cosserat_check::derivation::{load_str, Verdict};

const HEADER: &str = r#"
section = "t"
title = "re-verification"
dimension = 3
normal = "n"
tensors = ["A_ij"]
scalars = ["x", "y"]
"#;

fn decide(body: &str) -> Outcome {
    let text = format!("{HEADER}\n[[claim]]\nid = \"x\"\nprinted = 'x'\n{body}");
    let file = load_str("test.toml", &text).unwrap_or_else(|e| panic!("{e}"));
    decide_claim(&file.claims[0])
        .unwrap_or_else(|e| panic!("{e}"))
        .outcome
}

fn reverified(o: &Outcome) -> Option<Reverified> {
    o.counterexample.as_ref().and_then(|c| c.reverified)
}

#[test]
fn a_sampled_polynomial_counterexample_is_confirmed_exactly() {
    // (x + y)² ≤ 2 (x² + y²) holds; with the 2 dropped it fails, and the sides are
    // polynomial, so the sample's point is checked in exact arithmetic.
    let o = decide(
        "expect = \"fails\"\nreason = \"r\"\nstrategy = \"numeric\"\nrelation = \"<=\"\nsides = [\"(x + y)^2\", \"x^2 + y^2\"]",
    );
    assert_eq!(o.verdict(), Verdict::Fails);
    assert_eq!(reverified(&o), Some(Reverified::Exact));
    assert_eq!(o.strength(), Strength::Sampled, "no kernel proof behind it");
    // Through the normal (a point of the sphere made exact): A_ij n_i n_j = A_ii is false.
    let o = decide(
        "expect = \"fails\"\nreason = \"r\"\nstrategy = \"numeric\"\nsides = [\"A_ij n_i n_j\", \"A_kk\"]",
    );
    assert_eq!(o.verdict(), Verdict::Fails);
    assert_eq!(reverified(&o), Some(Reverified::Exact));
}

#[test]
fn a_sampled_non_polynomial_counterexample_is_confirmed_by_the_interpreter() {
    let o = decide(
        "expect = \"fails\"\nreason = \"r\"\nstrategy = \"numeric\"\nsides = [\"sqrt(x^2 + y^2)\", \"abs(x) + abs(y)\"]",
    );
    assert_eq!(o.verdict(), Verdict::Fails);
    // The interpreter confirms it, and the sides' interval enclosures exclude equality.
    assert_eq!(reverified(&o), Some(Reverified::Intervals));
    assert_eq!(o.strength(), Strength::Sampled);
    // Where the sides have no enclosure (an average of a non-polynomial), the
    // interpreter alone confirms it.
    let o = decide(
        "expect = \"fails\"\nreason = \"r\"\nstrategy = \"numeric\"\nsides = [\"avg(sqrt(1 + (A_ij n_i n_j)^2))\", \"1 + A_11 A_11\"]",
    );
    assert_eq!(o.verdict(), Verdict::Fails);
    assert_eq!(reverified(&o), Some(Reverified::Interpreter));
}

#[test]
fn rounding_is_never_a_counterexample() {
    // (e^x + 10^16) − 10^16 = e^x is an identity; in f64 the left side loses every digit
    // of e^x, so the samples violate it. In interval arithmetic the sides' enclosures
    // admit equality at random samples, where floating point therefore cannot tell:
    // undecided, with the reason, never `fails` (and never `holds`).
    let o = decide(
        "expect = \"undecided\"\nreason = \"r\"\nstrategy = \"numeric\"\nsides = [\"(exp(x) + 10000000000000000) - 10000000000000000\", \"exp(x)\"]",
    );
    assert_eq!(o.verdict(), Verdict::Undecided, "{o:?}");
    assert!(
        matches!(
            &o.finding,
            Some(Finding::Unresolved {
                why: Unresolved::WithinRounding { .. },
                ..
            })
        ),
        "{:?}",
        o.finding
    );
    let why = cosserat_check::report::evidence(&o);
    assert!(why.contains("rounding"), "{why}");
    // Polynomial sides are judged exactly at each state where floating point sees a
    // violation: (x + 10^16) − 10^16 = x then holds at every sample.
    let o = decide(
        "expect = \"holds\"\nstrategy = \"numeric\"\nsides = [\"(x + 10000000000000000) - 10000000000000000\", \"x\"]",
    );
    assert_eq!(
        (o.verdict(), o.strength()),
        (Verdict::Holds, Strength::Sampled),
        "{o:?}"
    );
    // A counterexample found in floating point is still confirmed by a second route:
    // exactly, and its values are the exact ones, not the sample's rounding.
    let o = decide(
        "expect = \"fails\"\nreason = \"r\"\nstrategy = \"numeric\"\nsides = [\"(x + 100000000) (x + 100000000) - 10000000000000000 - 200000000 x\", \"0\"]",
    );
    assert_eq!(o.verdict(), Verdict::Fails, "{o:?}");
    let cx = o.counterexample.as_ref().unwrap();
    assert_eq!(cx.reverified, Some(Reverified::Exact));
    let (x, left): (f64, f64) = (
        cx.point["x"].parse().unwrap(),
        cx.lhs_value.as_ref().unwrap().parse().unwrap(),
    );
    assert!(
        (left - x * x).abs() <= 1e-4 * x * x,
        "left {left} at x = {x}: x² exactly"
    );
    // The exact strategy proves it.
    let o = decide(
        "expect = \"holds\"\nstrategy = \"exact\"\nsides = [\"(x + 10000000000000000) - 10000000000000000\", \"x\"]",
    );
    assert_eq!(
        (o.verdict(), o.strength()),
        (Verdict::Holds, Strength::Proof)
    );
}

#[test]
fn exact_counterexamples_are_confirmed_by_the_interpreter() {
    let o = decide(
        "expect = \"fails\"\nreason = \"r\"\nsides = [\"avg(n_i n_j n_k n_l)\", \"1/3 (delta_ij delta_kl + delta_ik delta_jl + delta_il delta_jk)\"]",
    );
    assert_eq!(o.verdict(), Verdict::Fails);
    assert_eq!(reverified(&o), Some(Reverified::FloatingPoint));
    // A free normal in the counterexample: the whole unit vector is evaluated again.
    let o = decide("expect = \"fails\"\nreason = \"r\"\nsides = [\"A_ij n_j\", \"A_ji n_j\"]");
    assert_eq!(o.verdict(), Verdict::Fails);
    assert_eq!(reverified(&o), Some(Reverified::FloatingPoint));
}

/// A definition read at fixed index values is confirmed at that component only (its
/// body inlined there when it is a polynomial): a claim that holds only for a
/// symmetric tensor, written through a definition, is confirmed at the counterexample's
/// component, and one that holds still holds.
#[test]
fn a_definition_at_a_counterexample_s_indices_is_confirmed_at_that_component() {
    let with = |right: &str, expect: &str| {
        let text = format!(
            "{HEADER}\ndefine = [\"Q_ijk = A_ij x n_k + A_ji n_k\", \"P_ijk = {right}\"]\n[[claim]]\nid = \"x\"\nprinted = 'x'\nexpect = \"{expect}\"\nreason = \"r\"\nsides = [\"Q_ijk\", \"P_ijk\"]"
        );
        let file = load_str("test.toml", &text).unwrap_or_else(|e| panic!("{e}"));
        decide_claim(&file.claims[0]).unwrap().outcome
    };
    let wrong = with("A_ij (x + 1) n_k", "fails");
    assert_eq!(wrong.verdict(), Verdict::Fails);
    assert_eq!(reverified(&wrong), Some(Reverified::FloatingPoint));
    assert_eq!(
        with("(A_ij x + A_ji) n_k", "holds").verdict(),
        Verdict::Holds
    );
}
