//! Sound averages of integrands that are not polynomials in n (`eval::quadrature`):
//! exact values hold, mutants fail, an amplified quadrature error is refused rather
//! than reported as a counterexample, and the averages of the shear traction magnitude
//! |t^(t)| agree with an independent high-accuracy reference.

use cosserat_check::algebra::Tensor;
use cosserat_check::check::decide_claim;
use cosserat_check::decide::finding::{Finding, Unresolved};
use cosserat_check::derivation::{load_files, load_str, Strategy, Verdict};
use cosserat_check::eval::quadrature::{Level, Quadrature};
use cosserat_check::eval::real::RealEnv;
use cosserat_check::eval::tape::Tape;
use std::collections::HashMap;
use std::f64::consts::PI;
use std::path::PathBuf;

fn soundness(file: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/soundness")
        .join(file)
}

/// Decides every claim of `file` with each seed; every verdict must be the declared one.
fn verdicts_as_declared(file: &str, seeds: std::ops::RangeInclusive<u64>) {
    let mut files = load_files(&[soundness(file)]).unwrap();
    for seed in seeds {
        for claim in files.iter_mut().flat_map(|f| f.claims.iter_mut()) {
            let Strategy::Numeric { sampling, .. } = &mut claim.check.strategy else {
                panic!("{} is sampled", claim.id);
            };
            sampling.seed = seed;
            let d = decide_claim(claim).unwrap_or_else(|e| panic!("{}: {e}", claim.id));
            assert_eq!(
                d.outcome.verdict(),
                claim.expect,
                "{} with seed {seed}: {:?} {:?}",
                claim.id,
                d.outcome.finding,
                d.outcome.numeric
            );
            if d.outcome.verdict() == Verdict::Undecided {
                // Undecided because of the quadrature, said as data and in words.
                let finding = d.outcome.finding.as_ref().unwrap();
                assert!(
                    matches!(
                        finding,
                        Finding::Unresolved {
                            why: Unresolved::QuadratureError { .. }
                                | Unresolved::WithinError { .. },
                            ..
                        }
                    ),
                    "{finding:?}"
                );
                let why = cosserat_check::report::words::finding(finding);
                assert!(why.contains("adaptive quadrature cannot decide"), "{why}");
            }
        }
    }
}

#[test]
fn circle_averages_are_decided_soundly_for_seeds_1_to_10() {
    verdicts_as_declared("averages-circle.toml", 1..=10);
}

#[test]
#[ignore = "slow sweep: run by `cargo test --release -- --include-ignored`, as CI does"]
fn sphere_averages_are_decided_soundly() {
    // About 10 s a seed: each state takes a few 10^5 integrand evaluations.
    verdicts_as_declared("averages-sphere.toml", 1..=1);
}

/// The claim text of a file with one sampled claim about `avg(sqrt(tt_k tt_k))`.
fn shear_traction_file(dim: usize) -> String {
    format!(
        "section = \"t\"\ntitle = \"t\"\ndimension = {dim}\nnormal = \"n\"\n\
         tensors = [\"sigma_ij\"]\n\
         define = [\"t_i = sigma_ki n_k\", \"tn = t_i n_i\", \"tt_i = t_i - tn n_i\"]\n\
         [[claim]]\nid = \"c\"\nprinted = 'x'\nexpect = \"holds\"\nstrategy = \"numeric\"\n\
         sides = [\"avg(sqrt(tt_k tt_k))\", \"0\"]\n"
    )
}

/// |t^(t)| = √(|σᵀn|² − (n·σᵀn)²) by hand.
fn shear_traction(sigma: &[[f64; 3]; 3], n: &[f64]) -> f64 {
    let d = n.len();
    let t: Vec<f64> = (0..d)
        .map(|i| (0..d).map(|k| sigma[k][i] * n[k]).sum())
        .collect();
    let tn: f64 = (0..d).map(|i| t[i] * n[i]).sum();
    ((0..d).map(|i| t[i] * t[i]).sum::<f64>() - tn * tn)
        .max(0.0)
        .sqrt()
}

