//! Balance laws from a virtual power (issue 13, item 2): `variation(P, v_j)` derives
//! the Euler–Lagrange expression of a density exactly, on jet variables; a second
//! route perturbs the field and takes central differences, and must agree on every
//! claim; `strategy = "proportional"` accepts a law stated with another sign or scale.

use crate::support::float;
use cosserat_check::check::decide;
use cosserat_check::cli::decide_all;
use cosserat_check::decide::Reverified;
use cosserat_check::derivation::{load_files, load_str, Strategy, Verdict};

use crate::common;

const CORPUS: &str = "tests/soundness/balance-laws.toml";

#[test]
fn laws_hold_and_their_twins_fail_confirmed_by_perturbation() {
    common::assert_as_declared(CORPUS, 22, |rows| {
        common::assert_failures_confirmed(rows, 12, Reverified::TaylorDifferences);
        // A refuted proportionality shows where its factor was fixed.
        let wrong = rows
            .iter()
            .find(|r| r.claim.id == "cosserat-moment-balance-up-to-sign-wrong")
            .unwrap();
        let f = wrong
            .outcome
            .counterexample
            .as_ref()
            .unwrap()
            .factor
            .as_ref();
        assert_eq!(f.map(|f| f.factor.as_str()), Some("1"));
        // A proved one names its factor.
        let scaled = rows
            .iter()
            .find(|r| r.claim.id == "cosserat-force-balance-scaled")
            .unwrap();
        let words = cosserat_check::report::evidence(&scaled.outcome);
        assert!(words.contains("left = -1/2 · right"), "{words}");
    });
}

/// The perturbation route (`f64`, no jet variables, no symbolic ∂P/∂v_j,α) reaches
/// the exact verdict on every claim, the twins included.
#[test]
fn the_perturbation_route_agrees_with_the_exact_one() {
    let files = load_files(&[CORPUS]).unwrap();
    let mut compared = 0;
    for claim in files.iter().flat_map(|f| &f.claims) {
        let exact = decide(&claim.decls, &claim.check).unwrap().verdict();
        let float = float::decide(&claim.decls, &claim.check, 2, 11)
            .unwrap_or_else(|e| panic!("{}: {e}", claim.id))
            .unwrap_or_else(|| panic!("{}: not judged", claim.id));
        assert_eq!(float, exact, "{}", claim.id);
        compared += 1;
    }
    assert_eq!(compared, 22);
}

fn one_claim(header: &str, claim: &str) -> String {
    format!(
        "section = \"t\"\ntitle = \"t\"\ndimension = 3\nposition = \"x\"\nfields = [\"v_i\", \"w_i\", \"sigma_ij\"]\n{header}\n\n[[claim]]\nid = \"c\"\nprinted = 'c'\nexpect = \"holds\"\n{claim}\n"
    )
}

fn verdict(claim: &str) -> Verdict {
    let f = load_str("f.toml", &one_claim("", claim)).unwrap();
    let rows = decide_all(std::slice::from_ref(&f), None).unwrap();
    rows[0].outcome.verdict()
}

/// The convention, derived by hand: for P = σ_ij v_j,i,
/// δ∫P dV = ∫σ_ij δv_j,i dV = ∮σ_ij n_i δv_j dA − ∫σ_ij,i δv_j dV,
/// so the factor of δv_j is −σ_ij,i, and a density with a second derivative of the
/// field, integrated by parts twice, keeps its sign.
#[test]
fn the_sign_convention_is_the_hand_derivation() {
    assert_eq!(
        verdict("sides = [\"variation(sigma_ij v_j,i, v_k)\", \"-sigma_ik,i\"]"),
        Verdict::Holds
    );
    assert_eq!(
        verdict("sides = [\"variation(sigma_ij v_j,i, v_k)\", \"sigma_ik,i\"]"),
        Verdict::Fails
    );
    assert_eq!(
        verdict("sides = [\"variation(sigma_ij v_j,kk, v_l)\", \"sigma_il,kk\"]"),
        Verdict::Holds
    );
    // Undifferentiated: ∂P/∂w_k with no sign change.
    assert_eq!(
        verdict("sides = [\"variation(sigma_ij eps_ijk w_k, w_l)\", \"sigma_ij eps_ijl\"]"),
        Verdict::Holds
    );
}

#[test]
fn slips_are_located_errors() {
    let cases = [
        (
            "tensors = [\"A_ij\"]",
            "sides = [\"variation(A_ij v_j,i, A_kl)\", \"0\"]",
            "f.toml:12:33",
            "`A_kl` is not a declared field",
        ),
        (
            "",
            "sides = [\"variation(sigma_ij v_j,i, v_i)\", \"0\"]",
            "f.toml:12:39",
            "index `i` of the varied field is also an index of the density",
        ),
        (
            "",
            "sides = [\"variation(variation(sigma_ij v_j,i, v_k), w_l)\", \"0\"]",
            "f.toml:12:21",
            "a variation or gradient inside variation(…) is not supported",
        ),
        (
            "",
            "sides = [\"variation(sigma_ij v_j,i, v_k + 1)\", \"0\"]",
            "f.toml:12:37",
            "is a field with its indices",
        ),
        (
            "",
            "assume = [\"v_3 = 0\"]\nsides = [\"variation(sigma_ij v_j,i, v_k)\", \"-sigma_ik,i\"]",
            "f.toml:13:11",
            "`v` is varied, but an assumption constrains it",
        ),
        (
            "",
            "strategy = \"proportional\"\nsides = [\"v_1\", \"v_1\", \"v_1\"]",
            "f.toml:12:12",
            "compares exactly two sides",
        ),
        (
            "",
            "strategy = \"proportional\"\nrelation = \"<=\"\nsides = [\"v_1\", \"v_1\"]",
            "f.toml:13:12",
            "`relation` applies to strategy = \"numeric\" or \"sign\" only",
        ),
    ];
    for (header, claim, at, message) in cases {
        let e = common::error_of(&one_claim(header, claim));
        assert!(e.contains(at) && e.contains(message), "{claim}: {e}");
    }
}

#[test]
fn the_worked_example_is_decided_as_declared() {
    common::assert_as_declared("derivations/examples/balance.toml", 7, |rows| {
        assert!(rows
            .iter()
            .any(|r| matches!(r.claim.check.strategy, Strategy::Proportional { .. })));
    });
}
