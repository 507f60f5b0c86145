//! Classes of claims that went wrong on derivations nobody on the project wrote, each in
//! a file of fresh claims under `tests/unseen/` whose true verdicts were established by
//! a second route (the claim's note). Every claim, and every correction, must come out
//! as declared for every seed from 1 to 20.

use cosserat_check::check::decide_claim;
use cosserat_check::derivation::{load_files, Claim, Strategy};
use std::path::PathBuf;

/// Sets the seed of every sampled route of `claim` (and of its correction).
fn reseed(claim: &mut Claim, seed: u64) {
    let set = |s: &mut Strategy| match s {
        Strategy::Numeric { sampling, .. }
        | Strategy::Gradient { sampling, .. }
        | Strategy::Convex { sampling, .. } => sampling.seed = seed,
        Strategy::Scalar { seed: s, .. } => *s = seed,
        _ => {}
    };
    set(&mut claim.check.strategy);
    if let Some(c) = &mut claim.correction {
        set(&mut c.check.strategy);
    }
}

/// Decides every claim of `tests/unseen/NAME.toml` for seeds 1 to 20 and asserts each
/// verdict; returns the number of claims.
fn as_declared_for_every_seed(name: &str) -> usize {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("tests/unseen/{name}.toml"));
    let mut files = load_files(&[path]).unwrap_or_else(|e| panic!("{name}: {e}"));
    let claims = files.iter().map(|f| f.claims.len()).sum();
    for seed in 1..=20 {
        for claim in files.iter_mut().flat_map(|f| f.claims.iter_mut()) {
            reseed(claim, seed);
            let d = decide_claim(claim).unwrap_or_else(|e| panic!("{}: {e}", claim.id));
            assert_eq!(
                d.outcome.verdict(),
                claim.expect,
                "{} with seed {seed}: {}",
                claim.id,
                cosserat_check::report::evidence(&d.outcome)
            );
            if let (Some(c), Some(o)) = (&claim.correction, &d.correction) {
                assert_eq!(
                    o.verdict(),
                    c.expect,
                    "{}'s correction, seed {seed}",
                    claim.id
                );
            }
        }
    }
    claims
}

#[test]
fn strict_signs_broken_on_a_thin_set_fail_with_an_exact_point() {
    assert_eq!(as_declared_for_every_seed("strict-inequalities"), 9);
}

#[test]
fn a_law_times_a_factor_of_the_parameters_is_the_same_law() {
    assert_eq!(as_declared_for_every_seed("proportional-factors"), 10);
}

#[test]
fn component_assumptions_polynomial_in_parameters_are_solved() {
    assert_eq!(as_declared_for_every_seed("polynomial-assumptions"), 12);
}

#[test]
fn divisors_that_vanish_on_thin_sets_are_stepped_off_claim_by_claim() {
    assert_eq!(as_declared_for_every_seed("undefined-on-thin-sets"), 8);
}

#[test]
fn a_wrong_limit_is_refuted_at_generic_parameters() {
    assert_eq!(
        as_declared_for_every_seed("limits-at-generic-parameters"),
        6
    );
}

#[test]
fn implications_broken_next_to_a_hypothesis_boundary_fail() {
    assert_eq!(as_declared_for_every_seed("implications"), 4);
}

#[test]
fn fields_given_by_potentials_are_decided() {
    assert_eq!(as_declared_for_every_seed("potentials"), 5);
}

#[test]
fn roots_in_one_variable_times_a_factor_of_one_sign() {
    assert_eq!(
        as_declared_for_every_seed("roots-with-a-parameter-factor"),
        4
    );
}

#[test]
fn sides_that_cancel_in_floating_point_are_not_refuted_by_rounding() {
    assert_eq!(as_declared_for_every_seed("cancellation"), 17);
}

#[test]
fn monotone_and_sign_claims_times_a_factor_of_one_sign() {
    assert_eq!(as_declared_for_every_seed("one-sign-factors"), 11);
}

#[test]
fn a_locus_that_is_a_circle_is_refuted_by_its_circle() {
    assert_eq!(as_declared_for_every_seed("circles"), 8);
}
