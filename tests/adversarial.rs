//! Adversarial sampling: statements that are false only on a thin set of states must be
//! refuted with the default sample count for every seed from 1 to 20, and true ones
//! (including the sharp bound) must still hold (issue: no sampled `holds` without a
//! search for the worst violation).

use cosserat_check::derivation::{load_files, Strategy};
use cosserat_check::strategy::decide_claim;
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
                d.outcome.verdict, claim.expect,
                "{} with seed {seed}: {:?}",
                claim.id, d.outcome.numeric
            );
            decided += 1;
        }
    }
    assert_eq!(decided, 20 * 7);
}
