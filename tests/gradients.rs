//! Gradients with respect to a tensor whose components the assumptions tie together
//! (symmetric, traceless): the file states what ∂F/∂σ means, `convention =
//! "independent"` (F of the free components) or `"symmetrised"` (the gradient
//! projected onto the constrained set), and each convention refutes the other's closed
//! form. Without a convention the derivative is refused as ambiguous.

use cosserat_check::check::decide_claim;
use cosserat_check::derivation::{load_str, Verdict};

const HEADER: &str = r#"
section = "t"
title = "gradient conventions"
dimension = 3
tensors = ["sigma_ij"]
"#;

fn decide(assume: &str, function: &str, closed: &str, convention: Option<&str>) -> Verdict {
    let convention = convention.map_or(String::new(), |c| format!("convention = \"{c}\"\n"));
    let text = format!(
        "{HEADER}\n[[claim]]\nid = \"g\"\nprinted = 'g'\nexpect = \"holds\"\nstrategy = \"gradient\"\nsamples = 50\n\
         assume = [\"{assume}\"]\nfunction = \"{function}\"\ngradient = {{ sigma = \"{closed}\" }}\n{convention}"
    );
    let file = load_str("t.toml", &text).unwrap_or_else(|e| panic!("{e}"));
    decide_claim(&file.claims[0])
        .unwrap_or_else(|e| panic!("{e}"))
        .outcome
        .verdict()
}

#[test]
fn each_convention_proves_its_closed_form_and_refutes_the_other() {
    // F = σ_12 σ_21, which is σ_12² on the symmetric set.
    let (sym, f) = ("symmetric(sigma)", "sigma_12 sigma_21");
    let pair = "(delta_i1 delta_j2 + delta_i2 delta_j1)";
    // Symmetrised: ½(∂F/∂σ_12 + ∂F/∂σ_21) = ½(σ_21 + σ_12) = σ_12 on both of the pair.
    let once = format!("sigma_12 {pair}");
    // Independent components: moving the free one of the pair moves the other: 2 σ_12.
    let twice = format!("2 sigma_12 {pair}");
    assert_eq!(decide(sym, f, &once, Some("symmetrised")), Verdict::Holds);
    assert_eq!(decide(sym, f, &twice, Some("independent")), Verdict::Holds);
    assert_eq!(decide(sym, f, &once, Some("independent")), Verdict::Fails);
    assert_eq!(decide(sym, f, &twice, Some("symmetrised")), Verdict::Fails);
    // ½ σ:σ: its symmetrised gradient is σ itself.
    let half_square = "1/2 sigma_ij sigma_ij";
    assert_eq!(
        decide(sym, half_square, "sigma_ij", Some("symmetrised")),
        Verdict::Holds
    );
    assert_eq!(
        decide(sym, half_square, "sigma_ji", Some("symmetrised")),
        Verdict::Holds
    );
    assert_eq!(
        decide(sym, half_square, "2 sigma_ij", Some("symmetrised")),
        Verdict::Fails
    );
}

#[test]
fn the_symmetrised_gradient_of_one_component_is_split_between_the_pair() {
    let sym = "symmetric(sigma)";
    let half = "1/2 (delta_i1 delta_j2 + delta_i2 delta_j1)";
    assert_eq!(
        decide(sym, "sigma_12", half, Some("symmetrised")),
        Verdict::Holds
    );
    let whole = "delta_i1 delta_j2 + delta_i2 delta_j1";
    assert_eq!(
        decide(sym, "sigma_12", whole, Some("symmetrised")),
        Verdict::Fails
    );
    // A flipped sign and a swapped index are refuted too.
    let flipped = "-1/2 (delta_i1 delta_j2 + delta_i2 delta_j1)";
    assert_eq!(
        decide(sym, "sigma_12", flipped, Some("symmetrised")),
        Verdict::Fails
    );
    let swapped = "1/2 (delta_i1 delta_j3 + delta_i3 delta_j1)";
    assert_eq!(
        decide(sym, "sigma_12", swapped, Some("symmetrised")),
        Verdict::Fails
    );
}

#[test]
fn for_a_traceless_tensor_the_symmetrised_gradient_is_deviatoric() {
    let tl = "traceless(sigma)";
    let dev = "delta_i1 delta_j1 - 1/3 delta_ij";
    assert_eq!(
        decide(tl, "sigma_11", dev, Some("symmetrised")),
        Verdict::Holds
    );
    assert_eq!(
        decide(tl, "sigma_11", "delta_i1 delta_j1", Some("symmetrised")),
        Verdict::Fails
    );
}

#[test]
fn without_a_convention_tied_components_are_refused() {
    let text = format!(
        "{HEADER}\n[[claim]]\nid = \"g\"\nprinted = 'g'\nexpect = \"holds\"\nstrategy = \"gradient\"\nsamples = 50\n\
         assume = [\"symmetric(sigma)\"]\nfunction = \"1/2 sigma_ij sigma_ij\"\ngradient = {{ sigma = \"sigma_ij\" }}\n"
    );
    let file = load_str("t.toml", &text).unwrap();
    let err = decide_claim(&file.claims[0]).unwrap_err().to_string();
    assert!(
        err.contains("two meanings") && err.contains("convention"),
        "{err}"
    );
    // An unknown convention is a clear input error.
    let bad = text.replace("samples = 50", "samples = 50\nconvention = \"mean\"");
    let err = load_str("t.toml", &bad).unwrap_err().to_string();
    assert!(err.contains("unknown gradient convention"), "{err}");
}

#[test]
fn convexity_is_decided_in_the_free_components() {
    // Convexity on the constrained set does not depend on how it is parametrised.
    let text = |f: &str| {
        format!(
            "{HEADER}\n[[claim]]\nid = \"c\"\nprinted = 'c'\nexpect = \"holds\"\nstrategy = \"convex\"\nsamples = 50\n\
             assume = [\"symmetric(sigma)\"]\nfunction = \"{f}\"\nwrt = [\"sigma\"]\n"
        )
    };
    let verdict = |f: &str| {
        let file = load_str("t.toml", &text(f)).unwrap_or_else(|e| panic!("{e}"));
        decide_claim(&file.claims[0]).unwrap().outcome.verdict()
    };
    assert_eq!(verdict("sigma_ij sigma_ij"), Verdict::Holds);
    assert_eq!(verdict("-sigma_ij sigma_ij"), Verdict::Fails);
    // σ_12 σ_21 = σ_12² on the symmetric set: convex there, though not as a function
    // of independent σ_12, σ_21.
    assert_eq!(verdict("sigma_12 sigma_21"), Verdict::Holds);
}