/// A reference average by brute force, independent of the adaptive code: on the
/// circle the midpoint rule with 2^20 points; on the sphere a 4000 × 8000 midpoint
/// rule in (z, φ) (z = cos θ makes the measure uniform). Both converge at least
/// quadratically away from the kinks; here they agree with each other's refinements
/// to about 1e-9.
fn reference(dim: usize, sigma: &[[f64; 3]; 3]) -> f64 {
    if dim == 2 {
        let m = 1 << 20;
        (0..m)
            .map(|k| {
                let phi = 2.0 * PI * (k as f64 + 0.5) / m as f64;
                shear_traction(sigma, &[phi.cos(), phi.sin()])
            })
            .sum::<f64>()
            / m as f64
    } else {
        let (nz, nphi) = (4000, 8000);
        let mut total = 0.0;
        for i in 0..nz {
            let z = -1.0 + 2.0 * (i as f64 + 0.5) / nz as f64;
            let r = (1.0 - z * z).sqrt();
            for j in 0..nphi {
                let phi = 2.0 * PI * (j as f64 + 0.5) / nphi as f64;
                total += shear_traction(sigma, &[r * phi.cos(), r * phi.sin(), z]);
            }
        }
        total / (nz * nphi) as f64
    }
}

#[test]
fn the_shear_traction_magnitude_matches_a_brute_force_reference() {
    let sigma = [[0.9, -0.4, 0.3], [0.2, -0.7, 0.5], [-0.6, 0.1, 0.4]];
    for dim in [2usize, 3] {
        let file = load_str("t.toml", &shear_traction_file(dim)).unwrap();
        let claim = &file.claims[0];
        let node = claim.check.chains[0][0].node.as_ref().unwrap();
        let symbols = HashMap::from([(
            "sigma".to_owned(),
            Tensor::from_fn(dim, 2, |i| sigma[i[0]][i[1]]),
        )]);
        let env = RealEnv::new(&claim.decls, &claim.check.defs, symbols);
        let n = vec![1.0; dim];
        let by_interpreter = env.eval(node, &n).unwrap().tensor.into_scalar().unwrap();
        assert!(env.quadrature.used());
        let tape = Tape::compile(&claim.decls, &claim.check.defs, node).unwrap();
        let inputs: Vec<f64> = tape.inputs.iter().map(|(_, i)| sigma[i[0]][i[1]]).collect();
        let quad = Quadrature::new(Level::Fine);
        let by_tape = tape
            .eval(&inputs, &n, &quad)
            .unwrap()
            .tensor
            .into_scalar()
            .unwrap();
        let want = reference(dim, &sigma);
        let bound = quad.worst_error() + 1e-8;
        for got in [by_interpreter, by_tape] {
            assert!(
                (got - want).abs() <= bound,
                "dim {dim}: {got} vs {want} (bound {bound})"
            );
        }
        assert!(
            quad.worst_error() < 1e-5 * want,
            "dim {dim}: {}",
            quad.worst_error()
        );
    }
}

#[test]
fn derivatives_through_an_adaptive_average_are_refused_not_guessed() {
    let text = "section = \"t\"\ntitle = \"t\"\ndimension = 2\nnormal = \"n\"\n\
                tensors = [\"a_i\"]\n\
                [[claim]]\nid = \"g\"\nprinted = 'x'\nexpect = \"undecided\"\n\
                reason = \"Refused.\"\nstrategy = \"gradient\"\n\
                function = \"avg(abs(a_k n_k))\"\ngradient = { a = \"a_i\" }\n";
    // The closed form is irrelevant: the refusal comes before any comparison.
    let file = load_str("t.toml", text).unwrap();
    let d = decide_claim(&file.claims[0]).unwrap();
    assert_eq!(d.outcome.verdict(), Verdict::Undecided);
    assert_eq!(d.outcome.finding, Some(Finding::ThroughAdaptiveAverage));
    let why = cosserat_check::report::evidence(&d.outcome);
    assert!(why.contains("not a polynomial in n"), "{why}");
}

#[test]
fn an_undecided_claim_is_not_an_erratum() {
    let files = load_files(&[soundness("averages-circle.toml")]).unwrap();
    let claim = files[0]
        .claims
        .iter()
        .find(|c| c.id == "amplified-quadrature-error")
        .unwrap();
    let d = decide_claim(claim).unwrap();
    assert_eq!(d.outcome.verdict(), Verdict::Undecided);
    assert!(!cosserat_check::report::is_erratum(&d));
}
