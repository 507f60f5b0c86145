//! Adversarial sampling: statements that are false only on a thin set of states must be
//! refuted with the default sample count for every seed from 1 to 20, and true ones
//! (including the sharp bound) must still hold (issue: no sampled `holds` without a
//! search for the worst violation).

use cosserat_check::check::decide_claim;
use cosserat_check::derivation::{load_files, Strategy};
use std::path::PathBuf;

#[test]
fn thin_violations_are_found_for_every_seed_from_1_to_20() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/soundness/adversarial.toml");
    let mut files = load_files(&[path]).unwrap();
    let mut decided = 0;
    for seed in 1..=20 {
        for claim in files.iter_mut().flat_map(|f| f.claims.iter_mut()) {
            let Strategy::Numeric { sampling, .. } = &mut claim.check.strategy else {
                panic!("{} is sampled", claim.id);
            };
            assert_eq!(sampling.samples, 200, "the default sample count");
            sampling.seed = seed;
            let d = decide_claim(claim).unwrap_or_else(|e| panic!("{}: {e}", claim.id));
            assert_eq!(
                d.outcome.verdict(),
                claim.expect,
                "{} with seed {seed}: {:?}",
                claim.id,
                d.outcome.numeric
            );
            decided += 1;
        }
    }
    assert_eq!(decided, 20 * 7);
}

#[test]
fn sampled_and_proved_verdicts_are_labelled_differently() {
    use cosserat_check::decide::Strength;
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/soundness");
    let files = load_files(&[
        dir.join("adversarial.toml"),
        dir.join("assumption-order.toml"),
    ])
    .unwrap();
    let claims: Vec<_> = files.iter().flat_map(|f| &f.claims).collect();
    let find = |id: &str| *claims.iter().find(|c| c.id == id).unwrap();
    let sampled = decide_claim(find("lode-bound-sharp")).unwrap().outcome;
    assert_eq!(
        (sampled.strength(), sampled.verdict_text().as_str()),
        (Strength::Sampled, "holds (sampled)")
    );
    let search = sampled.numeric.unwrap().search.unwrap();
    assert!(search.evaluations > 0 && search.worst_margin <= 1e-9 && !search.at.is_empty());
    let proved = decide_claim(find("minor-kl-from-minor-ij-and-major"))
        .unwrap()
        .outcome;
    assert_eq!(
        (proved.strength(), proved.verdict_text().as_str()),
        (Strength::Proof, "holds")
    );
}
